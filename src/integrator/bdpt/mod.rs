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
use crate::light::AreaLight;
use crate::math::{Color, Ray, Vec3A, offset_ray_origin};
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
}

impl Context<'_> {
    /// A textured area light's radiance at its point `p` (normal `n`).
    fn emission_at(&self, area: &AreaLight, p: Vec3A, n: Vec3A) -> Color {
        let origin = offset_ray_origin(p, n);
        let reach = (origin - p).length() * 4.0;
        self.scene.emission_at(area, origin, -n, reach)
    }
}

/// The reusable memory of one thread's samples: the two subpaths.
#[derive(Default)]
pub struct Paths {
    camera: Vec<vertex::Vertex>,
    light: Vec<vertex::Vertex>,
}

impl Bdpt {
    /// The light of one camera sample along `ray` (a camera ray), with random numbers from
    /// `sampler` (started at this sample): the strategies with more than one camera vertex,
    /// for the pixel; each that joins a light vertex to the eye goes to `splat(x, y,
    /// colour)` (film position in pixels), for the pixel it lands in.
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
        let ctx = Context {
            scene,
            view: *view,
            mis: scene.settings.integrator.mis,
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
                let joined = connect::join(&ctx, light, camera, s, t, sampler, rays);
                if joined.light == Color::ZERO {
                    continue;
                }
                let w = mis::weight(&ctx, light, camera, joined.sampled.as_ref(), s, t);
                let c = joined.light * w;
                match joined.film {
                    Some((x, y)) => splat(x, y, c),
                    None => l += c,
                }
            }
        }
        l
    }
}
