//! A ray prepared for the node test of the eight-wide BVH, and that test: eight child
//! boxes against one ray in one 256-bit step where the build has AVX (and fused where it has
//! FMA), with a portable test beside it that every test build checks against it.

use super::WideNode;
use crate::math::{Ray, Vec3A};
#[cfg(any(test, not(all(target_arch = "x86_64", target_feature = "avx"))))]
use glam::Vec4;

/// A ray prepared for the tests against the eight child boxes of a BVH node.
///
/// obvhs's own node test clips every box at a fixed distance of 1e-4 (so a scene in
/// millimetres loses nearby hits) and culls flat boxes (a floor, a quad) by rounding; this one
/// starts at 0 and gives the far side a relative slack, as snell's object BVH does (and, in
/// its fused form, a margin for the rounding of the start values: see `NodeRay::new`).
pub(crate) struct NodeRay {
    origin: [Lanes; 3],
    inv_dir: [Lanes; 3],
    /// `inv_dir` times [`SLACK`], for the far sides.
    inv_far: [Lanes; 3],
    /// `-origin * inv_dir` and `-origin * inv_far`, moved down and up by more than their
    /// rounding, for the node test's fused multiply-adds.
    #[cfg(all(
        target_arch = "x86_64",
        target_feature = "avx2",
        target_feature = "fma"
    ))]
    start: [[Lanes; 3]; 2],
    /// Per axis, the side of the boxes the ray enters by: 1 (the largest coordinate) where
    /// it runs toward minus, else 0.
    near_side: [usize; 3],
}

/// A ray coordinate for the node test: in all eight lanes of a 256-bit vector where the build
/// has AVX; elsewhere one float, which the portable test spreads over 128-bit vectors.
#[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
type Lanes = safe_arch::m256;
#[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
type Lanes = f32;

