//! Light sources, all behind one interface ([`Emit`]) in one list: point, spot and
//! directional lights, area lights on emitting shapes (area.rs), the environment
//! (environment.rs, with sky/), and the choice among them by power for the path tracer
//! (select.rs). Point and
//! spot lights fall off with distance as their `falloff` says; by default not at all under
//! the Whitted integrator (the seed report's and POV-Ray's default, so a scene's brightness
//! does not depend on its scale), as `1 / d^2` under the path tracer.

pub mod area;
mod directional;
mod env_map;
pub mod environment;
mod point;
pub mod select;
pub mod sky;
mod spot;

pub use area::{AreaLight, Emitter, ObjectLights};
pub use directional::DirectionalLight;
pub use environment::{Environment, EnvironmentMap, EnvironmentSample, EnvironmentSource, Toward};
pub use point::PointLight;
pub use select::{LightChoice, LightSampler};
pub use spot::SpotLight;

use crate::math::{Color, Vec2, Vec3A};
use schemars::JsonSchema;
use serde::Deserialize;

/// How a point or spot light's light weakens with distance.
#[derive(Clone, Copy, Debug, Deserialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Falloff {
    /// Not at all: the same light at any distance (the seed report's and POV-Ray's default).
    None,
    /// As `1 / d^2`, as physics has it: `intensity` is then in watts per steradian.
    InverseSquare,
}

crate::closed_set! {
    /// What every light gives: light arriving at a point from it, and its power, by which
    /// next-event estimation chooses among lights. Implemented by each light in its file;
    /// [`Light`] forwards to them.
    pub trait Emit {
        /// The light arriving at `from` from a point of this light chosen by `u` (ignored by
        /// lights that are one point or one direction), unshadowed, falling off as the light
        /// says or, where it does not say, as `default`; `None` where none arrives (outside a
        /// spot's cone, `from` at the light, a dark sample).
        fn sample_li(&self, from: Vec3A, u: Vec2, default: Falloff) -> Option<LightSample>;

        /// Its power for choosing among lights, in luminance, in a scene of radius `radius`
        /// (a directional light's and the environment's power is what falls on a disk of that
        /// radius).
        fn power(&self, radius: f32) -> f32;

        /// Whether it lies in one point or one direction, which no BSDF sample can reach (no
        /// MIS).
        fn is_delta(&self) -> bool;

        /// The light's `type` in the scene file.
        fn kind_name(&self) -> &'static str;

        /// Light leaving it, for paths that start at the light (light tracing): a point of
        /// it chosen by `u` and a direction by `v`, and what the path starts carrying there
        /// ([`Emission`]). `world` is the scene's bounding sphere (centre, radius), which a
        /// directional light's and the environment's parallel rays are sent over. `None`
        /// where it sends nothing that way.
        fn sample_le(&self, u: Vec2, v: Vec2, world: (Vec3A, f32)) -> Option<Emission> {
            None
        }

        /// The densities with which [`Emit::sample_le`] sends light from a point of it (with
        /// surface normal `normal`, on the side it leaves, for an area light) in direction
        /// `dir` (unit, the way light travels), in a scene of bounding radius `radius`: of the
        /// point, per unit area (1 for a light that is one point; `1 / pi r^2` for the disk a
        /// directional light's or the environment's rays are sent over), and of the direction,
        /// per unit solid angle (0 for a direction a delta picks, or that it never sends).
        /// What bidirectional path tracing weighs its strategies by.
        fn pdf_le(&self, normal: Option<Vec3A>, dir: Vec3A, radius: f32) -> (f32, f32) {
            (0.0, 0.0)
        }

        /// Where the light is, for lights that have a position.
        fn position(&self) -> Option<Vec3A> {
            None
        }
    }

    /// A light source: one of a closed set, one file per light. A scene keeps all of its
    /// lights in one list ([`crate::Scene::lights`]): point, spot and directional lights
    /// first, then the area lights, then the environment.
    #[derive(Clone, Debug)]
    pub enum Light {
        /// Shines equally in every direction from a point.
        Point(PointLight),
        /// A point light limited to a cone, with a soft edge.
        Spot(SpotLight),
        /// Parallel light from infinitely far away (the sun).
        Directional(DirectionalLight),
        /// An emitting object.
        Area(AreaLight),
        /// Light from every direction, far away: a colour, an image or a sky.
        Environment(Environment),
    }
}

