//! The events a scene's paths are made of, numbered: the camera, each way of scattering
//! (reflection or transmission; diffuse, glossy or singular) at each material, and each
//! source of light. An expression's automaton reads these numbers, so that a render finds
//! an event's symbol with one multiplication and an addition.

use super::parse::{EventPattern, EventType, Scattering};
use crate::bsdf::Lobe;
use crate::light::Light;
use crate::scene::Scene;

/// One event of a path, numbered in its scene's [`Alphabet`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Symbol(pub u16);

/// What a source of light is, for the event types `L`, `O` and `B`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SourceKind {
    /// A point, spot or directional light.
    Light,
    /// A glowing object (its material emits).
    Object,
    /// The environment, or the background of a scene without one.
    Background,
}

/// A source of light, by name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Source {
    /// Its name: a light's, a glowing object's, `environment` or `background`.
    pub name: String,
    /// What it is.
    pub kind: SourceKind,
}

/// The name of the environment as a source of light.
pub const ENVIRONMENT: &str = "environment";
/// The name of any other surface as a source of light.
pub const OTHER: &str = "other surface";
/// The name of the background as a source of light.
pub const BACKGROUND: &str = "background";

/// A scene's events, numbered: 0 the camera; then six per material (reflection and
/// transmission, each diffuse, glossy and singular); then one per source of light.
#[derive(Clone, Debug)]
pub struct Alphabet {
    materials: Vec<String>,
    sources: Vec<Source>,
    /// The source of each of the scene's lights.
    source_of_light: Vec<u32>,
    /// The source of each object that glows (`u32::MAX` for the others).
    source_of_object: Vec<u32>,
    environment: u32,
    background: u32,
}

/// An event as a pattern sees it.
enum Event<'a> {
    Camera,
    Scatter {
        transmit: bool,
        scattering: Scattering,
        material: &'a str,
    },
    Light(&'a Source),
}

impl Alphabet {
    /// `scene`'s events.
    pub fn new(scene: &Scene) -> Alphabet {
        let mut sources: Vec<Source> = vec![];
        let mut index: std::collections::HashMap<(String, u8), u32> = Default::default();
        let mut source = |name: &str, kind: SourceKind| -> u32 {
            *index
                .entry((name.to_string(), kind as u8))
                .or_insert_with(|| {
                    sources.push(Source {
                        name: name.to_string(),
                        kind,
                    });
                    (sources.len() - 1) as u32
                })
        };
        let glows = |m: usize| scene.materials[m].emission.is_some();
        // Every object a light is made of glows; any other object's surface, should a path
        // find it glowing, counts as one source of its own (no object of the scenes snell
        // builds does).
        let lit: std::collections::HashSet<usize> = scene
            .lights
            .iter()
            .filter_map(|l| match l {
                Light::Area(a) => Some(a.object),
                _ => None,
            })
            .collect();
        let mut other = None;
        let source_of_object: Vec<u32> = scene
            .objects
            .iter()
            .enumerate()
            .map(|(i, o)| {
                if glows(o.material)
                    || o.slot_materials.iter().any(|&m| glows(m))
                    || lit.contains(&i)
                {
                    source(&o.name, SourceKind::Object)
                } else {
                    *other.get_or_insert_with(|| source(OTHER, SourceKind::Object))
                }
            })
            .collect();
        let mut delta = scene.light_names.iter();
        let source_of_light: Vec<u32> = scene
            .lights
            .iter()
            .map(|l| match l {
                Light::Area(a) => source_of_object[a.object],
                Light::Environment(_) => source(ENVIRONMENT, SourceKind::Background),
                _ => {
                    let name = delta.next().map_or("light", |n| n.as_str());
                    source(name, SourceKind::Light)
                }
            })
            .collect();
        let background = source(BACKGROUND, SourceKind::Background);
        // Rays that leave a scene without an environment see its background.
        let environment = match scene.environment_light {
            Some(_) => source(ENVIRONMENT, SourceKind::Background),
            None => background,
        };
        Alphabet {
            materials: scene.material_names.clone(),
            sources,
            source_of_light,
            source_of_object,
            environment,
            background,
        }
    }

