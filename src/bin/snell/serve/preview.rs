//! The preview's state, shared by the HTTP handlers, the file watcher and the render loop,
//! and the render loop itself: load the scene through the library's `RenderJob`, then
//! passes over a film (the path tracer's samples a few at a time; Whitted's one sample a
//! pixel, then all of them), each published as a frame. A change of a file or of the camera
//! cancels the pass in flight (between tiles) and starts again.

use snell::camera::{Camera, CameraView};
use snell::film::{Film, Image};
use snell::job::{Overrides, RenderJob};
use snell::render::adaptive::{Convergence, FIRST_DECISION};
use snell::render::{RenderOptions, render_pass, render_pass_adaptive};
use snell::scene::{IntegratorKind, Limits, Scene};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// Files are read again this long after the last change seen: an editor's save is often
/// several writes (truncate, write, rename), and a half-written file is not worth a render.
const SETTLE: Duration = Duration::from_millis(25);

/// A path-traced pass aims to take about this long, so that the picture refines smoothly
/// and a cancelled pass wastes little.
const PASS_TIME: f64 = 0.15;

/// What the command line asked of the preview.
#[derive(Clone, Debug)]
pub(crate) struct Settings {
    /// The scene file.
    pub scene: PathBuf,
    /// The longest side of the preview, in pixels (0: the scene's own size).
    pub size: u32,
    /// The frame of the scene's animation shown.
    pub frame: u32,
    /// Replacements of the scene's settings (integrator, sampler, clamp, samples).
    pub overrides: Overrides,
    /// Limits the scene is checked against.
    pub limits: Limits,
}

/// One published picture and what it took.
#[derive(Debug)]
pub(crate) struct Frame {
    /// Counts frames over the server's life.
    pub id: u64,
    /// The render it belongs to (see [`State::generation`]).
    pub generation: u64,
    /// The picture, linear.
    pub image: Image,
    /// Samples per pixel in it.
    pub spp: u32,
    /// Passes so far.
    pub passes: u32,
    /// Seconds since this render started.
    pub elapsed: f64,
    /// Rays a second over this render.
    pub rays_per_second: f64,
    /// Whether the render has all the samples it will take.
    pub done: bool,
    /// The scene's exposure and tone curve (its `[image]` table, or serve's flags): what
    /// `snell render` writes the PNG with, and what the picture is shown with unless the
    /// page asks otherwise.
    pub tone: snell::output::tone::Tone,
    /// The path tracer's film of sums the picture was made from, for the views read from
    /// it (`variance`, `spp`); `None` for Whitted and bdpt.
    pub film: Option<Film>,
    /// The scene the picture was rendered from (the state's may already be the next one's).
    pub scene: Arc<Scene>,
}

/// Everything the handlers read and the loop and the watcher change.
#[derive(Default)]
pub(crate) struct State {
    /// Bumped at every change a page should hear of.
    pub version: u64,
    /// Bumped at every new render (a load, a camera change).
    pub generation: u64,
    /// The scene being shown, with the preview's size and camera.
    pub scene: Option<Arc<Scene>>,
    /// The integrator's name.
    pub integrator: &'static str,
    /// The samples each pixel will get.
    pub target_spp: u32,
    /// The scene's problems as `snell check` prints them, when the last load failed (the
    /// last good picture stays).
    pub error: Option<String>,
    /// The newest picture.
    pub frame: Option<Arc<Frame>>,
    /// The camera the page has moved to, if it has.
    pub camera_override: Option<CameraView>,
    /// The camera the file gives.
    pub file_camera: Option<CameraView>,
    /// The files to watch: the scene and every file it reads.
    pub files: Vec<PathBuf>,
    /// Set by the watcher: read the files again.
    pub reload: bool,
    /// When the watcher last saw a change.
    pub last_change: Option<Instant>,
    /// Set by a camera change: render again.
    pub restart: bool,
    /// Frames made so far.
    pub frames: u64,
}