impl NodeRay {
    #[inline(always)]
    pub(crate) fn new(ray: &Ray) -> Self {
        let inv = capped_inverse(ray.dir);
        let inv_far = inv * SLACK;
        NodeRay {
            origin: splat3(ray.origin),
            inv_dir: splat3(inv),
            inv_far: splat3(inv_far),
            #[cfg(all(
                target_arch = "x86_64",
                target_feature = "avx2",
                target_feature = "fma"
            ))]
            start: {
                // `start` is `-origin * inv` (`inv_far` for the far sides) moved toward the
                // ray's origin on the near sides and away from it on the far ones by a margin
                // of 2^-22 of itself, applied before the multiplication: `(-origin * (1 -/+
                // margin)) * inv`, the sign of `-origin * inv` taken from the signs of the
                // origin and the direction (the inverse has the direction's sign, zeros
                // included), so the factor is ready before the division is and one
                // multiplication follows it. Its two roundings move the product by at most
                // 2^-23 of itself, half the margin. So `plane * inv + start` is, before its
                // own rounding, at most the exact `(plane - origin) * inv` on the near sides
                // and at least it on the far ones, and no box the ray meets is culled (the
                // far sides' slack covers the final rounding, as it did the
                // subtract-then-multiply's); boxes it misses by less than the margin (about
                // 2^-22 of |origin| / |direction| along an axis) may be met, which costs a
                // test, never a hit.
                const MARGIN: f32 = 1.0 / (1 << 22) as f32;
                let away = -ray.origin;
                let sign = Vec3A::ONE.copysign(away) * Vec3A::ONE.copysign(ray.dir);
                let near = away * (Vec3A::ONE - sign * MARGIN);
                let far = away * (Vec3A::ONE + sign * MARGIN);
                [splat3(near * inv), splat3(far * inv_far)]
            },
            // From the inverse's sign, so that a direction of -0 (whose inverse is negative)
            // takes the largest corner as its near side, as the inverse does.
            near_side: [0, 1, 2].map(|a| inv[a].is_sign_negative() as usize),
        }
    }

    /// Entry distances into the eight child boxes of `node`, and a bit per child whose box
    /// the ray meets in `[0, t_max]`. Empty children have inverted boxes, which never meet.
    /// The distances come as a plain array: a vector's lane picked by a variable index (as
    /// the walk picks them) compiles to a jump table, an indirect branch per child pushed.
    #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
    #[inline(always)]
    pub(crate) fn hits(&self, node: &WideNode, t_max: f32) -> ([f32; 8], u32) {
        use safe_arch::*;
        // `(plane - origin) * inverse`, a subtraction then a multiplication: cheaper to set
        // up than the mesh walks' fused test, for the one test of a small scene's eight
        // objects (the seed scene was 1 % slower with the fused one).
        let slab = |axis: usize| {
            let side = self.near_side[axis] & 1;
            let planes = &node.planes[axis];
            let n = m256::from_array(planes[side]);
            let f = m256::from_array(planes[side ^ 1]);
            let o = self.origin[axis];
            (
                mul_m256(sub_m256(n, o), self.inv_dir[axis]),
                mul_m256(sub_m256(f, o), self.inv_far[axis]),
            )
        };
        let ((n0, f0), (n1, f1), (n2, f2)) = (slab(0), slab(1), slab(2));
        // As trees, two steps deep rather than a chain of four.
        let near = max_m256(max_m256(n0, n1), max_m256(n2, set_splat_m256(0.0)));
        let far = min_m256(min_m256(f0, f1), min_m256(f2, set_splat_m256(t_max)));
        let met = cmp_op_mask_m256::<{ cmp_op!(LessEqualOrdered) }>(near, far);
        (near.to_array(), move_mask_m256(met) as u32)
    }

    /// The mesh walks' node test, where the build has AVX2 and FMA: the entry distances
    /// (as bits), and all ones in the lanes of the children *not* met.
    ///
    /// Each distance is one fused multiply-add from the start values made with the ray (4
    /// cycles less than a subtraction then a multiplication, and the margin in them keeps
    /// every box the ray meets: see `NodeRay::new`). The walks wait on this test at every
    /// node, so the rest is done on the distances' bits, with integer operations of one
    /// cycle where float ones take four: for floats that are not NaN (none arise: the
    /// inverse is capped), the signed integer maximum of the bits of the near sides and of
    /// 0 is the bits of their float maximum with 0, since non-negative floats order as their
    /// bits do and negative ones are negative integers. The integer minimum of the far sides
    /// and `t_max` is their float minimum when none is negative, and a negative float (not
    /// always the least) when one is, so the box is missed exactly when the float test
    /// misses it, but for a far side of -0, which the float test keeps only at a near
    /// distance of 0 too: a box that ends at the ray's origin, which holds no hit at `t > 0`.
    #[cfg(all(
        target_arch = "x86_64",
        target_feature = "avx2",
        target_feature = "fma"
    ))]
    #[inline(always)]
    pub(crate) fn fused_hits(
        &self,
        node: &WideNode,
        t_max: f32,
    ) -> (safe_arch::m256i, safe_arch::m256i) {
        use safe_arch::*;
        let slab = |axis: usize| {
            let side = self.near_side[axis] & 1;
            let planes = &node.planes[axis];
            let n = m256::from_array(planes[side]);
            let f = m256::from_array(planes[side ^ 1]);
            (
                cast_to_m256i_from_m256(fused_mul_add_m256(
                    n,
                    self.inv_dir[axis],
                    self.start[0][axis],
                )),
                cast_to_m256i_from_m256(fused_mul_add_m256(
                    f,
                    self.inv_far[axis],
                    self.start[1][axis],
                )),
            )
        };
        let ((n0, f0), (n1, f1), (n2, f2)) = (slab(0), slab(1), slab(2));
        let near = max_i32_m256i(
            max_i32_m256i(n0, n1),
            max_i32_m256i(n2, set_splat_i32_m256i(0)),
        );
        let far = min_i32_m256i(
            min_i32_m256i(f0, f1),
            min_i32_m256i(f2, set_splat_i32_m256i(t_max.to_bits() as i32)),
        );
        (near, cmp_gt_mask_i32_m256i(near, far))
    }

    /// [`NodeRay::hits`] without AVX.
    #[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
    #[inline(always)]
    pub(crate) fn hits(&self, node: &WideNode, t_max: f32) -> ([f32; 8], u32) {
        hits_portable(
            self.origin,
            self.inv_dir,
            self.inv_far,
            self.near_side,
            node,
            t_max,
        )
    }
}

/// `1 / d`, capped so that nothing in the node test overflows to infinity (and then to NaN
/// when multiplied by a zero) for coordinates up to the 1e15 scene files allow.
#[inline(always)]
fn capped_inverse(d: Vec3A) -> Vec3A {
    const CAP: f32 = 1e20;
    let inv = Vec3A::ONE / d;
    let capped = Vec3A::splat(CAP).copysign(inv);
    Vec3A::select(inv.abs().cmple(Vec3A::splat(CAP)), inv, capped)
}

