//! `[integrator]`: which integrator turns rays into colours, and the path tracer's settings.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// `[integrator]`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct IntegratorDef {
    /// `whitted` (the seed report's ray tracer, the default), `path` (physically based),
    /// `light` (light tracing) or `bdpt` (bidirectional path tracing).
    #[serde(rename = "type")]
    pub kind: IntegratorKind,
    /// Path: where the random numbers come from, `sobol` (default) or `independent`.
    pub sampler: SamplerDef,
    /// Path: the bounces after which Russian roulette may end a path, played first after
    /// bounce `rr_depth` (default 5, as Mitsuba's `rr_depth`).
    pub rr_depth: u32,
    /// Path: the largest value a sample may add to a pixel, per channel (default: no clamp).
    /// Clamping removes fireflies and darkens the image: it is biased.
    pub clamp: Option<f32>,
    /// Bdpt: how its strategies are weighed, `power` (default) or `balance` (Veach's
    /// heuristics).
    pub mis: Option<MisHeuristic>,
}

impl Default for IntegratorDef {
    fn default() -> Self {
        IntegratorDef {
            kind: IntegratorKind::Whitted,
            sampler: SamplerDef::Sobol,
            rr_depth: 5,
            clamp: None,
            mis: None,
        }
    }
}

/// The integrators.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum IntegratorKind {
    /// Whitted-style ray tracing: point lights, mirror reflection and refraction.
    #[default]
    Whitted,
    /// Unidirectional path tracing with next-event estimation and MIS.
    Path,
    /// Light tracing: paths from the lights, connected to the eye (Mitsuba's particle
    /// tracer). It finds the caustics of point and spot lights; mirrors, glass and the sky
    /// seen directly are black (docs/scene-format.md).
    Light,
    /// Bidirectional path tracing: paths from the eye and from a light, joined at every
    /// pair of their vertices and weighed by multiple importance sampling. It finds the
    /// caustics light tracing finds, and sees mirrors and glass as the path tracer does.
    Bdpt,
}

/// How bidirectional path tracing weighs the strategies that could have made a path
/// (Veach's heuristics).
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum MisHeuristic {
    /// Each strategy in proportion to its density squared.
    #[default]
    Power,
    /// Each strategy in proportion to its density.
    Balance,
}

/// The samplers of the path tracer.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SamplerDef {
    /// Owen-scrambled Sobol points.
    #[default]
    Sobol,
    /// Independent uniform numbers.
    Independent,
}
