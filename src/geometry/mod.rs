//! Shapes, each in its own object space: one file per shape implementing [`Intersect`],
//! forwarded to by the closed set [`Shape`]. Every shape returns the nearest hit in `(0, t_max)`, so a ray that
//! starts inside a solid finds its far side, and accepts rays whose direction is not unit
//! length (rays carried in by a transform).

mod cone;
mod csg;
mod cuboid;
mod cylinder;
mod disk;
pub mod mesh;
mod object;
mod plane;
mod rect;
mod sphere;
mod torus;
mod triangle;

pub use cone::Cone;
pub use csg::{Csg, CsgLeaf, CsgNode, CsgOp, MAX_CSG_LEAVES, MAX_CSG_MESH_TRIANGLES};
pub use cuboid::Cuboid;
pub use cylinder::Cylinder;
pub(crate) use cylinder::angle_u;
pub use disk::Disk;
pub use mesh::Mesh;
pub use object::Object;
pub use plane::Plane;
pub use rect::Rect;
pub use sphere::Sphere;
pub use torus::Torus;
pub use triangle::Triangle;

#[cfg(test)]
mod sample_tests;

/// A point sampled on a shape (an area light's), with the density it was chosen with:
/// per unit area, or per unit solid angle where the method says so.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceSample {
    /// The point, on the surface.
    pub point: Vec3A,
    /// The surface's unit normal there (its front side).
    pub normal: Vec3A,
    /// The density.
    pub pdf: f32,
}

/// A density per unit area at `point` (normal `normal`) as a density per unit solid angle
/// seen from `from`: `pdf d^2 / |cos theta|`; `None` where it is not a finite, positive
/// density (the surface seen edge-on, `from` on it).
pub fn area_to_solid_angle(pdf: f32, from: Vec3A, point: Vec3A, normal: Vec3A) -> Option<f32> {
    let v = area_to_solid_angle_across(pdf, point - from, normal).0;
    (v.is_finite() && v > 0.0).then_some(v)
}

/// [`area_to_solid_angle`] seen across `d` (from the point that sees to the point on the
/// surface), with the distance: `pdf |d|^2 (|d| / |d . normal|)`, where `|d . normal| / |d|`
/// is the cosine. Infinite or NaN where `d` is zero or runs along the surface. The square
/// root and the dot product are worked out side by side, then one division: a light sample
/// waited on a square root, a division and another division one after another. (`|d| /
/// |d . normal|` is at least 1, so the density overflows no sooner than `pdf d^2 / |cos|`.)
#[inline]
pub fn area_to_solid_angle_across(pdf: f32, d: Vec3A, normal: Vec3A) -> (f32, f32) {
    let d2 = d.length_squared();
    let distance = d2.sqrt();
    (pdf * d2 * (distance / d.dot(normal).abs()), distance)
}

use crate::math::differential::seamless;
use crate::math::{Aabb, Ray, Vec2, Vec3A};

/// The nearest intersection found by a shape: the ray parameter and which part of the
/// shape was hit (side or cap, box face), so the surface details can be worked out later,
/// once, for the closest hit only.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeHit {
    /// Ray parameter of the hit.
    pub t: f32,
    /// Shape-specific part index (0 for shapes with one part).
    pub part: u8,
    /// Index of the triangle hit, for meshes (0 otherwise).
    pub prim: u32,
    /// Barycentric weights of the second and third corners, for triangles (zero otherwise).
    pub bary: Vec2,
}

/// Surface details at a hit point, in object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// The hit point, projected back onto the surface to remove rounding error.
    pub point: Vec3A,
    /// Unit outward normal (for open surfaces, the side the shape defines as front).
    pub normal: Vec3A,
    /// The shape's own texture coordinates (see docs/scene-format.md for each shape).
    pub uv: Vec2,
}

/// Which rays leaving a shape's surface can never meet the shape again, so that a query for
/// such a ray may leave the shape out (see [`Shape::leaving`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Leaving {
    /// A flat shape (plane, rectangle, disk, triangle): a ray leaving it on either side stays
    /// off its plane.
    EitherSide,
    /// Part of the boundary of a convex solid (sphere, box, cylinder or cone, open or capped):
    /// a ray leaving on the side the outward normal points to stays outside the supporting
    /// half-space there, which holds the whole solid.
    Outside,
    /// A shape a ray may meet again from anywhere on it (a mesh).
    MayReturn,
}

