//! Building the object BVH: a binary tree by the surface area heuristic over the objects'
//! world bounds, collapsed into the four-wide nodes the walk tests, or one flat node of up
//! to eight children for a small scene.

use super::*;

/// Most objects in one leaf.
const LEAF_SIZE: usize = 1;

/// A node of the binary tree the builder makes, before it is collapsed to four-wide nodes.
#[derive(Clone, Copy, Debug)]
struct BinaryNode {
    bounds: Aabb,
    /// Leaf: first index into `order`; inner: index of the first child (the second follows).
    first: u32,
    /// Objects in a leaf; 0 for inner nodes.
    count: u32,
}

impl Bvh {
    /// Builds the hierarchy over the objects' world bounds: a binary tree by the surface area
    /// heuristic, collapsed to four children per node so one SIMD test covers four boxes.
    pub fn build(objects: &[Object]) -> Self {
        let mut bvh = Bvh::default();
        let mut items: Vec<(u32, Aabb)> = vec![];
        for (i, o) in objects.iter().enumerate() {
            match o.world_bounds {
                Some(b) if b.is_finite() => items.push((i as u32, b)),
                _ => bvh.unbounded.push(i as u32),
            }
        }
        bvh.extent = items
            .iter()
            .map(|(_, b)| b.min.abs().max(b.max.abs()).max_element())
            .fold(0.0, f32::max);
        if !items.is_empty() && items.len() <= FLAT {
            let mut flat = Flat {
                node: WideNode::EMPTY,
                first: items[0].1,
                used: 0,
                lone_walk: items.len() == 1 && {
                    let o = &objects[items[0].0 as usize];
                    o.transform.is_none() && matches!(o.shape, Shape::Mesh(_)) && MESH_ROOT_FIRST
                },
            };
            bvh.flat_bit = vec![0; objects.len()];
            for (k, (i, b)) in items.iter().enumerate() {
                flat.node.set_child(k, b, *i);
                flat.used |= 1 << k;
                bvh.flat_bit[*i as usize] = 1 << k;
            }
            bvh.flat = Some(flat);
        } else if !items.is_empty() {
            let mut binary = vec![BinaryNode {
                bounds: Aabb::EMPTY,
                first: 0,
                count: 0,
            }];
            split(&mut binary, &mut bvh.order, 0, &mut items, 1);
            let root = bvh.collapse(&binary, 0);
            bvh.root = Some((root, binary[0].bounds));
            bvh.depth = bvh.depth_below(root);
        }
        bvh
    }

    /// Levels of four-wide nodes from `r` down.
    fn depth_below(&self, r: u32) -> usize {
        if r & LEAF != 0 {
            return 0;
        }
        let n = &self.nodes[r as usize];
        1 + n
            .child
            .iter()
            .filter(|&&c| c != NO_CHILD)
            .map(|&c| self.depth_below(c))
            .max()
            .unwrap_or(0)
    }

    /// Turns binary node `b` (and its subtree) into four-wide nodes; returns its reference.
    fn collapse(&mut self, binary: &[BinaryNode], b: usize) -> u32 {
        let node = &binary[b];
        if node.count > 0 {
            self.leaves.push((node.first, node.count));
            return LEAF | (self.leaves.len() - 1) as u32;
        }
        // Open the largest inner child until there are four.
        let mut kids = vec![node.first as usize, node.first as usize + 1];
        while kids.len() < 4 {
            let widest = kids
                .iter()
                .enumerate()
                .filter(|(_, k)| binary[**k].count == 0)
                .max_by(|a, b| area(&binary[*a.1].bounds).total_cmp(&area(&binary[*b.1].bounds)));
            let Some((pos, &k)) = widest else {
                break;
            };
            kids.swap_remove(pos);
            kids.push(binary[k].first as usize);
            kids.push(binary[k].first as usize + 1);
        }
        let index = self.nodes.len();
        self.nodes.push(Node4::EMPTY);
        for (lane, &k) in kids.iter().enumerate() {
            let child = self.collapse(binary, k);
            self.nodes[index].set_lane(lane, &binary[k].bounds, child);
        }
        index as u32
    }
}

/// Splits binary node `node` over `items` by the surface area heuristic (every split of the
/// centroid order on each axis), down to `LEAF_SIZE` objects or `MAX_DEPTH` levels.
fn split(
    nodes: &mut Vec<BinaryNode>,
    order: &mut Vec<u32>,
    node: usize,
    items: &mut [(u32, Aabb)],
    depth: usize,
) {
    let bounds = items.iter().fold(Aabb::EMPTY, |b, (_, ib)| b.union(ib));
    nodes[node].bounds = bounds;
    if items.len() <= LEAF_SIZE || depth >= MAX_DEPTH {
        nodes[node].first = order.len() as u32;
        nodes[node].count = items.len() as u32;
        order.extend(items.iter().map(|(i, _)| *i));
        return;
    }
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
    if !best.0.is_finite() || best.2 == 0 {
        // No split has a finite cost (boxes too large for f32 areas): halve by count along
        // the widest axis, which always makes progress.
        let extent = bounds.max - bounds.min;
        let widest = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        best = (0.0, widest, items.len() / 2);
    }
    let (_, axis, at) = best;
    items.sort_by(|a, b| a.1.center()[axis].total_cmp(&b.1.center()[axis]));
    let first_child = nodes.len();
    for _ in 0..2 {
        nodes.push(BinaryNode {
            bounds: Aabb::EMPTY,
            first: 0,
            count: 0,
        });
    }
    nodes[node].first = first_child as u32;
    let (l, r) = items.split_at_mut(at);
    split(nodes, order, first_child, l, depth + 1);
    split(nodes, order, first_child + 1, r, depth + 1);
}

fn area(b: &Aabb) -> f32 {
    let d = (b.max - b.min).max(Vec3A::ZERO);
    d.x * d.y + d.y * d.z + d.z * d.x
}
