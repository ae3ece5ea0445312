//! Why a pixel has its colour: the tree of rays behind one sample, recorded while an
//! integrator traces it, printed as text or JSON (`snell explain`).
//!
//! An integrator reports what it does to a [`Recorder`]. Rendering uses [`NoRecord`], whose
//! methods are empty and whose `ACTIVE` is false, so the compiler removes every call; the
//! explainer uses [`TreeRecorder`], which builds [`RayNode`]s. Each node is one ray: where it
//! goes, what it hits, the material's terms, each light with its shadow ray, the Fresnel split
//! and the rays it spawns, and the colour it returns. A path tracer reports its one path the
//! same way, one child per bounce, filling in `pdf` and `mis_weight`.

use crate::math::{Color, Ray, Vec2, Vec3A};
use serde::Serialize;
use std::fmt::Write;

/// What kind of ray a node is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RayKind {
    /// From the camera through the pixel.
    Camera,
    /// Mirror reflection (or the reflected part of a Fresnel split).
    Reflection,
    /// Transmitted through a surface by Snell's law.
    Refraction,
}

/// Where a ray hit and what the surface there is made of.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HitRecord {
    /// The object's name.
    pub object: String,
    /// The object's index in the scene's `[[objects]]`.
    pub object_index: usize,
    /// Ray parameter (the distance, for a unit direction).
    pub t: f32,
    /// World-space point.
    pub point: [f32; 3],
    /// Outward geometric normal, world space.
    pub normal: [f32; 3],
    /// Shading normal (differs from `normal` on smooth meshes).
    pub shading_normal: [f32; 3],
    /// The texture coordinates the surface's texture reads (through its mapping), or the
    /// shape's own where the surface is a plain colour.
    pub uv: [f32; 2],
    /// `"outside"` when the ray arrives from the side the normal points to (entering a
    /// solid), `"inside"` when it leaves one.
    pub side: &'static str,
    /// The material's name.
    pub material: String,
    /// The material's terms at this point.
    pub terms: MaterialTerms,
}

/// A material's terms at a hit, with the texture's colour there.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MaterialTerms {
    /// Surface colour (texture evaluated at the hit).
    pub color: [f32; 3],
    /// Ambient coefficient.
    pub ambient: f32,
    /// Diffuse coefficient.
    pub diffuse: f32,
    /// Specular colour.
    pub specular: [f32; 3],
    /// Phong exponent.
    pub shininess: f32,
    /// Mirror weight.
    pub reflectivity: f32,
    /// Transmitted fraction.
    pub transparency: f32,
    /// Index of refraction.
    pub ior: f32,
    /// Beer-Lambert coefficient per unit length.
    pub absorption: [f32; 3],
}

/// One light's part in a hit's colour.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LightRecord {
    /// The light's index in `[[lights]]`.
    pub light: usize,
    /// `point`, `directional` or `spot`.
    pub kind: &'static str,
    /// Unit direction toward the light.
    pub to_light: [f32; 3],
    /// Distance to the light (`null` in JSON for directional lights, which are infinitely far).
    pub distance: Option<f32>,
    /// Cosine between the shading normal and the light direction.
    pub cos: f32,
    /// Light arriving before shadowing (colour times intensity, spot falloff included).
    pub radiance: [f32; 3],
    /// Diffuse response: colour x diffuse x cos x (1 - transparency).
    pub diffuse: [f32; 3],
    /// Phong highlight: specular x max(0, r . v)^shininess.
    pub specular: [f32; 3],
    /// The shadow ray, when one was traced.
    pub shadow: Option<ShadowRecord>,
    /// What the light adds: radiance x (diffuse + specular) x transmitted.
    pub contribution: [f32; 3],
    /// Why the light adds nothing without a shadow ray, when it does not.
    pub skipped: Option<&'static str>,
}

/// A shadow ray toward a light.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ShadowRecord {
    /// The opaque object in the way, if any.
    pub blocked_by: Option<String>,
    /// Transparent surfaces crossed, in order, with the fraction each lets through.
    pub crossings: Vec<Crossing>,
    /// Fraction of the light that arrives.
    pub transmitted: [f32; 3],
}

