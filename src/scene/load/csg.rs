//! `type = "csg"` to a [`Csg`]: the tree of shapes flattened into its solids, each with its
//! placement within the combination (its own transform, then its parents'), whether it is
//! subtracted, and the material it names (or its parents', or the object's).

use super::Builder;
use crate::geometry::{
    Csg, CsgLeaf, CsgNode, CsgOp, MAX_CSG_LEAVES, MAX_CSG_MESH_TRIANGLES, Shape,
};
use crate::math::Transform;
use crate::mesh_file;
use crate::scene::diag::DocPath;
use crate::scene::format::{CsgDef, CsgOpDef, MeshObjectDef, ObjectDef};
use std::sync::Arc;

/// Combinations nested deeper than this are refused.
const MAX_DEPTH: usize = 32;

/// A solid's material name and where the file gives it.
pub(super) type LeafMaterial = Option<(String, DocPath)>;

/// What the walk down the tree carries.
struct Walk<'a> {
    leaves: &'a mut Vec<CsgLeaf>,
    materials: &'a mut Vec<LeafMaterial>,
}

impl Builder<'_> {
    /// A combination and the material each of its solids names (`None`: the object's).
    pub(super) fn csg(&mut self, d: &CsgDef, path: &DocPath) -> Option<(Csg, Vec<LeafMaterial>)> {
        let (mut leaves, mut materials) = (vec![], vec![]);
        let mut walk = Walk {
            leaves: &mut leaves,
            materials: &mut materials,
        };
        let root = self.csg_node(d, path, None, false, None, &mut walk, 0)?;
        if leaves.len() > MAX_CSG_LEAVES {
            self.error(
                path.key("shapes"),
                format!(
                    "the combination has {} solids, more than the {MAX_CSG_LEAVES} one may have",
                    leaves.len()
                ),
            );
            return None;
        }
        Some((Csg { root, leaves }, materials))
    }

    /// A mesh file as a solid of a combination: read (OBJ or PLY, its materials not
    /// used), and refused unless its surface is closed.
    fn csg_mesh(&mut self, d: &MeshObjectDef, at: &DocPath) -> Option<Shape> {
        let Some(file) = &d.file else {
            self.error_help(
                at.clone(),
                "a mesh in a combination is given by its `file`",
                "name the OBJ or PLY file: file = \"solid.obj\"",
            );
            return None;
        };
        for (given, key) in [(d.mesh.is_some(), "mesh"), (d.lights.is_some(), "lights")] {
            if given {
                self.error(
                    at.key(key),
                    format!("`{key}` is not read for a mesh in a combination"),
                );
            }
        }
        let full = self.base_dir.join(file);
        self.files.push(full.clone());
        let gltf = full
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"));
        if gltf {
            self.error_help(
                at.key("file"),
                "a combination takes OBJ and PLY meshes, not glTF files",
                "export the solid as OBJ or PLY",
            );
            return None;
        }
        let data = match mesh_file::load(&full) {
            Ok(d) => d,
            Err(e) => {
                self.error_help(
                    at.key("file"),
                    format!("cannot load mesh: {e}"),
                    "paths are relative to the scene file's folder",
                );
                return None;
            }
        };
        for w in &data.warnings {
            self.warnings.push(format!("{file}: {w}"));
        }
        let (mesh, _) = self.build_mesh(file, data, d.smooth, "", &at.key("file"))?;
        if mesh.triangle_count() > MAX_CSG_MESH_TRIANGLES {
            self.error(
                at.key("file"),
                format!(
                    "{file} has {} triangles, more than the {MAX_CSG_MESH_TRIANGLES} a mesh in a combination may have",
                    mesh.triangle_count()
                ),
            );
            return None;
        }
        let open = mesh.open_edges();
        if open > 0 {
            self.error_help(
                at.key("file"),
                format!(
                    "{file} is not closed: {open} of its edges border one triangle (or more than two), so it has no inside to combine"
                ),
                "a combination takes closed (watertight) meshes: close the holes in a modeller",
            );
            return None;
        }
        Some(Shape::Mesh(Arc::new(mesh)))
    }

    #[allow(clippy::too_many_arguments)]
    fn csg_node(
        &mut self,
        d: &CsgDef,
        path: &DocPath,
        outer: Option<Transform>,
        negated: bool,
        material: LeafMaterial,
        walk: &mut Walk,
        depth: usize,
    ) -> Option<CsgNode> {
        if depth > MAX_DEPTH {
            self.error(
                path.clone(),
                format!("combinations nest deeper than {MAX_DEPTH}"),
            );
            return None;
        }
        if d.shapes.len() < 2 {
            self.error_help(
                path.key("shapes"),
                format!("a combination needs at least two shapes, not {}", d.shapes.len()),
                "list the solids to combine: shapes = [{ type = \"box\", ... }, { type = \"sphere\", ... }]",
            );
            return None;
        }
        let op = match d.operation {
            CsgOpDef::Union => CsgOp::Union,
            CsgOpDef::Intersection => CsgOp::Intersection,
            CsgOpDef::Difference => CsgOp::Difference,
        };
        let mut children = vec![];
        let mut ok = true;
        for (i, child) in d.shapes.iter().enumerate() {
            let at = path.key("shapes").index(i);
            let (_, name, transform) = child.common();
            if child.uv_scale().is_some() {
                self.error(
                    at.key("uv_scale"),
                    "a combination's shapes share its uv_scale: give it on the csg object",
                );
            }
            let own = transform
                .as_ref()
                .and_then(|t| self.transform(t, &at.key("transform")));
            // The shape's own placement first, then its parents'.
            let placed = match (own, outer) {
                (Some(a), Some(b)) => Some(a.then(&b)),
                (a, b) => a.or(b),
            };
            let neg = negated ^ (op == CsgOp::Difference && i > 0);
            let mat = name
                .clone()
                .map(|n| (n, at.key("material")))
                .or_else(|| material.clone());
            let node = match child {
                ObjectDef::Csg(c) => self.csg_node(c, &at, placed, neg, mat, walk, depth + 1),
                ObjectDef::Sphere(_)
                | ObjectDef::Cuboid(_)
                | ObjectDef::Torus(_)
                | ObjectDef::Cylinder(_)
                | ObjectDef::Cone(_) => {
                    let open = matches!(child, ObjectDef::Cylinder(c) if !c.capped)
                        || matches!(child, ObjectDef::Cone(c) if !c.capped);
                    if open {
                        self.error_help(
                            at.key("capped"),
                            "an open shape is not a solid: it has no inside to combine",
                            "leave capped = true in a combination",
                        );
                        None
                    } else {
                        self.shape(child, &at).map(|shape| {
                            walk.leaves.push(CsgLeaf::new(shape, placed, neg));
                            walk.materials.push(mat);
                            CsgNode::Leaf(walk.leaves.len() - 1)
                        })
                    }
                }
                ObjectDef::Mesh(m) => self.csg_mesh(m, &at).map(|shape| {
                    walk.leaves.push(CsgLeaf::new(shape, placed, neg));
                    walk.materials.push(mat);
                    CsgNode::Leaf(walk.leaves.len() - 1)
                }),
                other => {
                    let kind = match other {
                        ObjectDef::Plane(_) => "plane",
                        ObjectDef::Disk(_) => "disk",
                        ObjectDef::Triangle(_) => "triangle",
                        ObjectDef::Group(_) => "group",
                        _ => "rectangle",
                    };
                    self.error_help(
                        at.key("type"),
                        format!("a {kind} is not a solid snell can combine"),
                        "a combination takes spheres, boxes, capped cylinders and cones, tori, closed meshes, and combinations",
                    );
                    None
                }
            };
            match node {
                Some(n) => children.push(n),
                None => ok = false,
            }
        }
        ok.then_some(CsgNode::Op(op, children))
    }
}
