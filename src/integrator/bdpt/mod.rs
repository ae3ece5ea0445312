//! Bidirectional path tracing (Veach; pbrt's BDPT): for each camera sample, a subpath from
//! the eye and one from a light chosen by power, joined at every pair of their vertices.
//! Each way of making a path of `s` light vertices and `t` camera vertices is a strategy:
//! `s = 0` the camera path finding a light, `s = 1` next-event estimation, `t = 1` light
//! tracing (its light lands anywhere on the film, as a splat), the rest a connection
//! between two surfaces. Every strategy's light is weighed by multiple importance sampling
//! against all the others that could have made the same path (mis.rs), so together they
//! count each path once: light through glass from a point light (a caustic), which only
//! light tracing finds, and the mirror and the glass themselves, which only the camera
//! path sees. Depth counts segments as the path tracer does: a path of `s + t` vertices
//! has `s + t - 1`, at most `max_depth`.

mod connect;
mod mis;
mod vertex;
mod walk;

use super::{LightView, RayStats};
use crate::math::{Color, Ray};
use crate::sampler::Sampler;
use crate::scene::{MisHeuristic, Scene};

/// Bidirectional path tracing.
#[derive(Clone, Copy, Debug, Default)]
pub struct Bdpt;

/// What every sample of a render shares: the scene, the camera and film, the scene's
/// bounding sphere, and the heuristic.
pub(crate) struct Context<'a> {
    scene: &'a Scene,
    view: LightView<'a>,
    mis: MisHeuristic,
    /// The sample's wavelength, in a scene that disperses light: both subpaths follow it
    /// wherever an index depends on it.
    nm: Option<f32>,
}

/// The reusable memory of one thread's samples: the two subpaths.
#[derive(Default)]
pub struct Paths {
    camera: Vec<vertex::Vertex>,
    light: Vec<vertex::Vertex>,
}

/// One strategy of a sample, for `snell explain` and strategy images: `s` vertices of the
/// light's subpath joined to `t` of the eye's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Strategy {
    /// Vertices from the light (0: the eye's path found a light itself).
    pub s: usize,
    /// Vertices from the eye, the eye included (1: joined to the eye, a splat).
    pub t: usize,
    /// The light the joined path carries, before its weight.
    pub light: Color,
    /// Its multiple importance sampling weight.
    pub weight: f32,
    /// Where it lands on the film (pixels), for `t = 1`; the sample's own pixel otherwise.
    pub film: Option<(f32, f32)>,
}

/// A vertex of a subpath as `snell explain` shows it: where it is, and what is there.
#[derive(Clone, Debug, PartialEq)]
pub struct ShownVertex {
    /// Where it is; for a light far away or the background, a point in its direction (a
    /// point of the disk a light subpath's rays left, or one unit along the ray that left
    /// the scene).
    pub point: crate::math::Vec3A,
    /// What it is: the eye, a light, an object and its material, or the background.
    pub what: String,
}

impl Paths {
    /// The vertices of the last sample's subpaths: the eye's (the eye included), the light's.
    pub fn lengths(&self) -> (usize, usize) {
        (self.camera.len(), self.light.len())
    }

    /// The last sample's subpaths, the eye's then the light's, vertex by vertex.
    pub fn shown(&self, scene: &Scene) -> (Vec<ShownVertex>, Vec<ShownVertex>) {
        let show = |v: &vertex::Vertex| ShownVertex {
            point: v.point,
            what: match &v.kind {
                vertex::Kind::Camera => "the eye".to_string(),
                vertex::Kind::Light { light, toward, .. } => {
                    let far = if toward.is_some() {
                        " (far away, in the direction of this point)"
                    } else {
                        ""
                    };
                    match &scene.lights[*light] {
                        crate::light::Light::Area(a) => {
                            format!("area light on `{}`", scene.objects[a.object].name)
                        }
                        l => format!("{}{far}", l.kind_name()),
                    }
                }
                vertex::Kind::Surface(s) => format!(
                    "`{}` ({})",
                    scene.objects[s.hit.object].name, scene.material_names[s.hit.material]
                ),
                vertex::Kind::Background => {
                    "the background (in the direction of this point)".to_string()
                }
            },
        };
        (
            self.camera.iter().map(show).collect(),
            self.light.iter().map(show).collect(),
        )
    }
}

impl Bdpt {
    /// The light of one camera sample along `ray` (a camera ray), with random numbers from
    /// `sampler` (started at this sample): the strategies with more than one camera vertex,
    /// for the pixel; each that joins a light vertex to the eye goes to `splat(x, y,
    /// colour)` (film position in pixels), for the pixel it lands in.
    #[allow(clippy::too_many_arguments)]
    pub fn sample(
        &self,
        scene: &Scene,
        view: &LightView,
        ray: &Ray,
        sampler: &mut Sampler,
        paths: &mut Paths,
        rays: &mut RayStats,
        splat: &mut impl FnMut(f32, f32, Color),
    ) -> Color {
        self.sample_with(scene, view, ray, sampler, paths, rays, splat, &mut |_| {})
    }

    /// [`Bdpt::sample`], telling `each` of every strategy that carried light.
    #[allow(clippy::too_many_arguments)]
    pub fn sample_with(
        &self,
        scene: &Scene,
        view: &LightView,
        ray: &Ray,
        sampler: &mut Sampler,
        paths: &mut Paths,
        rays: &mut RayStats,
        splat: &mut impl FnMut(f32, f32, Color),
        each: &mut impl FnMut(&Strategy),
    ) -> Color {
        let wavelength = scene
            .disperses()
            .then(|| crate::math::Wavelength::sample(sampler.next_1d()));
        let ctx = Context {
            scene,
            view: *view,
            mis: scene.settings.integrator.mis,
            nm: wavelength.map(|w| w.nm),
        };
        walk::camera_path(&ctx, ray, sampler, rays, &mut paths.camera);
        walk::light_path(&ctx, sampler, rays, &mut paths.light);
        let (camera, light) = (&paths.camera, &paths.light);
        let max_depth = scene.settings.max_depth as usize;
        let mut l = Color::ZERO;
        for t in 1..=camera.len() {
            // `s = 1` samples a light of its own: it runs even where the light subpath is
            // empty (its light sent nothing its way, or was blocked).
            for s in 0..=light.len().max(1) {
                if s + t < 2 || (s == 1 && t == 1) || s + t - 1 > max_depth {
                    continue;
                }
                let mut joined = connect::join(&ctx, light, camera, s, t, sampler, rays);
                // A path through a dispersive surface carries the wavelength's weight (once,
                // whichever side met it).
                if let Some(w) = wavelength
                    && (camera[t - 1].dispersed
                        || (s > 0 && light.get(s - 1).is_some_and(|v| v.dispersed)))
                {
                    joined.light *= w.weight;
                }
                if joined.light == Color::ZERO {
                    continue;
                }
                let weight = mis::weight(&ctx, light, camera, joined.sampled.as_ref(), s, t);
                each(&Strategy {
                    s,
                    t,
                    light: joined.light,
                    weight,
                    film: joined.film,
                });
                let c = joined.light * weight;
                match joined.film {
                    Some((x, y)) => splat(x, y, c),
                    None => l += c,
                }
            }
        }
        l
    }
}
