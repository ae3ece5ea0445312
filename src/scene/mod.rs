//! The scene: read from a file (`format`), checked and resolved (`load`), then immutable
//! and shared by every render thread.

mod assets;
mod cutout;
mod detail;
mod diag;
mod footprint;
pub mod format;
mod gltf;
mod inside;
mod limits;
mod load;
mod meshes;
mod mtl;
mod settings;
mod stats;
mod summary;

pub use crate::geometry::Object;
pub use assets::AssetCache;
pub use detail::UvFrame;
pub use diag::{DocPath, Format, Problem, SceneDiagnostic, SceneError, Seg, did_you_mean};
pub use footprint::{RayDifferentials, SurfacePatch};
pub use format::{IntegratorKind, MisHeuristic, schema, schema_of_types};
pub use limits::{Limits, MemoryEstimate, available_memory, memory_estimate};
pub use load::{
    Animation, MAX_FRAMES, MAX_MAGNITUDE, load, load_frame, load_str, load_str_frame,
    load_str_with, load_with,
};
pub use settings::{Fog, IntegratorSettings, RenderSettings};
pub use stats::{BuildStats, MeshStats};

use crate::accel::Bvh;
pub use crate::accel::{Reach, Skip};
use crate::camera::Camera;
use crate::geometry::{Leaving, Shape, ShapeHit};
use crate::light::{AreaLight, Environment, Light, LightSampler};
use crate::material::Material;
use crate::math::{Color, LANES, Ray, Vec3A};
use crate::texture::{Texture, TexturePoint};
use std::collections::BTreeMap;
use std::path::PathBuf;

/// Everything known about the closest hit of a ray.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    /// Ray parameter.
    pub t: f32,
    /// World-space point on the surface.
    pub point: Vec3A,
    /// Unit geometric normal, world space, pointing out of the solid (front side).
    pub normal: Vec3A,
    /// Unit shading normal, world space, on the same side as `normal`: the interpolated
    /// vertex normal of a smooth mesh, `normal` itself for every other shape.
    pub shading_normal: Vec3A,
    /// Index of the object hit.
    pub object: usize,
    /// Index of the material at the hit (objects with one material: theirs).
    pub material: usize,
    /// The mesh's triangle hit (0 for other shapes).
    pub prim: u32,
    /// The shape's part hit (side or cap, box face; 0 for shapes of one part).
    pub part: u8,
    /// What textures need, in object space.
    pub tex: TexturePoint<'static>,
}

