//! Ways of turning a camera ray into a colour. One file per integrator; they are chosen
//! once per render, so a trait object is fine here.

mod whitted;

pub use whitted::Whitted;

use crate::math::{Color, Ray};
use crate::scene::Scene;

/// Computes the colour seen along a camera ray.
pub trait Integrator: Sync {
    /// Linear RGB arriving along `ray` (a camera ray, unit direction).
    fn radiance(&self, scene: &Scene, ray: &Ray) -> Color;
}
