//! `snell._snell`: the native half of the Python module `snell`. It holds what needs
//! Rust (building scenes, rendering with the interpreter's lock released, encoding and
//! decoding images); the Python package around it (python/snell) gives it its shape: the
//! `Scene` a script edits, the `Image` a notebook shows, keyword defaults and docstrings.
//!
//! Nothing here is `unsafe` of its own; what pyo3's macros generate is theirs.

#![deny(unsafe_code)]

mod errors;
mod images;
mod render;
mod scene;

use pyo3::prelude::*;

/// The module `snell._snell`.
#[pymodule]
fn _snell(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add("SettingsError", py.get_type::<errors::SettingsError>())?;
    m.add_class::<scene::NativeScene>()?;
    m.add_class::<scene::Assets>()?;
    m.add_function(wrap_pyfunction!(scene::load, m)?)?;
    m.add_function(wrap_pyfunction!(scene::loads, m)?)?;
    m.add_function(wrap_pyfunction!(render::render, m)?)?;
    m.add_function(wrap_pyfunction!(render::explain, m)?)?;
    m.add_function(wrap_pyfunction!(images::write, m)?)?;
    m.add_function(wrap_pyfunction!(images::read, m)?)?;
    m.add_function(wrap_pyfunction!(images::encode_png, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("CAN_DENOISE", snell::denoise::AVAILABLE)?;
    Ok(())
}
