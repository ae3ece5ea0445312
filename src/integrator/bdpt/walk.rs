//! The two subpaths of a bidirectional sample: one from the eye along the camera ray, one
//! from a light chosen by power, each a random walk that keeps every vertex with its
//! throughput and its densities both ways.

use super::Context;
use super::vertex::{Kind, Side, Surface, Vertex};
use crate::accel::Skip;
use crate::integrator::RayStats;
use crate::integrator::light_tracer::shading_correction;
use crate::math::{Color, Frame, Ray, Vec2, Vec3A, offset_ray_origin};
use crate::sampler::Sampler;

/// The camera's subpath for camera ray `ray` into `path` (cleared first): the eye, then up
/// to `max_depth` surfaces, or the environment (or the background) where it leaves.
pub(super) fn camera_path(
    ctx: &Context,
    ray: &Ray,
    sampler: &mut Sampler,
    rays: &mut RayStats,
    path: &mut Vec<Vertex>,
) {
    path.clear();
    path.push(Vertex::camera(ray.origin, Color::ONE));
    rays.camera += 1;
    let (w, h) = ctx.view.size;
    let pdf = ctx.view.camera.direction_pdf(ray.dir, w, h);
    let walk = Walk {
        side: Side::Eye,
        max: ctx.scene.settings.max_depth,
        first_unfalling: false,
    };
    walk.run(ctx, *ray, Color::ONE, pdf, sampler, rays, path);
}

/// A light's subpath into `path` (cleared first): a point of a light chosen by power, then
/// up to `max_depth - 1` surfaces (a connection to the eye is one more segment). Empty
/// where the scene has no light or the light sends nothing that way.
pub(super) fn light_path(
    ctx: &Context,
    sampler: &mut Sampler,
    rays: &mut RayStats,
    path: &mut Vec<Vertex>,
) {
    path.clear();
    let scene = ctx.scene;
    let [a, b, c, d] = sampler.next_4d();
    let Some((i, p_light)) = scene.light_sampler.pick(sampler.next_choice()) else {
        return;
    };
    let light = &scene.lights[i];
    let Some(e) = light.sample_le(Vec2::new(a, b), Vec2::new(c, d), ctx.view.world) else {
        return;
    };
    let (pdf_pos, pdf_dir) = light.pdf_le(e.normal, e.dir, ctx.view.world.1);
    let infinite = matches!(
        light,
        crate::light::Light::Environment(_) | crate::light::Light::Directional(_)
    );
    if infinite && ctx.view.blocked_from_afar(scene, &e) {
        return;
    }
    let kind = Kind::Light {
        light: i,
        normal: e.normal,
        toward: infinite.then_some(-e.dir),
    };
    let mut emission = e.weight;
    if let (crate::light::Light::Area(area), Some(n)) = (light, e.normal)
        && area.texture.is_some()
    {
        // A textured light's radiance where the point lies on it.
        let le = ctx.scene.emission_from(area, e.origin, n);
        emission *= le / area.radiance.max(Color::splat(1e-30));
    }
    let mut start = Vertex::new(kind, e.origin, e.normal.unwrap_or(Vec3A::ZERO), emission);
    start.pdf_fwd = if infinite {
        start.pdf_light_origin(ctx, &start)
    } else {
        p_light * pdf_pos
    };
    path.push(start);
    let beta = emission / p_light;
    let origin = e
        .normal
        .map_or(e.origin, |n| offset_ray_origin(e.origin, n));
    let walk = Walk {
        side: Side::Light,
        max: ctx.scene.settings.max_depth.saturating_sub(1),
        first_unfalling: e.unfalling,
    };
    if walk.max == 0 {
        return;
    }
    walk.run(
        ctx,
        Ray::new(origin, e.dir),
        beta,
        pdf_dir,
        sampler,
        rays,
        path,
    );
    // A light far away makes its first surface by the point of its disk: that density,
    // per unit area of the surface.
    if infinite && let Some(v) = path.get_mut(1) {
        v.pdf_fwd = pdf_pos;
        if v.on_surface() {
            v.pdf_fwd *= e.dir.dot(v.ng).abs();
        }
    }
}

/// How a random walk goes.
struct Walk {
    /// Whose subpath it is.
    side: Side,
    /// The most surfaces it may meet.
    max: u32,
    /// Whether it starts at a light that does not fall off with distance (its first
    /// segment then carries the light undimmed, as next-event estimation has it).
    first_unfalling: bool,
}

