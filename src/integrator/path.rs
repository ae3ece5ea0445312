//! Unidirectional path tracing with next-event estimation and multiple importance sampling.
//!
//! At each vertex the path adds the light of one light chosen by power (a shadow ray) and
//! continues in a direction the BSDF samples; light reached both ways (area lights hit by a
//! BSDF sample) is weighed between the two by the power heuristic. Depth counts segments as
//! Mitsuba 3 does: the camera ray is 1, so `max_depth = 1` shows only the lights seen
//! directly and `max_depth = 2` is direct light. Russian roulette may end a path once it has
//! bounced `rr_depth` times, with survival `min(max(throughput * eta^2), 0.95)`, as Mitsuba.
//! Rays that leave the scene see the environment (`[environment]`, sampled by next-event
//! estimation and weighed by MIS) or, without one, the background as a constant environment
//! (not sampled by next-event estimation). Inside a dielectric with absorption, light falls off by
//! Beer-Lambert; Whitted's ambient term and fog are not read.

use super::RayStats;
use super::escape::{Escape, Traced};
use super::path_explain::{
    BounceRecord, EmissionRecord, LightSampleRecord, NoPathRecord, PathEnd, PathRecorder,
    RouletteRecord, VertexRecord,
};
use crate::bsdf::{Bsdf, BsdfSample};
use crate::light::{Falloff, Light, Toward};
use crate::lpe::LightFrom;
use crate::math::differential::Differentials;
use crate::math::distribution::power_heuristic;
use crate::math::{Color, Frame, Ray, Vec2, Vec3A, offset_ray_origin};
use crate::sampler::Sampler;
use crate::scene::{Hit, RayDifferentials, Scene, SurfacePatch};

/// The path tracer.
#[derive(Clone, Copy, Debug, Default)]
pub struct Path;

/// How much of a shadow ray's length is tested: the last part would meet the light itself.
const SHADOW_SHORTEN: f32 = 1.0 - 1e-4;

/// A light sample's event, for light path expressions: the part of its light the BSDF's
/// diffuse part gave, which side of the surface the light is on, and which light.
struct SampledLight {
    diffuse: Color,
    transmit: bool,
    light: usize,
}

/// What a path needs at one of its vertices, in the surface's shading frame.
struct Vertex {
    /// The BSDF there.
    bsdf: Bsdf,
    /// The shading frame (`w` the shading normal, on the outward side).
    frame: Frame,
    /// Toward the previous vertex, local.
    wo: Vec3A,
    /// The geometric normal, outward.
    ng: Vec3A,
}

impl Path {
    /// The radiance arriving along the camera ray `ray`, with random numbers from
    /// `sampler` (started at this sample).
    #[inline]
    pub fn radiance(
        &self,
        scene: &Scene,
        ray: &Ray,
        sampler: &mut Sampler,
        rays: &mut RayStats,
    ) -> Color {
        self.trace(scene, ray, sampler, rays, &mut NoPathRecord)
    }

    /// [`Path::radiance`], or, for a path that leaves the scene under an environment map,
    /// the path unfinished with the map's memory asked for ([`Traced`]).
    #[inline]
    pub fn radiance_deferred(
        &self,
        scene: &Scene,
        ray: &Ray,
        sampler: &mut Sampler,
        rays: &mut RayStats,
    ) -> Traced {
        self.trace_deferring::<_, true>(scene, ray, sampler, rays, &mut NoPathRecord)
    }

    /// [`Path::radiance`], reporting the path to `rec` (`snell explain`).
    pub fn trace<R: PathRecorder>(
        &self,
        scene: &Scene,
        ray: &Ray,
        sampler: &mut Sampler,
        rays: &mut RayStats,
        rec: &mut R,
    ) -> Color {
        self.trace_deferring::<R, false>(scene, ray, sampler, rays, rec)
            .resolve(scene)
    }

