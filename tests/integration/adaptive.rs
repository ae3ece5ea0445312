//! Adaptive sampling (`--noise`, `[image] noise`): unbiased (block by block against
//! converged references), the same bytes at any thread count and when resumed, samples
//! where the noise is, and bad thresholds refused.

use super::{repo, scratch};
use snell::film::Film;
use snell::render::to_files::{Finished, RunOptions, run};
use snell::sampler::SamplerKind;
use snell::scene::Scene;
use std::process::Command;

/// `scene` at `w` x `h`, `spp` the cap, seed `seed`, adaptive to `noise` (or uniform).
fn render(
    scene: &mut Scene,
    (w, h): (u32, u32),
    spp: u32,
    seed: u64,
    noise: Option<f32>,
    threads: usize,
) -> Finished {
    let s = &mut scene.settings;
    (s.width, s.height, s.spp, s.seed, s.noise) = (w, h, spp, seed, noise);
    s.integrator.sampler = SamplerKind::Independent;
    let options = RunOptions {
        threads: Some(threads),
        progress: &|_| {},
        cancel: None,
        time: None,
        lpe: &[],
    };
    run(scene, &options).unwrap()
}

fn film(f: &Finished) -> &Film {
    f.film.as_ref().expect("the path tracer keeps its film")
}

/// The mean luminance of each `b` x `b` block of a `w`-wide image.
fn blocks(pixels: &[snell::math::Color], w: usize, b: usize) -> Vec<f64> {
    let h = pixels.len() / w;
    let mut out = vec![0.0; (w / b) * (h / b)];
    for (i, p) in pixels.iter().enumerate() {
        let (x, y) = (i % w, i / w);
        out[(y / b) * (w / b) + x / b] += snell::math::luminance(*p) as f64 / (b * b) as f64;
    }
    out
}

/// `K` adaptive renders (seeds 0..K) against a reference: each 4 x 4 block's mean
/// luminance, its spread over the renders giving its standard error (and the reference's
/// own, `reference_var`, per block); returns the z-scores and the share of pixels that
/// stopped short of the cap.
fn block_z(
    scene: &mut Scene,
    size: (u32, u32),
    cap: u32,
    noise: f32,
    reference: &[f64],
    reference_var: &[f64],
) -> (Vec<f64>, f64) {
    const K: usize = 16;
    let mut short = 0usize;
    let runs: Vec<Vec<f64>> = (0..K)
        .map(|k| {
            let f = render(scene, size, cap, k as u64, Some(noise), 2);
            short += film(&f).pixels().iter().filter(|p| p.samples < cap).count();
            blocks(&f.image.pixels, size.0 as usize, 4)
        })
        .collect();
    let z = (0..reference.len())
        .map(|b| {
            let v: Vec<f64> = runs.iter().map(|r| r[b]).collect();
            let m = v.iter().sum::<f64>() / K as f64;
            let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (K - 1) as f64;
            let se = (var / K as f64 + reference_var[b]).sqrt();
            if se == 0.0 {
                assert!(
                    (m - reference[b]).abs() <= 1e-4 * reference[b].max(1.0),
                    "block {b}"
                );
                0.0
            } else {
                (m - reference[b]) / se
            }
        })
        .collect();
    (
        z,
        short as f64 / (K as u64 * size.0 as u64 * size.1 as u64) as f64,
    )
}

/// The z-scores are what noise alone gives, as in the path tracer's own test against its
/// reference (tests/integration/path.rs): a few beyond 3, none beyond 8 (a path tracer's
/// light comes in rare bright paths, so a block's mean over 16 renders has heavy tails: a
/// uniform render of the same blocks shows a worst z of 6.5 with 8 renders), and no shift
/// of their mean.
fn assert_unbiased(z: &[f64], what: &str) {
    let n = z.len();
    let mean = z.iter().sum::<f64>() / n as f64;
    let worst = z.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let beyond3 = z.iter().filter(|v| v.abs() > 3.0).count();
    assert!(n >= 48, "{what}: {n} blocks");
    assert!(
        worst < 8.0 && beyond3 <= n / 12 && mean.abs() < 0.4,
        "{what}: worst z {worst:.2}, {beyond3} of {n} beyond 3, mean z {mean:.3}"
    );
}

/// The Cornell box rendered adaptively is its 65536-spp reference (tests/data), block by
/// block, up to noise: stopping pixels where their samples agree biases nothing seen.
#[test]
fn the_cornell_box_rendered_adaptively_is_unbiased() {
    let mut scene = snell::scene::load(&repo("scenes/cornell.toml")).unwrap();
    let img = image::open(repo("tests/data/cornell-32-ref.exr"))
        .unwrap()
        .to_rgb32f();
    let reference: Vec<snell::math::Color> = img
        .pixels()
        .map(|p| snell::math::Color::from(p.0))
        .collect();
    let reference = blocks(&reference, 32, 4);
    let (z, short) = block_z(&mut scene, (32, 32), 256, 0.2, &reference, &[0.0; 64]);
    assert_eq!(z.len(), 64);
    assert!(
        short > 0.3,
        "only {short} of the pixels stopped short of the cap"
    );
    assert_unbiased(&z, "Cornell box");
}

