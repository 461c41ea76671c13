//! lumiere's errors as Python exceptions: `Error` and a subclass per kind, each
//! carrying the command line's one-line message (the error and its causes joined
//! by ": ").

use lumiere::Error as E;
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(lumiere, Error, PyException, "Every error lumiere reports.");
create_exception!(
    lumiere,
    IoError,
    Error,
    "A file could not be read or written."
);
create_exception!(lumiere, ParseError, Error, "A scene's TOML does not parse.");
create_exception!(
    lumiere,
    OverrideError,
    Error,
    "An override (`key=value`) cannot be applied."
);
create_exception!(
    lumiere,
    SceneError,
    Error,
    "A scene value or catalogue id that cannot be used."
);
create_exception!(
    lumiere,
    ImageError,
    Error,
    "An image that cannot be read, or images of different sizes."
);
create_exception!(
    lumiere,
    UnsupportedError,
    Error,
    "A combination of settings a method does not handle."
);
create_exception!(
    lumiere,
    OverBudgetError,
    Error,
    "Settings that would need more memory than their budget."
);

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("Error", py.get_type::<Error>())?;
    m.add("IoError", py.get_type::<IoError>())?;
    m.add("ParseError", py.get_type::<ParseError>())?;
    m.add("OverrideError", py.get_type::<OverrideError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("ImageError", py.get_type::<ImageError>())?;
    m.add("UnsupportedError", py.get_type::<UnsupportedError>())?;
    m.add("OverBudgetError", py.get_type::<OverBudgetError>())?;
    Ok(())
}

/// The error and its causes on one line, as the command line prints them.
pub fn one_line(e: &dyn std::error::Error) -> String {
    let mut line = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        let text = c.to_string();
        if !line.ends_with(&text) {
            line.push_str(": ");
            line.push_str(&text);
        }
        cause = c.source();
    }
    line
}

/// A library error as the exception of its kind (by its innermost cause).
pub fn to_py(e: E) -> PyErr {
    let message = one_line(&e);
    match e.root() {
        E::Io { .. } => IoError::new_err(message),
        E::Parse { .. } => ParseError::new_err(message),
        E::Override { .. } => OverrideError::new_err(message),
        E::Image { .. } | E::Format { .. } | E::SizeMismatch { .. } => ImageError::new_err(message),
        E::Unsupported(_) => UnsupportedError::new_err(message),
        E::Memory { .. } | E::OverBudget(_) => OverBudgetError::new_err(message),
        E::Stopped => pyo3::exceptions::PyKeyboardInterrupt::new_err(message),
        _ => SceneError::new_err(message),
    }
}

/// `Result<T, lumiere::Error>` to `PyResult<T>`.
pub trait IntoPy<T> {
    fn py_err(self) -> PyResult<T>;
}

impl<T> IntoPy<T> for lumiere::Result<T> {
    fn py_err(self) -> PyResult<T> {
        self.map_err(to_py)
    }
}
