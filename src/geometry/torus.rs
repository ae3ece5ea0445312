//! A torus: the points at distance `minor` from a circle of radius `major` about `center`,
//! in the plane perpendicular to `axis` (a ring torus: `minor < major`).
//!
//! A ray meets it where a quartic in `t` vanishes. The ray is first moved to where it enters
//! the torus's bounding sphere, so the quartic's coefficients are of the torus's size
//! whatever the ray's distance, and the quartic is solved in `f64` by isolating each root
//! between the critical points (math::poly), not by Ferrari's formula, whose cancellations
//! lose rays that graze the tube.

use super::{Intersect, Leaving, ShapeHit, Surface, in_range};
use crate::math::poly::roots_in;
use crate::math::{Aabb, Frame, Ray, Vec2, Vec3A};
use std::f32::consts::TAU;

/// A ring torus.
#[derive(Clone, Debug, PartialEq)]
pub struct Torus {
    /// Centre of the ring.
    pub center: Vec3A,
    /// Frame whose `w` is the unit axis.
    pub frame: Frame,
    /// Radius of the ring (centre to the middle of the tube), positive.
    pub major: f32,
    /// Radius of the tube, positive and less than `major`.
    pub minor: f32,
}

impl Torus {
    /// A torus; `axis` need not be unit length but must not be zero.
    pub fn new(center: Vec3A, axis: Vec3A, major: f32, minor: f32) -> Self {
        Torus {
            center,
            frame: Frame::from_axis(axis.normalize()),
            major,
            minor,
        }
    }
}

impl Intersect for Torus {
    /// The nearest hit with `0 < t < t_max`.
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let len = ray.dir.length() as f64;
        if len == 0.0 || !len.is_finite() {
            return None;
        }
        let o = self.frame.to_local(ray.origin - self.center);
        let d = self.frame.to_local(ray.dir);
        let (o, d) = (
            [o.x as f64, o.y as f64, o.z as f64],
            [d.x as f64 / len, d.y as f64 / len, d.z as f64 / len],
        );
        let (big, small) = (self.major as f64, self.minor as f64);
        // The bounding sphere: where the ray is inside it, in distance along the unit
        // direction.
        let bound = big + small;
        let od = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
        let oo = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
        let disc = od * od - (oo - bound * bound);
        if disc <= 0.0 {
            return None;
        }
        // The sphere touches the tube along the outer equator, so a ray that crosses there
        // enters (or leaves) both at once, and the rounding of the frame's change (in `f32`)
        // may put the entry point a hair inside the tube, where the quartic's first root is
        // lost. Solving from a little before the sphere to a little after it keeps that root
        // inside the interval; a root out there is the sphere's own rounding, no false hit.
        let margin = 1e-3 * bound;
        let (enter, exit) = (-od - disc.sqrt() - margin, -od + disc.sqrt() + margin);
        let limit = (t_max as f64 * len).min(exit);
        let start = enter.max(0.0);
        if start >= limit {
            return None;
        }
        // From the entry point p = o + start d: (|p + s d|^2 + R^2 - r^2)^2 = 4 R^2 ((p + s
        // d)_x^2 + (p + s d)_y^2), a quartic in s.
        let p = [
            o[0] + start * d[0],
            o[1] + start * d[1],
            o[2] + start * d[2],
        ];
        let n = p[0] * d[0] + p[1] * d[1] + p[2] * d[2];
        let k = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + big * big - small * small;
        let r2 = 4.0 * big * big;
        let dxy = d[0] * d[0] + d[1] * d[1];
        let pdxy = p[0] * d[0] + p[1] * d[1];
        let pxy = p[0] * p[0] + p[1] * p[1];
        let quartic = [
            1.0,
            4.0 * n,
            4.0 * n * n + 2.0 * k - r2 * dxy,
            4.0 * n * k - 2.0 * r2 * pdxy,
            k * k - r2 * pxy,
        ];
        roots_in(&quartic, 0.0, limit - start)
            .into_iter()
            .map(|s| ((start + s) / len) as f32)
            .find_map(|t| in_range(t, t_max, 0))
    }

    /// Normal (outward, from the nearest point of the ring), and uv: `u` the angle about the
    /// axis (as a cylinder's), `v` the angle about the tube, 0 on the outer equator and
    /// growing over the top (toward `+axis`) through the hole; the point is put back on the
    /// surface, so a hit found a little inside does not shadow itself.
    fn surface(&self, p: Vec3A, _hit: &ShapeHit, want_uv: bool) -> Surface {
        let l = self.frame.to_local(p - self.center);
        let rho = (l.x * l.x + l.y * l.y).sqrt();
        let (cx, cy) = if rho > 0.0 {
            (l.x / rho, l.y / rho)
        } else {
            (1.0, 0.0)
        };
        let ring = Vec3A::new(cx * self.major, cy * self.major, 0.0);
        let n = (l - ring).normalize_or(Vec3A::new(cx, cy, 0.0));
        let uv = if want_uv {
            let tube = n.z.atan2(n.x * cx + n.y * cy);
            Vec2::new(super::cylinder::angle_u(l), tube.rem_euclid(TAU) / TAU)
        } else {
            Vec2::ZERO
        };
        Surface {
            point: self.center + self.frame.to_world(ring + n * self.minor),
            normal: self.frame.to_world(n),
            uv,
        }
    }

    /// True when `p` is strictly inside the tube.
    fn contains(&self, p: Vec3A) -> bool {
        let l = self.frame.to_local(p - self.center);
        let rho = (l.x * l.x + l.y * l.y).sqrt();
        (rho - self.major).powi(2) + l.z * l.z < self.minor * self.minor
    }

    /// Bounds: the ring's, grown by the tube's radius.
    fn bounds(&self) -> Option<Aabb> {
        let b = super::cylinder::disk_bounds(self.center, self.frame.w, self.major);
        Some(Aabb::new(b.min - self.minor, b.max + self.minor))
    }

    fn leaving(&self) -> Leaving {
        Leaving::MayReturn
    }

    fn kind(&self) -> &'static str {
        "torus"
    }
}

