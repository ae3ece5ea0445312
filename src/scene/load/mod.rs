//! From a scene file to a [`Scene`]: parse, check every value, resolve names and paths, load
//! textures. Problems are collected (not just the first) and located in the text. This file
//! holds the entry points and the `Builder` every part of the build writes its problems to;
//! the parts are one file each below.

use super::assets::AssetCache;
use super::diag::{DocPath, Format, Problem, SceneError};
use super::meshes::MeshCache;
use super::{BuildStats, Limits, Scene};
use parse::parse;
use std::path::{Path, PathBuf};

pub use crate::math::MAX_MAGNITUDE;
pub use animation::{Animation, MAX_FRAMES};
mod animation;
mod assemble;
pub(super) mod camera;
mod csg;
mod emitters;
mod environment;
mod group;
mod ior;
mod light;
mod lpe;
mod material;
mod object;
mod parse;
mod settings;
mod sky;
mod texture;
mod values;

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
    load_str_with(
        text,
        file,
        base_dir,
        format,
        &Limits::default(),
        frame,
        &mut assets,
    )
}

/// As [`load_str_frame`], checked against `limits` and reusing the images and meshes
/// `assets` kept from earlier builds (a script that edits a scene and renders it again reads
/// its textures once).
pub fn load_str_with(
    text: &str,
    file: &Path,
    base_dir: &Path,
    format: Format,
    limits: &Limits,
    frame: u32,
    assets: &mut AssetCache,
) -> Result<Scene, SceneError> {
    build(text, file, base_dir, format, limits, frame, assets)
}

/// Parses `text` and builds its scene at `frame`: the one path every entry point takes, so
/// a file and a string report the same problems in the same words.
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

/// The state of one build of a scene: the problems found so far (all reported together at
/// the end), warnings, and what it has loaded. Each part of the file is built by a method of
/// its own, in the file for that part.
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
}

#[cfg(test)]
mod tests;
