//! Ray differentials: how a ray changes from one pixel to the next, so that a texture can be
//! read over the patch of surface a pixel sees instead of at a point (Igehy 1999, as pbrt
//! carries them).

use super::{Ray, Vec2, Vec3A, refract};

/// The rays through the neighbouring pixel to the right (`x`) and below (`y`), as offsets
/// from a ray's origin and direction. Camera rays carry them, scaled down for the samples a
/// pixel takes; a mirror or glass keeps them; any other bounce ends them.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Differentials {
    /// Origin of the ray one pixel right, minus the ray's origin.
    pub dx_origin: Vec3A,
    /// Direction of the ray one pixel right, minus the ray's direction.
    pub dx_dir: Vec3A,
    /// Origin of the ray one pixel down, minus the ray's origin.
    pub dy_origin: Vec3A,
    /// Direction of the ray one pixel down, minus the ray's direction.
    pub dy_dir: Vec3A,
}

/// How far apart (in pixels) the neighbours of a camera ray are taken at `spp` samples per
/// pixel: the samples of a pixel lie about `1 / sqrt(spp)` apart, but no closer than an
/// eighth, so that a high sample count still filters a little (pbrt-v4's rule).
pub fn camera_scale(spp: u32) -> f32 {
    (1.0 / (spp.max(1) as f32).sqrt()).max(0.125)
}

/// The change of texture coordinates over a step, from the change `ahead` (stepping
/// forward) and `behind` (stepping back): of each coordinate the smaller, so that a step
/// across a seam, where `u` jumps from 1 to 0, does not count as a jump.
pub fn seamless(ahead: Vec2, behind: Vec2) -> Vec2 {
    let pick = |a: f32, b: f32| if a.abs() <= b.abs() { a } else { b };
    Vec2::new(pick(ahead.x, behind.x), pick(ahead.y, behind.y))
}

/// Where the two neighbouring rays meet the plane through `p` with normal `n`, as offsets
/// from `p`: the patch of surface between pixels. `None` where a neighbour runs along the
/// plane (or the differentials are not finite), when no patch can be told.
pub fn surface_offsets(ray: &Ray, d: &Differentials, p: Vec3A, n: Vec3A) -> Option<[Vec3A; 2]> {
    let at = |o: Vec3A, dir: Vec3A| {
        let denom = n.dot(dir);
        if denom.abs() < 1e-8 {
            return None;
        }
        let t = n.dot(p - o) / denom;
        let dp = o + dir * t - p;
        dp.is_finite().then_some(dp)
    };
    Some([
        at(ray.origin + d.dx_origin, ray.dir + d.dx_dir)?,
        at(ray.origin + d.dy_origin, ray.dir + d.dy_dir)?,
    ])
}

impl Differentials {
    /// The differentials with each neighbour brought `s` of the way toward the ray.
    pub fn scaled(&self, s: f32) -> Self {
        Differentials {
            dx_origin: self.dx_origin * s,
            dx_dir: self.dx_dir * s,
            dy_origin: self.dy_origin * s,
            dy_dir: self.dy_dir * s,
        }
    }

    /// The differentials of the ray a perfect mirror sends out, where `ray` met it at a
    /// surface whose unit normal is `n` (either side), with the neighbours meeting it
    /// `dp` away, where the normal is `n + dn`: each neighbour mirrored about its own normal,
    /// to first order (pbrt's), so that a curved mirror spreads them further apart than they
    /// came. With `wo = -d`, `wi = -wo + 2 (wo . n) n` changes by
    /// `-dwo + 2 ((wo . n) dn + d(wo . n) n)`.
    pub fn reflected(&self, ray: &Ray, dp: [Vec3A; 2], dn: [Vec3A; 2], n: Vec3A) -> Self {
        let wo = -ray.dir;
        let wo_n = wo.dot(n);
        let one = |ddir: Vec3A, dn: Vec3A| {
            let dwo = -ddir;
            let d_wo_n = dwo.dot(n) + wo.dot(dn);
            -dwo + 2.0 * (wo_n * dn + d_wo_n * n)
        };
        Differentials {
            dx_origin: dp[0],
            dx_dir: one(self.dx_dir, dn[0]),
            dy_origin: dp[1],
            dy_dir: one(self.dy_dir, dn[1]),
        }
    }

    /// As [`Differentials::reflected`] for the ray refracted into direction `out` with
    /// relative index `eta` (incident over transmitted), `n` facing the incoming ray. A
    /// neighbour that would be totally reflected keeps the ray's direction.
    pub fn refracted(
        &self,
        ray: &Ray,
        out: Vec3A,
        dp: [Vec3A; 2],
        dn: [Vec3A; 2],
        n: Vec3A,
        eta: f32,
    ) -> Self {
        let one = |ddir: Vec3A, dn: Vec3A| {
            let nn = (n + dn).normalize_or(n);
            refract((ray.dir + ddir).normalize_or(ray.dir), nn, eta)
                .map_or(Vec3A::ZERO, |d| d - out)
        };
        Differentials {
            dx_origin: dp[0],
            dx_dir: one(self.dx_dir, dn[0]),
            dy_origin: dp[1],
            dy_dir: one(self.dy_dir, dn[1]),
        }
    }

