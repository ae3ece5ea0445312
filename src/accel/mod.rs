//! Finding what a ray hits first: a bounding volume hierarchy over the scene's bounded
//! objects (built with the surface area heuristic), plus a list of unbounded ones (infinite
//! planes) that every ray tests. Meshes and instancing will add levels below the objects.

use crate::geometry::ShapeHit;
use crate::math::{Aabb, Ray, Vec3A};
use crate::scene::Object;

/// Most objects in one leaf.
const LEAF_SIZE: usize = 2;
/// Deepest tree built: below this depth a node becomes a leaf whatever its size, so the
/// traversal stack (one entry per level) can never overflow.
const MAX_DEPTH: usize = 24;

#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    /// Leaf: first index into `order`; inner: index of the first child (the second follows).
    first: u32,
    /// Objects in a leaf; 0 for inner nodes.
    count: u32,
}

/// The objects of a scene, arranged for fast ray queries.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Object indices in leaf order.
    order: Vec<u32>,
    /// Objects with no bounds.
    unbounded: Vec<u32>,
}

/// A ray with what the box test needs precomputed.
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

    /// Where the ray enters the box, if it meets it at some `t` in `[0, t_max]`.
    #[inline(always)]
    fn entry(&self, b: &Aabb, t_max: f32) -> Option<f32> {
        let t0 = (b.min - self.origin) * self.inv_dir;
        let t1 = (b.max - self.origin) * self.inv_dir;
        // `inv_dir` is finite, so no NaN can arise and plain comparisons (cheaper than
        // f32::max, which handles NaN) are exact here.
        let near = t0.min(t1).max(Vec3A::ZERO).max_element();
        let far = t0.max(t1).min(Vec3A::splat(t_max)).min_element();
        // A few ulps of slack so rays grazing an edge are not culled by rounding.
        (near <= far * (1.0 + 4.0 * f32::EPSILON)).then_some(near)
    }
}

impl Bvh {
    /// Builds the hierarchy over the objects' world bounds.
    pub fn build(objects: &[Object]) -> Self {
        let mut bvh = Bvh::default();
        let mut items: Vec<(u32, Aabb)> = vec![];
        for (i, o) in objects.iter().enumerate() {
            match o.world_bounds {
                Some(b) if b.is_finite() => items.push((i as u32, b)),
                _ => bvh.unbounded.push(i as u32),
            }
        }
        if !items.is_empty() {
            bvh.nodes.push(Node {
                bounds: Aabb::EMPTY,
                first: 0,
                count: 0,
            });
            bvh.split(0, &mut items, 1);
        }
        bvh
    }

    fn split(&mut self, node: usize, items: &mut [(u32, Aabb)], depth: usize) {
        let bounds = items.iter().fold(Aabb::EMPTY, |b, (_, ib)| b.union(ib));
        self.nodes[node].bounds = bounds;
        let make_leaf = |bvh: &mut Bvh, items: &[(u32, Aabb)]| {
            bvh.nodes[node].first = bvh.order.len() as u32;
            bvh.nodes[node].count = items.len() as u32;
            bvh.order.extend(items.iter().map(|(i, _)| *i));
        };
        if items.len() <= LEAF_SIZE || depth >= MAX_DEPTH {
            return make_leaf(self, items);
        }
        // Surface area heuristic over every split of the centroid order on each axis.
        let mut best = (f32::INFINITY, 0usize, 0usize);
        for axis in 0..3 {
            items.sort_by(|a, b| a.1.center()[axis].total_cmp(&b.1.center()[axis]));
            let mut right_areas = vec![0.0f32; items.len()];
            let mut acc = Aabb::EMPTY;
            for k in (1..items.len()).rev() {
                acc = acc.union(&items[k].1);
                right_areas[k] = area(&acc);
            }
            let mut left = Aabb::EMPTY;
            for k in 1..items.len() {
                left = left.union(&items[k - 1].1);
                let cost = area(&left) * k as f32 + right_areas[k] * (items.len() - k) as f32;
                if cost < best.0 {
                    best = (cost, axis, k);
                }
            }
        }
        let (_, axis, at) = best;
        items.sort_by(|a, b| a.1.center()[axis].total_cmp(&b.1.center()[axis]));
        let first_child = self.nodes.len();
        for _ in 0..2 {
            self.nodes.push(Node {
                bounds: Aabb::EMPTY,
                first: 0,
                count: 0,
            });
        }
        self.nodes[node].first = first_child as u32;
        let (l, r) = items.split_at_mut(at);
        self.split(first_child, l, depth + 1);
        self.split(first_child + 1, r, depth + 1);
    }