/// A transparent surface on a shadow ray.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Crossing {
    /// The object crossed.
    pub object: String,
    /// `"entering"` or `"leaving"`.
    pub way: &'static str,
    /// Fraction passed at this crossing (transparency x (1 - Fresnel), times the colour on
    /// the way in, or the absorption inside on the way out).
    pub fraction: [f32; 3],
}

/// The split of a ray at a transparent surface.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FresnelRecord {
    /// Cosine of the angle of incidence (to the shading normal).
    pub cos_i: f32,
    /// Sine of the angle of incidence.
    pub sin_i: f32,
    /// n_incident / n_transmitted.
    pub eta: f32,
    /// Sine of the angle of refraction, `eta * sin_i` by Snell's law (`null` on total
    /// internal reflection).
    pub sin_t: Option<f32>,
    /// Fraction reflected (exact Fresnel, unpolarised).
    pub reflectance: f32,
    /// Whether Snell's law has no solution.
    pub total_internal_reflection: bool,
}

/// One ray of the tree.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RayNode {
    /// Camera, reflection or refraction.
    pub kind: RayKind,
    /// Segment number: the camera ray is 1.
    pub depth: u32,
    /// Start (offset off the surface it leaves).
    pub origin: [f32; 3],
    /// Unit direction.
    pub direction: [f32; 3],
    /// What the parent multiplies this ray's colour by.
    pub weight: [f32; 3],
    /// Probability density of having chosen this ray (path tracers; `None` for Whitted).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pdf: Option<f32>,
    /// Multiple importance sampling weight (path tracers).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mis_weight: Option<f32>,
    /// What it hit; `None` for a ray that leaves the scene.
    pub hit: Option<HitRecord>,
    /// Ambient term: world ambient x colour x ambient x (1 - transparency).
    pub ambient: Option<[f32; 3]>,
    /// Each light.
    pub lights: Vec<LightRecord>,
    /// The Fresnel split, at a transparent surface.
    pub fresnel: Option<FresnelRecord>,
    /// Rays it spawned.
    pub children: Vec<RayNode>,
    /// The colour it returns (after absorption or fog on its way).
    pub color: [f32; 3],
    /// Anything else worth knowing (the background, fog, absorption, a cut).
    pub notes: Vec<String>,
}

/// Receives what an integrator does, ray by ray. Calls nest: `begin_ray`, then the hit and
/// its shading, then the children's `begin_ray` ... `end_ray`, then this ray's `end_ray`.
pub trait Recorder {
    /// False for the recorder used while rendering: the integrator may skip work whose only
    /// purpose is the record.
    const ACTIVE: bool;
    /// A ray starts.
    fn begin_ray(&mut self, _kind: RayKind, _ray: &Ray, _depth: u32, _weight: Color) {}
    /// It hit something.
    fn hit(&mut self, _hit: HitRecord) {}
    /// The ambient term.
    fn ambient(&mut self, _c: Color) {}
    /// A light's part.
    fn light(&mut self, _l: LightRecord) {}
    /// The Fresnel split.
    fn fresnel(&mut self, _f: FresnelRecord) {}
    /// A remark.
    fn note(&mut self, _s: String) {}
    /// The ray is done and returns `color`.
    fn end_ray(&mut self, _color: Color) {}
}

/// Records nothing (rendering).
#[derive(Clone, Copy, Debug, Default)]
pub struct NoRecord;

impl Recorder for NoRecord {
    const ACTIVE: bool = false;
}

/// Builds the tree of rays, up to a number of nodes.
#[derive(Debug)]
pub struct TreeRecorder {
    /// Rays begun but not ended (the path from the root to the current ray).
    open: Vec<RayNode>,
    /// The finished root.
    root: Option<RayNode>,
    /// Most nodes kept.
    max_nodes: usize,
    kept: usize,
    /// Rays begun but not kept that have not ended yet (events go nowhere meanwhile).
    skip_open: usize,
    /// Rays not kept, in all.
    skipped: usize,
}

