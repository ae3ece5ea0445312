//! The call of Intel Open Image Denoise (the `oidn` crate, which links the library): its
//! ray tracing filter ("RT") on a high dynamic range picture with clean albedo and normal
//! guides, on the default device (the CPU here).

use super::{DenoiseError, Guides};
use crate::film::Image;
use crate::math::Color;

/// Whether a device can be made.
pub(super) fn ready() -> Result<(), DenoiseError> {
    ::oidn::Device::new()
        .map(drop)
        .map_err(|e| DenoiseError::Library(e.to_string()))
}

/// `image` denoised with `guides`; any error of the library (it could not find a device,
/// the filter failed) as a message.
pub(super) fn filter(image: &Image, guides: &Guides) -> Result<Image, DenoiseError> {
    let failed = |e: ::oidn::Error| DenoiseError::Library(e.to_string());
    let flat = |v: &mut dyn Iterator<Item = [f32; 3]>| v.flatten().collect::<Vec<f32>>();
    let color = flat(&mut image.pixels.iter().map(|c| c.to_array()));
    let albedo = flat(&mut guides.albedo.iter().map(|c| c.to_array()));
    let normal = flat(&mut guides.normal.iter().map(|n| n.to_array()));
    let mut out = vec![0.0f32; color.len()];
    let device = ::oidn::Device::new().map_err(failed)?;
    ::oidn::RayTracing::try_new(&device)
        .map_err(failed)?
        .hdr(true)
        .clean_aux(true)
        .image_dimensions(image.width as usize, image.height as usize)
        .albedo_normal(&albedo, &normal)
        .filter(&color, &mut out)
        .map_err(failed)?;
    device.get_error().map_err(failed)?;
    Ok(Image {
        width: image.width,
        height: image.height,
        pixels: out
            .chunks_exact(3)
            .map(|c| Color::new(c[0], c[1], c[2]).max(Color::ZERO))
            .collect(),
    })
}
