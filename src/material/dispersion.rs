//! An index of refraction that changes with wavelength: Cauchy's `a + b / λ²` or Sellmeier's
//! `n² = 1 + Σ Bᵢ λ² / (λ² - Cᵢ)` (λ in micrometres, as glass catalogues give them), and the
//! named glasses a scene may ask for. A dielectric (or Phong glass) with one bends each
//! wavelength its own way: a prism splits white light, a diamond shows fire.

/// How the index changes with wavelength.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Dispersion {
    /// `n = a + b / λ²`, `b` in µm².
    Cauchy {
        /// The index at long wavelengths.
        a: f32,
        /// How fast it rises toward blue, µm².
        b: f32,
    },
    /// `n² = 1 + Σ Bᵢ λ² / (λ² - Cᵢ)`, `C` in µm².
    Sellmeier {
        /// Strengths.
        b: [f32; 3],
        /// Resonances' squared wavelengths, µm².
        c: [f32; 3],
    },
}

/// The wavelength at which a dispersive glass's single index is quoted: the helium d line,
/// 587.56 nm (catalogues' `n_d`), and what a renderer that follows no wavelength uses.
pub const D_LINE_NM: f32 = 587.56;

/// The glasses a scene may name, with their formulas (from refractiveindex.info's sources).
pub const NAMED: [(&str, Dispersion); 5] = [
    // Schott N-BK7, the common crown glass: n_d 1.5168, Abbe number 64.2.
    (
        "BK7",
        Dispersion::Sellmeier {
            b: [1.039_612, 0.231_792_34, 1.010_469_5],
            c: [0.006_000_698_7, 0.020_017_914, 103.560_65],
        },
    ),
    // Fused silica (Malitson 1965): n_d 1.4585.
    (
        "fused silica",
        Dispersion::Sellmeier {
            b: [0.696_166_3, 0.407_942_6, 0.897_479_4],
            c: [0.004_679_148, 0.013_512_063, 97.934_003],
        },
    ),
    // Schott SF11, a dense flint: n_d 1.7847, Abbe number 25.7 (much more dispersive).
    (
        "SF11",
        Dispersion::Sellmeier {
            b: [1.737_597, 0.313_747_35, 1.898_781],
            c: [0.013_188_707, 0.062_306_814, 155.236_3],
        },
    ),
    // Diamond (Peter 1923): n_d 2.417, Abbe number about 55 but a high index, so its fire.
    (
        "diamond",
        Dispersion::Sellmeier {
            b: [0.3306, 4.3356, 0.0],
            c: [0.030_625, 0.011_236, 0.0],
        },
    ),
    // Water at 20 °C, a two-term Cauchy fit: n_d 1.333.
    (
        "water",
        Dispersion::Cauchy {
            a: 1.324,
            b: 0.003_07,
        },
    ),
];

impl Dispersion {
    /// The glass named `name` (upper or lower case alike).
    pub fn named(name: &str) -> Option<Dispersion> {
        NAMED
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(name))
            .map(|(_, d)| *d)
    }

    /// The index at `nm` nanometres.
    #[inline]
    pub fn ior(&self, nm: f32) -> f32 {
        let l2 = (nm * 1e-3) * (nm * 1e-3);
        match *self {
            Dispersion::Cauchy { a, b } => a + b / l2,
            Dispersion::Sellmeier { b, c } => {
                let mut n2 = 1.0;
                for (b, c) in b.iter().zip(c) {
                    n2 += b * l2 / (l2 - c);
                }
                n2.max(0.0).sqrt()
            }
        }
    }

    /// Where in 360-830 nm the index is not a finite number of at least 1 (a Sellmeier
    /// resonance within the range, or coefficients that push it below 1), as the first
    /// wavelength found and the index there; `None` where it is one everywhere. Checked at
    /// every nanometre, and at each resonance in the range.
    pub fn first_bad(&self) -> Option<(f32, f32)> {
        let at = |nm: f32| {
            let n = self.ior(nm);
            (!(n.is_finite() && n >= 1.0)).then_some((nm, n))
        };
        if let Dispersion::Sellmeier { c, .. } = self {
            for &c in c {
                let nm = c.max(0.0).sqrt() * 1e3;
                if (360.0..=830.0).contains(&nm) {
                    // A pole: the index is imaginary just short of it.
                    return Some((nm, f32::NAN));
                }
            }
        }
        (360..=830).find_map(|nm| at(nm as f32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The named glasses give their catalogues' n_d, and rise toward blue (normal
    /// dispersion): n_F (486.1 nm) above n_C (656.3 nm) by their Abbe numbers.
    #[test]
    fn named_glasses_match_their_catalogues() {
        let cases = [
            ("BK7", 1.5168, 64.17),
            ("fused silica", 1.4585, 67.8),
            ("SF11", 1.7847, 25.68),
            ("diamond", 2.4175, 55.3),
            ("water", 1.3329, 55.7),
        ];
        for (name, n_d, abbe) in cases {
            let d = Dispersion::named(name).expect(name);
            let (nd, nf, nc) = (d.ior(D_LINE_NM), d.ior(486.13), d.ior(656.27));
            assert!((nd - n_d).abs() < 1.5e-3, "{name}: n_d {nd} against {n_d}");
            let v = (nd - 1.0) / (nf - nc);
            assert!(
                (v - abbe).abs() < 0.04 * abbe,
                "{name}: Abbe number {v} against {abbe}"
            );
            assert_eq!(d.first_bad(), None, "{name}");
        }
        assert_eq!(cases.len(), NAMED.len());
        assert!(Dispersion::named("bk7").is_some() && Dispersion::named("Diamond").is_some());
        assert!(Dispersion::named("flint").is_none());
    }

    /// An index below 1 somewhere, or a resonance in the visible range, is found.
    #[test]
    fn bad_formulas_are_found() {
        let low = Dispersion::Cauchy { a: 0.9, b: 0.01 };
        let (nm, n) = low.first_bad().expect("below 1 at the red end");
        assert!(n < 1.0 && nm >= 360.0, "{nm} {n}");
        let pole = Dispersion::Sellmeier {
            b: [1.0, 0.0, 0.0],
            c: [0.25, 0.0, 0.0],
        };
        let (nm, _) = pole.first_bad().expect("a resonance at 500 nm");
        assert!((nm - 500.0).abs() < 0.01, "{nm}");
        assert_eq!(Dispersion::Cauchy { a: 1.5, b: 0.004 }.first_bad(), None);
    }
}
