//! A mesh's binary BVH (obvhs's PLOC build) collapsed into the eight-wide tree the mesh walks,
//! with leaves of up to eight triangles, which the walk tests at once (in the lanes of a
//! [`TriangleBlock`], which leaves share: see `Mesh::new`).
//!
//! The collapse is the dynamic programme of Ylitie, Karras and Laine ("Efficient incoherent
//! ray traversal on GPUs through compressed wide BVHs", HPG 2017), which obvhs also uses for
//! its compressed BVH, but with costs for this walk: obvhs's leaves hold at most three
//! triangles, each tested on its own (its triangle cost is a third of a node's, made for
//! GPUs), while here a leaf of one to eight triangles costs one eight-lane test, about as
//! much as a node's box test, so leaves grow and the tree gets a level shallower. The child
//! boxes are the binary tree's exact boxes, not obvhs's quantised ones (which are larger by
//! up to 1/128 of the parent's size per side: rays met more boxes).
//!
//! [`TriangleBlock`]: super::triangle::TriangleBlock

use super::{LEAF, WideNode};
use crate::math::{Aabb, Vec3A};
use obvhs::bvh2::Bvh2;

/// Most triangles in a leaf: the eight lanes of a block, tested in one AVX step, which costs
/// about what a four-lane test does, so larger leaves make a shallower, smaller tree for
/// little more work. (Leaves of up to four, in blocks of four lanes, were slower and their
/// trees larger; leaves of eight as two four-lane blocks tested one after the other gained
/// nothing over those: docs/perf-log.md.)
pub(crate) const LEAF_SIZE: usize = 8;

/// What the walk pays to test a node's eight boxes, in the units of the SAH (per unit of a
/// box's half area).
const NODE_COST: f32 = 1.0;
/// What it pays to test a leaf of up to eight triangles, in the same units (0.4 to 2.4 made
/// no measurable difference with leaves of four, 0.5 to 1.6 none with leaves of eight).
const LEAF_COST: f32 = 0.8;

/// The eight-wide tree: nodes (the root first) and, per leaf, its triangles (indices into
/// the primitives the binary tree was built over; a leaf reference `LEAF | k` names the
/// `k`-th). A tree of one leaf has a root with that one child.
pub(crate) struct Collapsed {
    pub(crate) nodes: Vec<WideNode>,
    pub(crate) leaves: Vec<Vec<u32>>,
    /// Levels of nodes, the root included.
    pub(crate) depth: usize,
}

/// How a binary node stands for its subtree when it may take `i` slots of its parent.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Choice {
    /// One slot: a leaf of all its triangles.
    Leaf,
    /// One slot: a wide node, whose children are the slots of its two children, `k` of them
    /// from the first and the rest from the second.
    Node { k: u8 },
    /// `k` slots from the first child and `i - k` from the second.
    Split { k: u8 },
}

/// Collapses `bvh2` (leaves of one primitive each, as PLOC builds them) into an eight-wide
/// tree. Fails when a leaf holds more than [`LEAF_SIZE`] primitives (a binary tree not
/// built that way), never panics.
pub(crate) fn collapse(bvh2: &Bvh2) -> Result<Collapsed, String> {
    let nodes = &bvh2.nodes;
    if nodes.is_empty() {
        return Ok(Collapsed {
            nodes: vec![WideNode::EMPTY],
            leaves: vec![],
            depth: 1,
        });
    }
    let n = nodes.len();
    // cost[m][i - 1] and choice[m][i - 1]: the least cost of node m's subtree in i slots.
    let mut cost = vec![[0.0f32; 8]; n];
    let mut choice = vec![[Choice::Leaf; 8]; n];
    let mut count = vec![0u32; n];
    // Children before parents, without recursion (a degenerate mesh can make a deep tree).
    let mut order = Vec::with_capacity(n);
    let mut todo = vec![0u32];
    while let Some(m) = todo.pop() {
        order.push(m);
        let node = &nodes[m as usize];
        if node.prim_count == 0 {
            todo.push(node.first_index);
            todo.push(node.first_index + 1);
        }
    }
    for &m in order.iter().rev() {
        let m = m as usize;
        let node = &nodes[m];
        let area = node.aabb().half_area();
        if node.prim_count != 0 {
            if node.prim_count as usize > LEAF_SIZE {
                return Err(format!(
                    "a BVH leaf of {} triangles (at most {LEAF_SIZE} expected)",
                    node.prim_count
                ));
            }
            count[m] = node.prim_count;
            cost[m] = [area * LEAF_COST; 8];
            continue;
        }
        let (l, r) = (node.first_index as usize, node.first_index as usize + 1);
        count[m] = count[l] + count[r];
        // The best way to give the two children `i` slots between them (i from 2 to 8).
        let split = |i: usize| -> (f32, u8) {
            (1..i)
                .map(|k| (cost[l][k - 1] + cost[r][i - k - 1], k as u8))
                .fold((f32::INFINITY, 0), |a, b| if b.0 < a.0 { b } else { a })
        };
        let (spread, k) = split(8);
        let as_node = (area * NODE_COST + spread, Choice::Node { k });
        let as_leaf = if count[m] as usize <= LEAF_SIZE {
            area * LEAF_COST
        } else {
            f32::INFINITY
        };
        let one = if as_leaf <= as_node.0 {
            (as_leaf, Choice::Leaf)
        } else {
            as_node
        };
        let mut best = [(0.0, Choice::Leaf); 8];
        best[0] = one;
        for i in 2..=8 {
            let (c, k) = split(i);
            best[i - 1] = if c < best[i - 2].0 {
                (c, Choice::Split { k })
            } else {
                best[i - 2]
            };
        }
        cost[m] = best.map(|b| b.0);
        choice[m] = best.map(|b| b.1);
    }

    // Build the wide nodes from the root down; a node's children are given their places
    // together, so siblings lie side by side in memory.
    let mut out = Collapsed {
        nodes: vec![WideNode::EMPTY],
        leaves: vec![],
        depth: 1,
    };
    // (binary node, its wide node, that node's level)
    let mut todo = vec![];
    match choice[0][0] {
        Choice::Leaf => {
            let b = to_aabb(nodes[0].aabb());
            let leaf = out.push_leaf(bvh2, 0);
            out.nodes[0].set_child(0, &b, leaf);
            return Ok(out);
        }
        _ => todo.push((0usize, 0usize, 1usize)),
    }
    while let Some((m, wide, level)) = todo.pop() {
        out.depth = out.depth.max(level);
        let Choice::Node { k } = choice[m][0] else {
            unreachable!("only nodes are queued");
        };
        let first = nodes[m].first_index as usize;
        let mut slots = Vec::with_capacity(8);
        gather(&choice, bvh2, first, k as usize, &mut slots);
        gather(&choice, bvh2, first + 1, 8 - k as usize, &mut slots);
        let center = to_aabb(nodes[m].aabb()).center();
        for (slot, &c) in order_slots(bvh2, center, &slots).iter().enumerate() {
            let Some(c) = c else { continue };
            let b = to_aabb(nodes[c].aabb());
            let child = if choice[c][0] == Choice::Leaf {
                out.push_leaf(bvh2, c)
            } else {
                out.nodes.push(WideNode::EMPTY);
                let index = out.nodes.len() - 1;
                todo.push((c, index, level + 1));
                index as u32
            };
            out.nodes[wide].set_child(slot, &b, child);
        }
    }
    Ok(out)
}

