//! Where a pixel sample's random numbers come from: a `Sampler` is started at one sample of
//! one pixel and then hands out numbers in `[0, 1)`, one or two at a time, each request
//! taking the next dimension. The same (seed, pixel, sample index) gives the same numbers
//! whichever thread asks, so renders stay the same bytes at any thread count. Any number of
//! samples per pixel: nothing here needs a square.

mod independent;
mod sobol;

pub use independent::Independent;
pub use sobol::Sobol;

use crate::math::Vec2;

/// The kinds of sampler, chosen once per render.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplerKind {
    /// Independent uniform numbers.
    Independent,
    /// Owen-scrambled Sobol points, each pair of dimensions stratified.
    Sobol,
}

/// A sampler, closed set, dispatched by `match`.
// The Sobol sampler carries its pixel's scrambles (about half a kilobyte); a sampler is made
// once a pixel, on the stack, and a box would cost an allocation a pixel instead.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub enum Sampler {
    /// Independent uniform numbers.
    Independent(Independent),
    /// Owen-scrambled Sobol points.
    Sobol(Sobol),
}

impl Sampler {
    /// A sampler of `kind` for the render seeded by `seed`.
    pub fn new(kind: SamplerKind, seed: u64) -> Self {
        match kind {
            SamplerKind::Independent => Sampler::Independent(Independent::new(seed)),
            SamplerKind::Sobol => Sampler::Sobol(Sobol::new(seed)),
        }
    }

    /// Starts sample `index` of pixel `(x, y)`, from its first dimension.
    pub fn start(&mut self, x: u32, y: u32, index: u32) {
        match self {
            Sampler::Independent(s) => s.start(x, y, index),
            Sampler::Sobol(s) => s.start(x, y, index),
        }
    }

    /// The next number, in `[0, 1)`.
    pub fn next_1d(&mut self) -> f32 {
        match self {
            Sampler::Independent(s) => s.next_1d(),
            Sampler::Sobol(s) => s.next_1d(),
        }
    }

    /// The next two numbers, each in `[0, 1)` (for a pixel position, a lens, a direction).
    pub fn next_2d(&mut self) -> Vec2 {
        match self {
            Sampler::Independent(s) => s.next_2d(),
            Sampler::Sobol(s) => s.next_2d(),
        }
    }

    /// A number in `[0, 1)` for a discrete choice (which light, which lobe, whether Russian
    /// roulette ends the path), which gains little from stratification: Sobol hands out
    /// independent numbers here, at a quarter of a dimension's cost; it takes no dimension.
    pub fn next_choice(&mut self) -> f32 {
        match self {
            Sampler::Independent(s) => s.next_choice(),
            Sampler::Sobol(s) => s.next_choice(),
        }
    }

    /// The next four numbers, each in `[0, 1)`, taken together: the first two a pair as
    /// [`Sampler::next_2d`]'s (a direction), the others for choices (a lobe, a light,
    /// Russian roulette).
    pub fn next_4d(&mut self) -> [f32; 4] {
        match self {
            Sampler::Independent(s) => s.next_4d(),
            Sampler::Sobol(s) => s.next_4d(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::chi2::chi2_square;

    fn both() -> [Sampler; 2] {
        [
            Sampler::new(SamplerKind::Independent, 7),
            Sampler::new(SamplerKind::Sobol, 7),
        ]
    }

    #[test]
    fn the_same_sample_gives_the_same_numbers_and_others_differ() {
        for mut s in both() {
            let mut take = |x, y, i| {
                s.start(x, y, i);
                [s.next_1d(), s.next_2d().x, s.next_2d().y, s.next_1d()]
            };
            let a = take(3, 4, 5);
            assert_eq!(a, take(3, 4, 5));
            assert_ne!(a, take(4, 3, 5));
            assert_ne!(a, take(3, 4, 6));
            assert!(a.iter().all(|v| (0.0..1.0).contains(v)), "{a:?}");
        }
        let mut a = Sampler::new(SamplerKind::Sobol, 1);
        let mut b = Sampler::new(SamplerKind::Sobol, 2);
        a.start(0, 0, 0);
        b.start(0, 0, 0);
        assert_ne!(
            a.next_2d(),
            b.next_2d(),
            "the render's seed changes the points"
        );
    }

    /// Over many pixels and samples, every dimension pair is uniform on the square.
    #[test]
    fn every_dimension_is_uniform() {
        for mut s in both() {
            for dim in [0usize, 3] {
                let (mut pixel, mut index) = (0u32, 0u32);
                chi2_square(
                    &format!("{s:?} dimension pair {dim}"),
                    16,
                    |_| {
                        index += 1;
                        if index == 64 {
                            (pixel, index) = (pixel + 1, 0);
                        }
                        s.start(pixel % 97, pixel / 97, index);
                        for _ in 0..dim {
                            s.next_2d();
                        }
                        Some(s.next_2d())
                    },
                    |_| 1.0,
                )
                .unwrap();
            }
        }
    }
}
