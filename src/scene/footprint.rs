//! The patch of surface a pixel sees at a hit, from the ray's differentials: what texture
//! filtering reads, and what a mirror or glass needs to pass the differentials on.

use super::Object;
use super::{Hit, Scene};
use crate::geometry::{Shape, ShapeHit};
use crate::math::differential::{Differentials, surface_offsets};
use crate::math::{Ray, Vec2, Vec3A};
use crate::texture::Footprint;

/// Where a ray's neighbours meet the surface around a hit.
#[derive(Clone, Copy, Debug)]
pub struct SurfacePatch {
    /// The texture footprint there (object space, and the shape's uv where a texture reads
    /// it).
    pub footprint: Footprint,
    /// The offsets from the hit to where the neighbours right and below meet the tangent
    /// plane, world space.
    pub dp: [Vec3A; 2],
    /// How the unit shading normal changes over those offsets, world space (zero unless
    /// asked for).
    pub dn: [Vec3A; 2],
}

/// A ray's differentials, as far as they are known: a camera ray's are worked out only
/// where something reads them (most camera rays meet no texture and no mirror).
#[derive(Clone, Copy, Debug, Default)]
pub enum RayDifferentials {
    /// None (after a rough bounce, or with texture filtering off).
    #[default]
    None,
    /// The ray is a camera ray of the scene's camera: its differentials are the camera's.
    Camera,
    /// Worked out and carried with the ray: those a mirror or glass passed on from the ray
    /// before.
    Known(Differentials),
}

impl RayDifferentials {
    /// A camera ray's: the camera's where the scene filters textures, else none.
    pub fn camera(scene: &Scene) -> Self {
        if scene.settings.filter_textures {
            RayDifferentials::Camera
        } else {
            RayDifferentials::None
        }
    }

    /// The differentials of `ray`, if it has any.
    #[inline]
    pub fn of(&self, scene: &Scene, ray: &Ray) -> Option<Differentials> {
        match self {
            RayDifferentials::None => None,
            RayDifferentials::Camera => scene.camera_differentials(ray),
            RayDifferentials::Known(d) => Some(*d),
        }
    }

    /// Whether the ray has differentials.
    #[inline]
    pub fn is_some(&self) -> bool {
        !matches!(self, RayDifferentials::None)
    }
}

/// How object `o`'s second uv changes over object-space offsets `dp` on triangle `prim`,
/// if it is a mesh with a second set.
pub(super) fn second_uv_change(o: &Object, prim: u32, dp: [Vec3A; 2]) -> Option<[Vec2; 2]> {
    match &o.shape {
        Shape::Mesh(m) => {
            let [x, y] = dp.map(|d| m.second_uv_change(prim, d));
            Some([x?, y?])
        }
        _ => None,
    }
}

impl Scene {
    /// Whether the material at `hit` reads a texture that varies (so a footprint matters).
    #[inline]
    pub fn reads_textures(&self, hit: &Hit) -> bool {
        self.textured[hit.material]
    }

    /// The patch of surface around `hit` that `ray`'s neighbours `diff` meet, with the
    /// normal's change over it where `normals` asks (for differentials passed on by a mirror
    /// or glass). `None` where a neighbour runs along the surface.
    pub fn patch(
        &self,
        hit: &Hit,
        ray: &Ray,
        diff: &Differentials,
        normals: bool,
    ) -> Option<SurfacePatch> {
        let dp = surface_offsets(ray, diff, hit.point, hit.normal)?;
        let o = &self.objects[hit.object];
        let local = |v: Vec3A| o.transform.as_ref().map_or(v, |t| t.vector_to_object(v));
        let (dpdx, dpdy) = (local(dp[0]), local(dp[1]));
        let mut patch = SurfacePatch {
            footprint: Footprint {
                dpdx,
                dpdy,
                duvdx: Vec2::ZERO,
                duvdy: Vec2::ZERO,
                duv1dx: Vec2::ZERO,
                duv1dy: Vec2::ZERO,
            },
            dp,
            dn: [Vec3A::ZERO; 2],
        };
        let want_uv = self.needs_uv[hit.object];
        if !(want_uv || normals) {
            return Some(patch);
        }
        // What the shape needs of its hit (a mesh finds its barycentrics from the point).
        let shape_hit = ShapeHit {
            t: hit.t,
            part: hit.part,
            prim: hit.prim,
            bary: Vec2::ZERO,
        };
        let (duvdx, nx) = o
            .shape
            .differential(hit.tex.point, &shape_hit, dpdx, want_uv);
        let (duvdy, ny) = o
            .shape
            .differential(hit.tex.point, &shape_hit, dpdy, want_uv);
        patch.footprint.duvdx = duvdx * o.uv_scale;
        patch.footprint.duvdy = duvdy * o.uv_scale;
        if want_uv {
            let second = self.needs_uv1[hit.object]
                .then(|| second_uv_change(o, hit.prim, [dpdx, dpdy]))
                .flatten();
            let [x, y] = second.unwrap_or([duvdx, duvdy]);
            patch.footprint.duv1dx = x * o.uv_scale;
            patch.footprint.duv1dy = y * o.uv_scale;
        }
        if normals {
            // The normals there, to world space, less the hit's.
            let world = |n: Vec3A| {
                o.transform.as_ref().map_or(n, |t| t.normal_to_world(n)) - hit.shading_normal
            };
            patch.dn = [world(nx), world(ny)];
        }
        Some(patch)
    }
}