/// The state with its lock and the signals around it.
pub(crate) struct Shared {
    /// What the preview shows.
    pub state: Mutex<State>,
    /// Signalled at every change of `state`, and at stop.
    pub changed: Condvar,
    /// Set to stop the pass in flight (tiles not started are skipped).
    pub cancel: AtomicBool,
    /// Set when the server stops.
    pub stop: AtomicBool,
    /// The state's version, for the event streams (which wait on it without a thread each):
    /// sent at every change a page should hear of, and at stop.
    pub versions: tokio::sync::watch::Sender<u64>,
    /// The command line's settings.
    pub settings: Settings,
}

impl Shared {
    pub(crate) fn new(settings: Settings) -> Self {
        Shared {
            state: Mutex::new(State {
                reload: true,
                files: vec![settings.scene.clone()],
                ..State::default()
            }),
            changed: Condvar::new(),
            cancel: AtomicBool::new(false),
            stop: AtomicBool::new(false),
            versions: tokio::sync::watch::Sender::new(0),
            settings,
        }
    }

    /// The state, locked (a handler that panicked cannot leave it half changed: every
    /// change is a few assignments).
    pub(crate) fn lock(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A watched file changed: stop the pass in flight now, and load again once the files
    /// settle.
    pub(crate) fn files_changed(&self) {
        self.cancel.store(true, Ordering::SeqCst);
        let mut s = self.lock();
        s.reload = true;
        s.last_change = Some(Instant::now());
        drop(s);
        self.changed.notify_all();
    }

    /// The page moved the camera (`None`: back to the file's): render again.
    pub(crate) fn set_camera(&self, view: Option<CameraView>) {
        self.cancel.store(true, Ordering::SeqCst);
        let mut s = self.lock();
        s.camera_override = view;
        s.restart = true;
        drop(s);
        self.changed.notify_all();
    }

    /// Stops the loop and ends the event streams.
    pub(crate) fn shut_down(&self) {
        self.stop.store(true, Ordering::SeqCst);
        self.cancel.store(true, Ordering::SeqCst);
        self.changed.notify_all();
        self.versions.send_modify(|v| *v += 1);
    }

    /// Unlocks the state after a change a page should hear of (its version bumped), and
    /// tells the loop and the pages.
    fn announce(&self, s: MutexGuard<'_, State>) {
        let version = s.version;
        drop(s);
        self.changed.notify_all();
        self.versions.send_replace(version);
    }

    fn stopping(&self) -> bool {
        self.stop.load(Ordering::SeqCst)
    }
}

/// What the loop was woken for.
enum Work {
    Load,
    Render,
    Stop,
}

/// The render loop: runs until the server stops. `watch` is told the files to watch after
/// every load.
pub(crate) fn run(shared: &Shared, watch: &dyn Fn(&[PathBuf])) {
    loop {
        match next_work(shared) {
            Work::Stop => return,
            Work::Load => {
                let loaded = load(shared);
                let files = shared.lock().files.clone();
                watch(&files);
                // A scene with a mistake leaves the last picture as it was.
                if !loaded {
                    continue;
                }
            }
            Work::Render => {}
        }
        shared.cancel.store(false, Ordering::SeqCst);
        // A render that fails (or a bug that panics in it) is shown on the page, and the
        // server goes on: the next save or camera move tries again.
        let failed = match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| render(shared)))
        {
            Ok(Ok(())) => None,
            Ok(Err(e)) => Some(e),
            Err(panic) => Some(
                panic
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| panic.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "it stopped unexpectedly".into()),
            ),
        };
        if let Some(why) = failed {
            let mut s = shared.lock();
            s.error = Some(format!("error: the render failed: {why}\n"));
            s.version += 1;
            shared.announce(s);
        }
    }
}