    /// The differentials of a ray that goes on in the same direction from `dp` away (a thin
    /// sheet of glass, which does not bend light).
    pub fn passed(&self, dp: [Vec3A; 2]) -> Self {
        Differentials {
            dx_origin: dp[0],
            dy_origin: dp[1],
            ..*self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_on_a_plane_grow_with_distance_and_slant() {
        // Parallel neighbours 0.1 apart meet a plane facing them 0.1 apart; a pinhole's
        // neighbours, 0.001 apart in direction, meet it 0.001 x distance apart.
        let ray = Ray::new(Vec3A::ZERO, -Vec3A::Z);
        let d = Differentials {
            dx_origin: Vec3A::X * 0.1,
            dy_origin: Vec3A::Y * 0.1,
            ..Default::default()
        };
        let p = Vec3A::new(0.0, 0.0, -5.0);
        let [dx, dy] = surface_offsets(&ray, &d, p, Vec3A::Z).unwrap();
        assert!((dx - Vec3A::X * 0.1).length() < 1e-6 && (dy - Vec3A::Y * 0.1).length() < 1e-6);
        let d = Differentials {
            dx_dir: Vec3A::X * 0.001,
            dy_dir: Vec3A::Y * 0.001,
            ..Default::default()
        };
        let [dx, _] = surface_offsets(&ray, &d, p, Vec3A::Z).unwrap();
        assert!((dx.x - 0.005).abs() < 1e-7, "{dx}");
        // Tilted 60 degrees about y: the patch is twice as long across x.
        let n = Vec3A::new(60f32.to_radians().sin(), 0.0, 60f32.to_radians().cos());
        let [dx, dy] = surface_offsets(&ray, &d, p, n).unwrap();
        assert!((dx.length() - 0.01).abs() < 1e-4, "{dx}");
        assert!((dy.length() - 0.005).abs() < 1e-5, "{dy}");
        // Edge-on: no patch.
        assert!(surface_offsets(&ray, &d, p, Vec3A::X).is_none());
    }

    #[test]
    fn a_flat_mirror_keeps_the_spread_and_a_curved_one_widens_it() {
        let ray = Ray::new(Vec3A::ZERO, -Vec3A::Z);
        let d = Differentials {
            dx_dir: Vec3A::X * 0.001,
            dy_dir: Vec3A::Y * 0.001,
            ..Default::default()
        };
        let p = Vec3A::new(0.0, 0.0, -5.0);
        let dp = surface_offsets(&ray, &d, p, Vec3A::Z).unwrap();
        let flat = d.reflected(&ray, dp, [Vec3A::ZERO; 2], Vec3A::Z);
        assert!((flat.dx_dir.length() - 0.001).abs() < 1e-5, "{flat:?}");
        // A convex mirror of radius 1 there: the normal turns by dp / radius.
        let curved = d.reflected(&ray, dp, dp, Vec3A::Z);
        // Reflection doubles the normal's turn: 0.001 + 2 x 0.005.
        assert!((curved.dx_dir.length() - 0.011).abs() < 2e-4, "{curved:?}");
        assert_eq!(curved.dx_origin, dp[0]);
    }

    #[test]
    fn refraction_bends_the_neighbours_as_it_bends_the_ray() {
        let ray = Ray::new(Vec3A::ZERO, -Vec3A::Z);
        let d = Differentials {
            dx_dir: Vec3A::X * 0.001,
            ..Default::default()
        };
        let out = refract(ray.dir, Vec3A::Z, 1.0 / 1.5).unwrap();
        let r = d.refracted(
            &ray,
            out,
            [Vec3A::ZERO; 2],
            [Vec3A::ZERO; 2],
            Vec3A::Z,
            1.0 / 1.5,
        );
        // Near normal incidence Snell's law is linear: angles shrink by eta.
        assert!((r.dx_dir.x - 0.001 / 1.5).abs() < 1e-6, "{r:?}");
        assert_eq!(r.dy_dir, Vec3A::ZERO);
    }

    #[test]
    fn camera_scale_follows_the_sample_spacing() {
        assert_eq!(camera_scale(1), 1.0);
        assert_eq!(camera_scale(16), 0.25);
        assert_eq!(camera_scale(4096), 0.125);
        assert_eq!(camera_scale(0), 1.0);
    }
}
