//! Every route of `snell serve`, and the requests it must refuse.

use super::{current_frame, get, post, raw, scene_copy, seed_copy, start, status, wait_for};

/// The page and its files, the status, the frame (tone mapped on request), every debug
/// view, the explain data and the pick, the event stream, the camera.
#[test]
fn every_route_answers() {
    let dir = seed_copy("serve-routes");
    let s = start(&dir, "scenes/seed.toml", &["--size", "96"]);
    let p = s.port;
    let page = get(p, "/");
    assert_eq!(page.status, 200);
    assert!(
        page.header("content-type")
            .unwrap()
            .starts_with("text/html")
    );
    assert!(page.text().contains("<img id=\"frame\""));
    assert!(
        page.header("content-security-policy")
            .unwrap()
            .contains("default-src 'self'")
    );
    assert!(
        page.text()
            .contains("<script type=\"module\" src=\"/app.js\">")
    );
    // The script is ES modules, each served on its own route; every module one imports is
    // among them.
    let modules = [
        "app.js",
        "state.js",
        "picture.js",
        "explain.js",
        "paths.js",
        "camera.js",
    ];
    for (path, kind, needle) in [
        ("/app.js", "text/javascript", "EventSource"),
        ("/state.js", "text/javascript", "export const state"),
        ("/picture.js", "text/javascript", "/frame.jpg"),
        ("/explain.js", "text/javascript", "/explain?"),
        ("/paths.js", "text/javascript", "/paths?"),
        ("/camera.js", "text/javascript", "'/camera'"),
        ("/style.css", "text/css", "#frame-box"),
    ] {
        let r = get(p, path);
        assert_eq!(r.status, 200, "{path}");
        assert!(
            r.header("content-type").unwrap().starts_with(kind),
            "{path}"
        );
        let text = r.text();
        assert!(text.contains(needle), "{path}");
        for import in text.split(" from './").skip(1) {
            let name = import.split('\'').next().unwrap();
            assert!(modules.contains(&name), "{path} imports {name}");
        }
    }
    let st = wait_for(p, 30, "a finished picture", |s| {
        current_frame(s) && s["frame"]["done"] == true
    });
    assert_eq!(st["integrator"], "whitted");
    assert_eq!(st["size"], serde_json::json!([96, 96]));
    assert_eq!(st["frame"]["spp"], 16);
    assert!(st["error"].is_null());
    assert!(
        st["files"]
            .as_array()
            .unwrap()
            .iter()
            .any(|f| f.as_str().unwrap().ends_with("earth.jpg"))
    );
    // The frame, as a JPEG, tone mapped as asked without rendering again.
    let plain = get(p, "/frame.jpg");
    assert_eq!(plain.status, 200);
    assert_eq!(plain.header("content-type"), Some("image/jpeg"));
    assert_eq!(&plain.body[..2], &[0xFF, 0xD8]);
    let bright = get(p, "/frame.jpg?exposure=2&tone=aces");
    assert_eq!(bright.status, 200);
    assert_ne!(bright.body, plain.body);
    let decode = |b: &[u8]| image::load_from_memory(b).unwrap().to_rgb8();
    let (a, b) = (decode(&plain.body), decode(&bright.body));
    assert_eq!((a.width(), a.height()), (96, 96));
    let mean = |i: &image::RgbImage| i.pixels().map(|p| p.0[0] as f64).sum::<f64>();
    assert!(mean(&b) > mean(&a), "two stops brighter");
    assert_eq!(status(p)["generation"], st["generation"], "no new render");
    // Values are percent-decoded: `%61ces` is `aces`, `%2B2` is `+2`.
    let encoded = get(p, "/frame.jpg?exposure=%2B2&tone=%61ces");
    assert_eq!(encoded.status, 200);
    assert_eq!(encoded.body, bright.body);
    let mut refused = 0;
    for bad in [
        "/frame.jpg?tone=sepia",
        "/frame.jpg?exposure=x",
        "/frame.jpg?exposure=99",
        "/frame.jpg?exposure=1&exposure=2",
        "/frame.jpg?exposure=%ZZ",
    ] {
        assert_eq!(get(p, bad).status, 400, "{bad}");
        refused += 1;
    }
    assert_eq!(refused, 5);
    // Every debug view.
    for view in [
        "normal", "uv", "depth", "albedo", "object", "material", "bounces",
    ] {
        let r = get(p, &format!("/view/{view}.png"));
        assert_eq!(r.status, 200, "{view}");
        assert_eq!(&r.body[1..4], b"PNG", "{view}");
    }
    assert_eq!(get(p, "/view/colour.png").status, 404);
    // The denoised picture: without the feature, a 404 that says how to build it.
    if !snell::denoise::AVAILABLE {
        let r = get(p, "/denoised.png?g=1");
        assert_eq!(r.status, 404);
        assert!(r.text().contains("pip install pyoidn"), "{}", r.text());
    }
    assert_eq!(
        get(p, "/denoised.png?g=1&tone=sepia").status,
        if snell::denoise::AVAILABLE { 400 } else { 404 }
    );
    // The views read from the path tracer's film are not a Whitted preview's.
    for view in ["variance", "spp"] {
        let r = get(p, &format!("/view/{view}.png"));
        assert_eq!(r.status, 404, "{view}");
        assert!(r.text().contains("path tracer's"), "{}", r.text());
    }
    // The light path views (the path tracer's, though the preview is Whitted's), tone mapped
    // as asked; the four that share out every path add up to something brighter than each.
    let mut views = 0;
    for name in ["emission", "direct", "indirect", "specular", "caustics"] {
        let r = get(p, &format!("/lpe/{name}.png?g=1&exposure=1&tone=aces"));
        assert_eq!(r.status, 200, "{name}: {}", r.text());
        assert_eq!(r.header("content-type"), Some("image/png"));
        let img = image::load_from_memory(&r.body).unwrap();
        assert_eq!((img.width(), img.height()), (96, 96), "{name}");
        views += 1;
    }
    assert_eq!(views, 5);
    let mut refused = 0;
    for (bad, code) in [
        ("/lpe/per-light.png", 404),
        ("/lpe/sideways.png", 404),
        ("/lpe/direct", 404),
        ("/lpe/direct.png?exposure=99", 400),
        ("/lpe/direct.png?tone=sepia", 400),
        ("/lpe/direct.png?expr=CL", 400),
        ("/paths?x=96&y=0", 400),
        ("/paths?x=1", 400),
        ("/paths?x=1&y=2&samples=100000", 400),
    ] {
        assert_eq!(get(p, bad).status, code, "{bad}");
        refused += 1;
    }
    assert_eq!(refused, 9);
    // A pixel's light by kind of path: the red sphere's is mostly direct diffuse light, and
    // the kinds' shares add up to 1.
    let red = get(p, "/pick?x=71&y=79").json();
    assert_eq!(red["object"], "red sphere");
    let paths = get(p, "/paths?x=71&y=79");
    assert_eq!(paths.status, 200, "{}", paths.text());
    let doc = paths.json();
    let kinds = doc["kinds"].as_array().unwrap();
    let total: f64 = kinds.iter().map(|k| k["share"].as_f64().unwrap()).sum();
    assert!((total - 1.0).abs() < 1e-3, "{doc}");
    assert_eq!(kinds[1]["name"], "direct, diffuse");
    assert!(kinds[1]["share"].as_f64().unwrap() > 0.5, "{doc}");
    assert!(!doc["paths"].as_array().unwrap().is_empty());
    // The diamond sphere's pixel: a Whitted tree with a refraction in it, and its points
    // placed on the picture.
    let pick = get(p, "/pick?x=48&y=71").json();
    assert_eq!(pick["object"], "diamond sphere");
    assert_eq!(pick["material"], "diamond");
    let ex = get(p, "/explain?x=48&y=71");
    assert_eq!(ex.status, 200);
    let doc = ex.json();
    assert_eq!(doc["integrator"], "whitted");
    assert_eq!(doc["tree"]["hit"]["object"], "diamond sphere");
    let text = ex.text();
    assert!(text.contains("\"refraction\""), "{text}");
    let screen = &doc["tree"]["hit"]["screen"];
    let (x, y) = (screen[0].as_f64().unwrap(), screen[1].as_f64().unwrap());
    assert!((x - 48.5).abs() < 0.5 && (y - 71.5).abs() < 0.5, "{screen}");
    assert_eq!(
        get(p, "/pick?x=4%38&y=71").json()["object"],
        "diamond sphere"
    );
    let mut refused = 0;
    for bad in [
        "/explain",
        "/explain?x=96&y=0",
        "/explain?x=-1&y=3",
        "/pick?x=1",
        "/pick?x=48&y=71&x=2",
        "/pick?x=4.5&y=71",
    ] {
        assert_eq!(get(p, bad).status, 400, "{bad}");
        refused += 1;
    }
    assert_eq!(refused, 6);
    // The event stream starts with the status.
    let mut c = std::net::TcpStream::connect(("127.0.0.1", p)).unwrap();
    c.set_read_timeout(Some(std::time::Duration::from_secs(30)))
        .unwrap();
    std::io::Write::write_all(
        &mut c,
        format!("GET /events HTTP/1.1\r\nHost: 127.0.0.1:{p}\r\n\r\n").as_bytes(),
    )
    .unwrap();
    let mut got = vec![];
    let mut buf = [0u8; 4096];
    while !String::from_utf8_lossy(&got).contains("}\n\n") {
        let n = std::io::Read::read(&mut c, &mut buf).unwrap();
        assert!(n > 0, "the stream ended: {}", String::from_utf8_lossy(&got));
        got.extend_from_slice(&buf[..n]);
    }
    let got = String::from_utf8_lossy(&got);
    assert!(got.starts_with("HTTP/1.1 200"), "{got}");
    assert!(
        got.to_ascii_lowercase()
            .contains("content-type: text/event-stream"),
        "{got}"
    );
    assert!(got.contains("event: status\ndata: {"), "{got}");
    // The camera: moved, refused when it is no camera, and put back.
    let moved = post(
        p,
        "/camera",
        r#"{"position": [10, 5, 20], "look_at": [0, 0, -60], "up": [0, 1, 0], "fov": 30}"#,
    );
    assert_eq!(moved.status, 200, "{}", moved.text());
    let st = wait_for(p, 30, "the moved camera's picture", |s| {
        s["camera_moved"] == true && current_frame(s) && s["camera"]["position"][0] == 10.0
    });
    assert_eq!(st["camera"]["fov"], 30.0);
    for bad in [
        r#"{"position": [0, 0, 0], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 30}"#,
        r#"{"position": [0, 0, 0], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov": 30}"#,
        r#"{"position": [0, 0, 0], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov": 180}"#,
        r#"{"position": [0, 0], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov": 30}"#,
        r#"{"position": [0, 0, 0], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov": 30, "x": 1}"#,
        "not json",
    ] {
        assert_eq!(post(p, "/camera", bad).status, 400, "{bad}");
    }
    assert_eq!(post(p, "/camera/reset", "").status, 200);
    wait_for(p, 30, "the file's camera again", |s| {
        s["camera_moved"] == false && s["camera"]["position"][0] == 0.0
    });
    // The scene file was never written.
    assert_eq!(
        std::fs::read_to_string(dir.join("scenes/seed.toml")).unwrap(),
        std::fs::read_to_string(super::super::repo("scenes/seed.toml")).unwrap()
    );
    // Other methods.
    for (method, path) in [
        ("PUT", "/"),
        ("DELETE", "/status"),
        ("POST", "/frame.jpg"),
        ("GET", "/camera"),
    ] {
        let r = raw(
            p,
            &format!(
                "{method} {path} HTTP/1.1\nHost: 127.0.0.1:{p}\nContent-Length: 0\nConnection: close"
            ),
            b"",
        );
        assert_eq!(r.status, 405, "{method} {path}");
    }
}

