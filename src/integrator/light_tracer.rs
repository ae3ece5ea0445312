//! Light tracing (Mitsuba's particle tracer, pbrt's light path integrator): paths that start
//! at a light (a light chosen by power, a point and a direction of it) and carry its light
//! through the scene, connected to the eye at every surface that is not a delta, each
//! connection added to the film where it lands. It finds what a path tracer cannot: light
//! from a point or spot light that reaches a diffuse surface through glass or off a mirror
//! (a caustic). It cannot show mirrors and glass themselves, whose connection to the eye
//! is a delta, nor the sky seen directly (it lights the scene); bidirectional
//! path tracing (bdpt/) joins it to the path tracer. The transport is the adjoint
//! one: no `1 / eta^2` on refraction, and the shading normal's correction (Veach).

use super::RayStats;
use crate::bsdf::Bsdf;
use crate::camera::Camera;
use crate::light::Light;
use crate::math::{Color, Frame, Ray, Vec2, Vec3A, offset_ray_origin};
use crate::sampler::Sampler;
use crate::scene::Scene;

/// How much of a connection's length is tested: the last part would meet the eye's side.
const SHADOW_SHORTEN: f32 = 1.0 - 1e-4;

/// The light tracer.
#[derive(Clone, Copy, Debug, Default)]
pub struct LightTracer;

/// What a light path needs of the render: the camera, the film's size, and the scene's
/// bounding sphere (a directional light's rays are sent over it).
#[derive(Clone, Copy, Debug)]
pub struct LightView<'a> {
    /// The camera (a pinhole perspective one).
    pub camera: &'a Camera,
    /// The film's width and height, in pixels.
    pub size: (u32, u32),
    /// The sphere that bounds the scene's finite objects: centre and radius.
    pub world: (Vec3A, f32),
    /// Whether some object is unbounded (an infinite plane): then a ray from a light far
    /// away may start on the far side of it, and is first tested against it.
    pub open: bool,
}

impl<'a> LightView<'a> {
    /// The view of `scene`'s camera and image, and the sphere that bounds its objects.
    pub fn of(scene: &'a Scene) -> Self {
        let world = scene
            .objects
            .iter()
            .filter_map(|o| o.world_bounds)
            .reduce(|a, b| a.union(&b))
            .map_or((Vec3A::ZERO, 1.0), |b| {
                (
                    (b.min + b.max) * 0.5,
                    (0.5 * (b.max - b.min).length()).max(1e-3),
                )
            });
        LightView {
            camera: &scene.camera,
            size: (scene.settings.width, scene.settings.height),
            world,
            open: scene.objects.iter().any(|o| o.world_bounds.is_none()),
        }
    }

    /// Whether light `e` from a light far away (the environment, a directional light) that
    /// starts on the disk of [`LightView::world`] is blocked before it gets there: by an
    /// unbounded object between the disk and the light (the far side of an infinite
    /// ground, for light from below the horizon).
    pub fn blocked_from_afar(&self, scene: &Scene, e: &crate::light::Emission) -> bool {
        self.open
            && scene.occluded(
                &Ray::new(e.origin, -e.dir),
                f32::INFINITY,
                crate::accel::Skip::NONE,
            )
    }
}