/// Waits for something to do: files that changed and have settled, or a camera change.
fn next_work(shared: &Shared) -> Work {
    let mut s = shared.lock();
    loop {
        if shared.stopping() {
            return Work::Stop;
        }
        if s.reload {
            let settled = s.last_change.is_none_or(|t| t.elapsed() >= SETTLE);
            if settled {
                (s.reload, s.restart) = (false, false);
                return Work::Load;
            }
            let wait = SETTLE.saturating_sub(s.last_change.map_or(SETTLE, |t| t.elapsed()));
            s = shared
                .changed
                .wait_timeout(s, wait)
                .unwrap_or_else(|e| e.into_inner())
                .0;
            continue;
        }
        if s.restart {
            s.restart = false;
            return Work::Render;
        }
        s = shared.changed.wait(s).unwrap_or_else(|e| e.into_inner());
    }
}

/// Reads the scene again: on success it replaces the one shown; on failure its problems
/// are shown over the last good picture. Says whether it loaded.
fn load(shared: &Shared) -> bool {
    let set = &shared.settings;
    // Each load reads the files again: a save of a texture or mesh must show.
    let mut assets = snell::scene::AssetCache::default();
    let job = RenderJob::prepare_frame(
        &set.scene,
        &set.overrides,
        &set.limits,
        None,
        set.frame,
        &mut assets,
    );
    let loaded = job.is_ok();
    let mut s = shared.lock();
    s.version += 1;
    match job {
        Ok(job) => {
            let mut scene = job.scene;
            preview_size(&mut scene, set.size);
            s.files = watched(&set.scene, &scene.files);
            let file_camera = scene.camera.view();
            // A camera the page moved stays until the file's own camera changes.
            if s.file_camera.is_some_and(|c| c != file_camera) {
                s.camera_override = None;
            }
            s.file_camera = Some(file_camera);
            if let Some(c) = s
                .camera_override
                .map(|o| with_lens_of(o, file_camera))
                .and_then(Camera::from_view)
            {
                scene.camera = c;
            }
            s.integrator = match scene.settings.integrator.kind {
                IntegratorKind::Whitted => "whitted",
                IntegratorKind::Path => "path",
                // The preview has no light tracing: the path tracer, which agrees with it,
                // stands in.
                IntegratorKind::Light => "path (for light)",
                IntegratorKind::Bdpt => "bdpt",
            };
            s.target_spp = scene.settings.spp;
            s.scene = Some(Arc::new(scene));
            s.error = None;
        }
        Err(e) => {
            let (text, files) = match e {
                snell::job::JobError::Scene(e) => (crate::scene_error_text(&e, false), e.files),
                snell::job::JobError::Settings { message, help } => (
                    match help {
                        Some(h) => format!("error: {message}\n  help: {h}"),
                        None => format!("error: {message}"),
                    },
                    vec![],
                ),
            };
            s.error = Some(text);
            // Keep watching what the last good scene read, and what this one named.
            let mut all = s.files.clone();
            all.extend(watched(&set.scene, &files));
            all.sort();
            all.dedup();
            s.files = all;
        }
    }
    shared.announce(s);
    loaded
}

/// The scene file and the files it read, absolute.
fn watched(scene: &Path, files: &[PathBuf]) -> Vec<PathBuf> {
    let mut all: Vec<PathBuf> = std::iter::once(scene)
        .chain(files.iter().map(PathBuf::as_path))
        .map(|p| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf()))
        .collect();
    all.sort();
    all.dedup();
    all
}

/// Scales the image so that its longer side is `size` pixels (never up; 0 keeps it).
fn preview_size(scene: &mut Scene, size: u32) {
    let s = &mut scene.settings;
    let longest = s.width.max(s.height);
    if size == 0 || longest <= size {
        return;
    }
    let k = size as f64 / longest as f64;
    s.width = ((s.width as f64 * k).round() as u32).max(1);
    s.height = ((s.height as f64 * k).round() as u32).max(1);
}

