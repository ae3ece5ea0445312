//! Ways of turning a camera ray into a colour. One file per integrator; they are chosen
//! once per render, so a trait object is fine here.

pub mod aov;
mod bdpt;
mod escape;
pub mod explain;
mod light_tracer;
mod path;
pub mod path_explain;
mod whitted;

pub use bdpt::{Bdpt, Paths, ShownVertex, Strategy};
pub use escape::{Escape, Traced};
pub use light_tracer::{LightTracer, LightView};
pub use path::Path;
pub use whitted::Whitted;

use crate::math::{Color, Ray};
use crate::sampler::Sampler;
use crate::scene::{IntegratorKind, Reach, Scene};

/// The integrator a scene's settings choose. Light tracing and bidirectional path tracing
/// have no integrator of camera rays alone (their renders go through `render::light` and
/// `render::bdpt`, as their light lands anywhere on the film): what asks one camera ray's
/// colour of such a scene (an estimate of its time, the preview's stand-in) gets the path
/// tracer, which they agree with.
pub fn chosen(kind: IntegratorKind) -> &'static dyn Integrator {
    match kind {
        IntegratorKind::Whitted => &Whitted,
        IntegratorKind::Path | IntegratorKind::Light | IntegratorKind::Bdpt => &Path,
    }
}

/// Where a batch of camera rays starts: its first sample's pixel and index in the pixel
/// (the rest follow in order).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BatchStart {
    /// The pixel's column.
    pub x: u32,
    /// The pixel's row.
    pub y: u32,
    /// The first ray's sample index in the pixel.
    pub index: u32,
    /// Which objects the batch's rays may meet ([`Reach::ALL`] where that is not known).
    pub reach: Reach,
}

/// Computes the colour seen along a camera ray.
pub trait Integrator: Sync {
    /// Linear RGB arriving along `ray` (a camera ray, unit direction). Every ray traced for
    /// it is counted in `rays`.
    fn radiance(&self, scene: &Scene, ray: &Ray, rays: &mut RayStats) -> Color;

    /// [`Integrator::radiance`] of each ray of `batch`, into `out` (as long as `batch`): the
    /// camera rays of one pixel, samples `first.index`, `first.index + 1`... of pixel
    /// `(first.x, first.y)`, which an integrator may trace together (the same colours, to
    /// the bit, as one ray at a time where it draws nothing from the samples' indices).
    fn radiance_batch(
        &self,
        scene: &Scene,
        batch: &[Ray],
        first: BatchStart,
        out: &mut [Color],
        rays: &mut RayStats,
    ) {
        let _ = first;
        for (ray, o) in batch.iter().zip(out) {
            *o = self.radiance(scene, ray, rays);
        }
    }

    /// The colour of every camera ray that meets nothing, where it is one colour whatever
    /// the ray's direction (`None` where it is not, or where the integrator does not say):
    /// a pixel none of whose rays can meet anything then takes it for each sample without
    /// tracing them ([`crate::render::PixelJob`]). The same colour, to the bit, as
    /// [`Integrator::radiance_batch`] gives such a ray.
    fn camera_miss(&self, scene: &Scene) -> Option<Color> {
        let _ = scene;
        None
    }

    /// Whether each sample draws its random numbers from a [`Sampler`] (through
    /// [`Integrator::radiance_sampled`]): then a pixel's samples are placed by the sampler
    /// too, and any number of them is allowed. Whitted's are stratified jitter.
    fn uses_sampler(&self) -> bool {
        false
    }

    /// The colour seen along a camera ray with random numbers from `sampler`, started at
    /// this sample (whose first two numbers placed the ray on the film).
    fn radiance_sampled(
        &self,
        scene: &Scene,
        ray: &Ray,
        sampler: &mut Sampler,
        rays: &mut RayStats,
    ) -> Color {
        let _ = sampler;
        self.radiance(scene, ray, rays)
    }

    /// [`Integrator::radiance_sampled`], perhaps unfinished ([`Traced::resolve`] gives the
    /// colour): the path tracer hands back a path that left the scene before looking up
    /// the environment map's light, so that the caller may trace the next sample while the
    /// map's memory comes in.
    #[inline]
    fn radiance_deferred(
        &self,
        scene: &Scene,
        ray: &Ray,
        sampler: &mut Sampler,
        rays: &mut RayStats,
    ) -> Traced {
        Traced::Done(self.radiance_sampled(scene, ray, sampler, rays))
    }
}

impl Integrator for Path {
    /// One path, with numbers from sample 0 of pixel (0, 0) of the render's sampler (for
    /// tools that give a ray but no sample).
    fn radiance(&self, scene: &Scene, ray: &Ray, rays: &mut RayStats) -> Color {
        let s = &scene.settings;
        let mut sampler = Sampler::new(s.integrator.sampler, s.seed);
        sampler.start(0, 0, 0);
        Path::radiance(self, scene, ray, &mut sampler, rays)
    }

    fn uses_sampler(&self) -> bool {
        true
    }

    fn radiance_sampled(
        &self,
        scene: &Scene,
        ray: &Ray,
        sampler: &mut Sampler,
        rays: &mut RayStats,
    ) -> Color {
        Path::radiance(self, scene, ray, sampler, rays)
    }

    fn radiance_deferred(
        &self,
        scene: &Scene,
        ray: &Ray,
        sampler: &mut Sampler,
        rays: &mut RayStats,
    ) -> Traced {
        Path::radiance_deferred(self, scene, ray, sampler, rays)
    }
}

/// Rays traced, by kind (for `snell render --stats`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayStats {
    /// Rays from the camera.
    pub camera: u64,
    /// Reflected and refracted rays.
    pub secondary: u64,
    /// Shadow rays (each query toward a light, and each further query past a transparent
    /// surface, counts once).
    pub shadow: u64,
    /// The deepest segment reached (the camera ray is 1).
    pub deepest: u32,
}

impl RayStats {
    /// All rays.
    pub fn total(&self) -> u64 {
        self.camera + self.secondary + self.shadow
    }
}

impl std::ops::AddAssign for RayStats {
    fn add_assign(&mut self, o: RayStats) {
        self.camera += o.camera;
        self.secondary += o.secondary;
        self.shadow += o.shadow;
        self.deepest = self.deepest.max(o.deepest);
    }
}
