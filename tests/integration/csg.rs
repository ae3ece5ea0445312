//! `type = "csg"` in a scene: each solid shows its own material where its surface bounds the
//! result; a solid's transform applies within the combination, then the object's; a glass
//! combination with a hollow is a white furnace (its surfaces face out of the result, so
//! refraction knows which way it crosses); the showcase scene builds without a warning.

use super::{repo, scratch};
use snell::integrator::Path as PathTracer;
use snell::math::{Color, Ray, Vec3A};
use snell::render::render;
use snell::scene::{Format, Scene, Skip, load_str};

fn load(text: &str) -> Scene {
    let dir = scratch("csg");
    let scene = load_str(text, &dir.join("t.toml"), &dir, Format::Toml)
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    scene
}

/// A box minus a sphere at its top face, the sphere painted `ink`; placed 2x larger and
/// moved up by 1.
const DENTED: &str = r#"
[camera]
position = [0, 10, 0]
look_at = [0, 0, 0]
up = [0, 0, -1]
[[lights]]
type = "point"
position = [0, 10, 0]
[materials.body]
color = 0.8
[materials.ink]
color = 0.05
[[objects]]
type = "csg"
operation = "difference"
material = "body"
transform = { scale = 2, translate = [0, 1, 0] }
shapes = [
  { type = "box", min = [-1, -1, -1], max = [1, 1, 1] },
  { type = "sphere", center = [0, 1, 0], radius = 0.5, material = "ink" },
  { type = "csg", operation = "union", transform = { translate = [0.75, 0, 0] }, shapes = [
    { type = "sphere", center = [0, 1, 0.75], radius = 0.2 },
    { type = "sphere", center = [0, 1, -0.75], radius = 0.2 },
  ] },
]
"#;

fn hit_down(scene: &Scene, x: f32, z: f32) -> (f32, String, Vec3A) {
    let ray = Ray::new(Vec3A::new(x, 10.0, z), -Vec3A::Y);
    let h = scene
        .closest_hit_with_uv(&ray, f32::INFINITY, Skip::NONE)
        .expect("a hit");
    (
        h.t,
        scene.material_names[h.material].clone(),
        h.shading_normal,
    )
}

#[test]
fn solids_show_their_materials_where_they_bound_the_result() {
    let scene = load(DENTED);
    // The top face is at y = 3 (1 + 2 x 1); the dent's bottom at 3 - 2 x 0.5 = 2.
    let (t, m, n) = hit_down(&scene, 0.0, 0.0);
    assert!((t - 8.0).abs() < 1e-4 && m == "ink", "{t} {m}");
    assert!(
        (n - Vec3A::Y).length() < 1e-4,
        "the dent faces out of the solid: {n}"
    );
    let (t, m, _) = hit_down(&scene, -1.6, 0.0);
    assert!((t - 7.0).abs() < 1e-4 && m == "body", "{t} {m}");
    // The nested union of two small dents, moved 0.75 in x within the combination, then
    // 2x: centred at x = 1.5, z = +-1.5, 0.4 deep. They take the combination's material.
    let (t, m, _) = hit_down(&scene, 1.5, 1.5);
    assert!((t - 7.4).abs() < 1e-4 && m == "body", "{t} {m}");
    let (t, _, _) = hit_down(&scene, 1.5, -1.5);
    assert!((t - 7.4).abs() < 1e-4, "{t}");
    let (t, _, _) = hit_down(&scene, -1.5, 1.5);
    assert!((t - 7.0).abs() < 1e-4, "no dent there: {t}");
    let b = scene.objects[0].world_bounds.unwrap();
    assert!(
        (b.max - Vec3A::new(2.0, 3.0, 2.0)).length() < 1e-4,
        "{}",
        b.max
    );
}

