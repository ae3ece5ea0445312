//! The patch of surface a pixel sees at a hit, from the ray's differentials: what texture
//! filtering reads, and what a mirror or glass needs to pass the differentials on; and
//! where a bound on it shows a texture one colour over it, so that none need be worked out.

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
    /// (Always inlined: docs/perf-log.md, "The seed's hot helpers inlined".)
    #[inline(always)]
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

    /// The most a camera ray's differentials ([`Scene::camera_differentials`]) turn its
    /// direction: `None` where it has none, or its neighbours are offset (parallel rays).
    #[inline]
    pub fn camera_spread(&self) -> Option<f32> {
        let s = &self.settings;
        let spread = self.camera.pixel_spread(s.height)?;
        s.filter_textures
            .then(|| spread * crate::math::differential::camera_scale(s.spp))
    }

    /// Whether the material at `hit` reads one colour over any footprint that reaches no
    /// further than `reach` (world units) from the hit: its one varying texture is its
    /// colour's, the object is placed without a transform (so its space is the world's),
    /// and that texture says so ([`crate::texture::Texture::flat_within`]).
    /// (Always inlined: docs/perf-log.md, "The seed's hot helpers inlined".)
    #[inline(always)]
    pub fn texture_flat_within(&self, hit: &Hit, reach: f32) -> bool {
        self.base_only[hit.material]
            && self.objects[hit.object].transform.is_none()
            && self.textures[self.materials[hit.material].texture].flat_within(&hit.tex, reach)
    }

    /// Whether the textures at `hit` are one colour over the footprint of `ray`'s
    /// differentials `diff`, from a bound on the footprint that needs no footprint worked out
    /// ([`Scene::texture_flat_within`]). A neighbour whose origin is `do` and direction `dd`
    /// away meets the hit's tangent plane at
    /// `do + (dd c t - d f - dd f - d t e) / (c + e)` from the hit (`c = n . d`, `e = n . dd`,
    /// `f = n . do`, `t` the hit's distance along the unit `d`), no further than
    /// `|do| + (|dd| t (|c| + 1) + |do| (1 + |dd|)) / (|c| - |dd|)`; a camera ray's neighbours
    /// share its origin and turn by at most the camera's spread. Where that is inside one cell
    /// of a checker, the texture read at the point is what the footprint's filter gives, and
    /// the footprint is not worked out: most of a checker floor, seen or mirrored.
    /// (Always inlined: docs/perf-log.md, "The seed's hot helpers inlined".)
    #[inline(always)]
    pub fn footprint_is_flat(&self, ray: &Ray, hit: &Hit, diff: &RayDifferentials) -> bool {
        let c = ray.dir.dot(hit.normal).abs();
        let t = hit.t;
        let reach = |origin: f32, turn: f32| {
            (c > 2.0 * turn)
                .then(|| origin + (turn * t * (c + 1.0) + origin * (1.0 + turn)) / (c - turn))
        };
        let reach = match diff {
            RayDifferentials::None => None,
            RayDifferentials::Camera => self.camera_spread().and_then(|spread| reach(0.0, spread)),
            RayDifferentials::Known(d) => reach(d.dx_origin.length(), d.dx_dir.length())
                .zip(reach(d.dy_origin.length(), d.dy_dir.length()))
                .map(|(x, y)| x.max(y)),
        };
        // A hundredth more, for the rounding of the footprint's own arithmetic.
        reach.is_some_and(|r| self.texture_flat_within(hit, r * 1.01))
    }
}

