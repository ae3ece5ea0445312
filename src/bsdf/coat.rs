//! A rough dielectric coat's tables, as Mitsuba 3's `roughplastic` precomputes them: the
//! fraction of the light arriving from a direction that passes through the coat
//! (`transmittance`, at 64 cosines, read by linear interpolation), and the fraction of
//! diffuse light under the coat that it sends back down (`internal_reflectance`). Each
//! integrates over the microfacet normals visible from the direction, with a Gauss-Legendre
//! rule over the square those normals are sampled from: 32 x 32 nodes from outside, 128 x
//! 128 from inside, where total internal reflection makes the integrand jump.
//!
//! Tables depend only on the coat's index and roughness, and take milliseconds to make, so
//! they are made once per pair in a process and shared ([`CoatTable::of`]).

use super::dielectric::{fresnel, refract};
use super::microfacet::{Ggx, SMOOTH_ALPHA};
use crate::math::quadrature::gauss_legendre;
use crate::math::{Vec2, Vec3A};
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

/// How many cosines the transmittance is tabulated at (Mitsuba's
/// `MI_ROUGH_TRANSMITTANCE_RES`), evenly from 0 to 1.
pub const COSINES: usize = 64;

/// A rough coat's transmittance by cosine and its internal diffuse reflectance.
#[derive(Debug, PartialEq)]
pub struct CoatTable {
    transmittance: [f32; COSINES],
    internal: f32,
}

impl CoatTable {
    /// The table of a coat of index `eta` (inside over outside) and GGX roughness `alpha`,
    /// made once in the process and shared after. Each distinct pair keeps about 260 bytes
    /// for the life of the process.
    pub fn of(eta: f32, alpha: f32) -> &'static CoatTable {
        static TABLES: OnceLock<Mutex<HashMap<(u32, u32), &'static CoatTable>>> = OnceLock::new();
        let key = (eta.to_bits(), alpha.to_bits());
        let tables = TABLES.get_or_init(Default::default);
        if let Some(t) = tables.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
            return t;
        }
        // Made outside the lock: two threads may both make one, and the first kept wins.
        let made = CoatTable::new(eta, alpha);
        let mut tables = tables.lock().unwrap_or_else(|e| e.into_inner());
        tables
            .entry(key)
            .or_insert_with(|| Box::leak(Box::new(made)))
    }

    /// Works the tables out: the transmittance from outside at each cosine, and twice the
    /// mean over the same cosines of the reflectance from inside times the cosine.
    pub fn new(eta: f32, alpha: f32) -> Self {
        let ggx = Ggx::isotropic(alpha);
        let outside = Rule::new(32);
        let inside = Rule::new(128);
        let mut transmittance = [0.0; COSINES];
        let mut internal = 0.0f64;
        for (i, t) in transmittance.iter_mut().enumerate() {
            let mu = (i as f32 / (COSINES - 1) as f32).max(1e-6);
            let w = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
            *t = outside.mean(|u| {
                let m = ggx.sample_visible(w, u);
                let f = fresnel(w.dot(m), eta);
                match refract(w, m, eta) {
                    Some((wt, _)) if wt.z < 0.0 => (ggx.g1(wt) * (1.0 - f)) as f64,
                    _ => 0.0,
                }
            }) as f32;
            internal += inside.mean(|u| {
                let m = ggx.sample_visible(w, u);
                let wr = 2.0 * w.dot(m) * m - w;
                if wr.z <= 0.0 {
                    return 0.0;
                }
                (ggx.g1(wr) * fresnel(w.dot(m), 1.0 / eta)) as f64
            }) * mu as f64;
        }
        CoatTable {
            transmittance,
            internal: (2.0 * internal / COSINES as f64) as f32,
        }
    }

    /// The fraction of light arriving at `|cos| = cos` that passes into the coat (and, by
    /// reciprocity, of light inside that leaves toward that direction).
    #[inline]
    pub fn transmittance(&self, cos: f32) -> f32 {
        let x = cos.abs().min(1.0) * (COSINES - 1) as f32;
        let i = (x as usize).min(COSINES - 2);
        let w = x - i as f32;
        (1.0 - w) * self.transmittance[i] + w * self.transmittance[i + 1]
    }

    /// The fraction of diffuse light under the coat that it reflects back down.
    #[inline]
    pub fn internal_reflectance(&self) -> f32 {
        self.internal
    }
}

