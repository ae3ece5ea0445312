//! A light-traced render from the command line (`--integrator light`): every path at once,
//! tile by tile of the film's worth of paths, without the flags that need passes or tiles
//! of finished pixels.

use super::{Outcome, Run, STOP};
use crate::args::RenderArgs;
use crate::usage_error;
use snell::render::RenderOptions;
use std::process::ExitCode;

/// The flags light tracing does not take yet, refused with exit 2.
pub(super) fn check(args: &RenderArgs) -> Result<(), ExitCode> {
    let other = [
        (args.region.is_some(), "--region"),
        (args.checkpoint.is_some(), "--checkpoint"),
        (args.resume.is_some(), "--resume"),
        (args.time.is_some(), "--time"),
    ];
    match other.iter().find(|(given, _)| *given) {
        Some((_, flag)) => Err(usage_error(
            &format!("light tracing cannot be combined with {flag} yet"),
            Some("render without it, or with --integrator path"),
        )),
        None => Ok(()),
    }
}

/// Renders `run`'s scene by light tracing (Ctrl-C leaves the paths of the tiles not
/// started out: the picture is darker where they would have landed).
pub(super) fn render_light(run: &Run) -> Result<Outcome, String> {
    let options = RenderOptions {
        threads: run.threads,
        progress: &|n| run.bar.set_position(n),
        cancel: Some(&STOP),
        region: None,
    };
    let r = snell::render::light::render_light(run.scene, &options).map_err(|e| e.to_string())?;
    let spp = run.scene.settings.spp;
    Ok(Outcome {
        complete: r.complete(),
        spp,
        samples: r.pixels_rendered * spp as u64,
        done: format!(
            "the paths of {} of {} tiles traced (the picture lacks the others' light)",
            r.tiles_done, r.tiles_total
        ),
        checkpoint: None,
        image: r.image,
        rays: r.rays,
        bad_samples: r.bad_samples,
        error: None,
        film: None,
        layers: vec![],
    })
}
