//! Denoising: a render's picture made clean by Intel Open Image Denoise (OIDN), guided by its
//! albedo and normal images (guides.rs), where snell is built with the `denoise` feature
//! (oidn.rs); without it, [`denoise`] says how to build it. The guides are made either way.

pub mod guides;
#[cfg(feature = "denoise")]
mod oidn;

pub use guides::{Guides, guides};

use crate::film::Image;
use crate::math::Color;

/// Whether this build can denoise (the `denoise` feature).
pub const AVAILABLE: bool = cfg!(feature = "denoise");

/// How to build a snell that denoises, for messages.
pub const HOW_TO_BUILD: &str = "build snell with the `denoise` feature and the OIDN library the pyoidn wheel ships: `pip install pyoidn`, then `OIDN_DIR=$(python3 -c 'import pyoidn, os; print(os.path.dirname(pyoidn.__file__))')/oidn cargo build --release --features denoise` (docs/denoise.md)";

/// Why a picture could not be denoised.
#[derive(Debug, thiserror::Error)]
pub enum DenoiseError {
    /// This build has no denoiser.
    #[error("this snell was built without a denoiser (help: {HOW_TO_BUILD})")]
    NotBuilt,
    /// OIDN could not start or failed.
    #[error("Open Image Denoise failed: {0}")]
    Library(String),
    /// The guides do not fit the picture.
    #[error("the guides are {0} x {1}, the picture {2} x {3}")]
    Size(u32, u32, u32, u32),
}

/// Whether OIDN can start here (a device made and dropped): asked before a render that
/// will be denoised, so that a missing feature or device fails before any work.
pub fn ready() -> Result<(), DenoiseError> {
    #[cfg(feature = "denoise")]
    {
        oidn::ready()
    }
    #[cfg(not(feature = "denoise"))]
    {
        Err(DenoiseError::NotBuilt)
    }
}

/// `image` (linear, high dynamic range) denoised by OIDN's ray tracing filter, guided by
/// `guides` of the same size. The light the pixels see emitted is taken out before the
/// filter, as the render sampled it ([`Guides::light`]), and added back after it, sharp
/// ([`Guides::sharp_light`]): a lamp seen directly has no noise worth removing, only its
/// edge's place in a pixel, and the filter, made for pictures people look at, moved the
/// Cornell box's lamp 20 % brighter and smeared its edge over the ceiling.
pub fn denoise(image: &Image, guides: &Guides) -> Result<Image, DenoiseError> {
    if (guides.width, guides.height) != (image.width, image.height) {
        return Err(DenoiseError::Size(
            guides.width,
            guides.height,
            image.width,
            image.height,
        ));
    }
    let mut reflected = image.clone();
    for (p, &e) in reflected.pixels.iter_mut().zip(&guides.light) {
        *p = (*p - e).max(Color::ZERO);
    }
    let mut out = filtered(&reflected, guides)?;
    for (p, &e) in out.pixels.iter_mut().zip(&guides.sharp_light) {
        *p += e;
    }
    Ok(out)
}

/// OIDN's filter of `image`, where this build has it.
fn filtered(image: &Image, guides: &Guides) -> Result<Image, DenoiseError> {
    #[cfg(feature = "denoise")]
    {
        oidn::filter(image, guides)
    }
    #[cfg(not(feature = "denoise"))]
    {
        let _ = (image, guides);
        Err(DenoiseError::NotBuilt)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Vec3A;

    /// Guides of another size are refused; without the feature, the filter says how to get
    /// it.
    #[test]
    fn guides_must_fit_and_the_feature_is_named() {
        let raw = Image::new(3, 1);
        let guides = Guides {
            width: 2,
            height: 1,
            albedo: vec![Color::ONE; 2],
            normal: vec![Vec3A::Z; 2],
            light: vec![Color::ZERO; 2],
            sharp_light: vec![Color::ZERO; 2],
        };
        assert!(matches!(
            denoise(&raw, &guides),
            Err(DenoiseError::Size(2, 1, 3, 1))
        ));
        if !AVAILABLE {
            let fits = Guides {
                width: 3,
                albedo: vec![Color::ONE; 3],
                normal: vec![Vec3A::Z; 3],
                light: vec![Color::ZERO; 3],
                sharp_light: vec![Color::ZERO; 3],
                ..guides
            };
            let e = denoise(&raw, &fits).unwrap_err();
            assert!(e.to_string().contains("pip install pyoidn"), "{e}");
        }
    }
}
