//! Denoising (`--denoise`): without the `denoise` feature, refused before any work with
//! the two commands that build it; with it, the denoised Cornell box is closer to its
//! converged reference than the raw picture it was made from.

use super::{repo, scratch};
use std::process::Command;

fn snell(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(args)
        .output()
        .unwrap()
}

/// A build without the feature: exit 2, a message naming the feature and how to get it,
/// and no file written (not even the picture).
#[cfg(not(feature = "denoise"))]
#[test]
fn denoise_without_the_feature_says_how_to_build_it() {
    let dir = scratch("denoise-off");
    let out = dir.join("c.png");
    let o = snell(&[
        "render",
        repo("scenes/cornell.toml").to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--width",
        "8",
        "--height",
        "8",
        "--spp",
        "4",
        "--denoise",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("`denoise` feature"), "{err}");
    assert!(
        err.contains("pip install pyoidn") && err.contains("OIDN_DIR"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert!(left.is_empty(), "files written: {left:?}");
    assert!(matches!(
        snell::denoise::ready(),
        Err(snell::denoise::DenoiseError::NotBuilt)
    ));
}

/// With the feature: the Cornell box at 32 x 32 and 16 samples a pixel, denoised, has a
/// lower RMSE against its 65536-sample reference (tests/data) than the raw picture, in
/// linear values (the lamp's edge too, which the denoiser takes again over 256 samples) and
/// in display values; and the EXR holds both.
#[cfg(feature = "denoise")]
#[test]
fn the_denoised_cornell_box_is_closer_to_its_reference() {
    let dir = scratch("denoise-on");
    let out = dir.join("c.exr");
    let o = snell(&[
        "render",
        repo("scenes/cornell.toml").to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--width",
        "32",
        "--height",
        "32",
        "--spp",
        "16",
        "--denoise",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(String::from_utf8_lossy(&o.stdout).contains("denoised it in"));
    let reference = image::open(repo("tests/data/cornell-32-ref.exr"))
        .unwrap()
        .to_rgb32f();
    let layers = exr::prelude::read_all_flat_layers_from_file(&out).unwrap();
    let channel = |name: &str| -> Vec<f32> {
        let layer = &layers.layer_data[0];
        let c = layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .unwrap_or_else(|| panic!("no channel {name}"));
        c.sample_data.values_as_f32().collect()
    };
    let rmse = |prefix: &str, display: bool| {
        let cut = |v: f32| if display { v.min(1.0) } else { v };
        let (r, g, b) = (
            channel(&format!("{prefix}R")),
            channel(&format!("{prefix}G")),
            channel(&format!("{prefix}B")),
        );
        let mut sum = 0.0f64;
        let mut n = 0;
        for (i, p) in reference.pixels().enumerate() {
            for (v, want) in [r[i], g[i], b[i]].into_iter().zip(p.0) {
                // Display values are cut at 1, as a PNG shows them.
                sum += ((cut(v) - cut(want)) as f64).powi(2);
                n += 1;
            }
        }
        assert_eq!(n, 32 * 32 * 3);
        (sum / n as f64).sqrt()
    };
    for display in [false, true] {
        let (raw, denoised) = (rmse("", display), rmse("denoised.", display));
        assert!(
            denoised < 0.8 * raw,
            "display {display}: denoised {denoised}, raw {raw}"
        );
    }
}
