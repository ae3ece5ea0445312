//! A vertex of a camera or a light subpath, and the densities bidirectional path tracing
//! weighs its strategies by: how likely each side was to make a vertex from its neighbour,
//! per unit area (per unit solid angle for a light far away), as pbrt's BDPT keeps them.

use super::Context;
use crate::bsdf::Bsdf;
use crate::integrator::light_tracer::shading_correction;
use crate::light::Light;
use crate::math::{Color, Frame, Vec3A};
use crate::scene::{Hit, Scene};

/// Which way a subpath carries light: radiance from the eye's side, importance from the
/// lights' (the adjoint transport: no `1 / eta^2` on refraction, and Veach's correction for
/// shading normals).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Side {
    /// The camera's subpath.
    Eye,
    /// A light's subpath.
    Light,
}

/// A surface a subpath met.
#[derive(Clone, Debug)]
pub(super) struct Surface {
    /// The hit (its shading normal with the material's detail).
    pub hit: Hit,
    /// The BSDF there.
    pub bsdf: Bsdf,
    /// The shading frame.
    pub frame: Frame,
    /// Toward the previous vertex, world and local.
    pub wo_world: Vec3A,
    /// [`Surface::wo_world`] in the shading frame.
    pub wo: Vec3A,
    /// The area light the surface is, if light sampling can pick it.
    pub light: Option<usize>,
    /// The subpath's side.
    pub side: Side,
}

/// What a vertex is.
#[derive(Clone, Debug)]
pub(super) enum Kind {
    /// The eye (a point of the lens, for a camera with one).
    Camera,
    /// A point of light `light` (on an area light, with its normal), or for a light far away
    /// (the environment, a directional light) the unit direction toward it.
    Light {
        /// Its index in the scene's lights.
        light: usize,
        /// An area light's normal at the point, on the side the light leaves.
        normal: Option<Vec3A>,
        /// Toward the light, for one infinitely far away.
        toward: Option<Vec3A>,
    },
    /// A surface.
    Surface(Box<Surface>),
    /// The background a camera path that left the scene sees where there is no
    /// environment: no light can be sampled there, so only that path finds it.
    Background,
}

/// One vertex of a subpath.
#[derive(Clone, Debug)]
pub(super) struct Vertex {
    /// What it is.
    pub kind: Kind,
    /// Where it is (for a light far away, a point of the disk its rays left).
    pub point: Vec3A,
    /// The geometric normal of a surface or an area light (zero for other vertices).
    pub ng: Vec3A,
    /// The subpath's throughput up to here.
    pub beta: Color,
    /// Whether the subpath met a surface whose index depends on wavelength, here or before:
    /// a path that joins it is then weighed by the sample's wavelength.
    pub dispersed: bool,
    /// The light it sends toward the previous vertex (camera subpaths that meet an
    /// emitter or leave the scene).
    pub le: Color,
    /// The density of this vertex as its subpath made it, per unit area.
    pub pdf_fwd: f32,
    /// The density of this vertex as the other side would have made it, per unit area.
    pub pdf_rev: f32,
    /// Whether the subpath left it by a delta lobe (a mirror or smooth glass).
    pub delta: bool,
}

impl Vertex {
    /// The eye at `point`.
    pub fn camera(point: Vec3A, beta: Color) -> Self {
        Vertex::new(Kind::Camera, point, Vec3A::ZERO, beta)
    }

    /// A vertex of `kind` at `point`, with normal `ng` (zero off a surface).
    pub fn new(kind: Kind, point: Vec3A, ng: Vec3A, beta: Color) -> Self {
        Vertex {
            kind,
            point,
            ng,
            beta,
            dispersed: false,
            le: Color::ZERO,
            pdf_fwd: 0.0,
            pdf_rev: 0.0,
            delta: false,
        }
    }

    /// The surface, if it is one.
    pub fn surface(&self) -> Option<&Surface> {
        match &self.kind {
            Kind::Surface(s) => Some(s),
            _ => None,
        }
    }

    /// Whether it lies on a surface (a surface, or a point of an area light).
    pub fn on_surface(&self) -> bool {
        self.ng != Vec3A::ZERO
    }

    /// The light it is a point of (or a direction toward), if any: a light's vertex, or a
    /// surface that is an area light.
    pub fn light(&self) -> Option<usize> {
        match &self.kind {
            Kind::Light { light, .. } => Some(*light),
            Kind::Surface(s) => s.light,
            _ => None,
        }
    }

    /// Toward the light, for a vertex of a light infinitely far away.
    pub fn toward(&self) -> Option<Vec3A> {
        match &self.kind {
            Kind::Light { toward, .. } => *toward,
            _ => None,
        }
    }

    /// Whether it is a light infinitely far away (or the background).
    pub fn infinite(&self) -> bool {
        self.toward().is_some() || matches!(self.kind, Kind::Background)
    }

    /// Whether it is a point or a direction of a light that is a delta (point, spot,
    /// directional).
    pub fn delta_light(&self, scene: &Scene) -> bool {
        matches!(self.kind, Kind::Light { light, .. } if scene.lights[light].is_delta())
    }

