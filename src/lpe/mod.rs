//! Light path expressions: which of a pixel's light came by which kind of path, as images
//! of their own (`--lpe NAME=EXPR`, `[[image.lpe]]`). An expression is OSL's regular
//! expression over a path's events, read from the camera to the light (`C<RD>L`: light
//! reflected once by a diffuse surface); parse.rs reads it, alphabet.rs numbers a scene's
//! events, automaton.rs makes each expression a table the path tracer's events step
//! through, and tracker.rs follows one sample's path and adds what it carries to the
//! expressions it matches. docs/lpe.md is the user's guide.

mod alphabet;
mod automaton;
mod parse;
pub mod pixel;
mod tracker;

pub use alphabet::{Alphabet, Source, SourceKind, Symbol};
pub use automaton::Dfa;
pub use parse::{EventPattern, EventType, Node, Scattering, parse};
pub use tracker::{LightFrom, MAX_LAYERS, Tracker};

use crate::scene::Scene;

/// A mistake in an expression: where (1-based column), what, and how to put it right.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LpeError {
    /// The column it is at.
    pub column: usize,
    /// What is wrong.
    pub message: String,
    /// How to put it right.
    pub help: String,
}

impl LpeError {
    /// An error at `column`.
    pub fn new(column: usize, message: impl Into<String>, help: impl Into<String>) -> Self {
        LpeError {
            column,
            message: message.into(),
            help: help.into(),
        }
    }
}

impl std::fmt::Display for LpeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "column {}: {}", self.column, self.message)
    }
}

/// One expression to render, with the name of its image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Named {
    /// The layer's name (`NAME.R` in an EXR, `x.NAME.png`).
    pub name: String,
    /// The expression.
    pub expr: String,
}

/// What `--lpe` asks for: one expression, or a preset.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Request {
    /// `NAME=EXPR`.
    Expr(Named),
    /// A preset's name.
    Preset(Preset),
}

/// The presets: expressions that teach, by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// Lights and glowing surfaces seen directly: `CL`.
    Emission,
    /// Light from a light, scattered once by a diffuse or glossy surface: `C[DG]L`.
    Direct,
    /// Light scattered by a diffuse or glossy surface first, then more: `C[DG].+L`.
    Indirect,
    /// What mirrors and glass show: a singular event first, `CS.*L`.
    Specular,
    /// Light focused by mirrors or glass onto a diffuse surface: `C<RD>S+L`.
    Caustics,
    /// One layer per source of light: `C.*L'name'`.
    PerLight,
}

impl Preset {
    /// Every preset, in the order the docs give them.
    pub const ALL: [Preset; 6] = [
        Preset::Emission,
        Preset::Direct,
        Preset::Indirect,
        Preset::Specular,
        Preset::Caustics,
        Preset::PerLight,
    ];

    /// Its name on the command line (and its layer's, but for `per-light`).
    pub fn name(self) -> &'static str {
        match self {
            Preset::Emission => "emission",
            Preset::Direct => "direct",
            Preset::Indirect => "indirect",
            Preset::Specular => "specular",
            Preset::Caustics => "caustics",
            Preset::PerLight => "per-light",
        }
    }

    /// Its expression (`per-light`'s, with NAME for each light).
    pub fn expr(self) -> &'static str {
        match self {
            Preset::Emission => "CL",
            Preset::Direct => "C[DG]L",
            Preset::Indirect => "C[DG].+L",
            Preset::Specular => "CS.*L",
            Preset::Caustics => "C<RD>S+L",
            Preset::PerLight => "C.*L'NAME'",
        }
    }

    fn from_name(name: &str) -> Option<Preset> {
        Preset::ALL.into_iter().find(|p| p.name() == name)
    }
}

