//! A triangle mesh: its own BVH over its triangles (obvhs's PLOC binary tree, collapsed into
//! an eight-wide tree with leaves of up to eight triangles tested at once: see `collapse`),
//! watertight triangle tests, and per-vertex normals and uvs. A mesh is shared
//! (`Arc`) by every object that places it, so a thousand instances cost one copy.

mod colors;
mod second_uv;
mod solid;
mod tangents;

use super::triangle::{BlockRay, LANES, TriangleBlock};
use super::{Intersect, Leaving, ShapeHit, Surface};
use crate::accel::wide::collapse::collapse;
use crate::accel::wide::{LEAF, Visit, WideBvh, WideNode};
use crate::math::{Aabb, Ray, Vec2, Vec3, Vec3A};
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
    /// A second set of them (glTF's `TEXCOORD_1`), or empty.
    pub uvs1: Vec<Vec2>,
    /// Corner indices of each triangle, counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// Per triangle, the index of its material slot (the mesh keeps it per lane, see
    /// [`Mesh::slot`]), or empty.
    pub triangle_slots: Vec<u16>,
    /// Per-vertex tangents (unit `xyz`, the bitangent's sign in `w`: see `tangents`), or
    /// empty.
    pub tangents: Vec<[f32; 4]>,
    /// Per-vertex linear RGB colours, which multiply the base colour, or empty.
    pub colors: Vec<Vec3>,
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
    /// Per block, how many of its lanes hold a triangle of their own (the first lanes).
    filled: Vec<u8>,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
    /// The second set of uvs, or empty (see second_uv.rs).
    uvs1: Vec<Vec2>,
    /// Per-vertex colours, or empty (see colors.rs).
    colors: Vec<Vec3>,
    /// Material slot of each triangle, in BVH order, or empty.
    slots: Vec<u16>,
    /// Per corner of each triangle (`3 prim + k`), where a file gave them or a normal map
    /// asked for them ([`Mesh::ensure_tangents`]).
    tangents: std::sync::OnceLock<Vec<tangents::Tangent>>,
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
            uvs1,
            triangles,
            triangle_slots,
            tangents,
            colors,
        } = input;
        if triangles.len() > MAX_TRIANGLES {
            return Err(format!(
                "{} triangles is more than the {MAX_TRIANGLES} a mesh may have",
                triangles.len()
            ));
        }
        // Each per-vertex array is empty or one entry per vertex.
        for (len, what) in [
            (normals.len(), "normals"),
            (uvs.len(), "uvs"),
            (uvs1.len(), "second uvs"),
            (colors.len(), "colours"),
            (tangents.len(), "tangents"),
        ] {
            if len != 0 && len != positions.len() {
                return Err(format!("{len} {what} for {} vertices", positions.len()));
            }
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
        let corner_tangents = std::sync::OnceLock::new();
        if !tangents.is_empty() {
            let _ = corner_tangents.set(Mesh::corners_of(&faces, &tangents));
        }
        let bvh = WideBvh {
            nodes: wide.nodes,
            depth: wide.depth,
        };
        Ok((
            Mesh {
                blocks,
                faces,
                triangles: kept.len(),
                filled: taken.iter().map(|&n| n as u8).collect(),
                normals,
                uvs,
                uvs1,
                colors,
                slots,
                tangents: corner_tangents,
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
            + self.uvs1.len() * 8
            + self.colors.len() * 12
            + self.slots.len() * 2
            + self.filled.len()
            + self.tangents.get().map_or(0, |t| t.len() * 16)
    }

    /// Every triangle once (unfilled lanes left out), as `(prim, corners)` in object space,
    /// the corners in the order whose `(b - a) x (c - a)` is the front normal a hit on the
    /// triangle reports (see [`Mesh::surface`]; taken where its centre is hit).
    pub fn triangles(&self) -> impl Iterator<Item = (u32, [Vec3A; 3])> + '_ {
        self.filled.iter().enumerate().flat_map(move |(block, &n)| {
            (0..n as usize).map(move |lane| {
                let prim = (block * LANES + lane) as u32;
                let [a, b, c] = self.corners(prim);
                let centre = ShapeHit {
                    t: 0.0,
                    part: 0,
                    prim,
                    bary: Vec2::splat(1.0 / 3.0),
                };
                let flipped = self
                    .interpolated_normal(&centre)
                    .is_some_and(|n| n.dot((b - a).cross(c - a)) < 0.0);
                (prim, if flipped { [a, c, b] } else { [a, b, c] })
            })
        })
    }

    /// The triangle whose lane `prim` is: itself, or for an unfilled lane (which repeats
    /// its block's first triangle) that first triangle.
    #[inline]
    pub fn own_prim(&self, prim: u32) -> u32 {
        let (block, lane) = (prim as usize / LANES, prim as usize % LANES);
        if lane < self.filled[block] as usize {
            prim
        } else {
            (block * LANES) as u32
        }
    }

    /// The number of lanes, filled or not: one more than the largest `prim` a hit reports.
    pub fn lanes(&self) -> usize {
        self.faces.len()
    }

    /// Material slot of triangle `prim` (as reported in a [`ShapeHit`]); 0 without slots.
    #[inline]
    pub fn slot(&self, prim: u32) -> u16 {
        self.slots.get(prim as usize).copied().unwrap_or(0)
    }

    /// Surface details of a hit: the point re-projected from the barycentrics, the geometric
    /// normal (turned to agree with the vertex normals when there are any, since exporters
    /// keep normals consistent more reliably than winding), and the interpolated uv (the
    /// barycentrics when the mesh has none).
    pub fn hit_surface(&self, hit: &ShapeHit) -> Surface {
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

    /// Triangle `prim`'s first corner, and the barycentrics (of the second and third
    /// corners) of an offset in its plane; `None` for a triangle of no area.
    fn barycentrics_in_plane(&self, prim: u32) -> Option<(Vec3A, impl Fn(Vec3A) -> Vec2)> {
        let [a, b, c] = self.corners(prim);
        let (e1, e2) = (b - a, c - a);
        let (d00, d01, d11) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let denom = d00 * d11 - d01 * d01;
        if denom.is_nan() || denom <= 0.0 {
            return None;
        }
        Some((a, move |v: Vec3A| {
            let (d20, d21) = (v.dot(e1), v.dot(e2));
            Vec2::new(
                (d11 * d20 - d01 * d21) / denom,
                (d00 * d21 - d01 * d20) / denom,
            )
        }))
    }

    /// The barycentrics (of the second and third corners) of point `p` (object space) on
    /// triangle `prim` (zero for a triangle of no area).
    pub(super) fn barycentrics(&self, p: Vec3A, prim: u32) -> Vec2 {
        self.barycentrics_in_plane(prim)
            .map_or(Vec2::ZERO, |(a, b)| b(p - a))
    }

    /// How the barycentrics change over an offset `dp` in the plane of triangle `prim`
    /// (zero for a triangle of no area).
    fn barycentric_change(&self, prim: u32, dp: Vec3A) -> Vec2 {
        self.barycentrics_in_plane(prim)
            .map_or(Vec2::ZERO, |(_, b)| b(dp))
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

impl Intersect for Mesh {
    /// Object-space bounds.
    fn bounds(&self) -> Option<Aabb> {
        Some(self.bounds)
    }

    /// Nearest hit with `0 < t < t_max`: the triangle's index and barycentrics come back in
    /// `prim` and `bary`.
    #[inline]
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
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
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        let mut any = TriangleQuery::<true> {
            blocks: &self.blocks,
            source: ray,
            ray: None,
            hit: None,
        };
        self.bvh.walk::<false>(ray, t_max, &mut any);
        any.hit.is_some()
    }

    /// How the uv changes from a hit at `p` to the point `dp` away from it on the triangle's
    /// plane, and the shading normal there: the barycentrics' change times the corners' uvs
    /// (the barycentrics themselves where the mesh has no uvs), and the vertex normals
    /// interpolated there (the face's normal where the mesh has none).
    fn differential(&self, p: Vec3A, hit: &ShapeHit, dp: Vec3A, _want_uv: bool) -> (Vec2, Vec3A) {
        let Some((a, bary_of)) = self.barycentrics_in_plane(hit.prim) else {
            return (Vec2::ZERO, self.hit_surface(hit).normal);
        };
        let hit = &ShapeHit {
            bary: bary_of(p - a),
            ..*hit
        };
        let db = bary_of(dp);
        let f = self.faces[hit.prim as usize];
        let duv = if self.uvs.is_empty() {
            db
        } else {
            let t = |i: usize| self.uvs[f[i] as usize];
            (t(1) - t(0)) * db.x + (t(2) - t(0)) * db.y
        };
        let moved = ShapeHit {
            bary: hit.bary + db,
            ..*hit
        };
        let normal = self
            .interpolated_normal(&moved)
            .unwrap_or_else(|| self.hit_surface(hit).normal);
        (duv, normal)
    }

    fn surface(&self, _p: Vec3A, hit: &ShapeHit, _want_uv: bool) -> Surface {
        self.hit_surface(hit)
    }

    fn leaving(&self) -> Leaving {
        Leaving::MayReturn
    }

    fn kind(&self) -> &'static str {
        "mesh"
    }
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

/// Up to how many triangles a mesh's binary tree is optimised by reinsertion over all its
/// nodes; beyond, over this many of them (at least 5 %, obvhs's `medium_build`), so the
/// build's time keeps in step with the mesh's size. Reinsertion (with PLOC's medium search
/// from depth 1) makes rays through a mesh faster, but it is paid before the first pixel,
/// and over every node of a large mesh its time grows much faster than its rays gain: a
/// small picture of a large mesh would wait on the build (docs/perf-log.md).
const REINSERTION_TRIANGLES: f32 = 20_000.0;

/// How many of the last blocks a leaf may go into, when it has room there. Leaves hold one
/// to eight triangles, so a block per leaf would leave many lanes empty; sharing blocks fills
/// more of them the more blocks a leaf may choose from, and a window this small keeps the
/// leaves near their neighbours in the tree (windows of 4 and 64 measured the same).
/// Full blocks matter because a large mesh's triangles do not fit in the cache, and random
/// rays, which read them from memory, slow down with every byte a block takes
/// (docs/perf-log.md).
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
mod tests;
