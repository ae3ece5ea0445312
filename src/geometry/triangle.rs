//! A triangle, and the watertight ray-triangle test (Woop, Benthin and Wald) that single
//! triangles and meshes' blocks of eight both use.

use super::{Intersect, Leaving, ShapeHit, Surface};
use crate::math::{Aabb, Ray, Vec2, Vec3A};
use glam::{Mat3A, Vec4};

/// A ray prepared for the watertight ray-triangle test of Woop, Benthin and Wald (JCGT
/// 2013): translated to the origin and sheared so that it runs along +z. Two triangles that
/// share an edge compute exactly the same edge function for it (with opposite signs), so a
/// ray can never slip between them.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WatertightRay {
    origin: Vec3A,
    /// Permutes the axes (the ray's largest component last) and shears: applied to a vertex
    /// relative to the origin it gives `(x - sx z, y - sy z, sz z)` exactly as the paper's
    /// scalar code does, since the other terms are exact zeros and ones.
    shear: Mat3A,
}

/// The axes and shear of the watertight test for a ray: `([kx, ky, kz], [sx, sy, sz])`, the
/// ray's largest component's axis last.
#[inline(always)]
fn shear_of(ray: &Ray) -> ([usize; 3], [f32; 3]) {
    // The axis of the largest component, and the other two in cyclic order, swapped (to
    // keep the winding) when the ray runs toward -z. Written without branches: for random
    // directions each one would be mispredicted half the time.
    let d = ray.dir.to_array();
    let a = ray.dir.abs();
    let x_largest = (a.x >= a.y) & (a.x >= a.z);
    // 0 where x is largest, else 1 (y) or 2 (z): arithmetic, as the compiler turned an `if`
    // here back into branches once this was shared by two callers.
    let kz = (!x_largest) as usize * (2 - (a.y >= a.z) as usize);
    let backwards = (d[kz] < 0.0) as usize;
    const WRAP: [usize; 5] = [0, 1, 2, 0, 1];
    let kx = WRAP[kz + 1 + backwards];
    let ky = WRAP[kz + 2 - backwards];
    ([kx, ky, kz], [d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]])
}

/// Triangles in a [`TriangleBlock`].
pub(crate) const LANES: usize = 8;

/// Eight triangles for [`BlockRay`], coordinate by coordinate: `v[axis][corner]` holds that
/// coordinate of corner a, b or c of each of the eight triangles, one a lane. The lanes may
/// belong to different leaves of a BVH (a mesh packs leaves of one to eight triangles into
/// blocks, see `Mesh::new`); a test names the lanes it asks about, and the others' results
/// are dropped.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub(crate) struct TriangleBlock {
    v: [[[f32; LANES]; 3]; 3],
}

impl TriangleBlock {
    /// The block of `tris` (corners a, b, c of each), one a lane.
    pub(crate) fn new(tris: &[[Vec3A; 3]; LANES]) -> Self {
        TriangleBlock {
            v: std::array::from_fn(|axis| {
                std::array::from_fn(|corner| std::array::from_fn(|l| tris[l][corner][axis]))
            }),
        }
    }

    /// Asks the cache for the block's 288 bytes (five cache lines).
    #[inline(always)]
    pub(crate) fn prefetch(&self) {
        // Rows of 32 bytes, two a line: every other row, from the first.
        for (axis, corner) in [(0, 0), (0, 2), (1, 1), (2, 0), (2, 2)] {
            crate::math::prefetch(&self.v[axis][corner]);
        }
    }

    /// The corners a, b, c of the triangle in `lane` (0 to 7).
    pub(crate) fn corners(&self, lane: usize) -> [Vec3A; 3] {
        let at = |axis: usize, corner: usize| self.v[axis][corner][lane % LANES];
        [0, 1, 2].map(|c| Vec3A::new(at(0, c), at(1, c), at(2, c)))
    }
}

/// Lanes of floats for the block test: eight in a 256-bit vector where the build has AVX,
/// four in glam's `Vec4` elsewhere (a block then takes two steps).
trait Wide:
    Copy
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
    + std::ops::Div<Output = Self>
{
    /// All ones in the lanes where a comparison holds.
    type Mask: Copy
        + std::ops::BitAnd<Output = Self::Mask>
        + std::ops::BitOr<Output = Self::Mask>
        + std::ops::Not<Output = Self::Mask>;
    const WIDTH: usize;
    fn splat(x: f32) -> Self;
    /// Lanes `from..from + WIDTH` of a block's row.
    fn load(row: &[f32; LANES], from: usize) -> Self;
    fn lt(self, other: Self) -> Self::Mask;
    fn gt(self, other: Self) -> Self::Mask;
    fn eq(self, other: Self) -> Self::Mask;
    /// A bit per lane where `mask` holds.
    fn bits(mask: Self::Mask) -> u32;
    /// The lanes into `out[from..from + WIDTH]`.
    fn store(self, out: &mut [f32; LANES], from: usize);
}