/// No URL reaches a file: `..`, encoded dots and slashes, absolute paths, the scene's own
/// name, a symlink beside it. Only the page's three files and the routes answer.
#[test]
fn hostile_paths_reach_no_file() {
    let dir = seed_copy("serve-paths");
    #[cfg(unix)]
    std::os::unix::fs::symlink("/etc/passwd", dir.join("scenes/link")).unwrap();
    let s = start(&dir, "scenes/seed.toml", &["--size", "32"]);
    let p = s.port;
    for path in [
        "/../Cargo.toml",
        "/../../../../etc/passwd",
        "/%2e%2e/%2e%2e/%2e%2e/etc/passwd",
        "/%2E%2E%2F%2E%2E%2Fetc%2Fpasswd",
        "/..%2f..%2f..%2fetc%2fpasswd",
        "/..\\..\\etc\\passwd",
        "//etc/passwd",
        "/etc/passwd",
        "/scenes/seed.toml",
        "/seed.toml",
        "/scenes/link",
        "/link",
        "/assets/earth.jpg",
        "/view/../../scenes/seed.toml",
        "/view/%2e%2e/seed.toml",
        "/app.js/../../Cargo.toml",
        "/./app.js/..",
        "/state.js/../../Cargo.toml",
        "/page/app.js",
        "/main.js",
        "/frame.jpg/../../etc/passwd",
        "/index.html",
        "http://127.0.0.1/../etc/passwd",
        "*",
    ] {
        let r = get(p, path);
        assert!(matches!(r.status, 400 | 404), "{path}: {}", r.status);
        let body = r.text();
        assert!(
            !body.contains("root:") && !body.contains("[camera]") && !body.contains("[package]"),
            "{path} leaked a file: {body}"
        );
    }
    // A request line that is no HTTP at all gets no page, and the server goes on.
    let mut c = std::net::TcpStream::connect(("127.0.0.1", p)).unwrap();
    std::io::Write::write_all(&mut c, b"GARBAGE\r\n\r\n").unwrap();
    c.set_read_timeout(Some(std::time::Duration::from_secs(10)))
        .unwrap();
    let mut answer = vec![];
    let _ = std::io::Read::read_to_end(&mut c, &mut answer);
    let answer = String::from_utf8_lossy(&answer);
    assert!(!answer.contains(" 200 "), "{answer}");
    assert_eq!(get(p, "/status").status, 200);
}

