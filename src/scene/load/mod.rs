//! From a scene file to a [`Scene`]: parse, check every value, resolve names and paths, load
//! textures. Problems are collected (not just the first) and located in the text.

use super::assets::AssetCache;
use super::diag::{DocPath, Format, Problem, SceneError, did_you_mean, name_help, offset_of};
use super::format::*;
use super::meshes::{LoadedMesh, MeshCache, Palette};
use super::{
    BuildStats, Fog, IntegratorSettings, Limits, MeshStats, Object, RenderSettings, Scene,
};
use crate::accel::Bvh;
use crate::film::Filter;
use crate::geometry::{Cone, Cuboid, Cylinder, Disk, Plane, Rect, Shape, Sphere, Torus, Triangle};
use crate::light::{Light, LightSampler};
use crate::material::detail::SurfaceDetail;
use crate::math::{Color, Frame, Transform, Vec3, Vec3A};
use crate::sampler::SamplerKind;
use crate::texture::{ColorSpace, Mapping, Pattern, Texture, Wrap, Wraps};
use group::{Placement, Placing};
use material::MaterialTextures;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

pub use animation::{Animation, MAX_FRAMES};
mod animation;
pub(super) mod camera;
mod csg;
mod emitters;
mod environment;
mod group;
mod material;
mod sky;

/// Reads, checks and builds the scene in `path` (`.toml` or `.json`). Relative paths in it
/// resolve against its folder.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    load_with(path, &Limits::default())
}

/// As [`load`], checking the scene against `limits` (image size, samples, depth, texture
/// sizes, triangles) instead of the defaults.
pub fn load_with(path: &Path, limits: &Limits) -> Result<Scene, SceneError> {
    load_frame(path, limits, 0, &mut AssetCache::default())
}

