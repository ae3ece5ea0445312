//! A triangle mesh: its own BVH over its triangles (obvhs's PLOC binary tree, collapsed into
//! an eight-wide tree with leaves of up to eight triangles tested at once: see `collapse`),
//! watertight triangle tests, and per-vertex normals and uvs. A mesh is shared
//! (`Arc`) by every object that places it, so a thousand instances cost one copy.

use super::collapse::collapse;
use super::triangle::{BlockRay, LANES, TriangleBlock};
use super::{ShapeHit, Surface};
use crate::accel::push_child;
use crate::math::{Aabb, Ray, Vec2, Vec3, Vec3A};
#[cfg(any(test, not(all(target_arch = "x86_64", target_feature = "avx"))))]
use glam::Vec4;
use std::time::{Duration, Instant};

/// Most triangles one mesh may have (a leaf reference names one of at most 2^25 blocks of
/// eight; the BVH needs about 8 bytes and the mesh about 60 bytes per triangle, so this is
/// some 9 GiB). A scene may hold more in several meshes.
pub const MAX_TRIANGLES: usize = 1 << 27;

/// Geometry read from a file or built in code, before it is arranged for ray queries.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshInput {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Per-vertex normals (same length as `positions`), or empty.
    pub normals: Vec<Vec3>,
    /// Per-vertex texture coordinates, or empty.
    pub uvs: Vec<Vec2>,
    /// Corner indices of each triangle, counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// Per triangle, the index of its material slot (see [`Mesh::slots`]), or empty.
    pub triangle_slots: Vec<u16>,
}

/// A triangle mesh arranged for ray queries.
#[derive(Debug, PartialEq)]
pub struct Mesh {
    /// The triangles' corners, eight lanes a block, the BVH's leaves in the order they are
    /// named (gathered, so a leaf's test reads one place), each in the lanes left in one of
    /// the last blocks when it has enough (see [`PACKING_WINDOW`]), else from lane 0 of a
    /// new one (lanes no leaf fills repeat another of the block's triangles). Triangle
    /// `8 k + l` (a hit's `prim`) is lane `l` of block `k`. A leaf reference names its block
    /// and lanes (see [`LEAF_LANES`]).
    blocks: Vec<TriangleBlock>,
    /// Vertex indices of each triangle, in the blocks' order, unfilled lanes included (for
    /// normals and uvs).
    faces: Vec<[u32; 3]>,
    /// Number of triangles (not counting unfilled lanes).
    triangles: usize,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
    /// Material slot of each triangle, in BVH order, or empty.
    slots: Vec<u16>,
    bvh: WideBvh,
    bounds: Aabb,
    /// Time spent building the BVH.
    pub build_time: Duration,
}

impl Mesh {
    /// Arranges `input` for ray queries. Triangles with zero area (or non-finite corners) are
    /// dropped: the returned count says how many. Fails on an index out of range, a
    /// mismatched normal or uv count, or a mesh with no triangle left.
    pub fn new(input: MeshInput) -> Result<(Mesh, usize), String> {
        let MeshInput {
            positions,
            normals,
            uvs,
            triangles,
            triangle_slots,
        } = input;
        if triangles.len() > MAX_TRIANGLES {
            return Err(format!(
                "{} triangles is more than the {MAX_TRIANGLES} a mesh may have",
                triangles.len()
            ));
        }
        if !normals.is_empty() && normals.len() != positions.len() {
            return Err(format!(
                "{} normals for {} vertices",
                normals.len(),
                positions.len()
            ));
        }
        if !uvs.is_empty() && uvs.len() != positions.len() {
            return Err(format!(
                "{} uvs for {} vertices",
                uvs.len(),
                positions.len()
            ));
        }
        if !triangle_slots.is_empty() && triangle_slots.len() != triangles.len() {
            return Err(format!(
                "{} material slots for {} triangles",
                triangle_slots.len(),
                triangles.len()
            ));
        }
        let mut kept = Vec::with_capacity(triangles.len());
        let mut aabbs = Vec::with_capacity(triangles.len());
        let mut bounds = Aabb::EMPTY;
        for (i, t) in triangles.iter().enumerate() {
            if let Some(&bad) = t.iter().find(|&&k| k as usize >= positions.len()) {
                return Err(format!(
                    "triangle {i} uses vertex {bad}, but there are {} vertices",
                    positions.len()
                ));
            }
            let [a, b, c] = t.map(|k| Vec3A::from(positions[k as usize]));
            let area2 = (b - a).cross(c - a).length_squared();
            if !(area2 > 0.0 && area2.is_finite()) {
                continue;
            }
            let mut bx = Aabb::new(a, b);
            bx.grow(c);
            bounds = bounds.union(&bx);
            aabbs.push(obvhs::aabb::Aabb::new(bx.min, bx.max));
            kept.push(i);
        }
        let dropped = triangles.len() - kept.len();
        if kept.is_empty() {
            return Err(if triangles.is_empty() {
                "the mesh has no triangles".to_string()
            } else {
                format!(
                    "all {} triangles have zero area; nothing to render",
                    triangles.len()
                )
            });
        }
        let start = Instant::now();
        // obvhs's binary tree (PLOC, then reinsertion: its `medium_build`, searching wider
        // from the second level and reinserting more; see `REINSERTION_TRIANGLES`), collapsed
        // into an eight-wide tree with leaves of up to eight triangles (see `collapse`).
        let params = obvhs::BvhBuildParams::medium_build();
        let reinsertion = (REINSERTION_TRIANGLES / aabbs.len() as f32).clamp(0.05, 1.0);
        let mut bvh2 = obvhs::ploc::PlocBuilder::with_capacity(aabbs.len()).build(
            params.ploc_search_distance,
            &aabbs,
            (0..aabbs.len() as u32).collect(),
            params.sort_precision,
            1,
        );
        obvhs::bvh2::reinsertion::ReinsertionOptimizer::default().run(&mut bvh2, reinsertion, None);
        let mut wide = collapse(&bvh2)?;
        // Lay the triangles out in the order the BVH's leaves name them, each leaf in the
        // first of the last few blocks with room for it, else in a new block (see
        // `PACKING_WINDOW`), and make each leaf reference name its block and lanes instead
        // of its index.
        let mut order: Vec<usize> = Vec::with_capacity(kept.len() * 5 / 4);
        // Per block, the lanes taken.
        let mut taken: Vec<usize> = Vec::with_capacity(kept.len() / 3);
        let mut refs = Vec::with_capacity(wide.leaves.len());
        for leaf in &wide.leaves {
            let n = leaf.len();
            let recent = taken.len().saturating_sub(PACKING_WINDOW)..taken.len();
            let block = match recent.into_iter().find(|&b| taken[b] + n <= LANES) {
                Some(b) => b,
                None => {
                    taken.push(0);
                    order.extend([usize::MAX; LANES]);
                    taken.len() - 1
                }
            };
            let lane = taken[block];
            for (i, &p) in leaf.iter().enumerate() {
                order[block * LANES + lane + i] = kept[p as usize];
            }
            taken[block] += n;
            refs.push(leaf_reference(block, lane, n)?);
        }
        // Unfilled lanes repeat their block's first triangle.
        for (block, &n) in order.chunks_exact_mut(LANES).zip(&taken) {
            let first = block[0];
            block[n..].fill(first);
        }
        for node in &mut wide.nodes {
            for child in &mut node.child {
                if *child & LEAF != 0 {
                    *child = refs[(*child & !LEAF) as usize];
                }
            }
        }
        let faces: Vec<[u32; 3]> = order.iter().map(|&i| triangles[i]).collect();
        let blocks = faces
            .chunks_exact(LANES)
            .map(|lanes| {
                TriangleBlock::new(&std::array::from_fn(|l| {
                    lanes[l].map(|k| positions[k as usize].into())
                }))
            })
            .collect();
        let slots = if triangle_slots.is_empty() {
            vec![]
        } else {
            order.iter().map(|&i| triangle_slots[i]).collect()
        };
        let bvh = WideBvh {
            nodes: wide.nodes,
            depth: wide.depth,
        };
        Ok((
            Mesh {
                blocks,
                faces,
                triangles: kept.len(),
                normals,
                uvs,
                slots,
                bvh,
                bounds,
                build_time: start.elapsed(),
            },
            dropped,
        ))
    }

