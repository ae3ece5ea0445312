//! Keyframe curves: a value of `N` numbers at each key's time, and the value between keys
//! by a step, a straight line or a Catmull-Rom spline. Before the first key the curve holds
//! the first value, after the last the last.

/// How a curve goes from a key to the next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// Catmull-Rom: a cubic through the keys whose slope at each key is the slope from
    /// the key before to the key after (at an end, half the slope to its one neighbour, as
    /// if the end were repeated one step beyond); a component equal to its value at a
    /// neighbouring key has slope 0 there, so a held value stays flat.
    Smooth,
    /// A straight line.
    Linear,
    /// The key's value until the next key.
    Step,
}

/// One key: its time (in frames), its value, and how the curve leaves it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Key<const N: usize> {
    /// When, in frames; keys are in increasing order.
    pub t: f32,
    /// The value.
    pub v: [f32; N],
    /// How the curve goes on to the next key.
    pub how: Interpolation,
}

/// The curve through `keys` (in increasing time, at least one) at time `t`.
pub fn sample<const N: usize>(keys: &[Key<N>], t: f32) -> [f32; N] {
    let (first, last) = (keys[0], keys[keys.len() - 1]);
    if t <= first.t || keys.len() == 1 {
        return first.v;
    }
    if t >= last.t {
        return last.v;
    }
    // The segment holding t: keys[i].t <= t < keys[i + 1].t.
    let i = keys.partition_point(|k| k.t <= t) - 1;
    let (a, b) = (keys[i], keys[i + 1]);
    let h = b.t - a.t;
    let s = (t - a.t) / h;
    match a.how {
        Interpolation::Step => a.v,
        Interpolation::Linear => std::array::from_fn(|c| a.v[c] + (b.v[c] - a.v[c]) * s),
        Interpolation::Smooth => {
            let (m0, m1) = (slope(keys, i), slope(keys, i + 1));
            // Cubic Hermite basis on the segment, slopes scaled from per frame to per
            // segment.
            let (s2, s3) = (s * s, s * s * s);
            let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
            let h10 = s3 - 2.0 * s2 + s;
            let h01 = -2.0 * s3 + 3.0 * s2;
            let h11 = s3 - s2;
            std::array::from_fn(|c| h00 * a.v[c] + h10 * h * m0[c] + h01 * b.v[c] + h11 * h * m1[c])
        }
    }
}