impl Collapsed {
    /// Makes binary node `m`'s triangles a leaf; its reference.
    fn push_leaf(&mut self, bvh2: &Bvh2, m: usize) -> u32 {
        let mut prims = vec![];
        let mut todo = vec![m];
        while let Some(m) = todo.pop() {
            let node = &bvh2.nodes[m];
            if node.prim_count == 0 {
                todo.push(node.first_index as usize + 1);
                todo.push(node.first_index as usize);
            } else {
                let first = node.first_index as usize;
                prims.extend_from_slice(
                    &bvh2.primitive_indices[first..][..node.prim_count as usize],
                );
            }
        }
        self.leaves.push(prims);
        LEAF | (self.leaves.len() - 1) as u32
    }
}

/// The binary nodes that fill the `i` slots node `m` was given (its choice for `i` slots).
fn gather(choice: &[[Choice; 8]], bvh2: &Bvh2, m: usize, i: usize, slots: &mut Vec<usize>) {
    match choice[m][i - 1] {
        Choice::Split { k } => {
            let first = bvh2.nodes[m].first_index as usize;
            gather(choice, bvh2, first, k as usize, slots);
            gather(choice, bvh2, first + 1, i - k as usize, slots);
        }
        _ => slots.push(m),
    }
}

/// Places the children (binary nodes) in the eight slots so that, for a ray running toward
/// octant `o` (a set bit for each axis it runs toward plus, x the highest), the slots taken
/// in the order `s ^ o` from the highest down visit them front to back, roughly: slot `s`
/// goes to the child farthest along the direction `(-1)^bits(s)`, chosen greedily, the
/// best pair first (Ylitie et al. 2017).
fn order_slots(bvh2: &Bvh2, center: Vec3A, children: &[usize]) -> [Option<usize>; 8] {
    let dir = |s: usize| {
        Vec3A::new(
            if s & 4 != 0 { -1.0 } else { 1.0 },
            if s & 2 != 0 { -1.0 } else { 1.0 },
            if s & 1 != 0 { -1.0 } else { 1.0 },
        )
    };
    let offsets: Vec<Vec3A> = children
        .iter()
        .map(|&c| to_aabb(bvh2.nodes[c].aabb()).center() - center)
        .collect();
    let mut slots = [None; 8];
    let mut placed = vec![false; children.len()];
    for _ in 0..children.len() {
        let mut best = (f32::INFINITY, 0, 0);
        for (c, off) in offsets.iter().enumerate() {
            if placed[c] {
                continue;
            }
            for (s, slot) in slots.iter().enumerate() {
                let d = dir(s).dot(*off);
                if slot.is_none() && (d < best.0 || best.0 == f32::INFINITY) {
                    best = (d, c, s);
                }
            }
        }
        placed[best.1] = true;
        slots[best.2] = Some(children[best.1]);
    }
    slots
}

fn to_aabb(b: &obvhs::aabb::Aabb) -> Aabb {
    Aabb {
        min: b.min,
        max: b.max,
    }
}