    /// Number of triangles (after dropping degenerate ones).
    pub fn triangle_count(&self) -> usize {
        self.triangles
    }

    /// Whether the mesh has per-vertex normals (smooth shading).
    pub fn has_normals(&self) -> bool {
        !self.normals.is_empty()
    }

    /// Whether the mesh has texture coordinates.
    pub fn has_uvs(&self) -> bool {
        !self.uvs.is_empty()
    }

    /// Bytes taken by the BVH itself (nodes and primitive indices).
    pub fn bvh_bytes(&self) -> usize {
        self.bvh.nodes.len() * std::mem::size_of::<WideNode>()
    }

    /// Bytes taken by the triangles, normals, uvs and slots.
    pub fn geometry_bytes(&self) -> usize {
        self.blocks.len() * std::mem::size_of::<TriangleBlock>()
            + self.faces.len() * 12
            + self.normals.len() * 12
            + self.uvs.len() * 8
            + self.slots.len() * 2
    }

    /// Material slot of triangle `prim` (as reported in a [`ShapeHit`]); 0 without slots.
    #[inline]
    pub fn slot(&self, prim: u32) -> u16 {
        self.slots.get(prim as usize).copied().unwrap_or(0)
    }

    /// Object-space bounds.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Nearest hit with `0 < t < t_max`: the triangle's index and barycentrics come back in
    /// `prim` and `bary`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let mut closest = TriangleQuery::<false> {
            blocks: &self.blocks,
            source: ray,
            ray: None,
            hit: None,
        };
        self.bvh.walk::<true>(ray, t_max, &mut closest);
        closest.hit
    }

    /// Whether any triangle is hit with `0 < t < t_max`; stops at the first found.
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        let mut any = TriangleQuery::<true> {
            blocks: &self.blocks,
            source: ray,
            ray: None,
            hit: None,
        };
        self.bvh.walk::<false>(ray, t_max, &mut any);
        any.hit.is_some()
    }

    /// Surface details of a hit: the point re-projected from the barycentrics, the geometric
    /// normal (turned to agree with the vertex normals when there are any, since exporters
    /// keep normals consistent more reliably than winding), and the interpolated uv (the
    /// barycentrics when the mesh has none).
    pub fn surface(&self, hit: &ShapeHit) -> Surface {
        let [a, b, c] = self.corners(hit.prim);
        let (u, v) = (hit.bary.x, hit.bary.y);
        let w = 1.0 - u - v;
        let point = a * w + b * u + c * v;
        let mut normal = (b - a).cross(c - a).normalize();
        if let Some(shading) = self.interpolated_normal(hit)
            && shading.dot(normal) < 0.0
        {
            normal = -normal;
        }
        let uv = if self.uvs.is_empty() {
            hit.bary
        } else {
            let f = self.faces[hit.prim as usize];
            self.uvs[f[0] as usize] * w + self.uvs[f[1] as usize] * u + self.uvs[f[2] as usize] * v
        };
        Surface { point, normal, uv }
    }

    /// The corners of triangle `prim` (in BVH order).
    fn corners(&self, prim: u32) -> [Vec3A; 3] {
        self.blocks[prim as usize / LANES].corners(prim as usize % LANES)
    }

    /// The vertex normals interpolated at a hit (unit, object space), when the mesh has them.
    pub fn interpolated_normal(&self, hit: &ShapeHit) -> Option<Vec3A> {
        if self.normals.is_empty() {
            return None;
        }
        let f = self.faces[hit.prim as usize];
        let (u, v) = (hit.bary.x, hit.bary.y);
        let n = Vec3A::from(self.normals[f[0] as usize]) * (1.0 - u - v)
            + Vec3A::from(self.normals[f[1] as usize]) * u
            + Vec3A::from(self.normals[f[2] as usize]) * v;
        let n = n.normalize_or_zero();
        (n != Vec3A::ZERO).then_some(n)
    }
}

/// What a BVH walk does with the triangles of the leaves it reaches. A trait rather than a
/// closure, so that the triangle test is inlined into the walk.
trait Visit {
    /// Tests the triangles of leaf `leaf`, lowering `t_max` to a hit's distance; true stops
    /// the walk.
    fn visit(&mut self, leaf: u32, t_max: &mut f32) -> bool;
    /// Asks the cache for leaf `leaf`'s triangles, which will be tested soon.
    fn prefetch(&self, leaf: u32);
}

/// A ray's query of a mesh's triangles: the nearest hit (`ANY` false), or any hit, the walk
/// stopping at the first (`ANY` true).
struct TriangleQuery<'a, const ANY: bool> {
    blocks: &'a [TriangleBlock],
    source: &'a Ray,
    /// The ray prepared for triangle tests, made at the first one: a ray that meets no
    /// leaf (one that misses the mesh, for a start) never pays for it.
    ray: Option<BlockRay>,
    hit: Option<ShapeHit>,
}

