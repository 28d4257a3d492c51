//! Core errors as Python exceptions.
//!
//! The exception classes live in `tumble/errors.py` (so they can inherit from both `TumbleError`
//! and a built-in: `ValueError`, `LookupError`); they are looked up once and cached. The message
//! is always the core's `Display` text.

use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::PyType;
use tumble::{MassError, WorldError};

static VALUE_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();
static STALE_ERROR: PyOnceLock<Py<PyType>> = PyOnceLock::new();

fn error_class(py: Python<'_>, cell: &'static PyOnceLock<Py<PyType>>, name: &str) -> PyResult<Py<PyType>> {
    cell.get_or_try_init(py, || {
        let class = py.import("tumble.errors")?.getattr(name)?;
        Ok::<_, PyErr>(class.cast_into::<PyType>()?.unbind())
    })
    .map(|c| c.clone_ref(py))
}

fn raise(cell: &'static PyOnceLock<Py<PyType>>, name: &str, message: String) -> PyErr {
    Python::attach(|py| match error_class(py, cell, name) {
        Ok(class) => PyErr::from_type(class.into_bound(py), message),
        // The package files are missing (the extension module imported on its own): still a
        // Python exception with the core's message, never a crash.
        Err(_) => pyo3::exceptions::PyValueError::new_err(message),
    })
}

/// A rejected value: `tumble.TumbleValueError` (a `TumbleError` and a `ValueError`).
pub fn value_error(message: impl Into<String>) -> PyErr {
    raise(&VALUE_ERROR, "TumbleValueError", message.into())
}

/// A handle that names nothing: `tumble.StaleHandleError` (a `TumbleError` and a `LookupError`).
pub fn stale_error(message: impl Into<String>) -> PyErr {
    raise(&STALE_ERROR, "StaleHandleError", message.into())
}

/// Converts a core error into the matching Python exception.
pub fn world_error(e: WorldError) -> PyErr {
    match e {
        WorldError::StaleBody(_) | WorldError::StaleJoint(_) => stale_error(e.to_string()),
        _ => value_error(e.to_string()),
    }
}

pub fn mass_error(e: MassError) -> PyErr {
    value_error(e.to_string())
}

/// `?`-friendly conversions: `world.step(dt).map_err(world_error)?` reads worse than `.py()?`.
pub trait IntoPyResult<T> {
    fn py(self) -> PyResult<T>;
}

impl<T> IntoPyResult<T> for Result<T, WorldError> {
    fn py(self) -> PyResult<T> {
        self.map_err(world_error)
    }
}

impl<T> IntoPyResult<T> for Result<T, MassError> {
    fn py(self) -> PyResult<T> {
        self.map_err(mass_error)
    }
}