#[cfg(test)]
mod tests {
    /// Where a camera ray's footprint, or a mirrored ray's, is taken as flat without working
    /// it out, the texture read at the point is what the filter over the footprint gives, to
    /// the bit: a checker and stripes on floors under a tilted camera, at several sample
    /// counts, for camera rays and for rays with differentials of their own (as a mirror passes
    /// on); and both kinds of hit are found.
    #[test]
    fn a_flat_footprint_reads_what_the_filter_gives() {
        use crate::math::{Rng, Vec3A};
        use crate::scene::{Format, RayDifferentials, load_str};
        use crate::texture::TexturePoint;
        use std::path::Path;
        // Per kind of ray (camera, own differentials): footprints found flat, and not.
        let (mut flat, mut filtered) = ([0; 2], [0; 2]);
        for (spp, texture) in [
            (
                16,
                "type = \"checker\"\neven = [0.9, 0.8, 0.1]\nodd = [0.05, 0.2, 0.6]\nsize = 0.7",
            ),
            (4, "type = \"checker\"\nsize = 0.25"),
            (
                1,
                "type = \"stripes\"\na = [0.3, 0.7, 0.2]\nb = [1, 0.4, 0.9]\nwidth = 0.4",
            ),
        ] {
            let text = format!(
                "[image]\nwidth = 256\nheight = 192\nsamples = {spp}\n\
                 [camera]\nposition = [0, 2, 6]\nlook_at = [1, 0, -10]\nfov = 50\n\
                 [textures.t]\n{texture}\n\
                 mapping = {{ type = \"planar\", origin = [0.3, 0, 0.1], u = [1, 0, 0.2], v = [0, 0, 1.5] }}\n\
                 [materials.m]\ntexture = \"t\"\n\
                 [[objects]]\ntype = \"rectangle\"\ncorner = [-30, -1, 8]\nedge_u = [60, 0, 0]\nedge_v = [0, 0, -80]\nmaterial = \"m\"\n"
            );
            let scene = load_str(&text, Path::new("t.toml"), Path::new("."), Format::Toml).unwrap();
            let camera = scene.camera.raster(256, 192);
            let mut rng = Rng::new(spp as u64);
            let mut random = |scale: f32| {
                Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * (2.0 * scale) - scale
            };
            for k in 0..40_000 {
                // Camera rays, and rays with differentials of their own (as a mirror passes
                // on): from above the floor, down, their neighbours apart and turning.
                let (ray, diff) = if k % 2 == 0 {
                    let (x, y) = (random(128.0).x + 128.0, random(96.0).y + 96.0);
                    let ray = camera.ray(x, y);
                    (ray, RayDifferentials::Camera)
                } else {
                    let origin = random(5.0) + Vec3A::new(0.0, 6.0, -5.0);
                    let dir = (random(1.0) - Vec3A::Y * 1.2).normalize();
                    let d = crate::math::differential::Differentials {
                        dx_origin: random(0.02),
                        dx_dir: random(0.004),
                        dy_origin: random(0.02),
                        dy_dir: random(0.004),
                    };
                    (
                        crate::math::Ray::new(origin, dir),
                        RayDifferentials::Known(d),
                    )
                };
                let Some(hit) = scene.closest_hit(&ray, f32::INFINITY) else {
                    continue;
                };
                let Some(d) = diff.of(&scene, &ray) else {
                    continue;
                };
                let patch = scene.patch(&hit, &ray, &d, false);
                let footprint = patch.as_ref().map(|p| &p.footprint);
                let tex = TexturePoint {
                    footprint,
                    ..hit.tex
                };
                let through = scene.base_color(&hit, &tex);
                if scene.footprint_is_flat(&ray, &hit, &diff) {
                    let at_point = scene.base_color(&hit, &hit.tex);
                    assert_eq!(
                        at_point.to_array().map(f32::to_bits),
                        through.to_array().map(f32::to_bits),
                        "{spp} spp, {ray:?}"
                    );
                    flat[k % 2] += 1;
                } else {
                    filtered[k % 2] += 1;
                }
                assert!(hit.point.is_finite() && hit.normal != Vec3A::ZERO);
            }
        }
        for kind in 0..2 {
            assert!(
                flat[kind] > 2_000 && filtered[kind] > 500,
                "{flat:?} flat, {filtered:?} filtered"
            );
        }
    }
}
