//! Constructive solid geometry: the union, intersection or difference of solids (spheres,
//! boxes, capped cylinders and cones, tori, closed meshes, and such combinations nested),
//! each placed by its own transform.
//!
//! The tree is flattened into its leaves, each remembering whether it is subtracted (an
//! odd number of times): its surface then faces the other way on the result. A ray finds
//! every crossing of every leaf's surface, in order, and the first crossing where the
//! combination's inside changes is the hit. Each leaf's crossings are found by asking it
//! for its nearest hit again and again from just past the last one, so two surfaces of one
//! leaf closer than about 1e-5 of its size along the ray count as one.

use super::{Intersect, Leaving, Shape, ShapeHit, Surface};
use crate::math::{Aabb, Ray, Transform, Vec3A};

/// How children combine.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CsgOp {
    /// Inside any child.
    Union,
    /// Inside every child.
    Intersection,
    /// Inside the first child and none of the others.
    Difference,
}

/// A node of the tree.
#[derive(Clone, Debug, PartialEq)]
pub enum CsgNode {
    /// A leaf, by index into [`Csg::leaves`].
    Leaf(usize),
    /// Children combined.
    Op(CsgOp, Vec<CsgNode>),
}

/// A solid of the tree.
#[derive(Clone, Debug, PartialEq)]
pub struct CsgLeaf {
    /// A closed solid (not a flat shape, an open cylinder or cone, or an open mesh).
    pub shape: Shape,
    /// Its placement within the combination.
    pub transform: Option<Transform>,
    /// Whether the result's surface faces against this solid's (it is subtracted).
    pub negated: bool,
    /// Its bounds in the combination's space, grown by a hair: a ray that misses them
    /// does not cross it (most rays miss most of a die's pips).
    bounds: Aabb,
}

/// A combination of solids.
#[derive(Clone, Debug, PartialEq)]
pub struct Csg {
    /// The tree.
    pub root: CsgNode,
    /// Its solids, in the order the file gives them.
    pub leaves: Vec<CsgLeaf>,
}

/// Most crossings of one analytic solid along one ray (a torus has four).
const MAX_CROSSINGS: usize = 8;

/// Most crossings of one mesh along one ray.
const MAX_MESH_CROSSINGS: usize = 1024;

/// A hit's `prim` on a combination: its solid's index in the top 8 bits, the solid's own
/// `prim` (a mesh's triangle) below.
const LEAF_SHIFT: u32 = 24;

/// Most solids in one combination (the index must fit the top bits of `prim`).
pub const MAX_CSG_LEAVES: usize = 1 << (32 - LEAF_SHIFT);

/// Most triangles of a mesh in a combination (its `prim` must fit below the solid's index).
pub const MAX_CSG_MESH_TRIANGLES: usize = 1 << LEAF_SHIFT;

impl CsgLeaf {
    /// A solid of the tree (a bounded shape).
    pub fn new(shape: Shape, transform: Option<Transform>, negated: bool) -> Self {
        let b = shape
            .bounds()
            .map(|b| transform.as_ref().map_or(b, |t| t.bounds_to_world(&b)))
            .unwrap_or_else(|| Aabb::new(Vec3A::splat(-f32::MAX), Vec3A::splat(f32::MAX)));
        let pad = 1e-4 * (b.max - b.min).max_element().max(1.0);
        CsgLeaf {
            shape,
            transform,
            negated,
            bounds: Aabb::new(b.min - pad, b.max + pad),
        }
    }

    /// Whether `ray` (in the combination's space) may cross the solid in `(0, t_max)`: the
    /// slab test against its bounds (a zero direction component gives infinities, which
    /// `min` and `max` order; the NaN of a ray in a slab's plane is passed over by them).
    fn may_cross(&self, ray: &Ray, t_max: f32) -> bool {
        let inv = ray.dir.recip();
        let t1 = (self.bounds.min - ray.origin) * inv;
        let t2 = (self.bounds.max - ray.origin) * inv;
        let (lo, hi) = (t1.min(t2), t1.max(t2));
        let near = lo.x.max(lo.y).max(lo.z).max(0.0);
        let far = hi.x.min(hi.y).min(hi.z).min(t_max);
        near <= far
    }

    fn local(&self, ray: &Ray) -> Ray {
        self.transform
            .as_ref()
            .map_or(*ray, |t| t.ray_to_object(ray))
    }