/// How many roughnesses [`CoatKnots`] tabulates, evenly in the cube root of roughness
/// (closer together where the tables change fastest): enough for 0.6 % (tested).
const KNOTS: usize = 24;

/// The tables of a coat of one index at knots of roughness, for materials whose roughness
/// varies over the surface (a texture): [`CoatKnots::at`] interpolates between the two
/// knots around a point's roughness.
#[derive(Debug)]
pub struct CoatKnots {
    tables: [&'static CoatTable; KNOTS],
}

impl CoatKnots {
    /// The knots of index `eta`, made once in the process (in parallel: 24 tables' work,
    /// long enough to notice at start-up) and shared after.
    pub fn of(eta: f32) -> &'static CoatKnots {
        static KNOTS_BY_ETA: OnceLock<Mutex<HashMap<u32, &'static CoatKnots>>> = OnceLock::new();
        let all = KNOTS_BY_ETA.get_or_init(Default::default);
        if let Some(k) = all
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .get(&eta.to_bits())
        {
            return k;
        }
        use rayon::prelude::*;
        let tables: Vec<&'static CoatTable> = (0..KNOTS)
            .into_par_iter()
            .map(|k| CoatTable::of(eta, Self::alpha(k)))
            .collect();
        let made = CoatKnots {
            tables: tables.try_into().expect("one table per knot"),
        };
        let mut all = all.lock().unwrap_or_else(|e| e.into_inner());
        all.entry(eta.to_bits())
            .or_insert_with(|| Box::leak(Box::new(made)))
    }

    /// The roughness of knot `k`: evenly spaced in the cube root of roughness, from the
    /// smoothest rough coat to 1.
    fn alpha(k: usize) -> f32 {
        let lo = SMOOTH_ALPHA.cbrt();
        (lo + (1.0 - lo) * k as f32 / (KNOTS - 1) as f32).powi(3)
    }

    /// The coat at roughness `alpha`: the knots around it (the first or last beyond them),
    /// weighted linearly in the cube root of roughness.
    pub fn at(&self, alpha: f32) -> RoughCoat {
        let lo = SMOOTH_ALPHA.cbrt();
        let x = ((alpha.max(0.0).cbrt() - lo) / (1.0 - lo) * (KNOTS - 1) as f32)
            .clamp(0.0, (KNOTS - 1) as f32);
        let i = (x as usize).min(KNOTS - 2);
        RoughCoat {
            lo: self.tables[i],
            hi: self.tables[i + 1],
            w: x - i as f32,
        }
    }
}

/// Where a material finds its rough coat: the exact table of its one roughness, or the
/// knots of its index where a texture gives the roughness.
#[derive(Clone, Copy, Debug)]
pub enum CoatSource {
    /// A constant roughness's table.
    Exact(&'static CoatTable),
    /// Tables at knots of roughness.
    Knots(&'static CoatKnots),
}

impl CoatSource {
    /// The source for a coat of index `eta` whose roughness is `alpha` everywhere, or
    /// varies (`None`).
    pub fn new(eta: f32, alpha: Option<f32>) -> Self {
        match alpha {
            Some(a) => CoatSource::Exact(CoatTable::of(eta, a)),
            None => CoatSource::Knots(CoatKnots::of(eta)),
        }
    }

    /// The coat at a point of roughness `alpha` (the exact table ignores it).
    #[inline]
    pub fn at(&self, alpha: f32) -> RoughCoat {
        match *self {
            CoatSource::Exact(t) => RoughCoat {
                lo: t,
                hi: t,
                w: 0.0,
            },
            CoatSource::Knots(k) => k.at(alpha),
        }
    }
}

impl PartialEq for CoatSource {
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (CoatSource::Exact(a), CoatSource::Exact(b)) => std::ptr::eq(*a, *b),
            (CoatSource::Knots(a), CoatSource::Knots(b)) => std::ptr::eq(*a, *b),
            _ => false,
        }
    }
}

/// A rough coat at a point: one table, or two and the weight of the second.
#[derive(Clone, Copy, Debug)]
pub struct RoughCoat {
    lo: &'static CoatTable,
    hi: &'static CoatTable,
    w: f32,
}

