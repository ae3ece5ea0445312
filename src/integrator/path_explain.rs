//! What `snell explain --integrator path` shows: the one path of one sample, vertex by
//! vertex, with every number the path tracer used (the BSDF's sample and its density, the
//! light sample with both densities and both MIS weights, Russian roulette), the throughput
//! and what each vertex adds. The path tracer reports to a [`PathRecorder`]; rendering passes
//! [`NoPathRecord`], whose calls compile away.

use crate::bsdf::Lobe;
use crate::lpe::LightFrom;
use crate::math::Color;
use serde::Serialize;

/// Receives a path as the path tracer follows it: its records (what `explain` prints), or
/// its events (which light path expressions follow, `crate::lpe::Tracker`).
pub trait PathRecorder {
    /// Whether anything is recorded (`false` lets the compiler drop the recording).
    const ACTIVE: bool;
    /// Whether the path's events are wanted (`false` lets the compiler drop them).
    const EVENTS: bool = false;
    /// A vertex of the path, once all it adds is known.
    fn vertex(&mut self, v: VertexRecord);
    /// How the path ended.
    fn end(&mut self, end: PathEnd);
    /// The path went on, scattered by `lobe` at a surface of material `material`.
    fn scattered(&mut self, _lobe: Lobe, _material: usize) {}
    /// Light `c` (throughput and MIS weight applied) that the path met itself.
    fn reached(&mut self, _c: Color, _from: LightFrom) {}
    /// Light `c` from the scene's light `light` by next-event estimation at a surface of
    /// material `material`, `diffuse` of it by the BSDF's diffuse part; `transmit` where
    /// the light is on the other side of the surface.
    fn sampled(
        &mut self,
        _c: Color,
        _diffuse: Color,
        _transmit: bool,
        _material: usize,
        _light: usize,
    ) {
    }
    /// The sample came to `l`, and to `clamped` after the integrator's clamp.
    fn finished(&mut self, _l: Color, _clamped: Color) {}
}

/// Records nothing: what rendering uses.
pub struct NoPathRecord;

impl PathRecorder for NoPathRecord {
    const ACTIVE: bool = false;
    fn vertex(&mut self, _: VertexRecord) {}
    fn end(&mut self, _: PathEnd) {}
}

/// Two recorders at once: the path's records to one and its events to the other (a path
/// drawn with the kind of light it carries).
impl<A: PathRecorder, B: PathRecorder> PathRecorder for (A, B) {
    const ACTIVE: bool = A::ACTIVE || B::ACTIVE;
    const EVENTS: bool = A::EVENTS || B::EVENTS;
    fn vertex(&mut self, v: VertexRecord) {
        if B::ACTIVE {
            self.1.vertex(v.clone());
        }
        self.0.vertex(v);
    }
    fn end(&mut self, end: PathEnd) {
        if B::ACTIVE {
            self.1.end(end.clone());
        }
        self.0.end(end);
    }
    fn scattered(&mut self, lobe: Lobe, material: usize) {
        self.0.scattered(lobe, material);
        self.1.scattered(lobe, material);
    }
    fn reached(&mut self, c: Color, from: LightFrom) {
        self.0.reached(c, from);
        self.1.reached(c, from);
    }
    fn sampled(&mut self, c: Color, diffuse: Color, transmit: bool, material: usize, light: usize) {
        self.0.sampled(c, diffuse, transmit, material, light);
        self.1.sampled(c, diffuse, transmit, material, light);
    }
    fn finished(&mut self, l: Color, clamped: Color) {
        self.0.finished(l, clamped);
        self.1.finished(l, clamped);
    }
}

/// A whole path: what `explain` prints.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct PathRecord {
    /// The surfaces the path met, from the camera on.
    pub vertices: Vec<VertexRecord>,
    /// How it ended.
    pub end: Option<PathEnd>,
}

