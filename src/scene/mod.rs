//! The scene: read from a file (`format`), checked and resolved (`build`), then immutable
//! and shared by every render thread.

mod build;
mod diag;
pub mod format;
mod meshes;

pub use build::{MAX_MAGNITUDE, load, load_str, load_with};
pub use diag::{DocPath, Format, Problem, SceneDiagnostic, SceneError, Seg, did_you_mean};
pub use format::schema;

use crate::accel::Bvh;
pub use crate::accel::Skip;
use crate::camera::Camera;
use crate::film::Filter;
use crate::geometry::{Leaving, Shape, ShapeHit};
use crate::light::Light;
use crate::material::Material;
use crate::math::{Aabb, Color, LANES, Ray, Transform, Vec3A};
use crate::texture::{Texture, TexturePoint};
use std::collections::BTreeMap;

/// Render settings from the scene's `[image]` table (the command line may override them).
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel, a square number.
    pub spp: u32,
    /// Longest chain of rays, the camera ray included.
    pub max_depth: u32,
    /// Seed of the sample jitter.
    pub seed: u64,
    /// Reconstruction filter.
    pub filter: Filter,
}

impl RenderSettings {
    /// Largest image side accepted (pixel coordinates must stay exact in an `f32`).
    pub const MAX_SIDE: u32 = 65_536;

    /// Checks an image side.
    pub fn check_side(what: &str, v: u32) -> Result<(), String> {
        if v == 0 || v > Self::MAX_SIDE {
            Err(format!(
                "{what} must be between 1 and {} pixels, not {v}",
                Self::MAX_SIDE
            ))
        } else {
            Ok(())
        }
    }
}

/// Sane maximums for what a scene and a render may ask for, so a typo (an extra zero) gets a
/// clear message instead of exhausting the machine. Each can be raised from the command line
/// (`--max-pixels`, `--max-spp`, `--max-depth`, `--max-texture-pixels`, `--max-triangles`),
/// up to the hard ceilings in [`Limits::CEILING`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Pixels in the image (width x height).
    pub max_pixels: u64,
    /// Samples per pixel.
    pub max_spp: u32,
    /// Longest chain of rays, the camera ray included.
    pub max_depth: u32,
    /// Texels in one image texture (width x height).
    pub max_texture_pixels: u64,
    /// Triangles in all the scene's meshes (each mesh counted once, however often placed).
    pub max_triangles: u64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_pixels: 1 << 28,         // 16384 x 16384: 3 GiB of film
            max_spp: 65_536,             // 256 x 256
            max_depth: 64,               // far beyond what a picture shows
            max_texture_pixels: 1 << 28, // 16384 x 16384: 3 GiB decoded
            max_triangles: 1 << 28,      // about 20 GiB of meshes and BVHs
        }
    }
}

impl Limits {
    /// The most any limit may be raised to: what the renderer can represent (a ray tree's
    /// recursion, `u32` indices), whatever memory the machine has.
    pub const CEILING: Limits = Limits {
        max_pixels: 1 << 32,
        max_spp: 1 << 24,
        max_depth: 256,
        max_texture_pixels: 1 << 32,
        max_triangles: 1 << 32,
    };

    /// Checks these limits against [`Limits::CEILING`]: the flag and the ceiling when one
    /// is above it.
    pub fn check(&self) -> Result<(), String> {
        let c = Limits::CEILING;
        for (flag, v, max) in [
            ("--max-pixels", self.max_pixels, c.max_pixels),
            ("--max-spp", self.max_spp as u64, c.max_spp as u64),
            ("--max-depth", self.max_depth as u64, c.max_depth as u64),
            (
                "--max-texture-pixels",
                self.max_texture_pixels,
                c.max_texture_pixels,
            ),
            ("--max-triangles", self.max_triangles, c.max_triangles),
        ] {
            if v == 0 || v > max {
                return Err(format!("{flag} must be between 1 and {max}, not {v}"));
            }
        }
        Ok(())
    }

