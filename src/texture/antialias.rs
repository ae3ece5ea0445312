//! Closed-form filtered procedural patterns: a checker or stripes seen through a tent filter
//! as wide as the pixel's footprint, worked out exactly (as pbrt-v4 does) instead of read at
//! a point, so a far checker floor is its average grey rather than moire.

/// The square wave that is `+1` on cells `[2k, 2k + 1)` and `-1` on `[2k + 1, 2k + 2)`,
/// averaged under a tent filter of radius `r` centred at `x` (both in cells). Exact: the
/// tent's weights against the wave are the wave's second integral differenced,
/// `(S(x + r) - 2 S(x) + S(x - r)) / r^2`, taken in `f64` near `x` (the second integral
/// grows by 1 every period, so only `x` modulo 2 matters to the difference).
/// (Always inlined: docs/perf-log.md, "The seed's hot helpers inlined".)
#[inline(always)]
pub fn square_wave(x: f32, r: f32) -> f32 {
    if within_cell(x, r) || r.is_nan() || r <= 0.0 || !r.is_finite() {
        // The filter stays inside one cell (or there is no filter): the cell's value.
        return if (x.floor() as i64) & 1 == 0 {
            1.0
        } else {
            -1.0
        };
    }
    let x = x as f64;
    let x = x - 2.0 * (x / 2.0).floor();
    let r = r as f64;
    if r >= 1e6 {
        return 0.0;
    }
    ((second_integral(x + r) - 2.0 * second_integral(x) + second_integral(x - r)) / (r * r))
        .clamp(-1.0, 1.0) as f32
}

/// Whether [`square_wave`] at `x` under a tent of radius at most `r` is the cell's value:
/// the tent stays inside the cell of `x` (`square_wave`'s own test, so that the two agree
/// to the bit: a narrower tent's ends lie between these).
#[inline]
pub fn within_cell(x: f32, r: f32) -> bool {
    r.is_finite() && (x - r).floor() == (x + r).floor()
}

/// The square wave's second integral from 0: per period of 2 it rises by 1, as `f^2 / 2`
/// over the `+1` cell and `1/2 + 2 (f - 1) - (f^2 - 1) / 2` over the `-1` one, where `f` is
/// the position in the period.
fn second_integral(x: f64) -> f64 {
    let k = (x / 2.0).floor();
    let f = x - 2.0 * k;
    let within = if f < 1.0 {
        0.5 * f * f
    } else {
        0.5 + 2.0 * (f - 1.0) - 0.5 * (f * f - 1.0)
    };
    k + within
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wave(x: f64) -> f64 {
        if x.floor().rem_euclid(2.0) == 0.0 {
            1.0
        } else {
            -1.0
        }
    }

    /// The tent-filtered wave by quadrature: 20 000 midpoints across the tent.
    fn quadrature(x: f64, r: f64) -> f64 {
        let n = 20_000;
        let mut sum = 0.0;
        for i in 0..n {
            let t = -r + 2.0 * r * (i as f64 + 0.5) / n as f64;
            sum += (r - t.abs()) / (r * r) * wave(x + t) * (2.0 * r / n as f64);
        }
        sum
    }

    #[test]
    fn matches_quadrature_at_every_width() {
        for &(x, r) in &[
            (0.3, 0.5),
            (0.9, 0.2),
            (1.0, 1.0),
            (-2.7, 0.8),
            (5.5, 1.5),
            (100.25, 3.7),
            (-1000.6, 0.45),
            (12345.9, 0.3),
        ] {
            let got = square_wave(x as f32, r as f32) as f64;
            let want = quadrature(x as f32 as f64, r as f32 as f64);
            assert!((got - want).abs() < 2e-3, "x {x} r {r}: {got} vs {want}");
        }
    }

    #[test]
    fn a_wide_filter_is_the_mean_and_a_point_the_cell() {
        // Over whole periods the wave averages to nothing (up to the tent's ends).
        for x in [0.0f32, 0.37, 13.1, -7.9] {
            assert!(square_wave(x, 40.0).abs() < 1e-3, "{x}");
            assert!(square_wave(x, 1e9) == 0.0);
        }
        assert_eq!(square_wave(0.5, 0.0), 1.0);
        assert_eq!(square_wave(1.5, 0.0), -1.0);
        assert_eq!(square_wave(-0.5, 0.1), -1.0);
        assert_eq!(square_wave(2.5, f32::NAN), 1.0);
        // Far out, where f32 keeps no fraction, still a value in range.
        assert!(square_wave(1e30, 0.5).abs() <= 1.0);
    }
}