#[cfg(test)]
mod tests {
    use super::super::Shape;
    use super::super::test_util::*;
    use super::*;
    use proptest::prelude::*;

    /// Major 2, minor 0.5, about +y at the origin.
    fn torus() -> Shape {
        Shape::Torus(Torus::new(Vec3A::ZERO, Vec3A::Y, 2.0, 0.5))
    }

    /// Along a diameter in the ring's plane the ray crosses the tube twice: in at 2.5 from
    /// the centre, out at 1.5, in at -1.5, out at -2.5; each hit's normal points away from
    /// the ring's nearest point.
    #[test]
    fn a_diameter_crosses_the_tube_twice() {
        let s = torus();
        let (t, surf) = hit(&s, [5.0, 0.0, 0.0], [-1.0, 0.0, 0.0]).unwrap();
        assert!((t - 2.5).abs() < 1e-5, "{t}");
        assert_vec_close(surf.normal, Vec3A::X, 1e-5);
        // From inside the tube: out at x = 1.5, facing the hole.
        let (t, surf) = hit(&s, [2.0, 0.0, 0.0], [-1.0, 0.0, 0.0]).unwrap();
        assert!((t - 0.5).abs() < 1e-5, "{t}");
        assert_vec_close(surf.normal, -Vec3A::X, 1e-5);
        // From the hole: into the far side at x = -1.5.
        let (t, surf) = hit(&s, [0.0, 0.0, 0.0], [-1.0, 0.0, 0.0]).unwrap();
        assert!((t - 1.5).abs() < 1e-5, "{t}");
        assert_vec_close(surf.normal, Vec3A::X, 1e-5);
        // The top of the tube, from above: normal +y.
        let (t, surf) = hit(&s, [0.0, 3.0, 2.0], [0.0, -1.0, 0.0]).unwrap();
        assert!((t - 2.5).abs() < 1e-5, "{t}");
        assert_vec_close(surf.normal, Vec3A::Y, 1e-5);
    }

