//! Rays through the holes of cut-out surfaces (see [`crate::material::cutout`]): a query
//! that meets a hole goes on from the far side of it, as if the surface were not there.
//! Scenes without cut-outs never come here.

use super::{Hit, Scene, Skip};
use crate::math::{Ray, offset_ray_origin};

/// Most holes one ray goes through before the rest of its way counts as blocked (a forest
/// of leaves seen edge-on).
pub(super) const MAX_HOLES: usize = 256;

impl Scene {
    /// Whether `hit`, which `ray` met, falls in a hole of its material's cut-out.
    #[inline]
    pub(super) fn is_hole(&self, hit: &Hit, ray: &Ray) -> bool {
        let Some(c) = &self.materials[hit.material].cutout else {
            return false;
        };
        let alpha = self.textures[c.texture()].eval(&hit.tex).x;
        c.is_hole(alpha, ray, hit.t)
    }

    /// The ray that goes on past `hit` (met by `ray`), and the distance left of `t_max`.
    pub(super) fn through(hit: &Hit, ray: &Ray, t_max: f32) -> (Ray, f32) {
        let side = if ray.dir.dot(hit.normal) > 0.0 {
            hit.normal
        } else {
            -hit.normal
        };
        (
            Ray::new(offset_ray_origin(hit.point, side), ray.dir),
            t_max - hit.t,
        )
    }

    /// The closest hit in `(0, t_max)` that is not in a hole (its `t` from `ray`'s origin).
    pub(super) fn closest_hit_past_holes(
        &self,
        ray: &Ray,
        t_max: f32,
        skip: Skip,
        force_uv: bool,
    ) -> Option<Hit> {
        let (mut r, mut left, mut skip, mut travelled) = (*ray, t_max, skip, 0.0);
        for k in 0..MAX_HOLES {
            let (i, h) = self.accel.closest_hit(&self.objects, &r, left, skip)?;
            let mut hit = self.hit_details(&r, i, h, force_uv || self.cutouts[i]);
            // Past the last hole allowed, what the ray meets counts as solid.
            let last = k + 1 == MAX_HOLES;
            if last || !(self.cutouts[i] && self.is_hole(&hit, &r)) {
                hit.t += travelled;
                return Some(hit);
            }
            travelled += hit.t;
            (r, left) = Self::through(&hit, &r, left);
            skip = Skip::NONE;
        }
        unreachable!("the last pass returns")
    }

    /// Whether anything but `skip` that is not a hole blocks the ray in `(0, t_max)`.
    pub(super) fn occluded_past_holes(&self, ray: &Ray, t_max: f32, skip: Skip) -> bool {
        let (mut r, mut left, mut skip) = (*ray, t_max, skip);
        for _ in 0..MAX_HOLES {
            let Some((i, h)) = self.accel.closest_hit(&self.objects, &r, left, skip) else {
                return false;
            };
            if !self.cutouts[i] {
                return true;
            }
            let hit = self.hit_details(&r, i, h, true);
            if !self.is_hole(&hit, &r) {
                return true;
            }
            (r, left) = Self::through(&hit, &r, left);
            skip = Skip::NONE;
        }
        true
    }
}