impl Wide for Vec4 {
    type Mask = glam::BVec4A;
    const WIDTH: usize = 4;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        Vec4::splat(x)
    }
    #[inline(always)]
    fn load(row: &[f32; LANES], from: usize) -> Self {
        Vec4::from_slice(&row[from.min(LANES - 4)..])
    }
    #[inline(always)]
    fn lt(self, other: Self) -> Self::Mask {
        self.cmplt(other)
    }
    #[inline(always)]
    fn gt(self, other: Self) -> Self::Mask {
        self.cmpgt(other)
    }
    #[inline(always)]
    fn eq(self, other: Self) -> Self::Mask {
        self.cmpeq(other)
    }
    #[inline(always)]
    fn bits(mask: Self::Mask) -> u32 {
        mask.bitmask()
    }
    #[inline(always)]
    fn store(self, out: &mut [f32; LANES], from: usize) {
        self.write_to_slice(&mut out[from.min(LANES - 4)..]);
    }
}

/// Eight lanes in a 256-bit AVX vector (safe_arch's `m256` has the arithmetic and bitwise
/// operators already).
#[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
impl Wide for safe_arch::m256 {
    type Mask = safe_arch::m256;
    const WIDTH: usize = 8;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        safe_arch::set_splat_m256(x)
    }
    #[inline(always)]
    fn load(row: &[f32; LANES], _from: usize) -> Self {
        safe_arch::m256::from_array(*row)
    }
    #[inline(always)]
    fn lt(self, o: Self) -> Self {
        use safe_arch::{cmp_op, cmp_op_mask_m256};
        cmp_op_mask_m256::<{ cmp_op!(LessThanOrdered) }>(self, o)
    }
    #[inline(always)]
    fn gt(self, o: Self) -> Self {
        use safe_arch::{cmp_op, cmp_op_mask_m256};
        cmp_op_mask_m256::<{ cmp_op!(GreaterThanOrdered) }>(self, o)
    }
    #[inline(always)]
    fn eq(self, o: Self) -> Self {
        use safe_arch::{cmp_op, cmp_op_mask_m256};
        cmp_op_mask_m256::<{ cmp_op!(EqualOrdered) }>(self, o)
    }
    #[inline(always)]
    fn bits(mask: Self) -> u32 {
        safe_arch::move_mask_m256(mask) as u32
    }
    #[inline(always)]
    fn store(self, out: &mut [f32; LANES], _from: usize) {
        *out = self.to_array();
    }
}

/// The watertight test for a block of triangles at once ([`TriangleBlock`]): each lane does
/// the operations of [`WatertightRay::intersect`] in the same order, so it gives the same
/// hits, to the bit.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BlockRay {
    /// The axes `kx`, `ky`, `kz`.
    k: [usize; 3],
    /// The origin's coordinates along `kx`, `ky`, `kz`.
    origin: [f32; 3],
    /// `sx`, `sy`, `sz`.
    shear: [f32; 3],
}

/// A block's hits, lane by lane ([`BlockRay::lanes`]).
#[derive(Default)]
pub(crate) struct BlockHits {
    /// A bit per lane asked about and hit in `(0, t_max)`.
    pub(crate) mask: u32,
    t: [f32; LANES],
    /// `1 / det`, and the edge functions of b and c (`v`, `w`): the weights are their
    /// products.
    inv: [f32; LANES],
    v: [f32; LANES],
    w: [f32; LANES],
}

impl BlockHits {
    /// The hit in `lane`: `(t, weight of b, weight of c)`, as [`WatertightRay::intersect`]
    /// gives it.
    pub(crate) fn get(&self, lane: usize) -> (f32, f32, f32) {
        let l = lane % LANES;
        (self.t[l], self.v[l] * self.inv[l], self.w[l] * self.inv[l])
    }

