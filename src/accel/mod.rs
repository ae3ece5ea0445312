//! Finding what a ray hits first: a bounding volume hierarchy over the scene's bounded
//! objects (built with the surface area heuristic), plus a list of unbounded ones (infinite
//! planes) that every ray tests. A mesh object walks its own BVH below (`geometry::mesh`).

mod build;
mod reach;
pub(crate) mod wide;

use crate::geometry::Object;
use crate::geometry::{Shape, ShapeHit};
use crate::math::{Aabb, LANES, Ray, RayLanes, Vec3A};
use glam::Vec4;
use wide::{MESH_ROOT_FIRST, NodeRay, WideNode};

pub use reach::Reach;

/// Deepest tree built: below this depth a node becomes a leaf whatever its size, so the
/// traversal stack (one entry per level) can never overflow.
const MAX_DEPTH: usize = 16;

/// Marks a child reference as a leaf (index into `leaves`).
const LEAF: u32 = 1 << 31;
/// An unused lane of a four-wide node.
const NO_CHILD: u32 = u32::MAX;
/// Room on the traversal stack: each level pushes at most three more entries than it pops.
const STACK: usize = 3 * MAX_DEPTH + 1;
/// Levels of four-wide nodes a small tree has at most, for a stack that costs less to set up
/// (the seed scene's eight objects make two).
const SMALL_DEPTH: usize = 4;

/// Four children's boxes side by side (structure of arrays), tested against a ray at once.
#[derive(Clone, Copy, Debug)]
struct Node4 {
    min: [Vec4; 3],
    max: [Vec4; 3],
    /// Per lane: an inner node index, `LEAF | leaf index`, or `NO_CHILD`.
    child: [u32; 4],
}

impl Node4 {
    /// No children: every lane's box is inverted and names no child.
    const EMPTY: Node4 = Node4 {
        min: [Vec4::splat(f32::INFINITY); 3],
        max: [Vec4::splat(f32::NEG_INFINITY); 3],
        child: [NO_CHILD; 4],
    };

    /// Puts `child`, with bounds `b`, in lane `lane`.
    fn set_lane(&mut self, lane: usize, b: &Aabb, child: u32) {
        for axis in 0..3 {
            self.min[axis][lane] = b.min[axis];
            self.max[axis][lane] = b.max[axis];
        }
        self.child[lane] = child;
    }
}

/// Scenes with at most this many bounded objects get no tree: their boxes are tested all at
/// once, as the eight children of a mesh BVH node are (one 256-bit step where the build has
/// AVX; a plain box test for a lone object), and the objects met visited nearest first.
/// Small scenes (the seed scene has eight) are what learners write most, and a tree's stack
/// and indirections cost them more than testing every box.
const FLAT: usize = 8;

/// The boxes of a small scene, as one eight-wide node whose children name object indices.
#[derive(Clone, Copy, Debug)]
struct Flat {
    node: WideNode,
    /// The first object's box (the only one, when `used` is 1).
    first: Aabb,
    /// A bit per child slot that holds an object.
    used: u32,
    /// The lone object is a mesh in world space whose walk tests its root node before
    /// anything else: that test is the box test, so the object's own box is not tested
    /// first, which would cost every ray that meets the mesh a second test for nothing.
    lone_walk: bool,
}

/// An object a ray query leaves out: the one whose surface the ray leaves, when it cannot meet
/// it again (a flat shape, or a convex one left through its outside: see
/// [`crate::geometry::Leaving`]). Every ray leaving a surface in the seed scene is such a ray,
/// and the surface's own box, which holds the ray's origin, was the first one its walk
/// visited, for a test that could only miss.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Skip(u32);

impl Skip {
    /// Leaves nothing out.
    pub const NONE: Skip = Skip(u32::MAX);

    /// Leaves out object `i`.
    pub fn object(i: usize) -> Skip {
        Skip(i as u32)
    }
}

/// The objects of a scene, arranged for fast ray queries.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    /// Small scenes: every bounded object's box, instead of a tree.
    flat: Option<Flat>,
    /// Small scenes: per object, the bit of the slot its box has in `flat` (0 for none).
    flat_bit: Vec<u32>,
    nodes: Vec<Node4>,
    /// `(first, count)` ranges of `order`.
    leaves: Vec<(u32, u32)>,
    /// Object indices in leaf order.
    order: Vec<u32>,
    /// Objects with no bounds.
    unbounded: Vec<u32>,
    /// The root's child reference and bounds, when any object is bounded.
    root: Option<(u32, Aabb)>,
    /// Levels of four-wide nodes.
    depth: usize,
    /// The largest coordinate, in size, of any bounded object's box.
    extent: f32,
}