/// DNS rebinding: a page elsewhere that makes its own name point at 127.0.0.1 sends its own
/// name as Host; such requests, and ones without a Host, are refused. Cross-origin requests
/// (another site's page reading the stream or moving the camera) are refused too.
#[test]
fn foreign_hosts_and_origins_are_refused() {
    let dir = seed_copy("serve-hosts");
    let s = start(&dir, "scenes/seed.toml", &["--size", "32"]);
    let p = s.port;
    for host in [
        format!("attacker.example:{p}"),
        "attacker.example".to_string(),
        format!("127.0.0.1:{}", p.wrapping_add(1)),
        format!("localhost.attacker.example:{p}"),
    ] {
        let r = raw(
            p,
            &format!("GET /status HTTP/1.1\nHost: {host}\nConnection: close"),
            b"",
        );
        assert_eq!(r.status, 403, "Host: {host}");
        assert!(!r.text().contains("\"frame\""), "Host: {host}");
    }
    let none = raw(p, "GET /status HTTP/1.0", b"");
    assert_eq!(none.status, 403, "no Host");
    for ok in [
        format!("localhost:{p}"),
        format!("LOCALHOST:{p}"),
        format!("[::1]:{p}"),
    ] {
        let r = raw(
            p,
            &format!("GET /status HTTP/1.1\nHost: {ok}\nConnection: close"),
            b"",
        );
        assert_eq!(r.status, 200, "Host: {ok}");
    }
    let body = r#"{"position": [1, 1, 1], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov": 30}"#;
    for origin in [
        "http://attacker.example",
        "null",
        &format!("https://127.0.0.1:{p}"),
    ] {
        let events = raw(
            p,
            &format!(
                "GET /events HTTP/1.1\nHost: 127.0.0.1:{p}\nOrigin: {origin}\nConnection: close"
            ),
            b"",
        );
        assert_eq!(events.status, 403, "events from {origin}");
        let camera = raw(
            p,
            &format!(
                "POST /camera HTTP/1.1\nHost: 127.0.0.1:{p}\nOrigin: {origin}\nContent-Length: {}\nConnection: close",
                body.len()
            ),
            body.as_bytes(),
        );
        assert_eq!(camera.status, 403, "camera from {origin}");
    }
    assert_eq!(status(p)["camera_moved"], false);
    // A body past the limit is not read whole.
    let big = format!("{{\"position\": [{}1, 1, 1]}}", " ".repeat(10_000));
    assert_eq!(post(p, "/camera", &big).status, 413);
}

