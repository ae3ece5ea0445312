//! The library's entry point, `render::to_files::render_to_files`: the same files as
//! `snell render` of the same job, progress up to the whole, and a cancelled render's
//! picture beside the old one, never over it.

use crate::cli::snell;
use crate::{repo, scratch};
use snell::integrator::aov::Aov;
use snell::job::{Overrides, RenderJob};
use snell::render::to_files::{JobProgress, RunOptions, render_to_files};
use snell::scene::Limits;
use std::sync::Mutex;
use std::sync::atomic::AtomicBool;

fn prepared(scene: &str, overrides: &Overrides) -> RenderJob {
    RenderJob::prepare(&repo(scene), overrides, &Limits::default(), None).unwrap()
}

/// Both integrators, to PNG with views and to EXR with layers: the library writes what the
/// command line writes, byte for byte, and its progress ends at the total.
#[test]
fn the_library_writes_what_the_command_line_writes() {
    let dir = scratch("library-same");
    let cases = [
        ("scenes/seed.toml", None, "seed", "png"),
        ("scenes/cornell.toml", Some(4), "cornell", "png"),
        ("scenes/cornell.toml", Some(4), "cornell", "exr"),
    ];
    let mut compared = 0;
    for (scene, spp, name, ext) in cases {
        let overrides = Overrides {
            width: Some(48),
            height: Some(40),
            spp,
            ..Overrides::default()
        };
        let job = prepared(scene, &overrides);
        let ours = dir.join(format!("{name}-lib.{ext}"));
        let last = Mutex::new(None);
        let progress = |p: JobProgress| {
            let mut last = last.lock().unwrap();
            if last.is_none_or(|l: JobProgress| p.done >= l.done) {
                *last = Some(p);
            }
        };
        let options = RunOptions {
            threads: Some(2),
            progress: &progress,
            cancel: None,
            time: None,
            lpe: &[],
        };
        let views = [Aov::Normal, Aov::Depth];
        let done = render_to_files(&job, &ours, &views, &options).unwrap();
        assert!(done.complete, "{name}");
        let last = last.lock().unwrap().expect("progress was reported");
        assert_eq!(last.done, last.total, "{name}: progress ends at the whole");
        assert_eq!(last.total, 48 * 40 * done.spp as u64, "{name}");

        let theirs = dir.join(format!("{name}-cli.{ext}"));
        let mut args = vec![
            "render",
            scene,
            "--width",
            "48",
            "--height",
            "40",
            "--aov",
            "normal,depth",
            "--quiet",
            "-o",
            theirs.to_str().unwrap(),
        ];
        let spp_text = spp.map(|n| n.to_string());
        if let Some(n) = &spp_text {
            args.extend(["--spp", n]);
        }
        let out = snell(&args, &repo(""));
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let mut files = vec![(ours.clone(), theirs.clone())];
        if ext == "png" {
            for view in ["normal", "depth"] {
                let with = |p: &std::path::Path| p.with_extension(format!("{view}.png"));
                files.push((with(&ours), with(&theirs)));
            }
        }
        for (a, b) in files {
            let (a_bytes, b_bytes) = (std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
            assert!(
                a_bytes == b_bytes,
                "{} differs from {}",
                a.display(),
                b.display()
            );
            compared += 1;
        }
    }
    assert_eq!(compared, 7);
}

/// Cancelled before it starts, a render writes its picture to the partial name and leaves
/// an older picture alone; the variance view is refused for Whitted before anything is
/// written.
#[test]
fn a_cancelled_render_keeps_the_old_picture() {
    let dir = scratch("library-cancel");
    let out = dir.join("c.png");
    std::fs::write(&out, b"old").unwrap();
    let overrides = Overrides {
        width: Some(32),
        height: Some(32),
        spp: Some(4),
        ..Overrides::default()
    };
    let job = prepared("scenes/cornell.toml", &overrides);
    let cancel = AtomicBool::new(true);
    let options = RunOptions {
        threads: Some(1),
        progress: &|_| {},
        cancel: Some(&cancel),
        time: None,
        lpe: &[],
    };
    let done = render_to_files(&job, &out, &[], &options).unwrap();
    assert!(!done.complete);
    assert_eq!(std::fs::read(&out).unwrap(), b"old");
    assert!(dir.join("c.partial.png").is_file());

    let whitted = prepared("scenes/seed.toml", &overrides);
    let refused = render_to_files(&whitted, &dir.join("s.png"), &[Aov::Variance], &options);
    assert!(refused.unwrap_err().to_string().contains("variance"));
    assert!(!dir.join("s.png").exists());
}

/// A light path expression through the library's one call: its PNG beside the picture, the
/// command line's bytes; a Whitted scene's expression is an error before any file.
#[test]
fn render_to_files_writes_light_path_expressions_as_the_command_line_does() {
    use snell::lpe::{Preset, Request};
    let dir = scratch("library-lpe");
    let overrides = Overrides {
        width: Some(24),
        height: Some(20),
        spp: Some(4),
        ..Overrides::default()
    };
    let job = prepared("scenes/cornell.toml", &overrides);
    let lpe = [Request::Preset(Preset::Direct)];
    let options = RunOptions {
        threads: Some(2),
        progress: &|_| {},
        cancel: None,
        time: None,
        lpe: &lpe,
    };
    let done = render_to_files(&job, &dir.join("lib.png"), &[], &options).unwrap();
    assert!(done.complete);
    assert_eq!(done.layers.len(), 1);
    assert_eq!(done.layers[0].0, "direct");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(["render", repo("scenes/cornell.toml").to_str().unwrap()])
        .args([
            "-o", "cli.png", "--width", "24", "--height", "20", "--spp", "4", "-q",
        ])
        .args(["--lpe", "direct"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0));
    for (ours, theirs) in [("lib.png", "cli.png"), ("lib.direct.png", "cli.direct.png")] {
        assert_eq!(
            std::fs::read(dir.join(ours)).unwrap(),
            std::fs::read(dir.join(theirs)).unwrap(),
            "{ours}"
        );
    }
    let whitted = prepared("scenes/seed.toml", &overrides);
    let err = render_to_files(&whitted, &dir.join("w.png"), &[], &options).unwrap_err();
    assert!(err.to_string().contains("path tracer"), "{err}");
    assert!(!dir.join("w.png").exists());
}