/// A ray with what the box tests need precomputed.
struct BoxRay {
    origin: Vec3A,
    inv_dir: Vec3A,
}

impl BoxRay {
    fn new(ray: &Ray) -> Self {
        // 1/0 = inf would give 0 * inf = NaN for an origin on a slab plane; the largest
        // finite value gives 0 there instead, and still overflows to inf elsewhere.
        let inv = Vec3A::ONE / ray.dir;
        let finite = Vec3A::splat(f32::MAX).copysign(inv);
        BoxRay {
            origin: ray.origin,
            inv_dir: Vec3A::select(inv.abs().cmple(Vec3A::splat(f32::MAX)), inv, finite),
        }
    }

    /// Does the ray meet the box at some `t` in `[0, t_max]`?
    #[inline(always)]
    fn hits(&self, b: &Aabb, t_max: f32) -> bool {
        let t0 = (b.min - self.origin) * self.inv_dir;
        let t1 = (b.max - self.origin) * self.inv_dir;
        // `inv_dir` is finite, so no NaN can arise and SIMD min/max are exact here.
        let near = t0.min(t1).max(Vec3A::ZERO).max_element();
        let far = t0.max(t1).min(Vec3A::splat(t_max)).min_element();
        // A few ulps of slack so rays grazing an edge are not culled by rounding.
        near <= far * (1.0 + 4.0 * f32::EPSILON)
    }

    /// Entry distances into the four boxes of `n`, and a bit per lane whose box the ray
    /// meets in `[0, t_max]`.
    #[inline(always)]
    fn hits4(&self, n: &Node4, t_max: f32) -> (Vec4, u32) {
        let mut near = Vec4::ZERO;
        let mut far = Vec4::splat(t_max);
        for axis in 0..3 {
            let o = Vec4::splat(self.origin[axis]);
            let inv = Vec4::splat(self.inv_dir[axis]);
            let t0 = (n.min[axis] - o) * inv;
            let t1 = (n.max[axis] - o) * inv;
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1));
        }
        (near, near.cmple(far * (1.0 + 4.0 * f32::EPSILON)).bitmask())
    }
}

impl Bvh {
    /// Bytes the hierarchy takes.
    pub fn bytes(&self) -> usize {
        self.flat.map_or(0, |_| std::mem::size_of::<Flat>())
            + self.nodes.len() * std::mem::size_of::<Node4>()
            + self.leaves.len() * 8
            + (self.order.len() + self.unbounded.len() + self.flat_bit.len()) * 4
    }

    /// The largest coordinate, in size, of any bounded object's box (how much rounding a
    /// test against the boxes must allow for).
    pub fn extent(&self) -> f32 {
        self.extent
    }

    /// Calls `visit(object, t_max)` for every object but `skip` whose bounds the ray may
    /// meet before `t_max` (which `visit` lowers as it finds hits), nearer subtrees first.
    /// `visit` returns `Err(())` to stop early.
    #[inline(always)]
    fn traverse<const ORDERED: bool>(
        &self,
        ray: &Ray,
        mut t_max: f32,
        skip: Skip,
        mut visit: impl FnMut(usize, &mut f32) -> Result<(), ()>,
    ) {
        for &i in &self.unbounded {
            if i != skip.0 && visit(i as usize, &mut t_max).is_err() {
                return;
            }
        }
        if let Some(flat) = &self.flat {
            let skip_bit = self.flat_bit.get(skip.0 as usize).copied().unwrap_or(0);
            self.traverse_flat::<ORDERED>(flat, ray, t_max, skip_bit, visit)
        } else if self.depth <= SMALL_DEPTH {
            // Every ray sets up a stack: a small tree needs only a few entries, and filling
            // the full one cost 7 % of the seed scene's time.
            self.traverse_with::<ORDERED, { 3 * SMALL_DEPTH + 1 }>(ray, t_max, skip, visit)
        } else {
            self.traverse_with::<ORDERED, STACK>(ray, t_max, skip, visit)
        }
    }

