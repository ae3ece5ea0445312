//! How an image is cut into square tiles: the unit of work the render loop hands a thread,
//! of cancellation and of a checkpoint. A film keeps its pixels tile by tile (each tile row
//! by row), so that a tile is one contiguous slice a thread can own.

/// Side of a square tile, in pixels. Tiles on the right and bottom edges are cut short.
pub const TILE: u32 = 16;

/// The tiles of a `width` x `height` image, numbered row by row from the top left.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileGrid {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

impl TileGrid {
    /// Tiles across.
    pub fn tiles_x(&self) -> u32 {
        self.width.div_ceil(TILE)
    }

    /// How many tiles.
    pub fn count(&self) -> u32 {
        self.tiles_x() * self.height.div_ceil(TILE)
    }

    /// How many tiles share a pixel with `region` (all of them where `None`).
    pub fn tiles_in(&self, region: Option<super::Region>) -> u32 {
        match region {
            None => self.count(),
            Some(r) => (0..self.count())
                .filter(|&i| r.overlaps(self.rect(i)))
                .count() as u32,
        }
    }

    /// Pixels in the tiles that share a pixel with `region` (all where `None`).
    pub fn pixels_in(&self, region: Option<super::Region>) -> u64 {
        (0..self.count())
            .filter(|&i| region.is_none_or(|r| r.overlaps(self.rect(i))))
            .map(|i| self.len(i) as u64)
            .sum()
    }

    /// Tile `i`'s pixels: columns `x0..x1`, rows `y0..y1`, as `(x0, y0, x1, y1)`.
    pub fn rect(&self, i: u32) -> (u32, u32, u32, u32) {
        let tx = self.tiles_x();
        let (x0, y0) = ((i % tx) * TILE, (i / tx) * TILE);
        (
            x0,
            y0,
            (x0 + TILE).min(self.width),
            (y0 + TILE).min(self.height),
        )
    }

    /// Pixels in tile `i`.
    pub fn len(&self, i: u32) -> usize {
        let (x0, y0, x1, y1) = self.rect(i);
        ((x1 - x0) * (y1 - y0)) as usize
    }

    /// Where tile `i` starts in tile-by-tile order: the full bands of tiles above it, then
    /// the tiles to its left in its own band (all as tall as it).
    pub fn start(&self, i: u32) -> usize {
        let (x0, y0, _, y1) = self.rect(i);
        y0 as usize * self.width as usize + x0 as usize * (y1 - y0) as usize
    }

    /// Where pixel `(x, y)` is in tile-by-tile order: [`TileGrid::start`] of its tile plus
    /// its place in the tile, without a division.
    #[inline]
    pub fn index(&self, x: u32, y: u32) -> usize {
        let (x0, y0) = (x - x % TILE, y - y % TILE);
        let tile_w = (self.width - x0).min(TILE) as usize;
        let tile_h = (self.height - y0).min(TILE) as usize;
        y0 as usize * self.width as usize
            + x0 as usize * tile_h
            + (y - y0) as usize * tile_w
            + (x - x0) as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tiles cover the image once, in order: each starts where the one before ends, and
    /// every pixel's index falls in its own tile, different from every other pixel's.
    #[test]
    fn tiles_cover_the_image_once_in_order() {
        for (w, h) in [(1, 1), (16, 16), (17, 5), (40, 33), (100, 16), (3, 70)] {
            let g = TileGrid {
                width: w,
                height: h,
            };
            let mut next = 0;
            for i in 0..g.count() {
                assert_eq!(g.start(i), next, "{w} x {h}, tile {i}");
                next += g.len(i);
            }
            assert_eq!(next, (w * h) as usize);
            let mut seen = vec![false; next];
            for y in 0..h {
                for x in 0..w {
                    let k = g.index(x, y);
                    assert!(!seen[k], "{w} x {h}: ({x}, {y}) shares {k}");
                    seen[k] = true;
                    let i = (y / TILE) * g.tiles_x() + x / TILE;
                    assert!((g.start(i)..g.start(i) + g.len(i)).contains(&k));
                }
            }
        }
    }
}