    /// [`Path::trace`]; with `DEFER`, a path that leaves the scene under an environment
    /// map (and reports nothing) comes back unfinished.
    #[inline(always)]
    fn trace_deferring<R: PathRecorder, const DEFER: bool>(
        &self,
        scene: &Scene,
        ray: &Ray,
        sampler: &mut Sampler,
        rays: &mut RayStats,
        rec: &mut R,
    ) -> Traced {
        let settings = &scene.settings.integrator;
        let max_depth = scene.settings.max_depth;
        let mut l = Color::ZERO;
        let mut beta = Color::ONE;
        let mut eta_scale = 1.0f32;
        let mut ray = *ray;
        let mut skip = crate::accel::Skip::NONE;
        // Segments traced, the one under way included.
        let mut depth = 1u32;
        // The previous bounce: a delta lobe (or the camera), and its BSDF density.
        let (mut specular, mut prev_pdf, mut prev_point) = (true, 0.0f32, ray.origin);
        // The absorption of the solid the path is inside, if any.
        let mut medium: Option<Color> = None;
        // How the ray changes to the next pixels, while the path has met only mirrors and
        // glass (a rough bounce ends them, and textures are read at a point after it).
        let mut diff = RayDifferentials::camera(scene);
        // A scene with glass that disperses light draws a wavelength for every sample; its
        // weight joins the path's at the first surface whose index depends on it, and from
        // there the path follows that wavelength.
        let mut wavelength =
            crate::math::wavelength::Followed::draw(scene.disperses(), || sampler.next_1d());
        rays.camera += 1;
        loop {
            rays.deepest = rays.deepest.max(depth);
            // One request of four dimensions per bounce, drawn whether used or not, so that
            // each bounce takes the same dimensions: the BSDF's direction and a point on a
            // light; the choices (light, lobe, Russian roulette) are the sampler's
            // independent ones. Drawn before the ray is traced, which it does not depend on.
            let [b0, b1, l0, l1] = sampler.next_4d();
            // The hit is used where it was made: moved out of its `Option`, it was copied
            // in wide loads over the narrower stores that had just built it, which the
            // processor cannot forward (a stall on every bounce; docs/perf-log.md).
            let mut found = scene.closest_hit_skipping(&ray, f32::INFINITY, skip);
            let Some(hit) = found.as_mut() else {
                if DEFER
                    && !R::EVENTS
                    && !R::ACTIVE
                    && let Some(toward) = scene.environment().and_then(|e| e.prefetch(ray.dir))
                {
                    return Traced::Escaping(Escape {
                        gathered: l,
                        beta,
                        toward,
                        depth,
                        specular,
                        prev_pdf,
                    });
                }
                let (le, environment) =
                    self.escaped(scene, ray.dir.into(), depth, specular, prev_pdf);
                let c = beta * le;
                l += c;
                if R::EVENTS {
                    rec.reached(c, LightFrom::Sky(environment));
                }
                if R::ACTIVE {
                    rec.end(PathEnd::Escaped {
                        contribution: c.to_array(),
                    });
                }
                break;
            };
            if let Some(sigma) = medium {
                beta *= (-sigma * hit.t).exp();
            }
            // The patch of surface the pixel sees, where a texture reads it (with the normal's
            // change, for a mirror or glass to pass the differentials on).
            let patch = match diff {
                RayDifferentials::None => None,
                _ if !scene.reads_textures(hit) => None,
                d => d
                    .of(scene, &ray)
                    .and_then(|d| scene.patch(hit, &ray, &d, true)),
            };
            let tex = crate::texture::TexturePoint {
                footprint: patch.as_ref().map(|p| &p.footprint),
                ..hit.tex
            };
            let m = scene.material_at(hit);
            let front = ray.dir.dot(hit.normal) < 0.0;
            let mut record = R::ACTIVE.then(|| VertexRecord {
                depth,
                object: scene.objects[hit.object].name.clone(),
                material: scene.material_names[hit.material].clone(),
                point: hit.point.to_array(),
                front,
                throughput: beta.to_array(),
                ..Default::default()
            });
            let mut added = Color::ZERO;
            if let Some(e) = &m.emission {
                let le = e.emitted(front, &scene.textures, &tex);
                if le != Color::ZERO {
                    let (w, light_pdf) =
                        self.emitter_weight(scene, hit, specular, prev_pdf, prev_point);
                    let c = beta * le * w;
                    added += c;
                    if R::EVENTS {
                        rec.reached(c, LightFrom::Object(hit.object));
                    }
                    if let Some(r) = &mut record {
                        r.emission = Some(EmissionRecord {
                            radiance: le.to_array(),
                            mis_weight: w,
                            light_pdf,
                            contribution: c.to_array(),
                        });
                    }
                }
            }
            if depth >= max_depth {
                l += added;
                if let Some(mut r) = record {
                    r.bsdf = "none (max_depth reached)".into();
                    r.contribution = added.to_array();
                    rec.vertex(r);
                    rec.end(PathEnd::MaxDepth);
                }
                break;
            }
            scene.with_detail(hit, &tex);
            let base = scene.base_color(hit, &tex);
            let frame = Frame::from_axis(hit.shading_normal);
            beta *= wavelength.weigh(m.dispersion.is_some());
            let v = Vertex {
                bsdf: m.bsdf_at(&scene.textures, &tex, base, wavelength.nm()),
                wo: frame.to_local(-ray.dir),
                frame,
                ng: hit.normal,
            };
            if let Some(r) = &mut record {
                r.bsdf = v.bsdf.name().into();
            }
            let (u, ul) = (Vec2::new(b0, b1), Vec2::new(l0, l1));
            // The next direction is sampled before the light is: the path waits on it, and
            // the light sample's work (a shadow ray's walk among it) then fills the time
            // that waiting leaves, instead of coming first. The choices are drawn in the
            // same order as ever: the light's, then the lobe's.
            let light_choice = v.bsdf.has_non_delta().then(|| sampler.next_choice());
            let uc = sampler.next_choice();
            let sampled = v
                .bsdf
                .sample(v.wo, u, uc)
                .and_then(|bs| Some((bs, self.continue_from(&v, &bs)?)));
            if let Some(uc) = light_choice {
                let (c, lr, event) = self.light_sample::<R>(scene, hit, &v, uc, ul, rays);
                let c = beta * c;
                added += c;
                if let Some(e) = event {
                    rec.sampled(c, beta * e.diffuse, e.transmit, hit.material, e.light);
                }
                if let (Some(r), Some(mut lr)) = (&mut record, lr) {
                    lr.contribution = c.to_array();
                    r.light = Some(lr);
                }
            }
            l += added;
            if let Some(r) = &mut record {
                r.contribution = added.to_array();
            }
            let Some((bs, (dir, through))) = sampled else {
                if let Some(r) = record {
                    rec.vertex(r);
                    rec.end(PathEnd::Absorbed);
                }
                break;
            };
            let weight = bs.f * (bs.wi.z.abs() / bs.pdf);
            beta *= weight;
            if let Some(r) = &mut record {
                r.bounce = Some(BounceRecord {
                    lobe: format!("{:?}", bs.lobe),
                    direction: dir.to_array(),
                    pdf: bs.pdf,
                    f: bs.f.to_array(),
                    cos: bs.wi.z.abs(),
                    weight: weight.to_array(),
                });
            }
            if !beta.is_finite() || beta == Color::ZERO {
                if let Some(r) = record {
                    rec.vertex(r);
                    rec.end(PathEnd::Absorbed);
                }
                break;
            }
            if R::EVENTS {
                rec.scattered(bs.lobe, hit.material);
            }
            eta_scale *= v.bsdf.radiance_scale(v.wo, bs.wi);
            specular = bs.lobe.is_specular();
            prev_pdf = bs.pdf;
            prev_point = hit.point;
            let outward = dir.dot(hit.normal) > 0.0;
            if through {
                // Into the solid when the path came from outside, out of it otherwise.
                medium = if front { m.absorption_inside() } else { None };
            }
            let before = if specular {
                diff
            } else {
                RayDifferentials::None
            };
            diff = match before.of(scene, &ray) {
                Some(d) => self
                    .passed_on(scene, hit, &ray, &d, patch, dir, through, front)
                    .map_or(RayDifferentials::None, RayDifferentials::Known),
                None => RayDifferentials::None,
            };
            let side = if outward { hit.normal } else { -hit.normal };
            ray = Ray::new(offset_ray_origin(hit.point, side), dir);
            skip = scene.leaving(hit, outward);
            depth += 1;
            rays.secondary += 1;
            // `depth` is now the bounces so far plus one: roulette from the `rr_depth`-th
            // bounce on, as Mitsuba's `depth >= rr_depth` after its bounce count rises.
            if depth > settings.rr_depth {
                let q = ((beta * eta_scale).max_element()).min(0.95);
                let survived = sampler.next_choice() < q;
                if let Some(r) = &mut record {
                    r.roulette = Some(RouletteRecord {
                        survival: q,
                        survived,
                    });
                }
                if !survived {
                    if let Some(r) = record {
                        rec.vertex(r);
                        rec.end(PathEnd::Roulette);
                    }
                    break;
                }
                beta /= q;
            }
            if let Some(r) = record {
                rec.vertex(r);
            }
        }
        let clamped = Self::clamped(scene, l);
        if R::EVENTS {
            rec.finished(l, clamped);
        }
        Traced::Done(clamped)
    }

