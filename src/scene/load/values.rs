//! The checks every part of a scene applies to its numbers, points, directions and colours:
//! each reports a problem at the value's path and gives back a stand-in, so that building
//! goes on and finds the file's other problems too.

use super::Builder;
use crate::math::{Color, MAX_MAGNITUDE, Vec3A};
use crate::scene::diag::DocPath;
use crate::scene::format::{ColorDef, V3};

impl Builder<'_> {
    pub(super) fn finite(&mut self, x: f32, path: &DocPath) -> f32 {
        if x.is_nan() {
            self.error(path.clone(), "must be a finite number, not nan");
            0.0
        } else if x.is_infinite() {
            // `inf`, or a number too large for a 32-bit float (1e300): the same limit holds.
            self.error_help(
                path.clone(),
                format!("is too large: numbers must be at most {MAX_MAGNITUDE:e} in magnitude"),
                "squares of larger numbers overflow 32-bit floats; scale the scene down",
            );
            0.0
        } else if x.abs() > MAX_MAGNITUDE {
            self.error_help(
                path.clone(),
                format!("{x:e} is too large (at most {MAX_MAGNITUDE:e} in magnitude)"),
                "squares of larger numbers overflow 32-bit floats; scale the scene down",
            );
            0.0
        } else {
            x
        }
    }

    pub(super) fn positive(&mut self, x: f32, path: &DocPath) -> f32 {
        if !x.is_finite() || x.abs() > MAX_MAGNITUDE {
            self.finite(x, path);
            return 1.0;
        }
        if x <= 0.0 {
            self.error(path.clone(), format!("must be greater than 0, not {x}"));
            return 1.0;
        }
        x
    }

    pub(super) fn non_negative(&mut self, x: f32, path: &DocPath) -> f32 {
        let x = self.finite(x, path);
        if x < 0.0 {
            self.error(path.clone(), format!("must be 0 or more, not {x}"));
            return 0.0;
        }
        x
    }

    pub(super) fn in_range(&mut self, x: f32, lo: f32, hi: f32, path: &DocPath) -> f32 {
        let x = self.finite(x, path);
        if !(lo..=hi).contains(&x) {
            self.error(
                path.clone(),
                format!("must be between {lo} and {hi}, not {x}"),
            );
            return x.clamp(lo, hi);
        }
        x
    }

    pub(super) fn point(&mut self, v: V3, path: &DocPath) -> Vec3A {
        if v.iter().any(|x| x.is_nan()) {
            self.error(path.clone(), format!("must be finite numbers, not {v:?}"));
            Vec3A::ZERO
        } else if v.iter().any(|x| x.is_infinite() || x.abs() > MAX_MAGNITUDE) {
            self.error_help(
                path.clone(),
                if v.iter().any(|x| x.is_infinite()) {
                    // `inf`, or beyond a 32-bit float (1e300): naming the value would say `inf`.
                    format!(
                        "is too large: each number must be at most {MAX_MAGNITUDE:e} in magnitude"
                    )
                } else {
                    format!(
                        "{v:?} is too large (each number at most {MAX_MAGNITUDE:e} in magnitude)"
                    )
                },
                "squares of larger numbers overflow 32-bit floats; scale the scene down",
            );
            Vec3A::ZERO
        } else {
            Vec3A::from_array(v)
        }
    }

    pub(super) fn direction(&mut self, v: V3, path: &DocPath) -> Vec3A {
        let p = self.point(v, path);
        let len = p.length();
        if len == 0.0 || !len.is_finite() {
            if p.is_finite() {
                self.error(
                    path.clone(),
                    "must not be the zero vector: it gives the direction",
                );
            }
            return Vec3A::Y;
        }
        p / len
    }

    pub(super) fn color(&mut self, c: ColorDef, path: &DocPath) -> Color {
        let v = Vec3A::from_array(c.0);
        if !v.is_finite() || v.min_element() < 0.0 {
            self.error(
                path.clone(),
                format!("colour components must be finite and ≥ 0, not {:?}", c.0),
            );
            return Color::ZERO;
        }
        v
    }
}
