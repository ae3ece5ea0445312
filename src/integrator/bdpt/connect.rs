//! One strategy of a bidirectional sample: the first `s` vertices of the light's subpath
//! joined to the first `t` of the camera's, the light the joined path carries, unweighted.
//! `s = 0` is the camera path finding a light itself; `s = 1` samples a point of a light
//! from the camera path's last vertex (next-event estimation); `t = 1` joins the light
//! path's last vertex to the eye, landing anywhere on the film.

use super::Context;
use super::vertex::{Kind, Vertex};
use crate::integrator::RayStats;
use crate::light::{Falloff, Light};
use crate::math::{Color, Ray, Vec3A, offset_ray_origin};
use crate::sampler::Sampler;

/// How much of a connection's length is tested: the last part would meet its other end.
const SHADOW_SHORTEN: f32 = 1.0 - 1e-4;

/// What one strategy gave: its light (unweighted), the vertex a connection sampled (a
/// light's point for `s = 1`, the eye for `t = 1`), and for `t = 1` where it lands on the
/// film.
pub(super) struct Joined {
    /// The light the joined path carries to the eye, before its MIS weight.
    pub light: Color,
    /// The vertex the connection sampled, standing in for the subpath's own.
    pub sampled: Option<Vertex>,
    /// For `t = 1`: the film position, in pixels.
    pub film: Option<(f32, f32)>,
}

impl Joined {
    fn none() -> Self {
        Joined {
            light: Color::ZERO,
            sampled: None,
            film: None,
        }
    }
}

/// Joins `light[..s]` to `camera[..t]`.
pub(super) fn join(
    ctx: &Context,
    light: &[Vertex],
    camera: &[Vertex],
    s: usize,
    t: usize,
    sampler: &mut Sampler,
    rays: &mut RayStats,
) -> Joined {
    let scene = ctx.scene;
    let pt = &camera[t - 1];
    // A camera path that left the scene meets no vertex of a light path.
    if t > 1 && s != 0 && pt.infinite() {
        return Joined::none();
    }
    if s == 0 {
        return Joined {
            light: pt.le * pt.beta,
            ..Joined::none()
        };
    }
    if t == 1 {
        return to_eye(ctx, &light[s - 1], sampler, rays);
    }
    if s == 1 {
        return from_light(ctx, pt, sampler, rays);
    }
    let qs = &light[s - 1];
    if !qs.connectible(scene) || !pt.connectible(scene) {
        return Joined::none();
    }
    let l = qs.beta * qs.f_cos(pt) * pt.f_cos(qs) * pt.beta;
    if l == Color::ZERO {
        return Joined::none();
    }
    let d2 = (qs.point - pt.point).length_squared();
    if d2 == 0.0 {
        return Joined::none();
    }
    let Some(tr) = transmittance(ctx, pt, qs, rays) else {
        return Joined::none();
    };
    Joined {
        light: l * tr / d2,
        ..Joined::none()
    }
}

/// `t = 1`: the light path's last vertex `qs` joined to a point of the eye.
fn to_eye(ctx: &Context, qs: &Vertex, sampler: &mut Sampler, rays: &mut RayStats) -> Joined {
    let u = sampler.next_2d();
    if !qs.connectible(ctx.scene) || qs.surface().is_none() {
        return Joined::none();
    }
    let (w, h) = ctx.view.size;
    let Some(eye) = ctx.view.camera.connect(qs.point, u, w, h) else {
        return Joined::none();
    };
    let camera = Vertex::camera(eye.eye, Color::splat(eye.importance));
    let l = qs.beta * qs.f_cos(&camera) * eye.importance;
    if l == Color::ZERO {
        return Joined::none();
    }
    let Some(tr) = transmittance(ctx, qs, &camera, rays) else {
        return Joined::none();
    };
    Joined {
        light: l * tr,
        film: Some(eye.film),
        sampled: Some(camera),
    }
}

/// `s = 1`: a point of a light chosen by power, sampled from the camera path's last vertex
/// `pt` (next-event estimation).
fn from_light(ctx: &Context, pt: &Vertex, sampler: &mut Sampler, rays: &mut RayStats) -> Joined {
    let scene = ctx.scene;
    let uc = sampler.next_choice();
    let u = sampler.next_2d();
    if !pt.connectible(scene) {
        return Joined::none();
    }
    let Some((i, choice)) = scene.light_sampler.pick(uc) else {
        return Joined::none();
    };
    let light = &scene.lights[i];
    let (kind, point, ng, radiance, pdf) = match light {
        Light::Area(area) => {
            let Some(a) = area.sample(pt.point, u) else {
                return Joined::none();
            };
            let to_light = (pt.point - a.point).normalize_or_zero();
            let radiance = if area.texture.is_some() {
                ctx.scene.emission_from(area, a.point, a.normal)
            } else {
                area.emitted(a.normal, to_light)
            };
            let emits = area.two_sided || a.normal.dot(to_light) > 0.0;
            let kind = Kind::Light {
                light: i,
                normal: Some(a.normal),
                toward: None,
            };
            let radiance = if emits { radiance } else { Color::ZERO };
            (kind, a.point, a.normal, radiance, a.pdf)
        }
        _ => {
            let Some(ls) = light.sample_li(pt.point, u, Falloff::InverseSquare) else {
                return Joined::none();
            };
            let far = !ls.distance.is_finite();
            let point = if far {
                pt.point + ls.to_light
            } else {
                pt.point + ls.to_light * ls.distance
            };
            let kind = Kind::Light {
                light: i,
                normal: None,
                toward: far.then_some(ls.to_light),
            };
            (kind, point, Vec3A::ZERO, ls.radiance, ls.pdf)
        }
    };
    if radiance == Color::ZERO || pdf.is_nan() || pdf <= 0.0 || !pdf.is_finite() {
        return Joined::none();
    }
    let mut sampled = Vertex::new(kind, point, ng, radiance / (pdf * choice));
    sampled.pdf_fwd = sampled.pdf_light_origin(ctx, pt);
    let l = pt.beta * pt.f_cos(&sampled) * sampled.beta;
    if l == Color::ZERO {
        return Joined::none();
    }
    let Some(tr) = transmittance(ctx, pt, &sampled, rays) else {
        return Joined::none();
    };
    Joined {
        light: l * tr,
        sampled: Some(sampled),
        film: None,
    }
}

/// Whether nothing lies between surface vertex `a` and vertex `b`, and what the solid
/// between them lets through (Beer-Lambert, where the segment runs inside a solid with
/// absorption): `None` where it is blocked.
fn transmittance(ctx: &Context, a: &Vertex, b: &Vertex, rays: &mut RayStats) -> Option<Color> {
    let scene = ctx.scene;
    let s = a.surface()?;
    let dir = a.direction_to(b);
    let hit = &s.hit;
    let outward = dir.dot(hit.normal) > 0.0;
    let side = if outward { hit.normal } else { -hit.normal };
    let shadow = Ray::new(offset_ray_origin(hit.point, side), dir);
    let distance = if b.infinite() {
        f32::INFINITY
    } else {
        (b.point - a.point).length()
    };
    rays.shadow += 1;
    let t_max = if distance.is_finite() {
        distance * SHADOW_SHORTEN
    } else {
        f32::INFINITY
    };
    if scene.occluded(&shadow, t_max, scene.leaving(hit, outward)) {
        return None;
    }
    let inside = (!outward)
        .then(|| scene.material_at(hit).absorption_inside())
        .flatten();
    Some(match inside {
        Some(sigma) if distance.is_finite() => (-sigma * distance).exp(),
        Some(_) => Color::ZERO,
        None => Color::ONE,
    })
}
