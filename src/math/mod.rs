//! Small math vocabulary shared by every part of the renderer: rays, boxes, frames,
//! transforms, robust ray offsets, a deterministic random number generator, and the warps
//! that sampling builds on.

mod aabb;
pub mod approx;
pub mod chi2;
pub mod differential;
pub mod distribution;
pub mod distribution2d;
mod frame;
mod frustum;
pub mod keyframes;
mod offset;
pub mod poly;
pub mod quadrature;
mod rng;
pub mod sampling;
pub mod spectrum;
mod transform;
pub mod wavelength;

pub use aabb::Aabb;
pub use frame::Frame;
pub use frustum::{FilmPlanes, Frustum};
pub use glam::{Vec2, Vec3, Vec3A};
pub use offset::offset_ray_origin;
pub use rng::{Rng, hash_seed};
pub use transform::Transform;
pub use wavelength::Wavelength;

/// Largest magnitude of any number a scene or a mesh file may give: its square (1e30) still
/// fits in an `f32`, so lengths, areas and quadratics cannot overflow.
pub const MAX_MAGNITUDE: f32 = 1e15;

/// Linear RGB colour (not sRGB encoded), one `f32` per channel.
pub type Color = Vec3A;

/// The luminance of a linear RGB colour (Rec. 709 primaries, as sRGB).
#[inline]
pub fn luminance(c: Color) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// A half-line `origin + t * dir`. World-space rays carry a unit `dir`; rays carried into an
/// object's space by a transform may not, and every intersection routine accepts that.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: Vec3A,
    /// Which way it goes (unit length in world space).
    pub dir: Vec3A,
}

impl Ray {
    /// A ray from `origin` along `dir`.
    pub fn new(origin: Vec3A, dir: Vec3A) -> Self {
        Ray { origin, dir }
    }

    /// The point at parameter `t`.
    pub fn at(&self, t: f32) -> Vec3A {
        self.origin + self.dir * t
    }
}

/// How many rays a packet holds (see [`RayLanes`]): one 256-bit vector of `f32`.
pub const LANES: usize = 8;

/// A packet of rays stored coordinate by coordinate, so that one vector instruction works
/// on the same coordinate of every ray. Shapes test a packet at once where its rays are
/// likely to meet the same objects: the camera rays of one pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayLanes {
    /// The origins' x, y and z.
    pub origin: [[f32; LANES]; 3],
    /// The directions' x, y and z.
    pub dir: [[f32; LANES]; 3],
}

impl RayLanes {
    /// The packet of `rays` (one to [`LANES`] of them); lanes past the last ray repeat it,
    /// so that every lane holds a ray and works out something meaningful.
    pub fn new(rays: &[Ray]) -> Self {
        assert!(
            !rays.is_empty() && rays.len() <= LANES,
            "a packet holds 1 to {LANES} rays"
        );
        let mut p = RayLanes {
            origin: [[0.0; LANES]; 3],
            dir: [[0.0; LANES]; 3],
        };
        for l in 0..LANES {
            let r = &rays[l.min(rays.len() - 1)];
            for a in 0..3 {
                p.origin[a][l] = r.origin[a];
                p.dir[a][l] = r.dir[a];
            }
        }
        p
    }
}

/// Mirror reflection of direction `d` about the normal `n` (unit). The reflection keeps
/// `d`'s length, to rounding (a test bounds it), so a unit `d` needs no normalising after,
/// whose square root and division would lengthen every reflected ray's chain of dependent
/// operations. ([`refract`] normalises: an error in `d`'s length comes out of it multiplied
/// by `eta^2`.)
pub fn reflect(d: Vec3A, n: Vec3A) -> Vec3A {
    d - 2.0 * d.dot(n) * n
}

/// Refraction of the unit direction `d` through a surface with unit normal `n` facing the
/// incoming ray (`d . n < 0`), where `eta` is n_incident / n_transmitted. Returns `None` on
/// total internal reflection (Snell's law has no solution).
pub fn refract(d: Vec3A, n: Vec3A, eta: f32) -> Option<Vec3A> {
    let cos_i = (-d.dot(n)).min(1.0);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(refracted(d, n, cos_i, cos_t, eta))
}