/// A scene with a mistake when the server starts: the page shows the same message as
/// `snell check`; a scene file that does not exist is refused at once.
#[test]
fn a_broken_scene_is_shown_and_a_missing_one_refused() {
    let dir = super::super::scratch("serve-broken");
    std::fs::write(
        dir.join("bad.toml"),
        "[camera]\nlook_at = [0, 0, -1]\n[materials.m]\ncolour = 1\n",
    )
    .unwrap();
    let s = start(&dir, "bad.toml", &[]);
    let st = wait_for(s.port, 30, "the error", |s| s["error"].is_string());
    let check = std::process::Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(["check", "bad.toml"])
        .current_dir(&dir)
        .output()
        .unwrap();
    let check = String::from_utf8_lossy(&check.stderr);
    assert_eq!(
        st["error"].as_str().unwrap(),
        check,
        "the page shows what check prints"
    );
    assert!(
        check.contains("bad.toml:4:1") && check.contains("did you mean `color`?"),
        "{check}"
    );
    assert!(st["frame"].is_null());
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(["serve", "nowhere.toml", "--port", "0"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("cannot read nowhere.toml"));
}

/// The page shows the picture as `snell render` writes it: the scene's `[image] exposure`
/// and `tonemap` (environment.toml: ACES at -1 stop) are in the status for the page's
/// controls and are what `/frame.jpg` applies when not told otherwise, so the frame's mean
/// equals the rendered PNG's at the same samples (within JPEG's error), where exposure 0
/// and `clamp` (what the page used to show) are far off.
#[test]
fn the_frame_is_toned_as_the_render_writes_it() {
    let dir = super::super::scratch("serve-tone");
    std::fs::create_dir_all(dir.join("scenes")).unwrap();
    std::fs::create_dir_all(dir.join("assets/env")).unwrap();
    for f in ["scenes/environment.toml", "assets/env/studio.hdr"] {
        std::fs::copy(super::super::repo(f), dir.join(f)).unwrap();
    }
    let s = start(
        &dir,
        "scenes/environment.toml",
        &["--size", "64", "--spp", "8"],
    );
    let st = wait_for(s.port, 60, "a finished picture", |s| {
        current_frame(s) && s["frame"]["done"] == true
    });
    assert_eq!(
        st["tone"],
        serde_json::json!({"exposure": -1.0, "curve": "aces"})
    );
    let (w, h) = (
        st["size"][0].as_u64().unwrap(),
        st["size"][1].as_u64().unwrap(),
    );
    let spp = st["frame"]["spp"].as_u64().unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_snell"))
        .args([
            "render",
            "scenes/environment.toml",
            "-o",
            "r.png",
            "--quiet",
        ])
        .args(["--width", &w.to_string(), "--height", &h.to_string()])
        .args(["--spp", &spp.to_string()])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mean = |img: image::RgbImage| {
        img.pixels().flat_map(|p| p.0).map(f64::from).sum::<f64>() / (img.len() as f64)
    };
    let png = mean(image::open(dir.join("r.png")).unwrap().to_rgb8());
    let jpeg = |path: &str| {
        mean(
            image::load_from_memory(&get(s.port, path).body)
                .unwrap()
                .to_rgb8(),
        )
    };
    let shown = jpeg("/frame.jpg");
    assert!(
        (shown - png).abs() < 1.0,
        "the page's picture {shown}, the PNG {png}"
    );
    let asked = jpeg("/frame.jpg?exposure=-1&tone=aces");
    assert!((asked - shown).abs() < 0.01, "{asked} {shown}");
    let old = jpeg("/frame.jpg?exposure=0&tone=clamp");
    assert!(
        (old - png).abs() > 5.0,
        "exposure 0 and clamp: {old}, the PNG {png}"
    );
}

/// The sampling lab's page, script and answers, and the queries it refuses: unknown keys and
/// types, values out of range, a metal's name that is not a name.
#[test]
fn the_lab_answers_and_refuses_bad_queries() {
    let dir = seed_copy("serve-lab");
    let s = start(&dir, "scenes/seed.toml", &["--size", "32"]);
    let p = s.port;
    let page = get(p, "/lab");
    assert_eq!(page.status, 200);
    assert!(
        page.text()
            .contains("<script type=\"module\" src=\"/lab.js\">")
    );
    let script = get(p, "/lab.js");
    assert!(
        script
            .header("content-type")
            .unwrap()
            .starts_with("text/javascript")
    );
    assert!(script.text().contains("'/lab/bsdf?'"));
    assert!(get(p, "/").text().contains("href=\"/lab\""));
    let ok = get(p, "/lab/bsdf?type=plastic&roughness=0.3&angle=40");
    assert_eq!(ok.status, 200, "{}", ok.text());
    let t = ok.json();
    assert_eq!(t["passed"], true, "{t}");
    assert_eq!(t["observed"].as_array().unwrap().len(), 40 * 80);
    assert_eq!(t["samples"], 1 << 18);
    let gold = get(p, "/lab/bsdf?type=conductor&metal=Au&roughness=0.2");
    assert_eq!(gold.status, 200, "{}", gold.text());
    let mut refused = 0;
    for (query, said) in [
        ("type=plastik", "did you mean `plastic`"),
        ("type=plastic&samples=100000000", "samples"),
        ("type=plastic&angle=95", "angle"),
        ("type=plastic&roughness=abc", "roughness"),
        ("type=plastic&roughness=-1", "roughness"),
        ("type=diffuse&ior=1.5", "ior"),
        ("type=conductor&metal=Au%22%0A%5Bx%5D", "metal"),
        ("type=conductor&metal=Unobtainium", "metal"),
        ("roughness=0.3", "type"),
        ("type=plastic&type=diffuse", "type"),
    ] {
        let r = get(p, &format!("/lab/bsdf?{query}"));
        assert_eq!(r.status, 400, "{query}: {}", r.text());
        assert!(r.text().contains(said), "{query}: {}", r.text());
        refused += 1;
    }
    assert_eq!(refused, 10);
}

/// A scene rendered by bdpt is previewed by bdpt, in passes: its finished frame is the
/// render's picture at the same samples (within JPEG's error), caustics and all.
#[test]
fn a_bdpt_scene_is_previewed_bidirectionally() {
    let dir = scene_copy("serve-bdpt", "caustics.toml");
    let s = start(
        &dir,
        "scenes/caustics.toml",
        &["--size", "48", "--spp", "4"],
    );
    let st = wait_for(s.port, 60, "a finished picture", |s| {
        current_frame(s) && s["frame"]["done"] == true
    });
    assert_eq!(st["integrator"], "bdpt");
    let (w, h) = (
        st["size"][0].as_u64().unwrap(),
        st["size"][1].as_u64().unwrap(),
    );
    assert_eq!(st["frame"]["spp"], 4);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(["render", "scenes/caustics.toml", "-o", "r.png", "--quiet"])
        .args(["--width", &w.to_string(), "--height", &h.to_string()])
        .args(["--spp", "4"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mean = |img: image::RgbImage| {
        img.pixels().flat_map(|p| p.0).map(f64::from).sum::<f64>() / (img.len() as f64)
    };
    let png = mean(image::open(dir.join("r.png")).unwrap().to_rgb8());
    let shown = mean(
        image::load_from_memory(&get(s.port, "/frame.jpg").body)
            .unwrap()
            .to_rgb8(),
    );
    assert!(png > 5.0, "{png}");
    assert!(
        (shown - png).abs() < 1.0,
        "the page's picture {shown}, the PNG {png}"
    );
    // A pixel is explained bidirectionally, as `snell explain --integrator bdpt` does: the
    // sample's strategies and its two subpaths, whose first hit lies on the picture within
    // the filter's reach of the pixel.
    let ex = get(s.port, "/explain?x=24&y=30");
    assert_eq!(ex.status, 200, "{}", ex.text());
    let doc = ex.json();
    assert_eq!(doc["integrator"], "bdpt");
    assert!(doc["strategies"].is_array(), "{doc}");
    let eye = doc["camera_path"].as_array().unwrap();
    assert_eq!(eye[0]["what"], "the eye");
    assert!(eye[0]["screen"].is_null(), "{doc}");
    let hit = &eye[1]["screen"];
    let (x, y) = (hit[0].as_f64().unwrap(), hit[1].as_f64().unwrap());
    assert!((x - 24.5).abs() < 2.0 && (y - 30.5).abs() < 2.0, "{hit}");
    assert!(!doc["light_path"].as_array().unwrap().is_empty(), "{doc}");
}

/// A path-traced preview with `--noise` samples adaptively, as `render --noise` does: it
/// finishes once every pixel has converged or reached the cap, and its `spp` view maps the
/// samples (the light's pixels at 16, the dark corners at the cap) and `variance` the noise.
#[test]
fn an_adaptive_preview_maps_its_samples() {
    let dir = scene_copy("serve-adaptive", "cornell.toml");
    let s = start(
        &dir,
        "scenes/cornell.toml",
        &["--size", "32", "--spp", "128", "--noise", "0.1"],
    );
    let st = wait_for(s.port, 60, "a finished picture", |s| {
        current_frame(s) && s["frame"]["done"] == true
    });
    assert_eq!(st["integrator"], "path");
    let mut seen = 0;
    for view in ["spp", "variance"] {
        let r = get(s.port, &format!("/view/{view}.png?id=1"));
        assert_eq!(r.status, 200, "{view}: {}", r.text());
        let img = image::load_from_memory(&r.body).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), (32, 32), "{view}");
        let colours: std::collections::BTreeSet<[u8; 3]> = img.pixels().map(|p| p.0).collect();
        assert!(colours.len() >= 3, "{view}: {colours:?}");
        seen += 1;
    }
    assert_eq!(seen, 2);
}

/// With the `denoise` feature, the preview's denoised picture: the newest frame denoised, a
/// PNG of the preview's size; a bad tone is refused.
#[cfg(feature = "denoise")]
#[test]
fn the_preview_shows_the_picture_denoised() {
    let dir = scene_copy("serve-denoised", "cornell.toml");
    let s = start(&dir, "scenes/cornell.toml", &["--size", "48", "--spp", "8"]);
    wait_for(s.port, 60, "a finished picture", |s| {
        current_frame(s) && s["frame"]["done"] == true
    });
    let r = get(s.port, "/denoised.png?g=1&exposure=0&tone=clamp");
    assert_eq!(r.status, 200, "{}", r.text());
    let img = image::load_from_memory(&r.body).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (48, 48));
    assert!(img.pixels().any(|p| p.0[0] > 100), "something is lit");
    assert_eq!(get(s.port, "/denoised.png?g=1&tone=sepia").status, 400);
}
