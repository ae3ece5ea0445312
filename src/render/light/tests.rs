//! The light tracer against the path tracer: on the Cornell box (every surface diffuse, an
//! area light, seen directly) both converge to the same picture; and the same bytes at any
//! thread count.

use super::*;
use crate::integrator::Path;
use crate::render::pass::tests::{bits, options};
use crate::render::render;
use crate::scene::{Format, load_str};

fn cornell(size: u32, spp: u32) -> Scene {
    cornell_with(size, spp, "")
}

/// The Cornell box with `camera` added to its `[camera]` table.
fn cornell_with(size: u32, spp: u32, camera: &str) -> Scene {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/cornell.toml"))
        .unwrap()
        .replace("fov = 39.3077\n", &format!("fov = 39.3077\n{camera}\n"));
    assert!(camera.is_empty() || text.contains(camera));
    let mut s = load_str(
        &text,
        std::path::Path::new("cornell.toml"),
        std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes")),
        Format::Toml,
    )
    .unwrap();
    s.settings.width = size;
    s.settings.height = size;
    s.settings.spp = spp;
    s
}

/// The light-traced and the path-traced pictures of `scene`, 4 x 4-pixel blocks compared:
/// the worst block's relative difference and the means'.
fn compare(make: impl Fn() -> Scene) -> (f64, f64) {
    let path = render(&make(), &Path, Some(2), &|_| {}).unwrap().image;
    let light = render_light(&make(), &options(2)).unwrap().image;
    let size = path.width;
    let block = |img: &crate::film::Image, bx: u32, by: u32| {
        let mut sum = 0.0f64;
        for y in by * 4..by * 4 + 4 {
            for x in bx * 4..bx * 4 + 4 {
                sum += crate::math::luminance(img.get(x, y)) as f64;
            }
        }
        sum / 16.0
    };
    let mut worst = 0.0f64;
    let mut checked = 0;
    for by in 0..size / 4 {
        for bx in 0..size / 4 {
            let (p, l) = (block(&path, bx, by), block(&light, bx, by));
            worst = worst.max((l - p).abs() / p.max(0.02));
            checked += 1;
        }
    }
    assert_eq!(checked, (size / 4) * (size / 4));
    let mean = |img: &crate::film::Image| {
        img.pixels
            .iter()
            .map(|c| crate::math::luminance(*c) as f64)
            .sum::<f64>()
            / img.pixels.len() as f64
    };
    let (p, l) = (mean(&path), mean(&light));
    (worst, (l - p).abs() / p)
}

/// Through a lens (the boxes out of focus), light tracing joins each surface to a point of
/// the lens and lands where that line meets the plane in focus: the picture is the path
/// tracer's, block by block within noise (measured: the worst block 2.8 %, the means 0.2 %).
#[test]
fn the_cornell_box_through_a_lens_light_traced_is_the_path_traced_one() {
    let lens = "aperture = 0.15\nfocus_distance = 2.5";
    let l = cornell_with(8, 1, lens).camera.view().lens;
    assert!(
        l.is_some_and(|l| l.radius == 0.15 && l.focus == 2.5),
        "{l:?}"
    );
    let (worst, mean) = compare(|| cornell_with(24, 2048, lens));
    assert!(worst < 0.06, "worst block {worst}");
    assert!(mean < 0.005, "means {mean}");
}

/// Block by block (4 x 4 pixels), the light-traced Cornell box is the path-traced one
/// within 5 % (noise), and the whole picture's mean within 0.5 % (measured: 0.01 %, the
/// worst block 1.4 %).
#[test]
fn the_cornell_box_light_traced_is_the_path_traced_one() {
    let (worst, mean) = compare(|| cornell(24, 2048));
    assert!(worst < 0.05, "worst block {worst}");
    assert!(mean < 0.005, "means {mean}");
}

#[test]
fn the_same_bytes_at_any_thread_count() {
    let a = render_light(&cornell(16, 16), &options(1)).unwrap().image;
    let b = render_light(&cornell(16, 16), &options(2)).unwrap().image;
    assert_eq!(bits(&a.pixels), bits(&b.pixels));
    assert!(a.pixels.iter().any(|c| c.max_element() > 0.0));
}