/// Reads one `--lpe` argument: `NAME=EXPR` or a preset's name.
pub fn request(arg: &str) -> Result<Request, String> {
    if let Some((name, expr)) = arg.split_once('=') {
        let name = name.trim();
        check_name(name)?;
        return Ok(Request::Expr(Named {
            name: name.to_string(),
            expr: expr.to_string(),
        }));
    }
    Preset::from_name(arg.trim())
        .map(Request::Preset)
        .ok_or_else(|| {
            let names: Vec<&str> = Preset::ALL.iter().map(|p| p.name()).collect();
            format!(
                "`{arg}` is neither NAME=EXPR nor a preset (presets: {})",
                names.join(", ")
            )
        })
}

/// Whether `name` may name a layer: letters, digits, `_` and `-`, starting with a letter
/// or `_` (an EXR channel is `NAME.R`, a PNG `x.NAME.png`).
pub fn check_name(name: &str) -> Result<(), String> {
    let mut chars = name.chars();
    let ok = chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if ok {
        Ok(())
    } else {
        Err(format!(
            "`{name}` cannot name an image: use letters, digits, `_` and `-`, starting with a letter"
        ))
    }
}

/// `requests` as the expressions they come to in `scene` (a preset for each light, for
/// `per-light`), in order.
pub fn expand(requests: &[Request], scene: &Scene) -> Vec<Named> {
    let mut out = vec![];
    for r in requests {
        match r {
            Request::Expr(n) => out.push(n.clone()),
            Request::Preset(Preset::PerLight) => {
                for s in per_light_sources(scene) {
                    out.push(Named {
                        name: layer_name(&s.name),
                        expr: format!("C.*L'{}'", s.name),
                    });
                }
            }
            Request::Preset(p) => out.push(Named {
                name: p.name().to_string(),
                expr: p.expr().to_string(),
            }),
        }
    }
    out
}

/// The sources of light a `per-light` layer is made for: every light and glowing object,
/// the environment where the scene has one, the background where it is not black.
fn per_light_sources(scene: &Scene) -> Vec<Source> {
    let a = Alphabet::new(scene);
    a.sources()
        .iter()
        .filter(|s| match s.name.as_str() {
            alphabet::OTHER => false,
            _ if s.kind != SourceKind::Background => true,
            alphabet::ENVIRONMENT => scene.environment_light.is_some(),
            _ => scene.background != crate::math::Color::ZERO,
        })
        .cloned()
        .collect()
}

/// A source's name as a layer's: `point #0` is `point_0`.
fn layer_name(source: &str) -> String {
    let mut out = String::new();
    for c in source.chars() {
        if c.is_ascii_alphanumeric() || c == '-' {
            out.push(c);
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    let out = out.trim_matches('_').to_string();
    if out.starts_with(|c: char| c.is_ascii_alphabetic()) {
        out
    } else {
        format!("light_{out}")
    }
}

/// Why a render's expressions cannot be rendered.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RenderLpeError {
    /// The scene is not rendered by the path tracer (Whitted's ray tracer, or light
    /// tracing).
    Whitted,
    /// Two expressions have one name.
    Duplicate(String),
    /// An expression has the name of another image of the render (a debug view).
    Taken(String),
    /// An expression has a mistake.
    Expr {
        /// The expression.
        named: Named,
        /// Its mistake.
        error: LpeError,
    },
}

impl RenderLpeError {
    /// How to put it right.
    pub fn help(&self) -> String {
        match self {
            RenderLpeError::Whitted => {
                "render with the path tracer (--integrator path, [integrator] type = \"path\")"
                    .into()
            }
            RenderLpeError::Duplicate(_) => {
                "give each expression a name of its own (a per-light image is named after its light)"
                    .into()
            }
            RenderLpeError::Taken(_) => "name the expression otherwise".into(),
            RenderLpeError::Expr { error, .. } => error.help.clone(),
        }
    }
}

impl std::fmt::Display for RenderLpeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RenderLpeError::Whitted => f.write_str(
                "light path expressions follow the path tracer's paths, and this render is not the path tracer's (it is Whitted's, light tracing's or bdpt's)",
            ),
            RenderLpeError::Duplicate(n) => write!(f, "two light path expressions are named `{n}`"),
            RenderLpeError::Taken(n) => write!(
                f,
                "the light path expression `{n}` has the name of a debug view of the render"
            ),
            RenderLpeError::Expr { named, error } => write!(
                f,
                "light path expression `{}` = `{}`: {error}",
                named.name, named.expr
            ),
        }
    }
}