/// As [`load_with`], the scene at `frame` of its `[animation]` (a scene without one has
/// frame 0 only), reusing the images and meshes `assets` kept from earlier frames.
pub fn load_frame(
    path: &Path,
    limits: &Limits,
    frame: u32,
    assets: &mut AssetCache,
) -> Result<Scene, SceneError> {
    let format = match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("json") => Format::Json,
        Some(e) if e.eq_ignore_ascii_case("toml") => Format::Toml,
        _ => {
            return Err(SceneError::whole_file(
                path,
                "a scene file must end in .toml or .json",
            ));
        }
    };
    let bytes = crate::read_regular_file(path)
        .map_err(|e| SceneError::whole_file(path, format!("cannot read the scene file: {e}")))?;
    let text = String::from_utf8(bytes).map_err(|e| {
        SceneError::whole_file(
            path,
            format!(
                "the scene file is not UTF-8 text (bad byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })?;
    let base = path.parent().unwrap_or(Path::new("."));
    build(&text, path, base, format, limits, frame, assets)
}

/// Builds a scene from text. `file` names it in messages; `base_dir` resolves relative paths.
pub fn load_str(
    text: &str,
    file: &Path,
    base_dir: &Path,
    format: Format,
) -> Result<Scene, SceneError> {
    load_str_frame(text, file, base_dir, format, 0)
}

/// As [`load_str`], the scene at `frame` of its `[animation]`.
pub fn load_str_frame(
    text: &str,
    file: &Path,
    base_dir: &Path,
    format: Format,
    frame: u32,
) -> Result<Scene, SceneError> {
    let mut assets = AssetCache::default();
    let limits = Limits::default();
    build(text, file, base_dir, format, &limits, frame, &mut assets)
}

fn build(
    text: &str,
    file: &Path,
    base_dir: &Path,
    format: Format,
    limits: &Limits,
    frame: u32,
    assets: &mut AssetCache,
) -> Result<Scene, SceneError> {
    let mut def =
        parse(text, format).map_err(|p| SceneError::located(file, text, format, vec![p]))?;
    let mut b = Builder {
        assets,
        problems: vec![],
        warnings: vec![],
        base_dir,
        mesh_cache: Default::default(),
        stats: Default::default(),
        limits: *limits,
        triangles_loaded: 0,
        files: vec![],
    };
    let animation = b.animate(&mut def, frame);
    let mut scene = b.scene(def);
    scene.animation = animation;
    scene.source = text.into();
    scene.frame = frame;
    b.files.sort();
    b.files.dedup();
    // A group placed several times reports its objects' problems once.
    let mut seen = std::collections::HashSet::new();
    b.problems
        .retain(|p| seen.insert((p.path.to_string(), p.message.clone())));
    if b.problems.is_empty() {
        scene.files = b.files;
        Ok(scene)
    } else {
        let mut e = SceneError::located(file, text, format, b.problems);
        e.files = b.files;
        Err(e)
    }
}

fn parse(text: &str, format: Format) -> Result<SceneFile, Problem> {
    parse_unrefined(text, format).map_err(|p| refine(text, format, p))
}

/// Inside tagged tables (objects, lights, textures, mappings) serde buffers values and loses
/// their positions, so a type error is reported at the whole table. Find the value the
/// message describes (`invalid type: string "big"`, `invalid length 2`) below it.
fn refine(text: &str, format: Format, p: Problem) -> Problem {
    if p.at_key {
        // An unknown key in a table nested inside a tagged one (an object's `transform`)
        // comes with the tagged table's path: find the key below it.
        let Some((parent, super::diag::Seg::Key(field))) = p
            .path
            .0
            .split_last()
            .map(|(l, r)| (DocPath(r.to_vec()), l.clone()))
        else {
            return p;
        };
        let below = super::diag::values_below(text, format, &parent);
        if below.iter().any(|(q, _)| *q == p.path) {
            return p;
        }
        let nested = below
            .into_iter()
            .find(|(q, _)| q.0.last() == Some(&super::diag::Seg::Key(field.clone())));
        return match nested {
            Some((path, _)) => Problem { path, ..p },
            None => p,
        };
    }
    if !p.message.contains("invalid ") {
        return p;
    }
    let Some(described) = p.message.split("invalid ").nth(1) else {
        return p;
    };
    let matches = |raw: &str| -> bool {
        let raw = raw.trim();
        if let Some(rest) = described.strip_prefix("type: string ") {
            let want = rest
                .split(", expected")
                .next()
                .unwrap_or("")
                .trim_matches('"');
            (raw.starts_with('"') || raw.starts_with('\''))
                && raw.trim_matches(|c| c == '"' || c == '\'') == want
        } else if let Some(rest) = described
            .strip_prefix("type: integer `")
            .or_else(|| described.strip_prefix("value: integer `"))
            .or_else(|| described.strip_prefix("type: floating point `"))
            .or_else(|| described.strip_prefix("value: floating point `"))
        {
            let want = rest.split('`').next().unwrap_or("");
            raw.parse::<f64>()
                .ok()
                .zip(want.parse::<f64>().ok())
                .is_some_and(|(a, b)| a == b)
        } else if let Some(rest) = described.strip_prefix("type: boolean `") {
            raw == rest.split('`').next().unwrap_or("")
        } else if described.starts_with("type: sequence") {
            raw.starts_with('[')
        } else if let Some(rest) = described.strip_prefix("length ") {
            let n: usize = rest
                .split(',')
                .next()
                .unwrap_or("")
                .parse()
                .unwrap_or(usize::MAX);
            raw.starts_with('[') && count_items(raw) == Some(n)
        } else {
            false
        }
    };
    // Only a value the message singles out: with two arrays (or two equal strings) in the
    // table, the message could mean either, and the table itself is the honest answer.
    let mut found = super::diag::values_below(text, format, &p.path)
        .into_iter()
        .filter(|(_, span)| text.get(span.clone()).is_some_and(matches));
    let first = found.next();
    let unique = found.next().is_none();
    match first.filter(|_| unique) {
        Some((path, span)) if path != p.path => {
            let message = p.message.clone();
            Problem {
                span: Some(span),
                ..Problem::new(path, message)
            }
            .with_help(p.help)
        }
        _ => p,
    }
}

/// Number of items in a flat array literal such as `[1, 2]` (`None` if it nests).
fn count_items(raw: &str) -> Option<usize> {
    let inner = raw.strip_prefix('[')?.strip_suffix(']')?;
    if inner.contains('[') || inner.contains('{') {
        return None;
    }
    Some(inner.split(',').filter(|x| !x.trim().is_empty()).count())
}

fn parse_unrefined(text: &str, format: Format) -> Result<SceneFile, Problem> {
    match format {
        Format::Toml => {
            let table = toml::de::DeTable::parse(text).map_err(|e| Problem {
                span: e.span(),
                ..Problem::new(
                    DocPath::default(),
                    format!("TOML syntax: {}", e.message().trim_end()),
                )
            })?;
            serde_path_to_error::deserialize(toml::de::Deserializer::from(table)).map_err(|e| {
                let span = e.inner().span();
                serde_problem(e.path(), e.inner().message(), span)
            })
        }
        Format::Json => {
            let mut de = serde_json::Deserializer::from_str(text);
            let result: Result<SceneFile, _> = serde_path_to_error::deserialize(&mut de);
            let syntax = |inner: &serde_json::Error| {
                let at = offset_of(text, inner.line(), inner.column());
                let msg = inner.to_string();
                // serde_json appends " at line L column C"; the location is shown anyway.
                let msg = msg.split(" at line ").next().unwrap_or(&msg).to_string();
                (at, msg)
            };
            if let Ok(v) = result {
                return de.end().map(|_| v).map_err(|e| {
                    let (at, msg) = syntax(&e);
                    Problem {
                        span: Some(at..at),
                        ..Problem::new(DocPath::default(), format!("JSON syntax: {msg}"))
                    }
                });
            }
            result.map_err(|e| {
                let inner = e.inner();
                let (at, msg) = syntax(inner);
                if inner.is_syntax() || inner.is_eof() {
                    Problem {
                        span: Some(at..at),
                        ..Problem::new(DocPath::default(), format!("JSON syntax: {msg}"))
                    }
                } else {
                    let mut p = serde_problem(e.path(), &msg, None);
                    if p.path.0.is_empty() && p.span.is_none() {
                        p.span = Some(at..at);
                    }
                    p
                }
            })
        }
    }
}

/// Turns a serde error at a path into a problem with a hint.
fn serde_problem(
    path: &serde_path_to_error::Path,
    message: &str,
    span: Option<std::ops::Range<usize>>,
) -> Problem {
    use serde_path_to_error::Segment;
    let mut doc = DocPath::default();
    for seg in path.iter() {
        match seg {
            Segment::Seq { index } => doc = doc.index(*index),
            Segment::Map { key } => doc = doc.key(key),
            Segment::Enum { .. } => {}
            Segment::Unknown => break,
        }
    }
    let message = message.trim_end().to_string();
    if let Some(field) = between(&message, "unknown field `", "`") {
        let expected = backticked(message.split_once("expected").map_or("", |x| x.1));
        // serde_path_to_error records the unknown key itself for plain structs, not for
        // tagged ones.
        let path = if doc.0.last() == Some(&super::diag::Seg::Key(field.to_string())) {
            doc
        } else {
            doc.key(field)
        };
        let mut p = Problem::new(path, format!("unknown key `{field}`"));
        p.at_key = true;
        p.help = Some(
            match did_you_mean(field, expected.iter().map(String::as_str)) {
                Some(s) => format!("did you mean `{s}`?"),
                None if expected.is_empty() => "no other key belongs here".to_string(),
                None => format!("known keys here: {}", expected.join(", ")),
            },
        );
        return p;
    }
    if let Some(variant) = between(&message, "unknown variant `", "`") {
        let expected = backticked(message.split_once("expected").map_or("", |x| x.1));
        // A `type` names a kind of thing; other keys (a sampler, a tone curve) take values.
        let what = match doc.0.last() {
            Some(super::diag::Seg::Key(k)) if k == "type" => "type",
            _ => "value",
        };
        let mut p = Problem::new(doc, format!("unknown {what} `{variant}`"));
        p.span = span;
        p.help = Some(
            match did_you_mean(variant, expected.iter().map(String::as_str)) {
                Some(s) => format!("did you mean `{s}`?"),
                None => format!("expected one of: {}", expected.join(", ")),
            },
        );
        return p;
    }
    if let Some(field) = between(&message, "missing field `", "`") {
        let mut p = Problem::new(doc.clone(), format!("missing key `{field}`"));
        p.span = span;
        // The file's top level holds tables (`[camera]`); keys go inside them.
        p.help = Some(if doc.0.is_empty() {
            format!("add a `[{field}]` table (see docs/scene-format.md)")
        } else {
            format!("add `{field} = ...` here (see docs/scene-format.md)")
        });
        return p;
    }
    // A whole number of the wrong sign or size: say what the key takes, where a key says
    // more than its type does (a width of 0 is refused too).
    if let Some(n) = between(&message, "invalid value: integer `", "`") {
        let key = match doc.0.last() {
            Some(super::diag::Seg::Key(k)) => k.as_str(),
            _ => "",
        };
        let range = match key {
            "width" | "height" => {
                format!(
                    "from 1 to {} pixels",
                    crate::scene::RenderSettings::MAX_SIDE
                )
            }
            "samples" | "max_depth" | "rr_depth" => "from 1".to_string(),
            _ => "from 0".to_string(),
        };
        let mut p = Problem::new(
            doc,
            format!("`{n}` is not allowed here: a whole number {range}"),
        );
        p.span = span;
        return p;
    }
    let mut p = Problem::new(
        doc,
        message
            .replace("f32", "a number")
            .replace("u32", "a whole number ≥ 0")
            .replace("u64", "a whole number ≥ 0"),
    );
    p.span = span;
    p
}

fn between<'a>(s: &'a str, start: &str, end: &str) -> Option<&'a str> {
    let rest = &s[s.find(start)? + start.len()..];
    Some(&rest[..rest.find(end)?])
}

fn backticked(s: &str) -> Vec<String> {
    s.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

/// Largest magnitude of any number in a scene: its square (1e30) still fits in an `f32`, so
/// lengths, areas and quadratics cannot overflow.
pub const MAX_MAGNITUDE: f32 = 1e15;

pub(super) struct Builder<'a> {
    problems: Vec<Problem>,
    pub(super) warnings: Vec<String>,
    pub(super) base_dir: &'a Path,
    /// Images and meshes earlier builds of the scene loaded (an animation's frames).
    pub(super) assets: &'a mut AssetCache,
    /// Meshes loaded so far, by file and normals option (`None` where loading failed).
    pub(super) mesh_cache: MeshCache,
    pub(super) stats: BuildStats,
    pub(super) limits: Limits,
    /// Triangles in the meshes loaded so far (each file once).
    pub(super) triangles_loaded: u64,
    /// The files read or tried so far (textures, meshes, MTL files and their maps).
    pub(super) files: Vec<PathBuf>,
}

impl Builder<'_> {
    pub(super) fn problem_count(&self) -> usize {
        self.problems.len()
    }

    pub(super) fn error(&mut self, path: DocPath, msg: impl Into<String>) {
        self.problems.push(Problem::new(path, msg));
    }

    pub(super) fn error_help(
        &mut self,
        path: DocPath,
        msg: impl Into<String>,
        help: impl Into<String>,
    ) {
        self.problems.push(Problem::new(path, msg).help(help));
    }

    fn finite(&mut self, x: f32, path: &DocPath) -> f32 {
        if x.is_nan() {
            self.error(path.clone(), "must be a finite number, not nan");
            0.0
        } else if x.is_infinite() {
            // `inf`, or a number too large for a 32-bit float (1e300): the same limit holds.
            self.error_help(
                path.clone(),
                format!("is too large: numbers must be at most {MAX_MAGNITUDE:e} in magnitude"),
                "squares of larger numbers overflow 32-bit floats; scale the scene down",
            );
            0.0
        } else if x.abs() > MAX_MAGNITUDE {
            self.error_help(
                path.clone(),
                format!("{x:e} is too large (at most {MAX_MAGNITUDE:e} in magnitude)"),
                "squares of larger numbers overflow 32-bit floats; scale the scene down",
            );
            0.0
        } else {
            x
        }
    }

    fn positive(&mut self, x: f32, path: &DocPath) -> f32 {
        if !x.is_finite() || x.abs() > MAX_MAGNITUDE {
            self.finite(x, path);
            return 1.0;
        }
        if x <= 0.0 {
            self.error(path.clone(), format!("must be greater than 0, not {x}"));
            return 1.0;
        }
        x
    }

    fn non_negative(&mut self, x: f32, path: &DocPath) -> f32 {
        let x = self.finite(x, path);
        if x < 0.0 {
            self.error(path.clone(), format!("must be 0 or more, not {x}"));
            return 0.0;
        }
        x
    }

    fn in_range(&mut self, x: f32, lo: f32, hi: f32, path: &DocPath) -> f32 {
        let x = self.finite(x, path);
        if !(lo..=hi).contains(&x) {
            self.error(
                path.clone(),
                format!("must be between {lo} and {hi}, not {x}"),
            );
            return x.clamp(lo, hi);
        }
        x
    }

    fn point(&mut self, v: V3, path: &DocPath) -> Vec3A {
        if v.iter().any(|x| x.is_nan()) {
            self.error(path.clone(), format!("must be finite numbers, not {v:?}"));
            Vec3A::ZERO
        } else if v.iter().any(|x| x.is_infinite() || x.abs() > MAX_MAGNITUDE) {
            self.error_help(
                path.clone(),
                if v.iter().any(|x| x.is_infinite()) {
                    // `inf`, or beyond a 32-bit float (1e300): naming the value would say `inf`.
                    format!(
                        "is too large: each number must be at most {MAX_MAGNITUDE:e} in magnitude"
                    )
                } else {
                    format!(
                        "{v:?} is too large (each number at most {MAX_MAGNITUDE:e} in magnitude)"
                    )
                },
                "squares of larger numbers overflow 32-bit floats; scale the scene down",
            );
            Vec3A::ZERO
        } else {
            Vec3A::from_array(v)
        }
    }

    fn direction(&mut self, v: V3, path: &DocPath) -> Vec3A {
        let p = self.point(v, path);
        let len = p.length();
        if len == 0.0 || !len.is_finite() {
            if p.is_finite() {
                self.error(
                    path.clone(),
                    "must not be the zero vector: it gives the direction",
                );
            }
            return Vec3A::Y;
        }
        p / len
    }

    fn color(&mut self, c: ColorDef, path: &DocPath) -> Color {
        let v = Vec3A::from_array(c.0);
        if !v.is_finite() || v.min_element() < 0.0 {
            self.error(
                path.clone(),
                format!("colour components must be finite and ≥ 0, not {:?}", c.0),
            );
            return Color::ZERO;
        }
        v
    }

    fn scene(&mut self, def: SceneFile) -> Scene {
        let root = DocPath::default();
        let settings = self.settings(&def.image, &def.integrator, &root.key("image"));
        let camera = self.camera(&def.camera, &root.key("camera"));
        let background = self.color(def.image.background, &root.key("image").key("background"));
        let ambient = self.color(def.world.ambient, &root.key("world").key("ambient"));
        let fog = def.fog.as_ref().map(|f| self.fog(f, &root.key("fog")));
        let environment = def
            .environment
            .as_ref()
            .and_then(|e| self.environment(e, &root.key("environment")));

        let mut textures = vec![];
        let mut texture_names = BTreeMap::new();
        // Textures a material reads as a normal or bump map hold data, not colours.
        let data: std::collections::BTreeSet<&str> = def
            .materials
            .values()
            .flat_map(|m| [&m.normal_map, &m.bump])
            .flatten()
            .map(String::as_str)
            .collect();
        for (name, t) in &def.textures {
            let path = root.key("textures").key(name);
            texture_names.insert(name.clone(), textures.len());
            let data = data.contains(name.as_str());
            if data
                && let TextureDef::Image {
                    color_space: Some(ColorSpaceDef::Srgb),
                    ..
                } = t
            {
                self.warnings.push(format!(
                    "texture `{name}` is a normal or bump map but says color_space = \"srgb\": such maps hold data, stored linear"
                ));
            }
            textures.push(self.texture(t, &path, data));
        }
        let mut used_textures = vec![false; textures.len()];

        let mut materials = vec![];
        let mut material_names = vec![];
        for (name, m) in &def.materials {
            let path = root.key("materials").key(name);
            let mut names = MaterialTextures {
                textures: &mut textures,
                names: &texture_names,
                used: &mut used_textures,
            };
            materials.push(self.material(m, &path, &mut names));
            material_names.push(name.clone());
        }
        for (name, &i) in &texture_names {
            if !used_textures[i] {
                self.warnings.push(format!(
                    "texture `{name}` is defined but no material uses it"
                ));
            }
        }

        let mut lights: Vec<Light> = def
            .lights
            .iter()
            .enumerate()
            .map(|(i, l)| self.light(l, &root.key("lights").index(i)))
            .collect();

        let mut used_materials = vec![false; materials.len()];
        let user_materials = materials.len();
        let mut palette = Palette {
            materials: &mut materials,
            names: &mut material_names,
            textures: &mut textures,
        };
        let named_meshes = self.named_meshes(&def.meshes, &root.key("meshes"), &mut palette);
        let mut used_meshes = vec![false; named_meshes.len()];
        let mut objects = vec![];
        let mut used_groups = vec![false; def.groups.len()];
        let mut placing = Placing {
            named_meshes: &named_meshes,
            used_meshes: &mut used_meshes,
            palette: &mut palette,
            user_materials,
        };
        for (i, o) in def.objects.iter().enumerate() {
            let path = root.key("objects").index(i);
            let placed = match o {
                ObjectDef::Group(g) => {
                    self.group_placement(g, i, &path, &def.groups, &mut used_groups, &mut placing)
                }
                _ => self.objects_of(o, i, &path, &mut placing, None),
            };
            for obj in placed {
                if obj.slot_materials.is_empty() {
                    used_materials[obj.material] = true;
                }
                // A combination's solids name scene materials (a mesh's slots are the
                // file's own, after them).
                if matches!(obj.shape, Shape::Csg(_)) {
                    for &m in &obj.slot_materials {
                        used_materials[m] = true;
                    }
                }
                objects.push(obj);
            }
            if let ObjectDef::Mesh(m) = o
                && m.lights == Some(true)
            {
                lights.extend(self.gltf_object_lights(m, &path));
            }
        }
        for (name, used) in def.groups.keys().zip(&used_groups) {
            if !used {
                self.warnings
                    .push(format!("group `{name}` is defined but no object places it"));
            }
        }
        for ((name, _), used) in named_meshes.iter().zip(&used_meshes) {
            if !used {
                self.warnings
                    .push(format!("mesh `{name}` is defined but no object places it"));
            }
        }
        for (name, used) in material_names.iter().zip(&used_materials) {
            if !used {
                self.warnings.push(format!(
                    "material `{name}` is defined but no object uses it"
                ));
            }
        }
        if objects.is_empty() && self.problems.is_empty() {
            self.warnings
                .push("the scene has no objects: the image will be the background".into());
        }
        for (li, l) in lights.iter().enumerate() {
            if let Some(p) = l.position() {
                for o in objects.iter().filter(|o| o.contains(p)) {
                    let m = &materials[o.material];
                    if !m.is_transparent() {
                        self.warnings.push(format!(
                            "light {li} at {p} is inside object `{}`: nothing outside it will be lit by this light",
                            o.name
                        ));
                    }
                }
            }
        }

        let (area_lights, area_light_of) =
            emitters::area_lights(&objects, &materials, &textures, &mut self.warnings);
        // The radius of the bounded objects' box, for a directional light's power.
        let radius = objects
            .iter()
            .filter_map(|o| o.world_bounds)
            .reduce(|a, b| a.union(&b))
            .map_or(1.0, |b| 0.5 * (b.max - b.min).length());
        let light_sampler = LightSampler::new(&lights, &area_lights, environment.as_ref(), radius);
        let start = std::time::Instant::now();
        let accel = Bvh::build(&objects);
        self.stats.object_bvh_time = start.elapsed();
        let cache = &self.mesh_cache;
        let file_of = |m: &Arc<crate::geometry::Mesh>| {
            cache
                .values()
                .flatten()
                .flatten()
                .find(|l| Arc::ptr_eq(&l.mesh, m))
                .map_or_else(MeshStats::default, |l| MeshStats {
                    file: l.file.clone(),
                    label: l.label.clone(),
                    file_images: l.file_images,
                    ..MeshStats::default()
                })
        };
        let mut stats = std::mem::take(&mut self.stats);
        stats.record_objects(&objects, file_of);
        self.stats = stats;
        self.stats.bvh_bytes += accel.bytes();
        // An object with several materials (a mesh with an MTL file) counts as transparent,
        // or as reading uv (through any texture of any of them), when any of them does.
        let materials_of = |o: &Object| -> Vec<usize> {
            if o.slot_materials.is_empty() {
                vec![o.material]
            } else {
                o.slot_materials.clone()
            }
        };
        // Meshes a normal map reads through their own uv get tangents (MikkTSpace's where the
        // file gave none).
        for o in &objects {
            if let Shape::Mesh(m) = &o.shape
                && materials_of(o).iter().any(|&i| {
                    matches!(materials[i].detail, Some(SurfaceDetail::Normal { texture, .. })
                        if textures[texture].mapping.keeps_uv_axes())
                })
            {
                m.ensure_tangents();
            }
        }
        let cutouts: Vec<bool> = objects
            .iter()
            .map(|o| {
                materials_of(o)
                    .iter()
                    .any(|&m| materials[m].cutout.is_some())
            })
            .collect();
        // Shadow rays look through cut-outs as through glass (their holes, that is).
        let transparent: Vec<bool> = objects
            .iter()
            .zip(&cutouts)
            .map(|(o, &cut)| {
                cut || materials_of(o)
                    .iter()
                    .any(|&m| materials[m].is_transparent())
            })
            .collect();
        let transparent_objects = (0..objects.len()).filter(|&i| transparent[i]).collect();
        // Whether a texture one of object `o`'s materials reads is one `like` says.
        let reads = |o: &Object, like: &dyn Fn(&Texture) -> bool| {
            materials_of(o)
                .iter()
                .any(|&m| materials[m].textures().iter().any(|&t| like(&textures[t])))
        };
        let needs_uv = objects
            .iter()
            .map(|o| {
                reads(o, &|t| {
                    !matches!(t.pattern, Pattern::Solid(_)) && t.mapping.reads_shape_uv()
                })
            })
            .collect();
        let needs_uv1 = objects
            .iter()
            .map(|o| {
                matches!(&o.shape, Shape::Mesh(m) if m.has_second_uv())
                    && reads(o, &|t| matches!(t.mapping, Mapping::SecondUv { .. }))
            })
            .collect();
        let textured = materials
            .iter()
            .map(|m| {
                m.textures()
                    .iter()
                    .any(|&t| !matches!(textures[t].pattern, Pattern::Solid(_)))
            })
            .collect();
        let mut scene = Scene {
            camera,
            settings,
            background,
            environment,
            ambient,
            fog,
            objects,
            materials,
            textures,
            texture_names,
            material_names,
            lights,
            area_lights,
            area_light_of,
            light_sampler,
            warnings: std::mem::take(&mut self.warnings),
            accel,
            transparent,
            transparent_objects,
            needs_uv,
            needs_uv1,
            textured,
            any_cutout: cutouts.contains(&true),
            cutouts,
            stats: std::mem::take(&mut self.stats),
            limits: self.limits,
            files: vec![],
            animation: None,
            source: "".into(),
            frame: 0,
        };
        scene.warnings.extend(scene.lighting_warning());
        scene
    }

    fn settings(
        &mut self,
        d: &ImageDef,
        integrator: &IntegratorDef,
        path: &DocPath,
    ) -> RenderSettings {
        if let Err(e) = RenderSettings::check_side("width", d.width) {
            self.error(path.key("width"), e);
        }
        if let Err(e) = RenderSettings::check_side("height", d.height) {
            self.error(path.key("height"), e);
        }
        let limits = self.limits;
        for (key, check) in [
            ("width", limits.check_pixels(d.width, d.height)),
            (
                "samples",
                limits.check_spp(d.samples, integrator.kind == IntegratorKind::Whitted),
            ),
            ("max_depth", limits.check_depth(d.max_depth)),
        ] {
            if let Err((e, help)) = check {
                self.problems.push(Problem {
                    help,
                    ..Problem::new(path.key(key), e)
                });
            }
        }
        let fpath = path.key("filter");
        let radius = d.filter.radius.map(|r| {
            let r = self.positive(r, &fpath.key("radius"));
            if r > 8.0 {
                self.error(
                    fpath.key("radius"),
                    format!("must be at most 8 pixels, not {r}"),
                );
            }
            r
        });
        RenderSettings {
            width: d.width,
            height: d.height,
            spp: d.samples,
            max_depth: d.max_depth,
            seed: d.seed,
            filter: Filter::new(d.filter.kind, radius),
            integrator: self.integrator(integrator),
            tone: crate::output::tone::Tone {
                exposure: self.exposure(d.exposure, &path.key("exposure")),
                curve: d.tonemap,
            },
            filter_textures: d.filter_textures,
        }
    }

    /// An exposure in stops, within what a picture can use (2^±20 is a millionfold).
    fn exposure(&mut self, x: f32, path: &DocPath) -> f32 {
        self.in_range(x, -20.0, 20.0, path)
    }

    fn integrator(&mut self, d: &IntegratorDef) -> IntegratorSettings {
        let path = DocPath::default().key("integrator");
        if d.rr_depth == 0 {
            self.error(
                path.key("rr_depth"),
                "must be 1 or more (the camera ray is depth 1)",
            );
        }
        IntegratorSettings {
            kind: d.kind,
            sampler: match d.sampler {
                SamplerDef::Sobol => SamplerKind::Sobol,
                SamplerDef::Independent => SamplerKind::Independent,
            },
            rr_depth: d.rr_depth.max(1),
            clamp: d.clamp.map(|c| self.positive(c, &path.key("clamp"))),
        }
    }

    fn fog(&mut self, d: &FogDef, path: &DocPath) -> Fog {
        let color = self.color(d.color, &path.key("color"));
        match d.mode {
            FogMode::Linear => {
                let start = self.non_negative(d.start, &path.key("start"));
                let Some(end) = d.end else {
                    self.error_help(
                        path.clone(),
                        "linear fog needs `end`",
                        "add `end = DISTANCE` where the fog becomes complete",
                    );
                    return Fog::Linear {
                        color,
                        start,
                        end: start + 1.0,
                    };
                };
                let end = self.finite(end, &path.key("end"));
                if end <= start {
                    self.error(
                        path.key("end"),
                        format!("must be greater than start ({start}), not {end}"),
                    );
                }
                if d.density.is_some() {
                    self.error_help(
                        path.key("density"),
                        "density belongs to exponential fog",
                        "use mode = \"exponential\" or remove density",
                    );
                }
                Fog::Linear {
                    color,
                    start,
                    end: end.max(start + 1e-3),
                }
            }
            FogMode::Exponential => {
                let density = match d.density {
                    Some(x) => self.positive(x, &path.key("density")),
                    None => {
                        self.error_help(
                            path.clone(),
                            "exponential fog needs `density`",
                            "add `density = 0.01` (per scene unit)",
                        );
                        1.0
                    }
                };
                if d.end.is_some() {
                    self.error_help(
                        path.key("end"),
                        "end belongs to linear fog",
                        "use mode = \"linear\" or remove end",
                    );
                }
                let start = self.non_negative(d.start, &path.key("start"));
                Fog::Exponential {
                    color,
                    start,
                    density,
                }
            }
        }
    }

    fn mapping(&mut self, d: &MappingDef, path: &DocPath) -> Mapping {
        match d {
            MappingDef::Uv {} => Mapping::Uv,
            MappingDef::Spherical { center, rotate } => {
                let center = center.map(|c| self.point(c, &path.key("center")));
                let r = self.point(*rotate, &path.key("rotate"));
                let rotation = (r != Vec3A::ZERO).then(|| Transform::rotation(Vec3::from(r)));
                Mapping::Spherical { center, rotation }
            }
            MappingDef::Cylindrical {
                center,
                axis,
                height,
            } => Mapping::Cylindrical {
                center: center.map(|c| self.point(c, &path.key("center"))),
                frame: Frame::from_axis(self.direction(*axis, &path.key("axis"))),
                height: self.positive(*height, &path.key("height")),
            },
            MappingDef::Planar { origin, u, v } => {
                let origin = self.point(*origin, &path.key("origin"));
                let u_axis = self.point(*u, &path.key("u"));
                let v_axis = self.point(*v, &path.key("v"));
                if u_axis.cross(v_axis).length_squared() == 0.0 {
                    self.error(
                        path.key("v"),
                        "the u and v axes must be non-zero and not parallel",
                    );
                }
                Mapping::planar(origin, u_axis, v_axis)
            }
        }
    }

    /// A texture; `data` says a material reads it as a normal or bump map, which an image
    /// without a `color_space` is then read as (linear).
    fn texture(&mut self, d: &TextureDef, path: &DocPath, data: bool) -> Texture {
        match d {
            TextureDef::Solid { color } => Texture::solid(self.color(*color, &path.key("color"))),
            TextureDef::Image {
                file,
                color_space,
                wrap,
                mapping,
            } => {
                let mapping = self.mapping(mapping, &path.key("mapping"));
                let full = self.base_dir.join(file);
                self.files.push(full.clone());
                let space = match color_space {
                    Some(ColorSpaceDef::Srgb) => ColorSpace::Srgb,
                    Some(ColorSpaceDef::Linear) => ColorSpace::Linear,
                    None if data => ColorSpace::Linear,
                    None => ColorSpace::Srgb,
                };
                let pattern = match self.image(&full, space, true) {
                    Ok(img) => Pattern::Image(img),
                    Err(e) => {
                        self.error_help(
                            path.key("file"),
                            format!("cannot load texture: {e}"),
                            "paths are relative to the scene file's folder; PNG, JPEG, BMP and OpenEXR are supported",
                        );
                        Pattern::Solid(Color::ONE)
                    }
                };
                let wrap = match wrap {
                    WrapDef::Repeat => Wrap::Repeat,
                    WrapDef::Clamp => Wrap::Clamp,
                    WrapDef::Mirror => Wrap::Mirror,
                };
                Texture {
                    pattern,
                    mapping,
                    wrap: Wraps::both(wrap),
                }
            }
            TextureDef::Checker {
                even,
                odd,
                size,
                mapping,
            } => Texture {
                pattern: Pattern::Checker {
                    even: self.color(*even, &path.key("even")),
                    odd: self.color(*odd, &path.key("odd")),
                    size: self.positive(*size, &path.key("size")),
                },
                mapping: self.mapping(mapping, &path.key("mapping")),
                wrap: Wraps::REPEAT,
            },
            TextureDef::Stripes {
                a,
                b,
                width,
                mapping,
            } => Texture {
                pattern: Pattern::Stripes {
                    a: self.color(*a, &path.key("a")),
                    b: self.color(*b, &path.key("b")),
                    width: self.positive(*width, &path.key("width")),
                },
                mapping: self.mapping(mapping, &path.key("mapping")),
                wrap: Wraps::REPEAT,
            },
        }
    }

    fn light(&mut self, d: &LightDef, path: &DocPath) -> Light {
        match d {
            LightDef::Point {
                position,
                falloff,
                color,
                intensity,
                ..
            } => Light::Point {
                position: self.point(*position, &path.key("position")),
                color: self.color(*color, &path.key("color"))
                    * self.non_negative(*intensity, &path.key("intensity")),
                falloff: *falloff,
            },
            LightDef::Directional {
                direction,
                color,
                intensity,
                ..
            } => Light::Directional {
                direction: self.direction(*direction, &path.key("direction")),
                color: self.color(*color, &path.key("color"))
                    * self.non_negative(*intensity, &path.key("intensity")),
            },
            LightDef::Spot {
                position,
                falloff,
                look_at,
                direction,
                color,
                intensity,
                angle,
                soft_edge,
                ..
            } => {
                let position = self.point(*position, &path.key("position"));
                let direction = match (look_at, direction) {
                    (Some(_), Some(_)) => {
                        self.error_help(
                            path.key("direction"),
                            "a spot light takes `look_at` or `direction`, not both",
                            "remove one of them",
                        );
                        -Vec3A::Y
                    }
                    (None, None) => {
                        self.error_help(
                            path.clone(),
                            "a spot light needs `look_at` or `direction`",
                            "add `look_at = [x, y, z]`, the point the cone is aimed at",
                        );
                        -Vec3A::Y
                    }
                    (Some(l), None) => {
                        let target = self.point(*l, &path.key("look_at"));
                        let d = target - position;
                        if d.length_squared() == 0.0 {
                            self.error(
                                path.key("look_at"),
                                "the spot light looks at its own position",
                            );
                            -Vec3A::Y
                        } else {
                            d.normalize()
                        }
                    }
                    (None, Some(d)) => self.direction(*d, &path.key("direction")),
                };
                let angle = self.finite(*angle, &path.key("angle"));
                if !(angle > 0.0 && angle < 180.0) {
                    self.error(path.key("angle"), format!("the cone's half-angle must be between 0 and 180 degrees (exclusive), not {angle}"));
                }
                let soft = self.in_range(*soft_edge, 0.0, angle.max(0.0), &path.key("soft_edge"));
                Light::Spot {
                    position,
                    direction,
                    color: self.color(*color, &path.key("color"))
                        * self.non_negative(*intensity, &path.key("intensity")),
                    cos_outer: angle.to_radians().cos(),
                    cos_inner: (angle - soft).to_radians().cos(),
                    falloff: *falloff,
                }
            }
        }
    }

    fn object(
        &mut self,
        d: &ObjectDef,
        index: usize,
        path: &DocPath,
        material_names: &[String],
        mesh: Option<LoadedMesh>,
        placement: Option<&Placement>,
    ) -> Option<Object> {
        let (name, material, transform) = d.common();
        let mut slot_materials = vec![];
        let material = match (material, &mesh) {
            (None, Some(m)) if !m.slot_materials.is_empty() => {
                slot_materials = m.slot_materials.clone();
                Some(slot_materials[0])
            }
            (None, Some(m)) if !m.unread_mtl.is_empty() => {
                self.error_help(
                    path.clone(),
                    format!(
                        "the mesh file's materials could not be read (MTL file {}), so the object needs a `material`",
                        m.unread_mtl.join(", MTL file ")
                    ),
                    "put the MTL file where the OBJ file's `mtllib` says (relative to the OBJ file), or add material = \"NAME\"",
                );
                None
            }
            (None, Some(_)) => {
                self.error_help(
                    path.clone(),
                    "the mesh file names no materials, so the object needs a `material`",
                    "add material = \"NAME\", or give the OBJ file an MTL file with `mtllib`",
                );
                None
            }
            (None, None) => match placement.and_then(|p| p.material.as_ref()) {
                Some((name, at)) => self.material_named(name, at, material_names),
                None => {
                    self.error_help(
                        path.clone(),
                        "the object has no `material`",
                        "add material = \"NAME\" naming one of [materials]",
                    );
                    None
                }
            },
            (Some(material), _) => {
                self.material_named(material, &path.key("material"), material_names)
            }
        };
        let transform = transform
            .as_ref()
            .and_then(|t| self.transform(t, &path.key("transform")));
        // A glTF node's placement comes first, then the object's, then its group's.
        let (transform, part) = match &mesh {
            Some(LoadedMesh {
                node: Some(node),
                part,
                ..
            }) => (
                Some(transform.map_or(*node, |t| node.then(&t))),
                part.clone(),
            ),
            _ => (transform, None),
        };
        let transform = match (transform, placement.and_then(|p| p.transform)) {
            (Some(a), Some(b)) => Some(a.then(&b)),
            (a, b) => a.or(b),
        };
        let shape = match (mesh, d) {
            (Some(m), _) => Shape::Mesh(m.mesh),
            (None, ObjectDef::Csg(c)) => {
                let (csg, leaf_materials) = self.csg(c, path)?;
                // Solids with a material of their own: every solid gets a slot.
                if leaf_materials.iter().any(Option::is_some) {
                    let mut slots = vec![];
                    for m in leaf_materials {
                        slots.push(match m {
                            None => material?,
                            Some((name, at)) => self.material_named(&name, &at, material_names)?,
                        });
                    }
                    slot_materials = slots;
                }
                Shape::Csg(std::sync::Arc::new(csg))
            }
            (None, _) => self.shape(d, path)?,
        };
        let name = name
            .clone()
            .unwrap_or_else(|| format!("{} #{index}", shape.kind()));
        let name = match part {
            Some(part) => format!("{name}/{part}"),
            None => name,
        };
        let name = match placement {
            Some(p) => format!("{}/{name}", p.name),
            None => name,
        };
        let local_bounds = shape.bounds();
        let world_bounds = local_bounds.map(|b| match &transform {
            Some(t) => t.bounds_to_world(&b),
            None => b,
        });
        let uv_scale = match d.uv_scale() {
            None => crate::math::Vec2::ONE,
            Some(s) => {
                let at = path.key("uv_scale");
                let u = self.finite(s.0[0], &at);
                let v = self.finite(s.0[1], &at);
                if u == 0.0 || v == 0.0 {
                    self.error_help(
                        at,
                        "a uv scale of 0 shows one texel over the whole object",
                        "use a non-zero factor (negative ones mirror)",
                    );
                }
                crate::math::Vec2::new(u, v)
            }
        };
        Some(Object {
            name,
            uv_scale,
            center: local_bounds.map_or(Vec3A::ZERO, |b| b.center()),
            shape,
            transform,
            material: material?,
            slot_materials,
            world_bounds,
        })
    }

    /// The index of the material `name`, or an error at `at` suggesting one.
    fn material_named(
        &mut self,
        name: &str,
        at: &DocPath,
        material_names: &[String],
    ) -> Option<usize> {
        if let Some(i) = material_names.iter().position(|m| m == name) {
            return Some(i);
        }
        let help = name_help(
            name,
            material_names.iter().map(String::as_str),
            "defined materials",
            "define it under [materials.NAME]",
        );
        self.error_help(at.clone(), format!("no material named `{name}`"), help);
        None
    }

    fn transform(&mut self, d: &TransformDef, path: &DocPath) -> Option<Transform> {
        let scale = self.point(d.scale.0, &path.key("scale"));
        let rotate = self.point(d.rotate, &path.key("rotate"));
        let translate = self.point(d.translate, &path.key("translate"));
        if scale.cmpeq(Vec3A::ZERO).any() {
            self.error_help(
                path.key("scale"),
                "a scale of 0 flattens the object to nothing",
                "use a non-zero scale on every axis",
            );
            return None;
        }
        if scale == Vec3A::ONE && rotate == Vec3A::ZERO && translate == Vec3A::ZERO {
            return None;
        }
        Transform::from_srt(scale.into(), rotate.into(), translate.into())
    }

    fn shape(&mut self, d: &ObjectDef, path: &DocPath) -> Option<Shape> {
        let before = self.problems.len();
        let shape = match d {
            ObjectDef::Sphere(s) => Shape::Sphere(Sphere {
                center: self.point(s.center, &path.key("center")),
                radius: self.positive(s.radius, &path.key("radius")),
            }),
            ObjectDef::Plane(s) => Shape::Plane(Plane::new(
                self.point(s.point, &path.key("point")),
                self.direction(s.normal, &path.key("normal")),
            )),
            ObjectDef::Rectangle(s) => {
                let corner = self.point(s.corner, &path.key("corner"));
                let u = self.point(s.edge_u, &path.key("edge_u"));
                let v = self.point(s.edge_v, &path.key("edge_v"));
                match Rect::new(corner, u, v) {
                    Some(r) => Shape::Rect(r),
                    None => {
                        self.error(path.key("edge_v"), "the edges must be non-zero and not parallel (the rectangle has no area)");
                        return None;
                    }
                }
            }
            ObjectDef::Cuboid(s) => {
                let min = self.point(s.min, &path.key("min"));
                let max = self.point(s.max, &path.key("max"));
                if min.cmpge(max).any() {
                    self.error_help(
                        path.key("max"),
                        format!(
                            "max {:?} must be greater than min {:?} on every axis",
                            s.max, s.min
                        ),
                        "min is the smallest corner, max the largest",
                    );
                }
                Shape::Cuboid(Cuboid { min, max })
            }
            ObjectDef::Cylinder(s) => Shape::Cylinder(Cylinder::new(
                self.point(s.base, &path.key("base")),
                self.direction(s.axis, &path.key("axis")),
                self.positive(s.radius, &path.key("radius")),
                self.positive(s.height, &path.key("height")),
                s.capped,
            )),
            ObjectDef::Cone(s) => Shape::Cone(Cone::new(
                self.point(s.base, &path.key("base")),
                self.direction(s.axis, &path.key("axis")),
                self.positive(s.radius, &path.key("radius")),
                self.positive(s.height, &path.key("height")),
                s.capped,
            )),
            // (An object places a combination with its solids' materials: see `object`.)
            ObjectDef::Csg(c) => Shape::Csg(std::sync::Arc::new(self.csg(c, path)?.0)),
            ObjectDef::Torus(s) => {
                let major = self.positive(s.major_radius, &path.key("major_radius"));
                let minor = self.positive(s.minor_radius, &path.key("minor_radius"));
                if minor >= major {
                    self.error_help(
                        path.key("minor_radius"),
                        format!("must be less than major_radius ({major}), not {minor}"),
                        "a tube as wide as its ring closes the hole (a horn or spindle torus), which snell does not draw",
                    );
                }
                Shape::Torus(Torus::new(
                    self.point(s.center, &path.key("center")),
                    self.direction(s.axis, &path.key("axis")),
                    major,
                    minor,
                ))
            }
            ObjectDef::Disk(s) => Shape::Disk(Disk::new(
                self.point(s.center, &path.key("center")),
                self.direction(s.normal, &path.key("normal")),
                self.positive(s.radius, &path.key("radius")),
            )),
            ObjectDef::Triangle(s) => {
                let vp = path.key("vertices");
                let [a, b, c] = [0, 1, 2].map(|i| self.point(s.vertices[i], &vp.index(i)));
                match Triangle::new(a, b, c) {
                    Some(t) => Shape::Triangle(t),
                    None => {
                        self.error(vp, "the triangle has no area (its corners are on one line)");
                        return None;
                    }
                }
            }
            // Meshes are resolved (loaded or found in the cache) before this is called.
            ObjectDef::Mesh(_) | ObjectDef::Group(_) => return None,
        };
        (self.problems.len() == before).then_some(shape)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn errors(text: &str) -> String {
        match load_str(text, Path::new("t.toml"), Path::new("."), Format::Toml) {
            Ok(_) => panic!("expected an error"),
            Err(e) => e.to_string(),
        }
    }

    const CAMERA: &str = "[camera]\nlook_at = [0, 0, -1]\n[materials.m]\ncolor = 1\n";

    #[test]
    fn unknown_key_points_at_the_key_with_a_suggestion() {
        let e = errors(&format!(
            "{CAMERA}[[objects]]\ntype = \"sphere\"\nmaterial = \"m\"\nradus = 2\n"
        ));
        assert!(
            e.contains("t.toml:8:1: objects[0].radus: unknown key `radus`"),
            "{e}"
        );
        assert!(e.contains("did you mean `radius`?"), "{e}");
    }

    #[test]
    fn impossible_values_are_all_reported() {
        let e = errors(&format!(
            "{CAMERA}[[objects]]\ntype = \"sphere\"\nmaterial = \"m\"\nradius = -1\n[[objects]]\ntype = \"cylinder\"\nmaterial = \"m\"\naxis = [0, 0, 0]\nradius = 1\nheight = 2\n"
        ));
        assert!(
            e.contains("t.toml:8:10: objects[0].radius: must be greater than 0, not -1"),
            "{e}"
        );
        assert!(
            e.contains("t.toml:12:8: objects[1].axis: must not be the zero vector"),
            "{e}"
        );
    }

    #[test]
    fn missing_material_suggests_a_name() {
        let e = errors(&format!(
            "{CAMERA}[[objects]]\ntype = \"sphere\"\nmaterial = \"n\"\nradius = 1\n"
        ));
        assert!(
            e.contains("no material named `n`") && e.contains("did you mean `m`?"),
            "{e}"
        );
    }

    #[test]
    fn wrong_type_and_unknown_shape() {
        let e = errors(&format!(
            "{CAMERA}[[objects]]\ntype = \"sphere\"\nmaterial = \"m\"\nradius = \"big\"\n"
        ));
        assert!(
            e.contains("t.toml:8:10") && e.contains("expected a number"),
            "{e}"
        );
        let e = errors(&format!(
            "{CAMERA}[[objects]]\ntype = \"spere\"\nmaterial = \"m\"\n"
        ));
        assert!(
            e.contains("unknown type `spere`") && e.contains("did you mean `sphere`?"),
            "{e}"
        );
    }

    #[test]
    fn fov_out_of_range_and_toml_syntax() {
        let e = errors("[camera]\nlook_at = [0, 0, -1]\nfov = 180\n");
        assert!(
            e.contains("t.toml:3:7: camera.fov: field of view must be between 0 and 180"),
            "{e}"
        );
        let e = errors("[camera]\nlook_at = [0, 0, -1\n");
        assert!(e.contains("t.toml:2:") && e.contains("TOML syntax"), "{e}");
    }

    #[test]
    fn json_uses_the_same_types_and_locates_errors() {
        let json = "{\n  \"camera\": {\"look_at\": [0, 0, -1]},\n  \"materials\": {\"m\": {\"color\": 1}},\n  \"objects\": [{\"type\": \"sphere\", \"material\": \"m\", \"radius\": 0}]\n}\n";
        let e = load_str(json, Path::new("t.json"), Path::new("."), Format::Json)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("t.json:4:") && e.contains("objects[0].radius: must be greater than 0"),
            "{e}"
        );
        let ok = json.replace("\"radius\": 0", "\"radius\": 2");
        let s = load_str(&ok, Path::new("t.json"), Path::new("."), Format::Json).unwrap();
        assert_eq!(s.objects.len(), 1);
        let e = load_str(
            "{\"camera\": {\"look_at\": [0,0,-1]}, }",
            Path::new("t.json"),
            Path::new("."),
            Format::Json,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("t.json:1:") && e.contains("JSON syntax"), "{e}");
    }

    /// docs/scene-format.md names the keys where JSON's `null` means "not given" and those
    /// (with a default) where it is refused; this holds the parser to that list.
    #[test]
    fn json_null_is_taken_for_keys_without_a_default_only() {
        let scene = |camera: &str, object: &str| {
            format!(
                "{{\"$schema\": null, \"image\": {{\"width\": 8, \"height\": 6, \"filter\": {{\"type\": \"box\", \"radius\": null}}}}, \"camera\": {{\"look_at\": [0,0,-1]{camera}}}, \"fog\": null, \"materials\": {{\"m\": {{\"color\": null, \"texture\": null}}}}, \"objects\": [{{\"type\": \"sphere\", \"center\": [0,0,-3], \"radius\": 1, \"material\": \"m\", \"name\": null, \"transform\": null{object}}}]}}"
            )
        };
        let load = |text: &str| load_str(text, Path::new("t.json"), Path::new("."), Format::Json);
        assert!(load(&scene("", "")).is_ok());
        let fog = scene("", "").replace(
            "\"fog\": null",
            "\"fog\": {\"mode\": \"exponential\", \"end\": null, \"density\": 0.1}",
        );
        assert!(load(&fog).is_ok(), "{:?}", load(&fog).err());
        for (camera, object, key) in [
            (", \"up\": null", "", "camera.up"),
            (", \"aperture\": null", "", "camera.aperture"),
            (", \"position\": null", "", "camera.position"),
        ] {
            let e = load(&scene(camera, object)).unwrap_err().to_string();
            assert!(
                e.contains(&format!("{key}: invalid type: null")),
                "{key}: {e}"
            );
        }
    }
}