impl Light {
    /// [`Emit::sample_li`] of a point, spot or directional light; `None` for the others.
    /// The Whitted integrator reads only these, in its hottest loop: matching only them
    /// keeps the area lights' and the environment's sampling out of its code.
    #[inline]
    pub fn sample_delta(&self, from: Vec3A, default: Falloff) -> Option<LightSample> {
        match self {
            Light::Point(l) => l.sample_li(from, Vec2::ZERO, default),
            Light::Spot(l) => l.sample_li(from, Vec2::ZERO, default),
            Light::Directional(l) => l.sample_li(from, Vec2::ZERO, default),
            Light::Area(_) | Light::Environment(_) => None,
        }
    }
}

/// Light leaving a light along a ray, chosen by [`Emit::sample_le`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emission {
    /// Where it leaves (on the light).
    pub origin: Vec3A,
    /// Its unit direction.
    pub dir: Vec3A,
    /// The light's surface normal at `origin`, on the side the light leaves (area lights),
    /// for offsetting the ray off the surface.
    pub normal: Option<Vec3A>,
    /// Emitted radiance (intensity for a point or spot light, irradiance for a directional
    /// one) times the cosine at the light, over the densities of the point and the
    /// direction.
    pub weight: Color,
    /// The density of `origin` per unit area (1 for a light that is one point or whose
    /// points are not chosen by area: point, spot and directional lights).
    pub pdf_point: f32,
    /// Whether the light does not fall off with distance (`falloff = "none"`): a path from
    /// it then carries its light to the first surface it meets undimmed by distance, as
    /// next-event estimation has it.
    pub unfalling: bool,
}

/// Light arriving at a point from one source.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit direction from the point toward the light.
    pub to_light: Vec3A,
    /// Distance to the light (infinite for directional lights and the environment).
    pub distance: f32,
    /// Light arriving, before shadowing: radiance, or for a delta light irradiance.
    pub radiance: Color,
    /// The density of the direction per unit solid angle (1 for a delta light).
    pub pdf: f32,
}

/// `color` at `distance` from a light that falls off as `falloff` says, by default as
/// `default`.
#[inline]
fn fall_off(color: Color, distance: f32, falloff: Option<Falloff>, default: Falloff) -> Color {
    match falloff.unwrap_or(default) {
        Falloff::InverseSquare => color / (distance * distance),
        Falloff::None => color,
    }
}

