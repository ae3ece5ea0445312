//! `--lpe` and `[[image.lpe]]`: the expressions a render writes beside its picture, checked
//! before any work (a mistake is shown under the expression, at its column), and the
//! render that gathers them: every sample of each pixel at once, tile by tile.

use super::{Outcome, Run, STOP};
use crate::args::RenderArgs;
use crate::usage_error;
use snell::integrator::aov::Aov;
use snell::lpe::{self, LpeSet, RenderLpeError};
use snell::render::RenderOptions;
use snell::render::lpe::render_lpe;
use std::process::ExitCode;

/// The expressions of the scene's `[[image.lpe]]` and of `--lpe`, made ready for `scene`;
/// `None` where there are none. Whatever stops them is a usage error (exit 2).
pub(super) fn prepare(
    args: &RenderArgs,
    scene: &snell::Scene,
    aovs: &[Aov],
) -> Result<Option<LpeSet>, ExitCode> {
    let taken: Vec<&str> = aovs.iter().map(|a| a.name()).collect();
    let set = match lpe::for_render(scene, &args.lpe, &taken) {
        Ok(None) => return Ok(None),
        Ok(Some(set)) => set,
        Err(e @ RenderLpeError::Expr { .. }) => {
            eprintln!("error: {e}");
            if let RenderLpeError::Expr { named, error } = &e {
                // The expression again, with a mark under the column.
                eprintln!("    {}", named.expr);
                eprintln!("    {}^", " ".repeat(error.column.saturating_sub(1)));
            }
            eprintln!("  help: {}", e.help());
            return Err(ExitCode::from(2));
        }
        Err(e) => return Err(usage_error(&e.to_string(), Some(&e.help()))),
    };
    let other = [
        (args.region.is_some(), "--region"),
        (args.checkpoint.is_some(), "--checkpoint"),
        (args.resume.is_some(), "--resume"),
        (args.time.is_some(), "--time"),
        (
            scene.settings.noise.is_some(),
            "adaptive sampling (--noise, [image] noise)",
        ),
    ];
    if let Some((_, flag)) = other.iter().find(|(given, _)| *given) {
        return Err(usage_error(
            &format!("light path expressions cannot be combined with {flag} yet"),
            Some("render them without it"),
        ));
    }
    Ok(Some(set))
}

/// Renders `run`'s scene with the path tracer and `set`'s expressions beside it: every
/// sample of each pixel at once, tile by tile (Ctrl-C leaves the tiles not started black).
pub(super) fn render_with_lpe(run: &Run, set: &LpeSet) -> Result<Outcome, String> {
    let options = RenderOptions {
        threads: run.threads,
        progress: &|n| run.bar.set_position(n),
        cancel: Some(&STOP),
        region: None,
    };
    let r = render_lpe(run.scene, set, &options).map_err(|e| e.to_string())?;
    let spp = run.scene.settings.spp;
    let rendered = r.rendered;
    Ok(Outcome {
        complete: rendered.complete(),
        spp,
        samples: rendered.pixels_rendered * spp as u64,
        done: format!(
            "{} of {} tiles rendered (the rest are black)",
            rendered.tiles_done, rendered.tiles_total
        ),
        checkpoint: None,
        image: rendered.image,
        rays: rendered.rays,
        bad_samples: rendered.bad_samples,
        error: None,
        film: None,
        layers: r.layers,
        adaptive: None,
    })
}