    /// A sample's light `l` after the integrator's clamp, if any.
    #[inline]
    pub(super) fn clamped(scene: &Scene, l: Color) -> Color {
        match scene.settings.integrator.clamp {
            Some(c) => l.min(Color::splat(c)),
            None => l,
        }
    }

    /// The differentials of the ray a delta lobe sent on in direction `dir` from `hit`,
    /// which `ray` (with differentials `d`) met: mirrored, refracted, or passed straight
    /// through (thin glass). `patch` is the hit's if it was worked out already.
    #[allow(clippy::too_many_arguments)]
    fn passed_on(
        &self,
        scene: &Scene,
        hit: &Hit,
        ray: &Ray,
        d: &Differentials,
        patch: Option<SurfacePatch>,
        dir: Vec3A,
        through: bool,
        front: bool,
    ) -> Option<Differentials> {
        let p = patch.or_else(|| scene.patch(hit, ray, d, true))?;
        let side = if front { 1.0 } else { -1.0 };
        let (n, dn) = (hit.shading_normal * side, p.dn.map(|v| v * side));
        Some(if !through {
            d.reflected(ray, p.dp, dn, n)
        } else if (dir - ray.dir).length_squared() < 1e-10 {
            d.passed(p.dp)
        } else {
            let ior = scene.material_at(hit).ior;
            let eta = if front { 1.0 / ior } else { ior };
            d.refracted(ray, dir, p.dp, dn, n, eta)
        })
    }