impl<const ANY: bool> Visit for TriangleQuery<'_, ANY> {
    #[inline(always)]
    fn prefetch(&self, leaf: u32) {
        if let Some(block) = self.blocks.get((leaf & LEAF_BLOCK) as usize) {
            block.prefetch();
        }
    }

    #[inline(always)]
    fn visit(&mut self, leaf: u32, t_max: &mut f32) -> bool {
        let source = self.source;
        let ray = self.ray.get_or_insert_with(|| BlockRay::new(source));
        let Some(block) = self.blocks.get((leaf & LEAF_BLOCK) as usize) else {
            return false;
        };
        let hits = ray.lanes(
            block,
            LEAF_LANE_MASKS[(leaf >> LEAF_LANES) as usize & 63],
            *t_max,
        );
        let Some((lane, (t, u, v))) = (if ANY && hits.mask != 0 {
            // Any hit will do: the lowest lane's.
            let lane = hits.mask.trailing_zeros() as usize;
            Some((lane, hits.get(lane)))
        } else {
            hits.nearest()
        }) else {
            return false;
        };
        *t_max = t;
        self.hit = Some(ShapeHit {
            t,
            part: 0,
            prim: (leaf & LEAF_BLOCK) * LANES as u32 + lane as u32,
            bary: Vec2::new(u, v),
        });
        ANY
    }
}

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

/// Up to how many triangles a mesh's binary tree is optimised by reinsertion over all its
/// nodes; beyond, over this many of them (at least 5 %, obvhs's `medium_build`), so the
/// build's time keeps in step with the mesh's size. With PLOC's medium search from depth 1
/// instead of 3, the bunny's tree (29 % of its nodes) builds in 56 ms instead of 45 and a
/// million triangles in 0.69 s instead of 0.62; rays through the bunny: random 1.03 times as
/// fast, camera the same; the teapot (every node): random 1.07, camera 1.03. Renders at
/// 1024 x 1024: bunny.toml 0.973 of the time, field.toml 1.002 (at 256 x 256, where the
/// build is a larger share, 1.008 and 1.13). Every node for the bunny too: rays 1.04 times
/// as fast, but its build took 100 ms and a million triangles 2.2 s.
const REINSERTION_TRIANGLES: f32 = 20_000.0;

/// Marks a child reference as a leaf. `collapse` makes `LEAF | k` for its `k`-th leaf;
/// [`Mesh::new`] turns that into the leaf's block and lanes ([`leaf_reference`]).
pub(crate) const LEAF: u32 = 1 << 31;

/// How many of the last blocks a leaf may go into, when it has room there. Leaves hold one
/// to eight triangles (4.6 on average in the bunny's tree), so a block per leaf would leave
/// almost half the lanes empty; sharing blocks fills 80 % of them when a leaf may only go
/// into the last block, 89 % with 4, 94 % with 16 and 97 % with 64 (the bunny: 9,199 blocks
/// for 14,956 leaves with 16; 4, 16 and 64 measured the same), and the leaves stay near
/// their neighbours in the tree. The bunny's triangles take 2.6 MB, which matters where
/// they do not fit in the cache: with blocks of four lanes, sharing them took 3.7 MB down to
/// 2.6 and random rays through the bunny ran 3 % faster (48 bytes more a block, 8 % slower).
const PACKING_WINDOW: usize = 16;

/// Where a mesh leaf reference keeps its lanes: the first (three bits), then the count less
/// one (three bits).
const LEAF_LANES: u32 = 25;

/// The bits of a mesh leaf reference that give its block.
const LEAF_BLOCK: u32 = (1 << LEAF_LANES) - 1;

/// The lanes of a leaf, a bit each, by the six bits of its reference that give them.
static LEAF_LANE_MASKS: [u32; 64] = {
    let mut masks = [0; 64];
    let mut i = 0;
    while i < 64 {
        let (first, n) = (i & 7, (i >> 3) + 1);
        masks[i] = ((1 << n) - 1) << first & 255;
        i += 1;
    }
    masks
};

/// The reference of a leaf of `n` triangles from lane `lane` of block `block`.
fn leaf_reference(block: usize, lane: usize, n: usize) -> Result<u32, String> {
    // Two blocks in a row hold more than eight triangles (the second started because the
    // leaf did not fit in the first), so a mesh has at most 2 MAX_TRIANGLES / 9 + 1 blocks.
    if block > LEAF_BLOCK as usize || lane + n > LANES || n == 0 {
        return Err(format!(
            "a BVH leaf of {n} triangles at block {block}, lane {lane}"
        ));
    }
    Ok(LEAF | (((n - 1) << 3 | lane) as u32) << LEAF_LANES | block as u32)
}

// A mesh's blocks fit in the block bits.
const _: () = assert!(2 * MAX_TRIANGLES / (LANES + 1) < LEAF_BLOCK as usize);

/// A node of the eight-wide BVH, made by `collapse`: its children's boxes as floats and
/// their references (decoding obvhs's eight quantised boxes per node visit cost more than
/// reading the larger node). The object BVH's
/// flat layout of small scenes uses it too, its children naming objects.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub(crate) struct WideNode {
    /// Per axis, the children's smallest (side 0; +inf for empty children) and largest
    /// (side 1; -inf) box coordinates. A ray picks each axis's near side by an index made
    /// once per ray, which becomes part of the load's address.
    planes: [[[f32; 8]; 2]; 3],
    /// Per child: an inner node's index, or a leaf reference (see [`LEAF`]).
    pub(crate) child: [u32; 8],
}

impl WideNode {
    /// No children: every box inverted (never met).
    pub(crate) const EMPTY: WideNode = WideNode {
        planes: [[[f32::INFINITY; 8], [f32::NEG_INFINITY; 8]]; 3],
        child: [0; 8],
    };

    /// Puts `child`, with bounds `b`, in slot `i`.
    pub(crate) fn set_child(&mut self, i: usize, b: &Aabb, child: u32) {
        for (axis, [lo, hi]) in self.planes.iter_mut().enumerate() {
            lo[i] = b.min[axis];
            hi[i] = b.max[axis];
        }
        self.child[i] = child;
    }
}

/// Whether the mesh walks test the root node before setting anything else up, so that a ray
/// missing the mesh costs them no more than a test of its bounding box would.
pub(crate) const MESH_ROOT_FIRST: bool = cfg!(all(
    target_arch = "x86_64",
    target_feature = "avx2",
    target_feature = "fma"
));

/// The eight-wide BVH of a mesh, walked nearest child first.
#[derive(Clone, Debug, PartialEq, Default)]
struct WideBvh {
    nodes: Vec<WideNode>,
    /// Levels of nodes below the root, the root included.
    depth: usize,
}