    /// Calls `visit(object, t_max)` for every object whose bounds the ray may meet before
    /// `t_max` (which `visit` lowers as it finds hits), nearer subtrees first. `visit`
    /// returns `Err(())` to stop early.
    #[inline(always)]
    fn traverse(
        &self,
        ray: &Ray,
        mut t_max: f32,
        mut visit: impl FnMut(usize, &mut f32) -> Result<(), ()>,
    ) {
        for &i in &self.unbounded {
            if visit(i as usize, &mut t_max).is_err() {
                return;
            }
        }
        let Some(root) = self.nodes.first() else {
            return;
        };
        let br = BoxRay::new(ray);
        if br.entry(&root.bounds, t_max).is_none() {
            return;
        }
        let mut stack = [0u32; MAX_DEPTH];
        let mut top = 0;
        let mut node = root;
        loop {
            if node.count > 0 {
                for &o in &self.order[node.first as usize..(node.first + node.count) as usize] {
                    if visit(o as usize, &mut t_max).is_err() {
                        return;
                    }
                }
            } else {
                // Test both children here and descend into the nearer, keeping the other.
                let (a, b) = (node.first as usize, node.first as usize + 1);
                let ta = br.entry(&self.nodes[a].bounds, t_max);
                let tb = br.entry(&self.nodes[b].bounds, t_max);
                match (ta, tb) {
                    (Some(x), Some(y)) => {
                        let (near, far) = if x <= y { (a, b) } else { (b, a) };
                        // At most one entry per level below the root: no overflow.
                        stack[top] = far as u32;
                        top += 1;
                        node = &self.nodes[near];
                        continue;
                    }
                    (Some(_), None) => {
                        node = &self.nodes[a];
                        continue;
                    }
                    (None, Some(_)) => {
                        node = &self.nodes[b];
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // Pop the next subtree that is still worth visiting.
            loop {
                if top == 0 {
                    return;
                }
                top -= 1;
                let candidate = &self.nodes[stack[top] as usize];
                if br.entry(&candidate.bounds, t_max).is_some() {
                    node = candidate;
                    break;
                }
            }
        }
    }

    /// The nearest hit in `(0, t_max)`: object index and the shape's hit.
    #[inline]
    pub fn closest_hit(
        &self,
        objects: &[Object],
        ray: &Ray,
        t_max: f32,
    ) -> Option<(usize, ShapeHit)> {
        let mut best = None;
        self.traverse(ray, t_max, |i, limit| {
            if let Some(h) = objects[i].intersect(ray, *limit) {
                *limit = h.t;
                best = Some((i, h));
            }
            Ok(())
        });
        best
    }

    /// Whether any object for which `blocks(i)` holds is hit in `(0, t_max)`; stops at the
    /// first one found.
    #[inline]
    pub fn any_hit(
        &self,
        objects: &[Object],
        ray: &Ray,
        t_max: f32,
        blocks: impl Fn(usize) -> bool,
    ) -> bool {
        let mut found = false;
        self.traverse(ray, t_max, |i, limit| {
            found = blocks(i) && objects[i].intersect(ray, *limit).is_some();
            if found { Err(()) } else { Ok(()) }
        });
        found
    }
}

fn area(b: &Aabb) -> f32 {
    let d = (b.max - b.min).max(Vec3A::ZERO);
    d.x * d.y + d.y * d.z + d.z * d.x
}