impl LightTracer {
    /// One path from a light, with random numbers from `sampler` (started at this path),
    /// each connection to the eye given to `splat(x, y, colour)` (film position in pixels,
    /// and the colour it adds to a pixel's sum of paths).
    pub fn trace(
        &self,
        scene: &Scene,
        view: &LightView,
        sampler: &mut Sampler,
        rays: &mut RayStats,
        splat: &mut impl FnMut(f32, f32, Color),
    ) {
        let [a, b, c, d] = sampler.next_4d();
        let Some((i, p_light)) = scene.light_sampler.pick(sampler.next_choice()) else {
            return;
        };
        let light = &scene.lights[i];
        let Some(e) = light.sample_le(Vec2::new(a, b), Vec2::new(c, d), view.world) else {
            return;
        };
        if matches!(light, Light::Environment(_) | Light::Directional(_))
            && view.blocked_from_afar(scene, &e)
        {
            return;
        }
        // A textured light's radiance where the point lies on it, over the mean its sample
        // carries.
        let textured = match (light, e.normal) {
            (Light::Area(area), Some(n)) if area.texture.is_some() => {
                scene.emission_from(area, e.origin, n) / area.radiance.max(Color::splat(1e-30))
            }
            _ => Color::ONE,
        };
        // An area light seen by the eye: its point joined to the eye.
        if let (Light::Area(area), Some(n)) = (light, e.normal)
            && let Some(eye) =
                view.camera
                    .connect(e.origin, sampler.next_2d(), view.size.0, view.size.1)
        {
            let cos = n.dot(eye.to_eye);
            let le = area.emitted(n, eye.to_eye) * textured;
            if cos > 0.0 && le != Color::ZERO {
                let shadow = Ray::new(offset_ray_origin(e.origin, n), eye.to_eye);
                rays.shadow += 1;
                let blocked = scene.occluded(
                    &shadow,
                    eye.distance * SHADOW_SHORTEN,
                    crate::accel::Skip::NONE,
                );
                if !blocked {
                    let value = le * (cos * eye.importance / (p_light * e.pdf_point));
                    splat(eye.film.0, eye.film.1, value);
                }
            }
        }
        let mut beta = e.weight * textured / p_light;
        // A dispersive scene's path follows one wavelength from the first surface whose
        // index depends on it (see the path tracer).
        let mut wavelength =
            crate::math::wavelength::Followed::draw(scene.disperses(), || sampler.next_1d());
        let origin = e
            .normal
            .map_or(e.origin, |n| offset_ray_origin(e.origin, n));
        let mut ray = Ray::new(origin, e.dir);
        let mut skip = crate::accel::Skip::NONE;
        let max_depth = scene.settings.max_depth;
        let rr_depth = scene.settings.integrator.rr_depth;
        // Segments traced, the one under way included; the eye's connection is one more.
        let mut depth = 1u32;
        let mut medium: Option<Color> = None;
        loop {
            rays.secondary += 1;
            let Some(mut hit) = scene.closest_hit_skipping(&ray, f32::INFINITY, skip) else {
                break;
            };
            if depth == 1 && e.unfalling {
                // A light that does not fall off reaches its first surface undimmed.
                beta *= hit.t * hit.t;
            }
            if let Some(sigma) = medium {
                beta *= (-sigma * hit.t).exp();
            }
            let tex = hit.tex;
            let m = scene.material_at(&hit);
            let front = ray.dir.dot(hit.normal) < 0.0;
            scene.with_detail(&mut hit, &tex);
            let base = scene.base_color(&hit, &tex);
            let frame = Frame::from_axis(hit.shading_normal);
            beta *= wavelength.weigh(m.dispersion.is_some());
            let bsdf = m.bsdf_at(&scene.textures, &tex, base, wavelength.nm());
            let wo_world = -ray.dir;
            let wo = frame.to_local(wo_world);
            if bsdf.has_non_delta() && depth < max_depth {
                let at = Vertex {
                    hit: &hit,
                    bsdf: &bsdf,
                    frame: &frame,
                    wo,
                };
                self.connect_eye(scene, view, &at, beta, sampler, rays, splat);
            }
            if depth >= max_depth {
                break;
            }
            let u = sampler.next_2d();
            let Some(bs) = bsdf.sample(wo, u, sampler.next_choice()) else {
                break;
            };
            if bs.pdf.is_nan() || bs.pdf <= 0.0 {
                break;
            }
            let wi_world = frame.to_world(bs.wi).normalize_or_zero();
            let through_shading = bs.wi.z * wo.z < 0.0;
            let through = wi_world.dot(hit.normal) * wo_world.dot(hit.normal) < 0.0;
            if through != through_shading || wi_world == Vec3A::ZERO {
                break;
            }
            let correction = shading_correction(&hit, wo_world, wi_world);
            beta *= bs.f * (bs.wi.z.abs() / bs.pdf * bsdf.radiance_scale(wo, bs.wi) * correction);
            if !beta.is_finite() || beta == Color::ZERO {
                break;
            }
            let outward = wi_world.dot(hit.normal) > 0.0;
            if through {
                medium = if front { m.absorption_inside() } else { None };
            }
            let side = if outward { hit.normal } else { -hit.normal };
            ray = Ray::new(offset_ray_origin(hit.point, side), wi_world);
            skip = scene.leaving(&hit, outward);
            depth += 1;
            if depth > rr_depth {
                let q = beta.max_element().min(0.95);
                if sampler.next_choice() >= q {
                    break;
                }
                beta /= q;
            }
        }
    }

    /// The light a path carrying `beta` to `hit` (arriving from `wo`, local) sends to the
    /// eye, splatted where it lands, if the eye sees the point.
    #[allow(clippy::too_many_arguments)]
    fn connect_eye(
        &self,
        scene: &Scene,
        view: &LightView,
        at: &Vertex,
        beta: Color,
        sampler: &mut Sampler,
        rays: &mut RayStats,
        splat: &mut impl FnMut(f32, f32, Color),
    ) {
        let (hit, bsdf, frame, wo) = (at.hit, at.bsdf, at.frame, at.wo);
        let Some(eye) = view
            .camera
            .connect(hit.point, sampler.next_2d(), view.size.0, view.size.1)
        else {
            return;
        };
        let wi = frame.to_local(eye.to_eye);
        // The geometric and the shading normal must agree on the eye's side.
        let outward = eye.to_eye.dot(hit.normal) > 0.0;
        let wo_outward = frame.to_world(wo).dot(hit.normal) > 0.0;
        if (wi.z * wo.z > 0.0) != (outward == wo_outward) {
            return;
        }
        let f = bsdf.f(wo, wi) * bsdf.radiance_scale(wo, wi);
        if f == Color::ZERO {
            return;
        }
        let correction = shading_correction(hit, frame.to_world(wo), eye.to_eye);
        let value = beta * f * (wi.z.abs() * correction * eye.importance);
        if !value.is_finite() || value == Color::ZERO {
            return;
        }
        let side = if outward { hit.normal } else { -hit.normal };
        let shadow = Ray::new(offset_ray_origin(hit.point, side), eye.to_eye);
        rays.shadow += 1;
        if !scene.occluded(
            &shadow,
            eye.distance * SHADOW_SHORTEN,
            scene.leaving(hit, outward),
        ) {
            splat(eye.film.0, eye.film.1, value);
        }
    }
}

/// A surface a light path met: the hit, its BSDF and shading frame, and the direction back
/// toward the light (local).
struct Vertex<'a> {
    hit: &'a crate::scene::Hit,
    bsdf: &'a Bsdf,
    frame: &'a Frame,
    wo: Vec3A,
}

/// Veach's correction of adjoint transport for a shading normal that is not the geometric
/// one: `|wo.ns| |wi.ng| / (|wo.ng| |wi.ns|)` (1 where they agree).
pub(super) fn shading_correction(hit: &crate::scene::Hit, wo: Vec3A, wi: Vec3A) -> f32 {
    let (ns, ng) = (hit.shading_normal, hit.normal);
    let den = wo.dot(ng).abs() * wi.dot(ns).abs();
    if den == 0.0 {
        return 0.0;
    }
    wo.dot(ns).abs() * wi.dot(ng).abs() / den
}