impl RoughCoat {
    /// [`CoatTable::transmittance`] at the point's roughness.
    #[inline]
    pub fn transmittance(&self, cos: f32) -> f32 {
        let lo = self.lo.transmittance(cos);
        if self.w == 0.0 {
            return lo;
        }
        lo + self.w * (self.hi.transmittance(cos) - lo)
    }

    /// [`CoatTable::internal_reflectance`] at the point's roughness.
    #[inline]
    pub fn internal_reflectance(&self) -> f32 {
        self.lo.internal + self.w * (self.hi.internal - self.lo.internal)
    }
}

impl PartialEq for RoughCoat {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self.lo, other.lo) && std::ptr::eq(self.hi, other.hi) && self.w == other.w
    }
}

/// A product Gauss-Legendre rule over the unit square.
struct Rule {
    nodes: Vec<f32>,
    weights: Vec<f64>,
}

impl Rule {
    fn new(n: usize) -> Self {
        let (x, w) = gauss_legendre(n);
        Rule {
            nodes: x.iter().map(|x| (0.5 * x + 0.5) as f32).collect(),
            weights: w.iter().map(|w| 0.5 * w).collect(),
        }
    }

    /// The mean of `f` over the square.
    fn mean(&self, mut f: impl FnMut(Vec2) -> f64) -> f64 {
        let mut sum = 0.0;
        for (x, wx) in self.nodes.iter().zip(&self.weights) {
            for (y, wy) in self.nodes.iter().zip(&self.weights) {
                sum += wx * wy * f(Vec2::new(*x, *y));
            }
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::internal_diffuse_reflectance;

    /// Nearly smooth, the coat lets through `1 - F` of the light and returns the smooth
    /// boundary's share of diffuse light from inside, but for Mitsuba's rule over 64 evenly
    /// spaced cosines (not an exact integral); rougher coats let through less at grazing
    /// angles and more near them, and the figures for index 1.5 and alpha 0.1 hold.
    #[test]
    fn the_tables_have_their_landmarks() {
        let t = CoatTable::new(1.5, 0.002);
        for cos in [0.3f32, 0.6, 0.9, 1.0] {
            let smooth = 1.0 - fresnel(cos, 1.5);
            assert!((t.transmittance(cos) - smooth).abs() < 2e-3, "{cos}");
        }
        let smooth = internal_diffuse_reflectance(1.5);
        assert!(
            (t.internal_reflectance() - smooth).abs() < 0.02,
            "{}",
            t.internal
        );
        let rough = CoatTable::new(1.5, 0.1);
        assert!(
            (rough.internal_reflectance() - 0.552).abs() < 2e-3,
            "{}",
            rough.internal
        );
        assert!(rough.transmittance(0.05) > t.transmittance(0.05) + 0.1);
        assert!(std::ptr::eq(
            CoatTable::of(1.5, 0.1),
            CoatTable::of(1.5, 0.1)
        ));
        assert_eq!(*CoatTable::of(1.5, 0.1), rough);
    }

    /// Between its knots, a textured roughness's coat is within 0.6 % of the exact tables
    /// of its roughness (3 % at grazing incidence, where the transmittance of a nearly smooth
    /// coat changes fastest with roughness).
    #[test]
    fn knots_interpolate_the_exact_tables() {
        let knots = CoatKnots::of(1.5);
        let mut checked = 0;
        for alpha in [0.002f32, 0.02, 0.05, 0.13, 0.3, 0.55, 0.8, 1.0] {
            let (near, exact) = (knots.at(alpha), CoatTable::new(1.5, alpha));
            let (a, b) = (near.internal_reflectance(), exact.internal_reflectance());
            assert!((a - b).abs() < 0.006 * b, "alpha {alpha}: R_int {a} vs {b}");
            for i in 0..=20 {
                let cos = i as f32 / 20.0;
                let (a, b) = (near.transmittance(cos), exact.transmittance(cos));
                let tolerance = if i == 0 { 0.03 } else { 0.006 };
                assert!(
                    (a - b).abs() < tolerance * b,
                    "alpha {alpha}, cos {cos}: {a} vs {b}"
                );
                checked += 1;
            }
        }
        assert_eq!(checked, 8 * 21);
    }
}
