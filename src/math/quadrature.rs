//! Gauss-Legendre quadrature: the `n` nodes and weights on `[-1, 1]` that integrate every
//! polynomial of degree below `2n` exactly. For integrals worked out once per material
//! (a rough coat's transmittance, in `bsdf::coat`).

/// The nodes (ascending) and weights of the `n`-point rule on `[-1, 1]`: each node a root of
/// the Legendre polynomial `P_n`, found by Newton's method from Tricomi's estimate, in
/// double precision.
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    assert!(n >= 1, "a rule of no nodes");
    let (mut nodes, mut weights) = (vec![0.0; n], vec![0.0; n]);
    for i in 0..n.div_ceil(2) {
        // The i-th largest root: Tricomi's estimate, then Newton on P_n.
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        for _ in 0..100 {
            let (p, d) = legendre(n, x);
            let step = p / d;
            x -= step;
            if step.abs() < 1e-16 {
                break;
            }
        }
        let d = legendre(n, x).1;
        let w = 2.0 / ((1.0 - x * x) * d * d);
        nodes[i] = -x;
        nodes[n - 1 - i] = x;
        weights[i] = w;
        weights[n - 1 - i] = w;
    }
    (nodes, weights)
}

/// `P_n(x)` and its derivative, by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 2..=n {
        let k = k as f64;
        (p0, p1) = (p1, ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k);
    }
    let d = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The n-point rule integrates x^k exactly for every k < 2n, and no further.
    #[test]
    fn the_rule_is_exact_below_degree_2n() {
        let mut checked = 0;
        for n in [1usize, 2, 5, 32, 128] {
            let (x, w) = gauss_legendre(n);
            assert!(x.windows(2).all(|p| p[0] < p[1]), "nodes ascending");
            for k in 0..(2 * n).min(60) {
                let sum: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(k as i32)).sum();
                let exact = if k % 2 == 0 {
                    2.0 / (k as f64 + 1.0)
                } else {
                    0.0
                };
                assert!(
                    (sum - exact).abs() < 1e-12,
                    "n {n}, x^{k}: {sum} vs {exact}"
                );
                checked += 1;
            }
        }
        assert_eq!(checked, 2 + 4 + 10 + 60 + 60);
        // Two points cannot integrate x^4.
        let (x, w) = gauss_legendre(2);
        let sum: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(4)).sum();
        assert!((sum - 0.4).abs() > 0.1);
    }
}