crate::closed_set! {
    /// What every shape gives, in its own object space. Implemented by each shape in its
    /// file; [`Shape`] forwards to them.
    pub trait Intersect {
        /// Nearest hit with `0 < t < t_max`.
        fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit>;

        /// Whether anything is hit with `0 < t < t_max` (a mesh stops at the first triangle).
        fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
            self.intersect(ray, t_max).is_some()
        }

        /// Surface details for `hit`, at object-space point `p`. The uv costs trigonometry on
        /// round shapes, so it is only worked out when `want_uv` is set (it is zero
        /// otherwise).
        fn surface(&self, p: Vec3A, hit: &ShapeHit, want_uv: bool) -> Surface;

        /// How the shape's uv changes from the hit `hit` at `p` to the point `dp` away on its
        /// tangent plane (the patch a pixel sees; zero unless `want_uv`), and the unit normal
        /// there (the shading normal, for meshes). By default the uv is differenced forward
        /// and backward ([`differenced`]).
        fn differential(&self, p: Vec3A, hit: &ShapeHit, dp: Vec3A, want_uv: bool) -> (Vec2, Vec3A) {
            differenced(self, p, hit, dp, want_uv)
        }

        /// Object-space bounds; `None` for unbounded shapes (planes).
        fn bounds(&self) -> Option<Aabb>;

        /// True when the object-space point lies strictly inside a closed solid. Open and
        /// flat shapes contain nothing.
        fn contains(&self, p: Vec3A) -> bool {
            false
        }

        /// Which rays leaving this shape's surface cannot meet it again. An affine transform
        /// keeps flat shapes flat and convex ones convex, and the outward normal outward, so
        /// this holds of a placed object too.
        fn leaving(&self) -> Leaving;

        /// Short lower-case name of the shape, as written in scene files.
        fn kind(&self) -> &'static str;
    }

    /// Every kind of shape snell can intersect: one of a closed set, one file per shape.
    #[derive(Clone, Debug, PartialEq)]
    pub enum Shape {
        /// A sphere.
        Sphere(Sphere),
        /// An infinite plane.
        Plane(Plane),
        /// A parallelogram (rectangle when its edges are perpendicular).
        Rect(Rect),
        /// An axis-aligned box in object space.
        Cuboid(Cuboid),
        /// A finite cylinder, capped or open.
        Cylinder(Cylinder),
        /// A finite cone, capped or open at its base.
        Cone(Cone),
        /// A ring torus.
        Torus(Torus),
        /// A flat disk.
        Disk(Disk),
        /// A single triangle.
        Triangle(Triangle),
        /// A triangle mesh, shared by every object that places it.
        Mesh(std::sync::Arc<Mesh>),
        /// A union, intersection or difference of solids, shared like a mesh.
        Csg(std::sync::Arc<Csg>),
    }
}

/// [`Intersect::differential`] by differencing: the surface a step `dp` ahead gives the
/// normal; with `want_uv`, the uv is differenced forward and backward and the smaller of
/// each kept ([`seamless`]), so that a step across a seam (a sphere's `u` going from 1 to 0)
/// does not count as a jump.
pub fn differenced(
    shape: &(impl Intersect + ?Sized),
    p: Vec3A,
    hit: &ShapeHit,
    dp: Vec3A,
    want_uv: bool,
) -> (Vec2, Vec3A) {
    let ahead = shape.surface(p + dp, hit, want_uv);
    if !want_uv {
        return (Vec2::ZERO, ahead.normal);
    }
    let here = shape.surface(p, hit, true);
    let behind = shape.surface(p - dp, hit, true);
    (
        seamless(ahead.uv - here.uv, here.uv - behind.uv),
        ahead.normal,
    )
}

impl Shape {
    /// [`Intersect::intersect`] as the object walk calls it, inlined there: a mesh through
    /// [`Intersect::intersect`], every other shape through [`Shape::intersect_analytic`].
    /// The mesh's walk, inlined into [`Intersect::intersect`], brings its prologue (saved
    /// registers and a large aligned stack frame) to every call; this keeps it off the
    /// analytic shapes' path.
    #[inline(always)]
    pub(crate) fn intersect_walk(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        match self {
            Shape::Mesh(_) => self.intersect(ray, t_max),
            _ => self.intersect_analytic(ray, t_max),
        }
    }

    /// [`Intersect::occluded`] as the object walk calls it (see [`Shape::intersect_walk`]).
    #[inline(always)]
    pub(crate) fn occluded_walk(&self, ray: &Ray, t_max: f32) -> bool {
        match self {
            Shape::Mesh(_) => self.occluded(ray, t_max),
            _ => self.intersect_analytic(ray, t_max).is_some(),
        }
    }