/// [`NodeRay::hits`] four children at a time, in 128-bit vectors: the test of builds without
/// AVX. Test builds compile it everywhere, so that it is linted and checked against the AVX
/// test where the machine has AVX.
#[cfg(any(test, not(all(target_arch = "x86_64", target_feature = "avx"))))]
#[inline(always)]
fn hits_portable(
    origin: [f32; 3],
    inv_dir: [f32; 3],
    inv_far: [f32; 3],
    near_side: [usize; 3],
    node: &WideNode,
    t_max: f32,
) -> ([f32; 8], u32) {
    let mut nears = [0.0; 8];
    let mut mask = 0;
    for (half, nears) in nears.chunks_exact_mut(4).enumerate() {
        let slab = |axis: usize| {
            let side = near_side[axis] & 1;
            let planes = &node.planes[axis];
            let o = Vec4::splat(origin[axis]);
            let n = Vec4::from_slice(&planes[side][4 * half..]);
            let f = Vec4::from_slice(&planes[side ^ 1][4 * half..]);
            (
                (n - o) * Vec4::splat(inv_dir[axis]),
                (f - o) * Vec4::splat(inv_far[axis]),
            )
        };
        let ((n0, f0), (n1, f1), (n2, f2)) = (slab(0), slab(1), slab(2));
        let near = n0.max(n1).max(n2.max(Vec4::ZERO));
        let far = f0.min(f1).min(f2.min(Vec4::splat(t_max)));
        mask |= near.cmple(far).bitmask() << (half * 4);
        nears.copy_from_slice(&near.to_array());
    }
    (nears, mask)
}

