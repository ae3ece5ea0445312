//! The sampling of shapes for area lights, seen from a point as a light sampler sees it:
//! directions to the sampled points follow the densities the shapes report, converted to
//! solid angle, by the chi-square test of src/math/chi2.rs; and the densities integrate to
//! the shape's area.

use super::{
    Disk, Intersect, Rect, ShapeHit, Sphere, SurfaceSample, Triangle, area_to_solid_angle,
};
use crate::math::chi2::{SphereBins, chi2_sphere};
use crate::math::{Ray, Vec2, Vec3A};

/// Chi-square of the directions from `from` to points drawn by `sample` (densities per unit
/// area), against the density per solid angle of the point each direction meets first.
fn check_area_sampling(
    name: &str,
    from: Vec3A,
    sample: impl Fn(Vec2) -> SurfaceSample,
    hit: impl Fn(&Ray) -> Option<ShapeHit>,
    area_pdf: f32,
    normal_at: impl Fn(Vec3A) -> Vec3A,
) {
    chi2_sphere(
        name,
        SphereBins::default(),
        |u| {
            let s = sample(u);
            assert!(
                (s.pdf - area_pdf).abs() <= 1e-5 * area_pdf,
                "{name}: pdf {}",
                s.pdf
            );
            Some((s.point - from).normalize())
        },
        |dir| match hit(&Ray::new(from, dir)) {
            Some(h) => {
                let p = from + h.t * dir;
                area_to_solid_angle(area_pdf, from, p, normal_at(p)).unwrap_or(0.0)
            }
            None => 0.0,
        },
    )
    .unwrap();
}

#[test]
fn a_rectangle_sampled_by_area() {
    let r = Rect::new(
        Vec3A::new(-1.0, 2.0, -1.0),
        Vec3A::new(2.0, 0.0, 0.0),
        Vec3A::new(0.5, 0.0, 1.5),
    )
    .unwrap();
    assert!((r.area() - 3.0).abs() < 1e-6);
    let n = r.sample_area(Vec2::ZERO).normal;
    check_area_sampling(
        "rectangle",
        Vec3A::new(0.3, 0.0, 0.2),
        |u| r.sample_area(u),
        |ray| r.intersect(ray, f32::INFINITY),
        1.0 / 3.0,
        |_| n,
    );
}

#[test]
fn a_disk_sampled_by_area() {
    let d = Disk::new(Vec3A::new(0.0, 0.0, 3.0), Vec3A::new(0.2, 0.1, -1.0), 1.5);
    let n = d.frame.w;
    check_area_sampling(
        "disk",
        Vec3A::new(0.5, -0.2, 0.0),
        |u| d.sample_area(u),
        |ray| d.intersect(ray, f32::INFINITY),
        1.0 / d.area(),
        |_| n,
    );
}

#[test]
fn a_triangle_sampled_by_area() {
    let t = Triangle::new(
        Vec3A::new(-1.0, -1.0, 2.0),
        Vec3A::new(2.0, -0.5, 2.5),
        Vec3A::new(0.0, 1.5, 1.5),
    )
    .unwrap();
    let n = t.sample_area(Vec2::ZERO).normal;
    check_area_sampling(
        "triangle",
        Vec3A::ZERO,
        |u| t.sample_area(u),
        |ray| t.intersect(ray, f32::INFINITY),
        1.0 / t.area(),
        |_| n,
    );
}

/// From inside, every direction meets the sphere once: area sampling seen from there.
#[test]
fn a_sphere_sampled_by_area_from_inside() {
    let s = Sphere {
        center: Vec3A::new(0.2, 0.1, 0.0),
        radius: 2.0,
    };
    let c = s.center;
    check_area_sampling(
        "sphere from inside",
        Vec3A::new(0.5, -0.4, 0.3),
        |u| s.sample_area(u),
        |ray| s.intersect(ray, f32::INFINITY),
        1.0 / s.area(),
        |p| (p - c).normalize(),
    );
}

/// From outside, by the cone it fills: the directions fill the cone evenly, only the
/// visible cap is reached, and the reported density is the cone's.
#[test]
fn a_sphere_sampled_by_solid_angle() {
    let s = Sphere {
        center: Vec3A::new(1.0, 2.0, 4.0),
        radius: 1.5,
    };
    for from in [Vec3A::ZERO, Vec3A::new(1.0, 2.0, 6.0)] {
        chi2_sphere(
            &format!("sphere by solid angle from {from}"),
            SphereBins::default(),
            |u| {
                let p = s.sample_solid_angle(from, u).unwrap();
                let dir = (p.point - from).normalize();
                // On the cap that `from` sees: (p - c) . (from - c) >= r^2.
                let cap = (p.point - s.center).dot(from - s.center);
                assert!(
                    cap >= s.radius * s.radius * (1.0 - 1e-4),
                    "a point on the far side"
                );
                assert!((p.point - s.center).length() - s.radius < 1e-4);
                assert!((p.pdf - s.solid_angle_pdf(from, p.point)).abs() < 1e-6);
                Some(dir)
            },
            |dir| match s.intersect(&Ray::new(from, dir), f32::INFINITY) {
                Some(h) => s.solid_angle_pdf(from, from + h.t * dir),
                None => 0.0,
            },
        )
        .unwrap();
    }
}

/// The conversion to solid angle against its closed form, `pdf d^2 / cos`, near and as far
/// as a float's square allows; and no density where the surface is seen edge-on or from
/// on it.
#[test]
fn area_densities_convert_to_solid_angle() {
    let normal = Vec3A::new(0.0, 0.0, -1.0);
    let mut checked = 0;
    for distance in [1e-3f32, 0.5, 1.0, 7.0, 1e6, 1e12, 1e15] {
        for tilt in [0.0f32, 0.4, 1.2] {
            let point = Vec3A::new(distance * tilt.sin(), 0.0, distance * tilt.cos());
            let want = 0.25 * (distance as f64).powi(2) / (tilt as f64).cos();
            let got = area_to_solid_angle(0.25, Vec3A::ZERO, point, normal)
                .unwrap_or_else(|| panic!("distance {distance}, tilt {tilt}"));
            assert!(
                ((got as f64 - want) / want).abs() < 1e-5,
                "distance {distance}, tilt {tilt}: {got} against {want}"
            );
            let (_, d) = super::area_to_solid_angle_across(0.25, point, normal);
            assert!(((d - distance) / distance).abs() < 1e-6);
            checked += 1;
        }
    }
    assert_eq!(checked, 21);
    let edge_on = Vec3A::new(1.0, 0.0, 0.0);
    assert_eq!(area_to_solid_angle(1.0, Vec3A::ZERO, edge_on, normal), None);
    assert_eq!(area_to_solid_angle(1.0, edge_on, edge_on, normal), None);
}