    /// What a path leaving the scene along `ray` sees: the environment (weighed by MIS
    /// against light sampling, unless the bounce before was a delta or the camera) or, where
    /// there is none or the camera may not see it, the background.
    /// Whether it was the environment (`true`) or the background comes with it.
    pub(super) fn escaped(
        &self,
        scene: &Scene,
        toward: Toward,
        depth: u32,
        specular: bool,
        prev_pdf: f32,
    ) -> (Color, bool) {
        match (scene.environment(), scene.environment_light) {
            (Some(env), Some(i)) if env.visible || depth > 1 => {
                if specular {
                    return (env.radiance_toward(toward), true);
                }
                let (le, pdf) = env.radiance_pdf_toward(toward);
                let p_light = scene.light_sampler.probability(i) * pdf;
                (le * power_heuristic(prev_pdf, p_light), true)
            }
            _ => (scene.background, false),
        }
    }

    /// The MIS weight of emission found by a BSDF sample from `prev_point` with density
    /// `prev_pdf`: 1 after a delta bounce or for emitters light sampling never picks; with
    /// light sampling's density for the direction where it counts.
    fn emitter_weight(
        &self,
        scene: &Scene,
        hit: &Hit,
        specular: bool,
        prev_pdf: f32,
        prev_point: Vec3A,
    ) -> (f32, Option<f32>) {
        if specular {
            return (1.0, None);
        }
        let Some(a) = scene.area_light_at(hit) else {
            return (1.0, None);
        };
        let Some(light) = scene.area_light(a) else {
            return (1.0, None);
        };
        let p_light =
            scene.light_sampler.probability(a) * light.pdf(prev_point, hit.point, hit.normal);
        (power_heuristic(prev_pdf, p_light), Some(p_light))
    }

