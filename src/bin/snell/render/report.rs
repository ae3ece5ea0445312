//! What a render tells its user beside the picture: the warning before a render of over
//! an hour, the closing line (what was written, how many samples, how fast), the warning
//! about NaN or infinite samples, and the `--stats` report.

use super::Outcome;
use snell::render::Region;
use snell::scene::RenderSettings;
use std::path::Path;

/// Renders estimated at over an hour are told so before they start, with what would
/// shorten them; `time` (a `--time` cap) bounds the estimate where the path tracer's
/// passes honour it.
pub(super) fn warn_if_long(
    scene: &snell::Scene,
    threads: Option<usize>,
    time: Option<std::time::Duration>,
) {
    use snell::render::estimate::{PROBE_FROM_SAMPLES, in_words, render_time};
    let s = &scene.settings;
    if (s.width as u64) * (s.height as u64) * (s.spp as u64) < PROBE_FROM_SAMPLES {
        return;
    }
    let threads = threads.unwrap_or_else(rayon::current_num_threads);
    let integrator = snell::integrator::chosen(scene.settings.integrator.kind);
    if time.is_some_and(|t| t.as_secs_f64() <= 3600.0) && integrator.uses_sampler() {
        return;
    }
    let e = render_time(scene, integrator, threads);
    if e.seconds > 3600.0 {
        eprintln!(
            "warning: this render will take about {} on {threads} threads ({} x {} at {} spp, about {:.2} M samples/s from a probe of {} samples); Ctrl-C stops it and writes what is done",
            in_words(e.seconds),
            s.width,
            s.height,
            s.spp,
            e.samples_per_second / 1e6,
            e.probe_samples
        );
        eprintln!(
            "  help: fewer samples (--spp) or a smaller image (--width, --height) shorten it; --spp 1 at a quarter of the size gives a quick preview"
        );
    }
}

/// The closing line of a whole render: the file written, its size (a region's, where
/// one was rendered), its samples (those of this run, where it resumed one), how fast they
/// came, and the estimated error where the passes estimated one.
pub(super) fn print_written(
    out_path: &Path,
    region: Option<Region>,
    settings: &RenderSettings,
    outcome: &Outcome,
    elapsed: f64,
    threads: Option<usize>,
) {
    let spp = settings.spp;
    let (w, h, pixels) = match region {
        Some(r) => (r.width(), r.height(), r.pixels()),
        None => (
            settings.width,
            settings.height,
            settings.width as u64 * settings.height as u64,
        ),
    };
    let samples = match &outcome.adaptive {
        Some(a) => a.total,
        None => pixels * outcome.spp as u64,
    };
    // A resumed render's rate counts only the samples rendered in this run.
    let resumed_part = if outcome.samples < samples {
        format!(" ({} of them in this run)", outcome.samples)
    } else {
        String::new()
    };
    let error = outcome
        .error
        .map(|e| format!("; estimated error {:.2} %", 100.0 * e))
        .unwrap_or_default();
    let spp_words = match &outcome.adaptive {
        Some(a) => format!(
            "{} to {} spp ({:.1} on average, {:.1} % of pixels below {} % noise)",
            a.fewest,
            a.most,
            a.total as f64 / a.pixels.max(1) as f64,
            a.share(),
            (100.0 * a.noise as f64 * 1e4).round() / 1e4
        ),
        None => format!("{} spp", outcome.spp),
    };
    outln!(
        "wrote {}: {w} x {h}, {spp_words}{}, {samples} samples{resumed_part} in {elapsed:.2} s ({:.2} M samples/s, {} threads){error}",
        out_path.display(),
        if outcome.spp < spp && outcome.adaptive.is_none() {
            format!(" (--time stopped it short of {spp})")
        } else {
            String::new()
        },
        outcome.samples as f64 / elapsed.max(1e-9) / 1e6,
        threads.unwrap_or_else(rayon::current_num_threads),
    );
}

/// The warning about samples that came out NaN or infinite (left out of their pixels),
/// with the first few places they came from and how to look into one; nothing where
/// there were none.
pub(super) fn warn_bad_samples(scene: &snell::Scene, bad: &snell::render::BadSamples) {
    if bad.count == 0 {
        return;
    }
    let places: Vec<String> = bad
        .examples
        .iter()
        .take(3)
        .map(|b| {
            let what = match b.object {
                Some(i) => format!("object `{}`", scene.objects[i].name),
                None => "the background".to_string(),
            };
            let kind = if b.nan { "NaN" } else { "infinite" };
            format!("pixel ({}, {}) on {what} ({kind})", b.x, b.y)
        })
        .collect();
    eprintln!(
        "warning: {} samples came out NaN or infinite and were left out of their pixels; {}: {}",
        bad.count,
        if bad.count as usize > places.len() {
            "the first"
        } else {
            "at"
        },
        places.join("; ")
    );
    eprintln!(
        "  help: look for huge or extreme values in those objects' materials and lights, and run `snell explain SCENE --pixel X,Y` on one of them"
    );
}

/// The `--stats` report.
pub(super) fn print_stats(
    s: &snell::scene::BuildStats,
    load_time: std::time::Duration,
    rays: &snell::integrator::RayStats,
    render_secs: f64,
) {
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    let mib = |b: usize| b as f64 / (1u64 << 20) as f64;
    outln!(
        "scene:     {} objects; {} mesh(es), {} triangles ({} placed); loaded and built in {:.1} ms",
        s.objects,
        s.meshes,
        s.unique_triangles,
        s.instanced_triangles,
        ms(load_time)
    );
    outln!(
        "build:     mesh files read in {:.1} ms, mesh BVHs built in {:.1} ms, object BVH in {:.2} ms",
        ms(s.mesh_load_time),
        ms(s.mesh_bvh_time),
        ms(s.object_bvh_time)
    );
    let per_triangle = if s.unique_triangles > 0 {
        format!(
            " ({:.1} bytes per triangle)",
            s.bvh_bytes as f64 / s.unique_triangles as f64
        )
    } else {
        String::new()
    };
    outln!(
        "memory:    BVHs {:.2} MiB{per_triangle}, mesh data {:.2} MiB",
        mib(s.bvh_bytes),
        mib(s.mesh_bytes)
    );
    let rate = |n: u64| n as f64 / render_secs.max(1e-9) / 1e6;
    outln!(
        "rays:      {:.2} M in {render_secs:.2} s: {:.2} M rays/s",
        rays.total() as f64 / 1e6,
        rate(rays.total())
    );
    for (kind, n) in [
        ("camera", rays.camera),
        ("secondary", rays.secondary),
        ("shadow", rays.shadow),
    ] {
        outln!(
            "  {kind:<10} {:>8.2} M  {:>7.2} M/s of render time",
            n as f64 / 1e6,
            rate(n)
        );
    }
}
