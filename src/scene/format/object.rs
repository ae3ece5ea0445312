//! `[[objects]]`: one struct per shape, written once through a macro that adds the keys
//! every object has (name, material, transform, uv scale), and the combinations of `csg`.

use super::*;

/// How a `csg` object's shapes combine.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum CsgOpDef {
    /// Inside any of them.
    Union,
    /// Inside all of them.
    Intersection,
    /// Inside the first and none of the others.
    Difference,
}

macro_rules! object_defs {
    ($( $(#[$doc:meta])* $variant:ident ($name:ident) { $( $(#[$fdoc:meta])* $field:ident : $ty:ty $(= $default:literal)? ),* $(,)? } )*) => {
        /// `[[objects]]`: a shape with a material and an optional transform.
        #[derive(Debug, Deserialize, JsonSchema)]
        #[serde(tag = "type", rename_all = "lowercase")]
        pub enum ObjectDef {
            $( $(#[$doc])* $variant($name), )*
        }

        $(
            #[derive(Debug, Deserialize, JsonSchema)]
            #[serde(deny_unknown_fields)]
            $(#[$doc])*
            pub struct $name {
                /// Name shown in messages (default: the type and index).
                pub name: Option<String>,
                /// Name of the material (meshes may take theirs from their MTL file).
                pub material: Option<String>,
                /// Scale, rotation and offset from the shape's own coordinates to its parent's:
                /// the scene's, or those of the group or `csg` object it is in (default: none).
                pub transform: Option<TransformDef>,
                /// Factors on the shape's own uv, `[u, v]` or one number (default 1): a
                /// rectangle's `[width, height]` makes its uv run in scene units, as a plane's.
                pub uv_scale: Option<UvScaleDef>,
                $( $(#[$fdoc])* $(#[serde(default = $default)])? pub $field: $ty, )*
            }
        )*

        impl ObjectDef {
            /// The fields every object has: name, material, transform.
            pub fn common(&self) -> (&Option<String>, &Option<String>, &Option<TransformDef>) {
                match self {
                    $( ObjectDef::$variant(o) => (&o.name, &o.material, &o.transform), )*
                }
            }

            /// The object's name and transform, to be changed (by a frame of an animation).
            pub fn placement_mut(&mut self) -> (&Option<String>, &mut Option<TransformDef>) {
                match self {
                    $( ObjectDef::$variant(o) => (&o.name, &mut o.transform), )*
                }
            }

            /// The object's `uv_scale`.
            pub fn uv_scale(&self) -> Option<UvScaleDef> {
                match self {
                    $( ObjectDef::$variant(o) => o.uv_scale, )*
                }
            }
        }
    };
}

object_defs! {
    /// A sphere.
    Sphere(SphereDef) {
        /// Centre, in the object's own coordinates (before its `transform`).
        center: V3 = "origin",
        /// Radius, greater than 0, in the object's own units (before its `transform`).
        radius: f32,
    }
    /// An infinite plane.
    Plane(PlaneDef) {
        /// A point on it.
        point: V3 = "origin",
        /// Its normal.
        normal: V3 = "y_axis",
    }
    /// A parallelogram.
    #[serde(rename = "rectangle")]
    Rectangle(RectangleDef) {
        /// A corner.
        corner: V3,
        /// First edge from the corner.
        edge_u: V3,
        /// Second edge from the corner.
        edge_v: V3,
    }
    /// A box.
    #[serde(rename = "box")]
    Cuboid(BoxDef) {
        /// Smallest corner.
        min: V3,
        /// Largest corner.
        max: V3,
    }
    /// A cylinder.
    Cylinder(CylinderDef) {
        /// Centre of the bottom.
        base: V3 = "origin",
        /// Axis direction.
        axis: V3 = "y_axis",
        /// Radius, greater than 0, in the object's own units (before its `transform`).
        radius: f32,
        /// Length along the axis from `base` to the centre of the top, greater than 0.
        height: f32,
        /// Closed ends.
        capped: bool = "yes",
    }
    /// A cone.
    Cone(ConeDef) {
        /// Centre of the base.
        base: V3 = "origin",
        /// Axis direction, toward the apex.
        axis: V3 = "y_axis",
        /// Base radius.
        radius: f32,
        /// Base to apex.
        height: f32,
        /// Closed base.
        capped: bool = "yes",
    }
    /// A ring torus: a tube of radius `minor_radius` around a circle of radius
    /// `major_radius`.
    Torus(TorusDef) {
        /// Centre of the ring.
        center: V3 = "origin",
        /// Axis direction, perpendicular to the ring.
        axis: V3 = "y_axis",
        /// Radius of the ring, centre to the middle of the tube.
        major_radius: f32,
        /// Radius of the tube, less than `major_radius`.
        minor_radius: f32,
    }
    /// Constructive solid geometry: solids (spheres, boxes, capped cylinders and cones,
    /// tori, and `csg` objects) combined. Each shape may have its own `transform` (within
    /// the combination) and `material` (default: the combination's).
    Csg(CsgDef) {
        /// `union`, `intersection`, or `difference` (the first minus the others).
        operation: CsgOpDef,
        /// The solids, at least two.
        shapes: Vec<ObjectDef>,
    }
    /// A disk.
    Disk(DiskDef) {
        /// Centre, in the object's own coordinates (before its `transform`).
        center: V3 = "origin",
        /// Its normal: the direction perpendicular to it (any length but 0).
        normal: V3 = "y_axis",
        /// Radius, greater than 0, in the object's own units (before its `transform`).
        radius: f32,
    }
    /// A triangle.
    Triangle(TriangleDef) {
        /// The three corners.
        vertices: [V3; 3],
    }
    /// A triangle mesh: a file, or a mesh defined under `[meshes]`.
    Mesh(MeshObjectDef) {
        /// OBJ, PLY or glTF (.gltf, .glb) file, relative to the scene file.
        file: Option<String>,
        /// Name of a mesh under `[meshes]` (instead of `file`).
        mesh: Option<String>,
        /// As `smooth` under `[meshes]` (only with `file`).
        smooth: Option<bool>,
        /// glTF: whether the file's KHR_lights_punctual lights join the scene, placed as
        /// its meshes are (default false; only with `file`).
        lights: Option<bool>,
    }
    /// A group defined under `[groups]`, placed: its objects, each with its own transform
    /// and then this one's; `material` is for those of its objects that name none.
    Group(GroupObjectDef) {
        /// Name of a group under `[groups]`.
        group: String,
    }
}
