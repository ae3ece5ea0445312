//! Independent uniform numbers: a fresh generator for each pixel sample, seeded from
//! (render seed, pixel, sample index).

use crate::math::{Rng, Vec2, hash_seed};

/// Independent uniform numbers.
#[derive(Clone, Debug)]
pub struct Independent {
    seed: u64,
    rng: Rng,
}

impl Independent {
    /// A sampler for the render seeded by `seed`.
    pub fn new(seed: u64) -> Self {
        Independent {
            seed,
            rng: Rng::new(seed),
        }
    }

    /// Starts sample `index` of pixel `(x, y)`.
    pub fn start(&mut self, x: u32, y: u32, index: u32) {
        self.rng = Rng::new(hash_seed(&[self.seed, x as u64, y as u64, index as u64]));
    }

    /// The next number.
    pub fn next_1d(&mut self) -> f32 {
        self.rng.next_f32()
    }

    /// The next two numbers.
    pub fn next_2d(&mut self) -> Vec2 {
        Vec2::new(self.rng.next_f32(), self.rng.next_f32())
    }

    /// A number for a discrete choice: the next number.
    pub fn next_choice(&mut self) -> f32 {
        self.rng.next_f32()
    }

    /// The next four numbers.
    pub fn next_4d(&mut self) -> [f32; 4] {
        std::array::from_fn(|_| self.rng.next_f32())
    }
}
