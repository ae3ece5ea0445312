//! Chi-square goodness-of-fit tests of sampling routines against their densities, as pbrt-v4's
//! bsdfs_test.cpp and Mitsuba 3's chi2.py do: a million samples are binned, each bin's
//! expected count is the density integrated over the bin, bins expecting fewer than five
//! samples are pooled, and the test fails when the counts are unlikely under the density
//! (p below 1 %). Every warp, BSDF and light sampler's tests run through it, and `snell lab`
//! shows its histograms (crate::lab).

use super::{Rng, Vec2, Vec3A};
use std::f64::consts::PI;

/// Samples drawn per test.
pub const SAMPLES: usize = 1 << 20;
/// Subdivisions of each bin's sides when integrating the density over it.
const SUB: usize = 12;
/// Significance: a test fails when its p-value is below this.
pub const ALPHA: f64 = 0.01;

/// How a sphere of directions is binned: `theta` bands of equal angle from the pole (fine
/// near it, where narrow lobes live) times `phi` sectors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SphereBins {
    /// Bands from `theta = 0` (the pole, `+z`) to `pi`.
    pub theta: usize,
    /// Sectors of `phi` from 0 (`+x`) round to `2 pi`.
    pub phi: usize,
}

impl Default for SphereBins {
    /// An even number of bands, so the plane `z = 0` is an edge between two.
    fn default() -> Self {
        SphereBins { theta: 20, phi: 40 }
    }
}

fn direction(theta: f64, phi: f64) -> Vec3A {
    let (s, c) = theta.sin_cos();
    Vec3A::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, c as f32)
}

/// Where directions drawn by `sample` (from uniform points of the square, `samples` of them;
/// `None` for one absorbed) fall on `bins`: counts by band, then sector.
pub fn sphere_histogram(
    bins: SphereBins,
    samples: usize,
    mut sample: impl FnMut(Vec2) -> Option<Vec3A>,
) -> Result<Vec<f64>, String> {
    let (nt, np) = (bins.theta, bins.phi);
    let mut observed = vec![0.0f64; nt * np];
    let mut rng = Rng::new(0xc41_5a9e);
    for _ in 0..samples {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        let Some(d) = sample(u) else { continue };
        let d = d.normalize_or_zero();
        if d == Vec3A::ZERO || !d.is_finite() {
            return Err(format!("a sample direction is not finite or zero ({u})"));
        }
        let theta = (d.z as f64).clamp(-1.0, 1.0).acos();
        let mut t = ((theta / PI * nt as f64) as usize).min(nt - 1);
        // A direction in the plane (z = 0, a rounding's worth off) counts on the side its
        // sign says, where hemispherical densities live.
        if d.z >= 0.0 {
            t = t.min(nt / 2 - 1);
        } else {
            t = t.max(nt / 2);
        }
        let phi = (d.y as f64).atan2(d.x as f64).rem_euclid(2.0 * PI);
        let p = ((phi / (2.0 * PI) * np as f64) as usize).min(np - 1);
        observed[t * np + p] += 1.0;
    }
    Ok(observed)
}

/// The counts `samples` directions drawn with density `pdf` (per unit solid angle) are
/// expected to leave in each of `bins`: the density integrated over each bin.
pub fn sphere_expected(bins: SphereBins, samples: usize, pdf: impl Fn(Vec3A) -> f32) -> Vec<f64> {
    let (nt, np) = (bins.theta, bins.phi);
    let (dt, dphi) = (PI / nt as f64, 2.0 * PI / np as f64);
    // Fine in theta: a density's edge across a band (a cone's rim) costs the midpoint rule
    // about half a sub-step of the band.
    let sub = 16 * SUB;
    let mut expected = vec![0.0f64; nt * np];
    for t in 0..nt {
        for p in 0..np {
            let mut sum = 0.0;
            for i in 0..sub {
                let theta = dt * (t as f64 + (i as f64 + 0.5) / sub as f64);
                for j in 0..SUB {
                    let phi = dphi * (p as f64 + (j as f64 + 0.5) / SUB as f64);
                    sum += pdf(direction(theta, phi)) as f64 * theta.sin();
                }
            }
            expected[t * np + p] = sum * dt * dphi / (sub * SUB) as f64 * samples as f64;
        }
    }
    expected
}

