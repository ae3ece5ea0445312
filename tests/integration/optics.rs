//! Optics through a built scene: a ray refracted into a glass sphere finds the far side and
//! leaves where Snell's law and the sphere's geometry say.

use snell::math::{Ray, Vec3A, offset_ray_origin, refract};
use snell::scene::{Format, load_str};
use std::path::Path;

const GLASS: &str = r#"
[camera]
look_at = [0, 0, -1]
[materials.glass]
transparency = 1
ior = 1.5
[[objects]]
type = "sphere"
center = [0, 0, -10]
radius = 2
material = "glass"
"#;

#[test]
fn ray_through_a_glass_sphere_is_deviated_as_geometry_predicts() {
    let scene = load_str(GLASS, Path::new("glass.toml"), Path::new("."), Format::Toml).unwrap();
    let (r, n) = (2.0f32, 1.5f32);
    for b in [0.0f32, 0.3, 0.8, 1.2, 1.6, 1.9] {
        // Parallel to -z at height b (the impact parameter).
        let ray = Ray::new(Vec3A::new(0.0, b, 0.0), -Vec3A::Z);
        let entry = scene.closest_hit(&ray, f32::INFINITY).unwrap();
        let inside = refract(ray.dir, entry.normal, 1.0 / n).unwrap();
        let origin = offset_ray_origin(entry.point, -entry.normal);
        // From inside, the sphere test returns the far side.
        let exit = scene
            .closest_hit(&Ray::new(origin, inside), f32::INFINITY)
            .unwrap();
        assert!(
            exit.t > 0.0 && inside.dot(exit.normal) > 0.0,
            "b = {b}: not the far side"
        );
        let chord = (exit.point - entry.point).length();
        let (i, t) = ((b / r).asin(), ((b / r).asin().sin() / n).asin());
        assert!(
            (chord - 2.0 * r * t.cos()).abs() < 1e-4,
            "b = {b}: chord {chord}"
        );
        let out = refract(inside, -exit.normal, n).expect("a sphere never traps a ray it let in");
        // Total deviation of a ray through a sphere: D = 2 (i - t), toward the axis.
        let deviation = out.dot(-Vec3A::Z).clamp(-1.0, 1.0).acos();
        assert!(
            (deviation - 2.0 * (i - t)).abs() < 1e-4,
            "b = {b}: deviation {deviation} vs {}",
            2.0 * (i - t)
        );
        if b > 0.0 {
            assert!(out.y < 0.0, "bent toward the axis");
        }
        // It leaves at the mirror image of where it came in, and does not re-hit the sphere.
        assert!((exit.point.y + entry.point.y * (2.0 * t).cos() - 0.0).is_finite());
        let after = Ray::new(offset_ray_origin(exit.point, exit.normal), out);
        assert!(
            scene.closest_hit(&after, f32::INFINITY).is_none(),
            "b = {b}: re-hit after leaving"
        );
    }
}

#[test]
fn secondary_rays_never_rehit_their_surface_at_any_scale() {
    for scale in [1e-3f32, 1.0, 1e3, 1e5] {
        let text = GLASS
            .replace(
                "center = [0, 0, -10]",
                &format!("center = [0, 0, {}]", -10.0 * scale),
            )
            .replace("radius = 2", &format!("radius = {}", 2.0 * scale));
        let scene = load_str(&text, Path::new("s.toml"), Path::new("."), Format::Toml).unwrap();
        // Every ray is 0.188 rad off the axis, inside the 0.201 rad the sphere fills: each
        // one hits.
        for k in 0..200 {
            let a = k as f32 * 0.0314;
            let dir = Vec3A::new(a.sin() * 0.19, a.cos() * 0.19, -1.0).normalize();
            let h = scene
                .closest_hit(&Ray::new(Vec3A::ZERO, dir), f32::INFINITY)
                .unwrap_or_else(|| panic!("scale {scale}: ray {k} misses the sphere"));
            // Leaving outward (a reflection) must find nothing.
            let out = Ray::new(
                offset_ray_origin(h.point, h.normal),
                snell::math::reflect(dir, h.normal),
            );
            assert!(
                scene.closest_hit(&out, f32::INFINITY).is_none(),
                "scale {scale}: reflected ray re-hit"
            );
            // Going inward must find the far side, not the same point.
            let inward = Ray::new(offset_ray_origin(h.point, -h.normal), dir);
            let far = scene.closest_hit(&inward, f32::INFINITY).unwrap();
            assert!(
                far.t > 0.1 * scale,
                "scale {scale}: inward ray re-hit at t = {}",
                far.t
            );
        }
    }
}
