//! One `[[objects]]` entry to an [`Object`]: its material (named, a mesh file's own, or its
//! group's), its transform (after a glTF node's, before its group's), its shape checked, its
//! name and uv scale. Meshes and groups are resolved before they get here (group.rs).

use super::Builder;
use super::group::Placement;
use crate::geometry::{Cone, Cuboid, Cylinder, Disk, Plane, Rect, Shape, Sphere, Torus, Triangle};
use crate::math::{Transform, Vec3A};
use crate::scene::Object;
use crate::scene::diag::{DocPath, name_help};
use crate::scene::format::{ObjectDef, TransformDef};
use crate::scene::meshes::LoadedMesh;

impl Builder<'_> {
    pub(super) fn object(
        &mut self,
        d: &ObjectDef,
        index: usize,
        path: &DocPath,
        material_names: &[String],
        mesh: Option<LoadedMesh>,
        placement: Option<&Placement>,
    ) -> Option<Object> {
        let (name, material, transform) = d.common();
        let mut slot_materials = vec![];
        let material = match (material, &mesh) {
            (None, Some(m)) if !m.slot_materials.is_empty() => {
                slot_materials = m.slot_materials.clone();
                Some(slot_materials[0])
            }
            (None, Some(m)) if !m.unread_mtl.is_empty() => {
                self.error_help(
                    path.clone(),
                    format!(
                        "the mesh file's materials could not be read (MTL file {}), so the object needs a `material`",
                        m.unread_mtl.join(", MTL file ")
                    ),
                    "put the MTL file where the OBJ file's `mtllib` says (relative to the OBJ file), or add material = \"NAME\"",
                );
                None
            }
            (None, Some(_)) => {
                self.error_help(
                    path.clone(),
                    "the mesh file names no materials, so the object needs a `material`",
                    "add material = \"NAME\", or give the OBJ file an MTL file with `mtllib`",
                );
                None
            }
            (None, None) => match placement.and_then(|p| p.material.as_ref()) {
                Some((name, at)) => self.material_named(name, at, material_names),
                None => {
                    self.error_help(
                        path.clone(),
                        "the object has no `material`",
                        "add material = \"NAME\" naming one of [materials]",
                    );
                    None
                }
            },
            (Some(material), _) => {
                self.material_named(material, &path.key("material"), material_names)
            }
        };
        let transform = transform
            .as_ref()
            .and_then(|t| self.transform(t, &path.key("transform")));
        // A glTF node's placement comes first, then the object's, then its group's.
        let (transform, part) = match &mesh {
            Some(LoadedMesh {
                node: Some(node),
                part,
                ..
            }) => (
                Some(transform.map_or(*node, |t| node.then(&t))),
                part.clone(),
            ),
            _ => (transform, None),
        };
        let transform = match (transform, placement.and_then(|p| p.transform)) {
            (Some(a), Some(b)) => Some(a.then(&b)),
            (a, b) => a.or(b),
        };
        let shape = match (mesh, d) {
            (Some(m), _) => Shape::Mesh(m.mesh),
            (None, ObjectDef::Csg(c)) => {
                let (csg, leaf_materials) = self.csg(c, path)?;
                // Solids with a material of their own: every solid gets a slot.
                if leaf_materials.iter().any(Option::is_some) {
                    let mut slots = vec![];
                    for m in leaf_materials {
                        slots.push(match m {
                            None => material?,
                            Some((name, at)) => self.material_named(&name, &at, material_names)?,
                        });
                    }
                    slot_materials = slots;
                }
                Shape::Csg(std::sync::Arc::new(csg))
            }
            (None, _) => self.shape(d, path)?,
        };
        let name = name
            .clone()
            .unwrap_or_else(|| format!("{} #{index}", shape.kind()));
        let name = match part {
            Some(part) => format!("{name}/{part}"),
            None => name,
        };
        let name = match placement {
            Some(p) => format!("{}/{name}", p.name),
            None => name,
        };
        let local_bounds = shape.bounds();
        let world_bounds = local_bounds.map(|b| match &transform {
            Some(t) => t.bounds_to_world(&b),
            None => b,
        });
        let uv_scale = match d.uv_scale() {
            None => crate::math::Vec2::ONE,
            Some(s) => {
                let at = path.key("uv_scale");
                let u = self.finite(s.0[0], &at);
                let v = self.finite(s.0[1], &at);
                if u == 0.0 || v == 0.0 {
                    self.error_help(
                        at,
                        "a uv scale of 0 shows one texel over the whole object",
                        "use a non-zero factor (negative ones mirror)",
                    );
                }
                crate::math::Vec2::new(u, v)
            }
        };
        Some(Object {
            name,
            uv_scale,
            center: local_bounds.map_or(Vec3A::ZERO, |b| b.center()),
            shape,
            transform,
            material: material?,
            slot_materials,
            world_bounds,
        })
    }

    /// The index of the material `name`, or an error at `at` suggesting one.
    fn material_named(
        &mut self,
        name: &str,
        at: &DocPath,
        material_names: &[String],
    ) -> Option<usize> {
        if let Some(i) = material_names.iter().position(|m| m == name) {
            return Some(i);
        }
        let help = name_help(
            name,
            material_names.iter().map(String::as_str),
            "defined materials",
            "define it under [materials.NAME]",
        );
        self.error_help(at.clone(), format!("no material named `{name}`"), help);
        None
    }

    pub(super) fn transform(&mut self, d: &TransformDef, path: &DocPath) -> Option<Transform> {
        let scale = self.point(d.scale.0, &path.key("scale"));
        let rotate = self.point(d.rotate, &path.key("rotate"));
        let translate = self.point(d.translate, &path.key("translate"));
        if scale.cmpeq(Vec3A::ZERO).any() {
            self.error_help(
                path.key("scale"),
                "a scale of 0 flattens the object to nothing",
                "use a non-zero scale on every axis",
            );
            return None;
        }
        if scale == Vec3A::ONE && rotate == Vec3A::ZERO && translate == Vec3A::ZERO {
            return None;
        }
        Transform::from_srt(scale.into(), rotate.into(), translate.into())
    }

    pub(super) fn shape(&mut self, d: &ObjectDef, path: &DocPath) -> Option<Shape> {
        let before = self.problems.len();
        let shape = match d {
            ObjectDef::Sphere(s) => Shape::Sphere(Sphere {
                center: self.point(s.center, &path.key("center")),
                radius: self.positive(s.radius, &path.key("radius")),
            }),
            ObjectDef::Plane(s) => Shape::Plane(Plane::new(
                self.point(s.point, &path.key("point")),
                self.direction(s.normal, &path.key("normal")),
            )),
            ObjectDef::Rectangle(s) => {
                let corner = self.point(s.corner, &path.key("corner"));
                let u = self.point(s.edge_u, &path.key("edge_u"));
                let v = self.point(s.edge_v, &path.key("edge_v"));
                match Rect::new(corner, u, v) {
                    Some(r) => Shape::Rect(r),
                    None => {
                        self.error(path.key("edge_v"), "the edges must be non-zero and not parallel (the rectangle has no area)");
                        return None;
                    }
                }
            }
            ObjectDef::Cuboid(s) => {
                let min = self.point(s.min, &path.key("min"));
                let max = self.point(s.max, &path.key("max"));
                if min.cmpge(max).any() {
                    self.error_help(
                        path.key("max"),
                        format!(
                            "max {:?} must be greater than min {:?} on every axis",
                            s.max, s.min
                        ),
                        "min is the smallest corner, max the largest",
                    );
                }
                Shape::Cuboid(Cuboid { min, max })
            }
            ObjectDef::Cylinder(s) => Shape::Cylinder(Cylinder::new(
                self.point(s.base, &path.key("base")),
                self.direction(s.axis, &path.key("axis")),
                self.positive(s.radius, &path.key("radius")),
                self.positive(s.height, &path.key("height")),
                s.capped,
            )),
            ObjectDef::Cone(s) => Shape::Cone(Cone::new(
                self.point(s.base, &path.key("base")),
                self.direction(s.axis, &path.key("axis")),
                self.positive(s.radius, &path.key("radius")),
                self.positive(s.height, &path.key("height")),
                s.capped,
            )),
            // (An object places a combination with its solids' materials: see `object`.)
            ObjectDef::Csg(c) => Shape::Csg(std::sync::Arc::new(self.csg(c, path)?.0)),
            ObjectDef::Torus(s) => {
                let major = self.positive(s.major_radius, &path.key("major_radius"));
                let minor = self.positive(s.minor_radius, &path.key("minor_radius"));
                if minor >= major {
                    self.error_help(
                        path.key("minor_radius"),
                        format!("must be less than major_radius ({major}), not {minor}"),
                        "a tube as wide as its ring closes the hole (a horn or spindle torus), which snell does not draw",
                    );
                }
                Shape::Torus(Torus::new(
                    self.point(s.center, &path.key("center")),
                    self.direction(s.axis, &path.key("axis")),
                    major,
                    minor,
                ))
            }
            ObjectDef::Disk(s) => Shape::Disk(Disk::new(
                self.point(s.center, &path.key("center")),
                self.direction(s.normal, &path.key("normal")),
                self.positive(s.radius, &path.key("radius")),
            )),
            ObjectDef::Triangle(s) => {
                let vp = path.key("vertices");
                let [a, b, c] = [0, 1, 2].map(|i| self.point(s.vertices[i], &vp.index(i)));
                match Triangle::new(a, b, c) {
                    Some(t) => Shape::Triangle(t),
                    None => {
                        self.error(vp, "the triangle has no area (its corners are on one line)");
                        return None;
                    }
                }
            }
            // Meshes are resolved (loaded or found in the cache) before this is called.
            ObjectDef::Mesh(_) | ObjectDef::Group(_) => return None,
        };
        (self.problems.len() == before).then_some(shape)
    }
}