/// Tests directions drawn by `sample` (from a uniform point of the square; `None` for a
/// sample that is absorbed) against `pdf`, a density per unit solid angle.
#[cfg(test)]
pub(crate) fn chi2_sphere(
    name: &str,
    bins: SphereBins,
    sample: impl FnMut(Vec2) -> Option<Vec3A>,
    pdf: impl Fn(Vec3A) -> f32,
) -> Result<(), String> {
    let observed = sphere_histogram(bins, SAMPLES, sample).map_err(|e| format!("{name}: {e}"))?;
    verdict(name, &observed, &sphere_expected(bins, SAMPLES, pdf))
}

/// Tests points of the unit square drawn by `sample` against `pdf`, a density over the
/// square's area, on `res` x `res` bins.
#[cfg(test)]
pub(crate) fn chi2_square(
    name: &str,
    res: usize,
    mut sample: impl FnMut(Vec2) -> Option<Vec2>,
    pdf: impl Fn(Vec2) -> f32,
) -> Result<(), String> {
    let mut observed = vec![0.0f64; res * res];
    let mut rng = Rng::new(0x5a_0a4e);
    for _ in 0..SAMPLES {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        let Some(p) = sample(u) else { continue };
        if !(p.is_finite() && (0.0..=1.0).contains(&p.x) && (0.0..=1.0).contains(&p.y)) {
            return Err(format!(
                "{name}: sample {p} of {u} is outside the unit square"
            ));
        }
        let i = ((p.x as f64 * res as f64) as usize).min(res - 1);
        let j = ((p.y as f64 * res as f64) as usize).min(res - 1);
        observed[j * res + i] += 1.0;
    }
    let cell = 1.0 / res as f64;
    // Finer than the sphere's: a density's edge across a bin (a triangle's diagonal) costs
    // the midpoint rule about half a sub-step of the bin.
    let sub = 6 * SUB;
    let mut expected = vec![0.0f64; res * res];
    for j in 0..res {
        for i in 0..res {
            let mut sum = 0.0;
            for a in 0..sub {
                for b in 0..sub {
                    let x = cell * (i as f64 + (a as f64 + 0.5) / sub as f64);
                    let y = cell * (j as f64 + (b as f64 + 0.5) / sub as f64);
                    sum += pdf(Vec2::new(x as f32, y as f32)) as f64;
                }
            }
            expected[j * res + i] = sum * cell * cell / (sub * sub) as f64 * SAMPLES as f64;
        }
    }
    verdict(name, &observed, &expected)
}

/// What comparing counts with their expectation found.
#[derive(Clone, Debug, PartialEq)]
pub struct Chi2 {
    /// The statistic, over the bins expecting at least five samples and the pool of the
    /// rest.
    pub chi2: f64,
    /// Its degrees of freedom.
    pub dof: usize,
    /// The chance of a statistic at least this large were the samples drawn with the
    /// density: below [`ALPHA`] they are not.
    pub p: f64,
    /// The bin that strays most (index, observed, expected), among those expecting five.
    pub worst: Option<(usize, f64, f64)>,
    /// Samples where the density is 0 (more than a few fail the test whatever `p` says).
    pub stray: f64,
}

impl Chi2 {
    /// Whether the samples follow the density.
    pub fn passed(&self) -> bool {
        self.p >= ALPHA && self.stray <= 10.0
    }
}

/// Pools the bins expecting under five samples and compares the counts.
pub fn compare(observed: &[f64], expected: &[f64]) -> Chi2 {
    let (mut chi2, mut dof) = (0.0, 0usize);
    let (mut pooled_obs, mut pooled_exp) = (0.0, 0.0);
    let mut worst: Option<(usize, f64, f64)> = None;
    let mut worst_term = 0.0;
    let mut stray = 0.0f64;
    for (i, (&o, &e)) in observed.iter().zip(expected).enumerate() {
        if e >= 5.0 && (o - e) * (o - e) / e > worst_term {
            worst_term = (o - e) * (o - e) / e;
            worst = Some((i, o, e));
        }
        // A few samples on a density's edge (a triangle's side) may land in a bin whose
        // integration points all missed it; more than a few mean samples where none belong.
        if e <= 0.0 {
            stray = stray.max(o);
        }
        if e < 5.0 {
            pooled_obs += o;
            pooled_exp += e;
        } else {
            chi2 += (o - e) * (o - e) / e;
            dof += 1;
        }
    }
    if pooled_exp > 0.0 {
        chi2 += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
        dof += 1;
    } else {
        stray = stray.max(pooled_obs);
    }
    let dof = dof.saturating_sub(1).max(1);
    let p = 1.0 - gamma_p(dof as f64 / 2.0, chi2 / 2.0);
    Chi2 {
        chi2,
        dof,
        p,
        worst,
        stray,
    }
}

