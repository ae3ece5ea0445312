//! A render job: a scene file with the overrides a caller gives (the command line, the
//! Python module), checked against the limits and the machine's
//! memory before any work, with the fingerprint a checkpoint must match. What every caller
//! of a render must do lives here once, not in each front end.

use crate::checkpoint::{Checkpoint, fingerprint};
use crate::scene::{
    AssetCache, Limits, RenderSettings, Scene, SceneError, available_memory, memory_estimate,
};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Values that replace the scene's `[image]` settings.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Overrides {
    /// Image width in pixels.
    pub width: Option<u32>,
    /// Image height in pixels.
    pub height: Option<u32>,
    /// Samples per pixel.
    pub spp: Option<u32>,
    /// Sample seed.
    pub seed: Option<u64>,
    /// The integrator (`--integrator`).
    pub integrator: Option<crate::scene::IntegratorKind>,
    /// The path tracer's sampler (`--sampler`).
    pub sampler: Option<crate::sampler::SamplerKind>,
    /// The path tracer's clamp (`--clamp`).
    pub clamp: Option<f32>,
    /// Exposure of 8-bit outputs, in stops (`--exposure`).
    pub exposure: Option<f32>,
    /// Tone curve of 8-bit outputs (`--tonemap`).
    pub tonemap: Option<crate::output::tone::ToneCurve>,
    /// Adaptive sampling's threshold (`--noise`).
    pub noise: Option<f32>,
}

impl Overrides {
    /// Replaces the settings given here.
    pub fn apply(&self, s: &mut RenderSettings) {
        s.width = self.width.unwrap_or(s.width);
        s.height = self.height.unwrap_or(s.height);
        s.spp = self.spp.unwrap_or(s.spp);
        s.seed = self.seed.unwrap_or(s.seed);
        let i = &mut s.integrator;
        i.kind = self.integrator.unwrap_or(i.kind);
        i.sampler = self.sampler.unwrap_or(i.sampler);
        i.clamp = self.clamp.or(i.clamp);
        s.tone.exposure = self.exposure.unwrap_or(s.tone.exposure);
        s.tone.curve = self.tonemap.unwrap_or(s.tone.curve);
        s.noise = self.noise.or(s.noise);
    }
}

/// Why a job cannot start.
#[derive(Debug)]
pub enum JobError {
    /// The scene file has problems (each located in the file).
    Scene(SceneError),
    /// The settings ask for what cannot be done: a message and, where there is one, what
    /// to do instead.
    Settings {
        /// What is wrong.
        message: String,
        /// How to put it right.
        help: Option<String>,
    },
}

impl std::fmt::Display for JobError {
    /// The scene's problems as [`SceneError`] gives them; a settings message, then its help
    /// after "help: ".
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            JobError::Scene(e) => e.fmt(f),
            JobError::Settings {
                message,
                help: Some(help),
            } => write!(f, "{message} (help: {help})"),
            JobError::Settings {
                message,
                help: None,
            } => f.write_str(message),
        }
    }
}

impl std::error::Error for JobError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            JobError::Scene(e) => Some(e),
            JobError::Settings { .. } => None,
        }
    }
}

/// A scene loaded, its settings overridden and checked: ready to render.
#[derive(Debug)]
pub struct RenderJob {
    /// The scene, with the overrides applied.
    pub scene: Scene,
    /// The scene file.
    pub scene_path: PathBuf,
    /// What a checkpoint of this render must carry to be resumed by it.
    pub fingerprint: u64,
    /// Time to read and build the scene.
    pub load_time: Duration,
}

fn settings_error(message: impl Into<String>, help: Option<String>) -> JobError {
    JobError::Settings {
        message: message.into(),
        help,
    }
}