    /// The nearest hit: its lane and `(t, weight of b, weight of c)`; of equal distances,
    /// the lowest lane's, as testing the lanes one after the other finds.
    #[inline(always)]
    pub(crate) fn nearest(&self) -> Option<(usize, (f32, f32, f32))> {
        if self.mask == 0 {
            return None;
        }
        let mut rest = self.mask;
        let mut lane = rest.trailing_zeros() as usize % LANES;
        rest &= rest - 1;
        // More than one (rarely): the nearest, the first of equals.
        while rest != 0 {
            let l = rest.trailing_zeros() as usize % LANES;
            rest &= rest - 1;
            if self.t[l] < self.t[lane] {
                lane = l;
            }
        }
        Some((lane, self.get(lane)))
    }
}

impl BlockRay {
    /// Prepares `ray` (any non-zero direction).
    #[inline]
    pub(crate) fn new(ray: &Ray) -> Self {
        let (k, shear) = shear_of(ray);
        // An array, not the vector: indexing a glam vector by a variable is a `match`, three
        // branches that random directions mispredict.
        let o = ray.origin.to_array();
        BlockRay {
            k,
            origin: k.map(|k| o[k]),
            shear,
        }
    }

    /// The hits with `0 < t < t_max` of the block's triangles in the lanes `lanes` names
    /// (a bit each): in one step of eight lanes where the build has AVX.
    #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
    #[inline(always)]
    pub(crate) fn lanes(&self, block: &TriangleBlock, lanes: u32, t_max: f32) -> BlockHits {
        let mut hits = BlockHits::default();
        hits.mask = self.step::<safe_arch::m256>(block, 0, lanes, t_max, &mut hits);
        hits
    }

    /// [`BlockRay::lanes`] in two steps of four lanes, for builds without AVX.
    #[cfg(any(test, not(all(target_arch = "x86_64", target_feature = "avx"))))]
    #[inline(always)]
    pub(crate) fn lanes_in_halves(
        &self,
        block: &TriangleBlock,
        lanes: u32,
        t_max: f32,
    ) -> BlockHits {
        let mut hits = BlockHits::default();
        let mut mask = 0;
        for from in [0, 4] {
            if (lanes >> from) & 15 != 0 {
                mask |=
                    self.step::<Vec4>(block, from, (lanes >> from) & 15, t_max, &mut hits) << from;
            }
        }
        hits.mask = mask;
        hits
    }

    /// [`BlockRay::lanes`] without AVX.
    #[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
    #[inline(always)]
    pub(crate) fn lanes(&self, block: &TriangleBlock, lanes: u32, t_max: f32) -> BlockHits {
        self.lanes_in_halves(block, lanes, t_max)
    }

    /// Lanes `from..from + W::WIDTH` of the block: their hits in `hits` (`t`, `inv`, `v`,
    /// `w`), and a bit per lane asked about (in `lanes`, counted from `from`) and hit.
    #[inline(always)]
    fn step<W: Wide>(
        &self,
        block: &TriangleBlock,
        from: usize,
        lanes: u32,
        t_max: f32,
        hits: &mut BlockHits,
    ) -> u32 {
        let [kx, ky, kz] = self.k.map(|k| k.min(2));
        let [ox, oy, oz] = self.origin.map(W::splat);
        let [sx, sy, sz] = self.shear.map(W::splat);
        let zero = W::splat(0.0);
        let row = |axis: usize, corner: usize| W::load(&block.v[axis][corner], from);
        // Each corner translated and sheared: (x - sx z, y - sy z, sz z).
        let corner = |c: usize| {
            let z = row(kz, c) - oz;
            (
                (row(kx, c) - ox) - sx * z,
                (row(ky, c) - oy) - sy * z,
                sz * z,
            )
        };
        let (ax, ay, az) = corner(0);
        let (bx, by, bz) = corner(1);
        let (cx, cy, cz) = corner(2);
        let mut u = cx * by - cy * bx;
        let mut v = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        let on_edge = W::bits(u.eq(zero) | v.eq(zero) | w.eq(zero)) & lanes;
        if on_edge != 0 {
            // A lane on (or within rounding of) an edge: decided in double precision, as
            // the scalar test does.
            let mut a = [[0.0; LANES]; 9];
            for (out, x) in a.iter_mut().zip([ax, ay, bx, by, cx, cy, u, v, w]) {
                x.store(out, 0);
            }
            let [ax, ay, bx, by, cx, cy, mut uu, mut vv, mut ww] = a;
            for l in 0..W::WIDTH {
                if on_edge & (1 << l) != 0 {
                    uu[l] = exact_edge(cx[l], by[l], cy[l], bx[l]);
                    vv[l] = exact_edge(ax[l], cy[l], ay[l], cx[l]);
                    ww[l] = exact_edge(bx[l], ay[l], by[l], ax[l]);
                }
            }
            (u, v, w) = (W::load(&uu, 0), W::load(&vv, 0), W::load(&ww, 0));
        }
        let negative = u.lt(zero) | v.lt(zero) | w.lt(zero);
        let positive = u.gt(zero) | v.gt(zero) | w.gt(zero);
        let det = u + v + w;
        let t_scaled = u * az + v * bz + w * cz;
        // `finish`'s tests, lane by lane: t = t_scaled / det in (0, t_max), compared before
        // dividing (a NaN fails them all).
        let limit = det * W::splat(t_max);
        let ahead = (det.gt(zero) & t_scaled.gt(zero) & t_scaled.lt(limit))
            | (det.lt(zero) & t_scaled.lt(zero) & t_scaled.gt(limit));
        let inv = W::splat(1.0) / det;
        let t = t_scaled * inv;
        let hit = ahead & !(negative & positive) & t.gt(zero) & t.lt(W::splat(t_max));
        t.store(&mut hits.t, from);
        inv.store(&mut hits.inv, from);
        v.store(&mut hits.v, from);
        w.store(&mut hits.w, from);
        W::bits(hit) & lanes
    }
}

