//! Scenes: from a catalogue id, a scene file or TOML text, with the command line's
//! `key=value` overrides (the package turns keyword arguments into them), and the
//! catalogue's entries.

use crate::errors::IntoPy;
use crate::overrides;
use lumiere::{catalogue as cat, load_scene, scene_from_toml};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Where a scene came from, so an override can build it again.
#[derive(Clone, Debug)]
enum Source {
    Spec(String),
    Toml(String),
}

/// A scene: its geometry, materials, lights, camera and method settings.
#[pyclass(module = "lumiere", frozen)]
#[derive(Clone)]
pub struct Scene {
    source: Source,
    sets: Vec<String>,
    pub inner: lumiere::Scene,
}

impl Scene {
    /// The same source with `more` overrides after its own.
    pub fn with_sets(&self, more: &[String]) -> PyResult<Scene> {
        let mut sets = self.sets.clone();
        sets.extend_from_slice(more);
        Scene::build(self.source.clone(), sets)
    }

    fn build(source: Source, sets: Vec<String>) -> PyResult<Scene> {
        let inner = match &source {
            Source::Spec(spec) => load_scene(spec, &sets),
            Source::Toml(text) => scene_from_toml(text, &sets),
        }
        .py_err()?;
        Ok(Scene {
            source,
            sets,
            inner,
        })
    }
}

#[pymethods]
impl Scene {
    /// A catalogue entry or scene file (`.toml`, `.gltf`, `.glb`), with overrides as
    /// a dict or keyword arguments: the keys of `--set` (`camera.width`), or nested
    /// (`camera={"width": 256}`).
    #[staticmethod]
    #[pyo3(signature = (spec, overrides = None, **kwargs))]
    fn load(
        spec: std::path::PathBuf,
        overrides: Option<&Bound<'_, PyAny>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Scene> {
        let spec = spec.to_string_lossy().into_owned();
        Scene::build(Source::Spec(spec), overrides::sets("", overrides, kwargs)?)
    }

    /// A scene from the text of a scene file (it may `extends` a catalogue entry),
    /// with overrides as for `load`.
    #[staticmethod]
    #[pyo3(signature = (text, overrides = None, **kwargs))]
    fn from_toml(
        text: String,
        overrides: Option<&Bound<'_, PyAny>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Scene> {
        Scene::build(Source::Toml(text), overrides::sets("", overrides, kwargs)?)
    }

    /// This scene with more overrides applied after its own (as for `load`).
    #[pyo3(signature = (overrides = None, **kwargs))]
    fn with_overrides(
        &self,
        overrides: Option<&Bound<'_, PyAny>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Scene> {
        self.with_sets(&overrides::sets("", overrides, kwargs)?)
    }

    /// The overrides applied, in order.
    #[getter]
    fn sets(&self) -> Vec<String> {
        self.sets.clone()
    }

    /// The image's width in pixels.
    #[getter]
    fn width(&self) -> u32 {
        self.inner.camera.width
    }

    /// The image's height in pixels.
    #[getter]
    fn height(&self) -> u32 {
        self.inner.camera.height
    }

    /// The camera: eye, look_at, up, fov_y, width, height.
    #[getter]
    fn camera<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let c = &self.inner.camera;
        let d = PyDict::new(py);
        d.set_item("eye", c.eye.to_array())?;
        d.set_item("look_at", c.look_at.to_array())?;
        d.set_item("up", c.up.to_array())?;
        d.set_item("fov_y", c.fov_y)?;
        d.set_item("width", c.width)?;
        d.set_item("height", c.height)?;
        Ok(d)
    }

    /// The lights, each as (kind, label).
    #[getter]
    fn lights(&self) -> Vec<(String, String)> {
        self.inner
            .lights
            .iter()
            .enumerate()
            .map(|(i, l)| (l.kind().name().to_string(), l.label(i)))
            .collect()
    }

    /// The shadow method's name.
    #[getter]
    fn shadow_method(&self) -> String {
        self.inner.shadows.method.name().to_string()
    }

    /// Warnings the scene gave while it was built.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.inner.warnings.clone()
    }

    pub fn __repr__(&self) -> String {
        let source = match &self.source {
            Source::Spec(s) => s.clone(),
            Source::Toml(_) => "<toml>".into(),
        };
        format!(
            "Scene({source:?}, {}x{}, {} lights, shadows {:?})",
            self.inner.camera.width,
            self.inner.camera.height,
            self.inner.lights.len(),
            self.inner.shadows.method.name()
        )
    }
}

/// The catalogue: one dict per entry (id, year, topic, title, authors, summary,
/// citation), sorted by id.
#[pyfunction]
pub fn catalogue<'py>(py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let mut out = Vec::new();
    for id in cat::ids() {
        let a = cat::entry(&id).py_err()?.algorithm;
        let d = PyDict::new(py);
        d.set_item("id", &a.id)?;
        d.set_item("year", a.year)?;
        d.set_item("topic", a.topic.name())?;
        d.set_item("title", &a.title)?;
        d.set_item("authors", &a.authors)?;
        d.set_item("summary", &a.summary)?;
        d.set_item("citation", &a.citation)?;
        out.push(d);
    }
    Ok(out)
}
