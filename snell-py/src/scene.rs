//! Scenes built from files or text, and the images and meshes kept between builds.

use crate::errors;
use pyo3::prelude::*;
use snell::scene::{AssetCache, Format, Limits};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// A built scene, ready to render (immutable: a changed scene is built again).
#[pyclass(frozen, module = "snell._snell")]
pub struct NativeScene {
    /// Boxed: a scene holds 32-byte-aligned nodes, and Python allocates its objects at
    /// 16-byte alignment, so the scene cannot live inside the Python object itself.
    pub scene: Box<snell::Scene>,
    /// The file it names itself by in messages and `explain`.
    pub path: PathBuf,
    pub load_time: Duration,
}

/// The images and meshes earlier builds loaded, by file: a scene built again with the same
/// cache reads no file twice.
#[pyclass(frozen, module = "snell._snell")]
#[derive(Default)]
pub struct Assets(pub Mutex<AssetCache>);

#[pymethods]
impl Assets {
    #[new]
    fn new() -> Self {
        Assets::default()
    }
}

#[pymethods]
impl NativeScene {
    /// Width, height, samples per pixel, seed, integrator and maximum depth, as the scene
    /// file sets them.
    #[getter]
    fn settings(&self) -> (u32, u32, u32, u64, &'static str, u32) {
        let s = &self.scene.settings;
        (
            s.width,
            s.height,
            s.spp,
            s.seed,
            integrator_name(s.integrator.kind),
            s.max_depth,
        )
    }

    /// The exposure (stops) and tone curve its PNGs are written with.
    #[getter]
    fn tone(&self) -> (f32, &'static str) {
        let t = &self.scene.settings.tone;
        (t.exposure, t.curve.name())
    }

    /// The scene file (or the name given to text).
    #[getter]
    fn path(&self) -> String {
        self.path.display().to_string()
    }

    /// The text the scene was built from.
    #[getter]
    fn source(&self) -> &str {
        &self.scene.source
    }

    /// What the build warned of.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.scene.warnings.clone()
    }

    /// The files the build read (textures, meshes).
    #[getter]
    fn files(&self) -> Vec<String> {
        self.scene
            .files
            .iter()
            .map(|f| f.display().to_string())
            .collect()
    }

    /// The frame of the animation it was built at (0 for a still), and the animation's
    /// frames (1 for a still).
    #[getter]
    fn frame(&self) -> (u32, u32) {
        let frames = self.scene.animation.as_ref().map_or(1, |a| a.frames);
        (self.scene.frame, frames)
    }

    /// Seconds the build took.
    #[getter]
    fn load_seconds(&self) -> f64 {
        self.load_time.as_secs_f64()
    }

    /// `snell check`'s summary of the scene.
    fn summary(&self) -> String {
        self.scene.summary()
    }
}

/// The name `--integrator` takes for `kind`.
pub fn integrator_name(kind: snell::scene::IntegratorKind) -> &'static str {
    match kind {
        snell::scene::IntegratorKind::Whitted => "whitted",
        snell::scene::IntegratorKind::Path => "path",
        snell::scene::IntegratorKind::Light => "light",
        snell::scene::IntegratorKind::Bdpt => "bdpt",
    }
}

fn build(
    py: Python<'_>,
    path: PathBuf,
    assets: Option<&Assets>,
    make: impl FnOnce(&mut AssetCache) -> Result<snell::Scene, snell::scene::SceneError> + Send,
) -> PyResult<NativeScene> {
    let start = Instant::now();
    let scene = py.detach(|| match assets {
        Some(a) => {
            let mut cache = a.0.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
            make(&mut cache)
        }
        None => make(&mut AssetCache::default()),
    });
    let scene = scene.map_err(|e| errors::SceneError::new_err(e.to_string()))?;
    Ok(NativeScene {
        scene: Box::new(scene),
        path,
        load_time: start.elapsed(),
    })
}

/// Reads, checks and builds the scene file `path` (`.toml` or `.json`), at `frame` of its
/// animation.
#[pyfunction]
#[pyo3(signature = (path, assets=None, frame=0))]
pub fn load(
    py: Python<'_>,
    path: PathBuf,
    assets: Option<&Assets>,
    frame: u32,
) -> PyResult<NativeScene> {
    let file = path.clone();
    build(py, path, assets, move |cache| {
        snell::scene::load_frame(&file, &Limits::default(), frame, cache)
    })
}

/// Builds a scene from `text` in `format` (`"toml"` or `"json"`), named `name` in
/// messages, its relative paths resolved against `base_dir`, at `frame` of its animation.
#[pyfunction]
#[pyo3(signature = (text, format, name, base_dir, assets=None, frame=0))]
pub fn loads(
    py: Python<'_>,
    text: String,
    format: &str,
    name: PathBuf,
    base_dir: PathBuf,
    assets: Option<&Assets>,
    frame: u32,
) -> PyResult<NativeScene> {
    let format = match format.to_ascii_lowercase().as_str() {
        "toml" => Format::Toml,
        "json" => Format::Json,
        other => {
            return Err(errors::value(format!(
                "format must be \"toml\" or \"json\", not {other:?}"
            )));
        }
    };
    let file = name.clone();
    build(py, name, assets, move |cache| {
        snell::scene::load_str_with(
            &text,
            &file,
            Path::new(&base_dir),
            format,
            &Limits::default(),
            frame,
            cache,
        )
    })
}