    /// Down the axis a ray goes through the hole and meets nothing; just inside and outside
    /// the top of the tube, rays along it touch it or pass over it.
    #[test]
    fn the_axis_and_grazing_rays() {
        let s = torus();
        assert!(hit(&s, [0.0, 10.0, 0.0], [0.0, -1.0, 0.0]).is_none());
        assert!(hit(&s, [0.0, -10.0, 0.0], [0.0, 1.0, 0.0]).is_none());
        // The plane y = 0.5 touches the tube's top along the ring: a ray a hair below it
        // meets the tube near x = -2, one a hair above misses.
        let (t, _) = hit(&s, [-10.0, 0.499, 0.0], [1.0, 0.0, 0.0]).unwrap();
        assert!((t - 8.0).abs() < 0.1, "{t}");
        assert!(hit(&s, [-10.0, 0.501, 0.0], [1.0, 0.0, 0.0]).is_none());
        // Tangent to the outer equator: a hair inside meets it, a hair outside misses.
        assert!(hit(&s, [-10.0, 0.0, 2.499], [1.0, 0.0, 0.0]).is_some());
        assert!(hit(&s, [-10.0, 0.0, 2.501], [1.0, 0.0, 0.0]).is_none());
        // Far away, the same hit as near.
        let (t, _) = hit(&s, [1e5, 0.0, 0.0], [-1.0, 0.0, 0.0]).unwrap();
        assert!((t - (1e5 - 2.5)).abs() < 0.02, "{t}");
        // Not beyond t_max.
        let ray = Ray::new(Vec3A::new(5.0, 0.0, 0.0), -Vec3A::X);
        assert!(s.intersect(&ray, 2.4).is_none());
        assert!(s.intersect(&ray, 2.6).is_some());
    }

    #[test]
    fn inside_bounds_and_uv() {
        let t = Torus::new(Vec3A::new(1.0, 2.0, 3.0), Vec3A::Z, 2.0, 0.5);
        assert!(t.contains(Vec3A::new(3.0, 2.0, 3.0)));
        assert!(!t.contains(Vec3A::new(1.0, 2.0, 3.0)));
        assert!(!t.contains(Vec3A::new(3.6, 2.0, 3.0)));
        let b = t.bounds().unwrap();
        assert_vec_close(b.min, Vec3A::new(-1.5, -0.5, 2.5), 1e-5);
        assert_vec_close(b.max, Vec3A::new(3.5, 4.5, 3.5), 1e-5);
        // About +y: u as a cylinder's (0.5 toward +z, 0.75 toward +x); v 0 on the outer
        // equator, a quarter at the top, a half at the inner equator.
        let s = Torus::new(Vec3A::ZERO, Vec3A::Y, 2.0, 0.5);
        let uv = |p: [f32; 3]| s.surface(Vec3A::from(p), &on_part(0), true).uv;
        assert!((uv([0.0, 0.0, 2.5]) - Vec2::new(0.5, 0.0)).length() < 1e-5);
        assert!((uv([2.5, 0.0, 0.0]) - Vec2::new(0.75, 0.0)).length() < 1e-5);
        assert!((uv([0.0, 0.5, 2.0]) - Vec2::new(0.5, 0.25)).length() < 1e-5);
        assert!((uv([0.0, 0.0, 1.5]) - Vec2::new(0.5, 0.5)).length() < 1e-5);
    }

    /// The bounding sphere touches the tube along the outer equator: a ray from outside the
    /// sphere toward a point of that circle enters both there, and the hit is that point.
    /// Rounding once put the entry a hair inside the tube, and the solver found only the
    /// far side (from (-1.341, -0.125, -4.065) toward (0.894, 1.289, 0.608), 3.211 for
    /// 2.188).
    #[test]
    fn a_ray_entering_where_the_bounding_sphere_touches_the_tube() {
        let t = Torus::new(
            Vec3A::new(0.1, -0.2, 0.3),
            Vec3A::new(0.3, 1.0, 0.2),
            2.0,
            0.6,
        );
        let ray = Ray::new(
            Vec3A::new(-1.341, -0.125, -4.065),
            (Vec3A::new(0.894, 1.289, 0.608) - Vec3A::new(-1.341, -0.125, -4.065)).normalize(),
        );
        let got = t.intersect(&ray, f32::INFINITY).unwrap().t;
        assert!((got - 2.1882).abs() < 1e-3, "{got}");
        let mut checked = 0;
        for i in 0..64 {
            // A point of the outer equator, and an origin outside the sphere on its side.
            let a = i as f32 * 0.7;
            let local = Vec3A::new(a.cos(), a.sin(), 0.0);
            let q = t.center + t.frame.to_world(local * (t.major + t.minor));
            // Tilted from the normal there by up to about 50 degrees, so the ray crosses.
            let n = t.frame.to_world(local);
            let tilt = Vec3A::new((a * 3.1).sin(), (a * 1.7).cos(), (a * 2.3).sin()) * 0.7;
            let out = (n + tilt - n * n.dot(tilt)).normalize();
            let o = q + out * (3.0 + (i % 5) as f32);
            let hit = t.intersect(&Ray::new(o, (q - o).normalize()), f32::INFINITY);
            let want = (q - o).length();
            let got = hit.map(|h| h.t);
            assert!(
                got.is_some_and(|g| (g - want).abs() < 1e-3),
                "{i}: {got:?} vs {want}"
            );
            checked += 1;
        }
        assert_eq!(checked, 64);
    }