/// Renders the scene shown until it has all its samples, a change cancels it, or the server
/// stops; an error says why it could not.
fn render(shared: &Shared) -> Result<(), String> {
    let (scene, generation) = {
        let mut s = shared.lock();
        let Some(scene) = s.scene.clone() else {
            return Ok(());
        };
        s.generation += 1;
        // The camera may have changed since the scene was loaded.
        let wanted = match (s.camera_override, s.file_camera) {
            (Some(o), Some(f)) => Some(with_lens_of(o, f)),
            (o, f) => o.or(f),
        };
        let scene = match wanted.and_then(Camera::from_view) {
            Some(c) if c != scene.camera => {
                let mut moved = (*scene).clone();
                moved.camera = c;
                let moved = Arc::new(moved);
                s.scene = Some(moved.clone());
                moved
            }
            _ => scene,
        };
        s.version += 1;
        let generation = s.generation;
        shared.announce(s);
        (scene, generation)
    };
    let start = Instant::now();
    let integrator = snell::integrator::chosen(scene.settings.integrator.kind);
    let cancelled = || shared.cancel.load(Ordering::SeqCst) || shared.stopping();
    let options = RenderOptions {
        threads: None,
        progress: &|_| {},
        cancel: Some(&shared.cancel),
        region: None,
    };
    let mut rays = 0u64;
    let target = scene.settings.spp;
    if scene.settings.integrator.kind == IntegratorKind::Bdpt {
        // Bidirectional passes: the camera's samples and the light paths' splats together.
        let mut film =
            snell::render::bdpt::BdptFilm::new(&scene, false).map_err(|e| e.to_string())?;
        let (mut passes, mut per_sample) = (0u32, None::<f64>);
        while film.spp() < target && !cancelled() {
            let n = per_sample.map_or(1, |t| ((PASS_TIME / t) as u32).clamp(1, 64));
            let n = n.min(target - film.spp());
            let pass_start = Instant::now();
            let (traced, whole) = film
                .add_samples(&scene, n, &options)
                .map_err(|e| e.to_string())?;
            if !whole {
                return Ok(());
            }
            per_sample = Some(pass_start.elapsed().as_secs_f64() / n as f64);
            (passes, rays) = (passes + 1, rays + traced.total());
            let done = film.spp();
            publish(
                shared,
                &scene,
                generation,
                film.image(),
                done,
                passes,
                start,
                rays,
                done == target,
                None,
            );
        }
    } else if integrator.uses_sampler() {
        let mut film = Film::new(scene.settings.width, scene.settings.height);
        // Seconds one sample of one pixel takes, from the last pass.
        let (mut done, mut passes, mut per_pixel_sample) = (0u32, 0u32, None::<f64>);
        let noise = scene.settings.noise;
        // Adaptive sampling (`[image] noise`, `--noise`): once every pixel has its first
        // samples, only the pixels still above the threshold take a pass's. Which those are
        // is worked out after each pass (to know whether any goes on) and kept for the next.
        let decide = |film: &Film, done: u32| {
            noise
                .filter(|_| done >= FIRST_DECISION)
                .map(|v| Convergence::of(film, v, target, None))
        };
        let mut decided = None;
        while done < target && !cancelled() {
            let going_on = decided.take().or_else(|| decide(&film, done));
            let pixels = going_on
                .as_ref()
                .map_or(film.pixels().len() as u64, |c| c.active());
            // One sample first (the quickest picture), then as many as fill a pass's time.
            let n = per_pixel_sample.map_or(1, |t| {
                ((PASS_TIME / (t * pixels.max(1) as f64)) as u32).clamp(1, 64)
            });
            let mut n = n.min(target - done);
            // Every pixel takes the first decision's samples before any may stop.
            if noise.is_some() && done < FIRST_DECISION {
                n = n.min(FIRST_DECISION - done);
            }
            let pass_start = Instant::now();
            let before = film.pixels().iter().map(|p| p.samples as u64).sum::<u64>();
            let (stats, tiles) = match &going_on {
                Some(c) => {
                    let tiles = (0..film.grid().count())
                        .filter(|&t| c.tile_active(t))
                        .count();
                    let s =
                        render_pass_adaptive(&scene, integrator, &mut film, done + n, c, &options);
                    (s, tiles as u32)
                }
                None => (
                    render_pass(&scene, integrator, &mut film, done..done + n, &options),
                    film.grid().count(),
                ),
            };
            let stats = stats.map_err(|e| e.to_string())?;
            if stats.tiles_done < tiles {
                return Ok(());
            }
            let added = film.pixels().iter().map(|p| p.samples as u64).sum::<u64>() - before;
            per_pixel_sample = Some(pass_start.elapsed().as_secs_f64() / added.max(1) as f64);
            (done, passes, rays) = (done + n, passes + 1, rays + stats.rays.total());
            // Done once no pixel goes on, in an adaptive render.
            decided = decide(&film, done);
            let finished = done == target || decided.as_ref().is_some_and(|c| c.active() == 0);
            publish(
                shared,
                &scene,
                generation,
                film.image(),
                done,
                passes,
                start,
                rays,
                finished,
                Some(film.clone()),
            );
            if finished {
                break;
            }
        }
    } else {
        // Whitted's strata depend on the sample count: one sample a pixel first, then all.
        let counts: &[u32] = if target > 1 { &[1, target] } else { &[1] };
        for (pass, &spp) in counts.iter().enumerate() {
            if cancelled() {
                return Ok(());
            }
            let mut this = (*scene).clone();
            this.settings.spp = spp;
            let mut film = Film::new(this.settings.width, this.settings.height);
            let stats = render_pass(&this, integrator, &mut film, 0..spp, &options)
                .map_err(|e| e.to_string())?;
            if stats.tiles_done < film.grid().count() {
                return Ok(());
            }
            rays += stats.rays.total();
            let last = spp == target;
            publish(
                shared,
                &scene,
                generation,
                film.image(),
                spp,
                pass as u32 + 1,
                start,
                rays,
                last,
                None,
            );
        }
    }
    Ok(())
}