/// The refracted direction of `d` through `n` once both cosines are known.
#[inline(always)]
fn refracted(d: Vec3A, n: Vec3A, cos_i: f32, cos_t: f32, eta: f32) -> Vec3A {
    (eta * d + (eta * cos_i - cos_t) * n).normalize()
}

/// Unpolarised Fresnel reflectance of a dielectric boundary, exactly (not Schlick's
/// approximation). `cos_i` is the cosine between the incoming ray and the normal on its side
/// (positive), `eta` is n_incident / n_transmitted. Total internal reflection gives 1.
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    fresnel_of_cosines(cos_i, (1.0 - sin2_t).sqrt(), eta)
}

/// Fresnel's reflectance once both cosines are known.
#[inline(always)]
fn fresnel_of_cosines(cos_i: f32, cos_t: f32, eta: f32) -> f32 {
    // With n_i = eta, n_t = 1 (only the ratio matters).
    let r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    0.5 * (r_s * r_s + r_p * r_p)
}

/// [`fresnel_dielectric`] and [`refract`] of the unit direction `d` through the unit normal
/// `n` at once, `cos_i` being `-d . n`: where that is in `[0, 1]` both come from one square
/// root, to the bit what each gives alone (the reflectance, and the refracted direction
/// `None` on total internal reflection).
#[inline(always)]
pub fn fresnel_refract(d: Vec3A, n: Vec3A, cos_i: f32, eta: f32) -> (f32, Option<Vec3A>) {
    if !(0.0..=1.0).contains(&cos_i) {
        return (fresnel_dielectric(cos_i, eta), refract(d, n, eta));
    }
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return (1.0, None);
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    (
        fresnel_of_cosines(cos_i, cos_t, eta),
        Some(refracted(d, n, cos_i, cos_t, eta)),
    )
}