impl WatertightRay {
    /// Prepares `ray` (any non-zero direction).
    #[inline]
    pub(crate) fn new(ray: &Ray) -> Self {
        let ([kx, ky, kz], [sx, sy, sz]) = shear_of(ray);
        let mut cols = [Vec3A::ZERO; 3];
        cols[kx] = Vec3A::X;
        cols[ky] = Vec3A::Y;
        cols[kz] = Vec3A::new(-sx, -sy, sz);
        WatertightRay {
            origin: ray.origin,
            shear: Mat3A::from_cols(cols[0], cols[1], cols[2]),
        }
    }

    /// Hit of the triangle `(a, b, c)` with `0 < t < t_max`: `(t, weight of b, weight of c)`.
    #[inline(always)]
    pub(crate) fn intersect(
        &self,
        a: Vec3A,
        b: Vec3A,
        c: Vec3A,
        t_max: f32,
    ) -> Option<(f32, f32, f32)> {
        let a = self.shear * (a - self.origin);
        let b = self.shear * (b - self.origin);
        let c = self.shear * (c - self.origin);
        let mut u = c.x * b.y - c.y * b.x;
        let mut v = a.x * c.y - a.y * c.x;
        let mut w = b.x * a.y - b.y * a.x;
        if (u == 0.0) | (v == 0.0) | (w == 0.0) {
            // On (or within rounding of) an edge: decide in double precision, where these
            // products of floats are exact, so the two triangles of an edge agree.
            u = exact_edge(c.x, b.y, c.y, b.x);
            v = exact_edge(a.x, c.y, a.y, c.x);
            w = exact_edge(b.x, a.y, b.y, a.x);
        }
        // Signs mixed: the ray passes outside an edge. One branch for the six tests (a
        // random ray misses most triangles it is tested against, at any of the three edges).
        let negative = (u < 0.0) | (v < 0.0) | (w < 0.0);
        let positive = (u > 0.0) | (v > 0.0) | (w > 0.0);
        if negative & positive {
            return None;
        }
        finish(u + v + w, u * a.z + v * b.z + w * c.z, v, w, t_max)
    }
}

/// An edge function `p q - r s` in double precision, where the products of floats are
/// exact, so the two triangles of an edge agree on a ray within rounding of it.
#[inline(always)]
fn exact_edge(p: f32, q: f32, r: f32, s: f32) -> f32 {
    (p as f64 * q as f64 - r as f64 * s as f64) as f32
}

/// The end of both watertight tests, once the edge functions `u, v, w` agree in sign:
/// from `det = u + v + w` and `t_scaled = u za + v zb + w zc`, the hit `(t, weight of b,
/// weight of c)` with `0 < t < t_max`, if any.
#[inline(always)]
fn finish(det: f32, t_scaled: f32, v: f32, w: f32, t_max: f32) -> Option<(f32, f32, f32)> {
    if det == 0.0 || det.is_nan() {
        return None;
    }
    // Compare before dividing: t = t_scaled / det must lie in (0, t_max).
    if det > 0.0 {
        if t_scaled <= 0.0 || t_scaled >= t_max * det {
            return None;
        }
    } else if t_scaled >= 0.0 || t_scaled <= t_max * det {
        return None;
    }
    let inv = 1.0 / det;
    let t = t_scaled * inv;
    (t > 0.0 && t < t_max).then_some((t, v * inv, w * inv))
}

