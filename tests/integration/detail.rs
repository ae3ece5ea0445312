//! Normal and bump maps in whole renders: the shipped normal map and the height map it was
//! made from (assets/maps) light a floor alike, under a raking light that shows the relief.

use crate::repo;
use snell::film::Image;
use snell::integrator::{Integrator, Path as PathTracer, Whitted};
use snell::render::render;
use snell::scene::{Format, load_str};

/// The floor seen from above with material keys `material`, lit from one side and behind.
fn floor(material: &str, integrator: &dyn Integrator) -> Image {
    let text = format!(
        r#"
[image]
width = 256
height = 256
samples = 4
background = [0, 0, 0]
[integrator]
type = "{kind}"
[camera]
position = [0.5, 3, 0.5]
look_at = [0.5, 0, 0.5]
up = [0, 0, -1]
fov = 20
[world]
ambient = 0
[textures.n]
type = "image"
file = "assets/maps/tiles-normal.png"
mapping = {{ type = "planar", u = [1, 0, 0], v = [0, 0, 1] }}
[textures.h]
type = "image"
file = "assets/maps/tiles-height.png"
mapping = {{ type = "planar", u = [1, 0, 0], v = [0, 0, 1] }}
[materials.m]
type = "diffuse"
color = 0.8
{material}
[[lights]]
type = "directional"
direction = [1, -0.6, 0.7]
color = 2
[[objects]]
type = "plane"
point = [0, 0, 0]
normal = [0, 1, 0]
material = "m"
"#,
        kind = if integrator.uses_sampler() {
            "path"
        } else {
            "whitted"
        }
    );
    let scene = load_str(&text, &repo("detail.toml"), &repo(""), Format::Toml)
        .unwrap_or_else(|e| panic!("{e}"));
    render(&scene, integrator, Some(2), &|_| {}).unwrap().image
}

/// Mean relative difference of `a` from `b`, over every channel.
fn mrd(a: &Image, b: &Image) -> f64 {
    let (mut d, mut s) = (0.0, 0.0);
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        d += (*p - *q).abs().element_sum() as f64;
        s += q.abs().element_sum() as f64;
    }
    d / s
}

#[test]
fn a_normal_map_and_its_height_map_show_the_same_relief() {
    for integrator in [&Whitted as &dyn Integrator, &PathTracer] {
        let normal = floor("normal_map = \"n\"", integrator);
        let bump = floor("bump = \"h\"\nbump_height = 0.02", integrator);
        let flat = floor("", integrator);
        let same = mrd(&normal, &bump);
        let relief = mrd(&normal, &flat);
        assert!(same < 0.03, "normal and bump maps differ by {same}");
        assert!(relief > 5.0 * same, "the relief shows too little: {relief}");
        // Without any map the floor is one flat grey.
        let first = flat.pixels[0];
        assert!(
            flat.pixels
                .iter()
                .all(|p| (*p - first).abs().max_element() < 1e-4)
        );
    }
}