impl std::error::Error for RenderLpeError {}

/// The expressions a render of `scene` writes, made ready for it: the scene's own
/// (`[[image.lpe]]`), then `extra` (the caller's: one named like the scene's replaces it);
/// `None` where there are none. `taken` are the names of the render's other images (its
/// debug views), which an expression may not have.
pub fn for_render(
    scene: &Scene,
    extra: &[Request],
    taken: &[&str],
) -> Result<Option<LpeSet>, RenderLpeError> {
    let mut all = expand(&scene.lpe, scene);
    let mut given: Vec<String> = vec![];
    for n in expand(extra, scene) {
        if given.contains(&n.name) {
            return Err(RenderLpeError::Duplicate(n.name));
        }
        given.push(n.name.clone());
        all.retain(|m| m.name != n.name);
        all.push(n);
    }
    if all.is_empty() {
        return Ok(None);
    }
    if scene.settings.integrator.kind != crate::scene::IntegratorKind::Path {
        return Err(RenderLpeError::Whitted);
    }
    for (i, n) in all.iter().enumerate() {
        if all[..i].iter().any(|m| m.name == n.name) {
            return Err(RenderLpeError::Duplicate(n.name.clone()));
        }
        if taken.contains(&n.name.as_str()) {
            return Err(RenderLpeError::Taken(n.name.clone()));
        }
    }
    LpeSet::new(scene, &all)
        .map(Some)
        .map_err(|e| RenderLpeError::Expr {
            named: all[e.index.min(all.len() - 1)].clone(),
            error: e.error,
        })
}

/// Expressions made ready for one scene: its events numbered, each expression's table.
#[derive(Clone, Debug)]
pub struct LpeSet {
    /// The scene's events.
    pub alphabet: Alphabet,
    /// The expressions, in order.
    pub named: Vec<Named>,
    /// Each expression's automaton.
    pub dfas: Vec<Dfa>,
}

/// Why an expression cannot be rendered: which one, and its mistake.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExprError {
    /// Its index among those given.
    pub index: usize,
    /// The mistake.
    pub error: LpeError,
}

impl LpeSet {
    /// `named` made ready for `scene`: each parsed, its labels checked against the scene's
    /// materials and lights, and checked to match some path.
    pub fn new(scene: &Scene, named: &[Named]) -> Result<LpeSet, ExprError> {
        let alphabet = Alphabet::new(scene);
        if named.len() > MAX_LAYERS {
            return Err(ExprError {
                index: MAX_LAYERS,
                error: LpeError::new(
                    1,
                    format!("at most {MAX_LAYERS} expressions can be rendered at once"),
                    "render the rest in another run",
                ),
            });
        }
        if alphabet.len() > u16::MAX as usize {
            return Err(ExprError {
                index: 0,
                error: LpeError::new(
                    1,
                    "the scene has too many materials and lights for light path expressions",
                    "render a simpler scene",
                ),
            });
        }
        let mut dfas = vec![];
        for (index, n) in named.iter().enumerate() {
            let fail = |error| ExprError { index, error };
            let node = parse(&n.expr).map_err(fail)?;
            check_labels(&node, &alphabet).map_err(fail)?;
            let dfa = Dfa::new(&node, &alphabet).map_err(fail)?;
            if !dfa.matches_some_path(&alphabet) {
                return Err(fail(never_matches(&node)));
            }
            dfas.push(dfa);
        }
        Ok(LpeSet {
            alphabet,
            named: named.to_vec(),
            dfas,
        })
    }

    /// How many expressions.
    pub fn len(&self) -> usize {
        self.dfas.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.dfas.is_empty()
    }
}

