//! Rendering from Python: the command line's job (overrides checked, the scene's integrator,
//! the same pixels), run with the interpreter's lock released, while the calling thread
//! reports progress and listens for Ctrl-C.

use crate::errors;
use crate::images::{channels_array, image_array};
use crate::scene::NativeScene;
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError};
use pyo3::prelude::*;
use pyo3::types::{IntoPyDict, PyDict};
use snell::integrator::aov::Aov;
use snell::job::{Overrides, RenderJob};
use snell::render::render_aovs;
use snell::render::to_files::{Finished, JobProgress, RunOptions, run};
use snell::scene::{IntegratorKind, Limits};
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// How often the waiting thread takes the lock to report progress and check for Ctrl-C.
const POLL: Duration = Duration::from_millis(100);

fn integrator(name: &str) -> PyResult<IntegratorKind> {
    match name.to_ascii_lowercase().as_str() {
        "whitted" => Ok(IntegratorKind::Whitted),
        "path" => Ok(IntegratorKind::Path),
        "light" => Ok(IntegratorKind::Light),
        "bdpt" => Ok(IntegratorKind::Bdpt),
        other => Err(errors::value(format!(
            "integrator must be \"whitted\", \"path\", \"light\" or \"bdpt\", not {other:?}"
        ))),
    }
}

/// The scene with the caller's settings, checked as `snell render` checks its flags.
fn job(
    scene: &NativeScene,
    spp: Option<u32>,
    seed: Option<u64>,
    width: Option<u32>,
    height: Option<u32>,
    integrator_name: Option<&str>,
    noise: Option<f32>,
) -> PyResult<RenderJob> {
    let overrides = Overrides {
        width,
        height,
        spp,
        seed,
        integrator: integrator_name.map(integrator).transpose()?,
        noise,
        ..Overrides::default()
    };
    RenderJob::from_scene(
        (*scene.scene).clone(),
        &scene.path,
        &overrides,
        &Limits::default(),
        None,
        scene.scene.frame,
        scene.load_time,
    )
    .map_err(errors::job)
}

