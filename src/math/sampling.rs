//! Warps from the unit square to the shapes that rendering samples, each with its density:
//! the building blocks of BSDF and light sampling. Directions are in a local frame with `z`
//! as the pole (the shading normal, or a cone's axis). Each warp's density is checked
//! against its samples by a chi-square test (src/math/chi2.rs).

use super::{Vec2, Vec3A};
use std::f32::consts::{FRAC_PI_4, PI};

/// A point on the unit disk, by Shirley and Chiu's concentric map (neighbouring points of
/// the square stay neighbours, so stratified samples stay stratified). Density `1 / pi`
/// over the disk's area.
pub fn uniform_disk_concentric(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o == Vec2::ZERO {
        return Vec2::ZERO;
    }
    // The angle is `phi` from the x axis in the left and right quarters, and `pi/2 - phi`
    // in the top and bottom ones, whose cosine and sine are `phi`'s sine and cosine. Both
    // from the polynomial of `approx` (within 2e-7, as close as the library's on this
    // range), inlined: the library's `sincosf`, a call through the PLT that returns
    // through memory, was 3.6 % of the Cornell box's time (docs/perf-log.md).
    let (r, phi, turned) = if o.x.abs() > o.y.abs() {
        (o.x, FRAC_PI_4 * (o.y / o.x), false)
    } else {
        (o.y, FRAC_PI_4 * (o.x / o.y), true)
    };
    let (sin, cos) = super::approx::sin_cos(phi);
    r * if turned {
        Vec2::new(sin, cos)
    } else {
        Vec2::new(cos, sin)
    }
}

/// A direction about `+z` with density proportional to its cosine (Malley's method: a disk
/// point lifted to the hemisphere). Density [`cosine_hemisphere_pdf`].
pub fn cosine_hemisphere(u: Vec2) -> Vec3A {
    let d = uniform_disk_concentric(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    Vec3A::new(d.x, d.y, z)
}

/// The density of [`cosine_hemisphere`] per unit solid angle: `cos theta / pi` above the
/// plane `z = 0`, 0 below.
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    cos_theta.max(0.0) / PI
}

/// A direction on the whole unit sphere, every one equally likely: density `1 / (4 pi)`.
pub fn uniform_sphere(u: Vec2) -> Vec3A {
    // The cone that reaches all the way round.
    uniform_cone(u, -1.0)
}

/// The density of [`uniform_sphere`] per unit solid angle.
pub const UNIFORM_SPHERE_PDF: f32 = 1.0 / (4.0 * PI);

/// A direction within the cone about `+z` of half-angle `acos(cos_max)`, every one equally
/// likely (sampling a sphere light by the solid angle it covers). Density
/// [`uniform_cone_pdf`].
pub fn uniform_cone(u: Vec2, cos_max: f32) -> Vec3A {
    let z = 1.0 - u.x * (1.0 - cos_max);
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3A::new(r * phi.cos(), r * phi.sin(), z)
}

/// The density of [`uniform_cone`] per unit solid angle, inside the cone.
pub fn uniform_cone_pdf(cos_max: f32) -> f32 {
    1.0 / (2.0 * PI * (1.0 - cos_max))
}

/// Barycentric coordinates `(b0, b1)` of a point on a triangle, every point equally likely
/// (Heitz's low-distortion map: no square root, and it keeps stratification). The point is
/// `b0 p0 + b1 p1 + (1 - b0 - b1) p2`; its density is `1 / area` of the triangle.
pub fn uniform_triangle(u: Vec2) -> Vec2 {
    if u.y > u.x {
        let b0 = u.x / 2.0;
        let b1 = u.y - b0;
        Vec2::new(b0, b1)
    } else {
        let b1 = u.y / 2.0;
        let b0 = u.x - b1;
        Vec2::new(b0, b1)
    }
}

#[cfg(test)]
mod tests {
    use super::super::chi2::{SphereBins, chi2_sphere, chi2_square};
    use super::*;

    #[test]
    fn cosine_hemisphere_matches_its_pdf() {
        chi2_sphere(
            "cosine hemisphere",
            SphereBins::default(),
            |u| Some(cosine_hemisphere(u)),
            |d| cosine_hemisphere_pdf(d.z),
        )
        .unwrap();
    }

    #[test]
    fn uniform_sphere_matches_its_pdf() {
        chi2_sphere(
            "uniform sphere",
            SphereBins::default(),
            |u| Some(uniform_sphere(u)),
            |_| UNIFORM_SPHERE_PDF,
        )
        .unwrap();
    }

    #[test]
    fn uniform_cone_matches_its_pdf() {
        for cos_max in [0.95f32, 0.5, -0.3] {
            chi2_sphere(
                &format!("cone cos_max {cos_max}"),
                SphereBins::default(),
                |u| Some(uniform_cone(u, cos_max)),
                |d| {
                    if d.z >= cos_max {
                        uniform_cone_pdf(cos_max)
                    } else {
                        0.0
                    }
                },
            )
            .unwrap();
        }
    }

    /// The disk's points, mapped to `(r^2, phi / 2 pi)` in the unit square, where a uniform
    /// disk is uniform (the area element `r dr dphi` is `pi ds dt` there).
    #[test]
    fn concentric_disk_is_uniform() {
        chi2_square(
            "concentric disk",
            24,
            |u| {
                let p = uniform_disk_concentric(u);
                let phi = p.y.atan2(p.x).rem_euclid(2.0 * PI);
                Some(Vec2::new(p.length_squared().min(1.0), phi / (2.0 * PI)))
            },
            |_| 1.0,
        )
        .unwrap();
    }

    /// The triangle `(0,0) (1,0) (0,1)` in barycentrics `(b0, b1)`: density 2 on the lower
    /// half of the square, none above the diagonal.
    #[test]
    fn triangle_is_uniform() {
        chi2_square(
            "triangle",
            24,
            |u| Some(uniform_triangle(u)),
            |p| {
                if p.x + p.y <= 1.0 { 2.0 } else { 0.0 }
            },
        )
        .unwrap();
    }

    /// A density 10 % too high on a quarter of the directions is caught: the harness can
    /// fail, as every test built on it must.
    #[test]
    fn a_wrong_pdf_fails_the_test() {
        let wrong = |d: Vec3A| {
            let p = cosine_hemisphere_pdf(d.z);
            if d.x > 0.0 && d.y > 0.0 {
                p * 1.1
            } else {
                p * (1.0 - 0.1 / 3.0)
            }
        };
        assert!(
            chi2_sphere(
                "wrong",
                SphereBins::default(),
                |u| Some(cosine_hemisphere(u)),
                wrong
            )
            .is_err()
        );
        let wrong_cone = |d: Vec3A| {
            if d.z >= 0.6 {
                uniform_cone_pdf(0.5)
            } else if d.z >= 0.5 {
                uniform_cone_pdf(0.5) * 0.5
            } else {
                0.0
            }
        };
        assert!(
            chi2_sphere(
                "wrong cone",
                SphereBins::default(),
                |u| Some(uniform_cone(u, 0.5)),
                wrong_cone
            )
            .is_err()
        );
    }
}
