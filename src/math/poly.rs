//! Real roots of polynomials within an interval, robustly: the roots of the derivative split
//! the interval into pieces where the polynomial is monotonic, and each piece whose ends
//! differ in sign holds exactly one root, found by Newton's method kept inside the bracket
//! (bisection where a step would leave it). No closed form (Ferrari's quartic loses all its
//! digits at a torus's grazing rays); degree by degree down to the quadratic, in `f64`.

/// `p(x)`, coefficients from the highest power down.
#[inline]
pub fn eval(p: &[f64], x: f64) -> f64 {
    p.iter().fold(0.0, |acc, &c| acc * x + c)
}

/// The derivative's coefficients, highest power first.
fn derivative(p: &[f64]) -> Vec<f64> {
    let n = p.len() - 1;
    p[..n]
        .iter()
        .enumerate()
        .map(|(i, &c)| c * (n - i) as f64)
        .collect()
}

/// The real roots of `p` (highest power first) in `[lo, hi]`, ascending; a root of even
/// multiplicity (a touch, where the sign does not change) may be missed.
pub fn roots_in(p: &[f64], lo: f64, hi: f64) -> Vec<f64> {
    // Leading zeros lower the degree.
    let first = p.iter().position(|&c| c != 0.0).unwrap_or(p.len());
    let p = &p[first..];
    match p.len() {
        0 | 1 => vec![],
        2 => {
            let x = -p[1] / p[0];
            if (lo..=hi).contains(&x) {
                vec![x]
            } else {
                vec![]
            }
        }
        _ => {
            let mut points = vec![lo];
            points.extend(roots_in(&derivative(p), lo, hi));
            points.push(hi);
            let mut out: Vec<f64> = vec![];
            for w in points.windows(2) {
                let (a, b) = (w[0], w[1]);
                let (fa, fb) = (eval(p, a), eval(p, b));
                let x = if fa == 0.0 {
                    Some(a)
                } else if fa.signum() != fb.signum() {
                    Some(if fb == 0.0 { b } else { bracketed(p, a, b, fa) })
                } else {
                    None
                };
                if let Some(x) = x
                    && out.last().is_none_or(|&l| x > l)
                {
                    out.push(x);
                }
            }
            out
        }
    }
}

/// The root of `p` in `[a, b]`, where `p(a) = fa` and `p(b)` differ in sign.
fn bracketed(p: &[f64], mut a: f64, mut b: f64, mut fa: f64) -> f64 {
    let dp = derivative(p);
    let mut x = 0.5 * (a + b);
    for _ in 0..100 {
        let fx = eval(p, x);
        if fx == 0.0 {
            return x;
        }
        if fx.signum() == fa.signum() {
            (a, fa) = (x, fx);
        } else {
            b = x;
        }
        let step = fx / eval(&dp, x);
        let newton = x - step;
        let next = if newton > a && newton < b && step.is_finite() {
            newton
        } else {
            0.5 * (a + b)
        };
        if (next - x).abs() <= 1e-15 * x.abs().max(1e-300) || b - a <= 1e-15 * a.abs().max(b.abs())
        {
            return next;
        }
        x = next;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `(x - r0)(x - r1)...` expanded, highest power first.
    fn from_roots(roots: &[f64]) -> Vec<f64> {
        let mut p = vec![1.0];
        for &r in roots {
            let mut q = vec![0.0; p.len() + 1];
            for (i, &c) in p.iter().enumerate() {
                q[i] += c;
                q[i + 1] -= c * r;
            }
            p = q;
        }
        p
    }

    #[test]
    fn finds_every_simple_root_in_order() {
        for roots in [
            vec![-3.0, -1.0, 0.5, 2.0],
            vec![1.0, 1.001, 5.0, 100.0],
            vec![-0.25, 0.25, 7.0],
            vec![0.1, 0.2],
        ] {
            let got = roots_in(&from_roots(&roots), -10.0, 1000.0);
            assert_eq!(got.len(), roots.len(), "{roots:?}: {got:?}");
            for (g, r) in got.iter().zip(&roots) {
                assert!(
                    (g - r).abs() < 1e-9 * r.abs().max(1.0),
                    "{roots:?}: {got:?}"
                );
            }
        }
        // Only those in the interval.
        let got = roots_in(&from_roots(&[-3.0, -1.0, 0.5, 2.0]), 0.0, 1.0);
        assert_eq!(got.len(), 1);
        assert!((got[0] - 0.5).abs() < 1e-12);
        // None: x^4 + 1.
        assert!(roots_in(&[1.0, 0.0, 0.0, 0.0, 1.0], -10.0, 10.0).is_empty());
        // A lower degree given with leading zeros.
        assert_eq!(roots_in(&[0.0, 0.0, 2.0, -1.0], -1.0, 1.0), vec![0.5]);
    }
}