impl TreeRecorder {
    /// A recorder keeping at most `max_nodes` rays (the rest are counted, not kept).
    pub fn new(max_nodes: usize) -> Self {
        TreeRecorder {
            open: vec![],
            root: None,
            max_nodes: max_nodes.max(1),
            kept: 0,
            skip_open: 0,
            skipped: 0,
        }
    }

    /// The tree, once the camera ray has ended; a note on the root says if it was cut.
    pub fn finish(mut self) -> Option<RayNode> {
        let mut root = self.root.take()?;
        if self.skipped > 0 {
            root.notes.push(format!(
                "the tree was cut at {} rays: {} more {} traced but not shown",
                self.max_nodes,
                self.skipped,
                if self.skipped == 1 {
                    "ray was"
                } else {
                    "rays were"
                }
            ));
        }
        Some(root)
    }

    fn current(&mut self) -> Option<&mut RayNode> {
        if self.skip_open > 0 {
            None
        } else {
            self.open.last_mut()
        }
    }
}

fn v3(v: Vec3A) -> [f32; 3] {
    v.to_array()
}

impl Recorder for TreeRecorder {
    const ACTIVE: bool = true;

    fn begin_ray(&mut self, kind: RayKind, ray: &Ray, depth: u32, weight: Color) {
        if self.skip_open > 0 || self.kept >= self.max_nodes {
            self.skip_open += 1;
            self.skipped += 1;
            return;
        }
        self.kept += 1;
        self.open.push(RayNode {
            kind,
            depth,
            origin: v3(ray.origin),
            direction: v3(ray.dir),
            weight: v3(weight),
            pdf: None,
            mis_weight: None,
            hit: None,
            ambient: None,
            lights: vec![],
            fresnel: None,
            children: vec![],
            color: [0.0; 3],
            notes: vec![],
        });
    }

    fn hit(&mut self, hit: HitRecord) {
        if let Some(n) = self.current() {
            n.hit = Some(hit);
        }
    }

    fn ambient(&mut self, c: Color) {
        if let Some(n) = self.current() {
            n.ambient = Some(v3(c));
        }
    }

    fn light(&mut self, l: LightRecord) {
        if let Some(n) = self.current() {
            n.lights.push(l);
        }
    }

    fn fresnel(&mut self, f: FresnelRecord) {
        if let Some(n) = self.current() {
            n.fresnel = Some(f);
        }
    }

    fn note(&mut self, s: String) {
        if let Some(n) = self.current() {
            n.notes.push(s);
        }
    }

    fn end_ray(&mut self, color: Color) {
        if self.skip_open > 0 {
            self.skip_open -= 1;
            return;
        }
        let Some(mut node) = self.open.pop() else {
            return;
        };
        node.color = v3(color);
        match self.open.last_mut() {
            Some(parent) => parent.children.push(node),
            None => self.root = Some(node),
        }
    }
}