impl PathRecorder for PathRecord {
    const ACTIVE: bool = true;
    fn vertex(&mut self, v: VertexRecord) {
        self.vertices.push(v);
    }
    fn end(&mut self, end: PathEnd) {
        self.end = Some(end);
    }
}

/// One vertex: a surface the path met.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct VertexRecord {
    /// Segments traced to reach it (the camera ray is 1).
    pub depth: u32,
    /// The object met, by name.
    pub object: String,
    /// Its material, by name.
    pub material: String,
    /// The BSDF built there (its variant).
    pub bsdf: String,
    /// World-space point.
    pub point: [f32; 3],
    /// Whether the path met the front (outward) side.
    pub front: bool,
    /// The throughput arriving here (Beer-Lambert on the way included).
    pub throughput: [f32; 3],
    /// Emission seen here, its MIS weight and what it adds (throughput x emission x weight).
    pub emission: Option<EmissionRecord>,
    /// Next-event estimation here, if the BSDF has a lobe light sampling can reach.
    pub light: Option<LightSampleRecord>,
    /// The BSDF's sampled direction, if the path went on.
    pub bounce: Option<BounceRecord>,
    /// Russian roulette after the bounce, if it was played.
    pub roulette: Option<RouletteRecord>,
    /// What this vertex adds to the sample: emission and light sample together.
    pub contribution: [f32; 3],
}

/// Emission met by the path.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EmissionRecord {
    /// Radiance leaving toward the path.
    pub radiance: [f32; 3],
    /// The MIS weight against light sampling (1 after a delta bounce, for the camera ray and
    /// for emitters light sampling never chooses).
    pub mis_weight: f32,
    /// Light sampling's density for the same direction (solid angle), where it counts.
    pub light_pdf: Option<f32>,
    /// Throughput x radiance x weight.
    pub contribution: [f32; 3],
}

/// One light sample.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LightSampleRecord {
    /// The light chosen (its index among all lights: point, spot and directional first, then
    /// area lights), with what it is.
    pub light: usize,
    /// `point`, `spot`, `directional` or the area light's object name.
    pub what: String,
    /// Unit direction toward the light.
    pub direction: [f32; 3],
    /// Distance to it.
    pub distance: f32,
    /// Radiance (area) or irradiance (delta lights) arriving, unshadowed.
    pub radiance: [f32; 3],
    /// The light sample's density: choice x solid angle (the choice alone for deltas).
    pub light_pdf: f32,
    /// The BSDF's density for the same direction.
    pub bsdf_pdf: f32,
    /// `f x |cos|` for the direction.
    pub f_cos: [f32; 3],
    /// The light sample's MIS weight (1 for delta lights).
    pub mis_weight: f32,
    /// Why nothing was added, if nothing was.
    pub blocked: Option<String>,
    /// Throughput x f x |cos| x radiance x weight / pdf.
    pub contribution: [f32; 3],
}

/// The BSDF's sampled continuation.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BounceRecord {
    /// The lobe sampled.
    pub lobe: String,
    /// World direction.
    pub direction: [f32; 3],
    /// Its density (solid angle; for a delta lobe, the lobe's probability).
    pub pdf: f32,
    /// `f` for it.
    pub f: [f32; 3],
    /// `|cos|` at the shading normal.
    pub cos: f32,
    /// `f x |cos| / pdf`, the factor on the throughput.
    pub weight: [f32; 3],
}

/// Russian roulette.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RouletteRecord {
    /// The chance the path survived.
    pub survival: f32,
    /// Whether it did (the throughput is then divided by `survival`).
    pub survived: bool,
}

/// How a path ended.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "reason", rename_all = "snake_case")]
pub enum PathEnd {
    /// It left the scene and saw the background.
    Escaped {
        /// Throughput x background.
        contribution: [f32; 3],
    },
    /// `max_depth` segments were traced.
    MaxDepth,
    /// The BSDF sample was absorbed, or its direction disagreed with the geometric normal.
    Absorbed,
    /// Russian roulette ended it.
    Roulette,
}

