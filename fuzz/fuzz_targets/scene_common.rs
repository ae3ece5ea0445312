// Shared by the scene_toml and scene_json targets (included with `include!`, so each target
// stays one file that cargo fuzz can build on its own).

use snell::integrator::{Integrator, RayStats, Whitted};
use snell::scene::{Format, load_str, load_str_frame};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// An empty folder: the scene's relative file references (meshes, textures) resolve into it
/// and fail cleanly, the way a missing file does for a user.
fn empty_dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("snell-fuzz-empty-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("create the fuzzer's empty folder");
        dir
    })
}

/// Loads `data` as a scene; errors must render to text without panicking, and a scene that
/// loads must answer a few camera rays.
fn check_scene(data: &[u8], format: Format, name: &str) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    // Absolute or parent paths could reach devices (/dev/zero never ends): not what is tested.
    if text.contains("dev") || text.contains("proc") || text.contains("sys") {
        return;
    }
    match load_str(text, Path::new(name), empty_dir(), format) {
        Err(e) => {
            // Locating spans in the source and drawing the report (as `snell check` does)
            // must not panic either.
            let _ = e.to_string();
            let handler = miette::GraphicalReportHandler::new_themed(
                miette::GraphicalTheme::unicode_nocolor(),
            );
            for d in &e.diagnostics {
                let mut out = String::new();
                let _ = handler.render_report(&mut out, d);
            }
        }
        Ok(mut scene) => {
            let _ = scene.summary();
            // An animation's other frames put its keys' curves into the scene: the middle
            // one and the last build (or are refused) without panicking too.
            if let Some(a) = scene.animation {
                for frame in [a.frames / 2, a.frames - 1] {
                    let _ = load_str_frame(text, Path::new(name), empty_dir(), format, frame)
                        .map(|s| s.summary());
                }
            }
            // Whitted splits a ray at every glass surface, so the work grows as 2^depth: keep
            // the depth small so each input stays quick.
            scene.settings.max_depth = scene.settings.max_depth.min(5);
            let (w, h) = (scene.settings.width, scene.settings.height);
            let mut rays = RayStats::default();
            for (x, y) in [
                (0.5, 0.5),
                (w as f32 * 0.5, h as f32 * 0.5),
                (w as f32 - 0.5, h as f32 - 0.5),
            ] {
                let ray = scene.camera.ray(x, y, w, h);
                let _ = Whitted.radiance(&scene, &ray, &mut rays);
                let _ = scene.closest_hit_with_uv(&ray, f32::INFINITY, snell::scene::Skip::NONE);
            }
        }
    }
}