/// A scene ready to render: immutable, shared by all threads.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The camera.
    pub camera: Camera,
    /// Image and sampling settings.
    pub settings: RenderSettings,
    /// Colour of rays that hit nothing.
    pub background: Color,
    /// Where in [`Scene::lights`] the environment (`[environment]`) is, if the scene has
    /// one (see [`Scene::environment`]).
    pub environment_light: Option<usize>,
    /// Global ambient light.
    pub ambient: Color,
    /// Optional fog.
    pub fog: Option<Fog>,
    /// The placed shapes, each with its material and transform (the BVH's leaves index
    /// this list).
    pub objects: Vec<Object>,
    /// Materials (objects refer to them by index).
    pub materials: Vec<Material>,
    /// Textures (materials refer to them by index).
    pub textures: Vec<Texture>,
    /// Names of the named textures, by index.
    pub texture_names: BTreeMap<String, usize>,
    /// Names of the materials, by index.
    pub material_names: Vec<String>,
    /// Every light, in one list: the point, spot and directional lights, then the emitting
    /// objects the path tracer samples as area lights, then the environment.
    pub lights: Vec<Light>,
    /// The names of the point, spot and directional lights (the first of
    /// [`Scene::lights`], in order): given by `name`, or the light's kind and index
    /// (`point #0`); a glTF file's lights are its object's (`lamp light #0`).
    pub light_names: Vec<String>,
    /// The light path expressions of its `[[image.lpe]]`, each checked against it: the
    /// images a render writes beside the picture.
    pub lpe: Vec<crate::lpe::Request>,
    /// Per object, which of the lights it is (see [`Scene::area_light_at`]).
    pub area_light_of: Vec<crate::light::ObjectLights>,
    /// The choice among all lights by power, for the path tracer.
    pub light_sampler: LightSampler,
    /// Things that are allowed but probably not meant.
    pub warnings: Vec<String>,
    /// What building the scene cost.
    pub stats: BuildStats,
    /// The limits it was checked against (the render is checked against them too).
    pub limits: Limits,
    accel: Bvh,
    /// Per object: whether its material is transparent.
    transparent: Vec<bool>,
    /// Indices of the transparent objects (shadow rays look through these).
    transparent_objects: Vec<usize>,
    /// Per object: whether its texture reads the shape's own uv.
    needs_uv: Vec<bool>,
    /// Per object: whether it is a mesh with a second uv set that a texture of it reads
    /// (the others' second uv is their first).
    needs_uv1: Vec<bool>,
    /// Per material: whether it reads a texture that varies over the surface.
    textured: Vec<bool>,
    /// Per material: whether the one texture it reads that varies is its colour's.
    base_only: Vec<bool>,
    /// Per object: whether a material of it has holes cut by alpha (see `cutout.rs`).
    cutouts: Vec<bool>,
    /// Whether any object has.
    any_cutout: bool,
    /// Per object: whether a ray inside it can only meet it (see `inside.rs`).
    alone_inside: Vec<bool>,
    /// Whether a material disperses light (see [`Scene::disperses`]).
    dispersive: bool,
    /// The files the scene read besides itself (textures, meshes, MTL files and their
    /// maps), sorted: what a preview watches for changes.
    pub files: Vec<PathBuf>,
    /// Its `[animation]`'s frame count and rate, if it has one.
    pub animation: Option<Animation>,
    /// The text it was built from (what a render's fingerprint hashes: the file as it was
    /// read, not as it may be when asked again).
    pub source: std::sync::Arc<str>,
    /// The frame of the animation this is (0 for a scene without one).
    pub frame: u32,
}

impl Scene {
    /// The differentials of a camera ray of this scene's camera and image (none where
    /// textures are not filtered), its neighbours brought as close as the pixel's samples
    /// lie.
    #[inline]
    pub fn camera_differentials(
        &self,
        ray: &Ray,
    ) -> Option<crate::math::differential::Differentials> {
        let s = &self.settings;
        s.filter_textures.then(|| {
            self.camera
                .differentials(ray, s.height)
                .scaled(crate::math::differential::camera_scale(s.spp))
        })
    }

    /// The area light a hit is on (its index in [`Scene::lights`]), if the path tracer
    /// samples the emission there.
    #[inline]
    pub fn area_light_at(&self, hit: &Hit) -> Option<usize> {
        self.area_light_of[hit.object].at(hit.prim)
    }

    /// Light `i` if it is an area light.
    #[inline]
    pub fn area_light(&self, i: usize) -> Option<&AreaLight> {
        match self.lights.get(i) {
            Some(Light::Area(a)) => Some(a),
            _ => None,
        }
    }

    /// The area lights, in their order in [`Scene::lights`].
    pub fn area_lights(&self) -> impl Iterator<Item = &AreaLight> {
        self.lights.iter().filter_map(|l| match l {
            Light::Area(a) => Some(a),
            _ => None,
        })
    }

    /// The environment (`[environment]`), if the scene has one.
    #[inline]
    pub fn environment(&self) -> Option<&Environment> {
        match self.lights.get(self.environment_light?) {
            Some(Light::Environment(e)) => Some(e),
            _ => None,
        }
    }

    /// Closest hit of a world ray in `(0, t_max)`, with its surface details.
    #[inline]
    pub fn closest_hit(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.closest_hit_skipping(ray, t_max, Skip::NONE)
    }