    /// The implicit function's sign change found by marching in tiny steps and bisecting.
    fn brute_force(t: &Torus, ray: &Ray) -> Option<f32> {
        let f = |s: f64| {
            let p = ray.origin.as_dvec3() + ray.dir.as_dvec3() * s;
            let l = t.frame.to_local(p.as_vec3a() - t.center).as_dvec3();
            let (big, small) = (t.major as f64, t.minor as f64);
            let rho = (l.x * l.x + l.y * l.y).sqrt();
            (rho - big).powi(2) + l.z * l.z - small * small
        };
        let (steps, far) = (40_000, 20.0);
        let mut prev = f(0.0);
        for i in 1..=steps {
            let s = far * i as f64 / steps as f64;
            let v = f(s);
            if v.signum() != prev.signum() {
                let (mut a, mut b) = (far * (i - 1) as f64 / steps as f64, s);
                for _ in 0..60 {
                    let m = 0.5 * (a + b);
                    if f(m).signum() == prev.signum() {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                return Some(a as f32);
            }
            prev = v;
        }
        None
    }

    /// Random rays from around a tilted torus: the hit is where the implicit function
    /// changes sign first (or there is none), and the hit point is on the surface. The
    /// runner rather than `proptest!`, so that after the last case the test can count the
    /// rays that hit: a miss of both the solver and the marching checks nothing.
    #[test]
    fn hits_agree_with_brute_force() {
        use proptest::test_runner::{Config, RngSeed, TestRunner};
        use std::cell::Cell;
        let (cases, hits) = (Cell::new(0u32), Cell::new(0u32));
        // The same rays on every run, so that CI's verdict does not depend on the draw.
        let mut runner = TestRunner::new(Config {
            rng_seed: RngSeed::Fixed(0x7025),
            failure_persistence: None,
            ..Config::default()
        });
        let result = runner.run(
            &(
                prop::array::uniform3(-6.0f32..6.0),
                prop::array::uniform3(-2.5f32..2.5),
            ),
            |(o, target)| {
                let t = Torus::new(
                    Vec3A::new(0.1, -0.2, 0.3),
                    Vec3A::new(0.3, 1.0, 0.2),
                    2.0,
                    0.6,
                );
                let o = Vec3A::from(o);
                let d = (Vec3A::from(target) - o).normalize_or_zero();
                prop_assume!(d != Vec3A::ZERO && !t.contains(o));
                cases.set(cases.get() + 1);
                let ray = Ray::new(o, d);
                let got = t.intersect(&ray, f32::INFINITY).map(|h| h.t);
                let want = brute_force(&t, &ray);
                match (got, want) {
                    (Some(g), Some(w)) => prop_assert!((g - w).abs() < 2e-3, "{g} vs {w}"),
                    // A graze the marching steps step over, or a touch the solver misses: the
                    // ray passes within a hair of the surface either way.
                    (Some(g), None) | (None, Some(g)) => {
                        let s = t.surface(ray.at(g), &on_part(0), false);
                        prop_assert!((s.point - ray.at(g)).length() < 2e-3);
                        prop_assert!(
                            s.normal.dot(d).abs() < 0.05,
                            "not a graze: {got:?} {want:?}"
                        );
                    }
                    (None, None) => {}
                }
                if let Some(g) = got {
                    let s = t.surface(ray.at(g), &on_part(0), false);
                    prop_assert!((s.point - ray.at(g)).length() < 1e-3);
                    hits.set(hits.get() + 1);
                }
                Ok(())
            },
        );
        if let Err(e) = result {
            panic!("{e}\n{runner}");
        }
        // Every case the runner asked for.
        let (cases, hits) = (cases.get(), hits.get());
        assert!(cases >= runner.config().cases, "{cases} cases");
        // A target inside the tube (the tube is a ninth of the targets' cube) is always
        // reached, and rays toward the others often cross the tube on the way: about 45 %
        // of the rays hit. A fifth of them leaves a margin no seed comes near.
        assert!(hits >= cases / 5, "{hits} of {cases} rays hit");
    }
}