/// Makes `image` the newest frame, if its render is still the one shown.
#[allow(clippy::too_many_arguments)]
fn publish(
    shared: &Shared,
    scene: &Arc<Scene>,
    generation: u64,
    image: Image,
    spp: u32,
    passes: u32,
    start: Instant,
    rays: u64,
    done: bool,
    film: Option<Film>,
) {
    let mut s = shared.lock();
    if s.generation != generation {
        return;
    }
    let elapsed = start.elapsed().as_secs_f64();
    s.frames += 1;
    let tone = scene.settings.tone;
    s.frame = Some(Arc::new(Frame {
        id: s.frames,
        generation,
        image,
        spp,
        passes,
        elapsed,
        rays_per_second: rays as f64 / elapsed.max(1e-9),
        done,
        tone,
        film,
        scene: scene.clone(),
    }));
    s.version += 1;
    shared.announce(s);
}

/// A camera the page moved (placement and field of view), with the file camera's
/// projection and lens.
fn with_lens_of(moved: CameraView, file: CameraView) -> CameraView {
    CameraView {
        projection: file.projection,
        lens: file.lens,
        ..moved
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_preview_keeps_the_aspect_and_never_grows() {
        let mut scene = snell::scene::load_str(
            "[image]\nwidth = 1000\nheight = 250\n[camera]\nlook_at = [0, 0, -1]\n",
            Path::new("t.toml"),
            Path::new("."),
            snell::scene::Format::Toml,
        )
        .unwrap();
        preview_size(&mut scene, 512);
        assert_eq!((scene.settings.width, scene.settings.height), (512, 128));
        preview_size(&mut scene, 4096);
        assert_eq!((scene.settings.width, scene.settings.height), (512, 128));
        preview_size(&mut scene, 0);
        assert_eq!((scene.settings.width, scene.settings.height), (512, 128));
    }
}