/// What a light that does not fall off is scaled by for its power, so that it is as bright
/// as one that does at the scene's radius: the radius squared (1 for one that does, or that
/// leaves it to the integrator).
fn unfalling_scale(falloff: Option<Falloff>, radius: f32) -> f32 {
    if falloff == Some(Falloff::None) {
        (radius * radius).max(1e-6)
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spot(angle: f32, soft: f32) -> Light {
        Light::Spot(SpotLight {
            position: Vec3A::new(0.0, 10.0, 0.0),
            direction: -Vec3A::Y,
            color: Color::ONE,
            cos_outer: angle.to_radians().cos(),
            cos_inner: (angle - soft).to_radians().cos(),
            falloff: None,
        })
    }

    /// The light arriving at `p`, not falling off (the Whitted integrator's reading).
    fn at(l: &Light, p: Vec3A) -> Option<LightSample> {
        l.sample_li(p, Vec2::ZERO, Falloff::None)
    }

    fn at_angle(l: &Light, deg: f32) -> f32 {
        let p = Vec3A::new(10.0 * deg.to_radians().tan(), 0.0, 0.0);
        at(l, p).map_or(0.0, |s| s.radiance.x)
    }

    #[test]
    fn spot_cone_and_soft_edge() {
        let l = spot(30.0, 10.0);
        assert_eq!(at_angle(&l, 0.0), 1.0);
        assert_eq!(at_angle(&l, 19.0), 1.0);
        let mid = at_angle(&l, 25.0);
        assert!(mid > 0.2 && mid < 0.8, "{mid}");
        assert_eq!(at_angle(&l, 31.0), 0.0);
        let hard = spot(30.0, 0.0);
        assert_eq!(at_angle(&hard, 29.9), 1.0);
        assert_eq!(at_angle(&hard, 30.1), 0.0);
    }

    #[test]
    fn point_and_directional() {
        let p = Light::Point(PointLight {
            position: Vec3A::new(0.0, 4.0, 3.0),
            color: Color::splat(2.0),
            falloff: None,
        });
        let s = at(&p, Vec3A::ZERO).unwrap();
        assert!((s.distance - 5.0).abs() < 1e-6);
        assert!((s.to_light - Vec3A::new(0.0, 0.8, 0.6)).length() < 1e-6);
        assert_eq!(s.radiance, Color::splat(2.0), "no distance falloff");
        let s = p
            .sample_li(Vec3A::ZERO, Vec2::ZERO, Falloff::InverseSquare)
            .unwrap();
        assert!((s.radiance.x - 2.0 / 25.0).abs() < 1e-7, "1 / d^2");
        let d = Light::Directional(DirectionalLight {
            direction: -Vec3A::Y,
            color: Color::ONE,
        });
        let s = at(&d, Vec3A::new(100.0, 0.0, 0.0)).unwrap();
        assert_eq!(s.to_light, Vec3A::Y);
        assert!(s.distance.is_infinite());
    }

    /// Every light that sends light from a point sends its directions with the density
    /// `pdf_le` gives (chi-square), and the weight `sample_le` reports is its light times
    /// the cosine over the densities `pdf_le` gives of the point and the direction.
    #[test]
    fn emission_densities_match_the_sampling() {
        use crate::geometry::Disk;
        use crate::math::chi2::{SphereBins, chi2_sphere};
        let world = (Vec3A::new(0.5, 0.0, 0.0), 3.0);
        let disk = |two_sided| {
            Light::Area(AreaLight::new(
                Emitter::Disk(Disk::new(
                    Vec3A::new(0.0, 1.0, 0.0),
                    Vec3A::new(0.3, -1.0, 0.2).normalize(),
                    0.5,
                )),
                Color::new(2.0, 1.0, 0.5),
                None,
                two_sided,
                0,
            ))
        };
        let lights = [
            Light::Point(PointLight {
                position: Vec3A::new(0.0, 2.0, 0.0),
                color: Color::splat(3.0),
                falloff: None,
            }),
            spot(30.0, 10.0),
            disk(false),
            disk(true),
            Light::Environment(Environment {
                source: EnvironmentSource::Constant(Color::splat(0.7)),
                visible: true,
            }),
        ];
        let mut checked = 0;
        for (k, l) in lights.iter().enumerate() {
            let u = Vec2::new(0.3, 0.6);
            let normal = l.sample_le(u, Vec2::new(0.2, 0.2), world).unwrap().normal;
            let result = chi2_sphere(
                &format!("light {k}"),
                SphereBins::default(),
                |v| l.sample_le(u, v, world).map(|e| e.dir),
                |dir| l.pdf_le(normal, dir, world.1).1,
            );
            if let Err(e) = result {
                panic!("{e}");
            }
            for i in 0..64 {
                let v = Vec2::new((i % 8) as f32 / 8.0 + 0.05, (i / 8) as f32 / 8.0 + 0.05);
                let Some(e) = l.sample_le(u, v, world) else {
                    continue;
                };
                let (pos, dir) = l.pdf_le(e.normal, e.dir, world.1);
                let (light, cos) = match l {
                    Light::Area(a) => (a.radiance, e.normal.unwrap().dot(e.dir).abs()),
                    Light::Environment(env) => (env.radiance(-e.dir), 1.0),
                    Light::Spot(_) => continue,
                    _ => (Color::splat(3.0), 1.0),
                };
                let want = light * (cos / (pos * dir));
                assert!(
                    (e.weight - want).abs().max_element() < 1e-3 * want.max_element(),
                    "light {k}: {} vs {want}",
                    e.weight
                );
                checked += 1;
            }
        }
        assert_eq!(checked, 4 * 64);
        let sun = Light::Directional(DirectionalLight {
            direction: -Vec3A::Y,
            color: Color::ONE,
        });
        let e = sun
            .sample_le(Vec2::new(0.3, 0.3), Vec2::ZERO, world)
            .unwrap();
        let (pos, dir) = sun.pdf_le(None, e.dir, world.1);
        assert!((e.weight.x * pos - 1.0).abs() < 1e-5 && dir == 0.0);
    }
}
