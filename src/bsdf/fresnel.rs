//! Fresnel reflectance of conductors, whose index of refraction is complex (`eta + i k`: `k`
//! is how fast light dies inside the metal), per colour channel.

use crate::math::Color;

/// A complex number, just enough arithmetic for the Fresnel equations.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Complex {
    re: f32,
    im: f32,
}

impl Complex {
    fn new(re: f32, im: f32) -> Self {
        Complex { re, im }
    }
    fn add(self, o: Complex) -> Complex {
        Complex::new(self.re + o.re, self.im + o.im)
    }
    fn sub(self, o: Complex) -> Complex {
        Complex::new(self.re - o.re, self.im - o.im)
    }
    fn mul(self, o: Complex) -> Complex {
        Complex::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
    fn div(self, o: Complex) -> Complex {
        let d = o.re * o.re + o.im * o.im;
        Complex::new(
            (self.re * o.re + self.im * o.im) / d,
            (self.im * o.re - self.re * o.im) / d,
        )
    }
    fn norm(self) -> f32 {
        self.re * self.re + self.im * self.im
    }
    /// The principal square root.
    fn sqrt(self) -> Complex {
        let n = self.norm().sqrt();
        if n == 0.0 {
            return Complex::new(0.0, 0.0);
        }
        let t1 = (0.5 * (n + self.re.abs())).sqrt();
        let t2 = 0.5 * self.im / t1;
        if self.re >= 0.0 {
            Complex::new(t1, t2)
        } else {
            Complex::new(t2.abs(), t1.copysign(self.im))
        }
    }
}

/// The unpolarised reflectance of a conductor of index `eta + i k` (relative to the outside
/// medium) for light at `cos_i` to the normal.
pub fn conductor(cos_i: f32, eta: f32, k: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let eta = Complex::new(eta, k);
    let sin2_i = Complex::new(1.0 - cos_i * cos_i, 0.0);
    let sin2_t = sin2_i.div(eta.mul(eta));
    let cos_t = Complex::new(1.0, 0.0).sub(sin2_t).sqrt();
    let ci = Complex::new(cos_i, 0.0);
    let r_parl = eta.mul(ci).sub(cos_t).div(eta.mul(ci).add(cos_t));
    let r_perp = ci.sub(eta.mul(cos_t)).div(ci.add(eta.mul(cos_t)));
    (r_parl.norm() + r_perp.norm()) / 2.0
}

/// [`conductor`] per channel.
pub fn conductor_rgb(cos_i: f32, eta: Color, k: Color) -> Color {
    Color::new(
        conductor(cos_i, eta.x, k.x),
        conductor(cos_i, eta.y, k.y),
        conductor(cos_i, eta.z, k.z),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::fresnel_dielectric;

    /// At normal incidence `R = ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2)`; at grazing
    /// incidence every conductor reflects everything; with `k = 0` it is the dielectric's
    /// reflectance.
    #[test]
    fn landmarks_of_the_conductor_reflectance() {
        let (eta, k) = (0.2f32, 3.9f32);
        let normal = ((eta - 1.0).powi(2) + k * k) / ((eta + 1.0).powi(2) + k * k);
        assert!((conductor(1.0, eta, k) - normal).abs() < 1e-5);
        assert!((conductor(0.0, eta, k) - 1.0).abs() < 1e-5);
        for cos_i in [0.1f32, 0.4, 0.7, 1.0] {
            let d = fresnel_dielectric(cos_i, 1.0 / 1.5);
            assert!(
                (conductor(cos_i, 1.5, 0.0) - d).abs() < 1e-4,
                "{cos_i}: {d}"
            );
        }
    }
}