    /// [`Scene::closest_hit`] on every object but `skip` (see [`Scene::leaving`]).
    /// (Always inlined: docs/perf-log.md, "The seed's hot helpers inlined".)
    #[inline(always)]
    pub fn closest_hit_skipping(&self, ray: &Ray, t_max: f32, skip: Skip) -> Option<Hit> {
        if self.any_cutout {
            return self.closest_hit_past_holes(ray, t_max, skip, false);
        }
        let (i, h) = self.accel.closest_hit(&self.objects, ray, t_max, skip)?;
        Some(self.hit_details(ray, i, h, false))
    }

    /// What a ray leaving `hit`'s surface may leave out of its queries: the object hit, when
    /// the ray cannot meet it again (a flat shape, left on either side; a convex solid's
    /// surface, left on the side its outward normal points to, which `outward` says);
    /// otherwise nothing. The ray must really leave: its direction on the side it starts
    /// on, not along the surface.
    #[inline]
    pub fn leaving(&self, hit: &Hit, outward: bool) -> Skip {
        match self.objects[hit.object].shape.leaving() {
            Leaving::EitherSide => Skip::object(hit.object),
            Leaving::Outside if outward => Skip::object(hit.object),
            _ => Skip::NONE,
        }
    }

    /// Which objects the rays of `f` may meet (see [`Bvh::reach`]).
    #[inline]
    pub fn reach(&self, f: &crate::math::Frustum) -> Reach {
        self.accel.reach(&self.objects, f)
    }

    /// The largest coordinate, in size, of any bounded object's box.
    pub fn extent(&self) -> f32 {
        self.accel.extent()
    }

    /// Whether some material's index changes with wavelength: the physical integrators then
    /// draw a wavelength for every sample (and paths that meet such a material follow it),
    /// and scenes without one draw none and pay nothing.
    #[inline]
    pub fn disperses(&self) -> bool {
        self.dispersive
    }

    /// [`Scene::closest_hit`] of each of `rays` (any number; `out` as long), found a packet
    /// of [`LANES`] rays at a time (see [`Bvh::closest_hits`]): for the camera rays of a
    /// pixel, which mostly meet the same objects.
    /// `reach` says which objects the rays may meet at all ([`Reach::ALL`] where that is
    /// not known).
    pub fn closest_hits(&self, rays: &[Ray], out: &mut [Option<Hit>], reach: Reach) {
        assert_eq!(rays.len(), out.len(), "one hit per ray");
        let mut found = [None; LANES];
        for (rays, out) in rays.chunks(LANES).zip(out.chunks_mut(LANES)) {
            let found = &mut found[..rays.len()];
            self.accel.closest_hits(&self.objects, rays, found, reach);
            for ((ray, f), o) in rays.iter().zip(found.iter()).zip(out) {
                match f {
                    Some((i, _)) if self.any_cutout && self.cutouts[*i] => {
                        *o = self.closest_hit_past_holes(ray, f32::INFINITY, Skip::NONE, false)
                    }
                    // Field by field from the packet's entry, and the hit made straight into
                    // its slot: a whole entry, or a hit made aside, copied with loads wider
                    // than the stores that had just made it, which a processor cannot
                    // forward, waited for those stores to reach the cache.
                    Some((i, h)) => {
                        let h = ShapeHit {
                            t: h.t,
                            part: h.part,
                            prim: h.prim,
                            bary: h.bary,
                        };
                        *o = Some(self.hit_details(ray, *i, h, false));
                    }
                    None => *o = None,
                }
            }
        }
    }

    /// As [`Scene::closest_hit_skipping`], with the shape's uv worked out even where no
    /// texture reads it (for debug views).
    pub fn closest_hit_with_uv(&self, ray: &Ray, t_max: f32, skip: Skip) -> Option<Hit> {
        if self.any_cutout {
            return self.closest_hit_past_holes(ray, t_max, skip, true);
        }
        let (i, h) = self.accel.closest_hit(&self.objects, ray, t_max, skip)?;
        Some(self.hit_details(ray, i, h, true))
    }

