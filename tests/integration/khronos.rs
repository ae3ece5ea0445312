//! Khronos's glTF sample models the project ships (assets/models/khronos, from Debian's
//! assimp-testmodels): TextureTransformTest read as its README says a correct reader shows
//! it (KHR_texture_transform's offsets, the samplers' clamped edges), and BoxTextured with
//! its texture on every face; both in a golden image of scenes/khronos.toml.

use super::repo;
use snell::math::Color;
use snell::scene::{Format, Scene, load_str};
use snell::texture::{Pattern, Wrap, Wraps};

/// TextureTransformTest seen straight on through an orthographic camera, 100 pixels to a
/// scene unit: pixel (x, y) is the point (-1.65 + (x + 0.5) / 100, 1.1 - (y + 0.5) / 100)
/// of its quads' plane. Under an even white sky, which shows a surface's colour.
fn texture_transform_test() -> Scene {
    let dir = repo("assets/models/khronos/TextureTransformTest");
    let text = "[image]\nwidth = 330\nheight = 220\nsamples = 16\n\
                [integrator]\ntype = \"path\"\n\
                [camera]\ntype = \"orthographic\"\nheight = 2.2\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n\
                [environment]\ntype = \"constant\"\ncolor = 1\n\
                [[objects]]\ntype = \"mesh\"\nfile = \"TextureTransformTest.gltf\"\n";
    load_str(text, &dir.join("t.toml"), &dir, Format::Toml).unwrap_or_else(|e| panic!("{e}"))
}

fn mean(img: &snell::film::Image, x0: u32, y0: u32, x1: u32, y1: u32) -> Color {
    let mut sum = Color::ZERO;
    for y in y0..y1 {
        for x in x0..x1 {
            sum += img.get(x, y);
        }
    }
    sum / ((x1 - x0) * (y1 - y0)) as f32
}

/// The pixel of a point of the quads' plane.
fn pixel(x: f32, y: f32) -> (u32, u32) {
    (((x + 1.65) * 100.0) as u32, ((1.1 - y) * 100.0) as u32)
}

#[test]
fn texture_transform_test_shows_what_a_correct_reader_shows() {
    let scene = texture_transform_test();
    // The six quads' textures name its one sampler, which clamps both axes; the markers'
    // name none, and get glTF's default: repeat.
    let wraps: Vec<Wraps> = scene
        .textures
        .iter()
        .filter(|t| matches!(t.pattern, Pattern::Image(_)))
        .map(|t| t.wrap)
        .collect();
    let clamped = wraps
        .iter()
        .filter(|w| **w == Wraps::both(Wrap::Clamp))
        .count();
    assert_eq!(clamped, 6, "{wraps:?}");
    assert_eq!(wraps.len() - clamped, 3, "{wraps:?}");
    assert!(
        wraps
            .iter()
            .all(|w| *w == Wraps::both(Wrap::Clamp) || *w == Wraps::REPEAT)
    );
    let img = snell::render::render(&scene, &snell::integrator::Path, None, &|_| {})
        .unwrap()
        .image;
    // The top row: the quads' uvs run over UV.png's lower-left quarter (yellow, "not
    // supported") and their offsets move them to the green U, blue V and cyan UV quarters.
    // Near each quad's top-left corner, away from the tick and the letters:
    for (cx, want) in [(-1.1, "green"), (0.0, "blue"), (1.1, "cyan")] {
        let (x, y) = pixel(cx - 0.42, 0.97);
        let c = mean(&img, x, y, x + 8, y + 8);
        let (r, g, b) = (c.x, c.y, c.z);
        let ok = match want {
            "green" => g > 2.0 * r && g > 2.0 * b,
            "blue" => b > 2.0 * r && b > 2.0 * g,
            _ => g > 2.0 * r && b > 2.0 * r,
        };
        assert!(ok, "the quad at x = {cx} should be {want}, is {c}");
    }
    // The bottom middle quad scales uv by 1.5: beyond the image's right and bottom edges
    // the clamped sampler stretches its grey border (a repeating one would show the image
    // again, arrow and all). Down the quad's right side and along its bottom, one grey.
    let strip: Vec<Color> = (0..9)
        .map(|i| {
            let (x, y) = pixel(0.42, -0.12 - 0.1 * i as f32);
            mean(&img, x, y, x + 4, y + 4)
        })
        .chain((0..9).map(|i| {
            let (x, y) = pixel(-0.42 + 0.1 * i as f32, -0.98);
            mean(&img, x, y, x + 4, y + 4)
        }))
        .collect();
    let grey = strip[0];
    for c in &strip {
        assert!(
            (*c - grey).abs().max_element() < 0.05,
            "the clamped edge should be one grey ({grey}), found {c}"
        );
    }
    assert!(
        grey.max_element() < 0.9,
        "that grey is the border, not the white image: {grey}"
    );
}

#[test]
fn box_textured_has_its_texture_on_its_faces() {
    let dir = repo("assets/models/khronos");
    let text = "[image]\nwidth = 8\nheight = 8\n\
                [camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n\
                [[lights]]\ntype = \"point\"\nposition = [0, 5, 5]\n\
                [[objects]]\ntype = \"mesh\"\nfile = \"BoxTextured.glb\"\n";
    let scene = load_str(text, &dir.join("t.toml"), &dir, Format::Toml).unwrap();
    // One mesh (a node may carry a matrix turning it), one textured material.
    assert_eq!(scene.objects.len(), 1);
    let b = scene.objects[0].world_bounds.unwrap();
    assert!(
        ((b.max - b.min) - snell::math::Vec3A::ONE)
            .abs()
            .max_element()
            < 1e-4
    );
    let textured: Vec<_> = scene
        .textures
        .iter()
        .filter(|t| matches!(t.pattern, Pattern::Image(_)))
        .collect();
    assert_eq!(textured.len(), 1, "its base colour image");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}