    /// [`Intersect::intersect`] of every shape but a mesh (`None` for a mesh), inlined into
    /// the object walk: called out of line, its hit came back through memory written field
    /// by field, which the walk read back with wider loads that a processor cannot forward,
    /// and every ray waited for those stores to reach the cache (docs/perf-log.md). The one
    /// method whose arms are written out here rather than forwarded by `closed_set!`: the
    /// forward's own match holds the mesh walk, too large to inline, which cost every
    /// analytic shape test a call more. The match names every variant, so a new shape cannot
    /// be left out of it.
    #[inline(always)]
    fn intersect_analytic(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        match self {
            Shape::Sphere(s) => s.intersect(ray, t_max),
            Shape::Plane(s) => s.intersect(ray, t_max),
            Shape::Rect(s) => s.intersect(ray, t_max),
            Shape::Cuboid(s) => s.intersect(ray, t_max),
            Shape::Cylinder(s) => s.intersect(ray, t_max),
            Shape::Cone(s) => s.intersect(ray, t_max),
            Shape::Torus(s) => s.intersect(ray, t_max),
            Shape::Disk(s) => s.intersect(ray, t_max),
            Shape::Triangle(s) => s.intersect(ray, t_max),
            Shape::Csg(s) => s.intersect(ray, t_max),
            Shape::Mesh(_) => None,
        }
    }
}

/// Equirectangular coordinates of a unit direction: longitude 0 faces +z, east (+x) is to the
/// right, `u = 0.5 + longitude / 2 pi`, `v = 0.5 - latitude / pi` (v = 0 is the north pole,
/// the image's top row).
pub fn equirectangular_uv(n: Vec3A) -> Vec2 {
    let longitude = n.x.atan2(n.z);
    let latitude = n.y.clamp(-1.0, 1.0).asin();
    Vec2::new(
        0.5 + longitude / std::f32::consts::TAU,
        0.5 - latitude / std::f32::consts::PI,
    )
}

/// Roots of `a t^2 + 2 half_b t + c = 0` in ascending order, computed without the
/// cancellation of the textbook formula. `None` when there is no real root or `a` is zero.
#[inline]
pub(crate) fn solve_quadratic(a: f32, half_b: f32, c: f32) -> Option<(f32, f32)> {
    if a == 0.0 {
        return None;
    }
    let disc = half_b * half_b - a * c;
    if disc < 0.0 || disc.is_nan() {
        return None;
    }
    let q = -(half_b + disc.sqrt().copysign(half_b));
    if q == 0.0 {
        // half_b and c are zero: a double root at 0.
        return Some((0.0, 0.0));
    }
    let (t0, t1) = (c / q, q / a);
    Some(if t0 <= t1 { (t0, t1) } else { (t1, t0) })
}

/// Picks the nearer of two candidate hits.
#[inline]
pub(crate) fn nearer(a: Option<ShapeHit>, b: Option<ShapeHit>) -> Option<ShapeHit> {
    match (a, b) {
        (Some(x), Some(y)) => Some(if y.t < x.t { y } else { x }),
        (x, None) => x,
        (None, y) => y,
    }
}

/// `t` as a hit on `part` when it lies in `(0, t_max)`.
#[inline]
pub(crate) fn in_range(t: f32, t_max: f32, part: u8) -> Option<ShapeHit> {
    (t > 0.0 && t < t_max).then_some(ShapeHit {
        t,
        part,
        prim: 0,
        bary: Vec2::ZERO,
    })
}

#[cfg(test)]
pub(crate) mod test_util {
    use super::*;

    /// A hit on part `part` of a shape, for asking its surface there.
    pub fn on_part(part: u8) -> ShapeHit {
        ShapeHit {
            t: 1.0,
            part,
            prim: 0,
            bary: Vec2::ZERO,
        }
    }

    /// Asserts `a` and `b` are within `tol` of each other, component-wise.
    pub fn assert_vec_close(a: Vec3A, b: Vec3A, tol: f32) {
        assert!((a - b).abs().max_element() <= tol, "{a} != {b}");
    }

