//! A parallelogram (a rectangle with perpendicular edges): its hits, one ray at a time and
//! eight at once, its uv, and its points sampled by area for area lights.

use super::{Intersect, Leaving, ShapeHit, Surface, in_range};
use crate::math::{Aabb, LANES, Ray, RayLanes, Vec2, Vec3A};

/// A flat parallelogram: `corner + a * edge_u + b * edge_v` for `a, b` in `[0, 1]`. With
/// perpendicular edges it is a rectangle. Its front side is `edge_u x edge_v`.
#[derive(Clone, Debug, PartialEq)]
pub struct Rect {
    corner: Vec3A,
    edge_u: Vec3A,
    edge_v: Vec3A,
    normal: Vec3A,
    /// `n / (n . n)` with `n = edge_u x edge_v`, to solve for the edge coordinates.
    w: Vec3A,
}

impl Rect {
    /// From a corner and two edges; `None` when the edges are parallel or zero.
    pub fn new(corner: Vec3A, edge_u: Vec3A, edge_v: Vec3A) -> Option<Self> {
        let n = edge_u.cross(edge_v);
        let nn = n.length_squared();
        if nn == 0.0 || !nn.is_finite() {
            return None;
        }
        Some(Rect {
            corner,
            edge_u,
            edge_v,
            normal: n / nn.sqrt(),
            w: n / nn,
        })
    }

    /// [`Rect::intersect`] of every ray of a packet at once, each below its own `t_max`: the
    /// distances of the hits, infinite for a miss. The same distances to the bit, as for
    /// [`super::Sphere::intersect_lanes`]; the cross products as glam computes them (fused
    /// where the build has FMA).
    #[inline]
    pub(crate) fn intersect_lanes(&self, rays: &RayLanes, t_max: &[f32; LANES]) -> [f32; LANES] {
        let (n, c, w) = (self.normal, self.corner, self.w);
        let (eu, ev) = (self.edge_u, self.edge_v);
        let mut out = [f32::INFINITY; LANES];
        for l in 0..LANES {
            let (ox, oy, oz) = (rays.origin[0][l], rays.origin[1][l], rays.origin[2][l]);
            let (dx, dy, dz) = (rays.dir[0][l], rays.dir[1][l], rays.dir[2][l]);
            let denom = dx * n.x + dy * n.y + dz * n.z;
            let t = ((c.x - ox) * n.x + (c.y - oy) * n.y + (c.z - oz) * n.z) / denom;
            let rel = [ox + dx * t - c.x, oy + dy * t - c.y, oz + dz * t - c.z];
            let p = cross_as_glam(rel, [ev.x, ev.y, ev.z]);
            let q = cross_as_glam([eu.x, eu.y, eu.z], rel);
            let a = w.x * p[0] + w.y * p[1] + w.z * p[2];
            let b = w.x * q[0] + w.y * q[1] + w.z * q[2];
            let hit = denom != 0.0
                && t > 0.0
                && t < t_max[l]
                && (0.0..=1.0).contains(&a)
                && (0.0..=1.0).contains(&b);
            out[l] = if hit { t } else { f32::INFINITY };
        }
        out
    }

    fn coords(&self, p: Vec3A) -> (f32, f32) {
        let rel = p - self.corner;
        (
            self.w.dot(rel.cross(self.edge_v)),
            self.w.dot(self.edge_u.cross(rel)),
        )
    }
}

impl Intersect for Rect {
    /// Hit in `(0, t_max)` inside the parallelogram (edges included).
    #[inline]
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let denom = ray.dir.dot(self.normal);
        if denom == 0.0 {
            return None;
        }
        let t = (self.corner - ray.origin).dot(self.normal) / denom;
        let hit = in_range(t, t_max, 0)?;
        let (a, b) = self.coords(ray.at(t));
        ((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)).then_some(hit)
    }

    /// Normal and uv: `u` from 0 to 1 along `edge_u`, `v` from 1 at the corner to 0 at the
    /// far end of `edge_v`. Seen from the front, with `edge_u` to the right and `edge_v` up,
    /// an image appears upright with the corner at its bottom-left.
    fn surface(&self, p: Vec3A, _hit: &ShapeHit, _want_uv: bool) -> Surface {
        let (a, b) = self.coords(p);
        Surface {
            point: self.corner + a * self.edge_u + b * self.edge_v,
            normal: self.normal,
            uv: Vec2::new(a, 1.0 - b),
        }
    }

    /// The box around the parallelogram's four corners, object space.
    fn bounds(&self) -> Option<Aabb> {
        let mut b = Aabb::new(self.corner, self.corner + self.edge_u);
        b.grow(self.corner + self.edge_v);
        b.grow(self.corner + self.edge_u + self.edge_v);
        Some(b)
    }

    fn leaving(&self) -> Leaving {
        Leaving::EitherSide
    }

    fn kind(&self) -> &'static str {
        "rectangle"
    }
}

