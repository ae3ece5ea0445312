//! A light-traced or bidirectional render from the command line (`--integrator light`,
//! `--integrator bdpt`), whose light lands anywhere on the film: passes of 1, 2, 4 ...
//! samples a pixel (`--time` stops after a pass), without the flags that need a film of
//! sums alone or tiles of finished pixels.

use super::{Outcome, Run, STOP};
use crate::args::RenderArgs;
use crate::usage_error;
use snell::render::RenderOptions;
use snell::scene::IntegratorKind;
use std::process::ExitCode;

/// The flags light tracing and bdpt do not take yet, refused with exit 2.
pub(super) fn check(args: &RenderArgs, kind: IntegratorKind) -> Result<(), ExitCode> {
    let other = [
        (args.region.is_some(), "--region"),
        (args.checkpoint.is_some(), "--checkpoint"),
        (args.resume.is_some(), "--resume"),
    ];
    match other.iter().find(|(given, _)| *given) {
        Some((_, flag)) => Err(usage_error(
            &format!("{} cannot be combined with {flag} yet", name(kind)),
            Some("render without it, or with --integrator path"),
        )),
        None => Ok(()),
    }
}

/// What the integrator is called in messages.
fn name(kind: IntegratorKind) -> &'static str {
    match kind {
        IntegratorKind::Bdpt => "bdpt",
        _ => "light tracing",
    }
}

/// Renders `run`'s scene by light tracing or bdpt (as `kind` says), until its samples or
/// `time` are spent or Ctrl-C stops it (the pass under way is then left out: the picture is
/// that of the passes done).
pub(super) fn render_splatted(
    kind: IntegratorKind,
    strategies: bool,
    run: &Run,
    time: Option<std::time::Duration>,
) -> Result<Outcome, String> {
    let options = RenderOptions {
        threads: run.threads,
        progress: &|n| run.bar.set_position(n),
        cancel: Some(&STOP),
        region: None,
    };
    let (spp, r, layers) = if kind == IntegratorKind::Bdpt {
        let r = snell::render::bdpt::render_bdpt_for(run.scene, &options, time, strategies)
            .map_err(|e| e.to_string())?;
        (r.spp, r.rendered, r.strategies)
    } else {
        let r = snell::render::light::render_light_for(run.scene, &options, time)
            .map_err(|e| e.to_string())?;
        (r.spp, r.rendered, vec![])
    };
    let unit = if kind == IntegratorKind::Bdpt {
        "samples"
    } else {
        "paths"
    };
    let pixels = run.scene.settings.width as u64 * run.scene.settings.height as u64;
    Ok(Outcome {
        complete: r.complete(),
        spp,
        samples: pixels * spp as u64,
        done: format!("{spp} {unit} a pixel (the pass under way left out)"),
        checkpoint: None,
        image: r.image,
        rays: r.rays,
        bad_samples: r.bad_samples,
        error: None,
        film: None,
        layers,
        adaptive: None,
    })
}