    /// [`Bvh::traverse`]'s bounded objects for a scene without a tree: all boxes at once
    /// (or the lone object's box), then the objects met but the one in slot `skip_bit`,
    /// nearest box first when `ORDERED`.
    #[inline(always)]
    fn traverse_flat<const ORDERED: bool>(
        &self,
        flat: &Flat,
        ray: &Ray,
        mut t_max: f32,
        skip_bit: u32,
        mut visit: impl FnMut(usize, &mut f32) -> Result<(), ()>,
    ) {
        let used = flat.used & !skip_bit;
        if used == 0 {
            return;
        }
        if flat.used == 1 {
            // One bounded object (a model on an unbounded floor): one box, not a group of
            // eight, or none for a mesh whose walk tests its root first (see `Flat`). (Where
            // the walk sets up its stack before its first test, skipping the box cost rays
            // that miss the mesh a quarter more time.)
            if flat.lone_walk || BoxRay::new(ray).hits(&flat.first, t_max) {
                let _ = visit(flat.node.child[0] as usize, &mut t_max);
            }
            return;
        }
        let (nears, mask) = NodeRay::new(ray).hits(&flat.node, t_max);
        let mut mask = mask & used;
        while mask != 0 {
            let k = if ORDERED {
                // The nearest box left (a handful at most: a linear search beats sorting).
                let mut m = mask;
                let mut k = m.trailing_zeros() as usize;
                m &= m - 1;
                while m != 0 {
                    let j = m.trailing_zeros() as usize;
                    m &= m - 1;
                    if nears[j] < nears[k] {
                        k = j;
                    }
                }
                if nears[k] > t_max {
                    // Every box left starts beyond the hit found.
                    return;
                }
                k
            } else {
                mask.trailing_zeros() as usize
            };
            mask &= !(1 << k);
            if visit(flat.node.child[k] as usize, &mut t_max).is_err() {
                return;
            }
        }
    }