/// Renders `scene` and returns a dict: `image` (float32, height x width x 3, linear),
/// `complete`, `spp` (samples per pixel taken), `interrupted` (Ctrl-C stopped it),
/// `aovs` (name to float32 array, height x width x channels), `lpe` (each light path
/// expression's name to its float32 image: the scene's own and `lpe`'s), `seconds`, `rays`.
/// `noise`: adaptive sampling's threshold (the scene's `[image] noise` otherwise).
/// `denoise`: also `denoised`, the picture denoised by Open Image Denoise (a build with the
/// `denoise` feature; otherwise a `SettingsError` saying how to get one, before rendering).
#[pyfunction]
#[pyo3(signature = (scene, spp=None, seed=None, width=None, height=None, integrator=None, time=None, threads=None, aovs=None, progress=None, lpe=None, noise=None, denoise=false))]
#[allow(clippy::too_many_arguments)]
pub fn render<'py>(
    py: Python<'py>,
    scene: &NativeScene,
    spp: Option<u32>,
    seed: Option<u64>,
    width: Option<u32>,
    height: Option<u32>,
    integrator: Option<&str>,
    time: Option<f64>,
    threads: Option<usize>,
    aovs: Option<Vec<String>>,
    progress: Option<Py<PyAny>>,
    lpe: Option<Vec<String>>,
    noise: Option<f32>,
    denoise: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let job = job(scene, spp, seed, width, height, integrator, noise)?;
    if denoise {
        match snell::denoise::ready() {
            Ok(()) => {}
            Err(e @ snell::denoise::DenoiseError::NotBuilt) => {
                return Err(errors::settings(e.to_string()));
            }
            Err(e) => return Err(PyRuntimeError::new_err(e.to_string())),
        }
    }
    let views = aovs
        .unwrap_or_default()
        .iter()
        .map(|name| {
            Aov::from_name(name).ok_or_else(|| {
                let known: Vec<&str> = Aov::ALL.iter().map(|a| a.name()).collect();
                errors::value(format!(
                    "no debug view {name:?}; the views are {}",
                    known.join(", ")
                ))
            })
        })
        .collect::<PyResult<Vec<Aov>>>()?;
    let requests = lpe
        .unwrap_or_default()
        .iter()
        .map(|a| snell::lpe::request(a).map_err(errors::settings))
        .collect::<PyResult<Vec<_>>>()?;
    // Checked here, before the render, as `snell render` checks its flags.
    let taken: Vec<&str> = views.iter().map(|a| a.name()).collect();
    if let Err(e) = snell::lpe::for_render(&job.scene, &requests, &taken) {
        return Err(errors::settings(format!("{e} (help: {})", e.help())));
    }
    let s = &job.scene.settings;
    if let Some(a) = views.iter().find(|a| a.from_film())
        && s.integrator.kind != IntegratorKind::Path
    {
        return Err(errors::value(format!(
            "the {} view is the path tracer's: Whitted's samples are fixed strata",
            a.name()
        )));
    }
    let time = match time {
        Some(t) if !(t.is_finite() && t > 0.0) => {
            return Err(errors::value(format!(
                "time must be a positive number of seconds, not {t}"
            )));
        }
        t => t.map(Duration::from_secs_f64),
    };
    if threads == Some(0) {
        return Err(errors::value("threads must be at least 1"));
    }
    let total = s.width as u64 * s.height as u64 * s.spp as u64;
    let start = Instant::now();
    let run = Run {
        job: &job,
        threads,
        time,
        lpe: &requests,
    };
    let (finished, stopped_by) = run_waiting(py, &run, total, progress.as_ref());
    let finished = finished?;
    let interrupted = match stopped_by {
        Some(e) if e.is_instance_of::<PyKeyboardInterrupt>(py) => true,
        Some(e) => return Err(e),
        None => false,
    };
    let seconds = start.elapsed().as_secs_f64();
    let out = PyDict::new(py);
    let (w, h) = (s.width as usize, s.height as usize);
    out.set_item("image", image_array(py, &finished.image))?;
    out.set_item("complete", finished.complete)?;
    out.set_item("spp", finished.spp)?;
    out.set_item("interrupted", interrupted)?;
    out.set_item("seconds", seconds)?;
    let r = &finished.rays;
    out.set_item(
        "rays",
        [
            ("camera", r.camera),
            ("secondary", r.secondary),
            ("shadow", r.shadow),
        ]
        .into_py_dict(py)?,
    )?;
    let views_out = PyDict::new(py);
    if !views.is_empty() && !interrupted {
        let scene = &job.scene;
        let buffers = py.detach(|| {
            let mut b = render_aovs(scene, threads);
            if let (Ok(b), Some(film)) = (&mut b, &finished.film) {
                b.read_film(film);
            }
            b
        });
        let buffers = buffers.map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        for a in views {
            views_out.set_item(a.name(), channels_array(py, &buffers.channels(a), w, h)?)?;
        }
    }
    out.set_item("aovs", views_out)?;
    let layers = PyDict::new(py);
    for (name, img) in &finished.layers {
        layers.set_item(name, image_array(py, img))?;
    }
    out.set_item("lpe", layers)?;
    if denoise && !interrupted {
        let options = snell::render::RenderOptions {
            threads,
            progress: &|_| {},
            cancel: None,
            region: None,
        };
        let denoised = py.detach(|| {
            snell::denoise::guides(&job.scene, finished.spp, &options)
                .map_err(|e| e.to_string())
                .and_then(|g| {
                    snell::denoise::denoise(&finished.image, &g).map_err(|e| e.to_string())
                })
        });
        let denoised = denoised.map_err(PyRuntimeError::new_err)?;
        out.set_item("denoised", image_array(py, &denoised))?;
    }
    Ok(out)
}

/// What a render runs: the job, its threads, its time limit and its extra light path
/// expressions.
#[derive(Clone, Copy)]
struct Run<'a> {
    job: &'a RenderJob,
    threads: Option<usize>,
    time: Option<Duration>,
    lpe: &'a [snell::lpe::Request],
}