/// Each coordinate of `v` in every lane of a vector of its own. With AVX, from one 16-byte
/// copy of `v` shuffled in registers: reading the coordinates one by one from a ray just
/// stored (a shadow ray, made and walked at once) compiled to an 8-byte load across the
/// middle of the 16-byte store, which the processor cannot forward, and the walk waited
/// for the store to reach the cache.
#[inline(always)]
fn splat3(v: Vec3A) -> [Lanes; 3] {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
    {
        use safe_arch::{load_m128_splat_m256, m128, permute_m256};
        let both = load_m128_splat_m256(&m128(v.into()));
        [
            permute_m256::<0b00_00_00_00>(both),
            permute_m256::<0b01_01_01_01>(both),
            permute_m256::<0b10_10_10_10>(both),
        ]
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
    [v.x, v.y, v.z]
}

/// Widens every box's far side by this factor, so rounding never culls a box the ray only
/// grazes or a box with no thickness. The node test folds it into the inverse direction it
/// multiplies the far sides by (one multiply less on the way to the next node); the
/// product's own rounding, a few parts in 10^7, is far below it.
const SLACK: f32 = 1.0 + 1e-5;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rng;

    /// The node test (the AVX one or the portable one, whichever this build has) against
    /// the plain slab test, child by child: random boxes (some empty, some flat, some
    /// behind the ray) and random rays, with directions that have +0 and -0 components.
    /// The portable test, which every test build compiles, gives the same answers to the
    /// bit.
    #[test]
    fn node_test_agrees_with_the_slab_test() {
        let mut rng = Rng::new(5);
        let mut r = |lo: f32, hi: f32| lo + (hi - lo) * rng.next_f32();
        // Cases tested, and boxes the plain test finds the ray meets.
        let (mut cases, mut met_boxes) = (0, 0);
        for case in 0..2000 {
            let mut planes = [[[f32::INFINITY; 8], [f32::NEG_INFINITY; 8]]; 3];
            let mut used = [false; 8];
            for (child, used) in used.iter_mut().enumerate() {
                if r(0.0, 1.0) < 0.2 {
                    continue; // empty: an inverted box
                }
                *used = true;
                for (axis, [lo, hi]) in planes.iter_mut().enumerate() {
                    let a = r(-2.0, 2.0);
                    // Every fifth box is flat along x.
                    let b = if axis == 0 && child % 5 == 0 {
                        a
                    } else {
                        r(-2.0, 2.0)
                    };
                    (lo[child], hi[child]) = (a.min(b), a.max(b));
                }
            }
            let node = WideNode {
                planes,
                child: [0; 8],
            };
            let mut d = Vec3A::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0));
            match case % 4 {
                1 => d.x = 0.0,
                2 => d.y = -0.0,
                3 => (d.x, d.z) = (-0.0, 0.0),
                _ => {}
            }
            if d == Vec3A::ZERO {
                continue;
            }
            cases += 1;
            let ray = Ray::new(Vec3A::new(r(-3.0, 3.0), r(-3.0, 3.0), r(-3.0, 3.0)), d);
            let t_max = if case % 3 == 0 {
                f32::INFINITY
            } else {
                r(0.0, 4.0)
            };
            let (nears, mask) = NodeRay::new(&ray).hits(&node, t_max);
            // The mesh walks' test, with fused multiply-adds, where the build has AVX2 and FMA.
            #[cfg(all(
                target_arch = "x86_64",
                target_feature = "avx2",
                target_feature = "fma"
            ))]
            let (fused_nears, fused_mask) = {
                let (n, missed) = NodeRay::new(&ray).fused_hits(&node, t_max);
                let n: [f32; 8] = bytemuck::cast(<[i32; 8]>::from(n));
                (
                    n,
                    !safe_arch::move_mask_m256(safe_arch::cast_to_m256_from_m256i(missed)) as u32
                        & 255,
                )
            };
            #[cfg(not(all(
                target_arch = "x86_64",
                target_feature = "avx2",
                target_feature = "fma"
            )))]
            let (fused_nears, fused_mask) = (nears, mask);
            let inv = capped_inverse(ray.dir);
            let near_side = [0, 1, 2].map(|a| inv[a].is_sign_negative() as usize);
            let (portable_nears, portable_mask) = hits_portable(
                ray.origin.to_array(),
                inv.to_array(),
                (inv * SLACK).to_array(),
                near_side,
                &node,
                t_max,
            );
            let inv = (Vec3A::ONE / ray.dir).to_array().map(|i| {
                if i.abs() <= 1e20 {
                    i
                } else {
                    1e20f32.copysign(i)
                }
            });
            for child in 0..8 {
                let (mut near, mut far) = (0.0f32, f32::INFINITY);
                // Where the box really is, in double precision (but for the capped inverse).
                let (mut near64, mut far64) = (0.0f64, f64::INFINITY);
                for axis in 0..3 {
                    let [lo, hi] = planes[axis].map(|p| p[child]);
                    let (n, f) = if inv[axis].is_sign_negative() {
                        (hi, lo)
                    } else {
                        (lo, hi)
                    };
                    let o = ray.origin[axis];
                    near = near.max((n - o) * inv[axis]);
                    far = far.min((f - o) * (inv[axis] * SLACK));
                    near64 = near64.max((n as f64 - o as f64) * inv[axis] as f64);
                    far64 = far64.min((f as f64 - o as f64) * inv[axis] as f64);
                }
                // The plain test and the portable one: these formulas, to the bit.
                let met = near <= far.min(t_max);
                assert_eq!(mask >> child & 1 == 1, met, "case {case}, child {child}");
                assert_eq!(
                    portable_mask >> child & 1 == 1,
                    met,
                    "case {case}, child {child}"
                );
                assert!(used[child] || !met, "case {case}: empty child {child} met");
                if met {
                    met_boxes += 1;
                    assert_eq!(nears[child], near, "case {case}, child {child}");
                    assert_eq!(
                        portable_nears[child].to_bits(),
                        near.to_bits(),
                        "case {case}"
                    );
                }
                // The fused test rounds otherwise, but never culls a box the ray meets
                // (flat ones and grazed ones included), nor puts its entry later...
                let found = fused_mask >> child & 1 == 1;
                assert!(
                    used[child] || !found,
                    "case {case}: empty child {child} met"
                );
                if near64 <= far64 && near64 < t_max as f64 * (1.0 - 1e-6) {
                    assert!(found, "case {case}, child {child}: culled");
                    assert!(
                        fused_nears[child] as f64 <= near64 * (1.0 + 1e-6),
                        "case {case}, child {child}: {} after {near64}",
                        fused_nears[child]
                    );
                }
                // ... and, for rays along no axis, none met that the ray misses by more
                // than the margins (a few parts in 10^6 here).
                if found && inv.iter().all(|i| i.abs() < 1e6) {
                    assert!(
                        near64 <= far64 + 1e-5 * (1.0 + far64.abs()),
                        "case {case}, child {child}: met, {near64} > {far64}"
                    );
                }
            }
        }
        // A direction is zero only where a drawn component is exactly 0 (one draw in 2^24)
        // and the case zeroes the others: none of these 2000.
        assert_eq!(cases, 2000, "cases with a direction");
        // Replaying the generator: some 270 of the 12,800 boxes (random ones, a few units
        // from random rays, most of which stop within 4) are met.
        assert!(met_boxes > 100, "{met_boxes} boxes met");
    }
}