impl WideBvh {
    /// Calls `visit.visit(leaf, t_max)` for every leaf whose box the ray meets before
    /// `t_max` (which `visit` may lower); `visit` returns true to stop. `ORDERED`: nearer
    /// children first (closest-hit queries); otherwise in the order found (any-hit queries).
    #[inline(always)]
    fn walk<const ORDERED: bool>(&self, ray: &Ray, t_max: f32, visit: &mut impl Visit) {
        // Each level pushes at most seven more entries than it pops. A stack sized for the
        // tree at hand: setting up a larger one costs every ray.
        #[cfg(all(
            target_arch = "x86_64",
            target_feature = "avx2",
            target_feature = "fma"
        ))]
        if ORDERED {
            // Its pushes write eight entries, of which up to seven count.
            return match 7 * self.depth + 8 {
                0..=64 => self.walk_nearest::<64>(ray, t_max, visit, &mut [], &mut []),
                65..=160 => self.walk_nearest::<160>(ray, t_max, visit, &mut [], &mut []),
                n => self.walk_nearest::<0>(ray, t_max, visit, &mut vec![0; n], &mut vec![0.0; n]),
            };
        }
        #[cfg(all(
            target_arch = "x86_64",
            target_feature = "avx2",
            target_feature = "fma"
        ))]
        if !ORDERED {
            return match 7 * self.depth + 8 {
                0..=64 => self.walk_any::<64>(ray, t_max, visit, &mut []),
                65..=160 => self.walk_any::<160>(ray, t_max, visit, &mut []),
                n => self.walk_any::<0>(ray, t_max, visit, &mut vec![0; n]),
            };
        }
        match 7 * self.depth + 1 {
            0..=64 => self.walk_with::<ORDERED, 64>(ray, t_max, visit, &mut []),
            65..=160 => self.walk_with::<ORDERED, 160>(ray, t_max, visit, &mut []),
            n => self.walk_with::<ORDERED, 0>(ray, t_max, visit, &mut vec![(0, 0.0); n]),
        }
    }

    /// [`WideBvh::walk`] for closest hits where the build has AVX2 and FMA, with nothing in
    /// a node's visit branching on how many of its children the ray meets: for random rays
    /// that number changes from node to node, and the branches on it (none, one or more
    /// met, the insertion sort of those pushed) were mispredicted about six times a ray
    /// (cachegrind, 11 a random teapot ray in all; 6 with this walk, as many as Embree's).
    ///
    /// The nearest child met is found as the least of eight keys, each an entry distance
    /// with its slot in the three low bits (the children not met get the largest key), and
    /// visited next. The others are pushed in one shuffle and one eight-wide store each for
    /// the children and their distances (a table gives the shuffle that packs the children
    /// a mask names), farthest first by the order obvhs gives a node's slots: sorted by
    /// where their centres lie, so that for a ray of octant `o` the slots `s ^ o` taken from
    /// the highest run front to back (Ylitie et al. 2017).
    #[cfg(all(
        target_arch = "x86_64",
        target_feature = "avx2",
        target_feature = "fma"
    ))]
    #[inline(always)]
    fn walk_nearest<const N: usize>(
        &self,
        ray: &Ray,
        mut t_max: f32,
        visit: &mut impl Visit,
        heap_kids: &mut [u32],
        heap_nears: &mut [f32],
    ) {
        use safe_arch::*;
        if self.nodes.is_empty() {
            return;
        }
        let nr = NodeRay::new(ray);
        // The root's test comes before anything else is set up: a ray that misses the mesh
        // (most camera rays around a model) leaves here.
        let mut node = &self.nodes[0];
        let (mut near, mut missed) = nr.fused_hits(node, t_max);
        if move_mask_m256(cast_to_m256_from_m256i(missed)) == 255 {
            return;
        }
        // The stack, in two arrays (children, their entry distances), each with room for
        // the eight entries a push writes above the top.
        let mut fixed_kids = [0u32; N];
        let mut fixed_nears = [0.0f32; N];
        let (kids, nears): (&mut [u32], &mut [f32]) = if N == 0 {
            (heap_kids, heap_nears)
        } else {
            (&mut fixed_kids, &mut fixed_nears)
        };
        let slots = m256i::from([0, 1, 2, 3, 4, 5, 6, 7]);
        // obvhs's octant of the ray: a set bit for each axis it runs toward plus.
        let octant = (ray.dir.x >= 0.0) as usize * 4
            + (ray.dir.y >= 0.0) as usize * 2
            + (ray.dir.z >= 0.0) as usize;
        let octant_bytes = octant as u64 * 0x0101_0101_0101_0101;
        let mut top = 0usize;
        // Next: the nearest entry left that starts before the hit found so far.
        let pop = |top: &mut usize, kids: &[u32], nears: &[f32], t_max: f32| loop {
            if *top == 0 {
                return None;
            }
            *top -= 1;
            if nears[*top] <= t_max {
                return Some(kids[*top]);
            }
        };
        // At the top of the loop: `node`, an inner node, tested (`near`, `missed`).
        loop {
            let mask = !move_mask_m256(cast_to_m256_from_m256i(missed)) as u32 & 255;
            let mut current = if mask != 0 {
                // Entry distances are at least 0, so their bits order them as unsigned
                // integers do; replacing the three low bits by the slot keeps the keys
                // apart and moves a distance by a few units in the last place at most.
                // The children not met get all ones, the largest key.
                let keys = bitor_m256i(
                    bitor_m256i(bitand_m256i(near, set_splat_i32_m256i(!7)), slots),
                    missed,
                );
                // The least key, in every lane: pairs, then quadruples, then halves.
                let m = min_u32_m256i(keys, shuffle_ai_i32_half_m256i::<0b01_00_11_10>(keys));
                let m = min_u32_m256i(m, shuffle_ai_i32_half_m256i::<0b10_11_00_01>(m));
                let m = min_u32_m256i(m, shuffle_ai_i64_all_m256i::<0b01_00_11_10>(m));
                let slot = get_i32_from_m128i_s(cast_to_m128i_from_m256i(m)) as usize & 7;
                // The nearest child, picked by the key's slot bits in a vector shuffle:
                // shorter than the child's load from the slot's index.
                let children = load_unaligned_m256i(bytemuck::cast_ref(&node.child));
                let next = get_i32_from_m128i_s(cast_to_m128i_from_m256i(shuffle_av_i32_all_m256i(
                    children, m,
                ))) as u32;
                // The others, by rank `s ^ octant` (the top of the stack, visited first, the
                // highest): their ranks' mask packed, then turned back into slots.
                let rest = mask & !(1 << slot);
                let ranked = XOR_BITS[octant][rest as usize & 255];
                let order = convert_to_i16_m256i_from_lower8_u8_m128i(set_i64_m128i_s(
                    (COMPACT[ranked as usize] ^ octant_bytes) as i64,
                ));
                kids[top..top + 8].copy_from_slice(&packed_children(node, order));
                nears[top..top + 8].copy_from_slice(
                    &shuffle_av_i32_all_m256(cast_to_m256_from_m256i(near), order).to_array(),
                );
                top += rest.count_ones() as usize;
                next
            } else {
                // No child met: on to the stack.
                match pop(&mut top, kids, nears, t_max) {
                    Some(c) => c,
                    None => return,
                }
            };
            while current & LEAF != 0 {
                if visit_leaf(current, visit, &mut t_max) {
                    return;
                }
                current = match pop(&mut top, kids, nears, t_max) {
                    Some(c) => c,
                    None => return,
                };
            }
            node = &self.nodes[current as usize];
            (near, missed) = nr.fused_hits(node, t_max);
        }
    }

    /// [`WideBvh::walk`] for any hit where the build has AVX2 and FMA: the first child met is
    /// visited next, the others pushed as [`WideBvh::walk_nearest`] pushes them, in slot
    /// order. Nothing is culled when popped: the limit changes only when the walk ends.
    #[cfg(all(
        target_arch = "x86_64",
        target_feature = "avx2",
        target_feature = "fma"
    ))]
    #[inline(always)]
    fn walk_any<const N: usize>(
        &self,
        ray: &Ray,
        mut t_max: f32,
        visit: &mut impl Visit,
        heap: &mut [u32],
    ) {
        use safe_arch::*;
        if self.nodes.is_empty() {
            return;
        }
        let nr = NodeRay::new(ray);
        // The root's test first, as in `walk_nearest`.
        let mut node = &self.nodes[0];
        let (_, mut missed) = nr.fused_hits(node, t_max);
        if move_mask_m256(cast_to_m256_from_m256i(missed)) == 255 {
            return;
        }
        let mut fixed = [0u32; N];
        let kids: &mut [u32] = if N == 0 { heap } else { &mut fixed };
        let mut top = 0usize;
        // At the top of the loop: `node`, an inner node, tested (`missed`).
        loop {
            let mask = !move_mask_m256(cast_to_m256_from_m256i(missed)) as u32 & 255;
            let mut current = if mask != 0 {
                let rest = mask & (mask - 1);
                let order = convert_to_i16_m256i_from_lower8_u8_m128i(set_i64_m128i_s(
                    COMPACT[rest as usize & 255] as i64,
                ));
                kids[top..top + 8].copy_from_slice(&packed_children(node, order));
                top += rest.count_ones() as usize;
                node.child[mask.trailing_zeros() as usize & 7]
            } else if top == 0 {
                return;
            } else {
                top -= 1;
                kids[top]
            };
            while current & LEAF != 0 {
                if visit_leaf(current, visit, &mut t_max) || top == 0 {
                    return;
                }
                top -= 1;
                current = kids[top];
            }
            node = &self.nodes[current as usize];
            (_, missed) = nr.fused_hits(node, t_max);
        }
    }

    /// [`WideBvh::walk`] with a stack of `N` entries on the machine stack, or `heap` when
    /// `N` is 0 (trees too deep for a fixed array).
    #[inline(always)]
    fn walk_with<const ORDERED: bool, const N: usize>(
        &self,
        ray: &Ray,
        mut t_max: f32,
        visit: &mut impl Visit,
        heap: &mut [(u32, f32)],
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let nr = NodeRay::new(ray);
        let mut fixed = [(0u32, 0.0f32); N];
        let stack: &mut [(u32, f32)] = if N == 0 { heap } else { &mut fixed };
        let mut top = 0;
        // The node or leaf being visited; the root first.
        let mut current = 0u32;
        loop {
            if current & LEAF == 0 {
                let node = &self.nodes[current as usize];
                let (nears, mut mask) = nr.hits(node, t_max);
                if mask != 0 && mask & (mask - 1) == 0 {
                    // One child met (the common case deep down): go straight on.
                    // (`& 7`: the compiler cannot tell that an eight-bit mask's lowest set
                    // bit is below 8, and would check the index.)
                    current = node.child[mask.trailing_zeros() as usize & 7];
                    continue;
                }
                if mask != 0 {
                    // Push the children met, sorted, and go on with the nearest.
                    let base = top;
                    while mask != 0 {
                        let k = mask.trailing_zeros() as usize & 7;
                        mask &= mask - 1;
                        let child = node.child[k];
                        if child & LEAF != 0 {
                            // Its triangles are tested after the nearer children: start
                            // fetching them now (random rays through the bunny miss the
                            // cache there most).
                            visit.prefetch(child & !LEAF);
                        } else if let Some(n) = self.nodes.get(child as usize) {
                            // So are an inner node's boxes and children: its four cache
                            // lines too (random rays through the bunny: 4 to 11 % faster).
                            crate::math::prefetch(&n.planes[0]);
                            crate::math::prefetch(&n.planes[1]);
                            crate::math::prefetch(&n.planes[2]);
                            crate::math::prefetch(&n.child);
                        }
                        push_child::<ORDERED>(stack, base, &mut top, (child, nears[k]));
                    }
                    top -= 1;
                    current = stack[top].0;
                    continue;
                }
            } else {
                if visit_leaf(current, visit, &mut t_max) {
                    return;
                }
            }
            // Next: the nearest entry left that starts before the hit found so far.
            loop {
                if top == 0 {
                    return;
                }
                top -= 1;
                let (r, near) = stack[top];
                if near <= t_max {
                    current = r;
                    break;
                }
            }
        }
    }
}