/// [`compare`] as a test's verdict: a message naming `name` when the samples fail.
#[cfg(test)]
fn verdict(name: &str, observed: &[f64], expected: &[f64]) -> Result<(), String> {
    let c = compare(observed, expected);
    if c.stray > 10.0 {
        return Err(format!(
            "{name}: {} samples fell where the density is 0",
            c.stray
        ));
    }
    if c.passed() {
        return Ok(());
    }
    let (bin, o, e) = c.worst.unwrap_or((0, 0.0, 0.0));
    Err(format!(
        "{name}: the samples do not follow the density: chi^2 = {:.1} with {} degrees of freedom, p = {:.3e}; bin {bin} has {o} samples where {e:.1} are expected",
        c.chi2, c.dof, c.p
    ))
}

/// `ln Gamma(x)` for `x > 0` (Lanczos, g = 7, nine terms: about 15 digits).
fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection: Gamma(x) Gamma(1 - x) = pi / sin(pi x).
        return (PI / (PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// The regularised lower incomplete gamma function `P(a, x)`: the chi-square distribution's
/// CDF is `P(k / 2, x / 2)`. A series below `a + 1`, a continued fraction above
/// (Numerical Recipes' gser and gcf).
fn gamma_p(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    let front = (-x + a * x.ln() - ln_gamma(a)).exp();
    if x < a + 1.0 {
        let (mut sum, mut term, mut n) = (1.0 / a, 1.0 / a, a);
        for _ in 0..1000 {
            n += 1.0;
            term *= x / n;
            sum += term;
            if term.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        sum * front
    } else {
        // Lentz's method for the continued fraction of Q(a, x).
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..1000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let delta = d * c;
            h *= delta;
            if (delta - 1.0).abs() < 1e-15 {
                break;
            }
        }
        1.0 - front * h
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_chi_square_cdf_has_its_known_values() {
        // ln Gamma at integers and at 1/2 (sqrt(pi)).
        assert!((ln_gamma(5.0) - 24f64.ln()).abs() < 1e-12);
        assert!((ln_gamma(0.5) - PI.sqrt().ln()).abs() < 1e-12);
        // With 2 degrees of freedom the CDF is 1 - exp(-x / 2).
        for x in [0.1, 1.0, 3.0, 10.0, 40.0] {
            let cdf = gamma_p(1.0, x / 2.0);
            assert!((cdf - (1.0 - (-x / 2.0f64).exp())).abs() < 1e-12, "{x}");
        }
        // Tables: chi^2 with 10 degrees of freedom is below 23.209 with probability 0.99,
        // with 100 below 135.807 with probability 0.99.
        assert!((gamma_p(5.0, 23.209 / 2.0) - 0.99).abs() < 1e-4);
        assert!((gamma_p(50.0, 135.807 / 2.0) - 0.99).abs() < 1e-4);
    }

    #[test]
    fn counts_far_from_the_expected_fail_and_close_ones_pass() {
        let expected = vec![1000.0; 100];
        let mut observed = expected.clone();
        observed[0] += 30.0;
        observed[1] -= 30.0;
        assert!(verdict("close", &observed, &expected).is_ok());
        observed[2] += 300.0;
        observed[3] -= 300.0;
        assert!(verdict("far", &observed, &expected).is_err());
        let mut stray = expected.clone();
        stray[50] = 50.0;
        let mut none = expected.clone();
        none[50] = 0.0;
        assert!(verdict("stray", &stray, &none).is_err());
    }
}