/// Every label must name a material (where a scattering event may carry it) or a source
/// of light (where a light may).
fn check_labels(node: &Node, a: &Alphabet) -> Result<(), LpeError> {
    match node {
        Node::Event(p) => check_label(p, a),
        Node::Set { items, .. } => items.iter().try_for_each(|p| check_label(p, a)),
        Node::Seq(parts) | Node::Alt(parts) => parts.iter().try_for_each(|p| check_labels(p, a)),
        Node::Repeat { node, .. } => check_labels(node, a),
    }
}

fn check_label(p: &EventPattern, a: &Alphabet) -> Result<(), LpeError> {
    let Some((label, column)) = &p.label else {
        return Ok(());
    };
    let light = matches!(
        p.kind,
        EventType::Light | EventType::Object | EventType::Background
    );
    let scatter = matches!(p.kind, EventType::Reflect | EventType::Transmit)
        || p.scattering != Scattering::Any;
    let is_light = a.sources().iter().any(|s| s.name == *label);
    let is_material = a.materials().iter().any(|m| m == label);
    let list = |names: Vec<&str>| {
        let shown: Vec<String> = names.iter().take(8).map(|n| format!("'{n}'")).collect();
        let more = if names.len() > 8 { ", ..." } else { "" };
        format!("{}{more}", shown.join(", "))
    };
    let lights = || {
        let names = a.sources().iter().map(|s| s.name.as_str());
        list(names.filter(|&n| n != alphabet::OTHER).collect())
    };
    let materials = || list(a.materials().iter().map(String::as_str).collect());
    if p.kind == EventType::Camera {
        return Err(LpeError::new(
            *column,
            "the camera has no label",
            "a label right after a letter labels that event; for an event labelled after the camera, put a space: `C 'floor' L`",
        ));
    }
    if light && !is_light {
        return Err(LpeError::new(
            *column,
            format!("no light is named '{label}'"),
            format!("the scene's lights: {}", lights()),
        ));
    }
    if scatter && !is_material {
        return Err(LpeError::new(
            *column,
            format!("no material is named '{label}'"),
            format!("the scene's materials: {}", materials()),
        ));
    }
    if !light && !scatter && !is_light && !is_material {
        return Err(LpeError::new(
            *column,
            format!("no material or light is named '{label}'"),
            format!("materials: {}; lights: {}", materials(), lights()),
        ));
    }
    Ok(())
}

/// The mistake of an expression no path matches: where its start cannot be the camera or
/// its end a light, or else the whole of it.
fn never_matches(node: &Node) -> LpeError {
    let parts: Vec<&Node> = match node {
        Node::Seq(p) => p.iter().collect(),
        n => vec![n],
    };
    let plain = |n: &Node| match n {
        Node::Event(p) if p.label.is_none() => Some(p.clone()),
        _ => None,
    };
    let first = parts.first().and_then(|n| plain(n));
    let last = parts.last().and_then(|n| plain(n));
    let camera = |p: &EventPattern| {
        matches!(p.kind, EventType::Camera | EventType::Any) && p.scattering == Scattering::Any
    };
    let light = |p: &EventPattern| {
        matches!(
            p.kind,
            EventType::Light | EventType::Object | EventType::Background | EventType::Any
        ) && p.scattering == Scattering::Any
    };
    if let Some(p) = first.filter(|p| !camera(p)) {
        return LpeError::new(
            p.column,
            "no path matches: a path starts at the camera",
            "read paths from the camera to the light: begin with `C` and end with `L`, as in `C<RD>L`",
        );
    }
    if let Some(p) = last.filter(|p| !light(p)) {
        return LpeError::new(
            p.column,
            "no path matches: a path ends at a light",
            "end the expression with `L` (any light), `O` (a glowing surface) or `B` (the sky)",
        );
    }
    LpeError::new(
        1,
        "no path matches this expression in this scene",
        "paths are `C`, then scattering events (`<RD>`, `<TS>` ...), then a light `L`; check its order and its labels",
    )
}

#[cfg(test)]
mod tests;
