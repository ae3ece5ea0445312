//! Owen-scrambled Sobol points (Burley, "Practical Hash-based Owen Scrambling", 2020), padded:
//! every request, one number or two, draws the first dimensions of a Sobol sequence of its
//! own, scrambled and shuffled by a hash of (render seed, pixel, request), so that each pair
//! is a stratified (0, 2)-sequence over a pixel's samples and the pairs are independent of
//! one another. Up to 2^16 samples a pixel, as many as [`crate::scene::Limits`] allows.

use crate::math::{Rng, Vec2, hash_seed};

/// Owen-scrambled, padded Sobol points.
#[derive(Clone, Debug)]
pub struct Sobol {
    seed: u64,
    /// The pixel started last, and its seed.
    pixel: Option<(u32, u32)>,
    pixel_seed: u64,
    index: u32,
    dimension: u32,
    /// The sample's own generator, for [`Sobol::next_choice`].
    choices: Rng,
    /// The scrambles of the pixel's first [`KEPT`] requests, which depend on the pixel and
    /// the request but not on the sample: worked out for its first sample, used by the
    /// others. Bit `d` of `known` says whether request `d`'s is there.
    kept: [Scramble; KEPT],
    known: u32,
}

/// Requests whose scrambles a sampler keeps from one sample of a pixel to the next (a path
/// of 16 bounces and its camera take 17).
const KEPT: usize = 24;

/// What a request's seed scrambles a sample with: the sample index's shuffle and the
/// scramble of each of the four dimensions (two hashes, most of a request's work).
#[derive(Clone, Copy, Debug, Default)]
struct Scramble {
    index: u32,
    lanes: [u32; 4],
}

impl Scramble {
    /// The scrambles `sobol_burley::sample_4d` derives from `seed`.
    #[inline]
    fn of(seed: u32) -> Self {
        use sobol_burley::parts::{Int4, hash, hash_int4};
        let scramble: Int4 = [seed.wrapping_mul(0x9c8f_2d3b); 4].into();
        let scramble = scramble ^ [0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8].into();
        let lanes = hash_int4(scramble);
        Scramble {
            index: hash(seed ^ 0x79c6_8e4a),
            lanes: lanes.into(),
        }
    }
}

/// Samples per pixel the sequence holds.
pub const MAX_SAMPLES: u32 = 1 << 16;

impl Sobol {
    /// A sampler for the render seeded by `seed`.
    pub fn new(seed: u64) -> Self {
        Sobol {
            seed,
            pixel: None,
            pixel_seed: 0,
            index: 0,
            dimension: 0,
            choices: Rng::new(seed),
            kept: [Scramble::default(); KEPT],
            known: 0,
        }
    }

    /// Starts sample `index` (below `MAX_SAMPLES`, 65,536; larger ones wrap) of pixel `(x, y)`.
    pub fn start(&mut self, x: u32, y: u32, index: u32) {
        if self.pixel != Some((x, y)) {
            self.pixel = Some((x, y));
            self.pixel_seed = hash_seed(&[self.seed, x as u64, y as u64]);
            self.known = 0;
        }
        self.index = index % MAX_SAMPLES;
        self.dimension = 0;
        self.choices =
            Rng::new(self.pixel_seed ^ (index as u64).wrapping_mul(0xA24B_AED4_963E_E407));
    }

    /// A number for a discrete choice (a light, a lobe, Russian roulette): independent,
    /// from the sample's own generator. A Sobol request costs several of them (the index
    /// shuffled, the points looked up, the scramble); these choices gain little from it.
    #[inline]
    pub fn next_choice(&mut self) -> f32 {
        self.choices.next_f32()
    }

    /// The seed of the next request's own sequence: one splitmix step of the pixel's seed
    /// and the request's number (the crate hashes it again; a full `hash_seed` per request
    /// was a tenth of a Cornell box's time).
    #[inline]
    fn request(&mut self) -> u32 {
        let d = self.dimension as u64 + 1;
        self.dimension += 1;
        let mut z = self
            .pixel_seed
            .wrapping_add(d.wrapping_mul(0x9E37_79B9_7F4A_7C15));
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        (z ^ (z >> 31)) as u32
    }

    /// The next number.
    #[inline]
    pub fn next_1d(&mut self) -> f32 {
        let seed = self.request();
        sobol_burley::sample(self.index, 0, seed)
    }

    /// The next two numbers: a point of a stratified 2D sequence.
    #[inline]
    pub fn next_2d(&mut self) -> Vec2 {
        let [a, b, _, _] = self.next_4d();
        Vec2::new(a, b)
    }

    /// The next four numbers: the first four dimensions of one scrambled Sobol sequence,
    /// computed together (SIMD, and the index shuffled once). The first two are a
    /// stratified pair as [`Sobol::next_2d`]'s; the last two are less well stratified
    /// against them, fit for a lobe choice or Russian roulette.
    #[inline]
    pub fn next_4d(&mut self) -> [f32; 4] {
        let d = self.dimension as usize;
        if d < KEPT && self.known & (1 << d) != 0 {
            self.dimension += 1;
            return sample_4d_scrambled(self.index, &self.kept[d]);
        }
        let scramble = Scramble::of(self.request());
        if d < KEPT {
            self.kept[d] = scramble;
            self.known |= 1 << d;
        }
        sample_4d_scrambled(self.index, &scramble)
    }
}

