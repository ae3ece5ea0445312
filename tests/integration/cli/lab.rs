//! `snell lab`: a material's sampling tested against its density, its picture, and its
//! refusals of bad input (exit 2 with the loader's words).

use super::*;

#[test]
fn lab_tests_a_materials_sampling_and_draws_it() {
    let dir = scratch("lab-plastic");
    let out = expect(
        &[
            "lab",
            "bsdf",
            "plastic",
            "--roughness",
            "0.3",
            "--angle",
            "60",
            "--samples",
            "200000",
            "-o",
            "lab.png",
        ],
        &dir,
        0,
    );
    let text = stdout(&out);
    assert!(
        text.starts_with("plastic (roughness = 0.3), light leaving at 60° from the normal\n"),
        "{text}"
    );
    assert!(text.contains("200000 samples: "), "{text}");
    assert!(
        text.contains(": the samples follow the density\n"),
        "{text}"
    );
    let img = image::open(dir.join("lab.png")).unwrap();
    assert_eq!((img.width(), img.height()), (3 * 480 + 2 * 6, 240));
    // Smooth glass is all deltas: nothing to draw, and nothing fails.
    let glass = stdout(&expect(
        &["lab", "bsdf", "dielectric", "--samples", "1000"],
        &dir,
        0,
    ));
    assert!(glass.contains("0 in the histogram"), "{glass}");
}

#[test]
fn lab_refuses_what_it_cannot_build_with_exit_2() {
    let dir = scratch("lab-bad");
    let cases: [(&[&str], &str); 6] = [
        (&["lab", "bsdf", "plastik"], "did you mean `plastic`?"),
        (
            &["lab", "bsdf", "plastic", "--roughness", "-1"],
            "roughness",
        ),
        (&["lab", "bsdf", "diffuse", "--ior", "1.5"], "ior"),
        (&["lab", "bsdf", "diffuse", "--param", "colour=1"], "colour"),
        (&["lab", "bsdf", "diffuse", "--angle", "95"], "--angle 95"),
        (
            &["lab", "bsdf", "diffuse", "-o", "no/such/folder/x.png"],
            "x.png",
        ),
    ];
    let mut checked = 0;
    for (args, said) in cases {
        let err = stderr(&expect(args, &dir, 2));
        assert!(err.contains(said), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        checked += 1;
    }
    assert_eq!(checked, 6);
    let list = stdout(&expect(&["lab", "list"], &dir, 0));
    assert_eq!(list.lines().count(), 9, "{list}");
}

#[test]
fn lab_tests_a_scenes_lights_from_a_point() {
    let dir = scratch("lab-light");
    let cornell = repo("scenes/cornell.toml").to_string_lossy().into_owned();
    let out = stdout(&expect(
        &[
            "lab",
            "light",
            &cornell,
            "--from",
            "0,0,0",
            "--samples",
            "200000",
            "-o",
            "l.png",
        ],
        &dir,
        0,
    ));
    assert!(
        out.contains("200000 samples: 200000 in the histogram"),
        "{out}"
    );
    assert!(out.contains(": the samples follow the density\n"), "{out}");
    assert!(dir.join("l.png").is_file());
    // The seed's one light is a point: nothing to bin, said so.
    let seed = repo("scenes/seed.toml").to_string_lossy().into_owned();
    let out = stdout(&expect(
        &[
            "lab",
            "light",
            &seed,
            "--from",
            "0,0,-30",
            "--samples",
            "1000",
        ],
        &dir,
        0,
    ));
    assert!(out.contains("no sample has a density to test"), "{out}");
    let mut checked = 0;
    for (args, said) in [
        (
            vec!["lab", "light", &seed, "--from", "0,0"],
            "is not a point",
        ),
        (
            vec!["lab", "light", "none.toml", "--from", "0,0,0"],
            "none.toml",
        ),
        (
            vec!["lab", "light", &seed, "--from", "0,0,0", "--samples", "5"],
            "--samples 5",
        ),
    ] {
        let err = stderr(&expect(&args, &dir, 2));
        assert!(err.contains(said), "{args:?}: {err}");
        checked += 1;
    }
    assert_eq!(checked, 3);
}