    /// Closest hit in `(0, t_max)` without its surface details: the object's index and the
    /// shape's hit (what a ray query alone returns, for benchmarks and tools).
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(usize, ShapeHit)> {
        self.accel
            .closest_hit(&self.objects, ray, t_max, Skip::NONE)
    }

    /// Closest hit in `(0, t_max)` among the transparent objects only (cut-outs count as
    /// transparent, and their holes are gone through). Always inlined into the shadow ray's
    /// query, as the blocker's walk is.
    #[inline(always)]
    pub fn closest_transparent_hit(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let (mut r, mut left, mut travelled) = (*ray, t_max, 0.0);
        for k in 0..cutout::MAX_HOLES {
            let mut best: Option<(usize, ShapeHit)> = None;
            for &i in &self.transparent_objects {
                if let Some(h) = self.objects[i].intersect(&r, best.map_or(left, |b| b.1.t)) {
                    best = Some((i, h));
                }
            }
            let (i, h) = best?;
            let mut hit = self.hit_details(&r, i, h, self.cutouts[i]);
            // Past the last hole allowed, what the ray meets counts as solid.
            let last = k + 1 == cutout::MAX_HOLES;
            if last || !(self.cutouts[i] && self.is_hole(&hit, &r)) {
                hit.t += travelled;
                return Some(hit);
            }
            travelled += hit.t;
            (r, left) = Self::through(&hit, &r, left);
        }
        unreachable!("the last pass returns")
    }

    /// The radiance that area light `light` sends back along the ray from `origin` (unit
    /// direction `dir`) to a point a light sample chose `distance` away: its constant
    /// radiance, or where a texture gives it, the texture read where the ray meets the
    /// light's object (found by testing that object alone). Black where the ray misses it,
    /// which only a grazing ray at the light's rim can, where it sends next to nothing.
    pub fn emission_at(
        &self,
        light: &crate::light::AreaLight,
        origin: Vec3A,
        dir: Vec3A,
        distance: f32,
    ) -> Color {
        let Some(t) = light.texture else {
            return light.radiance;
        };
        let ray = Ray::new(origin, dir);
        let reach = distance * 1.001 + 1e-4;
        self.objects[light.object]
            .intersect(&ray, reach)
            .map_or(Color::ZERO, |h| {
                let hit = self.hit_details(&ray, light.object, h, true);
                self.textures[t].eval(&hit.tex)
            })
    }

    /// The radiance area light `light` sends from its point `p` (unit normal `n`, the side
    /// it leaves by): its constant radiance, or where a texture gives it, the texture read
    /// there (the light's object met from just off the point). For paths that start on a
    /// light (light tracing, bidirectional), whose sampled points carry the light's mean.
    pub fn emission_from(&self, light: &crate::light::AreaLight, p: Vec3A, n: Vec3A) -> Color {
        let origin = crate::math::offset_ray_origin(p, n);
        let reach = (origin - p).length() * 4.0;
        self.emission_at(light, origin, -n, reach)
    }

