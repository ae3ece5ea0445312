//! `snell serve` following the files: every way editors save, a texture the scene reads, a
//! mistake and its fix; a long render cancelled by a save; many pages, a stalled one among
//! them; Ctrl-C.

use super::{current_frame, get, seed_copy, start, status, wait_for};
use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::Path;
use std::time::Duration;

const EARTH: &str = "center = [10, 8, -80]\nradius = 4\n";

/// The seed scene with the Earth's radius changed to `r`.
fn with_radius(text: &str, r: &str) -> String {
    assert!(
        text.contains(EARTH),
        "the Earth is where this test expects it"
    );
    text.replace(EARTH, &format!("center = [10, 8, -80]\nradius = {r}\n"))
}

/// Waits for a picture of a render newer than `after`, and returns the status.
fn new_picture(port: u16, after: &serde_json::Value, what: &str) -> serde_json::Value {
    let g = after["generation"].as_u64().unwrap();
    wait_for(port, 30, what, |s| {
        s["generation"].as_u64().unwrap() > g && current_frame(s) && s["error"].is_null()
    })
}

/// Waits for a finished picture newer than `after` after which nothing changes for a
/// while (an editor's save may come as several events), and returns the status.
fn settled(port: u16, after: &serde_json::Value, what: &str) -> serde_json::Value {
    new_picture(port, after, what);
    loop {
        let st = wait_for(port, 30, what, |s| {
            current_frame(s) && s["frame"]["done"] == true
        });
        std::thread::sleep(Duration::from_millis(300));
        let now = status(port);
        if now["generation"] == st["generation"] && now["frame"] == st["frame"] {
            return now;
        }
    }
}

/// Writing in place, writing a new file and renaming it over (vim, VS Code), deleting and
/// writing again, a mistake (shown as `snell check` shows it, over the last picture) and its
/// fix: each brings a new picture, and each new picture differs from the last.
#[test]
fn every_kind_of_save_is_followed() {
    let dir = seed_copy("serve-saves");
    let s = start(&dir, "scenes/seed.toml", &["--size", "64"]);
    let p = s.port;
    let scene = dir.join("scenes/seed.toml");
    let original = std::fs::read_to_string(&scene).unwrap();
    let mut st = settled(
        p,
        &serde_json::json!({"generation": 0}),
        "the first picture",
    );
    let mut last = get(p, "/frame.jpg").body;
    let mut check = |st: &serde_json::Value, what: &str| {
        let frame = get(p, "/frame.jpg").body;
        assert_ne!(frame, last, "{what}: the picture did not change");
        last = frame;
        st.clone()
    };
    // In place.
    std::fs::write(&scene, with_radius(&original, "6")).unwrap();
    st = check(&settled(p, &st, "a save in place"), "in place");
    // A new file renamed over the old one.
    let tmp = dir.join("scenes/.seed.toml.swp");
    std::fs::write(&tmp, with_radius(&original, "2")).unwrap();
    std::fs::rename(&tmp, &scene).unwrap();
    st = check(&settled(p, &st, "a rename over the file"), "renamed over");
    // Deleted, then written again.
    std::fs::remove_file(&scene).unwrap();
    let gone = wait_for(p, 30, "the missing file's message", |s| {
        s["error"].is_string()
    });
    assert!(
        gone["error"]
            .as_str()
            .unwrap()
            .contains("cannot read the scene file")
    );
    assert!(current_frame(&gone), "the last picture stays");
    std::fs::write(&scene, with_radius(&original, "3")).unwrap();
    st = check(&settled(p, &st, "the file written again"), "recreated");
    // A mistake, then its fix.
    std::fs::write(&scene, with_radius(&original, "\"big\"")).unwrap();
    let broken = wait_for(p, 30, "the mistake's message", |s| s["error"].is_string());
    let message = broken["error"].as_str().unwrap();
    assert!(
        message.contains("scenes/seed.toml:114:10") && message.contains("radius = \"big\""),
        "{message}"
    );
    assert_eq!(broken["frame"], st["frame"], "the last good picture stays");
    assert_eq!(status(p)["generation"], st["generation"]);
    std::fs::write(&scene, &original).unwrap();
    check(&settled(p, &st, "the fixed file"), "fixed");
}

/// A texture the scene reads is a file like the scene: a new Earth, a new picture. A swap
/// file beside the scene (what vim writes as one types) is not.
#[test]
fn a_texture_the_scene_reads_is_followed() {
    let dir = seed_copy("serve-texture");
    let s = start(&dir, "scenes/seed.toml", &["--size", "64"]);
    let p = s.port;
    let st = wait_for(p, 30, "the first picture", |s| {
        current_frame(s) && s["frame"]["done"] == true
    });
    std::fs::write(dir.join("scenes/.seed.toml.swp"), "typing").unwrap();
    std::fs::write(dir.join("assets/notes.txt"), "unrelated").unwrap();
    std::thread::sleep(Duration::from_millis(500));
    assert_eq!(
        status(p)["generation"],
        st["generation"],
        "other files are ignored"
    );
    // A plain red Earth.
    image::RgbImage::from_pixel(8, 4, image::Rgb([255, 0, 0]))
        .save(dir.join("assets/earth.jpg"))
        .unwrap();
    new_picture(p, &st, "the new texture");
    // The Earth's centre (10, 8, -80) is at pixel (48, 19) of 64 x 64, and its surface
    // colour is now red.
    assert_eq!(get(p, "/pick?x=48&y=19").json()["object"], "earth");
    let albedo = image::load_from_memory(&get(p, "/view/albedo.png").body)
        .unwrap()
        .to_rgb8();
    // Red, to the JPEG's rounding.
    let [r, g, b] = albedo.get_pixel(48, 19).0;
    assert!(r > 240 && g < 16 && b < 16, "{:?}", [r, g, b]);
}

