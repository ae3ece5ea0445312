//! Whitted's render (and a resumed checkpoint of tiles): every sample of each pixel at
//! once, tile by tile, with checkpoints of the finished tiles saved from a thread of
//! their own.

use super::{Outcome, Run, STOP};
use snell::render::{RenderOptions, TileStore};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// Every sample of each pixel at once, tile by tile (Whitted, whose strata are fixed by the
/// sample count, and a resumed checkpoint of tiles), from `earlier` tiles on, with
/// checkpoints saved from a thread of their own.
pub(super) fn render_tiles(
    run: &Run,
    earlier: std::collections::BTreeMap<u32, Vec<snell::math::Color>>,
) -> Result<Outcome, String> {
    let store = TileStore::new(earlier);
    let finished = AtomicBool::new(false);
    let rendered = std::thread::scope(|scope| {
        if let Some(path) = run.checkpoint {
            let (store, finished) = (&store, &finished);
            let (every, saver) = (run.every, run.saver);
            scope.spawn(move || {
                let mut last = Instant::now();
                while !finished.load(Ordering::SeqCst) {
                    std::thread::sleep(std::time::Duration::from_millis(50));
                    if last.elapsed() >= every {
                        if let Err(e) = saver.checkpoint(store.snapshot(), None).save(path) {
                            eprintln!(
                                "warning: cannot save the checkpoint {}: {e}",
                                path.display()
                            );
                        }
                        last = Instant::now();
                    }
                }
            });
        }
        let options = RenderOptions {
            threads: run.threads,
            progress: &|n| run.bar.set_position(n),
            cancel: Some(&STOP),
            region: run.region,
        };
        // Tiles are kept (a copy of the picture) only for a checkpoint to save: a resumed
        // render has one too.
        let kept = run.checkpoint.map(|_| &store);
        let r = snell::render::render_with(run.scene, run.integrator, &options, kept);
        finished.store(true, Ordering::SeqCst);
        r
    })
    .map_err(|e| e.to_string())?;
    let spp = run.scene.settings.spp;
    // Only an unfinished render's checkpoint is saved.
    let checkpoint = (run.checkpoint.is_some() && !rendered.complete())
        .then(|| run.saver.checkpoint(store.snapshot(), None));
    Ok(Outcome {
        complete: rendered.complete(),
        spp,
        samples: rendered.pixels_rendered * spp as u64,
        done: format!(
            "{} of {} tiles rendered (the rest are black)",
            rendered.tiles_done, rendered.tiles_total
        ),
        checkpoint,
        image: rendered.image,
        rays: rendered.rays,
        bad_samples: rendered.bad_samples,
        error: None,
        film: None,
        layers: vec![],
        adaptive: None,
    })
}