impl Walk {
    /// Walks from `ray` carrying `beta`, the ray's direction taken with density `pdf` (per
    /// unit solid angle) at the last vertex of `path`, adding each vertex met.
    #[allow(clippy::too_many_arguments)]
    fn run(
        &self,
        ctx: &Context,
        mut ray: Ray,
        mut beta: Color,
        mut pdf: f32,
        sampler: &mut Sampler,
        rays: &mut RayStats,
        path: &mut Vec<Vertex>,
    ) {
        let scene = ctx.scene;
        let rr_depth = scene.settings.integrator.rr_depth;
        let mut skip = Skip::NONE;
        let mut medium: Option<Color> = None;
        let mut eta_scale = 1.0f32;
        // Surfaces met so far; the segment under way is `depth + 1`.
        let mut depth = 0u32;
        loop {
            rays.deepest = rays.deepest.max(depth + 1);
            let Some(mut hit) = scene.closest_hit_skipping(&ray, f32::INFINITY, skip) else {
                if self.side == Side::Eye {
                    let mut v = escaped(ctx, &ray, depth, beta, pdf);
                    v.dispersed = path.last().is_some_and(|p| p.dispersed);
                    path.push(v);
                }
                break;
            };
            if depth == 0 && self.first_unfalling {
                beta *= hit.t * hit.t;
            }
            if let Some(sigma) = medium {
                beta *= (-sigma * hit.t).exp();
            }
            let tex = hit.tex;
            let m = scene.material_at(&hit);
            let front = ray.dir.dot(hit.normal) < 0.0;
            let le = match (&m.emission, self.side) {
                (Some(e), Side::Eye) => e.emitted(front, &scene.textures, &tex),
                _ => Color::ZERO,
            };
            scene.with_detail(&mut hit, &tex);
            let base = scene.base_color(&hit, &tex);
            let frame = Frame::from_axis(hit.shading_normal);
            let bsdf = m.bsdf_at(&scene.textures, &tex, base, ctx.nm);
            let wo_world = -ray.dir;
            let surface = Surface {
                hit,
                bsdf,
                frame,
                wo_world,
                wo: frame.to_local(wo_world),
                light: scene.area_light_at(&hit),
                side: self.side,
            };
            let mut v = Vertex::new(
                Kind::Surface(Box::new(surface)),
                hit.point,
                hit.normal,
                beta,
            );
            v.le = le;
            let prev = path.last().expect("a walk starts from a vertex");
            v.dispersed = prev.dispersed || (ctx.nm.is_some() && m.dispersion.is_some());
            v.pdf_fwd = prev.to_area(pdf, &v);
            path.push(v);
            depth += 1;
            if depth >= self.max {
                break;
            }
            let u = sampler.next_2d();
            let uc = sampler.next_choice();
            let n = path.len();
            let Some(Kind::Surface(s)) = path.last().map(|v| &v.kind) else {
                unreachable!("the vertex just added is a surface")
            };
            let Some(bs) = s.bsdf.sample(s.wo, u, uc) else {
                break;
            };
            if bs.pdf.is_nan() || bs.pdf <= 0.0 {
                break;
            }
            let wi_world = frame.to_world(bs.wi).normalize_or_zero();
            let through_shading = bs.wi.z * s.wo.z < 0.0;
            let through = wi_world.dot(hit.normal) * wo_world.dot(hit.normal) < 0.0;
            if through != through_shading || wi_world == Vec3A::ZERO {
                break;
            }
            let mut weight = bs.f * (bs.wi.z.abs() / bs.pdf);
            let scale = s.bsdf.radiance_scale(s.wo, bs.wi);
            match self.side {
                Side::Eye => eta_scale *= scale,
                Side::Light => weight *= scale * shading_correction(&hit, wo_world, wi_world),
            }
            let specular = bs.lobe.is_specular();
            let (pdf_fwd, pdf_rev) = if specular {
                (0.0, 0.0)
            } else {
                (bs.pdf, s.bsdf.pdf(bs.wi, s.wo))
            };
            beta *= weight;
            if !beta.is_finite() || beta == Color::ZERO {
                break;
            }
            let rev = path[n - 1].to_area(pdf_rev, &path[n - 2]);
            path[n - 2].pdf_rev = rev;
            path[n - 1].delta = specular;
            pdf = pdf_fwd;
            let outward = wi_world.dot(hit.normal) > 0.0;
            if through {
                // Into the solid when the walk came from outside, out of it otherwise.
                medium = if front { m.absorption_inside() } else { None };
            }
            let side = if outward { hit.normal } else { -hit.normal };
            ray = Ray::new(offset_ray_origin(hit.point, side), wi_world);
            skip = scene.leaving(&hit, outward);
            rays.secondary += 1;
            // Russian roulette from the `rr_depth`-th bounce on, as the path tracer plays it.
            if depth + 1 > rr_depth {
                let q = (beta * eta_scale).max_element().min(0.95);
                if sampler.next_choice() >= q {
                    break;
                }
                beta /= q;
            }
        }
    }
}

/// The vertex a camera subpath that left the scene along `ray` ends at: the environment
/// (where the camera may see it, or past the first bounce), or the background.
fn escaped(ctx: &Context, ray: &Ray, depth: u32, beta: Color, pdf: f32) -> Vertex {
    let scene = ctx.scene;
    let far = ray.origin + ray.dir;
    let mut v = match (scene.environment(), scene.environment_light) {
        (Some(env), Some(i)) if env.visible || depth > 0 => {
            let kind = Kind::Light {
                light: i,
                normal: None,
                toward: Some(ray.dir),
            };
            let mut v = Vertex::new(kind, far, Vec3A::ZERO, beta);
            v.le = env.radiance(ray.dir);
            v
        }
        _ => {
            let mut v = Vertex::new(Kind::Background, far, Vec3A::ZERO, beta);
            v.le = scene.background;
            v
        }
    };
    v.pdf_fwd = pdf;
    v
}