    /// [`Bvh::traverse`]'s bounded objects, through the tree, with a stack of `N` entries,
    /// which must be at least `3 * self.depth + 1`.
    #[inline(always)]
    fn traverse_with<const ORDERED: bool, const N: usize>(
        &self,
        ray: &Ray,
        mut t_max: f32,
        skip: Skip,
        mut visit: impl FnMut(usize, &mut f32) -> Result<(), ()>,
    ) {
        let Some((root, bounds)) = self.root else {
            return;
        };
        let br = BoxRay::new(ray);
        // A root that is a leaf has no four-wide node to test its box.
        if root & LEAF != 0 && !br.hits(&bounds, t_max) {
            return;
        }
        let mut stack = [(0u32, 0.0f32); N];
        stack[0] = (root, 0.0);
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let (r, near) = stack[top];
            if near > t_max {
                continue;
            }
            if r & LEAF != 0 {
                let (first, count) = self.leaves[(r & !LEAF) as usize];
                for &o in &self.order[first as usize..(first + count) as usize] {
                    if o != skip.0 && visit(o as usize, &mut t_max).is_err() {
                        return;
                    }
                }
                continue;
            }
            let n = &self.nodes[r as usize];
            let (nears, mask) = br.hits4(n, t_max);
            // As a plain array: a vector's lane picked by a variable index compiles to a jump
            // table.
            let nears = nears.to_array();
            // Push the children hit, farthest first, so the nearest is visited next.
            let base = top;
            for (lane, (&child, &near)) in n.child.iter().zip(&nears).enumerate() {
                if mask & (1 << lane) != 0 && child != NO_CHILD {
                    push_child::<ORDERED>(&mut stack, base, &mut top, (child, near));
                }
            }
        }
    }

    /// The nearest hit in `(0, t_max)` on any object but `skip`: object index and the
    /// shape's hit.
    #[inline]
    pub fn closest_hit(
        &self,
        objects: &[Object],
        ray: &Ray,
        t_max: f32,
        skip: Skip,
    ) -> Option<(usize, ShapeHit)> {
        let mut best = None;
        self.traverse::<true>(ray, t_max, skip, |i, limit| {
            if let Some(h) = objects[i].intersect(ray, *limit) {
                *limit = h.t;
                best = Some((i, h));
            }
            Ok(())
        });
        best
    }

    /// [`Bvh::closest_hit`] of each of `rays` (one to [`LANES`] of them; `out` as long),
    /// found together where the scene has the flat layout: each ray's boxes are tested as
    /// the walk tests them, then each object is tested once for every ray whose box it is,
    /// spheres and rectangles for all the rays at once. The camera rays of a pixel mostly
    /// meet the same objects, and one vector test does the work of eight, without the
    /// walk's branches and calls.
    ///
    /// The same hits as one walk per ray, to the bit (a test checks it), ties included:
    /// where two objects are hit at exactly the same distance (a cylinder standing on a
    /// floor, seen from inside), the walk keeps the one whose box it entered first, and so
    /// does this.
    ///
    /// Always inlined into the scene's batch query: the inliner left it out of line once
    /// that query grew, and the call, paid on every batch of camera rays, made renders
    /// slower (docs/perf-log.md).
    ///
    /// `reach` says which objects the rays may meet at all (see [`Bvh::reach`]): the others
    /// are not tested, and where that leaves a few spheres or rectangles (a pixel that sees
    /// only the floor, or a ball on it), the packet is tested against each of them, without
    /// the boxes (`closest_among_few`).
    #[inline(always)]
    pub fn closest_hits(
        &self,
        objects: &[Object],
        rays: &[Ray],
        out: &mut [Option<(usize, ShapeHit)>],
        reach: Reach,
    ) {
        assert!(rays.len() <= LANES && out.len() == rays.len());
        let flat = match &self.flat {
            // A lone object is tested against one box, not a group (see traverse_flat).
            Some(flat) if flat.used != 1 && !rays.is_empty() => flat,
            _ => {
                for (ray, o) in rays.iter().zip(out.iter_mut()) {
                    *o = self.closest_hit(objects, ray, f32::INFINITY, Skip::NONE);
                }
                return;
            }
        };
        let used = flat.used & reach.0;
        if used.count_ones() <= FEW
            && self.unbounded.is_empty()
            && closest_among_few(objects, flat, used, rays, out)
        {
            return;
        }
        // Each lane's nearest hit so far, as the walk finds it: unbounded objects first.
        let mut limit = [f32::INFINITY; LANES];
        for (l, ray) in rays.iter().enumerate() {
            out[l] = None;
            for &i in &self.unbounded {
                if let Some(h) = objects[i as usize].intersect(ray, limit[l]) {
                    limit[l] = h.t;
                    out[l] = Some((i as usize, h));
                }
            }
        }
        // For each box, the rays that meet it; for each ray, where it enters each box (the
        // walk's order of visits, which settles ties).
        let mut lanes_of = [0u32; FLAT];
        let mut nears = [[0.0f32; FLAT]; LANES];
        for (l, ray) in rays.iter().enumerate() {
            let (near, mask) = NodeRay::new(ray).hits(&flat.node, limit[l]);
            nears[l] = near;
            let mut m = mask & used;
            while m != 0 {
                lanes_of[m.trailing_zeros() as usize] |= 1 << l;
                m &= m - 1;
            }
        }
        // The slot of each lane's hit, `FLAT` for none or an unbounded object (which the walk
        // met first, so it keeps a tie).
        let mut slot = [FLAT; LANES];
        let packet = RayLanes::new(rays);
        const NO_LIMIT: [f32; LANES] = [f32::INFINITY; LANES];
        for (k, &lanes) in lanes_of.iter().enumerate() {
            if lanes == 0 {
                continue;
            }
            let i = flat.node.child[k] as usize;
            let object = &objects[i];
            // A packet test finds the nearest hit of each lane without a limit, so that it
            // does not wait for the objects before it (which set the lanes' limits): the
            // nearest hit, if below a limit, is what a test below that limit finds. Other
            // tests stop at each lane's distance so far, included, so that a tie is seen.
            let ts = match (&object.transform, &object.shape) {
                (None, Shape::Sphere(s)) => Some(s.intersect_lanes(&packet, &NO_LIMIT)),
                (None, Shape::Rect(r)) => Some(r.intersect_lanes(&packet, &NO_LIMIT)),
                _ => None,
            };
            let mut m = lanes;
            while m != 0 {
                let l = m.trailing_zeros() as usize;
                m &= m - 1;
                // The distance is compared before a hit is made of it: a hit built on the
                // stack and read back at once, a byte and a word written and a double word
                // read, is a load the processor cannot forward from its stores.
                let (t, hit) = match &ts {
                    Some(ts) => (ts[l], None),
                    None => match object.intersect(&rays[l], limit[l].next_up()) {
                        Some(h) => (h.t, Some(h)),
                        None => continue,
                    },
                };
                let first = t < limit[l]
                    || (t == limit[l] && slot[l] < FLAT && nears[l][k] < nears[l][slot[l]]);
                // (An infinite distance is a packet test's miss.)
                if first && t != f32::INFINITY {
                    limit[l] = t;
                    slot[l] = k;
                    // Spheres and rectangles report one part, no triangle.
                    out[l] = Some((
                        i,
                        hit.unwrap_or(ShapeHit {
                            t,
                            part: 0,
                            prim: 0,
                            bary: glam::Vec2::ZERO,
                        }),
                    ));
                }
            }
        }
    }

    /// Whether any object for which `blocks(i)` holds is hit in `(0, t_max)`; stops at the
    /// first one found.
    #[inline]
    pub fn any_hit(
        &self,
        objects: &[Object],
        ray: &Ray,
        t_max: f32,
        skip: Skip,
        blocks: impl Fn(usize) -> bool,
    ) -> bool {
        self.first_blocker_and_others(objects, ray, t_max, skip, blocks)
            .0
            .is_some()
    }

    /// The first object but `skip` found (not necessarily the nearest) for which `blocks(i)`
    /// holds and that the ray hits in `(0, t_max)`, and whether the ray met the bounds of any
    /// other object that does not block (before a blocker was found): when it met none, no
    /// such object but `skip` can be hit in `(0, t_max)` either, and a shadow ray need not
    /// look for glass. Always inlined: its one caller, the shadow ray, is the hottest query
    /// after the camera's, and out of line it paid a call and a frame for each.
    #[inline(always)]
    pub fn first_blocker_and_others(
        &self,
        objects: &[Object],
        ray: &Ray,
        t_max: f32,
        skip: Skip,
        blocks: impl Fn(usize) -> bool,
    ) -> (Option<usize>, bool) {
        let mut found = None;
        let mut others = false;
        self.traverse::<false>(ray, t_max, skip, |i, limit| {
            if !blocks(i) {
                others = true;
                Ok(())
            } else if objects[i].occluded(ray, *limit) {
                found = Some(i);
                Err(())
            } else {
                Ok(())
            }
        });
        (found, others)
    }
}

