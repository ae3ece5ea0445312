//! The module's exceptions, and snell's errors turned into them with the command line's
//! words: a scene's problems as `file:line:col: message`, a setting's with its help.

use pyo3::exceptions::{PyException, PyOSError, PyValueError};
use pyo3::{PyErr, create_exception};
use snell::job::JobError;

create_exception!(
    _snell,
    SceneError,
    PyException,
    "A scene that cannot be built: each problem on its own line, located in the text as \
     `file:line:col: message`, as `snell render` prints them."
);
create_exception!(
    _snell,
    SettingsError,
    PyValueError,
    "Render settings that cannot be used (a side of the image, a sample count past the \
     limits), with what to do instead."
);

/// A job's error as its exception.
pub fn job(e: JobError) -> PyErr {
    match e {
        JobError::Scene(e) => SceneError::new_err(e.to_string()),
        e @ JobError::Settings { .. } => SettingsError::new_err(e.to_string()),
    }
}

/// A file that could not be read or written.
pub fn io(e: impl std::fmt::Display) -> PyErr {
    PyOSError::new_err(e.to_string())
}

/// Render settings that cannot be used, with what to do instead.
pub fn settings(message: impl Into<String>) -> PyErr {
    SettingsError::new_err(message.into())
}

/// A bad argument.
pub fn value(message: impl Into<String>) -> PyErr {
    PyValueError::new_err(message.into())
}
