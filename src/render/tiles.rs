//! The one render loop: a film's tiles handed to the threads one at a time, in a scattered
//! order, with progress, cancellation and tiles to skip. Every way of filling a film goes
//! through it: a whole render, a pass of some more samples, and the debug views.

use super::{RenderError, RenderOptions};
use crate::film::Film;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// Calls `work(x, y, pixel, stats)` for every pixel of `film` outside the tiles `skip`
/// names (and of the tiles that share a pixel with `options.region`, if given; progress
/// then counts those tiles' pixels only), each tile on one thread, then `finished(i, tile)`
/// with the tile's pixels. Once `options.cancel` is set, tiles not yet started are left as
/// they were, and a tile under way stops at its next row: each of its pixels is whole or
/// untouched, and the tile is not reported. Returns each tile
/// rendered with what its `stats` gathered, in tile order (so that whatever the stats keep
/// is the same at any thread count).
pub(crate) fn for_each_tile<P, S>(
    film: &mut Film<P>,
    options: &RenderOptions,
    skip: impl Fn(u32) -> bool + Sync,
    work: impl Fn(u32, u32, &mut P, &mut S) + Sync,
    finished: impl Fn(u32, &[P]) + Sync,
) -> Result<Vec<(u32, S)>, RenderError>
where
    P: Send,
    S: Default + Send,
{
    let pool = super::thread_pool(options.threads)?;
    let grid = film.grid();
    let n = grid.count();
    // Progress counts the tiles done before (a resumed render's) as done, and leaves out
    // those outside the region.
    let outside = |i: u32| options.region.is_some_and(|r| !r.overlaps(grid.rect(i)));
    let done = AtomicU64::new(
        (0..n)
            .filter(|&i| skip(i) && !outside(i))
            .map(|i| grid.len(i) as u64)
            .sum(),
    );
    let skip = |i: u32| skip(i) || outside(i);
    // Visit the tiles in a scattered order, so every stretch of work mixes sky and busy
    // regions and the progress bar's ETA holds steady; each tile is its own slice of the
    // film, so the picture does not depend on the order.
    let step = scatter_step(n);
    let mut tiles: Vec<Option<&mut [P]>> = film.tiles_mut().into_iter().map(Some).collect();
    let order: Vec<(u32, &mut [P])> = (0..n)
        .map(|k| {
            let i = ((k as u64 * step as u64) % n as u64) as u32;
            let tile = tiles[i as usize].take();
            (i, tile.expect("the scattered order visits each tile once"))
        })
        .collect();
    let mut rendered: Vec<(u32, S)> = pool.install(|| {
        order
            .into_par_iter()
            // One tile per job: rayon otherwise hands threads long runs of tiles that cannot
            // be split once started, and near the end one core would sit idle while the other
            // finishes its run (a quarter of a second of the seed scene).
            .with_max_len(1)
            .filter_map(|(i, tile)| {
                if skip(i) || options.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                    return None;
                }
                let (x0, y0, x1, _) = grid.rect(i);
                let mut stats = S::default();
                for (row, y) in tile.chunks_exact_mut((x1 - x0) as usize).zip(y0..) {
                    // A tile of many samples a pixel takes seconds: cancellation also stops
                    // one between rows, leaving it unfinished (not reported, not counted):
                    // each pixel is whole or untouched.
                    if options.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                        return None;
                    }
                    for (pixel, x) in row.iter_mut().zip(x0..) {
                        work(x, y, pixel, &mut stats);
                    }
                }
                finished(i, tile);
                let len = tile.len() as u64;
                (options.progress)(done.fetch_add(len, Ordering::Relaxed) + len);
                Some((i, stats))
            })
            .collect()
    });
    rendered.sort_by_key(|(i, _)| *i);
    Ok(rendered)
}

/// A step coprime with `n` near `n / phi`: `k * step mod n` then visits every index once,
/// spread evenly over the range.
fn scatter_step(n: u32) -> u32 {
    fn gcd(a: u32, b: u32) -> u32 {
        if b == 0 { a } else { gcd(b, a % b) }
    }
    let mut step = ((n as f64 / 1.618_034) as u32).max(1);
    while gcd(step, n) != 1 {
        step += 1;
    }
    step
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;
    use std::sync::atomic::AtomicBool;

    #[test]
    fn scattered_order_visits_every_tile_once() {
        for n in [1u32, 2, 7, 64, 100, 4096, 4097] {
            let step = scatter_step(n);
            let mut seen = vec![false; n as usize];
            for k in 0..n {
                let i = ((k as u64 * step as u64) % n as u64) as usize;
                assert!(!seen[i], "n = {n}: tile {i} twice");
                seen[i] = true;
            }
        }
    }

    /// Every pixel outside the skipped tiles gets its own coordinates, once; the skipped
    /// tiles keep what they held; the tiles come back in order with their pixel counts;
    /// progress ends at the whole image, skipped tiles included.
    #[test]
    fn every_pixel_is_visited_once_outside_the_skipped_tiles() {
        let (w, h) = (37, 21);
        let mut film: Film<(u32, u32, u32)> = Film::new(w, h);
        let skipped = |i: u32| i == 1 || i == 4;
        for i in [1, 4] {
            film.tile_mut(i).fill((7, 7, 7));
        }
        let last = AtomicU64::new(0);
        let finished = Mutex::new(vec![]);
        let progress = |n| {
            last.fetch_max(n, Ordering::Relaxed);
        };
        let options = RenderOptions {
            threads: Some(2),
            progress: &progress,
            cancel: None,
            region: None,
        };
        let tiles = for_each_tile(
            &mut film,
            &options,
            skipped,
            |x, y, p: &mut (u32, u32, u32), count: &mut u32| {
                *p = (x, y, p.2 + 1);
                *count += 1;
            },
            |i, t| finished.lock().unwrap().push((i, t.len())),
        )
        .unwrap();
        let grid = film.grid();
        let want: Vec<u32> = (0..grid.count()).filter(|&i| !skipped(i)).collect();
        assert_eq!(tiles.iter().map(|t| t.0).collect::<Vec<_>>(), want);
        for (i, count) in &tiles {
            assert_eq!(*count as usize, grid.len(*i));
        }
        assert_eq!(finished.lock().unwrap().len(), want.len());
        assert_eq!(last.load(Ordering::Relaxed), (w * h) as u64);
        for y in 0..h {
            for x in 0..w {
                let i = (y / 16) * grid.tiles_x() + x / 16;
                let p = *film.get(x, y);
                if skipped(i) {
                    assert_eq!(p, (7, 7, 7));
                } else {
                    assert_eq!(p, (x, y, 1), "pixel ({x}, {y})");
                }
            }
        }
        // Cancelled before it starts: nothing is touched.
        let stop = AtomicBool::new(true);
        let options = RenderOptions {
            cancel: Some(&stop),
            region: None,
            ..options
        };
        let before = film.clone();
        let none = for_each_tile(
            &mut film,
            &options,
            |_| false,
            |_, _, p, _: &mut ()| p.2 += 1,
            |_, _| {},
        )
        .unwrap();
        assert!(none.is_empty());
        assert_eq!(film, before);
    }
}