/// The white furnace's cousin: a diffuse ball of albedo 0.5 in a constant environment of
/// radiance 1 reflects 0.5 toward the eye everywhere on it (a convex surface sees only the
/// sky); light tracing starts its paths at the environment and finds that, and leaves the
/// sky seen directly black.
#[test]
fn an_environment_lights_a_ball_as_the_furnace_says() {
    let text = "[image]\nwidth = 16\nheight = 16\nsamples = 4096\n\
                [integrator]\ntype = \"light\"\n\
                [camera]\nposition = [0, 0, 4]\nlook_at = [0, 0, 0]\nfov = 30\n\
                [environment]\ntype = \"constant\"\ncolor = 1\n\
                [materials.grey]\ntype = \"diffuse\"\ncolor = 0.5\n\
                [[objects]]\ntype = \"sphere\"\nradius = 1\nmaterial = \"grey\"\n";
    let scene = load_str(
        text,
        std::path::Path::new("t.toml"),
        std::path::Path::new("."),
        Format::Toml,
    )
    .unwrap();
    let img = render_light(&scene, &options(2)).unwrap().image;
    // The 4 x 4 pixels in the middle see the ball; the corners the sky.
    let mut sum = 0.0;
    for y in 6..10 {
        for x in 6..10 {
            sum += img.get(x, y).element_sum() / 3.0;
        }
    }
    let mean = sum / 16.0;
    assert!((mean - 0.5).abs() < 0.02, "{mean}");
    assert_eq!(img.get(0, 0), crate::math::Color::ZERO);
}

/// A render stopped by its time after some passes is the render of that many paths a
/// pixel, to the bit (splats add up as integers); the first pass is always taken.
#[test]
fn a_render_stopped_by_time_is_the_render_of_its_paths() {
    let stopped = render_light_for(&cornell(16, 4096), &options(2), Some(Duration::ZERO)).unwrap();
    assert_eq!(stopped.spp, 1, "only the first pass");
    assert!(stopped.rendered.complete());
    let short = render_light_for(
        &cornell(16, 4096),
        &options(2),
        Some(Duration::from_millis(30)),
    )
    .unwrap();
    assert!(short.spp >= 1 && short.spp < 4096, "{}", short.spp);
    for r in [stopped, short] {
        let whole = render_light(&cornell(16, r.spp), &options(1)).unwrap();
        assert_eq!(
            bits(&r.rendered.image.pixels),
            bits(&whole.image.pixels),
            "{}",
            r.spp
        );
    }
}

/// Passes resumed from a render stopped after its first passes give the bytes of the render
/// never stopped (at 2 threads, resumed at 1: the splats are integers); bdpt's state is
/// refused, and so is one of more paths than the render takes.
#[test]
fn passes_resumed_are_the_render_never_stopped() {
    let stopped = render_light_for(&cornell(16, 4), &options(2), None).unwrap();
    assert_eq!(stopped.state.spp, 4);
    let mut told = vec![];
    let resumed = render_light_from(
        &cornell(16, 16),
        &options(1),
        None,
        Some(stopped.state.clone()),
        &mut |state| told.push(state().spp),
    )
    .unwrap();
    // Passes 4..8 and 8..16, each told with its state.
    assert_eq!(told, [8, 16]);
    let whole = render_light(&cornell(16, 16), &options(2)).unwrap();
    assert_eq!(
        bits(&resumed.rendered.image.pixels),
        bits(&whole.image.pixels)
    );
    let mut bdpt = stopped.state.clone();
    bdpt.film = Some(Film::new(16, 16));
    let mut refused = 0;
    for (state, says) in [
        (bdpt, "bdpt's"),
        (
            Splatted {
                spp: 32,
                ..stopped.state.clone()
            },
            "more paths",
        ),
        (
            Splatted {
                splats: vec![[0; 3]; 3],
                ..stopped.state
            },
            "another size",
        ),
    ] {
        let e = render_light_from(
            &cornell(16, 16),
            &options(1),
            None,
            Some(state),
            &mut |_| {},
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains(says), "{e}");
        refused += 1;
    }
    assert_eq!(refused, 3);
}
