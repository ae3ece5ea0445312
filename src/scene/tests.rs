//! Tests of the scene's queries: rays leaving surfaces, packets against single rays.
use super::*;
use crate::geometry::test_util::in_unit_cube;
use crate::math::Rng;
use std::path::Path;

fn scene(objects: &str) -> Scene {
    let text = format!("[camera]\nlook_at = [0, 0, -1]\n[materials.m]\ncolor = 1\n{objects}");
    load_str(&text, Path::new("t.toml"), Path::new("."), Format::Toml).unwrap()
}

fn object(kind: &str, rest: &str) -> String {
    format!("[[objects]]\ntype = \"{kind}\"\nmaterial = \"m\"\n{rest}\n")
}

/// A ray leaving a surface finds the same hit whether or not its walk leaves out the
/// object it leaves (`Scene::leaving`), and the object's own test misses it: for every
/// kind of analytic shape, placed as given and mirrored, sheared and turned by
/// transforms, in the flat layout and in a tree, for shadow-like and reflected rays
/// from the offset origins the renderer uses. Rays leaving solids inward skip nothing.
#[test]
fn leaving_a_surface_skips_only_what_cannot_be_met() {
    let shapes = [
        object("sphere", "center = [0, 0, -10]\nradius = 2"),
        object("box", "min = [2, -3, -14]\nmax = [4, -1, -12]"),
        object(
            "cylinder",
            "base = [-3, -3, -12]\naxis = [0, 1, 0]\nradius = 1\nheight = 3\ncapped = true",
        ),
        object(
            "cone",
            "base = [3, 1, -9]\naxis = [0.2, 1, 0]\nradius = 1\nheight = 2\ncapped = false",
        ),
        object(
            "sphere",
            "radius = 1\ntransform = { scale = [-2, 1, 0.7], rotate = [30, 10, 0], translate = [1, 2, -9] }",
        ),
        object(
            "box",
            "min = [-1, -1, -1]\nmax = [1, 1, 1]\ntransform = { scale = [1, -0.5, 2], rotate = [0, 45, 20], translate = [-2, 2, -13] }",
        ),
        object("disk", "center = [0, 2, -16]\nnormal = [0, 0, 1]\nradius = 2"),
        object(
            "rectangle",
            "corner = [-5, -3, -20]\nedge_u = [10, 0, 0]\nedge_v = [0, 0, 15]",
        ),
        object("plane", "point = [0, -3.5, 0]"),
    ]
    .concat();
    let crowd: String = (0..12)
        .map(|i| {
            object(
                "sphere",
                &format!(
                    "center = [{}, {}, -11]\nradius = 0.9",
                    i % 4 * 2 - 3,
                    i / 4 * 2 - 2
                ),
            )
        })
        .collect();
    let mut rng = Rng::new(17);
    for (scene, name) in [
        (scene(&shapes), "shapes"),
        (scene(&(shapes.clone() + &crowd)), "tree"),
    ] {
        let (mut skipped, mut inward) = (0, 0);
        for _ in 0..6000 {
            let eye = in_unit_cube(&mut rng) * 16.0 + Vec3A::new(0.0, 0.0, -10.0);
            let to = in_unit_cube(&mut rng) * 6.0 + Vec3A::new(0.0, 0.0, -11.0);
            let Some(hit) =
                scene.closest_hit(&Ray::new(eye, (to - eye).normalize()), f32::INFINITY)
            else {
                continue;
            };
            let dir_in = (to - eye).normalize();
            let outward = dir_in.dot(hit.normal) < 0.0;
            let n = if outward { hit.normal } else { -hit.normal };
            // A random direction on the side the ray arrived from.
            let mut d = (in_unit_cube(&mut rng) * 2.0 - Vec3A::ONE).normalize_or(n);
            if d.dot(n) < 0.0 {
                d = -d;
            }
            if d.dot(n) < 1e-3 {
                continue;
            }
            let ray = Ray::new(crate::math::offset_ray_origin(hit.point, n), d);
            let skip = scene.leaving(&hit, outward);
            if skip == Skip::NONE {
                inward += 1;
            } else {
                skipped += 1;
                assert!(
                    scene.objects[hit.object]
                        .intersect(&ray, f32::INFINITY)
                        .is_none(),
                    "{name}: {} met again",
                    scene.objects[hit.object].name
                );
            }
            let key = |h: Option<Hit>| h.map(|h| (h.object, h.t.to_bits()));
            assert_eq!(
                key(scene.closest_hit_skipping(&ray, f32::INFINITY, skip)),
                key(scene.closest_hit(&ray, f32::INFINITY)),
                "{name}: {ray:?} leaving {}",
                scene.objects[hit.object].name
            );
        }
        assert!(
            skipped > 1000 && inward > 50,
            "{name}: {skipped} skipped, {inward} inward"
        );
    }
}

