//! The preview in a real browser: headless Chromium, driven by ChromeDriver over WebDriver,
//! opens the page, waits for a picture, sees it change when the scene is saved, clicks the
//! diamond sphere and finds the refraction in the explain tree, and explains a pixel of a
//! bidirectional render with both its subpaths drawn.
//!
//! It needs Debian's `chromium` and `chromium-driver` (`apt-get install chromium
//! chromium-driver`), so plain `cargo test` lists it as ignored, and `cargo test --
//! --include-ignored` (which `.ci/run` runs) runs it; without them it fails and says how to
//! install them, never passing without its browser. `SNELL_SCREENSHOT=FILE` saves the page
//! as it ends (the README's picture: `SNELL_SCREENSHOT=docs/images/serve.png cargo test
//! browser -- --include-ignored`).

use super::{scene_copy, seed_copy, start, wait_for};
use serde_json::{Value, json};
use std::io::{Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const CHROMIUM: &str = "/usr/bin/chromium";
const DRIVER: &str = "/usr/bin/chromedriver";

/// ChromeDriver, stopped when dropped.
struct Driver {
    child: Child,
    port: u16,
    session: String,
}

impl Drop for Driver {
    fn drop(&mut self) {
        if !self.session.is_empty() {
            let _ = self.call("DELETE", &format!("/session/{}", self.session), None);
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Driver {
    /// A WebDriver command: `Value` of the answer, or the error it gave.
    fn call(&self, method: &str, path: &str, body: Option<Value>) -> Result<Value, String> {
        let body = body.map(|b| b.to_string()).unwrap_or_default();
        let mut s = TcpStream::connect(("127.0.0.1", self.port)).map_err(|e| e.to_string())?;
        s.set_read_timeout(Some(Duration::from_secs(60))).ok();
        write!(
            s,
            "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}",
            self.port,
            body.len()
        )
        .map_err(|e| e.to_string())?;
        // ChromeDriver keeps the connection open: read the head, then Content-Length bytes.
        let mut all = vec![];
        let mut buf = [0u8; 65536];
        let (head_end, length) = loop {
            let n = s.read(&mut buf).map_err(|e| e.to_string())?;
            if n == 0 {
                return Err(format!("ChromeDriver closed the connection: {all:?}"));
            }
            all.extend_from_slice(&buf[..n]);
            if let Some(end) = all.windows(4).position(|w| w == b"\r\n\r\n") {
                let head = String::from_utf8_lossy(&all[..end]).to_ascii_lowercase();
                let length = head
                    .lines()
                    .find_map(|l| l.strip_prefix("content-length:"))
                    .and_then(|v| v.trim().parse::<usize>().ok())
                    .ok_or_else(|| format!("no Content-Length in {head}"))?;
                break (end + 4, length);
            }
        };
        while all.len() < head_end + length {
            let n = s.read(&mut buf).map_err(|e| e.to_string())?;
            if n == 0 {
                break;
            }
            all.extend_from_slice(&buf[..n]);
        }
        let text = String::from_utf8_lossy(&all[head_end..]);
        let v: Value = serde_json::from_str(&text).map_err(|e| format!("{e}: {text}"))?;
        if v["value"]["error"].is_string() {
            return Err(v["value"].to_string());
        }
        Ok(v["value"].clone())
    }

    fn session_call(&self, method: &str, path: &str, body: Option<Value>) -> Value {
        self.call(method, &format!("/session/{}{path}", self.session), body)
            .unwrap_or_else(|e| panic!("WebDriver {method} {path}: {e}"))
    }

    /// A click on the centre of pixel `(x, y)` of the picture (`#frame`), `size` pixels
    /// large, at its place in the viewport (in whole CSS pixels, within half of one of it).
    fn click(&self, size: (f64, f64), (x, y): (f64, f64)) {
        let r = self.run(
            "const r = document.getElementById('frame').getBoundingClientRect(); return [r.left, r.top, r.width, r.height]",
        );
        let r: Vec<f64> = r
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let at_x = r[0] + (x + 0.5) / size.0 * r[2];
        let at_y = r[1] + (y + 0.5) / size.1 * r[3];
        self.session_call(
            "POST",
            "/actions",
            Some(json!({ "actions": [{
                "type": "pointer", "id": "mouse", "parameters": { "pointerType": "mouse" },
                "actions": [
                    { "type": "pointerMove", "origin": "viewport", "x": at_x.round() as i64, "y": at_y.round() as i64 },
                    { "type": "pause", "duration": 300 },
                    { "type": "pointerDown", "button": 0 },
                    { "type": "pointerUp", "button": 0 },
                ],
            }]})),
        );
    }

    /// Runs `script` in the page and returns its value.
    fn run(&self, script: &str) -> Value {
        self.session_call(
            "POST",
            "/execute/sync",
            Some(json!({ "script": script, "args": [] })),
        )
    }

    /// Waits (up to `secs`) for `script` to return something other than null or false.
    fn wait(&self, secs: u64, what: &str, script: &str) -> Value {
        let start = Instant::now();
        loop {
            let v = self.run(script);
            if !v.is_null() && v != json!(false) {
                return v;
            }
            assert!(
                start.elapsed().as_secs() < secs,
                "waited {secs} s for {what}"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

/// Starts ChromeDriver and a headless Chromium session; fails, never skips, without them.
fn browser(name: &str) -> Driver {
    assert!(
        std::path::Path::new(CHROMIUM).exists() && std::path::Path::new(DRIVER).exists(),
        "the browser test needs {CHROMIUM} and {DRIVER}: apt-get install chromium chromium-driver"
    );
    let port = free_port();
    let child = Command::new(DRIVER)
        .arg(format!("--port={port}"))
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut driver = Driver {
        child,
        port,
        session: String::new(),
    };
    let profile = super::super::scratch(&format!("browser-profile-{name}"));
    let caps = json!({ "capabilities": { "alwaysMatch": {
        "browserName": "chrome",
        "goog:chromeOptions": {
            "binary": CHROMIUM,
            "args": [
                "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--disable-quic", "--no-first-run", "--disable-background-networking",
                "--disable-component-update", "--disable-sync", "--window-size=1400,820",
                "--hide-scrollbars", format!("--user-data-dir={}", profile.display()),
            ],
        },
    }}});
    let start = Instant::now();
    let session = loop {
        match driver.call("POST", "/session", Some(caps.clone())) {
            Ok(v) => break v,
            Err(e) if start.elapsed().as_secs() < 30 => {
                let _ = e;
                std::thread::sleep(Duration::from_millis(100));
            }
            Err(e) => panic!("no browser session: {e}"),
        }
    };
    driver.session = session["sessionId"].as_str().unwrap().to_string();
    driver
}

#[test]
#[ignore = "needs Chromium and ChromeDriver (apt-get install chromium chromium-driver): cargo test -- --include-ignored"]
fn browser_shows_follows_and_explains() {
    let driver = browser("seed");
    let dir = seed_copy("browser");
    let s = start(&dir, "scenes/seed.toml", &[]);
    let p = s.port;
    wait_for(p, 60, "the first picture", super::current_frame);
    driver.session_call(
        "POST",
        "/url",
        Some(json!({ "url": format!("http://127.0.0.1:{p}/") })),
    );
    // A picture arrives over the event stream.
    driver.wait(
        60,
        "a picture on the page",
        "return document.getElementById('frame').dataset.loaded || null",
    );
    let first = driver.wait(
        60,
        "the finished picture",
        "const p = document.getElementById('progress').textContent; return p.includes('done') ? document.getElementById('frame').dataset.frame : null",
    );
    assert!(
        driver
            .run("return document.getElementById('progress').textContent")
            .as_str()
            .unwrap()
            .contains("16 / 16 spp")
    );
    // An edit of the scene file shows on the page.
    let scene = dir.join("scenes/seed.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    let bigger = text.replace(
        "center = [10, 8, -80]\nradius = 4\n",
        "center = [10, 8, -80]\nradius = 7\n",
    );
    assert_ne!(bigger, text);
    std::fs::write(&scene, bigger).unwrap();
    let script = format!(
        "const f = document.getElementById('frame').dataset.frame; return f && f !== '{}' ? f : null",
        first.as_str().unwrap()
    );
    driver.wait(60, "the edited scene's picture", &script);
    // A mistake shows its message over the picture, and its fix takes it away.
    std::fs::write(&scene, text.replace("radius = 4\n", "radius = \"big\"\n")).unwrap();
    let message = driver.wait(
        60,
        "the message",
        "const e = document.getElementById('error'); return e.hidden ? null : e.textContent",
    );
    assert!(
        message.as_str().unwrap().contains("seed.toml:114:10"),
        "{message}"
    );
    std::fs::write(&scene, &text).unwrap();
    driver.wait(
        60,
        "the message gone",
        "return document.getElementById('error').hidden",
    );
    driver.wait(
        60,
        "the finished picture again",
        "return document.getElementById('progress').textContent.includes('done') || null",
    );
    // The page's exposure and curve start from the scene's, and follow the file's when
    // they change there.
    let controls = "return [document.getElementById('exposure').value, document.getElementById('tone').value, document.getElementById('frame').src]";
    let now = driver.run(controls);
    assert_eq!(
        (now[0].as_str(), now[1].as_str()),
        (Some("0"), Some("clamp")),
        "{now}"
    );
    let toned = text.replace(
        "background = [0, 0, 0]\n",
        "background = [0, 0, 0]\nexposure = -1.5\ntonemap = \"aces\"\n",
    );
    assert_ne!(toned, text);
    std::fs::write(&scene, &toned).unwrap();
    let now = driver.wait(
        60,
        "the scene's exposure and curve in the controls",
        &format!("{}; return (c[0] === '-1.5' && c[1] === 'aces' && c[2].includes('exposure=-1.5&tone=aces')) ? c : null", controls.replace("return ", "const c = ")),
    );
    assert_eq!(now[1].as_str(), Some("aces"));
    std::fs::write(&scene, &text).unwrap();
    driver.wait(
        60,
        "the controls back with the file",
        "return (document.getElementById('tone').value === 'clamp' && document.getElementById('progress').textContent.includes('done')) || null",
    );
    // A click on the diamond sphere (pixel 256, 380 of 512 x 512) explains it.
    let click = |x: f64, y: f64| driver.click((512.0, 512.0), (x, y));
    click(256.0, 380.0);
    let tree = driver.wait(
        60,
        "the explain tree",
        "const t = document.getElementById('tree'); return t.dataset.pixel ? t.textContent : null",
    );
    let tree = tree.as_str().unwrap();
    assert!(
        tree.contains("camera ray, depth 1: hits diamond sphere (diamond)"),
        "{tree}"
    );
    assert!(tree.contains("refraction ray"), "{tree}");
    let marks = driver.run("return document.querySelectorAll('#overlay .hit').length");
    assert!(marks.as_u64().unwrap() >= 2, "hit points drawn: {marks}");
    // Its light by kind of path: the floor seen through the diamond there is a black
    // square, and the page says no path brought light.
    let said = driver.wait(
        60,
        "the pixel's paths",
        "const p = document.getElementById('paths'); return p.dataset.pixel ? [p.dataset.pixel, p.textContent] : null",
    );
    assert!(
        said[1].as_str().unwrap().contains("No path brought"),
        "{said}"
    );
    // The red sphere's: a bar whose shares add up to 1, most of it direct diffuse light, and
    // sampled paths drawn from above and from the side, each vertex saying its numbers on
    // hover.
    click(380.0, 420.0);
    driver.wait(
        60,
        "the red sphere's paths",
        &format!(
            "const p = document.getElementById('paths').dataset.pixel; return p && p !== '{}' && document.querySelector('.paths-segment') ? p : null",
            said[0].as_str().unwrap()
        ),
    );
    let shares = driver.run(
        "return [...document.querySelectorAll('.paths-segment')].map((s) => [s.dataset.kind, Number(s.dataset.share)])",
    );
    let shares = shares.as_array().unwrap();
    let total: f64 = shares.iter().map(|s| s[1].as_f64().unwrap()).sum();
    assert!((total - 1.0).abs() < 0.01, "{shares:?}");
    let direct = shares
        .iter()
        .find(|s| s[0] == "direct, diffuse")
        .map_or(0.0, |s| s[1].as_f64().unwrap());
    assert!(direct > 0.5, "{shares:?}");
    let drawn = driver.run(
        "return [document.querySelectorAll('.paths-view').length, document.querySelectorAll('.paths-path').length, [...document.querySelectorAll('.paths-vertex title')].map((t) => t.textContent)]",
    );
    assert_eq!(drawn[0], 2, "{drawn}");
    assert!(drawn[1].as_u64().unwrap() >= 2, "{drawn}");
    let hovers = drawn[2].as_array().unwrap();
    assert!(!hovers.is_empty());
    assert!(
        hovers
            .iter()
            .all(|t| t.as_str().unwrap().contains("throughput")),
        "{drawn}"
    );
    assert!(
        hovers.iter().any(|t| t.as_str().unwrap().contains("pdf")),
        "{drawn}"
    );
    // A light path view: the direct light alone, in place of the picture.
    driver.run(
        "const v = document.getElementById('view'); v.value = 'lpe:direct'; v.dispatchEvent(new Event('change')); return true",
    );
    driver.wait(
        60,
        "the direct light's view",
        "const f = document.getElementById('frame'); return f.src.includes('/lpe/direct.png') && f.complete && f.naturalWidth > 0 ? f.src : null",
    );
    driver.run(
        "const v = document.getElementById('view'); v.value = 'picture'; v.dispatchEvent(new Event('change')); return true",
    );
    // The hover says what is under the pointer.
    driver.wait(
        30,
        "the hover",
        "const h = document.getElementById('hover'); return h.hidden ? null : h.textContent",
    );
    if let Ok(path) = std::env::var("SNELL_SCREENSHOT") {
        driver.wait(
            60,
            "the finished picture for the screenshot",
            "return document.getElementById('progress').textContent.includes('done') || null",
        );
        let png = driver.session_call("GET", "/screenshot", None);
        std::fs::write(path, base64(png.as_str().unwrap())).unwrap();
    }
    // The sampling lab, linked from the page: a rough gold at 60 degrees tested and drawn.
    let href = driver.run("return document.querySelector('a[href=\"/lab\"]').href");
    driver.session_call("POST", "/url", Some(json!({ "url": href })));
    driver.wait(
        30,
        "the lab's form",
        "return document.getElementById('lab-form') && true",
    );
    driver.run(
        "document.getElementById('lab-type').value = 'conductor'; \
         document.getElementById('lab-metal').value = 'Au'; \
         document.getElementById('lab-roughness').value = '0.2'; \
         document.getElementById('lab-angle').value = '60'; \
         document.getElementById('lab-run').click(); return true",
    );
    let done = driver.wait(
        60,
        "the lab's answer",
        "return document.getElementById('lab-result').dataset.done || null",
    );
    assert_eq!(done, "passed");
    let text = driver.run("return document.getElementById('lab-result').textContent");
    let text = text.as_str().unwrap();
    assert!(
        text.starts_with("conductor (roughness = 0.2, metal = \"Au\"), light leaving at 60°"),
        "{text}"
    );
    // The histogram was drawn: some pixel of the samples' panel is lit.
    let lit = driver.run(
        "const c = document.getElementById('lab-observed'); \
         const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data; \
         let n = 0; for (let i = 0; i < d.length; i += 4) if (d[i] > 0) n++; return n",
    );
    assert!(lit.as_u64().unwrap() > 100, "lit pixels: {lit}");
}

/// A click on a pixel of a bidirectionally rendered scene explains it bidirectionally: the
/// sample's strategies and both subpaths in the tree, the eye's subpath and the light's drawn
/// over the picture, and a ring where its light path joined to the eye lands.
/// `SNELL_SCREENSHOT_BDPT=FILE` saves the page as it ends.
#[test]
#[ignore = "needs Chromium and ChromeDriver (apt-get install chromium chromium-driver): cargo test -- --include-ignored"]
fn browser_explains_a_bidirectional_sample() {
    let driver = browser("bdpt");
    let dir = scene_copy("browser-bdpt", "caustics.toml");
    let s = start(
        &dir,
        "scenes/caustics.toml",
        &["--size", "240", "--spp", "4"],
    );
    let st = wait_for(s.port, 60, "the first picture", super::current_frame);
    assert_eq!(st["integrator"], "bdpt");
    assert_eq!(st["size"], json!([240, 180]));
    driver.session_call(
        "POST",
        "/url",
        Some(json!({ "url": format!("http://127.0.0.1:{}/", s.port) })),
    );
    driver.wait(
        60,
        "the finished picture",
        "return document.getElementById('progress').textContent.includes('done') || null",
    );
    // A pixel of the table lit by the spot, explained as a click does (the page's own
    // `explain`, called for the exact pixel: a click's place is good to a CSS pixel, and a
    // pixel here is about one): its sample 0 joins the spot's path, which passes through the
    // glass and the water, to the eye (s = 2, t = 1), landing elsewhere on the picture, and
    // samples the lamp from the table (s = 1, t = 2), as `snell explain --integrator bdpt`
    // says of it.
    driver.run("return import('/explain.js').then((m) => m.explain([101, 150])).then(() => true)");
    let tree = driver.wait(
        60,
        "the explain tree",
        "const t = document.getElementById('tree'); return t.dataset.pixel === '101,150' ? t.textContent : null",
    );
    let tree = tree.as_str().unwrap();
    for said in [
        "(s=2, t=1) the light's path joined to the eye",
        "(s=1, t=2) a light sampled from the eye's path",
        "camera_path 1: `table` (table)",
        "light_path 0: spot",
        "light_path 2: `glass` (glass)",
        "lands_at",
    ] {
        assert!(tree.contains(said), "{said}: {tree}");
    }
    let hint = driver.run("return document.getElementById('explain-hint').textContent");
    assert!(
        hint.as_str()
            .unwrap()
            .starts_with("Pixel (101, 150), bidirectional sample 0:"),
        "{hint}"
    );
    // What is drawn is what the explain data places on the picture: each subpath a chain
    // through its vertices the camera sees (the eye's from the pixel), and a ring for each
    // landing.
    let doc = super::get(s.port, "/explain?x=101&y=150").json();
    let seen = |path: &Value| -> Vec<bool> {
        path.as_array()
            .unwrap()
            .iter()
            .map(|v| v["screen"].is_array())
            .collect()
    };
    let links = |seen: &[bool]| seen.windows(2).filter(|w| w[0] && w[1]).count();
    let eye: Vec<bool> = std::iter::once(true)
        .chain(seen(&doc["camera_path"]).into_iter().skip(1))
        .collect();
    let light = seen(&doc["light_path"]);
    let lands = doc["strategies"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["lands_at"].is_array())
        .count();
    let expected = json!([
        links(&eye),
        eye.iter().skip(1).filter(|&&b| b).count(),
        links(&light),
        light.iter().filter(|&&b| b).count(),
        lands
    ]);
    let drawn = driver.run(
        "return ['ray', 'hit', 'light-ray', 'light-hit', 'lands'].map((c) => document.querySelectorAll(`#overlay .${c}`).length)",
    );
    assert_eq!(
        drawn, expected,
        "eye's segments and hits, the light's, landings"
    );
    assert!(lands >= 1 && links(&light) >= 3, "{doc}");
    if let Ok(path) = std::env::var("SNELL_SCREENSHOT_BDPT") {
        let png = driver.session_call("GET", "/screenshot", None);
        std::fs::write(path, base64(png.as_str().unwrap())).unwrap();
    }
}

/// Standard base64, for the screenshot WebDriver sends.
fn base64(text: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => Some(c - b'A'),
        b'a'..=b'z' => Some(c - b'a' + 26),
        b'0'..=b'9' => Some(c - b'0' + 52),
        b'+' => Some(62),
        b'/' => Some(63),
        _ => None,
    };
    let digits: Vec<u8> = text.bytes().filter_map(value).collect();
    digits
        .chunks(4)
        .flat_map(|c| {
            let n = c.iter().fold(0u32, |n, &d| (n << 6) | d as u32) << (6 * (4 - c.len()));
            let bytes = [(n >> 16) as u8, (n >> 8) as u8, n as u8];
            bytes.into_iter().take(c.len().saturating_sub(1))
        })
        .collect()
}