    /// Checks a sample count: a square number (n x n strata) within the limit.
    pub fn check_spp(&self, spp: u32) -> Result<(), (String, Option<String>)> {
        let n = (spp as f64).sqrt().round() as u32;
        if spp == 0 || spp > self.max_spp {
            Err((
                format!(
                    "samples per pixel must be between 1 and {}, not {spp}",
                    self.max_spp
                ),
                (spp > self.max_spp).then(|| "raise the limit with --max-spp".to_string()),
            ))
        } else if n * n != spp {
            let lo = ((spp as f64).sqrt().floor() as u32).max(1);
            Err((
                format!("samples per pixel must be a square number (n x n stratified), not {spp}"),
                Some(format!(
                    "use {} ({lo} x {lo}) or {} ({} x {})",
                    lo * lo,
                    (lo + 1) * (lo + 1),
                    lo + 1,
                    lo + 1
                )),
            ))
        } else {
            Ok(())
        }
    }

    /// Checks the pixel count, so a huge image is refused instead of exhausting memory.
    pub fn check_pixels(&self, width: u32, height: u32) -> Result<(), (String, Option<String>)> {
        let pixels = width as u64 * height as u64;
        if pixels > self.max_pixels {
            Err((
                format!(
                    "{width} x {height} is {pixels} pixels, more than the {} a render may have; the image alone would need {:.1} GiB",
                    self.max_pixels,
                    pixels as f64 * Self::BYTES_PER_PIXEL as f64 / GIB
                ),
                Some("make it smaller, or raise the limit with --max-pixels".into()),
            ))
        } else {
            Ok(())
        }
    }

    /// Checks the longest ray chain.
    pub fn check_depth(&self, depth: u32) -> Result<(), (String, Option<String>)> {
        if depth == 0 || depth > self.max_depth {
            Err((
                format!(
                    "must be between 1 (camera rays only) and {}, not {depth}",
                    self.max_depth
                ),
                (depth > self.max_depth).then(|| "raise the limit with --max-depth".to_string()),
            ))
        } else {
            Ok(())
        }
    }

    /// Bytes a render keeps per pixel: the film (three `f32`), the finished tiles (three
    /// more, kept for checkpoints) and the encoded output.
    pub const BYTES_PER_PIXEL: u64 = 12 + 12 + 4;
}

const GIB: f64 = (1u64 << 30) as f64;

/// Memory a render of `scene` at its settings needs, roughly, in bytes: the image (see
/// [`Limits::BYTES_PER_PIXEL`]), the meshes and BVHs, and the decoded textures.
pub fn memory_estimate(scene: &Scene) -> MemoryEstimate {
    let s = &scene.settings;
    MemoryEstimate {
        image: s.width as u64 * s.height as u64 * Limits::BYTES_PER_PIXEL,
        geometry: (scene.stats.bvh_bytes + scene.stats.mesh_bytes) as u64,
        textures: scene.textures.iter().map(|t| t.bytes() as u64).sum(),
    }
}

/// What a render will take in memory, by part.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemoryEstimate {
    /// Film, tiles and output.
    pub image: u64,
    /// Meshes and BVHs.
    pub geometry: u64,
    /// Decoded image textures.
    pub textures: u64,
}

impl MemoryEstimate {
    /// All of it.
    pub fn total(&self) -> u64 {
        self.image + self.geometry + self.textures
    }

    /// Refuses the render when it would need more than `available` bytes, with the estimate.
    pub fn check(&self, available: u64) -> Result<(), String> {
        if self.total() > available {
            Err(format!(
                "this render would need about {:.1} GiB (image {:.1} GiB, meshes and BVHs {:.1} GiB, textures {:.1} GiB), but only {:.1} GiB of memory is available",
                self.total() as f64 / GIB,
                self.image as f64 / GIB,
                self.geometry as f64 / GIB,
                self.textures as f64 / GIB,
                available as f64 / GIB
            ))
        } else {
            Ok(())
        }
    }
}

/// Memory the system can still give (Linux's `MemAvailable`); `None` where unknown.
pub fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Fog over distance travelled outside solids.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fog {
    /// Fog fraction rises linearly from 0 at `start` to 1 at `end`.
    Linear {
        /// Colour of full fog.
        color: Color,
        /// Distance where it starts.
        start: f32,
        /// Distance where it is complete.
        end: f32,
    },
    /// Fog fraction `1 - exp(-density * (distance - start))` beyond `start`.
    Exponential {
        /// Colour of full fog.
        color: Color,
        /// Distance where it starts.
        start: f32,
        /// Per scene unit.
        density: f32,
    },
}

