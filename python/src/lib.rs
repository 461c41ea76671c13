//! lumiere in Python: the native module `lumiere._lumiere` behind the package
//! `lumiere` (python/lumiere/__init__.py gives it Python's idiom: keyword
//! overrides, docstrings, type stubs).
//!
//! Every library error becomes a `lumiere.Error` subclass carrying the command
//! line's one-line message; renders release the GIL and stop at a
//! KeyboardInterrupt; nothing here panics across into Python.

mod arrays;
mod errors;
mod overrides;
mod renderer;
mod scene;
mod tools;

use pyo3::prelude::*;

#[pymodule]
fn _lumiere(m: &Bound<'_, PyModule>) -> PyResult<()> {
    errors::register(m)?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<renderer::Renderer>()?;
    m.add_class::<renderer::Frame>()?;
    m.add_function(wrap_pyfunction!(scene::catalogue, m)?)?;
    m.add_function(wrap_pyfunction!(tools::compare, m)?)?;
    m.add_function(wrap_pyfunction!(tools::export_scene, m)?)?;
    m.add_function(wrap_pyfunction!(tools::form_factors, m)?)?;
    m.add_function(wrap_pyfunction!(tools::shadow_polygons, m)?)?;
    m.add_function(wrap_pyfunction!(tools::read_image, m)?)?;
    m.add_function(wrap_pyfunction!(tools::write_image, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
