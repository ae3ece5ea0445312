//! Renders with light path expressions: partitions of the paths add up to the picture (with a
//! clamp too), lobes and lights share out their light, `C<RD>L` and `CL` are a render of depth
//! two, and Whitted is refused.

use super::*;
use crate::lpe::{Named, Preset, Request, expand};
use crate::render::pass::tests::{bits, options};
use crate::render::render;
use crate::scene::{Format, load_str};

/// A small room with a diffuse floor, a mirror, glass, a glowing sphere, a point light and
/// an environment: every kind of event.
fn scene(extra: &str) -> Scene {
    let text = format!(
        "[image]\nwidth = 24\nheight = 18\nsamples = 8\n{extra}\n[integrator]\ntype = \"path\"\n\
         [camera]\nposition = [0, 1, 5]\nlook_at = [0, 0, 0]\nfov = 45\n\
         [environment]\ntype = \"constant\"\ncolor = [0.2, 0.25, 0.3]\n\
         [materials.white]\ntype = \"diffuse\"\ncolor = 0.6\n\
         [materials.mirror]\ntype = \"conductor\"\nmetal = \"Ag\"\n\
         [materials.rough]\ntype = \"plastic\"\ncolor = [0.7, 0.2, 0.1]\nroughness = 0.3\n\
         [materials.glass]\ntype = \"dielectric\"\nior = 1.5\n\
         [materials.glow]\ntype = \"diffuse\"\ncolor = 0\nemission = 6\n\
         [[lights]]\ntype = \"point\"\nname = \"sun\"\nposition = [2, 4, 2]\nintensity = 20\n\
         [[objects]]\ntype = \"sphere\"\nname = \"lamp\"\ncenter = [-1.5, 1.5, -1]\nradius = 0.4\nmaterial = \"glow\"\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0.9, 0, 0]\nradius = 0.6\nmaterial = \"glass\"\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [-0.8, 0, 0]\nradius = 0.6\nmaterial = \"mirror\"\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0, 0.2, -1.5]\nradius = 0.7\nmaterial = \"rough\"\n\
         [[objects]]\ntype = \"plane\"\npoint = [0, -0.6, 0]\nmaterial = \"white\"\n"
    );
    load_str(
        &text,
        std::path::Path::new("t.toml"),
        std::path::Path::new("."),
        Format::Toml,
    )
    .unwrap()
}

fn named(pairs: &[(&str, &str)]) -> Vec<Named> {
    pairs
        .iter()
        .map(|(n, e)| Named {
            name: n.to_string(),
            expr: e.to_string(),
        })
        .collect()
}

/// The sum of some layers, pixel by pixel.
fn sum(layers: &[Image]) -> Vec<Color> {
    let mut out = vec![Color::ZERO; layers[0].pixels.len()];
    for l in layers {
        for (o, p) in out.iter_mut().zip(&l.pixels) {
            *o += *p;
        }
    }
    out
}

/// Asserts that `a` and `b` agree within float rounding of sums of a few terms.
fn assert_close(a: &[Color], b: &[Color], what: &str) {
    assert_eq!(a.len(), b.len());
    let mut checked = 0;
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        let tol = 1e-5 * x.max_element().max(y.max_element()).max(1.0);
        assert!(
            (*x - *y).abs().max_element() <= tol,
            "{what}: pixel {i}: {x} against {y}"
        );
        checked += 1;
    }
    assert_eq!(checked, 24 * 18);
}

/// Expressions that share out every path add up to the picture, pixel by pixel, within
/// float rounding: the four, and the presets' four; the picture is the plain
/// render's, to the bit; and the parts are not empty (each shows some light).
#[test]
fn a_partition_of_paths_adds_up_to_the_picture() {
    let scene = scene("");
    let plain = render(&scene, &Path, Some(2), &|_| {}).unwrap();
    for set in [
        named(&[
            ("a", "CL"),
            ("b", "C<RD>L"),
            ("c", "C<RD>.+L"),
            ("d", "C[^D].*L"),
        ]),
        expand(
            &[
                Preset::Emission,
                Preset::Direct,
                Preset::Indirect,
                Preset::Specular,
            ]
            .map(Request::Preset),
            &scene,
        ),
    ] {
        let lpe = LpeSet::new(&scene, &set).unwrap();
        let r = render_lpe(&scene, &lpe, &options(2)).unwrap();
        assert_eq!(bits(&r.rendered.image.pixels), bits(&plain.image.pixels));
        assert_eq!(r.layers.len(), 4);
        assert_close(
            &sum(&r.layers),
            &r.rendered.image.pixels,
            &format!("{set:?}"),
        );
        for (l, n) in r.layers.iter().zip(&set) {
            let total: f32 = l.pixels.iter().map(|c| c.element_sum()).sum();
            assert!(total > 0.0, "{} is black", n.name);
        }
    }
}

