//! `--lpe` and `[[image.lpe]]`: the expressions a render writes beside its picture, checked
//! before any work (a mistake is shown under the expression, at its column), and the
//! render that gathers them: every sample of each pixel at once, tile by tile.

use super::{Outcome, Run, STOP};
use crate::args::RenderArgs;
use crate::usage_error;
use snell::integrator::aov::Aov;
use snell::lpe::{self, LpeSet, Named};
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
    let from_scene = lpe::expand(&scene.lpe, scene);
    let from_args = lpe::expand(&args.lpe, scene);
    if from_scene.is_empty() && from_args.is_empty() {
        return Ok(None);
    }
    if scene.settings.integrator.kind != snell::scene::IntegratorKind::Path {
        return Err(usage_error(
            "light path expressions follow the path tracer's paths, and this render is Whitted's",
            Some("render with --integrator path (or [integrator] type = \"path\")"),
        ));
    }
    let other = [
        (args.region.is_some(), "--region"),
        (args.checkpoint.is_some(), "--checkpoint"),
        (args.resume.is_some(), "--resume"),
        (args.time.is_some(), "--time"),
    ];
    if let Some((_, flag)) = other.iter().find(|(given, _)| *given) {
        return Err(usage_error(
            &format!("light path expressions cannot be combined with {flag} yet"),
            Some("render them without it"),
        ));
    }
    let mut all: Vec<Named> = from_scene;
    let mut given: Vec<String> = vec![];
    for n in from_args {
        if given.contains(&n.name) {
            return Err(usage_error(
                &format!("two light path expressions are named `{}`", n.name),
                Some("give each --lpe a name of its own: NAME=EXPR"),
            ));
        }
        given.push(n.name.clone());
        // One given on the command line replaces the scene's of the same name.
        all.retain(|m| m.name != n.name);
        all.push(n);
    }
    let mut seen: Vec<&str> = vec![];
    for n in &all {
        if seen.contains(&n.name.as_str()) {
            return Err(usage_error(
                &format!("two light path expressions are named `{}`", n.name),
                Some("rename one of them (a per-light image is named after its light)"),
            ));
        }
        if aovs.iter().any(|a| a.name() == n.name) {
            return Err(usage_error(
                &format!(
                    "the light path expression `{}` has the name of a debug view",
                    n.name
                ),
                Some("name it otherwise: NAME=EXPR"),
            ));
        }
        seen.push(&n.name);
    }
    LpeSet::new(scene, &all).map(Some).map_err(|e| {
        let n = &all[e.index.min(all.len() - 1)];
        eprintln!(
            "error: light path expression `{}` = `{}`: {}",
            n.name, n.expr, e.error
        );
        // The expression again, with a mark under the column.
        eprintln!("    {}", n.expr);
        eprintln!("    {}^", " ".repeat(e.error.column.saturating_sub(1)));
        eprintln!("  help: {}", e.error.help);
        ExitCode::from(2)
    })
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
    })
}