impl PathRecord {
    /// The sum of what every vertex and the escape add: the sample's value before a clamp.
    pub fn total(&self) -> [f32; 3] {
        let mut t = [0.0f32; 3];
        let add = |t: &mut [f32; 3], c: &[f32; 3]| {
            for i in 0..3 {
                t[i] += c[i];
            }
        };
        for v in &self.vertices {
            add(&mut t, &v.contribution);
        }
        if let Some(PathEnd::Escaped { contribution }) = &self.end {
            add(&mut t, contribution);
        }
        t
    }

    /// The path as text, one block per vertex.
    pub fn to_text(&self) -> String {
        use std::fmt::Write;
        let f3 = |v: &[f32; 3]| format!("({:.4}, {:.4}, {:.4})", v[0], v[1], v[2]);
        let mut s = String::new();
        for v in &self.vertices {
            let _ = writeln!(
                s,
                "vertex {} (segment {}): `{}`, material `{}` ({}), {} side, at {}",
                v.depth - 1,
                v.depth,
                v.object,
                v.material,
                v.bsdf,
                if v.front { "front" } else { "back" },
                f3(&v.point)
            );
            let _ = writeln!(s, "  throughput {}", f3(&v.throughput));
            if let Some(e) = &v.emission {
                let _ = writeln!(
                    s,
                    "  emits {}; MIS weight {:.4}{}; adds {}",
                    f3(&e.radiance),
                    e.mis_weight,
                    e.light_pdf
                        .map_or(String::new(), |p| format!(" (light pdf {p:.4})")),
                    f3(&e.contribution)
                );
            }
            if let Some(l) = &v.light {
                let _ = writeln!(
                    s,
                    "  light sample: light {} ({}), direction {}, distance {:.4}, radiance {}",
                    l.light,
                    l.what,
                    f3(&l.direction),
                    l.distance,
                    f3(&l.radiance)
                );
                let _ = writeln!(
                    s,
                    "    light pdf {:.5}, BSDF pdf {:.5}, MIS weight {:.4}, f cos {}",
                    l.light_pdf,
                    l.bsdf_pdf,
                    l.mis_weight,
                    f3(&l.f_cos)
                );
                match &l.blocked {
                    Some(why) => {
                        let _ = writeln!(s, "    adds nothing: {why}");
                    }
                    None => {
                        let _ = writeln!(s, "    adds {}", f3(&l.contribution));
                    }
                }
            }
            if let Some(b) = &v.bounce {
                let _ = writeln!(
                    s,
                    "  bounce: {} toward {}, pdf {:.5}, f {}, cos {:.4}: throughput x {}",
                    b.lobe,
                    f3(&b.direction),
                    b.pdf,
                    f3(&b.f),
                    b.cos,
                    f3(&b.weight)
                );
            }
            if let Some(r) = &v.roulette {
                let _ = writeln!(
                    s,
                    "  Russian roulette: survival {:.4}, {}",
                    r.survival,
                    if r.survived {
                        "survived (throughput / survival)"
                    } else {
                        "ended the path"
                    }
                );
            }
            let _ = writeln!(s, "  vertex adds {}", f3(&v.contribution));
        }
        match &self.end {
            Some(PathEnd::Escaped { contribution }) => {
                let _ = writeln!(
                    s,
                    "the path leaves the scene: the background adds {}",
                    f3(contribution)
                );
            }
            Some(PathEnd::MaxDepth) => {
                let _ = writeln!(s, "the path ends: max_depth reached");
            }
            Some(PathEnd::Absorbed) => {
                let _ = writeln!(s, "the path ends: the BSDF sample was absorbed");
            }
            Some(PathEnd::Roulette) => {
                let _ = writeln!(s, "the path ends: Russian roulette");
            }
            None => {}
        }
        s
    }
}
