//! `snell explain`: the tree of rays behind one sample of one pixel.

use crate::args::ExplainArgs;
use crate::{check_size_and_spp, load, usage_error};
use snell::integrator::Whitted;
use snell::integrator::explain::TreeRecorder;
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
    let path = s.integrator.kind == snell::scene::IntegratorKind::Path;
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
        Some(k) => {
            let mut at = (0.0, 0.0);
            let mut i = 0;
            snell::render::for_each_sample(s, x, y, |px, py, _| {
                if i == k {
                    at = (px, py);
                }
                i += 1;
            });
            at
        }
    };
    if path {
        return explain_path(&args, &scene, args.sample.unwrap_or(0));
    }
    let lens = args
        .sample
        .map(|k| snell::render::whitted_lens_sample(s, x, y, k));
    let Some((color, rays, tree)) = whitted_tree(&scene, film, lens, args.max_rays) else {
        eprintln!("error: no ray was recorded");
        return ExitCode::from(1);
    };
    let which = match args.sample {
        None => "the ray through its centre".to_string(),
        Some(k) => format!("sample {k} of {}", scene.settings.spp),
    };
    if args.json {
        let doc = whitted_json(
            &scene,
            &args.scene,
            (x, y),
            args.sample,
            film,
            color,
            &rays,
            &tree,
        );
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

/// The Whitted tree of the ray through film position `film` (and the lens at `lens`, if the
/// camera has one; its centre without): the colour it returns, the rays traced, and the
/// tree (`None` when nothing was recorded).
pub(crate) fn whitted_tree(
    scene: &snell::Scene,
    film: (f32, f32),
    lens: Option<snell::math::Vec2>,
    max_rays: usize,
) -> Option<(
    snell::math::Color,
    snell::integrator::RayStats,
    snell::integrator::explain::RayNode,
)> {
    let s = &scene.settings;
    let camera = scene.camera.raster(s.width, s.height);
    let ray = match lens {
        Some(u) => camera.ray_lens(film.0, film.1, u),
        None => camera.ray(film.0, film.1),
    };
    let mut rec = TreeRecorder::new(max_rays);
    let mut rays = snell::integrator::RayStats::default();
    let color = Whitted.explain(scene, &ray, &mut rays, &mut rec);
    rec.finish().map(|tree| (color, rays, tree))
}

/// `explain --json`'s document for a Whitted tree.
#[allow(clippy::too_many_arguments)]
pub(crate) fn whitted_json(
    scene: &snell::Scene,
    scene_path: &std::path::Path,
    pixel: (u32, u32),
    sample: Option<u32>,
    film: (f32, f32),
    color: snell::math::Color,
    rays: &snell::integrator::RayStats,
    tree: &snell::integrator::explain::RayNode,
) -> serde_json::Value {
    serde_json::json!({
        "scene": scene_path.display().to_string(),
        "integrator": "whitted",
        "image": [scene.settings.width, scene.settings.height],
        "pixel": [pixel.0, pixel.1],
        "sample": sample,
        "film_position": [film.0, film.1],
        "color": color.to_array(),
        "rays_traced": { "camera": rays.camera, "secondary": rays.secondary, "shadow": rays.shadow },
        "tree": tree,
    })
}

/// The one path of sample `k` of pixel `(x, y)` under the path tracer, as `explain --json`
/// gives it, with the path's record (for the text form).
pub(crate) fn path_json(
    scene: &snell::Scene,
    scene_path: &std::path::Path,
    (x, y): (u32, u32),
    k: u32,
) -> (
    serde_json::Value,
    snell::integrator::path_explain::PathRecord,
    snell::math::Color,
    snell::integrator::RayStats,
    (f32, f32),
) {
    use snell::integrator::Path;
    use snell::integrator::path_explain::PathRecord;
    let s = &scene.settings;
    let mut sampler = snell::sampler::Sampler::new(s.integrator.sampler, s.seed);
    let (px, py, _) = snell::render::start_sample(s, &mut sampler, x, y, k);
    let camera = scene.camera.raster(s.width, s.height);
    let ray = snell::render::camera_ray(&camera, &mut sampler, px, py);
    let mut rays = snell::integrator::RayStats::default();
    let mut rec = PathRecord::default();
    let color = Path.trace(scene, &ray, &mut sampler, &mut rays, &mut rec);
    let doc = serde_json::json!({
        "scene": scene_path.display().to_string(),
        "integrator": "path",
        "image": [s.width, s.height],
        "pixel": [x, y],
        "sample": k,
        "film_position": [px, py],
        "color": color.to_array(),
        "sum_of_contributions": rec.total(),
        "clamp": s.integrator.clamp,
        "rays_traced": { "camera": rays.camera, "secondary": rays.secondary, "shadow": rays.shadow },
        "path": &rec,
    });
    (doc, rec, color, rays, (px, py))
}

/// `explain` under the path tracer: the one path of sample `k`, as the renderer takes it.
fn explain_path(args: &ExplainArgs, scene: &snell::Scene, k: u32) -> ExitCode {
    let s = &scene.settings;
    let (x, y) = args.pixel;
    let (doc, rec, color, rays, (px, py)) = path_json(scene, &args.scene, (x, y), k);
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