/// Each light's layer (`per-light`) adds up to the picture too; a glossy plastic's light
/// samples are shared between its diffuse base and its coat (`D` and `G`), which add up to
/// all that one bounce off it gives.
#[test]
fn lights_and_lobes_share_out_the_light() {
    let scene = scene("");
    let per = expand(&[Request::Preset(Preset::PerLight)], &scene);
    let names: Vec<&str> = per.iter().map(|n| n.name.as_str()).collect();
    assert_eq!(names, ["lamp", "sun", "environment"]);
    let set = LpeSet::new(&scene, &per).unwrap();
    let r = render_lpe(&scene, &set, &options(1)).unwrap();
    assert_close(&sum(&r.layers), &r.rendered.image.pixels, "per-light");
    let lobes = named(&[
        ("d", "C<RD'rough'>L"),
        ("g", "C<RG'rough'>L"),
        ("both", "C 'rough' L"),
    ]);
    let set = LpeSet::new(&scene, &lobes).unwrap();
    let r = render_lpe(&scene, &set, &options(2)).unwrap();
    assert_close(&sum(&r.layers[..2]), &r.layers[2].pixels, "D + G");
    for l in &r.layers[..2] {
        assert!(l.pixels.iter().any(|c| c.max_element() > 0.0));
    }
}

/// With a clamp, each expression's share of a clamped sample is cut in the same ratio, so
/// the parts still add up to the picture.
#[test]
fn a_clamped_render_still_adds_up() {
    let mut scene = scene("");
    scene.settings.integrator.clamp = Some(0.5);
    let set = expand(
        &[
            Preset::Emission,
            Preset::Direct,
            Preset::Indirect,
            Preset::Specular,
        ]
        .map(Request::Preset),
        &scene,
    );
    let lpe = LpeSet::new(&scene, &set).unwrap();
    let r = render_lpe(&scene, &lpe, &options(2)).unwrap();
    assert_close(&sum(&r.layers), &r.rendered.image.pixels, "clamped");
}

/// `C<RD>L` and `CL` of the Cornell box (every surface diffuse) add up to a render of
/// direct light alone (`max_depth = 2`): the same samples take the same numbers for their
/// first bounce.
#[test]
fn direct_diffuse_light_is_a_render_of_depth_two() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/cornell.toml"))
        .unwrap();
    let load = |text: &str| {
        let mut s = load_str(
            text,
            std::path::Path::new("cornell.toml"),
            std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes")),
            Format::Toml,
        )
        .unwrap();
        s.settings.width = 32;
        s.settings.height = 32;
        s.settings.spp = 4;
        s
    };
    let full = load(&text);
    let mut direct = load(&text);
    direct.settings.max_depth = 2;
    let expected = render(&direct, &Path, Some(2), &|_| {}).unwrap();
    let set = LpeSet::new(&full, &named(&[("e", "CL"), ("d", "C<RD>L")])).unwrap();
    let r = render_lpe(&full, &set, &options(2)).unwrap();
    let mut checked = 0;
    for (i, (got, want)) in sum(&r.layers)
        .iter()
        .zip(&expected.image.pixels)
        .enumerate()
    {
        let tol = 1e-5 * want.max_element().max(1.0);
        assert!(
            (*got - *want).abs().max_element() <= tol,
            "pixel {i}: {got} against {want}"
        );
        checked += 1;
    }
    assert_eq!(checked, 32 * 32);
    // And the full render has more light than that: the indirect.
    let total = |p: &[Color]| p.iter().map(|c| c.element_sum()).sum::<f32>();
    assert!(total(&r.rendered.image.pixels) > 1.2 * total(&expected.image.pixels));
}

#[test]
fn whitted_is_refused() {
    let mut scene = scene("");
    scene.settings.integrator.kind = IntegratorKind::Whitted;
    let set = LpeSet::new(&scene, &named(&[("a", "CL")])).unwrap();
    assert!(matches!(
        render_lpe(&scene, &set, &options(1)),
        Err(LpeRenderError::NotPathTracer)
    ));
}