/// Most objects [`Bvh::closest_hits`] tests against a whole packet each, without boxes.
const FEW: u32 = 3;

/// [`Bvh::closest_hits`] where the rays may meet only the objects in the slots of `used`
/// (at most [`FEW`]), all spheres or rectangles in world space: each is tested against the
/// whole packet at once and each ray keeps its nearest hit (a pixel that sees a ball on a
/// floor). False, with `out` left unfinished, where it cannot say: another kind of object,
/// or two objects at exactly one distance along some ray (a tie the walk settles by the
/// order in which it enters their boxes).
#[inline(always)]
fn closest_among_few(
    objects: &[Object],
    flat: &Flat,
    used: u32,
    rays: &[Ray],
    out: &mut [Option<(usize, ShapeHit)>],
) -> bool {
    const NO_LIMIT: [f32; LANES] = [f32::INFINITY; LANES];
    let packet = RayLanes::new(rays);
    let (mut nearest, mut which) = ([f32::INFINITY; LANES], [0usize; LANES]);
    let mut left = used;
    while left != 0 {
        let i = flat.node.child[left.trailing_zeros() as usize] as usize;
        left &= left - 1;
        let ts = match (&objects[i].transform, &objects[i].shape) {
            (None, Shape::Sphere(s)) => s.intersect_lanes(&packet, &NO_LIMIT),
            (None, Shape::Rect(r)) => r.intersect_lanes(&packet, &NO_LIMIT),
            _ => return false,
        };
        for l in 0..rays.len() {
            // (An infinite distance is a packet test's miss.)
            if ts[l] == nearest[l] && ts[l] != f32::INFINITY {
                return false;
            }
            if ts[l] < nearest[l] {
                (nearest[l], which[l]) = (ts[l], i);
            }
        }
    }
    for ((o, &t), &i) in out.iter_mut().zip(&nearest).zip(&which) {
        *o = (t != f32::INFINITY).then_some((
            i,
            ShapeHit {
                t,
                part: 0,
                prim: 0,
                bary: glam::Vec2::ZERO,
            },
        ));
    }
    true
}

/// Pushes `entry` (a child's reference and where the ray enters its box) on top of
/// `stack[..*top]`. When `ORDERED`, the entries pushed since `base` stay sorted farthest
/// first, so that the nearest child is popped next; any-hit walks stop at the first hit
/// wherever it is and skip the sorting. Shared by the object BVH and the mesh BVHs.
#[inline(always)]
pub(crate) fn push_child<const ORDERED: bool>(
    stack: &mut [(u32, f32)],
    base: usize,
    top: &mut usize,
    entry: (u32, f32),
) {
    let mut at = *top;
    while ORDERED && at > base && stack[at - 1].1 < entry.1 {
        stack[at] = stack[at - 1];
        at -= 1;
    }
    stack[at] = entry;
    *top += 1;
}

#[cfg(test)]
mod tests;