/// The Catmull-Rom slope (per frame) of each component at key `i`.
fn slope<const N: usize>(keys: &[Key<N>], i: usize) -> [f32; N] {
    let k = keys[i];
    let before = i.checked_sub(1).map(|j| keys[j]);
    let after = keys.get(i + 1).copied();
    std::array::from_fn(|c| {
        let flat =
            before.is_some_and(|b| b.v[c] == k.v[c]) || after.is_some_and(|a| a.v[c] == k.v[c]);
        if flat {
            return 0.0;
        }
        match (before, after) {
            (Some(b), Some(a)) => (a.v[c] - b.v[c]) / (a.t - b.t),
            // An end: as if it were repeated one step beyond, half the slope to its
            // neighbour.
            (None, Some(a)) => 0.5 * (a.v[c] - k.v[c]) / (a.t - k.t),
            (Some(b), None) => 0.5 * (k.v[c] - b.v[c]) / (k.t - b.t),
            (None, None) => 0.0,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use Interpolation::*;

    fn key(t: f32, v: f32, how: Interpolation) -> Key<1> {
        Key { t, v: [v], how }
    }

    fn at(keys: &[Key<1>], t: f32) -> f32 {
        sample(keys, t)[0]
    }

    #[test]
    fn before_the_first_key_and_after_the_last_the_ends_are_held() {
        let keys = [key(2.0, 1.0, Smooth), key(6.0, 5.0, Smooth)];
        assert_eq!(at(&keys, 0.0), 1.0);
        assert_eq!(at(&keys, 2.0), 1.0);
        assert_eq!(at(&keys, 6.0), 5.0);
        assert_eq!(at(&keys, 100.0), 5.0);
        assert_eq!(at(&[key(3.0, 7.0, Linear)], 1.0), 7.0);
        assert_eq!(at(&[key(3.0, 7.0, Linear)], 9.0), 7.0);
    }

    #[test]
    fn linear_and_step_between_keys() {
        let keys = [
            key(0.0, 0.0, Linear),
            key(4.0, 8.0, Step),
            key(6.0, 2.0, Linear),
        ];
        assert_eq!(at(&keys, 1.0), 2.0);
        assert_eq!(at(&keys, 3.0), 6.0);
        // The step key holds its value until the next key, then jumps.
        assert_eq!(at(&keys, 4.0), 8.0);
        assert_eq!(at(&keys, 5.999), 8.0);
        assert_eq!(at(&keys, 6.0), 2.0);
    }

    #[test]
    fn smooth_matches_catmull_rom_worked_by_hand() {
        // Keys (0, 0), (1, 1), (2, 4), (3, 9): interior slopes (4 - 0) / 2 = 2 at t = 1
        // and (9 - 1) / 2 = 4 at t = 2. Halfway through the middle segment the Hermite
        // cubic gives (0 + 1 + 4) / 2 ... precisely: 0.5 * 1 + 0.125 * 2 + 0.5 * 4
        // - 0.125 * 4 = 2.25 (the parabola t^2 it samples also gives 2.25: Catmull-Rom
        // reproduces quadratics on even spacing).
        let keys = [
            key(0.0, 0.0, Smooth),
            key(1.0, 1.0, Smooth),
            key(2.0, 4.0, Smooth),
            key(3.0, 9.0, Smooth),
        ];
        assert!((at(&keys, 1.5) - 2.25).abs() < 1e-6, "{}", at(&keys, 1.5));
        // A quarter in: h00 = 0.84375, h10 = 0.140625, h01 = 0.15625, h11 = -0.046875:
        // 0.84375 + 0.140625 * 2 + 0.15625 * 4 - 0.046875 * 4 = 1.5625 = 1.25^2.
        assert!(
            (at(&keys, 1.25) - 1.5625).abs() < 1e-6,
            "{}",
            at(&keys, 1.25)
        );
        // The first segment: slope 0.5 at t = 0 (half of 1 / 1), 2 at t = 1. At 0.5:
        // 0.125 * 0.5 + 0.5 * 1 - 0.125 * 2 = 0.3125.
        assert!((at(&keys, 0.5) - 0.3125).abs() < 1e-6, "{}", at(&keys, 0.5));
    }

    #[test]
    fn smooth_with_two_keys_eases_in_and_out_symmetrically() {
        let keys = [key(0.0, 0.0, Smooth), key(10.0, 10.0, Smooth)];
        // Slopes 0.5 at both ends: at s = 0.25, 0.15625 * 10 + 0.140625 * 5 - 0.046875 * 5
        // = 2.03125; by symmetry 10 - that at s = 0.75; the middle is the middle.
        assert!(
            (at(&keys, 2.5) - 2.03125).abs() < 1e-5,
            "{}",
            at(&keys, 2.5)
        );
        assert!((at(&keys, 7.5) - 7.96875).abs() < 1e-5);
        assert!((at(&keys, 5.0) - 5.0).abs() < 1e-6);
    }

    #[test]
    fn a_held_value_stays_flat_under_smooth_interpolation() {
        // 0 -> 5, held 5 -> 5, then 5 -> 0: the hold is flat (no overshoot past 5).
        let keys = [
            key(0.0, 0.0, Smooth),
            key(2.0, 5.0, Smooth),
            key(4.0, 5.0, Smooth),
            key(6.0, 0.0, Smooth),
        ];
        for i in 0..=40 {
            let t = 2.0 + 2.0 * i as f32 / 40.0;
            assert!((at(&keys, t) - 5.0).abs() < 1e-6, "t = {t}");
        }
        for i in 0..=60 {
            let v = at(&keys, 6.0 * i as f32 / 60.0);
            assert!((-1e-6..=5.0 + 1e-6).contains(&v), "{v}");
        }
    }

    #[test]
    fn uneven_spacing_and_components_are_independent() {
        let keys = [
            Key {
                t: 0.0,
                v: [0.0, 3.0],
                how: Linear,
            },
            Key {
                t: 1.0,
                v: [10.0, 3.0],
                how: Linear,
            },
            Key {
                t: 11.0,
                v: [20.0, -7.0],
                how: Linear,
            },
        ];
        assert_eq!(sample(&keys, 0.5), [5.0, 3.0]);
        assert_eq!(sample(&keys, 6.0), [15.0, -2.0]);
    }
}