impl Fog {
    /// Blends `c`, seen from `distance` away, toward the fog colour.
    #[inline]
    pub fn apply(&self, c: Color, distance: f32) -> Color {
        let (fog, f) = match *self {
            Fog::Linear { color, start, end } => {
                (color, ((distance - start) / (end - start)).clamp(0.0, 1.0))
            }
            Fog::Exponential {
                color,
                start,
                density,
            } => (color, 1.0 - (-density * (distance - start).max(0.0)).exp()),
        };
        c.lerp(fog, f)
    }
}

/// What building a scene cost, for `snell render --stats`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BuildStats {
    /// Time reading mesh files.
    pub mesh_load_time: std::time::Duration,
    /// Time building the meshes' BVHs.
    pub mesh_bvh_time: std::time::Duration,
    /// Time building the BVH over the objects.
    pub object_bvh_time: std::time::Duration,
    /// Objects in the scene (each placement of a mesh counts once).
    pub objects: usize,
    /// Distinct meshes (shared by their placements).
    pub meshes: usize,
    /// Triangles in the distinct meshes.
    pub unique_triangles: usize,
    /// Triangles in the scene, every placement counted.
    pub instanced_triangles: usize,
    /// Bytes of all BVHs: the meshes' and the objects'.
    pub bvh_bytes: usize,
    /// Bytes of the distinct meshes' triangles, normals and uvs.
    pub mesh_bytes: usize,
    /// Each distinct mesh, in the order first placed.
    pub per_mesh: Vec<MeshStats>,
}

/// One distinct mesh of a scene: its file, triangles and placements.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MeshStats {
    /// The file as the scene names it.
    pub file: String,
    /// Triangles loaded from the file (degenerate ones dropped).
    pub triangles: usize,
    /// Objects that place it.
    pub placements: usize,
}

impl BuildStats {
    /// Counts objects, meshes and triangles.
    /// `file_of` names the file a mesh was read from.
    pub(crate) fn record_objects(
        &mut self,
        objects: &[Object],
        file_of: impl Fn(&std::sync::Arc<crate::geometry::Mesh>) -> String,
    ) {
        let mut seen = std::collections::HashMap::new();
        self.objects = objects.len();
        for o in objects {
            if let Shape::Mesh(m) = &o.shape {
                self.instanced_triangles += m.triangle_count();
                let i = *seen.entry(std::sync::Arc::as_ptr(m)).or_insert_with(|| {
                    self.meshes += 1;
                    self.unique_triangles += m.triangle_count();
                    self.bvh_bytes += m.bvh_bytes();
                    self.mesh_bytes += m.geometry_bytes();
                    self.per_mesh.push(MeshStats {
                        file: file_of(m),
                        triangles: m.triangle_count(),
                        placements: 0,
                    });
                    self.per_mesh.len() - 1
                });
                self.per_mesh[i].placements += 1;
            }
        }
    }
}

/// A shape placed in the scene with its material.
#[derive(Clone, Debug)]
pub struct Object {
    /// Name for messages (given, or type and index).
    pub name: String,
    /// The shape, in object space.
    pub shape: Shape,
    /// Object to world placement; `None` when object space is world space.
    pub transform: Option<Transform>,
    /// Index into `Scene::materials`.
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

