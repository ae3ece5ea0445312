//! Bidirectional path tracing against the path tracer, on scenes the path tracer handles:
//! the same picture block by block within noise.

use super::*;
use crate::render::pass::tests::{bits, options};
use crate::render::render;
use crate::scene::{Format, load_str};

fn scene(text: &str) -> Scene {
    load_str(
        text,
        std::path::Path::new("t.toml"),
        std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes")),
        Format::Toml,
    )
    .unwrap()
}

fn cornell(size: u32, spp: u32) -> Scene {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/cornell.toml"))
        .unwrap();
    let mut s = scene(&text);
    s.settings.width = size;
    s.settings.height = size;
    s.settings.spp = spp;
    s
}

#[test]
fn cornell_quick_look() {
    let b = render_bdpt(&cornell(24, 256), &options(2)).unwrap().image;
    let p = render(&cornell(24, 256), &Path, Some(2), &|_| {}).unwrap().image;
    let mean = |img: &Image| img.pixels.iter().map(|c| crate::math::luminance(*c) as f64).sum::<f64>() / img.pixels.len() as f64;
    panic!("bdpt {} path {}", mean(&b), mean(&p));
}