/// Tests the triangles of leaf reference `leaf`; true when `visit` stops the walk.
#[inline(always)]
fn visit_leaf(leaf: u32, visit: &mut impl Visit, t_max: &mut f32) -> bool {
    visit.visit(leaf & !LEAF, t_max)
}

/// `node`'s children in the slots `order` names, lane by lane (the walks' pushes).
#[cfg(all(
    target_arch = "x86_64",
    target_feature = "avx2",
    target_feature = "fma"
))]
#[inline(always)]
fn packed_children(node: &WideNode, order: safe_arch::m256i) -> [u32; 8] {
    use safe_arch::*;
    let children = load_unaligned_m256i(bytemuck::cast_ref(&node.child));
    bytemuck::cast(<[i32; 8]>::from(shuffle_av_i32_all_m256i(children, order)))
}

/// For each eight-bit mask, the positions of its set bits in ascending order, one a byte
/// (the bytes past them 0): the shuffle that packs the children a mask names.
#[cfg(all(
    target_arch = "x86_64",
    target_feature = "avx2",
    target_feature = "fma"
))]
static COMPACT: [u64; 256] = {
    let mut table = [0u64; 256];
    let mut mask = 0;
    while mask < 256 {
        let (mut bit, mut n, mut packed) = (0, 0, 0u64);
        while bit < 8 {
            if mask & (1 << bit) != 0 {
                packed |= (bit as u64) << (8 * n);
                n += 1;
            }
            bit += 1;
        }
        table[mask] = packed;
        mask += 1;
    }
    table
};