    fn contains(&self, p: Vec3A) -> bool {
        let p = self.transform.as_ref().map_or(p, |t| t.point_to_object(p));
        match &self.shape {
            // A mesh is a solid only here, where it was checked to be closed.
            Shape::Mesh(m) => m.encloses(p),
            s => s.contains(p),
        }
    }

    /// Every crossing of this solid with `0 < t < t_max`, nearest first.
    fn crossings(&self, ray: &Ray, t_max: f32, out: &mut Vec<(f32, ShapeHit)>) {
        if !self.may_cross(ray, t_max) {
            return;
        }
        let local = self.local(ray);
        let len = local.dir.length();
        if len == 0.0 || !len.is_finite() {
            return;
        }
        let mut from = 0.0f32;
        let most = match self.shape {
            Shape::Mesh(_) => MAX_MESH_CROSSINGS,
            _ => MAX_CROSSINGS,
        };
        for _ in 0..most {
            let start = local.at(from);
            let Some(h) = self
                .shape
                .intersect(&Ray::new(start, local.dir), t_max - from)
            else {
                return;
            };
            let t = from + h.t;
            out.push((t, h));
            // Past this crossing by a hair of the solid's size, so that it is not found
            // again.
            let scale = local.at(t).abs().max_element().max(1.0);
            from = t + 1e-5 * scale / len;
            if from >= t_max {
                return;
            }
        }
    }
}

impl Csg {
    /// Whether the combination holds a point whose solids hold `inside`.
    fn eval(node: &CsgNode, inside: &[bool]) -> bool {
        match node {
            CsgNode::Leaf(i) => inside[*i],
            CsgNode::Op(CsgOp::Union, c) => c.iter().any(|n| Self::eval(n, inside)),
            CsgNode::Op(CsgOp::Intersection, c) => c.iter().all(|n| Self::eval(n, inside)),
            CsgNode::Op(CsgOp::Difference, c) => match c.split_first() {
                Some((first, rest)) => {
                    Self::eval(first, inside) && !rest.iter().any(|n| Self::eval(n, inside))
                }
                None => false,
            },
        }
    }

    /// The solid a hit's `prim` names.
    #[inline]
    pub fn leaf_of(prim: u32) -> usize {
        (prim >> LEAF_SHIFT) as usize
    }

    fn node_bounds(&self, node: &CsgNode) -> Option<Aabb> {
        match node {
            CsgNode::Leaf(i) => {
                let leaf = &self.leaves[*i];
                let b = leaf.shape.bounds()?;
                Some(leaf.transform.as_ref().map_or(b, |t| t.bounds_to_world(&b)))
            }
            CsgNode::Op(CsgOp::Union, c) => c
                .iter()
                .filter_map(|n| self.node_bounds(n))
                .reduce(|a, b| a.union(&b)),
            CsgNode::Op(CsgOp::Intersection, c) => {
                let mut all = c.iter().map(|n| self.node_bounds(n));
                let first = all.next()??;
                all.try_fold(first, |a, b| {
                    let b = b?;
                    Some(Aabb::new(
                        a.min.max(b.min),
                        a.max.min(b.max).max(a.min.max(b.min)),
                    ))
                })
            }
            CsgNode::Op(CsgOp::Difference, c) => c.first().and_then(|n| self.node_bounds(n)),
        }
    }
}

