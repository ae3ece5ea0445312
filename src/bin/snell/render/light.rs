//! A light-traced or bidirectional render from the command line (`--integrator light`,
//! `--integrator bdpt`), whose light lands anywhere on the film: passes of 1, 2, 4 ...
//! samples a pixel (`--time` stops after a pass), checkpoints between passes, and Ctrl-C
//! writing the picture of the passes done; not a region (its pixels take light from the
//! paths of every other pixel).

use super::{Outcome, PeriodicSaves, Run, STOP};
use crate::args::RenderArgs;
use crate::usage_error;
use snell::checkpoint::Splatted;
use snell::render::RenderOptions;
use snell::scene::IntegratorKind;
use std::process::ExitCode;

/// The flags light tracing and bdpt do not take yet, refused with exit 2.
pub(super) fn check(
    args: &RenderArgs,
    kind: IntegratorKind,
    strategies: bool,
) -> Result<(), ExitCode> {
    if args.region.is_some() {
        return Err(usage_error(
            &format!("{} cannot be combined with --region yet", name(kind)),
            Some("render without it, or with --integrator path"),
        ));
    }
    let saved = [
        (args.checkpoint.is_some(), "--checkpoint"),
        (args.resume.is_some(), "--resume"),
    ];
    if strategies && let Some((_, flag)) = saved.iter().find(|(given, _)| *given) {
        return Err(usage_error(
            &format!(
                "the strategy images cannot be combined with {flag} yet: a checkpoint does not keep them"
            ),
            Some("render the strategy images without a checkpoint"),
        ));
    }
    Ok(())
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
    earlier: Option<Splatted>,
) -> Result<Outcome, String> {
    let options = RenderOptions {
        threads: run.threads,
        progress: &|n| run.bar.set_position(n),
        cancel: Some(&STOP),
        region: None,
    };
    let first = earlier.as_ref().map_or(0, |e| e.spp);
    let mut saves = PeriodicSaves::new();
    let mut on_pass =
        |state: &dyn Fn() -> Splatted| saves.pass_done(run, || run.saver.splatted(state()));
    let (spp, r, layers, state) = if kind == IntegratorKind::Bdpt {
        let r = snell::render::bdpt::render_bdpt_from(
            run.scene,
            &options,
            time,
            strategies,
            earlier,
            &mut on_pass,
        )
        .map_err(|e| e.to_string())?;
        (r.spp, r.rendered, r.strategies, r.state)
    } else {
        let r = snell::render::light::render_light_from(
            run.scene,
            &options,
            time,
            earlier,
            &mut on_pass,
        )
        .map_err(|e| e.to_string())?;
        (r.spp, r.rendered, vec![], r.state)
    };
    saves.warn(run);
    let unit = if kind == IntegratorKind::Bdpt {
        "samples"
    } else {
        "paths"
    };
    let pixels = run.scene.settings.width as u64 * run.scene.settings.height as u64;
    let complete = r.complete();
    Ok(Outcome {
        complete,
        spp,
        samples: pixels * (spp - first) as u64,
        done: format!("{spp} {unit} a pixel (the pass under way left out)"),
        // Where an interrupted render stopped, for `--resume`.
        checkpoint: (!complete).then(|| run.saver.splatted(state)),
        image: r.image,
        rays: r.rays,
        bad_samples: r.bad_samples,
        error: None,
        film: None,
        layers,
        adaptive: None,
    })
}