/// The courtyard under the sky and a small sun (scenes/outdoor-noon.toml) rendered
/// adaptively is a uniform render of 1024 spp, block by block, up to both one's noise.
#[test]
fn a_sunlit_scene_rendered_adaptively_is_unbiased() {
    let mut scene = snell::scene::load(&repo("scenes/outdoor-noon.toml")).unwrap();
    let size = (32, 24);
    let uniform = render(&mut scene, size, 1024, 99, None, 2);
    let reference = blocks(&uniform.image.pixels, 32, 4);
    // A block's variance: its pixels' estimates' variances over the block's size squared.
    let var: Vec<snell::math::Color> =
        film(&uniform).rows(|p| snell::math::Color::splat(p.variance_of_mean().unwrap()));
    let reference_var: Vec<f64> = blocks(&var, 32, 4).iter().map(|v| v / 16.0).collect();
    let (z, short) = block_z(&mut scene, size, 256, 0.05, &reference, &reference_var);
    assert_eq!(z.len(), 48);
    assert!(
        short > 0.3,
        "only {short} of the pixels stopped short of the cap"
    );
    assert_unbiased(&z, "courtyard");
}

/// The samples go where the noise is: on the courtyard, the sky (the same in every sample)
/// stops at the first decision while the shaded ground takes more; the pixels that stopped
/// short of the cap are below the threshold; the render takes fewer samples than a uniform
/// one of its cap; and it is the same bytes on one thread and on two.
#[test]
fn samples_go_where_the_noise_is_and_the_bytes_do_not_depend_on_threads() {
    let mut scene = snell::scene::load(&repo("scenes/outdoor-noon.toml")).unwrap();
    let (w, h) = (48, 32);
    let one = render(&mut scene, (w, h), 512, 3, Some(0.05), 1);
    let two = render(&mut scene, (w, h), 512, 3, Some(0.05), 2);
    let bits = |f: &Finished| -> Vec<u32> {
        f.image
            .pixels
            .iter()
            .flat_map(|c| c.to_array().map(f32::to_bits))
            .collect()
    };
    assert_eq!(bits(&one), bits(&two));
    let counts = film(&one).rows(|p| p.samples);
    assert_eq!(counts, film(&two).rows(|p| p.samples));
    let first = snell::render::adaptive::FIRST_DECISION;
    assert!(
        counts.iter().all(|&n| (first..=512).contains(&n)),
        "{counts:?}"
    );
    let total: u64 = counts.iter().map(|&n| n as u64).sum();
    assert!(total < (w * h) as u64 * 512 / 2, "{total} samples");
    // The top row is sky in this view: no spread, no more samples.
    assert!(
        counts[..w as usize].iter().all(|&n| n == first),
        "{:?}",
        &counts[..w as usize]
    );
    assert!(counts.contains(&512));
    let mut checked = 0;
    for p in film(&one).pixels().iter().filter(|p| p.samples < 512) {
        let e = snell::film::relative_error(
            p.variance_of_mean().unwrap(),
            snell::math::luminance(p.value()),
        );
        assert!(
            e <= 0.05,
            "a pixel stopped at {} samples with error {e}",
            p.samples
        );
        checked += 1;
    }
    assert!(
        checked > (w * h) as usize / 4,
        "{checked} pixels stopped short"
    );
}

fn snell_cmd(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(args)
        .output()
        .unwrap()
}

/// Bad thresholds, and integrators and flags adaptive sampling does not go with, are
/// refused before anything is written, with exit 2 and a message saying why.
#[test]
fn bad_noise_thresholds_and_combinations_are_refused() {
    let dir = scratch("adaptive-bad");
    let out = dir.join("x.png");
    let out = out.to_str().unwrap();
    let cornell = repo("scenes/cornell.toml");
    let cornell = cornell.to_str().unwrap();
    let seed = repo("scenes/seed.toml");
    let seed = seed.to_str().unwrap();
    let cases: [(&[&str], &str); 9] = [
        (&[cornell, "--noise", "0"], "is not a noise threshold"),
        (&[cornell, "--noise", "-0.1"], "is not a noise threshold"),
        (&[cornell, "--noise", "1.5"], "is not a noise threshold"),
        (&[cornell, "--noise", "abc"], "is not a noise threshold"),
        (&[cornell, "--noise", "NaN"], "is not a noise threshold"),
        (
            &[seed, "--noise", "0.01"],
            "adaptive sampling (noise) is the path tracer's: Whitted's",
        ),
        (
            &[cornell, "--noise", "0.01", "--integrator", "bdpt"],
            "is the path tracer's: light and bdpt",
        ),
        (
            &[cornell, "--noise", "0.01", "--region", "0,0,8,8"],
            "--region cannot be combined with adaptive sampling",
        ),
        (
            &[cornell, "--noise", "0.01", "--lpe", "direct"],
            "cannot be combined with adaptive sampling",
        ),
    ];
    let mut checked = 0;
    for (args, says) in cases {
        let mut all = vec![
            "render", "-o", out, "--spp", "4", "--width", "8", "--height", "8",
        ];
        all.extend_from_slice(args);
        let o = snell_cmd(&all);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(
            !std::path::Path::new(out).exists(),
            "{args:?} wrote the picture"
        );
        checked += 1;
    }
    assert_eq!(checked, 9);
    // In the scene: the key's place in the file.
    let text = std::fs::read_to_string(cornell)
        .unwrap()
        .replace("[image]\n", "[image]\nnoise = 2\n");
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, text).unwrap();
    let o = snell_cmd(&["check", bad.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("bad.toml:") && err.contains("noise threshold"),
        "{err}"
    );
}