/// A render that would take minutes (Whitted at 65,536 samples a pixel) is cancelled by a
/// save: the new scene's first picture comes long before the old render could have ended.
#[test]
fn a_save_cancels_a_long_render() {
    let dir = seed_copy("serve-cancel");
    let s = start(
        &dir,
        "scenes/seed.toml",
        &["--size", "128", "--spp", "65536"],
    );
    let p = s.port;
    // The one-sample picture, then the long pass under way.
    let st = wait_for(p, 30, "the first picture", current_frame);
    assert_eq!(st["frame"]["spp"], 1);
    std::thread::sleep(Duration::from_millis(300));
    let scene = dir.join("scenes/seed.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    std::fs::write(&scene, with_radius(&text, "6")).unwrap();
    // Without cancellation the old pass (128 x 128 x 65,536 samples) would hold the loop for
    // minutes; the test waits 30 s at most.
    let st = new_picture(p, &st, "the new scene's first picture");
    assert_eq!(st["frame"]["spp"], 1);
}

/// Many pages at once each get the stream; a page that stops reading neither stops the
/// render nor the other pages.
#[test]
fn many_pages_and_a_stalled_one() {
    let dir = seed_copy("serve-pages");
    let s = start(&dir, "scenes/seed.toml", &["--size", "64"]);
    let p = s.port;
    let st = wait_for(p, 30, "the first picture", current_frame);
    let open = || {
        let mut c = TcpStream::connect(("127.0.0.1", p)).unwrap();
        write!(c, "GET /events HTTP/1.1\r\nHost: 127.0.0.1:{p}\r\n\r\n").unwrap();
        c
    };
    // A stalled page: it asked for the stream and never reads it.
    let _stalled: Vec<TcpStream> = (0..3).map(|_| open()).collect();
    let mut pages: Vec<TcpStream> = (0..8).map(|_| open()).collect();
    let scene = dir.join("scenes/seed.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    let mut last = st;
    for r in ["5", "6", "7"] {
        std::fs::write(&scene, with_radius(&text, r)).unwrap();
        last = new_picture(p, &last, "a picture with pages open");
    }
    for page in &mut pages {
        page.set_read_timeout(Some(Duration::from_secs(10)))
            .unwrap();
        let mut buf = vec![0u8; 8192];
        let n = page.read(&mut buf).unwrap();
        let got = String::from_utf8_lossy(&buf[..n]);
        assert!(got.contains("text/event-stream"), "{got}");
    }
    assert_eq!(get(p, "/frame.jpg").status, 200);
}

/// Ctrl-C (SIGINT) stops the server cleanly: exit code 0 and a last word.
#[cfg(unix)]
#[test]
fn ctrl_c_stops_the_server() {
    let dir = seed_copy("serve-stop");
    let mut s = start(&dir, "scenes/seed.toml", &["--size", "32"]);
    wait_for(s.port, 30, "the first picture", current_frame);
    // An open stream does not hold the server up.
    let _page = TcpStream::connect(("127.0.0.1", s.port)).map(|mut c| {
        let _ = write!(
            c,
            "GET /events HTTP/1.1\r\nHost: 127.0.0.1:{}\r\n\r\n",
            s.port
        );
        c
    });
    let killed = std::process::Command::new("kill")
        .args(["-INT", &s.child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let start = std::time::Instant::now();
    let code = loop {
        if let Some(c) = s.child.try_wait().unwrap() {
            break c;
        }
        assert!(start.elapsed().as_secs() < 20, "still running after Ctrl-C");
        std::thread::sleep(Duration::from_millis(20));
    };
    assert_eq!(code.code(), Some(0));
    let mut out = String::new();
    s.child
        .stdout
        .take()
        .unwrap()
        .read_to_string(&mut out)
        .unwrap();
    assert!(out.contains("stopped"), "{out}");
    assert!(
        !Path::new(&s.dir)
            .join("scenes/seed.toml")
            .with_extension("png")
            .exists()
    );
}

/// `--frame N` shows that frame of an animated scene; a frame it does not have is the
/// scene's error on the page, as any mistake in the file is.
#[test]
fn a_frame_of_an_animation_is_shown() {
    let dir = crate::scratch("serve-frame");
    std::fs::write(
        dir.join("anim.toml"),
        "[image]\nwidth = 32\nheight = 24\n[camera]\nposition = [0, 0, 6]\nlook_at = [0, 0, 0]\n\
         [materials.m]\ncolor = 0.5\n[[lights]]\ntype = \"point\"\nposition = [0, 4, 6]\n\
         [[objects]]\nname = \"ball\"\ntype = \"sphere\"\nradius = 1\nmaterial = \"m\"\n\
         [animation]\nframes = 4\n[[animation.objects]]\nobject = \"ball\"\nframe = 0\n\
         translate = [0, 0, 0]\n[[animation.objects]]\nobject = \"ball\"\nframe = 3\n\
         translate = [1, 0, 0]\n",
    )
    .unwrap();
    let shown = start(&dir, "anim.toml", &["--frame", "2"]);
    let s = wait_for(shown.port, 30, "frame 2's picture", |s| {
        current_frame(s) && s["error"].is_null()
    });
    assert!(s["error"].is_null(), "{s}");
    let past = start(&dir, "anim.toml", &["--frame", "9"]);
    let s = wait_for(past.port, 30, "the missing frame's message", |s| {
        s["error"].is_string()
    });
    let message = s["error"].as_str().unwrap();
    assert!(
        message.contains("frame 9 was asked for, but the animation has 4 frames"),
        "{message}"
    );
}
