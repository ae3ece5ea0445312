//! `snell explain`: the tree of rays behind one sample of one pixel.

use crate::args::ExplainArgs;
use crate::{check_size_and_spp, load, usage_error};
use std::process::ExitCode;

pub(crate) fn explain(args: ExplainArgs) -> ExitCode {
    let limits = match args.limits.get() {
        Ok(l) => l,
        Err(code) => return code,
    };
    let mut scene = match load(&args.scene, &limits) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let s = &mut scene.settings;
    args.image.overrides(None).apply(s);
    if let Err(code) = check_size_and_spp(s, &limits) {
        return code;
    }
    let (x, y) = args.pixel;
    if x >= s.width || y >= s.height {
        return usage_error(
            &format!(
                "pixel {x},{y} is outside the {} x {} image",
                s.width, s.height
            ),
            Some(&format!(
                "columns go from 0 to {}, rows from 0 to {}",
                s.width - 1,
                s.height - 1
            )),
        );
    }
    // Light tracing has no camera paths: its scene is explained by the path tracer's path of
    // the same sample, which light tracing agrees with.
    let path = s.integrator.kind != snell::scene::IntegratorKind::Whitted;
    if s.integrator.kind == snell::scene::IntegratorKind::Light && !args.json {
        println!("({})", snell::explain_pixel::LIGHT_NOTE);
    }
    let film = match args.sample {
        None if path => (0.0, 0.0),
        None => (x as f32 + 0.5, y as f32 + 0.5),
        Some(k) if k >= s.spp => {
            let (has, help) = if s.spp == 1 {
                (
                    "1 sample".to_string(),
                    "use --sample 0 (its only one), or more samples with --spp".to_string(),
                )
            } else {
                (
                    format!("{} samples", s.spp),
                    format!(
                        "use --sample 0 to {}, or more samples with --spp",
                        s.spp - 1
                    ),
                )
            };
            return usage_error(
                &format!("sample {k} does not exist: the pixel has {has}"),
                Some(&help),
            );
        }
        // Checked above to be a sample of the pixel.
        Some(k) => snell::render::sample_position(s, x, y, k).unwrap_or_default(),
    };
    if s.integrator.kind == snell::scene::IntegratorKind::Bdpt {
        return explain_bdpt(&args, &scene, args.sample.unwrap_or(0));
    }
    if path {
        return explain_path(&args, &scene, args.sample.unwrap_or(0));
    }
    // With one sample a pixel, the ray through its centre is the render's sample 0 (its
    // lens point and wavelength too).
    let sample = args
        .sample
        .or((s.spp == 1).then_some(0))
        .map(|k| ((x, y), k));
    let Some(explained) = snell::explain_pixel::whitted(&scene, film, sample, args.max_rays) else {
        eprintln!("error: no ray was recorded");
        return ExitCode::from(1);
    };
    let (color, rays, tree) = (explained.color, &explained.rays, &explained.tree);
    let which = match args.sample {
        None => "the ray through its centre".to_string(),
        Some(k) => format!("sample {k} of {}", scene.settings.spp),
    };
    if args.json {
        let doc = explained.to_json(&scene, &args.scene, (x, y), args.sample);
        match serde_json::to_string_pretty(&doc) {
            Ok(text) => outln!("{text}"),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(1);
            }
        }
    } else {
        outln!(
            "pixel {x},{y} of {} ({} x {}), {which}, film position ({}, {}):",
            args.scene.display(),
            scene.settings.width,
            scene.settings.height,
            film.0,
            film.1
        );
        out!("{}", tree.to_text());
        outln!(
            "{} rays traced ({} camera, {} reflected or refracted, {} shadow); the sample's colour is ({}, {}, {}) in linear RGB",
            rays.camera + rays.secondary + rays.shadow,
            rays.camera,
            rays.secondary,
            rays.shadow,
            color.x,
            color.y,
            color.z
        );
    }
    ExitCode::SUCCESS
}

/// `explain` under the path tracer: the one path of sample `k`, as the renderer takes it.
fn explain_path(args: &ExplainArgs, scene: &snell::Scene, k: u32) -> ExitCode {
    let s = &scene.settings;
    let (x, y) = args.pixel;
    let explained = snell::explain_pixel::path(scene, (x, y), k);
    let doc = explained.to_json(scene, &args.scene);
    let (rec, color, rays, (px, py)) = (
        &explained.record,
        explained.color,
        &explained.rays,
        explained.film,
    );
    let total = rec.total();
    let clamped = s.integrator.clamp.filter(|c| total.iter().any(|t| t > c));
    if args.json {
        match serde_json::to_string_pretty(&doc) {
            Ok(text) => outln!("{text}"),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(1);
            }
        }
        return ExitCode::SUCCESS;
    }
    outln!(
        "pixel {x},{y} of {} ({} x {}), path-traced sample {k} of {}, film position ({px}, {py}):",
        args.scene.display(),
        s.width,
        s.height,
        s.spp
    );
    out!("{}", rec.to_text());
    let clamp_note = match clamped {
        Some(c) => format!(
            ", clamped to {c} per channel from ({}, {}, {})",
            total[0], total[1], total[2]
        ),
        None => String::new(),
    };
    outln!(
        "{} traced ({} camera, {}, {} shadow); the sample's value, the sum of what the vertices add, is ({}, {}, {}) in linear RGB{clamp_note}",
        crate::count(rays.camera + rays.secondary + rays.shadow, "ray"),
        rays.camera,
        crate::count(rays.secondary, "bounce"),
        rays.shadow,
        color.x,
        color.y,
        color.z
    );
    ExitCode::SUCCESS
}

/// `explain` of a bidirectional sample: every strategy that carried light, with its weight.
fn explain_bdpt(args: &ExplainArgs, scene: &snell::Scene, k: u32) -> ExitCode {
    let s = &scene.settings;
    let (x, y) = args.pixel;
    let explained = snell::explain_pixel::bdpt(scene, (x, y), k);
    if args.json {
        match serde_json::to_string_pretty(&explained.to_json(scene, &args.scene)) {
            Ok(text) => outln!("{text}"),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(1);
            }
        }
        return ExitCode::SUCCESS;
    }
    let (px, py) = explained.film;
    outln!(
        "pixel {x},{y} of {} ({} x {}), bidirectional sample {k} of {}, film position ({px}, {py}), {:?} heuristic:",
        args.scene.display(),
        s.width,
        s.height,
        s.spp,
        s.integrator.mis
    );
    out!("{}", explained.to_text());
    let (r, c) = (&explained.rays, explained.color);
    outln!(
        "{} traced ({} camera, {}, {} shadow); the sample adds ({}, {}, {}) to its pixel in linear RGB, and each light path joined to the eye where it lands",
        crate::count(r.camera + r.secondary + r.shadow, "ray"),
        r.camera,
        crate::count(r.secondary, "bounce"),
        r.shadow,
        c.x,
        c.y,
        c.z
    );
    ExitCode::SUCCESS
}