    /// Checks a shape's packet test (`lanes`) against its test of one ray (`one`), lane by
    /// lane and bit for bit, on 4,000 packets of rays from `origin()` toward `target()`
    /// (points on or near the shape, so that many rays hit it and some graze it): with
    /// unit, long, short, axis-aligned and zero directions, and limits that cut some hits
    /// off. Returns how many rays hit.
    pub fn assert_lanes_match(
        one: impl Fn(&Ray, f32) -> Option<ShapeHit>,
        lanes: impl Fn(&crate::math::RayLanes, &[f32; crate::math::LANES]) -> [f32; crate::math::LANES],
        mut origin: impl FnMut(&mut crate::math::Rng) -> Vec3A,
        mut target: impl FnMut(&mut crate::math::Rng) -> Vec3A,
    ) -> usize {
        use crate::math::{LANES, RayLanes, Rng};
        let mut rng = Rng::new(5);
        let mut hits = 0;
        for _ in 0..4000 {
            let mut rays = [Ray::new(Vec3A::ZERO, Vec3A::X); LANES];
            let mut t_max = [f32::INFINITY; LANES];
            for (l, ray) in rays.iter_mut().enumerate() {
                let o = origin(&mut rng);
                let to = target(&mut rng) - o;
                let mut d = match l {
                    0 | 1 => to,
                    2 => to * 1e-3,
                    3 => to * 1e3,
                    _ => to.normalize(),
                };
                if l == 4 {
                    d.x = 0.0;
                } else if l == 5 && rng.next_f32() < 0.05 {
                    d = Vec3A::ZERO;
                }
                *ray = Ray::new(o, d);
                let u = rng.next_f32();
                if u < 0.3 {
                    // Somewhere around the target: before the hit, or just past it.
                    t_max[l] = to.length() / d.length().max(1e-30) * (0.5 + u * 2.0);
                }
            }
            let got = lanes(&RayLanes::new(&rays), &t_max);
            for l in 0..LANES {
                let want = one(&rays[l], t_max[l]).map(|h| h.t.to_bits());
                let got = (got[l] != f32::INFINITY).then(|| got[l].to_bits());
                assert_eq!(got, want, "{:?}, t_max {}", rays[l], t_max[l]);
                hits += want.is_some() as usize;
            }
        }
        hits
    }