impl Intersect for Csg {
    /// The nearest crossing of the result's surface with `0 < t < t_max`: `prim` names the
    /// leaf (see [`Csg::leaf_of`]) and holds the leaf's own, `part` is the leaf's own.
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        let mut inside: Vec<bool> = self.leaves.iter().map(|l| l.contains(ray.origin)).collect();
        let mut events: Vec<(f32, usize, ShapeHit)> = vec![];
        let mut one = vec![];
        for (i, leaf) in self.leaves.iter().enumerate() {
            one.clear();
            leaf.crossings(ray, t_max, &mut one);
            events.extend(one.iter().map(|&(t, h)| (t, i, h)));
        }
        events.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut state = Self::eval(&self.root, &inside);
        for (t, i, h) in events {
            inside[i] = !inside[i];
            let now = Self::eval(&self.root, &inside);
            if now != state {
                return Some(ShapeHit {
                    t,
                    part: h.part,
                    prim: ((i as u32) << LEAF_SHIFT) | h.prim,
                    bary: h.bary,
                });
            }
            state = now;
        }
        None
    }

    /// The surface at a hit: the leaf's, facing out of the result.
    fn surface(&self, p: Vec3A, hit: &ShapeHit, want_uv: bool) -> Surface {
        let leaf = &self.leaves[Self::leaf_of(hit.prim)];
        let lp = leaf.transform.as_ref().map_or(p, |t| t.point_to_object(p));
        let own = ShapeHit {
            prim: hit.prim & ((1 << LEAF_SHIFT) - 1),
            ..*hit
        };
        let s = leaf.shape.surface(lp, &own, want_uv);
        let (point, normal) = match &leaf.transform {
            None => (s.point, s.normal),
            Some(t) => (
                t.point_to_world(s.point),
                t.normal_to_world(s.normal).normalize(),
            ),
        };
        Surface {
            point,
            normal: if leaf.negated { -normal } else { normal },
            uv: s.uv,
        }
    }

    /// Whether `p` is strictly inside the result.
    fn contains(&self, p: Vec3A) -> bool {
        let inside: Vec<bool> = self.leaves.iter().map(|l| l.contains(p)).collect();
        Self::eval(&self.root, &inside)
    }

    /// Bounds: of a union, its children's together; of an intersection, where they overlap;
    /// of a difference, its first child's.
    fn bounds(&self) -> Option<Aabb> {
        Some(
            self.node_bounds(&self.root)
                .unwrap_or_else(|| Aabb::new(Vec3A::ZERO, Vec3A::ZERO)),
        )
    }

    fn leaving(&self) -> Leaving {
        Leaving::MayReturn
    }

    fn kind(&self) -> &'static str {
        "csg"
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_util::*;
    use super::super::{Cuboid, Sphere};
    use super::*;
    use proptest::prelude::*;

    fn sphere(c: [f32; 3], r: f32) -> Shape {
        Shape::Sphere(Sphere {
            center: Vec3A::from(c),
            radius: r,
        })
    }

    fn cube() -> Shape {
        Shape::Cuboid(Cuboid {
            min: Vec3A::splat(-1.0),
            max: Vec3A::splat(1.0),
        })
    }

    fn csg(op: CsgOp, shapes: Vec<Shape>) -> Shape {
        let n = shapes.len();
        Shape::Csg(std::sync::Arc::new(Csg {
            root: CsgNode::Op(op, (0..n).map(CsgNode::Leaf).collect()),
            leaves: shapes
                .into_iter()
                .enumerate()
                .map(|(i, shape)| CsgLeaf::new(shape, None, op == CsgOp::Difference && i > 0))
                .collect(),
        }))
    }

    /// A cube minus a sphere at its +z face's centre: down the z axis the ray passes the
    /// face (now a hollow) and meets the sphere's inside, facing out of the result (+z).
    #[test]
    fn a_cube_minus_a_sphere_has_a_hollow() {
        let s = csg(
            CsgOp::Difference,
            vec![cube(), sphere([0.0, 0.0, 1.0], 0.5)],
        );
        let (t, surf) = hit(&s, [0.0, 0.0, 5.0], [0.0, 0.0, -1.0]).unwrap();
        assert!((t - 4.5).abs() < 1e-5, "{t}");
        assert_vec_close(surf.normal, Vec3A::Z, 1e-5);
        // Beside the hollow, the face itself.
        let (t, surf) = hit(&s, [0.8, 0.8, 5.0], [0.0, 0.0, -1.0]).unwrap();
        assert!((t - 4.0).abs() < 1e-5, "{t}");
        assert_vec_close(surf.normal, Vec3A::Z, 1e-5);
        // Inside the hollow the solid is not; below it, it is.
        assert!(!s.contains(Vec3A::new(0.0, 0.0, 0.9)));
        assert!(s.contains(Vec3A::new(0.0, 0.0, 0.4)));
        assert_eq!(s.bounds().unwrap().max, Vec3A::ONE);
    }

    /// Two overlapping spheres: the union's surface is the outer of the two, the
    /// intersection's the lens between them.
    #[test]
    fn union_and_intersection_of_two_spheres() {
        let a = sphere([-0.5, 0.0, 0.0], 1.0);
        let b = sphere([0.5, 0.0, 0.0], 1.0);
        let u = csg(CsgOp::Union, vec![a.clone(), b.clone()]);
        let (t, surf) = hit(&u, [-5.0, 0.0, 0.0], [1.0, 0.0, 0.0]).unwrap();
        assert!((t - 3.5).abs() < 1e-5, "{t}");
        assert_vec_close(surf.normal, -Vec3A::X, 1e-5);
        // From inside the union, out through the far sphere only.
        let (t, _) = hit(&u, [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]).unwrap();
        assert!((t - 1.5).abs() < 1e-5, "{t}");
        let i = csg(CsgOp::Intersection, vec![a, b]);
        let (t, surf) = hit(&i, [-5.0, 0.0, 0.0], [1.0, 0.0, 0.0]).unwrap();
        assert!((t - 4.5).abs() < 1e-5, "{t}");
        assert_vec_close(surf.normal, -Vec3A::X, 1e-5);
        assert!(hit(&i, [-5.0, 0.95, 0.0], [1.0, 0.0, 0.0]).is_none());
        let b = i.bounds().unwrap();
        assert_vec_close(b.min, Vec3A::new(-0.5, -1.0, -1.0), 1e-6);
        assert_vec_close(b.max, Vec3A::new(0.5, 1.0, 1.0), 1e-6);
    }

    /// Random rays against a cube minus two spheres: the hit is the first point along the
    /// ray, sampled finely, where `contains` changes, and none is missed. The runner rather
    /// than `proptest!`, so that after the last case the test can count the rays that hit:
    /// a miss of both the solid and the marching checks nothing.
    #[test]
    fn hits_agree_with_marching_contains() {
        use proptest::test_runner::{Config, RngSeed, TestRunner};
        use std::cell::Cell;
        let (cases, hits) = (Cell::new(0u32), Cell::new(0u32));
        // The same rays on every run, so that CI's verdict does not depend on the draw.
        let mut runner = TestRunner::new(Config {
            rng_seed: RngSeed::Fixed(0xc59),
            failure_persistence: None,
            ..Config::default()
        });
        let result = runner.run(
            &(
                prop::array::uniform3(-4.0f32..4.0),
                prop::array::uniform3(-1.2f32..1.2),
            ),
            |(o, target)| {
                let s = csg(
                    CsgOp::Difference,
                    vec![
                        cube(),
                        sphere([0.0, 0.0, 1.0], 0.6),
                        sphere([1.0, 1.0, 0.0], 0.7),
                    ],
                );
                let o = Vec3A::from(o);
                let d = (Vec3A::from(target) - o).normalize_or_zero();
                prop_assume!(d != Vec3A::ZERO);
                cases.set(cases.get() + 1);
                let ray = Ray::new(o, d);
                let start = s.contains(o);
                let steps = 20_000;
                let want = (1..=steps)
                    .map(|k| 12.0 * k as f32 / steps as f32)
                    .find(|&t| s.contains(ray.at(t)) != start);
                let got = s.intersect(&ray, f32::INFINITY).map(|h| h.t);
                hits.set(hits.get() + u32::from(got.is_some()));
                // A sliver: the other side lasts under 3e-3 along the ray (a graze of an edge
                // or of a sphere), which the steps may or may not catch.
                let sliver = |t: f32| s.contains(ray.at(t + 3e-3)) == start;
                match (got, want) {
                    (Some(g), Some(w)) => {
                        prop_assert!((g - w).abs() < 2e-3 || (g < w && sliver(g)), "{g} vs {w}")
                    }
                    (None, Some(w)) => prop_assert!(sliver(w), "missed the crossing at {w}"),
                    (Some(g), None) => prop_assert!(sliver(g), "a crossing at {g} that is not"),
                    (None, None) => {}
                }
                Ok(())
            },
        );
        if let Err(e) = result {
            panic!("{e}\n{runner}");
        }
        // Every case the runner asked for.
        let (cases, hits) = (cases.get(), hits.get());
        assert!(cases >= runner.config().cases, "{cases} cases");
        // Half the targets lie inside the solid (the cube is 58 % of their box, the two
        // hollows take a tenth of it), and a ray from outside toward one of them must cross
        // the surface: over half the rays hit. A quarter leaves a margin no seed comes near.
        assert!(hits >= cases / 4, "{hits} of {cases} rays hit");
    }
}
