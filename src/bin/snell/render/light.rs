//! A light-traced render from the command line (`--integrator light`): passes of 1, 2, 4
//! ... paths a pixel (`--time` stops after a pass), without the flags that need a film of
//! sums or tiles of finished pixels.

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
    ];
    match other.iter().find(|(given, _)| *given) {
        Some((_, flag)) => Err(usage_error(
            &format!("light tracing cannot be combined with {flag} yet"),
            Some("render without it, or with --integrator path"),
        )),
        None => Ok(()),
    }
}

/// Renders `run`'s scene by light tracing, until its samples or `time` are spent or Ctrl-C
/// stops it (the pass under way is then left out: the picture is that of the passes done).
pub(super) fn render_light(
    run: &Run,
    time: Option<std::time::Duration>,
) -> Result<Outcome, String> {
    let options = RenderOptions {
        threads: run.threads,
        progress: &|n| run.bar.set_position(n),
        cancel: Some(&STOP),
        region: None,
    };
    let r = snell::render::light::render_light_for(run.scene, &options, time)
        .map_err(|e| e.to_string())?;
    let (spp, r) = (r.spp, r.rendered);
    let pixels = run.scene.settings.width as u64 * run.scene.settings.height as u64;
    Ok(Outcome {
        complete: r.complete(),
        spp,
        samples: pixels * spp as u64,
        done: format!("{spp} paths a pixel (the pass under way left out)"),
        checkpoint: None,
        image: r.image,
        rays: r.rays,
        bad_samples: r.bad_samples,
        error: None,
        film: None,
        layers: vec![],
    })
}