/// `XOR_BITS[o][m]`: mask `m` with bit `i` moved to bit `i ^ o`.
#[cfg(all(
    target_arch = "x86_64",
    target_feature = "avx2",
    target_feature = "fma"
))]
static XOR_BITS: [[u8; 256]; 8] = {
    let mut table = [[0u8; 256]; 8];
    let mut o = 0;
    while o < 8 {
        let mut mask = 0;
        while mask < 256 {
            let mut bit = 0;
            let mut out = 0u8;
            while bit < 8 {
                if mask & (1 << bit) != 0 {
                    out |= 1 << (bit ^ o);
                }
                bit += 1;
            }
            table[o][mask] = out;
            mask += 1;
        }
        o += 1;
    }
    table
};

/// Widens every box's far side by this factor, so rounding never culls a box the ray only
/// grazes or a box with no thickness. The node test folds it into the inverse direction it
/// multiplies the far sides by (one multiply less on the way to the next node); the
/// product's own rounding, a few parts in 10^7, is far below it.
const SLACK: f32 = 1.0 + 1e-5;

/// Area-weighted vertex normals: each triangle adds its unnormalised normal (whose length is
/// twice its area) to its three corners.
pub fn area_weighted_normals(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
    let mut normals = vec![Vec3::ZERO; positions.len()];
    for t in triangles {
        let Some(p) = t
            .iter()
            .map(|&k| positions.get(k as usize).copied())
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        let n = (p[1] - p[0]).cross(p[2] - p[0]);
        if n.is_finite() {
            for &k in t {
                normals[k as usize] += n;
            }
        }
    }
    for n in &mut normals {
        *n = n.normalize_or_zero();
    }
    normals
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::triangle::WatertightRay;
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
    }

    /// The test of a block's triangles at once gives, lane by lane, what the scalar
    /// watertight test gives, for rays in every direction (so every choice of axes and
    /// winding) and rays aimed at corners and edges, where the test falls back to double
    /// precision; and it never reports a lane it was not asked about (another leaf's).
    #[test]
    fn block_test_agrees_with_the_scalar_watertight_test() {
        let mut rng = Rng::new(11);
        let mut r = |lo: f32, hi: f32| lo + (hi - lo) * rng.next_f32();
        for case in 0..12000 {
            let corners: [Vec3A; 3] =
                std::array::from_fn(|_| Vec3A::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0)));
            // A leaf of `n` triangles from lane `first`, the triangle in one of its lanes,
            // the others random; the lanes outside the leaf random, or (every other case)
            // copies of the triangle, which must not be reported.
            let n = 1 + (case / 4) % LANES;
            let first = (case / 32) % (LANES + 1 - n);
            let lane = first + case % n;
            let leaf = ((1 << n) - 1) << first;
            let mut tris: [[Vec3A; 3]; LANES] = std::array::from_fn(|_| {
                std::array::from_fn(|_| Vec3A::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0)))
            });
            tris[lane] = corners;
            for (l, t) in tris.iter_mut().enumerate() {
                if leaf & (1 << l) == 0 && case % 2 == 0 {
                    *t = corners;
                }
            }
            let block = TriangleBlock::new(&tris);
            let origin = Vec3A::new(r(-3.0, 3.0), r(-3.0, 3.0), r(-3.0, 3.0));
            // Aimed at a corner, a point on an edge, or anywhere near the triangle.
            let (a, b) = (case % 3, (case + 1) % 3);
            let target = match case % 4 {
                0 => corners[a],
                1 => corners[a].lerp(corners[b], r(0.0, 1.0)),
                _ => Vec3A::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0)),
            };
            if target == origin {
                continue;
            }
            let ray = Ray::new(origin, target - origin);
            let t_max = if case % 5 == 0 {
                r(0.0, 2.0)
            } else {
                f32::INFINITY
            };
            let scalar =
                WatertightRay::new(&ray).intersect(corners[0], corners[1], corners[2], t_max);
            let hits = BlockRay::new(&ray).lanes(&block, leaf, t_max);
            let lanes = (hits.mask & (1 << lane) != 0).then(|| hits.get(lane));
            // `==` on floats, so a zero weight may differ in sign only.
            assert_eq!(lanes, scalar, "case {case}");
            assert_eq!(hits.mask & !leaf, 0, "case {case}: a lane outside the leaf");
            // The test of builds without AVX, in two halves, finds the same.
            let halves = BlockRay::new(&ray).lanes_in_halves(&block, leaf, t_max);
            assert_eq!(halves.mask, hits.mask, "case {case}");
            for l in (0..LANES).filter(|l| hits.mask & (1 << l) != 0) {
                assert_eq!(halves.get(l), hits.get(l), "case {case}");
            }
            // The nearest lane is the nearest of the leaf's triangles tested one by one.
            let one_by_one = (first..first + n)
                .filter_map(|l| {
                    let [a, b, c] = block.corners(l);
                    WatertightRay::new(&ray)
                        .intersect(a, b, c, t_max)
                        .map(|h| (l, h))
                })
                .fold(
                    None,
                    |best: Option<(usize, (f32, f32, f32))>, h| match best {
                        Some(b) if b.1.0 <= h.1.0 => Some(b),
                        _ => Some(h),
                    },
                );
            assert_eq!(hits.nearest(), one_by_one, "case {case}");
        }
    }

    /// A closed unit cube from 12 triangles, outward winding.
    fn cube() -> MeshInput {
        let positions: Vec<Vec3> = (0..8)
            .map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32))
            .collect();
        let quads = [
            [0, 2, 3, 1], // z = 0, facing -z
            [4, 5, 7, 6], // z = 1
            [0, 1, 5, 4], // y = 0
            [2, 6, 7, 3], // y = 1
            [0, 4, 6, 2], // x = 0
            [1, 3, 7, 5], // x = 1
        ];
        let triangles = quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        MeshInput {
            positions,
            triangles,
            ..Default::default()
        }
    }

    #[test]
    fn closed_cube_is_hit_from_outside_and_inside() {
        let (m, dropped) = Mesh::new(cube()).unwrap();
        assert_eq!((m.triangle_count(), dropped), (12, 0));
        let ray = Ray::new(Vec3A::new(0.3, 0.4, 5.0), Vec3A::NEG_Z);
        let h = m.intersect(&ray, f32::INFINITY).unwrap();
        assert!((h.t - 4.0).abs() < 1e-6);
        let s = m.surface(&h);
        assert!(
            (s.normal - Vec3A::Z).length() < 1e-6,
            "outward normal {}",
            s.normal
        );
        assert!((s.point - Vec3A::new(0.3, 0.4, 1.0)).length() < 1e-6);
        // From inside, the far side.
        let inside = Ray::new(Vec3A::splat(0.5), Vec3A::X);
        let h = m.intersect(&inside, f32::INFINITY).unwrap();
        assert!((h.t - 0.5).abs() < 1e-6);
        assert!(m.intersect(&inside, 0.4).is_none(), "t_max respected");
        assert!(m.occluded(&inside, 0.6) && !m.occluded(&inside, 0.4));
        // A miss.
        let miss = Ray::new(Vec3A::new(2.0, 2.0, 5.0), Vec3A::NEG_Z);
        assert!(m.intersect(&miss, f32::INFINITY).is_none());
    }

    #[test]
    fn directions_of_minus_zero_hit_like_plus_zero() {
        // A direction component of -0 (as a reflection or a transform can give) has an
        // inverse of -inf: the node test must then treat the axis as running backwards, or
        // every box's slab comes out empty and the ray misses the mesh.
        let (m, _) = Mesh::new(cube()).unwrap();
        let top = Vec3A::new(0.3, 0.4, 1.0);
        let side = Vec3A::new(1.0, 0.4, 0.3);
        for (dir, entry) in [
            (Vec3A::new(-0.0, -0.0, -1.0), top),
            (Vec3A::new(-0.0, 0.0, -1.0), top),
            (Vec3A::new(0.0, -0.0, -1.0), top),
            (Vec3A::new(-1.0, -0.0, -0.0), side),
        ] {
            let ray = Ray::new(entry - dir * 5.0, dir);
            let h = m.intersect(&ray, f32::INFINITY);
            assert!(h.is_some_and(|h| (h.t - 5.0).abs() < 1e-5), "{dir}: {h:?}");
            assert!(m.occluded(&ray, f32::INFINITY), "{dir}");
        }
    }

    #[test]
    fn no_ray_slips_through_shared_edges() {
        // A flat grid of 2 x 32 x 32 triangles sharing edges and vertices: rays aimed at the
        // edges and vertices themselves (where each triangle's test is at its limit) must
        // all hit, from every direction.
        let n = 32;
        let positions: Vec<Vec3> = (0..=n)
            .flat_map(|j| {
                (0..=n).map(move |i| Vec3::new(i as f32 / n as f32, j as f32 / n as f32, 0.0))
            })
            .collect();
        let idx = |i: u32, j: u32| j * (n + 1) + i;
        let mut triangles = vec![];
        for j in 0..n {
            for i in 0..n {
                triangles.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
                triangles.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
            }
        }
        let (m, _) = Mesh::new(MeshInput {
            positions,
            triangles,
            ..Default::default()
        })
        .unwrap();
        let mut rng = Rng::new(7);
        let mut misses = 0;
        for k in 0..20_000 {
            // Targets on the grid lines (and the diagonals), strictly inside the grid.
            let a = 1 + (rng.next_f32() * (n - 1) as f32) as u32;
            let f = rng.next_f32();
            let target = match k % 3 {
                0 => Vec3A::new(a as f32 / n as f32, f * 0.9 + 0.05, 0.0),
                1 => Vec3A::new(f * 0.9 + 0.05, a as f32 / n as f32, 0.0),
                _ => {
                    let b = 1 + (rng.next_f32() * (n - 1) as f32) as u32;
                    let t = rng.next_f32() / n as f32;
                    Vec3A::new(a as f32 / n as f32 + t, b as f32 / n as f32 + t, 0.0)
                }
            };
            let dir = Vec3A::new(
                rng.next_f32() - 0.5,
                rng.next_f32() - 0.5,
                -(0.05 + rng.next_f32()),
            )
            .normalize();
            let origin = target - dir * (1.0 + 3.0 * rng.next_f32());
            let ray = Ray::new(origin, dir);
            if m.intersect(&ray, f32::INFINITY).is_none() {
                let wt = super::super::triangle::WatertightRay::new(&ray);
                let brute = (0..m.triangle_count() as u32).any(|p| {
                    let [a, b, c] = m.corners(p);
                    wt.intersect(a, b, c, f32::INFINITY).is_some()
                });
                eprintln!("miss k={k} target={target} brute={brute}");
                misses += 1;
            }
        }
        assert_eq!(misses, 0, "rays slipped between triangles");
    }

    #[test]
    fn smooth_normals_and_uvs_are_interpolated() {
        let input = MeshInput {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            normals: vec![Vec3::Z, Vec3::new(1.0, 0.0, 1.0).normalize(), Vec3::Z],
            uvs: vec![Vec2::ZERO, Vec2::new(1.0, 0.0), Vec2::new(0.0, 2.0)],
            triangles: vec![[0, 1, 2]],
            triangle_slots: vec![],
        };
        let (m, _) = Mesh::new(input).unwrap();
        let h = m
            .intersect(&Ray::new(Vec3A::new(0.5, 0.25, 1.0), Vec3A::NEG_Z), 10.0)
            .unwrap();
        assert!((h.bary - Vec2::new(0.5, 0.25)).length() < 1e-6);
        let s = m.surface(&h);
        assert!((s.uv - Vec2::new(0.5, 0.5)).length() < 1e-6);
        let n = m.interpolated_normal(&h).unwrap();
        assert!(n.x > 0.1 && n.z > 0.5 && (n.length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn bad_input_is_refused_and_degenerate_triangles_dropped() {
        let mut c = cube();
        c.triangles.push([0, 1, 99]);
        assert!(Mesh::new(c).unwrap_err().contains("vertex 99"));
        let mut c = cube();
        c.triangles.push([0, 1, 1]);
        c.triangles.push([0, 1, 1]);
        assert_eq!(Mesh::new(c).unwrap().1, 2);
        let flat = MeshInput {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0],
            triangles: vec![[0, 1, 2]],
            ..Default::default()
        };
        assert!(Mesh::new(flat).unwrap_err().contains("zero area"));
    }

    #[test]
    fn area_weighted_normals_favour_big_triangles() {
        // A big triangle facing +z and a small one facing +x share vertex 0.
        let positions = vec![Vec3::ZERO, Vec3::X * 10.0, Vec3::Y * 10.0, Vec3::Y, Vec3::Z];
        let n = area_weighted_normals(&positions, &[[0, 1, 2], [0, 3, 4]]);
        assert!(n[0].z > 0.99 && n[0].x > 0.0, "{}", n[0]);
        assert!((n[3] - Vec3::X).length() < 1e-6);
    }

    /// A soup of `count` separate small triangles in the cube [-1, 1]^3: each has its corners
    /// within `size` of a random centre along each axis.
    fn soup(rng: &mut Rng, count: u32, size: f32) -> MeshInput {
        let mut r = |lo: f32, hi: f32| lo + (hi - lo) * rng.next_f32();
        let mut positions = vec![];
        let mut triangles = vec![];
        for i in 0..count {
            let c = Vec3::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0));
            for _ in 0..3 {
                positions.push(c + Vec3::new(r(-size, size), r(-size, size), r(-size, size)));
            }
            triangles.push([3 * i, 3 * i + 1, 3 * i + 2]);
        }
        MeshInput {
            positions,
            triangles,
            ..MeshInput::default()
        }
    }

    /// Leaves share blocks: each leaf's lanes lie in one block, no lane belongs to two
    /// leaves, and the leaves' lanes hold every triangle once; lanes no leaf names repeat
    /// one of their block's.
    #[test]
    fn leaves_are_packed_into_blocks_and_hold_every_triangle_once() {
        let input = soup(&mut Rng::new(5), 2000, 0.1);
        let triangles = input.triangles.clone();
        let (m, dropped) = Mesh::new(input).unwrap();
        assert_eq!(dropped, 0);
        let mut owner = vec![None; m.faces.len()];
        let mut leaves = 0;
        for (i, node) in m.bvh.nodes.iter().enumerate() {
            for &child in node.child.iter().filter(|&&c| c & LEAF != 0) {
                let block = (child & LEAF_BLOCK) as usize;
                let lanes = LEAF_LANE_MASKS[(child >> LEAF_LANES) as usize & 63];
                assert!(lanes != 0 && block < m.blocks.len(), "{child:#x}");
                for lane in (0..LANES).filter(|l| lanes & (1 << l) != 0) {
                    let prim = block * LANES + lane;
                    assert_eq!(owner[prim], None, "triangle {prim} in two leaves");
                    owner[prim] = Some(i);
                }
                leaves += 1;
            }
        }
        let mut held: Vec<[u32; 3]> = (0..m.faces.len())
            .filter(|&p| owner[p].is_some())
            .map(|p| m.faces[p])
            .collect();
        held.sort();
        let mut all = triangles;
        all.sort();
        assert_eq!(held, all);
        for (p, face) in m.faces.iter().enumerate() {
            let block = &m.faces[p / LANES * LANES..][..LANES];
            assert!(owner[p].is_some() || block.contains(face));
            assert_eq!(m.corners(p as u32), m.blocks[p / LANES].corners(p % LANES));
        }
        // Most leaves hold fewer than eight triangles, and blocks are shared.
        assert_eq!(m.triangle_count(), 2000);
        assert!(
            m.blocks.len() < leaves,
            "{} blocks, {leaves} leaves",
            m.blocks.len()
        );
        assert!(
            m.blocks.len() * LANES < 2000 * 11 / 10,
            "{} blocks",
            m.blocks.len()
        );
    }

    #[test]
    fn walks_find_the_hit_that_testing_every_triangle_finds() {
        // A soup of small triangles in a cube, so that rays cross many overlapping boxes
        // and the order of visits matters; rays from inside and outside it, in random
        // directions and along the axes (zero and minus-zero components).
        let mut rng = Rng::new(17);
        let (m, _) = Mesh::new(soup(&mut rng, 3000, 0.2)).unwrap();
        let mut r = |lo: f32, hi: f32| lo + (hi - lo) * rng.next_f32();
        let (mut hits, mut misses) = (0, 0);
        for case in 0..3000 {
            let o = Vec3A::new(r(-1.5, 1.5), r(-1.5, 1.5), r(-1.5, 1.5));
            let mut d = Vec3A::new(r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0));
            match case % 5 {
                1 => (d.x, d.y) = (0.0, -0.0),
                2 => d.z = -0.0,
                _ => {}
            }
            let ray = Ray::new(o, d);
            // Every triangle, one by one, with the same test the walks use.
            let scalar = WatertightRay::new(&ray);
            let mut nearest: Option<(f32, u32)> = None;
            for p in 0..m.faces.len() as u32 {
                let limit = nearest.map_or(f32::INFINITY, |n| n.0);
                let [a, b, c] = m.corners(p);
                if let Some((t, _, _)) = scalar.intersect(a, b, c, limit) {
                    nearest = Some((t, p));
                }
            }
            let found = m.intersect(&ray, f32::INFINITY).map(|h| (h.t, h.prim));
            assert_eq!(found, nearest, "{ray:?}");
            // The portable walks (the only ones in builds without AVX2 and FMA) agree too.
            let mut query = TriangleQuery::<false> {
                blocks: &m.blocks,
                source: &ray,
                ray: None,
                hit: None,
            };
            m.bvh
                .walk_with::<true, 160>(&ray, f32::INFINITY, &mut query, &mut []);
            assert_eq!(query.hit.map(|h| (h.t, h.prim)), nearest, "{ray:?}");
            let mut any = TriangleQuery::<true> {
                blocks: &m.blocks,
                source: &ray,
                ray: None,
                hit: None,
            };
            m.bvh
                .walk_with::<false, 160>(&ray, f32::INFINITY, &mut any, &mut []);
            assert_eq!(any.hit.is_some(), nearest.is_some(), "{ray:?}");
            assert_eq!(
                m.occluded(&ray, f32::INFINITY),
                nearest.is_some(),
                "{ray:?}"
            );
            // Nothing is nearer than the nearest.
            if let Some((t, _)) = nearest {
                assert_eq!(m.intersect(&ray, t), None, "{ray:?}");
                hits += 1;
            } else {
                misses += 1;
            }
        }
        assert!(hits > 1000 && misses > 300, "{hits} hits, {misses} misses");
    }

    #[test]
    fn coincident_triangles_are_all_found_through_a_deep_bvh() {
        // Found by the `mesh` fuzz target: an OBJ whose polygons repeat the same corners
        // gives hundreds of coincident triangles, and obvhs builds them into a chain so deep
        // that its own debug validation (off in snell's builds) rejects it. The eight-wide
        // BVH snell traverses must still find every hit, and the other triangle beside them.
        let positions = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(5.0, 0.0, 0.0),
            Vec3::new(6.0, 0.0, 0.0),
            Vec3::new(5.0, 1.0, 0.0),
        ];
        let mut triangles = vec![[0, 1, 2]; 2000];
        triangles.push([3, 4, 5]);
        let (m, dropped) = Mesh::new(MeshInput {
            positions,
            triangles,
            ..MeshInput::default()
        })
        .unwrap();
        assert_eq!((m.triangle_count(), dropped), (2001, 0));
        for i in 0..50 {
            let (x, y) = (0.05 + (i % 10) as f32 * 0.05, 0.05 + (i / 10) as f32 * 0.05);
            for (ox, dz) in [(0.0, -1.0), (0.0, 1.0), (5.0, -1.0), (5.0, 1.0)] {
                let ray = Ray::new(Vec3A::new(ox + x, y, -3.0 * dz), Vec3A::new(0.0, 0.0, dz));
                let hit = m.intersect(&ray, f32::INFINITY);
                assert!(hit.is_some_and(|h| (h.t - 3.0).abs() < 1e-5), "{ray:?}");
                assert!(m.occluded(&ray, f32::INFINITY), "{ray:?}");
            }
        }
    }
}