/// Hits found a packet at a time are the hits found one ray at a time, to the bit: in a
/// scene of every kind of shape (the flat layout, an unbounded plane, a transformed
/// sphere), in one of many spheres (the tree) and in one of a lone sphere; for camera
/// rays of one pixel and for rays in every direction, in whole and partial packets.
#[test]
fn packets_find_what_single_rays_find() {
    let every_kind = [
        object("sphere", "center = [0, 0, -10]\nradius = 2"),
        object(
            "rectangle",
            "corner = [-5, -3, -20]\nedge_u = [10, 0, 0]\nedge_v = [0, 0, 15]",
        ),
        object("box", "min = [2, -3, -14]\nmax = [4, -1, -12]"),
        object(
            "cylinder",
            "base = [-3, -3, -12]\naxis = [0, 1, 0]\nradius = 1\nheight = 3\ncapped = true",
        ),
        object(
            "sphere",
            "radius = 1\ntransform = { scale = [2, 1, 1], translate = [1, 2, -9] }",
        ),
        object(
            "disk",
            "center = [0, 2, -16]\nnormal = [0, 0, 1]\nradius = 2",
        ),
        object(
            "triangle",
            "vertices = [[-4, 0, -8], [-2, 0, -9], [-3, 2, -8.5]]",
        ),
        object("plane", "point = [0, -3.5, 0]"),
    ]
    .concat();
    let many: String = (0..20)
        .map(|i| {
            object(
                "sphere",
                &format!(
                    "center = [{}, {}, -12]\nradius = 0.8",
                    i % 5 * 2 - 4,
                    i / 5 * 2 - 3
                ),
            )
        })
        .collect();
    let lone = [
        object("sphere", "center = [0, 0, -10]\nradius = 2"),
        object("plane", "point = [0, -3, 0]"),
    ]
    .concat();
    let mut rng = Rng::new(3);
    for (name, text) in [("every kind", every_kind), ("many", many), ("lone", lone)] {
        let scene = scene(&text);
        let mut hits = 0;
        for round in 0..3000 {
            let n = [16, 8, 3, 13][round % 4];
            let camera_like = round % 2 == 0;
            let center = Vec3A::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, -1.0);
            let rays: Vec<Ray> = (0..n)
                .map(|_| {
                    let jitter = Vec3A::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, 0.0);
                    if camera_like {
                        Ray::new(Vec3A::ZERO, (center + jitter * 0.01).normalize())
                    } else {
                        let o = in_unit_cube(&mut rng) * 20.0 - Vec3A::new(0.0, 0.0, 15.0);
                        Ray::new(o, in_unit_cube(&mut rng).normalize())
                    }
                })
                .collect();
            let mut found = vec![None; n];
            scene.closest_hits(&rays, &mut found, crate::scene::Reach::ALL);
            for (ray, got) in rays.iter().zip(&found) {
                let want = scene.closest_hit(ray, f32::INFINITY);
                // Debug prints every float exactly (the shortest form that reads back).
                assert_eq!(format!("{got:?}"), format!("{want:?}"), "{name}: {ray:?}");
                hits += want.is_some() as usize;
            }
        }
        assert!(hits > 5000, "{name}: {hits} hits");
    }
}