    /// Object `i`'s hit `h` of `ray` made whole: point, normals, material and texture point
    /// (its uv where a texture reads it, or where `force_uv` asks).
    /// (Always inlined: docs/perf-log.md, "The seed's hot helpers inlined".)
    #[inline(always)]
    fn hit_details(&self, ray: &Ray, i: usize, h: ShapeHit, force_uv: bool) -> Hit {
        /// Out of line: few objects have a second uv set, and `hit_details` is inlined
        /// into every ray query, which this would otherwise keep the inliner from doing.
        #[cold]
        #[inline(never)]
        fn second_uv(o: &Object, h: &ShapeHit) -> Option<crate::math::Vec2> {
            match &o.shape {
                Shape::Mesh(m) => m.second_uv(h),
                _ => None,
            }
        }
        let o = &self.objects[i];
        let want_uv = force_uv || self.needs_uv[i];
        let local = match &o.transform {
            None => *ray,
            Some(t) => t.ray_to_object(ray),
        };
        let s = o.shape.surface(local.at(h.t), &h, want_uv);
        let shading = match &o.shape {
            Shape::Mesh(m) => m.interpolated_normal(&h),
            _ => None,
        };
        let uv1 = if want_uv && self.needs_uv1[i] {
            second_uv(o, &h)
        } else {
            None
        };
        let (point, normal, shading_normal) = match &o.transform {
            None => (s.point, s.normal, shading.unwrap_or(s.normal)),
            Some(t) => {
                let n = t.normal_to_world(s.normal);
                (
                    t.point_to_world(s.point),
                    n,
                    shading.map_or(n, |sn| t.normal_to_world(sn)),
                )
            }
        };
        Hit {
            t: h.t,
            point,
            normal,
            shading_normal,
            object: i,
            material: o.material_at(&h),
            prim: h.prim,
            part: h.part,
            tex: TexturePoint {
                point: s.point,
                uv: s.uv * o.uv_scale,
                uv1: uv1.unwrap_or(s.uv) * o.uv_scale,
                center: o.center,
                footprint: None,
            },
        }
    }

    /// Whether an opaque object blocks the ray in `(0, t_max)`.
    #[inline]
    pub fn opaque_blocked(&self, ray: &Ray, t_max: f32) -> bool {
        self.accel
            .any_hit(&self.objects, ray, t_max, Skip::NONE, |i| {
                !self.transparent[i]
            })
    }

    /// Whether anything but `skip` blocks the ray in `(0, t_max)`, glass included (the path
    /// tracer's shadow rays). Always inlined into the path tracer's light sample, as it was
    /// before the refactoring moved the inliner's choices (docs/perf-log.md).
    #[inline(always)]
    pub fn occluded(&self, ray: &Ray, t_max: f32, skip: Skip) -> bool {
        if self.any_cutout {
            return self.occluded_past_holes(ray, t_max, skip);
        }
        self.accel
            .any_hit(&self.objects, ray, t_max, skip, |_| true)
    }

    /// An opaque object but `skip` that blocks the ray in `(0, t_max)`, if any (the first
    /// found), and whether the ray met the bounds of a transparent object but `skip` (or an
    /// unbounded one) on the way: if not, it crosses no glass but `skip` in `(0, t_max)`.
    #[inline]
    pub fn opaque_blocker_seeing_glass(
        &self,
        ray: &Ray,
        t_max: f32,
        skip: Skip,
    ) -> (Option<usize>, bool) {
        self.accel
            .first_blocker_and_others(&self.objects, ray, t_max, skip, |i| !self.transparent[i])
    }

    /// The uv the surface's texture reads at a hit: through its mapping (spherical, planar
    /// ...), or the shape's own where the surface is a plain colour. For debugging tools.
    pub fn texture_uv(&self, hit: &Hit) -> crate::math::Vec2 {
        let texture = &self.textures[self.material_at(hit).texture];
        match texture.pattern {
            crate::texture::Pattern::Solid(_) => hit.tex.uv,
            _ => texture.mapping.uv(&hit.tex),
        }
    }

    /// The base colour at a hit, read through `tex` (the hit's texture point, with its
    /// footprint where known): the material's texture, times a mesh's vertex colours.
    /// (Always inlined: docs/perf-log.md, "The seed's hot helpers inlined".)
    #[inline(always)]
    pub fn base_color(&self, hit: &Hit, tex: &TexturePoint) -> Color {
        let c = self.textures[self.material_at(hit).texture].eval(tex);
        match &self.objects[hit.object].shape {
            Shape::Mesh(m) if m.has_colors() => c * m.color_at(hit.tex.point, hit.prim),
            _ => c,
        }
    }

    /// The material at a hit.
    #[inline]
    pub fn material_at(&self, hit: &Hit) -> &Material {
        &self.materials[hit.material]
    }
}

#[cfg(test)]
mod tests;