    /// The material (index into `Scene::materials`) at a hit on this object.
    #[inline]
    pub fn material_at(&self, hit: &ShapeHit) -> usize {
        match &self.shape {
            Shape::Mesh(m) if !self.slot_materials.is_empty() => self
                .slot_materials
                .get(m.slot(hit.prim) as usize)
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
    /// What textures need, in object space.
    pub tex: TexturePoint,
}

/// A scene ready to render: immutable, shared by all threads.
#[derive(Debug)]
pub struct Scene {
    /// The camera.
    pub camera: Camera,
    /// Image and sampling settings.
    pub settings: RenderSettings,
    /// Colour of rays that hit nothing.
    pub background: Color,
    /// Global ambient light.
    pub ambient: Color,
    /// Optional fog.
    pub fog: Option<Fog>,
    /// Shapes.
    pub objects: Vec<Object>,
    /// Materials (objects refer to them by index).
    pub materials: Vec<Material>,
    /// Textures (materials refer to them by index).
    pub textures: Vec<Texture>,
    /// Names of the named textures, by index.
    pub texture_names: BTreeMap<String, usize>,
    /// Names of the materials, by index.
    pub material_names: Vec<String>,
    /// Light sources.
    pub lights: Vec<Light>,
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
}

impl Scene {
    /// Closest hit of a world ray in `(0, t_max)`, with its surface details.
    #[inline]
    pub fn closest_hit(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.closest_hit_skipping(ray, t_max, Skip::NONE)
    }

    /// [`Scene::closest_hit`] on every object but `skip` (see [`Scene::leaving`]).
    #[inline]
    pub fn closest_hit_skipping(&self, ray: &Ray, t_max: f32, skip: Skip) -> Option<Hit> {
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

    /// [`Scene::closest_hit`] of each of `rays` (any number; `out` as long), found a packet
    /// of [`LANES`] rays at a time (see [`Bvh::closest_hits`]): for the camera rays of a
    /// pixel, which mostly meet the same objects.
    pub fn closest_hits(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        assert_eq!(rays.len(), out.len(), "one hit per ray");
        let mut found = [None; LANES];
        for (rays, out) in rays.chunks(LANES).zip(out.chunks_mut(LANES)) {
            let found = &mut found[..rays.len()];
            self.accel.closest_hits(&self.objects, rays, found);
            for ((ray, f), o) in rays.iter().zip(found.iter()).zip(out) {
                *o = f.map(|(i, h)| self.hit_details(ray, i, h, false));
            }
        }
    }

    /// As [`Scene::closest_hit_skipping`], with the shape's uv worked out even where no
    /// texture reads it (for debug views).
    pub fn closest_hit_with_uv(&self, ray: &Ray, t_max: f32, skip: Skip) -> Option<Hit> {
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

    /// Closest hit in `(0, t_max)` among the transparent objects only.
    #[inline]
    pub fn closest_transparent_hit(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let mut best: Option<(usize, ShapeHit)> = None;
        for &i in &self.transparent_objects {
            if let Some(h) = self.objects[i].intersect(ray, best.map_or(t_max, |b| b.1.t)) {
                best = Some((i, h));
            }
        }
        best.map(|(i, h)| self.hit_details(ray, i, h, false))
    }

    fn hit_details(&self, ray: &Ray, i: usize, h: ShapeHit, force_uv: bool) -> Hit {
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
            tex: TexturePoint {
                point: s.point,
                uv: s.uv * o.uv_scale,
                center: o.center,
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

    /// The material at a hit.
    #[inline]
    pub fn material_at(&self, hit: &Hit) -> &Material {
        &self.materials[hit.material]
    }

    /// A short human summary: counts of objects by type, lights, textures, materials.
    pub fn summary(&self) -> String {
        let mut kinds: BTreeMap<&str, usize> = BTreeMap::new();
        for o in &self.objects {
            *kinds.entry(o.shape.kind()).or_default() += 1;
        }
        let kinds: Vec<String> = kinds.iter().map(|(k, n)| format!("{n} {k}")).collect();
        let mut lights: BTreeMap<&str, usize> = BTreeMap::new();
        for l in &self.lights {
            let k = match l {
                Light::Point { .. } => "point",
                Light::Directional { .. } => "directional",
                Light::Spot { .. } => "spot",
            };
            *lights.entry(k).or_default() += 1;
        }
        let lights: Vec<String> = lights.iter().map(|(k, n)| format!("{n} {k}")).collect();
        let s = &self.settings;
        let mut meshes = String::new();
        let st = &self.stats;
        if st.meshes > 0 {
            meshes = format!(
                "\nmeshes:    {} ({} triangles loaded, {} placed)",
                st.meshes, st.unique_triangles, st.instanced_triangles
            );
            for m in &st.per_mesh {
                meshes += &format!(
                    "\n  {}: {} triangles, placed {} time{} ({} triangles)",
                    m.file,
                    m.triangles,
                    m.placements,
                    if m.placements == 1 { "" } else { "s" },
                    m.triangles * m.placements
                );
            }
        }
        format!(
            "image:     {} x {}, {} spp, max depth {}, seed {}\nobjects:   {} ({})\nlights:    {} ({})\nmaterials: {}\ntextures:  {}{}{meshes}",
            s.width,
            s.height,
            s.spp,
            s.max_depth,
            s.seed,
            self.objects.len(),
            kinds.join(", "),
            self.lights.len(),
            lights.join(", "),
            self.material_names.len(),
            self.texture_names.len(),
            if self.texture_names.is_empty() {
                String::new()
            } else {
                format!(
                    " ({})",
                    self.texture_names
                        .keys()
                        .cloned()
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            }
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::test_util::in_unit_cube;
    use crate::math::Rng;
    use std::path::Path;

    fn scene(objects: &str) -> Scene {
        let text = format!("[camera]\nlook_at = [0, 0, -1]\n[materials.m]\ncolor = 1\n{objects}");
        load_str(&text, Path::new("t.toml"), Path::new("."), Format::Toml).unwrap()
    }

    fn object(kind: &str, rest: &str) -> String {
        format!("[[objects]]\ntype = \"{kind}\"\nmaterial = \"m\"\n{rest}\n")
    }

    /// A ray leaving a surface finds the same hit whether or not its walk leaves out the
    /// object it leaves (`Scene::leaving`), and the object's own test misses it: for every
    /// kind of analytic shape, placed as given and mirrored, sheared and turned by
    /// transforms, in the flat layout and in a tree, for shadow-like and reflected rays
    /// from the offset origins the renderer uses. Rays leaving solids inward skip nothing.
    #[test]
    fn leaving_a_surface_skips_only_what_cannot_be_met() {
        let shapes = [
            object("sphere", "center = [0, 0, -10]\nradius = 2"),
            object("box", "min = [2, -3, -14]\nmax = [4, -1, -12]"),
            object(
                "cylinder",
                "base = [-3, -3, -12]\naxis = [0, 1, 0]\nradius = 1\nheight = 3\ncapped = true",
            ),
            object(
                "cone",
                "base = [3, 1, -9]\naxis = [0.2, 1, 0]\nradius = 1\nheight = 2\ncapped = false",
            ),
            object(
                "sphere",
                "radius = 1\ntransform = { scale = [-2, 1, 0.7], rotate = [30, 10, 0], translate = [1, 2, -9] }",
            ),
            object(
                "box",
                "min = [-1, -1, -1]\nmax = [1, 1, 1]\ntransform = { scale = [1, -0.5, 2], rotate = [0, 45, 20], translate = [-2, 2, -13] }",
            ),
            object("disk", "center = [0, 2, -16]\nnormal = [0, 0, 1]\nradius = 2"),
            object(
                "rectangle",
                "corner = [-5, -3, -20]\nedge_u = [10, 0, 0]\nedge_v = [0, 0, 15]",
            ),
            object("plane", "point = [0, -3.5, 0]"),
        ]
        .concat();
        let crowd: String = (0..12)
            .map(|i| {
                object(
                    "sphere",
                    &format!(
                        "center = [{}, {}, -11]\nradius = 0.9",
                        i % 4 * 2 - 3,
                        i / 4 * 2 - 2
                    ),
                )
            })
            .collect();
        let mut rng = Rng::new(17);
        for (scene, name) in [
            (scene(&shapes), "shapes"),
            (scene(&(shapes.clone() + &crowd)), "tree"),
        ] {
            let (mut skipped, mut inward) = (0, 0);
            for _ in 0..6000 {
                let eye = in_unit_cube(&mut rng) * 16.0 + Vec3A::new(0.0, 0.0, -10.0);
                let to = in_unit_cube(&mut rng) * 6.0 + Vec3A::new(0.0, 0.0, -11.0);
                let Some(hit) =
                    scene.closest_hit(&Ray::new(eye, (to - eye).normalize()), f32::INFINITY)
                else {
                    continue;
                };
                let dir_in = (to - eye).normalize();
                let outward = dir_in.dot(hit.normal) < 0.0;
                let n = if outward { hit.normal } else { -hit.normal };
                // A random direction on the side the ray arrived from.
                let mut d = (in_unit_cube(&mut rng) * 2.0 - Vec3A::ONE).normalize_or(n);
                if d.dot(n) < 0.0 {
                    d = -d;
                }
                if d.dot(n) < 1e-3 {
                    continue;
                }
                let ray = Ray::new(crate::math::offset_ray_origin(hit.point, n), d);
                let skip = scene.leaving(&hit, outward);
                if skip == Skip::NONE {
                    inward += 1;
                } else {
                    skipped += 1;
                    assert!(
                        scene.objects[hit.object]
                            .intersect(&ray, f32::INFINITY)
                            .is_none(),
                        "{name}: {} met again",
                        scene.objects[hit.object].name
                    );
                }
                let key = |h: Option<Hit>| h.map(|h| (h.object, h.t.to_bits()));
                assert_eq!(
                    key(scene.closest_hit_skipping(&ray, f32::INFINITY, skip)),
                    key(scene.closest_hit(&ray, f32::INFINITY)),
                    "{name}: {ray:?} leaving {}",
                    scene.objects[hit.object].name
                );
            }
            assert!(
                skipped > 1000 && inward > 50,
                "{name}: {skipped} skipped, {inward} inward"
            );
        }
    }

    /// Hits found a packet at a time are the hits found one ray at a time, to the bit: in a
    /// scene of every kind of shape (the flat layout, an unbounded plane, a transformed
    /// sphere), in one of many spheres (the tree) and in one of a lone sphere; for camera
    /// rays of one pixel and for rays in every direction, in whole and partial packets.
    #[test]
    fn packets_find_what_single_rays_find() {
        let every_kind = [
            object("sphere", "center = [0, 0, -10]\nradius = 2"),
            object(
                "rectangle",
                "corner = [-5, -3, -20]\nedge_u = [10, 0, 0]\nedge_v = [0, 0, 15]",
            ),
            object("box", "min = [2, -3, -14]\nmax = [4, -1, -12]"),
            object(
                "cylinder",
                "base = [-3, -3, -12]\naxis = [0, 1, 0]\nradius = 1\nheight = 3\ncapped = true",
            ),
            object(
                "sphere",
                "radius = 1\ntransform = { scale = [2, 1, 1], translate = [1, 2, -9] }",
            ),
            object(
                "disk",
                "center = [0, 2, -16]\nnormal = [0, 0, 1]\nradius = 2",
            ),
            object(
                "triangle",
                "vertices = [[-4, 0, -8], [-2, 0, -9], [-3, 2, -8.5]]",
            ),
            object("plane", "point = [0, -3.5, 0]"),
        ]
        .concat();
        let many: String = (0..20)
            .map(|i| {
                object(
                    "sphere",
                    &format!(
                        "center = [{}, {}, -12]\nradius = 0.8",
                        i % 5 * 2 - 4,
                        i / 5 * 2 - 3
                    ),
                )
            })
            .collect();
        let lone = [
            object("sphere", "center = [0, 0, -10]\nradius = 2"),
            object("plane", "point = [0, -3, 0]"),
        ]
        .concat();
        let mut rng = Rng::new(3);
        for (name, text) in [("every kind", every_kind), ("many", many), ("lone", lone)] {
            let scene = scene(&text);
            let mut hits = 0;
            for round in 0..3000 {
                let n = [16, 8, 3, 13][round % 4];
                let camera_like = round % 2 == 0;
                let center = Vec3A::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, -1.0);
                let rays: Vec<Ray> = (0..n)
                    .map(|_| {
                        let jitter = Vec3A::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, 0.0);
                        if camera_like {
                            Ray::new(Vec3A::ZERO, (center + jitter * 0.01).normalize())
                        } else {
                            let o = in_unit_cube(&mut rng) * 20.0 - Vec3A::new(0.0, 0.0, 15.0);
                            Ray::new(o, in_unit_cube(&mut rng).normalize())
                        }
                    })
                    .collect();
                let mut found = vec![None; n];
                scene.closest_hits(&rays, &mut found);
                for (ray, got) in rays.iter().zip(&found) {
                    let want = scene.closest_hit(ray, f32::INFINITY);
                    // Debug prints every float exactly (the shortest form that reads back).
                    assert_eq!(format!("{got:?}"), format!("{want:?}"), "{name}: {ray:?}");
                    hits += want.is_some() as usize;
                }
            }
            assert!(hits > 5000, "{name}: {hits} hits");
        }
    }
}