    /// A random point in the cube of side 1 centred on the origin.
    pub fn in_unit_cube(rng: &mut crate::math::Rng) -> Vec3A {
        Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) - 0.5
    }

    /// Hits `shape` with `ray` and returns (t, surface at the hit).
    pub fn hit(shape: &Shape, origin: [f32; 3], dir: [f32; 3]) -> Option<(f32, Surface)> {
        let ray = Ray::new(Vec3A::from_array(origin), Vec3A::from_array(dir));
        shape.intersect(&ray, f32::INFINITY).map(|h| {
            assert!(h.t.is_finite() && h.t > 0.0);
            (h.t, shape.surface(ray.at(h.t), &h, true))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equirectangular_landmarks() {
        // The point facing +z is longitude 0: the centre of the image.
        let uv = equirectangular_uv(Vec3A::Z);
        assert!((uv - Vec2::new(0.5, 0.5)).length() < 1e-6);
        // The north pole is the top row.
        assert!(equirectangular_uv(Vec3A::Y).y.abs() < 1e-6);
        assert!((equirectangular_uv(-Vec3A::Y).y - 1.0).abs() < 1e-6);
        // East (+x, to the camera's right) is longitude +90: three quarters across.
        assert!((equirectangular_uv(Vec3A::X).x - 0.75).abs() < 1e-6);
        assert!((equirectangular_uv(-Vec3A::X).x - 0.25).abs() < 1e-6);
        // The seam (u = 0 and 1) is at the back, -z.
        let back = equirectangular_uv(Vec3A::new(1e-6, 0.0, -1.0)).x;
        assert!(!(0.001..=0.999).contains(&back));
        // 45 degrees north: v = 0.25.
        let n = Vec3A::new(0.0, 1.0, 1.0).normalize();
        assert!((equirectangular_uv(n).y - 0.25).abs() < 1e-6);
    }

    #[test]
    fn report_formula_would_repeat_the_front_at_the_back() {
        // The report's u = 0.5 + asin(n.x) / pi gives the same u for a point and its mirror
        // through the x-y plane; the equirectangular mapping tells them apart.
        let front = Vec3A::new(0.5, 0.0, 0.866);
        let back = Vec3A::new(0.5, 0.0, -0.866);
        let report = |n: Vec3A| 0.5 + n.x.asin() / std::f32::consts::PI;
        assert_eq!(report(front), report(back));
        assert!((equirectangular_uv(front).x - equirectangular_uv(back).x).abs() > 0.3);
    }

    /// What [`Shape::leaving`] promises, for the offset origins rays really start from: a
    /// ray leaving a flat shape on either side, or a convex one through its outside, never
    /// meets the shape again. Rays leaving a solid inward do (so the test can fail), and a
    /// mesh promises nothing.
    #[test]
    fn rays_leaving_a_surface_outward_never_meet_it_again() {
        use crate::math::{Rng, offset_ray_origin};
        let mut rng = Rng::new(21);
        let unit = |rng: &mut Rng| {
            loop {
                let v =
                    Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - Vec3A::ONE;
                if (0.01..=1.0).contains(&v.length_squared()) {
                    return v.normalize();
                }
            }
        };
        let (p0, axis) = (Vec3A::new(0.3, -0.2, 0.1), Vec3A::new(0.2, 1.0, -0.3));
        let shapes = [
            Shape::Sphere(Sphere {
                center: p0,
                radius: 1.3,
            }),
            Shape::Cuboid(Cuboid {
                min: Vec3A::new(-1.0, -0.5, -0.7),
                max: Vec3A::new(0.8, 1.1, 0.9),
            }),
            Shape::Cylinder(Cylinder::new(p0, axis, 0.9, 1.7, true)),
            Shape::Cylinder(Cylinder::new(p0, axis, 0.9, 1.7, false)),
            Shape::Cone(Cone::new(p0, axis, 1.1, 1.5, true)),
            Shape::Cone(Cone::new(p0, axis, 1.1, 1.5, false)),
            Shape::Disk(Disk::new(p0, axis, 1.2)),
            Shape::Rect(
                Rect::new(p0, Vec3A::new(1.5, 0.2, 0.0), Vec3A::new(0.0, 0.3, 1.4)).unwrap(),
            ),
            Shape::Triangle(
                Triangle::new(
                    p0,
                    p0 + Vec3A::new(1.5, 0.2, 0.0),
                    p0 + Vec3A::new(0.0, 0.3, 1.4),
                )
                .unwrap(),
            ),
            Shape::Plane(Plane::new(p0, axis)),
        ];
        for shape in &shapes {
            let leaving = shape.leaving();
            assert_ne!(leaving, Leaving::MayReturn, "{}", shape.kind());
            let (mut hits, mut back_inside) = (0, 0);
            for _ in 0..3000 {
                let eye = p0 + unit(&mut rng) * 6.0;
                let target = p0 + unit(&mut rng) * 0.8;
                let Some(h) =
                    shape.intersect(&Ray::new(eye, (target - eye).normalize()), f32::INFINITY)
                else {
                    continue;
                };
                hits += 1;
                let s = shape.surface(eye + (target - eye).normalize() * h.t, &h, false);
                for side in [1.0f32, -1.0] {
                    let n = s.normal * side;
                    let mut dir = unit(&mut rng);
                    if dir.dot(n) < 0.0 {
                        dir = -dir;
                    }
                    if dir.dot(n) < 1e-3 {
                        continue;
                    }
                    let again = shape
                        .intersect(&Ray::new(offset_ray_origin(s.point, n), dir), f32::INFINITY);
                    let promised = leaving == Leaving::EitherSide || side > 0.0;
                    if promised {
                        assert!(again.is_none(), "{} met again: {again:?}", shape.kind());
                    } else if again.is_some() {
                        back_inside += 1;
                    }
                }
            }
            assert!(hits > 300, "{}: {hits} hits", shape.kind());
            if leaving == Leaving::Outside {
                assert!(
                    back_inside > 100,
                    "{}: {back_inside} inward rays met it",
                    shape.kind()
                );
            }
        }
        let (mesh, _) = Mesh::new(mesh::MeshInput {
            positions: vec![glam::Vec3::ZERO, glam::Vec3::X, glam::Vec3::Y],
            triangles: vec![[0, 1, 2]],
            ..Default::default()
        })
        .unwrap();
        assert_eq!(
            Shape::Mesh(std::sync::Arc::new(mesh)).leaving(),
            Leaving::MayReturn
        );
        // Nor does a torus: a ray leaving its outside may cross the hole to the far side.
        let torus = Shape::Torus(Torus::new(Vec3A::ZERO, Vec3A::Y, 2.0, 0.5));
        assert_eq!(torus.leaving(), Leaving::MayReturn);
        let h = torus
            .intersect(
                &Ray::new(Vec3A::new(-1.5, 0.0, 0.0), Vec3A::X),
                f32::INFINITY,
            )
            .unwrap();
        assert!((h.t - 3.0).abs() < 1e-5, "{}", h.t);
    }

    #[test]
    fn quadratic_is_stable() {
        let (t0, t1) = solve_quadratic(1.0, -1e4, 1.0).unwrap(); // t^2 - 2e4 t + 1
        assert!((t0 - 5e-5).abs() / 5e-5 < 1e-4, "{t0}");
        assert!((t1 - 2e4).abs() / 2e4 < 1e-6);
        assert!(solve_quadratic(1.0, 0.0, 1.0).is_none());
        assert!(solve_quadratic(0.0, 1.0, 1.0).is_none());
    }
}