    /// Whether another vertex may be joined to it: a surface with scattering that is not a
    /// delta, the eye, or a light that is not one direction.
    pub fn connectible(&self, scene: &Scene) -> bool {
        match &self.kind {
            Kind::Camera => true,
            Kind::Light { light, .. } => !matches!(scene.lights[*light], Light::Directional(_)),
            Kind::Surface(s) => s.bsdf.has_non_delta(),
            Kind::Background => false,
        }
    }

    /// The unit direction from it to `next`.
    pub fn direction_to(&self, next: &Vertex) -> Vec3A {
        match next.toward() {
            Some(w) => w,
            None => (next.point - self.point).normalize_or_zero(),
        }
    }

    /// A density per unit solid angle at this vertex of the direction to `next`, as a
    /// density per unit area at `next` (unchanged for a light far away).
    pub fn to_area(&self, pdf: f32, next: &Vertex) -> f32 {
        if next.infinite() {
            return pdf;
        }
        let d = next.point - self.point;
        let d2 = d.length_squared();
        if d2 == 0.0 {
            return 0.0;
        }
        let cos = if next.on_surface() {
            next.ng.dot(d).abs() / d2.sqrt()
        } else {
            1.0
        };
        pdf * cos / d2
    }

    /// The density with which this vertex, reached from `prev`, makes `next`, per unit area
    /// at `next`: by its BSDF, by the camera's rays, or by the light's emission.
    pub fn pdf(&self, ctx: &Context, prev: Option<&Vertex>, next: &Vertex) -> f32 {
        match &self.kind {
            Kind::Light { .. } => self.pdf_light(ctx, next),
            Kind::Camera => {
                let (w, h) = ctx.view.size;
                let pdf = ctx.view.camera.direction_pdf(self.direction_to(next), w, h);
                self.to_area(pdf, next)
            }
            Kind::Surface(s) => {
                let Some(prev) = prev else { return 0.0 };
                let wp = s.frame.to_local(self.direction_to(prev));
                let wn = s.frame.to_local(self.direction_to(next));
                self.to_area(s.bsdf.pdf(wp, wn), next)
            }
            Kind::Background => 0.0,
        }
    }

    /// The density with which the light this vertex is a point of sends light to `next`,
    /// per unit area at `next` (per unit area of the disk a light far away sends over).
    pub fn pdf_light(&self, ctx: &Context, next: &Vertex) -> f32 {
        let Some(i) = self.light() else { return 0.0 };
        let w = self.direction_to(next);
        let pdf = if self.infinite() {
            // Over the disk of the scene's bounding sphere that faces the light: a point
            // outside the cylinder it sweeps (an infinite plane's far parts) no light path
            // reaches.
            let (centre, r) = ctx.view.world;
            let v = next.point - centre;
            let across = (v - w * v.dot(w)).length_squared();
            if across > r * r || v.dot(w) < -r {
                return 0.0;
            }
            1.0 / (std::f32::consts::PI * r * r)
        } else {
            let d2 = (next.point - self.point).length_squared();
            if d2 == 0.0 {
                return 0.0;
            }
            let (_, pdf_dir) = ctx.scene.lights[i].pdf_le(self.light_normal(), w, ctx.view.world.1);
            pdf_dir / d2
        };
        if next.on_surface() {
            pdf * next.ng.dot(w).abs()
        } else {
            pdf
        }
    }

    /// The density with which a light subpath starts at this vertex of a light (chosen by
    /// power, then the point; for a light far away, the direction), toward `next`.
    pub fn pdf_light_origin(&self, ctx: &Context, next: &Vertex) -> f32 {
        let Some(i) = self.light() else { return 0.0 };
        let choice = ctx.scene.light_sampler.probability(i);
        let light = &ctx.scene.lights[i];
        match (light, self.toward()) {
            (Light::Environment(env), Some(toward)) => choice * env.pdf(toward),
            (_, Some(_)) => 0.0,
            (light, None) => {
                let w = self.direction_to(next);
                choice * light.pdf_le(self.light_normal(), w, ctx.view.world.1).0
            }
        }
    }

    /// An area light's normal at the vertex, on the side that emits.
    fn light_normal(&self) -> Option<Vec3A> {
        match &self.kind {
            Kind::Light { normal, .. } => *normal,
            Kind::Surface(_) => Some(self.ng),
            _ => None,
        }
    }

    /// The BSDF's value from the previous vertex to `next` (for a light subpath, the adjoint
    /// one), times the cosine at this vertex toward `next` (the shading normal's); 0 where
    /// the geometric and the shading normal disagree about the side `next` is on.
    pub fn f_cos(&self, next: &Vertex) -> Color {
        let Some(s) = self.surface() else {
            return Color::ZERO;
        };
        let w = self.direction_to(next);
        let wi = s.frame.to_local(w);
        let (wo, ng) = (s.wo, s.hit.normal);
        if (wi.z * wo.z > 0.0) != (w.dot(ng) * s.wo_world.dot(ng) > 0.0) {
            return Color::ZERO;
        }
        let f = s.bsdf.f(wo, wi) * wi.z.abs();
        match s.side {
            Side::Eye => f,
            Side::Light => {
                f * (s.bsdf.radiance_scale(wo, wi) * shading_correction(&s.hit, s.wo_world, w))
            }
        }
    }
}