/// `a x b` with the rounding of glam's `Vec3A::cross`: each component is a product less
/// another, the subtraction fused with the second product where the build has FMA (glam
/// uses a fused negated multiply-add there), both products rounded elsewhere.
#[inline(always)]
fn cross_as_glam(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    #[cfg(target_feature = "fma")]
    let f = |p: f32, q: f32, r: f32, s: f32| (-r).mul_add(s, p * q);
    #[cfg(not(target_feature = "fma"))]
    let f = |p: f32, q: f32, r: f32, s: f32| p * q - r * s;
    [
        f(a[1], b[2], b[1], a[2]),
        f(a[2], b[0], b[2], a[0]),
        f(a[0], b[1], b[0], a[1]),
    ]
}

impl Rect {
    /// The corner and the two edges it was made from.
    pub fn corner_and_edges(&self) -> (Vec3A, Vec3A, Vec3A) {
        (self.corner, self.edge_u, self.edge_v)
    }

    /// The parallelogram's area.
    pub fn area(&self) -> f32 {
        self.edge_u.cross(self.edge_v).length()
    }

    /// A point on the parallelogram, every one equally likely (density `1 / area`).
    pub fn sample_area(&self, u: Vec2) -> super::SurfaceSample {
        super::SurfaceSample {
            point: self.corner + u.x * self.edge_u + u.y * self.edge_v,
            normal: self.normal,
            pdf: 1.0 / self.area(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::Shape;
    use super::super::test_util::*;
    use super::*;

    fn floor() -> Shape {
        Shape::Rect(
            Rect::new(
                Vec3A::new(-25.0, -15.0, -40.0),
                Vec3A::new(50.0, 0.0, 0.0),
                Vec3A::new(0.0, 0.0, -160.0),
            )
            .unwrap(),
        )
    }

    /// The packet test gives what the test of one ray gives, to the bit, also on rays aimed
    /// exactly at the edges and corners, where the rounding of the cross products decides.
    #[test]
    fn packets_match_single_rays() {
        use crate::math::Rng;
        let rects = [
            Rect::new(
                Vec3A::new(-25.0, -15.0, -40.0),
                Vec3A::new(50.0, 0.0, 0.0),
                Vec3A::new(0.0, 0.0, -160.0),
            ),
            Rect::new(
                Vec3A::new(0.3, 1.7, -2.9),
                Vec3A::new(1.1, 0.4, 0.7),
                Vec3A::new(-0.2, 0.9, 0.3),
            ),
        ];
        for r in rects.map(Option::unwrap) {
            let (corner, eu, ev) = (r.corner, r.edge_u, r.edge_v);
            let on_rect = |rng: &mut Rng| {
                let mut pick = || match (rng.next_f32() * 6.0) as u32 {
                    0 => 0.0,
                    1 => 1.0,
                    _ => rng.next_f32() * 1.2 - 0.1,
                };
                let (a, b) = (pick(), pick());
                corner + eu * a + ev * b
            };
            let size = eu.length() + ev.length();
            let origin = |rng: &mut Rng| corner + in_unit_cube(rng) * (size * 3.0);
            let hits = assert_lanes_match(
                |ray, t_max| r.intersect(ray, t_max),
                |rays, t_max| r.intersect_lanes(rays, t_max),
                origin,
                on_rect,
            );
            assert!(hits > 10_000, "{hits} hits");
        }
    }

    #[test]
    fn seed_floor_faces_up_and_maps_uv() {
        let (t, s) = hit(&floor(), [0.0, 0.0, -120.0], [0.0, -1.0, 0.0]).unwrap();
        assert!((t - 15.0).abs() < 1e-5);
        assert_vec_close(s.normal, Vec3A::Y, 1e-6);
        assert!((s.uv - Vec2::new(0.5, 0.5)).length() < 1e-5);
    }

    #[test]
    fn outside_edges_and_parallel_rays_miss() {
        assert!(hit(&floor(), [26.0, 0.0, -120.0], [0.0, -1.0, 0.0]).is_none());
        assert!(hit(&floor(), [0.0, 0.0, -30.0], [0.0, -1.0, 0.0]).is_none());
        assert!(hit(&floor(), [0.0, -15.0, 0.0], [0.0, 0.0, -1.0]).is_none());
        assert!(Rect::new(Vec3A::ZERO, Vec3A::X, Vec3A::X * 2.0).is_none());
    }
}
