//! Tone mapping for 8-bit pictures: linear radiance scaled by an exposure (in stops) and
//! brought into `[0, 1]` by a tone curve, before the sRGB encoding. EXR keeps the linear
//! values as they are.

use crate::math::Color;

/// How values above 1 are brought into range (`[image] tonemap`, `--tonemap`).
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    Eq,
    serde::Deserialize,
    serde::Serialize,
    schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum ToneCurve {
    /// Cut at 1 (the default: what a PNG has always shown).
    #[default]
    Clamp,
    /// Reinhard's `x / (1 + x)` per channel: every value fits, highlights go grey.
    Reinhard,
    /// Narkowicz's fit of the ACES filmic curve: a toe, a shoulder, saturated highlights
    /// that roll off to white.
    Aces,
}

impl ToneCurve {
    /// Every curve, in the order they are documented.
    pub const ALL: [ToneCurve; 3] = [ToneCurve::Clamp, ToneCurve::Reinhard, ToneCurve::Aces];

    /// The curve's name (`clamp`, `reinhard`, `aces`).
    pub fn name(self) -> &'static str {
        match self {
            ToneCurve::Clamp => "clamp",
            ToneCurve::Reinhard => "reinhard",
            ToneCurve::Aces => "aces",
        }
    }

    /// The curve with this name.
    pub fn from_name(name: &str) -> Option<Self> {
        ToneCurve::ALL.into_iter().find(|c| c.name() == name)
    }

    #[inline]
    fn apply(self, x: f32) -> f32 {
        match self {
            ToneCurve::Clamp => x,
            ToneCurve::Reinhard => x / (1.0 + x),
            ToneCurve::Aces => (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14),
        }
    }
}

/// Exposure and curve.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tone {
    /// Stops: values are multiplied by `2^exposure`.
    pub exposure: f32,
    /// The curve after the exposure.
    pub curve: ToneCurve,
}

impl Tone {
    /// The display value in `[0, 1]` of linear value `v` (0 for NaN or negative values).
    #[inline]
    pub fn apply(&self, v: f32, scale: f32) -> f32 {
        let v = v * scale;
        if v.is_finite() {
            self.curve.apply(v.max(0.0)).clamp(0.0, 1.0)
        } else if v == f32::INFINITY {
            1.0
        } else {
            0.0
        }
    }

    /// The factor the exposure multiplies by.
    #[inline]
    pub fn scale(&self) -> f32 {
        self.exposure.exp2()
    }

    /// [`Tone::apply`] of each channel.
    pub fn color(&self, c: Color) -> Color {
        let s = self.scale();
        Color::new(self.apply(c.x, s), self.apply(c.y, s), self.apply(c.z, s))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Clamp at exposure 0 changes nothing in range; a stop doubles; every curve is 0 at 0,
    /// rises, and stays in [0, 1] for any input.
    #[test]
    fn curves_rise_and_stay_in_range() {
        let t = Tone::default();
        assert_eq!(
            t.color(Color::new(0.25, 0.5, 2.0)),
            Color::new(0.25, 0.5, 1.0)
        );
        let up = Tone { exposure: 1.0, ..t };
        assert_eq!(up.color(Color::splat(0.25)), Color::splat(0.5));
        for curve in ToneCurve::ALL {
            assert_eq!(ToneCurve::from_name(curve.name()), Some(curve));
            let t = Tone {
                exposure: 0.0,
                curve,
            };
            let mut last = -1.0;
            for k in 0..=1000 {
                let v = t.apply(k as f32 * 0.02, 1.0);
                assert!((0.0..=1.0).contains(&v) && v >= last, "{curve:?} at {k}");
                last = v;
            }
            assert_eq!(t.apply(0.0, 1.0), 0.0);
            for bad in [f32::NAN, -1.0, f32::NEG_INFINITY] {
                assert_eq!(t.apply(bad, 1.0), 0.0, "{curve:?} {bad}");
            }
            assert_eq!(t.apply(f32::INFINITY, 1.0), 1.0);
        }
        // Narkowicz's fit lifts middle grey (0.18 to 0.267, as his formula gives) and
        // compresses the highlights.
        let aces = Tone {
            exposure: 0.0,
            curve: ToneCurve::Aces,
        };
        assert!((aces.apply(0.18, 1.0) - 0.2669).abs() < 1e-3);
        assert!(aces.apply(4.0, 1.0) > 0.95 && aces.apply(4.0, 1.0) < 1.0);
    }
}