/// An adaptive render through the command line: the spp view written beside the picture,
/// the summary line saying where the samples went; a percentage is a threshold too.
#[test]
fn the_command_line_renders_adaptively_with_an_spp_view() {
    let dir = scratch("adaptive-cli");
    let out = dir.join("c.png");
    let o = snell_cmd(&[
        "render",
        repo("scenes/cornell.toml").to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--width",
        "24",
        "--height",
        "24",
        "--spp",
        "128",
        "--noise",
        "10%",
        "--aov",
        "spp",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    let said = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(
        said.contains("16 to 128 spp") && said.contains("below 10 % noise"),
        "{said}"
    );
    let map = image::open(dir.join("c.spp.png")).unwrap().to_rgb8();
    assert_eq!(map.dimensions(), (24, 24));
    // The light (16 samples) and the darkest corner (the cap) differ on the map.
    let distinct: std::collections::BTreeSet<[u8; 3]> = map.pixels().map(|p| p.0).collect();
    assert!(distinct.len() >= 3, "{distinct:?}");
}

/// An adaptive render cancelled in a pass (which is left out) and taken up again from its film (what
/// `--resume` does) gives the bytes of one never stopped: the decisions read the film alone.
#[test]
fn an_adaptive_render_stopped_and_resumed_is_the_same_bytes() {
    use snell::render::RenderOptions;
    use snell::render::progressive::{Ended, PassEvent, Until, render_progressive};
    use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
    let mut scene = snell::scene::load(&repo("scenes/cornell.toml")).unwrap();
    let s = &mut scene.settings;
    (s.width, s.height, s.spp) = (40, 40, 128);
    let until = Until {
        spp: 128,
        time: None,
        noise: Some(0.1),
    };
    let whole = {
        let mut film = Film::new(40, 40);
        let options = RenderOptions {
            threads: Some(2),
            progress: &|_| {},
            cancel: None,
            region: None,
        };
        let p = render_progressive(
            &scene,
            &snell::integrator::Path,
            &mut film,
            until,
            &options,
            &mut |_, _| {},
        )
        .unwrap();
        assert_eq!(p.ended, Some(Ended::Complete));
        film
    };
    // Cancelled in the sixth pass (16 -> 32, the first adaptive one), after its first tile.
    let stop = AtomicBool::new(false);
    let passes = AtomicU32::new(0);
    let progress = |_| {
        if passes.load(Ordering::SeqCst) == 6 {
            stop.store(true, Ordering::SeqCst);
        }
    };
    let options = RenderOptions {
        threads: Some(1),
        progress: &progress,
        cancel: Some(&stop),
        region: None,
    };
    let mut film = Film::new(40, 40);
    let p = render_progressive(
        &scene,
        &snell::integrator::Path,
        &mut film,
        until,
        &options,
        &mut |e, _| {
            if let PassEvent::Start { .. } = e {
                passes.fetch_add(1, Ordering::SeqCst);
            }
        },
    )
    .unwrap();
    assert_eq!((p.ended, p.passes), (Some(Ended::Cancelled), 6));
    // The cancelled pass is left out: every pixel is where the pass found it.
    assert!(film.pixels().iter().all(|p| p.samples == 16));
    let options = RenderOptions {
        threads: Some(2),
        progress: &|_| {},
        cancel: None,
        region: None,
    };
    render_progressive(
        &scene,
        &snell::integrator::Path,
        &mut film,
        until,
        &options,
        &mut |_, _| {},
    )
    .unwrap();
    let bits = |f: &Film| -> Vec<u32> {
        f.image()
            .pixels
            .iter()
            .flat_map(|c| c.to_array().map(f32::to_bits))
            .collect()
    };
    assert_eq!(bits(&film), bits(&whole));
    assert_eq!(film.rows(|p| p.samples), whole.rows(|p| p.samples));
}
