//! A shape placed in the world with its materials: what the object BVH (`crate::accel`)
//! holds and the scene's objects are. Below both, so that neither reaches up for it.

use super::{Shape, ShapeHit};
use crate::math::{Aabb, Ray, Transform, Vec3A};

/// A shape placed in the scene with its material.
#[derive(Clone, Debug)]
pub struct Object {
    /// Name for messages (given, or type and index).
    pub name: String,
    /// The shape, in object space.
    pub shape: Shape,
    /// Object to world placement; `None` when object space is world space.
    pub transform: Option<Transform>,
    /// Index into the scene's materials.
    pub material: usize,
    /// For meshes with materials of their own (from an MTL file): the scene material of each
    /// of the mesh's slots. Empty when `material` covers the whole object.
    pub slot_materials: Vec<usize>,
    /// Bounds in world space; `None` when unbounded.
    pub world_bounds: Option<Aabb>,
    /// Centre of the object-space bounds (the default centre of spherical mappings).
    pub center: Vec3A,
    /// Factors on the shape's own uv (`uv_scale` in the file; 1 by default).
    pub uv_scale: crate::math::Vec2,
}

impl Object {
    /// Nearest hit of a world ray in `(0, t_max)`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<ShapeHit> {
        match &self.transform {
            None => self.shape.intersect_walk(ray, t_max),
            Some(t) => self.shape.intersect_walk(&t.ray_to_object(ray), t_max),
        }
    }

    /// Whether anything of the object is hit by a world ray in `(0, t_max)`.
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        match &self.transform {
            None => self.shape.occluded_walk(ray, t_max),
            Some(t) => self.shape.occluded_walk(&t.ray_to_object(ray), t_max),
        }
    }

    /// The material (index into the scene's materials) at a hit on this object.
    #[inline]
    pub fn material_at(&self, hit: &ShapeHit) -> usize {
        match &self.shape {
            Shape::Mesh(m) if !self.slot_materials.is_empty() => self
                .slot_materials
                .get(m.slot(hit.prim) as usize)
                .copied()
                .unwrap_or(self.material),
            // A combination's solids may each have their own: `prim` names the solid.
            Shape::Csg(_) if !self.slot_materials.is_empty() => self
                .slot_materials
                .get(crate::geometry::Csg::leaf_of(hit.prim))
                .copied()
                .unwrap_or(self.material),
            _ => self.material,
        }
    }

    /// True when the world-space point is strictly inside this object's solid.
    pub fn contains(&self, p: Vec3A) -> bool {
        let p = self.transform.as_ref().map_or(p, |t| t.point_to_object(p));
        self.shape.contains(p)
    }
}