/// Glass with a hollow (a ball minus a ball, the outer one cut by a larger sphere that
/// contains it, so the intersection must not lose it), under a uniform white environment:
/// every path leaves with all its light, as for any closed smooth dielectric, if the
/// surfaces face the right ways. (A concentric shell traps no light: a box would, bouncing
/// by total internal reflection past any depth.)
#[test]
fn a_hollowed_glass_solid_is_a_white_furnace() {
    let text = r#"
[image]
width = 8
height = 8
samples = 64
max_depth = 64
[integrator]
type = "path"
[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
fov = 12
[environment]
type = "constant"
color = 1
[materials.glass]
type = "dielectric"
ior = 1.5
[[objects]]
type = "csg"
operation = "difference"
material = "glass"
shapes = [
  { type = "csg", operation = "intersection", shapes = [
    { type = "sphere", radius = 1 },
    { type = "sphere", radius = 3, center = [0, 0, 0.5] },
  ] },
  { type = "sphere", radius = 0.5 },
]
"#;
    let scene = load(text);
    let img = render(&scene, &PathTracer, Some(2), &|_| {}).unwrap().image;
    // Every path leaves with weight 1 but for Russian roulette's, whose survivors weigh
    // more: the mean is 1, each pixel within its noise.
    let mean = img.pixels.iter().copied().sum::<Color>() / img.pixels.len() as f32;
    assert!((mean - Color::ONE).abs().max_element() < 0.005, "{mean}");
    for p in &img.pixels {
        assert!((*p - Color::ONE).abs().max_element() < 0.05, "{p}");
    }
}

#[test]
fn the_solids_scene_builds_cleanly() {
    let scene = snell::scene::load(&repo("scenes/solids.toml")).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let csg = scene
        .objects
        .iter()
        .filter(|o| o.shape.kind() == "csg")
        .count();
    assert_eq!(csg, 2);
}

/// The dented box of `DENTED` with a closed mesh cube (tests/data/csg/cube.obj, the same
/// box) in place of the analytic one.
fn dented_with_mesh() -> Scene {
    let dir = repo("tests/data/csg");
    let text = DENTED.replace(
        r#"{ type = "box", min = [-1, -1, -1], max = [1, 1, 1] },"#,
        r#"{ type = "mesh", file = "cube.obj" },"#,
    );
    assert_ne!(text, DENTED);
    load_str(&text, &dir.join("t.toml"), &dir, Format::Toml).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_closed_mesh_is_a_solid_with_the_same_hits_as_the_box_it_models() {
    let analytic = load(DENTED);
    let mesh = dented_with_mesh();
    assert!(mesh.warnings.is_empty(), "{:?}", mesh.warnings);
    // Rays from every side (and from inside the box, where the mesh's inside is found by
    // counting crossings), at scattered points: the same hit, material and normal.
    let mut rng = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut hits = 0;
    for i in 0..2000 {
        let origin = if i % 4 == 0 {
            // Inside the placed box (from -1 to 3 in y after the object's transform).
            Vec3A::new(3.6 * next() - 1.8, 4.0 * next() - 1.0, 3.6 * next() - 1.8)
        } else {
            Vec3A::new(
                16.0 * next() - 8.0,
                16.0 * next() - 7.0,
                16.0 * next() - 8.0,
            )
        };
        let target = Vec3A::new(4.0 * next() - 2.0, 4.0 * next() - 1.0, 4.0 * next() - 2.0);
        let Some(dir) = (target - origin).try_normalize() else {
            continue;
        };
        let ray = Ray::new(origin, dir);
        let a = analytic.closest_hit_with_uv(&ray, f32::INFINITY, Skip::NONE);
        let b = mesh.closest_hit_with_uv(&ray, f32::INFINITY, Skip::NONE);
        match (a, b) {
            (None, None) => {}
            (Some(a), Some(b)) => {
                hits += 1;
                assert!(
                    (a.t - b.t).abs() < 1e-3 * a.t.max(1.0),
                    "{ray:?}: {} vs {}",
                    a.t,
                    b.t
                );
                assert_eq!(a.material, b.material, "{ray:?}");
                // Edges and corners may differ in which face's normal they take.
                let p = ray.at(a.t);
                let on_edge = [p.x.abs() - 2.0, p.y - 3.0, p.y + 1.0, p.z.abs() - 2.0]
                    .iter()
                    .filter(|d| d.abs() < 1e-2)
                    .count()
                    > 1;
                if !on_edge {
                    assert!(
                        (a.normal - b.normal).length() < 1e-3,
                        "{ray:?}: {} vs {}",
                        a.normal,
                        b.normal
                    );
                }
            }
            (a, b) => panic!("{ray:?}: {:?} against {:?}", a.map(|h| h.t), b.map(|h| h.t)),
        }
    }
    assert!(hits > 500, "{hits} rays hit");
    // A point inside the placed box but in the dent is outside the result, both ways.
    for s in [&analytic, &mesh] {
        let inside = |p: [f32; 3]| s.objects[0].contains(Vec3A::from_array(p));
        assert!(inside([0.0, 0.0, 0.0]));
        assert!(!inside([0.0, 2.9, 0.0]), "the dent");
        assert!(!inside([2.5, 0.0, 0.0]));
    }
}