/// `sobol_burley::sample_4d(index, 0, seed)` (what the tests check against the crate).
#[cfg(test)]
fn sample_4d(index: u32, seed: u32) -> [f32; 4] {
    sample_4d_scrambled(index, &Scramble::of(seed))
}

/// `sobol_burley::sample_4d(index, 0, seed)`, the same numbers, given the scrambles
/// [`Scramble::of`] derives from `seed`, with the Sobol points looked up rather than built
/// bit by bit. The crate XORs one direction vector per set bit of the shuffled index, a
/// loop of up to 16 rounds with a branch no predictor learns; the points are linear in the
/// index's bits, so two tables over its bytes (8 KiB, in L1) give them with one XOR. The
/// shuffle and the scramble around it are the crate's own functions, with its constants; a
/// test checks every index against the crate.
#[inline]
fn sample_4d_scrambled(index: u32, scramble: &Scramble) -> [f32; 4] {
    use sobol_burley::parts::owen_scramble_rev;
    let shuffled_rev = owen_scramble_rev(index.reverse_bits(), scramble.index);
    let tables = &*POINTS;
    let (hi, lo) = (
        (shuffled_rev >> 24) as usize,
        (shuffled_rev >> 16 & 0xff) as usize,
    );
    let [a, b] = [tables[1][hi], tables[0][lo]];
    // The crate's `owen_scramble_int4_rev`, `reverse_bits` and `to_f32_norm`, lane by lane
    // in plain integers, which the compiler puts in one vector as the crate does, but whose
    // bit reversal it can do in two instructions where the processor has GFNI (the crate's
    // own takes fifteen).
    std::array::from_fn(|k| {
        let mut x = a[k] ^ b[k];
        x ^= x.wrapping_mul(0x3d20_adea);
        x = x.wrapping_add(scramble.lanes[k]);
        x = x.wrapping_mul(scramble.lanes[k] >> 16 | 1);
        x ^= x.wrapping_mul(0x0552_6c56);
        x ^= x.wrapping_mul(0x53a2_2864);
        f32::from_bits(x.reverse_bits() >> 9 | 0x3f80_0000) - 1.0
    })
}

/// The first four dimensions' Sobol points (bit-reversed) of each byte of a 16-bit
/// bit-reversed index: `[0]` its low byte (bits 16 to 23), `[1]` its high byte.
static POINTS: std::sync::LazyLock<Box<[[[u32; 4]; 256]; 2]>> = std::sync::LazyLock::new(|| {
    let point = |rev: u32| -> [u32; 4] { sobol_burley::parts::sobol_int4_rev(rev, 0).into() };
    Box::new([
        std::array::from_fn(|b| point((b as u32) << 16)),
        std::array::from_fn(|b| point((b as u32) << 24)),
    ])
});

#[cfg(test)]
mod tests {
    use super::*;

    /// The table lookup gives the crate's numbers, bit for bit, at every index.
    #[test]
    fn table_points_are_the_crates() {
        for seed in [0u32, 1, 0x9e37_79b9, u32::MAX, 12345] {
            for index in 0..MAX_SAMPLES {
                assert_eq!(
                    sample_4d(index, seed),
                    sobol_burley::sample_4d(index, 0, seed),
                    "index {index}, seed {seed}"
                );
            }
        }
    }

    /// The scrambles kept from a pixel's earlier samples give what a fresh sampler gives,
    /// whether the pixel was just started or others came between, and past the requests
    /// kept.
    #[test]
    fn kept_scrambles_give_a_fresh_samplers_numbers() {
        let draw = |s: &mut Sobol, x, y, i| -> Vec<[f32; 4]> {
            s.start(x, y, i);
            (0..KEPT + 4).map(|_| s.next_4d()).collect()
        };
        let mut kept = Sobol::new(9);
        let mut compared = 0;
        for (x, y, i) in [
            (3, 4, 0),
            (3, 4, 1),
            (3, 4, 7),
            (5, 4, 0),
            (3, 4, 2),
            (5, 4, 1),
        ] {
            let fresh = draw(&mut Sobol::new(9), x, y, i);
            assert_eq!(
                draw(&mut kept, x, y, i),
                fresh,
                "pixel ({x}, {y}), sample {i}"
            );
            compared += fresh.len();
        }
        assert_eq!(compared, 6 * (KEPT + 4));
    }

    /// A pixel's first 2^k samples of any request are a (0, k, 2)-net: every box of the
    /// square `2^a` wide and `2^(k - a)` high holds exactly one point. This is what makes
    /// Sobol sampling converge faster than independent numbers.
    #[test]
    fn a_pixels_first_power_of_two_samples_are_stratified_in_every_pair() {
        let mut s = Sobol::new(42);
        for k in [4u32, 6, 8] {
            let n = 1u32 << k;
            for request in 0..4 {
                let points: Vec<Vec2> = (0..n)
                    .map(|i| {
                        s.start(5, 9, i);
                        for _ in 0..request {
                            s.next_2d();
                        }
                        s.next_2d()
                    })
                    .collect();
                for a in 0..=k {
                    let (w, h) = (1u32 << a, 1u32 << (k - a));
                    let mut cells = vec![0u32; n as usize];
                    for p in &points {
                        let (i, j) = ((p.x * w as f32) as u32, (p.y * h as f32) as u32);
                        cells[(j * w + i) as usize] += 1;
                    }
                    assert!(
                        cells.iter().all(|&c| c == 1),
                        "{n} samples, request {request}, boxes {w} x {h}: {cells:?}"
                    );
                }
            }
        }
    }
}