    /// Next-event estimation at `hit`: one light chosen by power, its light through the
    /// BSDF, weighed by MIS against the BSDF's sampling of the same direction.
    fn light_sample<R: PathRecorder>(
        &self,
        scene: &Scene,
        hit: &Hit,
        v: &Vertex,
        uc: f32,
        ul: Vec2,
        rays: &mut RayStats,
    ) -> (Color, Option<LightSampleRecord>, Option<SampledLight>) {
        let Some(mut c) =
            scene
                .light_sampler
                .sample(&scene.lights, hit.point, uc, ul, Falloff::InverseSquare)
        else {
            return (Color::ZERO, None, None);
        };
        // A textured light's radiance is read where the sample lies on it.
        if let Some(light) = scene.area_light(c.light)
            && light.texture.is_some()
        {
            let side = if c.to_light.dot(v.ng) > 0.0 {
                v.ng
            } else {
                -v.ng
            };
            let origin = offset_ray_origin(hit.point, side);
            c.radiance = scene.emission_at(light, origin, c.to_light, c.distance);
        }
        if c.pdf.is_nan() || c.pdf <= 0.0 {
            return (Color::ZERO, None, None);
        }
        let wi = v.frame.to_local(c.to_light);
        // The light sample's MIS weight, and the BSDF's density it weighs against.
        let weight = || {
            let bsdf_pdf = if c.delta { 0.0 } else { v.bsdf.pdf(v.wo, wi) };
            let w = if c.delta {
                1.0
            } else {
                power_heuristic(c.pdf, bsdf_pdf)
            };
            (w, bsdf_pdf)
        };
        let f = v.bsdf.f(v.wo, wi) * wi.z.abs();
        let record = |blocked: Option<&str>| {
            R::ACTIVE.then(|| {
                let (w, bsdf_pdf) = weight();
                LightSampleRecord {
                    light: c.light,
                    what: match &scene.lights[c.light] {
                        Light::Area(a) => {
                            format!("area light on `{}`", scene.objects[a.object].name)
                        }
                        Light::Environment(_) => "the environment".to_string(),
                        l => l.kind_name().to_string(),
                    },
                    direction: c.to_light.to_array(),
                    distance: c.distance,
                    radiance: c.radiance.to_array(),
                    light_pdf: c.pdf,
                    bsdf_pdf,
                    f_cos: f.to_array(),
                    mis_weight: w,
                    blocked: blocked.map(str::to_string),
                    contribution: [0.0; 3],
                }
            })
        };
        // The geometric and the shading normal must agree on the side the light is on, or
        // light would leak through the surface.
        let outward = c.to_light.dot(v.ng) > 0.0;
        let wo_outward = v.frame.to_world(v.wo).dot(v.ng) > 0.0;
        if (wi.z * v.wo.z > 0.0) != (outward == wo_outward) {
            return (
                Color::ZERO,
                record(Some(
                    "the shading and the true normal disagree about its side",
                )),
                None,
            );
        }
        if f == Color::ZERO {
            return (
                Color::ZERO,
                record(Some("the BSDF returns nothing toward it")),
                None,
            );
        }
        let side = if outward { v.ng } else { -v.ng };
        let shadow = Ray::new(offset_ray_origin(hit.point, side), c.to_light);
        rays.shadow += 1;
        let t_max = if c.distance.is_finite() {
            c.distance * SHADOW_SHORTEN
        } else {
            f32::INFINITY
        };
        if scene.occluded(&shadow, t_max, scene.leaving(hit, outward)) {
            return (Color::ZERO, record(Some("the shadow ray is blocked")), None);
        }
        let (w, _) = weight();
        let event = R::EVENTS.then(|| SampledLight {
            diffuse: v.bsdf.f_diffuse(v.wo, wi) * wi.z.abs() * c.radiance * (w / c.pdf),
            transmit: wi.z * v.wo.z < 0.0,
            light: c.light,
        });
        (f * c.radiance * (w / c.pdf), record(None), event)
    }

    /// The world direction of a BSDF sample and whether it passes through the surface;
    /// `None` where the geometric normal and the shading normal disagree about that (a
    /// reflection that would go into the solid, or a refraction that would stay out).
    fn continue_from(&self, v: &Vertex, bs: &BsdfSample) -> Option<(Vec3A, bool)> {
        if bs.pdf.is_nan() || bs.pdf <= 0.0 {
            return None;
        }
        let dir = v.frame.to_world_unit(bs.wi);
        let wo = v.frame.to_world(v.wo);
        let through_shading = bs.wi.z * v.wo.z < 0.0;
        let through = dir.dot(v.ng) * wo.dot(v.ng) < 0.0;
        (through == through_shading && dir != Vec3A::ZERO).then_some((dir, through))
    }
}