    /// How many symbols.
    pub fn len(&self) -> usize {
        1 + 6 * self.materials.len() + self.sources.len()
    }

    /// Whether there are none (never: the camera is one).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The sources of light.
    pub fn sources(&self) -> &[Source] {
        &self.sources
    }

    /// The materials' names.
    pub fn materials(&self) -> &[String] {
        &self.materials
    }

    /// The camera's event.
    pub fn camera(&self) -> Symbol {
        Symbol(0)
    }

    /// Scattering by `lobe` at material `material`.
    #[inline]
    pub fn scatter(&self, lobe: Lobe, material: usize) -> Symbol {
        let (transmit, scattering) = match lobe {
            Lobe::DiffuseReflection => (false, 0),
            Lobe::GlossyReflection => (false, 1),
            Lobe::SpecularReflection => (false, 2),
            Lobe::GlossyTransmission => (true, 1),
            Lobe::SpecularTransmission => (true, 2),
        };
        self.scatter_as(transmit, scattering, material)
    }

    /// Scattering at material `material`, through the surface or not, diffuse (0), glossy
    /// (1) or singular (2).
    #[inline]
    pub fn scatter_as(&self, transmit: bool, scattering: usize, material: usize) -> Symbol {
        Symbol((1 + material * 6 + transmit as usize * 3 + scattering) as u16)
    }

    /// Light from the scene's light `light` (an index into [`Scene::lights`]).
    #[inline]
    pub fn light(&self, light: usize) -> Symbol {
        self.source(self.source_of_light[light])
    }

    /// Light from object `object`'s glowing surface.
    #[inline]
    pub fn object(&self, object: usize) -> Symbol {
        self.source(self.source_of_object[object])
    }

    /// Light from the environment (`true`) or the background.
    #[inline]
    pub fn sky(&self, environment: bool) -> Symbol {
        self.source(if environment {
            self.environment
        } else {
            self.background
        })
    }

    fn source(&self, s: u32) -> Symbol {
        Symbol((1 + 6 * self.materials.len()) as u16 + s as u16)
    }

    /// Every light's symbol.
    pub fn lights(&self) -> impl Iterator<Item = Symbol> + '_ {
        (0..self.sources.len()).map(|s| self.source(s as u32))
    }

    /// Every scattering event's symbol.
    pub fn scatterings(&self) -> impl Iterator<Item = Symbol> {
        (1..1 + 6 * self.materials.len()).map(|s| Symbol(s as u16))
    }

    fn event(&self, s: Symbol) -> Event<'_> {
        let i = s.0 as usize;
        let m = self.materials.len();
        if i == 0 {
            Event::Camera
        } else if i <= 6 * m {
            let k = i - 1;
            Event::Scatter {
                transmit: (k % 6) >= 3,
                scattering: [
                    Scattering::Diffuse,
                    Scattering::Glossy,
                    Scattering::Singular,
                ][k % 3],
                material: &self.materials[k / 6],
            }
        } else {
            Event::Light(&self.sources[i - 1 - 6 * m])
        }
    }

    /// Whether pattern `p` matches the event `s`.
    pub fn matches(&self, p: &EventPattern, s: Symbol) -> bool {
        let event = self.event(s);
        let kind = match (&event, p.kind) {
            (_, EventType::Any) => true,
            (Event::Camera, EventType::Camera) => true,
            (Event::Scatter { transmit, .. }, EventType::Reflect) => !transmit,
            (Event::Scatter { transmit, .. }, EventType::Transmit) => *transmit,
            (Event::Light(_), EventType::Light) => true,
            (Event::Light(src), EventType::Object) => src.kind == SourceKind::Object,
            (Event::Light(src), EventType::Background) => src.kind == SourceKind::Background,
            _ => false,
        };
        let scattering = match (&event, p.scattering) {
            (_, Scattering::Any) => true,
            (Event::Scatter { scattering, .. }, want) => *scattering == want,
            _ => false,
        };
        let label = match (&event, &p.label) {
            (_, None) => true,
            (Event::Scatter { material, .. }, Some((l, _))) => material == l,
            (Event::Light(src), Some((l, _))) => src.name == *l,
            (Event::Camera, Some(_)) => false,
        };
        kind && scattering && label
    }
}
