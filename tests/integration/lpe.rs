//! Light path expressions from the command line and the scene file: the images written
//! (PNGs beside the picture, layers of one EXR that add up to it), and every mistake
//! stopped before rendering with exit 2, its column and a hint.

use super::{repo, scratch};
use std::path::Path;
use std::process::{Command, Output};

fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

const SMALL: [&str; 7] = ["--width", "32", "--height", "24", "--spp", "4", "-q"];

/// PNGs: one beside the picture for each expression, a preset's named after it.
#[test]
fn each_expression_gets_a_png_beside_the_picture() {
    let dir = scratch("lpe-png");
    let cornell = repo("scenes/cornell.toml");
    let o = run(
        &dir,
        &[
            &["render", cornell.to_str().unwrap(), "-o", "c.png"][..],
            &["--lpe", "direct", "--lpe", "bounced=C<RD><RD>.*L"],
            &SMALL,
        ]
        .concat(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let mut written = 0;
    for name in ["c.png", "c.direct.png", "c.bounced.png"] {
        let img = image::open(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!((img.width(), img.height()), (32, 24), "{name}");
        written += 1;
    }
    assert_eq!(written, 3);
}

/// An EXR holds each expression as a layer `NAME.R/G/B`; the presets that share out every
/// path add up to the picture; a `[[image.lpe]]` of the scene is written too.
#[test]
fn exr_layers_add_up_to_the_picture() {
    let dir = scratch("lpe-exr");
    let text = std::fs::read_to_string(repo("scenes/cornell.toml")).unwrap();
    // The scene's own expression, in an `[[image.lpe]]` table after the file's tables.
    let scene = dir.join("cornell.toml");
    std::fs::write(
        &scene,
        format!(
            "{text}\n[[image.lpe]]\nname = \"walls\"\nexpr = \"C<RD'red'>.*L | C<RD'green'>.*L\"\n"
        ),
    )
    .unwrap();
    let o = run(
        &dir,
        &[
            &["render", "cornell.toml", "-o", "c.exr"][..],
            &["--lpe", "emission", "--lpe", "direct", "--lpe", "indirect"],
            &["--lpe", "specular"],
            &SMALL,
        ]
        .concat(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let exr = exr::prelude::read_all_flat_layers_from_file(dir.join("c.exr")).unwrap();
    let channels = &exr.layer_data[0].channel_data.list;
    let get = |name: &str| -> Vec<f32> {
        let c = channels
            .iter()
            .find(|c| c.name.to_string() == name)
            .unwrap_or_else(|| panic!("no channel {name}"));
        c.sample_data.values_as_f32().collect()
    };
    let mut names: Vec<String> = channels.iter().map(|c| c.name.to_string()).collect();
    names.sort();
    assert_eq!(names.len(), 3 + 5 * 3, "{names:?}");
    let mut checked = 0;
    for c in ["R", "G", "B"] {
        let beauty = get(c);
        let parts: Vec<Vec<f32>> = ["emission", "direct", "indirect", "specular"]
            .iter()
            .map(|l| get(&format!("{l}.{c}")))
            .collect();
        for (i, b) in beauty.iter().enumerate() {
            let s: f32 = parts.iter().map(|p| p[i]).sum();
            assert!(
                (s - b).abs() <= 1e-5 * b.max(1.0),
                "{c} pixel {i}: {s} against {b}"
            );
            checked += 1;
        }
        // The red and green walls light something.
        assert!(get(&format!("walls.{c}")).iter().any(|&v| v > 0.0));
    }
    assert_eq!(checked, 3 * 32 * 24);
}

/// Mistakes: each exits 2 before rendering (no picture written), with the expression, a
/// mark under its column and a hint.
#[test]
fn mistakes_stop_before_rendering_with_their_column() {
    let dir = scratch("lpe-bad");
    let cornell = repo("scenes/cornell.toml");
    let cornell = cornell.to_str().unwrap();
    let seed = repo("scenes/seed.toml");
    let cases: [(&[&str], &[&str]); 9] = [
        (
            &["--lpe", "x=C<RX>L"],
            &[
                "`x` = `C<RX>L`: column 4: `X` is not an event",
                "    C<RX>L\n       ^",
                "help:",
            ],
        ),
        (
            &["--lpe", "x=LC"],
            &[
                "column 1: no path matches: a path starts at the camera",
                "begin with `C`",
            ],
        ),
        (
            &["--lpe", "x=C.*L'sun'"],
            &[
                "column 5: no light is named 'sun'",
                "the scene's lights: 'light'",
            ],
        ),
        (
            &["--lpe", "nope"],
            &["neither NAME=EXPR nor a preset", "per-light"],
        ),
        (&["--lpe", "1x=CL"], &["cannot name an image"]),
        (
            &["--lpe", "a=CL", "--lpe", "a=CDL"],
            &["two light path expressions are named `a`"],
        ),
        (
            &["--lpe", "depth=CL", "--aov", "depth"],
            &["the name of a debug view"],
        ),
        (
            &["--lpe", "direct", "--time", "5"],
            &["cannot be combined with --time"],
        ),
        (
            &["--lpe", "direct", "--integrator", "whitted"],
            &["Whitted's", "--integrator path"],
        ),
    ];
    let mut checked = 0;
    for (flags, words) in cases {
        let out = dir.join("x.png");
        let o = run(
            &dir,
            &[&["render", cornell, "-o", "x.png"][..], flags, &SMALL].concat(),
        );
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{flags:?}: {err}");
        for w in words {
            assert!(err.contains(w), "{flags:?}: {w:?} not in {err}");
        }
        assert!(!err.contains("panicked"), "{err}");
        assert!(!out.exists(), "{flags:?} wrote the picture");
        checked += 1;
    }
    assert_eq!(checked, 9);
    // The seed scene is Whitted's.
    let o = run(
        &dir,
        &[
            "render",
            seed.to_str().unwrap(),
            "-o",
            "s.png",
            "--lpe",
            "direct",
        ],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("path tracer"));
}

/// A mistake in a scene's `[[image.lpe]]` is reported at the file's line and column, with
/// the expression's column.
#[test]
fn a_scene_files_mistake_names_its_line() {
    let dir = scratch("lpe-scene");
    let text = std::fs::read_to_string(repo("scenes/cornell.toml")).unwrap();
    let lines = text.lines().count();
    let cases = [
        (
            "name = \"a\"\nexpr = \"C<RD>Q\"",
            "column 6: `Q` is not an event",
        ),
        ("preset = \"diect\"", "`diect` is not a preset"),
        ("name = \"a\"", "needs `name` and `expr`, or `preset` alone"),
        ("name = \"a b\"\nexpr = \"CL\"", "cannot name an image"),
    ];
    let mut checked = 0;
    for (table, words) in cases {
        std::fs::write(
            dir.join("s.toml"),
            format!("{text}\n[[image.lpe]]\n{table}\n"),
        )
        .unwrap();
        let o = run(&dir, &["check", "s.toml"]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{table}: {err}");
        assert!(err.contains(words), "{table}: {err}");
        // The table (after a blank line) or its key, past the file's last line.
        let at = (lines + 2..=lines + 4).find(|l| err.contains(&format!("s.toml:{l}:")));
        assert!(at.is_some(), "{table}: {err}");
        checked += 1;
    }
    assert_eq!(checked, 4);
}
