//! A prepared job rendered to its files: the one entry point a caller (the command line,
//! a script, the Python module) needs beyond a scene and an output path, with progress and
//! cancellation as callbacks. The scene's integrator decides the way: the path tracer in
//! passes of a film of sums (1, 2, 4 ... samples per pixel, so a cancelled render still
//! has every pixel), Whitted tile by tile. The picture and its debug views are reserved
//! before the render starts (a bad path fails before any work) and written atomically; an
//! unfinished picture goes beside the old one (`x.partial.png`), never over it.

use super::lpe::{LpeRenderError, render_lpe};
use super::progressive::{Ended, PassEvent, SampleCount, Until, film_samples, render_progressive};
use super::{BadSamples, PassError, RenderError, RenderOptions, render_aovs, render_with};
use crate::Scene;
use crate::film::{Film, Image};
use crate::integrator::aov::Aov;
use crate::integrator::{self, RayStats};
use crate::job::RenderJob;
use crate::lpe::{self, RenderLpeError, Request};
use crate::output::{ExrLayer, OutputError, OutputFormat, PendingOutput, encode_exr_layers};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::Duration;

/// How far a render has come: `done` of `total` samples (pixels times samples per pixel).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct JobProgress {
    /// Samples taken.
    pub done: u64,
    /// Samples to take.
    pub total: u64,
}

/// How a job is run.
#[derive(Clone, Copy)]
pub struct RunOptions<'a> {
    /// Render threads; `None` uses every core.
    pub threads: Option<usize>,
    /// Called from the render threads as samples are taken.
    pub progress: &'a (dyn Fn(JobProgress) + Sync),
    /// Set to stop: the path tracer ends its pass early, Whitted skips the tiles not yet
    /// started; what is done is kept.
    pub cancel: Option<&'a AtomicBool>,
    /// For the path tracer and light tracing: stop after the pass that spends this much
    /// time.
    pub time: Option<Duration>,
    /// Light path expressions to render beside the picture, besides the scene's own
    /// (`[[image.lpe]]`; one named like the scene's replaces it). With any, the path
    /// tracer takes every sample of each pixel at once, and `time` is not read.
    pub lpe: &'a [Request],
}

/// What a render came to.
#[derive(Clone, Debug)]
pub struct Finished {
    /// The picture.
    pub image: Image,
    /// The path tracer's film of sums (its variance view reads it); `None` for Whitted.
    pub film: Option<Film>,
    /// Whether the picture is whole (not cancelled; a render stopped by `time` is whole,
    /// with fewer samples).
    pub complete: bool,
    /// Samples per pixel in the picture (the fewest any pixel has).
    pub spp: u32,
    /// The rays traced.
    pub rays: RayStats,
    /// Samples that came out NaN or infinite (left out of their pixels).
    pub bad_samples: BadSamples,
    /// Each light path expression's name and image (linear), in order.
    pub layers: Vec<(String, Image)>,
}

impl Finished {
    /// What a render of every sample of each pixel at once came to (no film of sums kept):
    /// `spp` samples a pixel, and the expressions' images `layers`.
    fn whole(r: super::Rendered, spp: u32, layers: Vec<(String, Image)>) -> Self {
        Finished {
            complete: r.complete(),
            image: r.image,
            film: None,
            spp,
            rays: r.rays,
            bad_samples: r.bad_samples,
            layers,
        }
    }
}

