//! Cut-outs: a surface whose alpha (glTF's `alphaMode`) makes holes in it, as leaves and
//! fences are modelled. A hole is not there at all: rays, shadow rays included, go on
//! through it as if the surface were absent.

use crate::math::{Ray, hash_seed};

/// How a material's alpha makes holes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cutout {
    /// A hole wherever alpha is below `cutoff` (glTF's `MASK`).
    Mask {
        /// Index of the texture whose red channel is alpha.
        texture: usize,
        /// Alpha below which the surface is a hole.
        cutoff: f32,
    },
    /// A hole with chance `1 - alpha` (glTF's `BLEND`, as stochastic transparency: each ray
    /// decides by a hash of itself, so the render stays a function of its seed, and the
    /// mean over a pixel's samples is the blend).
    Blend {
        /// Index of the texture whose red channel is alpha.
        texture: usize,
    },
}

impl Cutout {
    /// The texture holding alpha.
    pub fn texture(&self) -> usize {
        match *self {
            Cutout::Mask { texture, .. } | Cutout::Blend { texture } => texture,
        }
    }

    /// Whether a surface of alpha `alpha` is a hole to `ray`, which met it at `t`.
    pub fn is_hole(&self, alpha: f32, ray: &Ray, t: f32) -> bool {
        match *self {
            Cutout::Mask { cutoff, .. } => alpha < cutoff,
            Cutout::Blend { .. } => {
                let (o, d) = (ray.origin, ray.dir);
                let h = hash_seed(&[o.x, o.y, o.z, d.x, d.y, d.z, t].map(|x| x.to_bits() as u64));
                let u = (h >> 40) as f32 / (1u64 << 24) as f32;
                u >= alpha
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Rng, Vec3A};

    #[test]
    fn a_mask_cuts_below_its_cutoff() {
        let m = Cutout::Mask {
            texture: 0,
            cutoff: 0.5,
        };
        let r = Ray::new(Vec3A::ZERO, Vec3A::Z);
        assert!(m.is_hole(0.49, &r, 1.0));
        assert!(!m.is_hole(0.5, &r, 1.0));
    }

    #[test]
    fn a_blend_lets_through_one_minus_alpha_of_rays() {
        let b = Cutout::Blend { texture: 0 };
        let mut rng = Rng::new(7);
        for alpha in [0.0, 0.25, 0.7, 1.0] {
            let n = 20_000;
            let holes = (0..n)
                .filter(|_| {
                    let o = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
                    let d = Vec3A::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, 1.0);
                    b.is_hole(alpha, &Ray::new(o, d.normalize()), rng.next_f32() * 10.0)
                })
                .count() as f32
                / n as f32;
            assert!((holes - (1.0 - alpha)).abs() < 0.015, "{alpha}: {holes}");
        }
        // Camera rays: one origin, directions a hair apart.
        let o = Vec3A::new(0.3, 1.0, 5.0);
        let n = 20_000;
        let holes = (0..n)
            .filter(|k| {
                let (x, y) = ((k % 200) as f32 * 1e-4, (k / 200) as f32 * 1e-4);
                let d = Vec3A::new(x, y, -1.0).normalize();
                b.is_hole(0.25, &Ray::new(o, d), 5.0 / d.z.abs())
            })
            .count() as f32
            / n as f32;
        assert!((holes - 0.75).abs() < 0.015, "{holes}");
        // The same ray decides the same way.
        let r = Ray::new(Vec3A::new(0.1, 0.2, 0.3), Vec3A::Z);
        assert_eq!(b.is_hole(0.5, &r, 2.0), b.is_hole(0.5, &r, 2.0));
    }
}