/// Checks an image's sides and samples against `limits` (`what` names the sides, as the
/// caller's user knows them: `--width`).
pub fn check_settings(s: &RenderSettings, limits: &Limits) -> Result<(), JobError> {
    for (what, v) in [("--width", s.width), ("--height", s.height)] {
        RenderSettings::check_side(what, v).map_err(|e| settings_error(e, None))?;
    }
    limits
        .check_spp(
            s.spp,
            s.integrator.kind == crate::scene::IntegratorKind::Whitted,
        )
        .map_err(|(e, help)| settings_error(e, help))?;
    limits
        .check_pixels(s.width, s.height)
        .map_err(|(e, help)| settings_error(e, help))?;
    if let Some(noise) = s.noise {
        RenderSettings::check_noise(noise).map_err(|e| settings_error(e, None))?;
        use crate::scene::IntegratorKind::*;
        let why = match s.integrator.kind {
            Path => return Ok(()),
            Whitted => "Whitted's samples are fixed strata, all taken at once",
            Light | Bdpt => {
                "light and bdpt splat their light anywhere on the film, not into one pixel"
            }
        };
        return Err(settings_error(
            format!("adaptive sampling (noise) is the path tracer's: {why}"),
            Some("render with --integrator path (or [integrator] type = \"path\"), or without --noise and [image] noise".into()),
        ));
    }
    Ok(())
}

/// The settings of `s` its integrator does not read, from a scene written for another
/// integrator (`--integrator` chose this one): a warning each. A `--clamp` given for light
/// tracing or bdpt, which never clamp, is refused.
fn unread_settings(s: &RenderSettings, overrides: &Overrides) -> Result<Vec<String>, JobError> {
    use crate::scene::IntegratorKind::*;
    let i = &s.integrator;
    let mut warnings = vec![];
    let name = match i.kind {
        Light => "light tracing",
        Bdpt => "bdpt",
        _ => "",
    };
    if !name.is_empty() && i.clamp.is_some() {
        if overrides.clamp.is_some() {
            return Err(settings_error(
                format!(
                    "--clamp is the path tracer's: {name} does not clamp (its samples add to many pixels)"
                ),
                Some("render without --clamp, or with --integrator path".into()),
            ));
        }
        warnings.push(format!(
            "the scene's `clamp` is the path tracer's: {name} does not clamp, so it is not used"
        ));
    }
    if i.kind != Bdpt && i.mis != crate::scene::MisHeuristic::Power {
        warnings.push("the scene's `mis` is bdpt's: this integrator does not read it".into());
    }
    Ok(warnings)
}

impl RenderJob {
    /// Loads `scene_path` and applies, in order, a resumed checkpoint's settings and then
    /// `overrides`; refuses settings past `limits`, a render the machine's memory cannot
    /// hold, and a checkpoint of another scene or other settings.
    pub fn prepare(
        scene_path: &Path,
        overrides: &Overrides,
        limits: &Limits,
        resumed: Option<&Checkpoint>,
    ) -> Result<RenderJob, JobError> {
        let mut assets = AssetCache::default();
        Self::prepare_frame(scene_path, overrides, limits, resumed, 0, &mut assets)
    }

    /// As [`RenderJob::prepare`], for `frame` of the scene's animation, with the images
    /// and meshes `assets` kept from the frames prepared before. A frame's fingerprint is
    /// its own, so regions of different frames do not merge.
    pub fn prepare_frame(
        scene_path: &Path,
        overrides: &Overrides,
        limits: &Limits,
        resumed: Option<&Checkpoint>,
        frame: u32,
        assets: &mut AssetCache,
    ) -> Result<RenderJob, JobError> {
        let start = Instant::now();
        let scene =
            crate::scene::load_frame(scene_path, limits, frame, assets).map_err(JobError::Scene)?;
        let load_time = start.elapsed();
        Self::from_scene(
            scene, scene_path, overrides, limits, resumed, frame, load_time,
        )
    }

