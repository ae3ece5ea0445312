//! A rectangle of an image's pixels, rendered alone (`snell render --region`): the same
//! pixels, bit for bit, as the same part of a whole render, since every pixel's samples are
//! seeded by the pixel itself and land in it alone.

use super::Image;

/// Columns `x0..x1` and rows `y0..y1` of an image (ends exclusive, pixel (0, 0) at the top
/// left).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// One past the last column.
    pub x1: u32,
    /// One past the last row.
    pub y1: u32,
}

impl Region {
    /// `X0,Y0,X1,Y1`, as the command line gives it.
    pub fn parse(s: &str) -> Result<Region, String> {
        let parts: Vec<&str> = s.split(',').map(str::trim).collect();
        let [x0, y0, x1, y1] = parts[..] else {
            return Err(format!(
                "a region is X0,Y0,X1,Y1 (four whole numbers: its first column and row, and one past its last), not `{s}`"
            ));
        };
        let n = |v: &str| {
            v.parse::<u32>()
                .map_err(|_| format!("`{v}` is not a pixel coordinate (a whole number, 0 or more)"))
        };
        let r = Region {
            x0: n(x0)?,
            y0: n(y0)?,
            x1: n(x1)?,
            y1: n(y1)?,
        };
        if r.x1 <= r.x0 || r.y1 <= r.y0 {
            return Err(format!(
                "the region {s} is empty: X1 must be greater than X0 and Y1 than Y0"
            ));
        }
        Ok(r)
    }

    /// An error unless the region lies within an image of `width` x `height`.
    pub fn check(&self, width: u32, height: u32) -> Result<(), String> {
        if self.x1 > width || self.y1 > height {
            return Err(format!(
                "the region {},{},{},{} reaches past the {width} x {height} image",
                self.x0, self.y0, self.x1, self.y1
            ));
        }
        Ok(())
    }

    /// Its width in pixels.
    pub fn width(&self) -> u32 {
        self.x1 - self.x0
    }

    /// Its height in pixels.
    pub fn height(&self) -> u32 {
        self.y1 - self.y0
    }

    /// Pixels in it.
    pub fn pixels(&self) -> u64 {
        self.width() as u64 * self.height() as u64
    }

    /// Whether it shares a pixel with the rectangle `(x0, y0, x1, y1)`.
    pub fn overlaps(&self, (x0, y0, x1, y1): (u32, u32, u32, u32)) -> bool {
        self.x0 < x1 && x0 < self.x1 && self.y0 < y1 && y0 < self.y1
    }

    /// Its pixels of `img`, which it must lie within.
    pub fn crop(&self, img: &Image) -> Image {
        let mut out = Image::new(self.width(), self.height());
        for (row, y) in out
            .pixels
            .chunks_exact_mut(self.width() as usize)
            .zip(self.y0..)
        {
            let from = (y * img.width + self.x0) as usize;
            row.copy_from_slice(&img.pixels[from..from + self.width() as usize]);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Color;

    #[test]
    fn regions_parse_and_are_checked() {
        let r = Region::parse("2, 3,10,7").unwrap();
        assert_eq!((r.x0, r.y0, r.x1, r.y1), (2, 3, 10, 7));
        assert_eq!((r.width(), r.height(), r.pixels()), (8, 4, 32));
        assert!(r.check(10, 7).is_ok());
        assert!(
            r.check(9, 7)
                .unwrap_err()
                .contains("reaches past the 9 x 7 image")
        );
        assert!(Region::parse("1,2,3").unwrap_err().contains("X0,Y0,X1,Y1"));
        assert!(Region::parse("4,0,4,5").unwrap_err().contains("is empty"));
        assert!(Region::parse("-1,0,4,5").unwrap_err().contains("`-1`"));
        assert!(r.overlaps((0, 0, 3, 4)));
        assert!(!r.overlaps((10, 0, 16, 16)));
        assert!(!r.overlaps((0, 7, 16, 16)));
    }

    #[test]
    fn a_crop_takes_the_regions_pixels() {
        let mut img = Image::new(5, 4);
        for (i, p) in img.pixels.iter_mut().enumerate() {
            *p = Color::splat(i as f32);
        }
        let c = Region::parse("1,2,4,4").unwrap().crop(&img);
        assert_eq!((c.width, c.height), (3, 2));
        let got: Vec<f32> = c.pixels.iter().map(|p| p.x).collect();
        assert_eq!(got, vec![11.0, 12.0, 13.0, 16.0, 17.0, 18.0]);
    }
}