/// Asks the CPU to bring the cache line holding `value` into the cache, without waiting for
/// it: a hint, with no effect on what the program computes. A no-op off x86-64.
#[inline(always)]
pub(crate) fn prefetch<T>(value: &T) {
    // PREFETCHT0 only hints the cache: it cannot fault, even on a bad address, and changes
    // nothing the program reads. On random rays through the bunny this gained 2 to 14 %
    // (median 8 %; commit fc131a9).
    #[cfg(all(target_arch = "x86_64", target_feature = "sse"))]
    safe_arch::prefetch_t0(value);
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse")))]
    let _ = value;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f32, b: f32, tol: f32) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn snell_law_holds_for_refracted_direction() {
        // 30 degrees from the normal, from air (1.0) into glass (1.5).
        let theta = 30f32.to_radians();
        let d = Vec3A::new(theta.sin(), -theta.cos(), 0.0);
        let n = Vec3A::Y;
        let t = refract(d, n, 1.0 / 1.5).unwrap();
        let sin_t = t.x;
        assert!(close(sin_t, theta.sin() / 1.5, 1e-6), "sin_t = {sin_t}");
        assert!(t.y < 0.0, "transmitted ray goes through the surface");
        assert!(close(t.length(), 1.0, 1e-6));
    }

    #[test]
    fn total_internal_reflection_past_the_critical_angle() {
        let eta = 2.42; // diamond to air
        let critical = (1.0f32 / eta).asin();
        let just_below = critical - 0.01;
        let just_above = critical + 0.01;
        let dir = |a: f32| Vec3A::new(a.sin(), -a.cos(), 0.0);
        assert!(refract(dir(just_below), Vec3A::Y, eta).is_some());
        assert!(refract(dir(just_above), Vec3A::Y, eta).is_none());
        assert_eq!(fresnel_dielectric(just_above.cos(), eta), 1.0);
        assert!(fresnel_dielectric(just_below.cos(), eta) < 1.0);
    }

    #[test]
    fn fresnel_matches_closed_forms() {
        // Normal incidence: ((n1 - n2) / (n1 + n2))^2, both ways.
        let f0 = ((1.0f32 - 1.5) / (1.0 + 1.5)).powi(2);
        assert!(close(fresnel_dielectric(1.0, 1.0 / 1.5), f0, 1e-6));
        assert!(close(fresnel_dielectric(1.0, 1.5), f0, 1e-6));
        let f0_diamond = ((2.42f32 - 1.0) / 3.42).powi(2);
        assert!(close(fresnel_dielectric(1.0, 1.0 / 2.42), f0_diamond, 1e-6));
        // Brewster's angle: p-polarised reflectance vanishes, so F = r_s^2 / 2.
        let n = 1.5f32;
        let brewster = n.atan();
        let (ci, ct) = (brewster.cos(), (brewster.sin() / n).asin().cos());
        let r_s = (ci - n * ct) / (ci + n * ct);
        assert!(close(
            fresnel_dielectric(ci, 1.0 / n),
            0.5 * r_s * r_s,
            1e-6
        ));
        // Grazing incidence reflects everything.
        assert!(close(fresnel_dielectric(0.0, 1.0 / 1.5), 1.0, 1e-6));
    }

    /// Fresnel and refraction at once give what each gives alone, to the bit: entering and
    /// leaving glass and diamond, at total internal reflection, and where a shading normal
    /// faces away from the ray (`-d . n` outside `[0, 1]`).
    #[test]
    fn fresnel_refract_is_both_to_the_bit() {
        let mut rng = Rng::new(29);
        let (mut through, mut total, mut away) = (0, 0, 0);
        for k in 0..20_000 {
            let unit = |rng: &mut Rng| {
                Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - 1.0
            };
            let n = unit(&mut rng).normalize_or(Vec3A::Z);
            let d = unit(&mut rng).normalize_or(-Vec3A::Z);
            // Mostly toward the surface, a tenth away from it.
            let d = if (d.dot(n) < 0.0) == (k % 10 != 0) {
                d
            } else {
                -d
            };
            let eta = [1.0 / 1.5, 1.5, 1.0 / 2.42, 2.42][k % 4];
            let cos_i = (-d).dot(n);
            let (f, r) = fresnel_refract(d, n, cos_i, eta);
            assert_eq!(f.to_bits(), fresnel_dielectric(cos_i, eta).to_bits());
            let alone = refract(d, n, eta);
            assert_eq!(
                r.map(|v| v.to_array().map(f32::to_bits)),
                alone.map(|v| v.to_array().map(f32::to_bits))
            );
            match (cos_i < 0.0, r) {
                (true, _) => away += 1,
                (false, Some(_)) => through += 1,
                (false, None) => total += 1,
            }
        }
        assert!(
            through > 5_000 && total > 1_000 && away > 1_000,
            "{through} {total} {away}"
        );
    }

    /// Reflected directions are not normalised: from unit vectors they come out unit to a
    /// few units in the last place, and stay so over the longest chain of bounces a scene
    /// may ask for.
    #[test]
    fn reflected_directions_stay_unit() {
        let mut rng = Rng::new(11);
        let unit = |rng: &mut Rng| loop {
            let v = crate::geometry::test_util::in_unit_cube(rng) * 2.0;
            if (0.01..1.0).contains(&v.length_squared()) {
                return v.normalize();
            }
        };
        let mut worst = 0.0f32;
        for _ in 0..100_000 {
            let (d, n) = (unit(&mut rng), unit(&mut rng));
            worst = worst.max((reflect(d, n).length() - 1.0).abs());
        }
        assert!(worst <= 8.0 * f32::EPSILON, "{worst}");
        // A ray reflected 256 times (the deepest tree a scene may ask for).
        let mut d = unit(&mut rng);
        for _ in 0..256 {
            d = reflect(d, unit(&mut rng));
        }
        assert!((d.length() - 1.0).abs() < 1e-5, "{}", d.length());
    }

    #[test]
    fn reflect_mirrors_about_the_normal() {
        let d = Vec3A::new(1.0, -1.0, 0.0).normalize();
        let r = reflect(d, Vec3A::Y);
        assert!(close(r.x, d.x, 1e-7) && close(r.y, -d.y, 1e-7));
    }
}