/// Why a job could not be rendered to its files.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The render could not run.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// The path tracer's passes could not run.
    #[error(transparent)]
    Pass(#[from] PassError),
    /// A file could not be reserved or written.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// A debug view this render cannot give.
    #[error("{0}")]
    View(String),
    /// A scene light tracing cannot render.
    #[error(transparent)]
    Light(#[from] super::light::LightTraceError),
    /// A scene bidirectional path tracing cannot render.
    #[error(transparent)]
    Bdpt(#[from] super::bdpt::BdptError),
    /// What adaptive sampling cannot be combined with (yet).
    #[error(
        "adaptive sampling (noise) cannot be combined with {0} (help: render without --noise and [image] noise)"
    )]
    Adaptive(&'static str),
    /// Light path expressions this render cannot give.
    #[error("{error} (help: {help})", help = .0.help(), error = .0)]
    Lpe(#[from] RenderLpeError),
}

/// Renders `scene` as its settings say (see the module's doc).
pub fn run(scene: &Scene, options: &RunOptions) -> Result<Finished, RunError> {
    let s = &scene.settings;
    let integrator = integrator::chosen(s.integrator.kind);
    let pixels = s.width as u64 * s.height as u64;
    let total = pixels * s.spp as u64;
    // Renders that take every sample of a pixel at once (expressions, light tracing,
    // Whitted) report the pixels finished.
    let whole_progress = |n: u64| {
        (options.progress)(JobProgress {
            done: n * s.spp as u64,
            total,
        })
    };
    let whole = RenderOptions {
        threads: options.threads,
        progress: &whole_progress,
        cancel: options.cancel,
        region: None,
    };
    if let Some(set) = lpe::for_render(scene, options.lpe, &[])? {
        if s.noise.is_some() {
            return Err(RunError::Adaptive(
                "light path expressions: their render takes every sample of a pixel at once",
            ));
        }
        let r = render_lpe(scene, &set, &whole).map_err(|e| match e {
            LpeRenderError::Render(e) => RunError::Render(e),
            LpeRenderError::NotPathTracer => RunError::Lpe(RenderLpeError::Whitted),
        })?;
        let names = set.named.iter().map(|n| n.name.clone());
        return Ok(Finished::whole(
            r.rendered,
            s.spp,
            names.zip(r.layers).collect(),
        ));
    }
    if s.integrator.kind == crate::scene::IntegratorKind::Light {
        let r = super::light::render_light_for(scene, &whole, options.time)?;
        return Ok(Finished::whole(r.rendered, r.spp, vec![]));
    }
    if s.integrator.kind == crate::scene::IntegratorKind::Bdpt {
        let r = super::bdpt::render_bdpt_for(scene, &whole, options.time, false)?;
        return Ok(Finished::whole(r.rendered, r.spp, vec![]));
    }
    if !integrator.uses_sampler() {
        let r = render_with(scene, integrator, &whole, None)?;
        return Ok(Finished::whole(r, s.spp, vec![]));
    }
    let count = SampleCount::default();
    let progress = |n: u64| {
        let done = count.after(n);
        (options.progress)(JobProgress {
            done: done.min(total),
            total,
        })
    };
    let render = RenderOptions {
        threads: options.threads,
        progress: &progress,
        cancel: options.cancel,
        region: None,
    };
    let mut film = Film::new(s.width, s.height);
    let until = Until {
        spp: s.spp,
        time: options.time,
        noise: s.noise,
    };
    let done = render_progressive(
        scene,
        integrator,
        &mut film,
        until,
        &render,
        &mut |event, film| {
            if let PassEvent::Start { from, to, .. } = event {
                if s.noise.is_some() {
                    let taken = film.pixels().iter().map(|p| p.samples as u64).sum();
                    count.adaptive_pass(taken, to - from);
                } else {
                    count.pass(pixels, from, to);
                }
            }
        },
    )?;
    Ok(Finished {
        image: film.image(),
        complete: done.ended.unwrap_or(Ended::Cancelled) != Ended::Cancelled,
        spp: film_samples(&film),
        film: Some(film),
        rays: done.rays,
        bad_samples: done.bad_samples,
        layers: vec![],
    })
}

/// A render's files, reserved before it starts: the picture, and its debug views and light
/// path expressions' images as layers of the one EXR or as a PNG each beside the picture
/// ([`Outputs::view_path`], [`Outputs::layer_path`]).
#[derive(Debug)]
pub struct Outputs {
    picture: PendingOutput,
    views: Vec<Aov>,
    pngs: Vec<(Aov, PendingOutput)>,
    /// The expressions' images: name, file where a PNG, and the image once rendered.
    layers: Vec<(String, Option<PendingOutput>, Option<Image>)>,
}

impl Outputs {
    /// Reserves `path` and, for a PNG, a file for each of `views`.
    pub fn reserve(path: &Path, views: &[Aov]) -> Result<Outputs, OutputError> {
        let mut outputs = Outputs {
            picture: PendingOutput::create(path)?,
            views: vec![],
            pngs: vec![],
            layers: vec![],
        };
        outputs.add_views(views)?;
        Ok(outputs)
    }

    /// Adds debug views to the files: for a PNG, a file reserved for each.
    pub fn add_views(&mut self, views: &[Aov]) -> Result<(), OutputError> {
        for &a in views {
            if self.picture.format() == OutputFormat::Png {
                let path = Self::view_path(self.picture.path(), a);
                self.pngs.push((a, PendingOutput::create(&path)?));
            }
            self.views.push(a);
        }
        Ok(())
    }

    /// Adds the images of light path expressions named `names` to the files: for a PNG, a
    /// file reserved for each.
    pub fn add_layers(&mut self, names: &[String]) -> Result<(), OutputError> {
        for name in names {
            let png = if self.picture.format() == OutputFormat::Png {
                Some(PendingOutput::create(&Self::layer_path(
                    self.picture.path(),
                    name,
                ))?)
            } else {
                None
            };
            self.layers.push((name.clone(), png, None));
        }
        Ok(())
    }

    /// Gives up the layer named `name` (its file, if reserved, is not written).
    pub fn drop_layer(&mut self, name: &str) {
        self.layers.retain(|l| l.0 != name);
    }

    /// Gives the expressions' images, in the order of [`Outputs::add_layers`].
    pub fn set_layer_images(&mut self, images: Vec<Image>) {
        for (layer, image) in self.layers.iter_mut().zip(images) {
            layer.2 = Some(image);
        }
    }

    /// Where a PNG's light path expression named `name` goes: `out.direct.png`.
    pub fn layer_path(out: &Path, name: &str) -> PathBuf {
        let mut file = out.file_stem().unwrap_or_default().to_os_string();
        file.push(format!(".{name}."));
        file.push(out.extension().unwrap_or_default());
        out.with_file_name(file)
    }

    /// Where a PNG's debug view goes: `out.png` with the view's name before the extension,
    /// `out.normal.png`.
    pub fn view_path(out: &Path, view: Aov) -> PathBuf {
        let mut name = out.file_stem().unwrap_or_default().to_os_string();
        name.push(format!(".{}.", view.name()));
        name.push(out.extension().unwrap_or_default());
        out.with_file_name(name)
    }

    /// Sends every file to its partial name (`x.partial.png`), for an unfinished render.
    pub fn make_partial(&mut self) {
        self.picture.make_partial();
        for (_, out) in &mut self.pngs {
            out.make_partial();
        }
        for out in self.layers.iter_mut().filter_map(|l| l.1.as_mut()) {
            out.make_partial();
        }
    }

    /// Writes `region` of the picture `image` as a region file (an EXR that `snell merge`
    /// puts in its place, carrying `fingerprint` where the region is finished).
    pub fn commit_region(
        self,
        image: &Image,
        region: super::Region,
        tone: &crate::output::tone::Tone,
        fingerprint: Option<u64>,
    ) -> Result<(), OutputError> {
        self.picture.commit_region(image, region, tone, fingerprint)
    }

    /// Writes the picture `image` and the debug views (rendered here, one ray through each
    /// pixel's centre; the variance view read from `film`).
    pub fn commit(
        self,
        scene: &Scene,
        image: &Image,
        film: Option<&Film>,
        threads: Option<usize>,
    ) -> Result<(), RunError> {
        let tone = &scene.settings.tone;
        if self.views.is_empty() && self.layers.is_empty() {
            return Ok(self.picture.commit_toned(image, tone)?);
        }
        let buffers = if self.views.is_empty() {
            None
        } else {
            let mut buffers = render_aovs(scene, threads)?;
            if let Some(film) = film {
                buffers.read_film(film);
            }
            Some(buffers)
        };
        let black = Image::new(image.width, image.height);
        if self.picture.format() == OutputFormat::Exr {
            let mut layers: Vec<ExrLayer> = match &buffers {
                Some(b) => self
                    .views
                    .iter()
                    .map(|&a| (a.name(), b.channels(a)))
                    .collect(),
                None => vec![],
            };
            for (name, _, img) in &self.layers {
                let img = img.as_ref().unwrap_or(&black);
                let channel =
                    |f: fn(&crate::math::Color) -> f32| img.pixels.iter().map(f).collect();
                layers.push((
                    name.as_str(),
                    vec![
                        ("R", channel(|c| c.x)),
                        ("G", channel(|c| c.y)),
                        ("B", channel(|c| c.z)),
                    ],
                ));
            }
            let bytes = encode_exr_layers(image, &layers, self.picture.path())?;
            return Ok(self.picture.commit_bytes(&bytes)?);
        }
        self.picture.commit_toned(image, tone)?;
        if let Some(buffers) = &buffers {
            for (a, out) in self.pngs {
                out.commit(&buffers.display(a, scene.settings.max_depth))?;
            }
        }
        for (_, out, img) in self.layers {
            if let Some(out) = out {
                out.commit_toned(img.as_ref().unwrap_or(&black), tone)?;
            }
        }
        Ok(())
    }
}

/// Renders `job` to `out` (PNG or EXR, by its extension) with the debug views `views` and
/// the scene's light path expressions and `options.lpe`'s (beside a PNG, or as layers of the
/// EXR): the files reserved first, the render run ([`run`]), then the files written, to their partial
/// names if the render was cancelled. The variance view is the path tracer's only.
pub fn render_to_files(
    job: &RenderJob,
    out: &Path,
    views: &[Aov],
    options: &RunOptions,
) -> Result<Finished, RunError> {
    let scene = &job.scene;
    let sampled = scene.settings.integrator.kind == crate::scene::IntegratorKind::Path;
    if let Some(a) = views.iter().find(|a| a.from_film())
        && !sampled
    {
        return Err(RunError::View(format!(
            "the {} view is the path tracer's: Whitted's samples are fixed strata",
            a.name()
        )));
    }
    let taken: Vec<&str> = views.iter().map(|a| a.name()).collect();
    let names: Vec<String> = lpe::for_render(scene, options.lpe, &taken)?
        .map(|set| set.named.into_iter().map(|n| n.name).collect())
        .unwrap_or_default();
    let mut outputs = Outputs::reserve(out, views)?;
    outputs.add_layers(&names)?;
    let finished = run(scene, options)?;
    outputs.set_layer_images(finished.layers.iter().map(|(_, i)| i.clone()).collect());
    if !finished.complete {
        outputs.make_partial();
    }
    outputs.commit(
        scene,
        &finished.image,
        finished.film.as_ref(),
        options.threads,
    )?;
    Ok(finished)
}
