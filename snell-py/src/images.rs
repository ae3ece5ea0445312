//! Pictures between snell and numpy: a render's image as an array, arrays written as PNG or
//! EXR (atomically, through the command line's writer), files read back as linear arrays.

use crate::errors;
use numpy::{PyArray1, PyArray3, PyArrayMethods, PyReadonlyArray3};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use snell::film::Image;
use snell::math::Color;
use snell::output::PendingOutput;
use snell::output::tone::{Tone, ToneCurve};
use snell::texture::{ColorSpace, ImageData};
use std::path::PathBuf;

/// `img` as a float32 array, height x width x 3: the values an EXR of it holds.
pub fn image_array<'py>(py: Python<'py>, img: &Image) -> Bound<'py, PyArray3<f32>> {
    let data: Vec<f32> = img.pixels.iter().flat_map(|c| c.to_array()).collect();
    let (w, h) = (img.width as usize, img.height as usize);
    PyArray1::from_vec(py, data)
        .reshape([h, w, 3])
        .expect("a picture's pixels are its width times its height")
}

/// A debug view's channels (each one value per pixel) as one array, height x width x
/// channels.
pub fn channels_array<'py>(
    py: Python<'py>,
    channels: &[(&str, Vec<f32>)],
    w: usize,
    h: usize,
) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let n = channels.len();
    let mut data = vec![0.0f32; w * h * n];
    for (c, (_, values)) in channels.iter().enumerate() {
        for (i, v) in values.iter().enumerate() {
            data[i * n + c] = *v;
        }
    }
    PyArray1::from_vec(py, data).reshape([h, w, n])
}

/// An array (height x width x 3, linear) as an image.
fn to_image(array: &PyReadonlyArray3<'_, f32>) -> PyResult<Image> {
    let a = array.as_array();
    let (h, w, c) = a.dim();
    if c != 3 {
        return Err(errors::value(format!(
            "an image has 3 channels (height x width x 3), not {c}"
        )));
    }
    if w == 0 || h == 0 || w > u32::MAX as usize || h > u32::MAX as usize {
        return Err(errors::value(format!("an image of {w} x {h} pixels")));
    }
    // Each pixel's three values, row by row (whatever the array's strides).
    let pixels = a
        .lanes(numpy::ndarray::Axis(2))
        .into_iter()
        .map(|p| Color::new(p[0], p[1], p[2]))
        .collect();
    Ok(Image {
        width: w as u32,
        height: h as u32,
        pixels,
    })
}

fn tone(exposure: f32, tonemap: &str) -> PyResult<Tone> {
    if !exposure.is_finite() {
        return Err(errors::value(format!(
            "exposure must be finite, not {exposure}"
        )));
    }
    let curve = ToneCurve::from_name(tonemap).ok_or_else(|| {
        errors::value(format!(
            "no tone curve {tonemap:?}; the curves are {}",
            ToneCurve::ALL.map(|c| c.name()).join(", ")
        ))
    })?;
    Ok(Tone { exposure, curve })
}

/// Writes `array` to `path`: a PNG (8-bit sRGB after `exposure` stops and the tone curve)
/// or an EXR (linear floats as they are), by the extension; written beside and renamed into
/// place, so a failed write leaves no half file and an old file stays whole.
#[pyfunction]
#[pyo3(signature = (array, path, exposure=0.0, tonemap="clamp"))]
pub fn write(
    py: Python<'_>,
    array: PyReadonlyArray3<'_, f32>,
    path: PathBuf,
    exposure: f32,
    tonemap: &str,
) -> PyResult<()> {
    let img = to_image(&array)?;
    let tone = tone(exposure, tonemap)?;
    py.detach(|| PendingOutput::create(&path)?.commit_toned(&img, &tone))
        .map_err(errors::io)
}

/// The PNG bytes of `array` after `exposure` and the tone curve (what a notebook shows).
#[pyfunction]
#[pyo3(signature = (array, exposure=0.0, tonemap="clamp"))]
pub fn encode_png<'py>(
    py: Python<'py>,
    array: PyReadonlyArray3<'_, f32>,
    exposure: f32,
    tonemap: &str,
) -> PyResult<Bound<'py, PyBytes>> {
    let img = to_image(&array)?;
    let tone = tone(exposure, tonemap)?;
    let bytes = snell::output::encode_display(&img, &tone, None).map_err(errors::io)?;
    Ok(PyBytes::new(py, &bytes))
}

/// Reads a PNG, JPEG, BMP, Radiance HDR or OpenEXR file as a linear float32 array, height x
/// width x 3 (8-bit files are taken as sRGB, as textures are).
#[pyfunction]
pub fn read(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyArray3<f32>>> {
    let img = py
        .detach(|| ImageData::load(&path, ColorSpace::Srgb))
        .map_err(errors::io)?;
    let (w, h) = (img.width(), img.height());
    let mut data = Vec::with_capacity(w as usize * h as usize * 3);
    for y in 0..h {
        for x in 0..w {
            data.extend(img.texel(x, y).to_array());
        }
    }
    PyArray1::from_vec(py, data).reshape([h as usize, w as usize, 3])
}