    /// As [`RenderJob::prepare_frame`], for `scene` already built (from `scene_path`, or
    /// from text that names itself so) in `load_time`: the overrides applied and checked,
    /// the fingerprint made from the text it was built from.
    pub fn from_scene(
        mut scene: Scene,
        scene_path: &Path,
        overrides: &Overrides,
        limits: &Limits,
        resumed: Option<&Checkpoint>,
        frame: u32,
        load_time: Duration,
    ) -> Result<RenderJob, JobError> {
        let lighting = scene.lighting_warning();
        let s = &mut scene.settings;
        if let Some(c) = resumed {
            (s.width, s.height, s.spp, s.seed) = (c.width, c.height, c.spp, c.seed);
            if let Some(i) = c.integrator {
                i.apply(s);
            }
        }
        overrides.apply(s);
        check_settings(s, limits)?;
        let unread = unread_settings(s, overrides)?;
        scene.warnings.extend(unread);
        scene.recheck_lighting(lighting);
        if let Some(available) = available_memory()
            && let Err(e) = memory_estimate(&scene).check(available)
        {
            return Err(settings_error(
                e,
                Some("render a smaller image (--width, --height)".into()),
            ));
        }
        let s = &scene.settings;
        // The integrator's settings change the picture as the seed does.
        let i = &s.integrator;
        let settings_hash = crate::math::hash_seed(&[
            s.seed,
            i.kind as u64,
            i.sampler as u64,
            i.clamp.map_or(0, |c| c.to_bits() as u64 + 1),
        ]);
        // Adaptive sampling too (a render without it keeps the fingerprint it had).
        let settings_hash = match s.noise {
            Some(v) => crate::math::hash_seed(&[settings_hash, v.to_bits() as u64]),
            None => settings_hash,
        };
        let seed_and_integrator =
            if *i == crate::scene::IntegratorSettings::default() && s.noise.is_none() {
                s.seed
            } else {
                settings_hash
            };
        // The frame too, in an animation (a still's fingerprint stays as it was).
        let seed_and_integrator = match scene.animation {
            Some(_) => crate::math::hash_seed(&[seed_and_integrator, frame as u64]),
            None => seed_and_integrator,
        };
        // The text the scene was built from, not the file read again (which may have
        // changed since).
        let fingerprint = fingerprint(
            scene.source.as_bytes(),
            s.width,
            s.height,
            s.spp,
            seed_and_integrator,
        );
        if let Some(c) = resumed
            && c.fingerprint != fingerprint
        {
            return Err(settings_error(
                "the scene file or the settings changed since the checkpoint was saved, so resuming would not give the same picture",
                Some("render again without --resume, or restore the scene as it was".into()),
            ));
        }
        Ok(RenderJob {
            scene,
            scene_path: scene_path.to_path_buf(),
            fingerprint,
            load_time,
        })
    }