/// Formats a number for people: up to 4 significant digits, no trailing zeros.
fn num(x: f32) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    let digits = (4 - 1 - x.abs().log10().floor() as i32).clamp(0, 6) as usize;
    let s = format!("{x:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

fn vec(v: [f32; 3]) -> String {
    format!("({}, {}, {})", num(v[0]), num(v[1]), num(v[2]))
}

fn uv(v: [f32; 2]) -> String {
    format!("({}, {})", num(v[0]), num(v[1]))
}

impl RayNode {
    /// The tree as indented text, one ray per block, for people.
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        self.write_text(&mut out, "", "");
        out
    }

    fn write_text(&self, out: &mut String, first: &str, rest: &str) {
        let kind = match self.kind {
            RayKind::Camera => "camera ray",
            RayKind::Reflection => "reflected ray",
            RayKind::Refraction => "refracted ray",
        };
        let weight = if self.kind == RayKind::Camera {
            String::new()
        } else {
            format!(", weight {}", vec(self.weight))
        };
        let _ = writeln!(
            out,
            "{first}{kind} (depth {}{weight}) from {} along {}",
            self.depth,
            vec(self.origin),
            vec(self.direction)
        );
        let line = |out: &mut String, s: String| {
            let _ = writeln!(out, "{rest}│ {s}");
        };
        match &self.hit {
            None => line(out, "hits nothing".into()),
            Some(h) => {
                line(
                    out,
                    format!(
                        "hits \"{}\" (object {}) at t = {}, point {}, from the {}",
                        h.object,
                        h.object_index,
                        num(h.t),
                        vec(h.point),
                        h.side
                    ),
                );
                let shading = if h.shading_normal != h.normal {
                    format!(", shading normal {}", vec(h.shading_normal))
                } else {
                    String::new()
                };
                line(
                    out,
                    format!("normal {}{shading}, uv {}", vec(h.normal), uv(h.uv)),
                );
                let m = &h.terms;
                line(
                    out,
                    format!(
                        "material \"{}\": colour {}, ambient {}, diffuse {}, specular {}, shininess {}, reflectivity {}, transparency {}, ior {}{}",
                        h.material,
                        vec(m.color),
                        num(m.ambient),
                        num(m.diffuse),
                        vec(m.specular),
                        num(m.shininess),
                        num(m.reflectivity),
                        num(m.transparency),
                        num(m.ior),
                        if m.absorption != [0.0; 3] {
                            format!(", absorption {}", vec(m.absorption))
                        } else {
                            String::new()
                        }
                    ),
                );
            }
        }
        if let Some(a) = self.ambient {
            line(out, format!("ambient {}", vec(a)));
        }
        for l in &self.lights {
            let dist = l
                .distance
                .map_or("infinitely far".into(), |d| format!("{} away", num(d)));
            let head = format!(
                "light {} ({}, {dist}, direction {}): cos {}",
                l.light,
                l.kind,
                vec(l.to_light),
                num(l.cos)
            );
            if let Some(why) = l.skipped {
                line(out, format!("{head}: {why}"));
                continue;
            }
            let shadow = match &l.shadow {
                None => String::new(),
                Some(s) => match &s.blocked_by {
                    Some(b) => format!("; shadow ray blocked by \"{b}\""),
                    None if s.crossings.is_empty() => "; shadow ray clear".into(),
                    None => format!(
                        "; shadow ray through {}: {} arrives",
                        s.crossings
                            .iter()
                            .map(|c| format!(
                                "\"{}\" {}, passing {}",
                                c.object,
                                c.way,
                                vec(c.fraction)
                            ))
                            .collect::<Vec<_>>()
                            .join(", "),
                        vec(s.transmitted)
                    ),
                },
            };
            line(
                out,
                format!(
                    "{head}, diffuse {}, highlight {}{shadow}; adds {}",
                    vec(l.diffuse),
                    vec(l.specular),
                    vec(l.contribution)
                ),
            );
        }
        if let Some(f) = &self.fresnel {
            let snell = match f.sin_t {
                Some(st) => format!(
                    "sin t = eta sin i = {} x {} = {}",
                    num(f.eta),
                    num(f.sin_i),
                    num(st)
                ),
                None => format!(
                    "total internal reflection (eta sin i = {} > 1)",
                    num(f.eta * f.sin_i)
                ),
            };
            line(
                out,
                format!(
                    "Fresnel: cos i = {}, eta = {}, {snell}, reflectance {}",
                    num(f.cos_i),
                    num(f.eta),
                    num(f.reflectance)
                ),
            );
        }
        for n in &self.notes {
            line(out, n.clone());
        }
        for c in &self.children {
            c.write_text(out, &format!("{rest}├─ "), &format!("{rest}│  "));
        }
        let _ = writeln!(out, "{rest}└ returns {}", vec(self.color));
    }
}

/// A texture coordinate as an array.
pub(crate) fn uv2(v: Vec2) -> [f32; 2] {
    v.to_array()
}