/// Runs `job` on other threads while this one, every [`POLL`], takes the interpreter's
/// lock to call `progress(done, total)` and to check for signals. A signal's exception (or
/// the callback's) stops the render, keeping what is done, and is returned beside it.
fn run_waiting(
    py: Python<'_>,
    run_: &Run,
    total: u64,
    progress: Option<&Py<PyAny>>,
) -> (PyResult<Finished>, Option<PyErr>) {
    let Run {
        job,
        threads,
        time,
        lpe,
    } = *run_;
    let cancel = AtomicBool::new(false);
    let done = AtomicU64::new(0);
    let mut stopped_by: Option<PyErr> = None;
    let report = |stopped_by: &mut Option<PyErr>, n: u64| {
        Python::attach(|py| {
            let checked = py.check_signals().and_then(|()| match progress {
                Some(cb) => cb.call1(py, (n, total)).map(drop),
                None => Ok(()),
            });
            if let Err(e) = checked {
                *stopped_by = Some(e);
                cancel.store(true, Ordering::Relaxed);
            }
        })
    };
    let result = py.detach(|| {
        std::thread::scope(|s| {
            let (tx, rx) = mpsc::channel::<()>();
            let worker = s.spawn(|| {
                let on_progress = |p: JobProgress| done.store(p.done, Ordering::Relaxed);
                let options = RunOptions {
                    threads,
                    progress: &on_progress,
                    cancel: Some(&cancel),
                    time,
                    lpe,
                };
                let r = run(&job.scene, &options);
                drop(tx);
                r
            });
            while let Err(mpsc::RecvTimeoutError::Timeout) = rx.recv_timeout(POLL) {
                if stopped_by.is_none() {
                    report(&mut stopped_by, done.load(Ordering::Relaxed));
                }
            }
            worker.join()
        })
    });
    let result = match result {
        Ok(r) => r.map_err(|e| PyRuntimeError::new_err(e.to_string())),
        Err(_) => Err(PyRuntimeError::new_err("the render thread panicked")),
    };
    if stopped_by.is_none() && result.as_ref().is_ok_and(|f| f.complete) {
        // The last report says all of it, even for a render shorter than one poll.
        report(&mut stopped_by, total);
    }
    (result, stopped_by)
}

/// `snell explain --json`'s document for pixel `(x, y)`, as text: under the path tracer the
/// path of sample `sample` (0 by default; light tracing's scene by the path tracer's path,
/// said so in its `note`), under bdpt that sample's two subpaths and strategies, under
/// Whitted sample `sample` or by default the ray through the pixel's centre, with at most
/// `max_rays` of its tree. A sample past the pixel's last is refused.
#[pyfunction]
#[pyo3(signature = (scene, x, y, sample=None, max_rays=200))]
pub fn explain(
    py: Python<'_>,
    scene: &NativeScene,
    x: u32,
    y: u32,
    sample: Option<u32>,
    max_rays: usize,
) -> PyResult<String> {
    let sc = &scene.scene;
    let (w, h) = (sc.settings.width, sc.settings.height);
    if x >= w || y >= h {
        return Err(errors::value(format!(
            "pixel ({x}, {y}) is outside the {w} x {h} image"
        )));
    }
    if let Some(k) = sample
        && k >= sc.settings.spp
    {
        return Err(errors::value(format!(
            "sample {k} does not exist: the pixel has {} sample(s), 0 to {}",
            sc.settings.spp,
            sc.settings.spp - 1
        )));
    }
    let path: &Path = &scene.path;
    let doc =
        py.detach(|| {
            let mut doc =
                match (sc.settings.integrator.kind, sample) {
                    (IntegratorKind::Whitted, Some(k)) => {
                        let film = snell::render::sample_position(&sc.settings, x, y, k)?;
                        snell::explain_pixel::whitted(sc, film, Some(((x, y), k)), max_rays)?
                            .to_json(sc, path, (x, y), Some(k))
                    }
                    (IntegratorKind::Path | IntegratorKind::Light, Some(k)) => {
                        snell::explain_pixel::path(sc, (x, y), k).to_json(sc, path)
                    }
                    (IntegratorKind::Bdpt, Some(k)) => {
                        snell::explain_pixel::bdpt(sc, (x, y), k).to_json(sc, path)
                    }
                    _ => return snell::explain_pixel::pixel_json(sc, path, (x, y), max_rays),
                };
            snell::explain_pixel::place_on_picture(&mut doc, sc);
            Some(doc)
        });
    let doc = doc.ok_or_else(|| errors::value("nothing was recorded for that pixel"))?;
    Ok(doc.to_string())
}
