//! The eight-wide BVH: its nodes, their ray test, and the walks over them. A mesh builds
//! one over its triangles (`collapse` turns obvhs's binary tree into it) and the object BVH's
//! flat layout of small scenes uses its node; the walks reach leaves through [`Visit`], so
//! the triangle test of whoever owns the leaves is inlined into them.

pub(crate) mod collapse;
mod node_ray;

pub(crate) use node_ray::NodeRay;

use crate::accel::push_child;
use crate::math::{Aabb, Ray};

/// What a BVH walk does with the triangles of the leaves it reaches. A trait rather than a
/// closure, so that the triangle test is inlined into the walk.
pub(crate) trait Visit {
    /// Tests the triangles of leaf `leaf`, lowering `t_max` to a hit's distance; true stops
    /// the walk.
    fn visit(&mut self, leaf: u32, t_max: &mut f32) -> bool;
    /// Asks the cache for leaf `leaf`'s triangles, which will be tested soon.
    fn prefetch(&self, leaf: u32);
}

/// Marks a child reference as a leaf. `collapse` makes `LEAF | k` for its `k`-th leaf;
/// [`Mesh::new`] turns that into the leaf's block and lanes ([`leaf_reference`]).
pub(crate) const LEAF: u32 = 1 << 31;

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

    /// The children's boxes: per axis, their smallest coordinates, then their largest.
    pub(crate) fn bounds(&self) -> &[[[f32; 8]; 2]; 3] {
        &self.planes
    }

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
pub(crate) struct WideBvh {
    pub(crate) nodes: Vec<WideNode>,
    /// Levels of nodes below the root, the root included.
    pub(crate) depth: usize,
}

impl WideBvh {
    /// Calls `visit.visit(leaf, t_max)` for every leaf whose box the ray meets before
    /// `t_max` (which `visit` may lower); `visit` returns true to stop. `ORDERED`: nearer
    /// children first (closest-hit queries); otherwise in the order found (any-hit queries).
    #[inline(always)]
    pub(crate) fn walk<const ORDERED: bool>(&self, ray: &Ray, t_max: f32, visit: &mut impl Visit) {
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
    /// met, the insertion sort of those pushed) were half of the walk's mispredictions;
    /// without them it mispredicts about as often as Embree's (docs/perf-log.md).
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
    pub(crate) fn walk_with<const ORDERED: bool, const N: usize>(
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