/// A triangle with corners `a`, `b`, `c`; its front side is `(b - a) x (c - a)`
/// (counter-clockwise seen from the front). Both sides are hit.
#[derive(Clone, Debug, PartialEq)]
pub struct Triangle {
    a: Vec3A,
    e1: Vec3A,
    e2: Vec3A,
    normal: Vec3A,
}

impl Triangle {
    /// A triangle; `None` when its area is zero.
    pub fn new(a: Vec3A, b: Vec3A, c: Vec3A) -> Option<Self> {
        let (e1, e2) = (b - a, c - a);
        let n = e1.cross(e2);
        let len = n.length();
        (len > 0.0 && len.is_finite()).then(|| Triangle {
            a,
            e1,
            e2,
            normal: n / len,
        })
    }

    fn barycentric(&self, p: Vec3A) -> Vec2 {
        let rel = p - self.a;
        let (d00, d01, d11) = (
            self.e1.dot(self.e1),
            self.e1.dot(self.e2),
            self.e2.dot(self.e2),
        );
        let (d20, d21) = (rel.dot(self.e1), rel.dot(self.e2));
        let denom = d00 * d11 - d01 * d01;
        Vec2::new(
            (d11 * d20 - d01 * d21) / denom,
            (d00 * d21 - d01 * d20) / denom,
        )
    }
}

impl Intersect for Triangle {
    /// Watertight intersection (the same test as mesh triangles).
    #[inline]
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let (t, u, v) =
            WatertightRay::new(ray).intersect(self.a, self.a + self.e1, self.a + self.e2, t_max)?;
        Some(ShapeHit {
            t,
            part: 0,
            prim: 0,
            bary: Vec2::new(u, v),
        })
    }

    /// Normal and barycentric uv (`u` toward `b`, `v` toward `c`).
    fn surface(&self, p: Vec3A, _hit: &ShapeHit, _want_uv: bool) -> Surface {
        let uv = self.barycentric(p);
        Surface {
            point: self.a + self.e1 * uv.x + self.e2 * uv.y,
            normal: self.normal,
            uv,
        }
    }

    /// The box around the triangle's three corners, object space.
    fn bounds(&self) -> Option<Aabb> {
        let mut b = Aabb::new(self.a, self.a + self.e1);
        b.grow(self.a + self.e2);
        Some(b)
    }

    fn leaving(&self) -> Leaving {
        Leaving::EitherSide
    }

    fn kind(&self) -> &'static str {
        "triangle"
    }
}

impl Triangle {
    /// The first corner and the edges from it to the second and the third.
    pub fn corner_and_edges(&self) -> (Vec3A, Vec3A, Vec3A) {
        (self.a, self.e1, self.e2)
    }

    /// The triangle's area.
    pub fn area(&self) -> f32 {
        0.5 * self.e1.cross(self.e2).length()
    }

    /// A point on the triangle, every one equally likely (density `1 / area`).
    pub fn sample_area(&self, u: Vec2) -> super::SurfaceSample {
        let b = crate::math::sampling::uniform_triangle(u);
        // b.x weighs the first corner, b.y the second, the rest the third.
        super::SurfaceSample {
            point: self.a + b.y * self.e1 + (1.0 - b.x - b.y) * self.e2,
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

    fn tri() -> Shape {
        Shape::Triangle(Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::Y).unwrap())
    }

    #[test]
    fn hit_inside_with_barycentrics() {
        let (t, s) = hit(&tri(), [0.25, 0.5, 2.0], [0.0, 0.0, -1.0]).unwrap();
        assert!((t - 2.0).abs() < 1e-6);
        assert_vec_close(s.normal, Vec3A::Z, 1e-6);
        assert!((s.uv - Vec2::new(0.25, 0.5)).length() < 1e-6);
        // From behind it is hit too.
        assert!(hit(&tri(), [0.25, 0.25, -2.0], [0.0, 0.0, 1.0]).is_some());
    }

    #[test]
    fn misses_outside_parallel_and_degenerate() {
        assert!(hit(&tri(), [0.6, 0.6, 2.0], [0.0, 0.0, -1.0]).is_none());
        assert!(hit(&tri(), [0.2, 0.2, 0.0], [1.0, 0.0, 0.0]).is_none());
        assert!(Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::X * 2.0).is_none());
    }
}