    /// The output a render of `scene_path` writes when none is named: the scene's name with
    /// `.png`, in the current folder (`cap.day.toml` gives `cap.day.png`).
    pub fn default_output(scene_path: &Path) -> PathBuf {
        let mut name = scene_path.file_stem().unwrap_or_default().to_os_string();
        name.push(".png");
        PathBuf::from(name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene_file(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("snell-job-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("s.toml");
        std::fs::write(
            &path,
            "[image]\nwidth = 8\nheight = 6\n[camera]\nlook_at = [0, 0, -1]\n[materials.m]\ncolor = 1\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, -3]\nradius = 1\nmaterial = \"m\"\n",
        )
        .unwrap();
        path
    }

    #[test]
    fn overrides_replace_the_scenes_settings_and_are_checked() {
        let path = scene_file("overrides");
        let limits = Limits::default();
        let job = RenderJob::prepare(&path, &Overrides::default(), &limits, None).unwrap();
        assert_eq!(
            (job.scene.settings.width, job.scene.settings.height),
            (8, 6)
        );
        let o = Overrides {
            width: Some(32),
            spp: Some(4),
            seed: Some(9),
            ..Overrides::default()
        };
        let job2 = RenderJob::prepare(&path, &o, &limits, None).unwrap();
        let s = &job2.scene.settings;
        assert_eq!((s.width, s.height, s.spp, s.seed), (32, 6, 4, 9));
        assert_ne!(
            job.fingerprint, job2.fingerprint,
            "the settings are in the fingerprint"
        );
        let bad = Overrides {
            spp: Some(10),
            ..Overrides::default()
        };
        match RenderJob::prepare(&path, &bad, &limits, None) {
            Err(JobError::Settings { message, help }) => {
                assert!(message.contains("square number"), "{message}");
                assert!(help.is_some());
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            RenderJob::prepare(
                &path.with_file_name("none.toml"),
                &Overrides::default(),
                &limits,
                None
            ),
            Err(JobError::Scene(_))
        ));
    }

    #[test]
    fn a_checkpoint_of_other_settings_is_refused_and_its_own_accepted() {
        let path = scene_file("resume");
        let limits = Limits::default();
        let job = RenderJob::prepare(&path, &Overrides::default(), &limits, None).unwrap();
        let s = &job.scene.settings;
        // The fingerprint hashes the file's bytes as the scene was built from them (so a
        // checkpoint of an earlier build, which read the file again, is still accepted).
        let text = std::fs::read(&path).unwrap();
        assert_eq!(job.scene.source.as_bytes(), &text[..]);
        assert_eq!(
            job.fingerprint,
            fingerprint(&text, s.width, s.height, s.spp, s.seed)
        );
        let mut c = Checkpoint {
            fingerprint: job.fingerprint,
            width: s.width,
            height: s.height,
            spp: s.spp,
            seed: s.seed,
            integrator: Some(crate::checkpoint::CheckpointIntegrator::of(s)),
            scene: path.clone(),
            output: "s.png".into(),
            tiles: Default::default(),
            film: None,
            splatted: None,
        };
        assert!(RenderJob::prepare(&path, &Overrides::default(), &limits, Some(&c)).is_ok());
        c.fingerprint ^= 1;
        assert!(matches!(
            RenderJob::prepare(&path, &Overrides::default(), &limits, Some(&c)),
            Err(JobError::Settings { .. })
        ));
        // A checkpoint keeps the integrator a render had from the command line, so a resume
        // needs no flags again.
        let path_tracer = Overrides {
            integrator: Some(crate::scene::IntegratorKind::Path),
            clamp: Some(4.0),
            ..Overrides::default()
        };
        let job = RenderJob::prepare(&path, &path_tracer, &limits, None).unwrap();
        let c = Checkpoint {
            fingerprint: job.fingerprint,
            integrator: Some(crate::checkpoint::CheckpointIntegrator::of(
                &job.scene.settings,
            )),
            ..c
        };
        let resumed = RenderJob::prepare(&path, &Overrides::default(), &limits, Some(&c)).unwrap();
        assert_eq!(
            resumed.scene.settings.integrator,
            job.scene.settings.integrator
        );
        assert_eq!(resumed.fingerprint, job.fingerprint);
        assert_eq!(
            RenderJob::default_output(Path::new("a/cap.day.toml")),
            Path::new("cap.day.png")
        );
    }

    /// A job's error reads as the command line prints it, so callers of the library (a
    /// script, the Python module) can show it as it is.
    #[test]
    fn a_job_error_says_what_and_how() {
        let e = settings_error(
            "--spp must be at least 1",
            Some("give --spp 1 or more".into()),
        );
        assert_eq!(
            e.to_string(),
            "--spp must be at least 1 (help: give --spp 1 or more)"
        );
        assert_eq!(settings_error("no", None).to_string(), "no");
        let missing = RenderJob::prepare(
            Path::new("no/such/scene.toml"),
            &Overrides::default(),
            &Limits::default(),
            None,
        )
        .unwrap_err();
        assert!(missing.to_string().contains("scene.toml"), "{missing}");
        assert!(std::error::Error::source(&missing).is_some());
    }
}
