//! A renderer that keeps its pre-passes between frames, and the frames it makes.
//!
//! A frame renders on a worker thread with the GIL released; the calling thread
//! waits in short sleeps and looks for signals between them, so a KeyboardInterrupt
//! pulls the renderer's stop switch and the frame ends after its current band.

use crate::arrays::{buffer_to_array, image_to_array};
use crate::errors::{IntoPy, to_py};
use crate::overrides;
use crate::scene::Scene;
use lumiere::{Buffer, Image};
use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// A scene and the view-independent work of its frames (shadow maps, shadow
/// polygons and volumes, a radiosity solution), kept while the camera, the lights
/// and the shadow settings change.
#[pyclass(module = "lumiere")]
pub struct Renderer {
    /// The scene as last changed (its overrides build the changes).
    scene: Scene,
    inner: lumiere::Renderer,
    stop: Arc<AtomicBool>,
    texture_filter: Option<String>,
}

impl Renderer {
    fn make(scene: Scene) -> Renderer {
        let stop = Arc::new(AtomicBool::new(false));
        let mut inner = lumiere::Renderer::new(scene.inner.clone());
        inner.set_stop(stop.clone());
        Renderer {
            scene,
            inner,
            stop,
            texture_filter: None,
        }
    }

    /// The scene with more overrides.
    fn changed(&self, sets: Vec<String>) -> PyResult<Scene> {
        self.scene.with_sets(&sets)
    }
}

#[pymethods]
impl Renderer {
    #[new]
    fn new(scene: &Scene) -> Renderer {
        Renderer::make(scene.clone())
    }

    /// The scene as the renderer now has it.
    #[getter]
    fn scene(&self) -> Scene {
        self.scene.clone()
    }

    /// How many view-independent pre-passes were built: occluders, light_shadows,
    /// radiosity, captures.
    #[getter]
    fn prepasses(&self) -> std::collections::BTreeMap<&'static str, usize> {
        let p = self.inner.prepasses();
        [
            ("occluders", p.occluders),
            ("light_shadows", p.light_shadows),
            ("radiosity", p.radiosity),
            ("captures", p.captures),
        ]
        .into_iter()
        .collect()
    }

    /// What the scene's methods warn about.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.inner.warnings()
    }

    /// The buffers this scene's frame can make, as (name, description).
    fn available_buffers(&self) -> PyResult<Vec<(String, String)>> {
        Ok(self
            .inner
            .available_buffers()
            .py_err()?
            .into_iter()
            .map(|b| (b.name, b.description))
            .collect())
    }

    /// Moves the camera: `eye`, `look_at`, `up`, `fov_y`, `width`, `height` (the
    /// keys of `camera.*`); the pre-passes are kept.
    #[pyo3(signature = (**fields))]
    fn set_camera(&mut self, fields: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
        let scene = self.changed(overrides::sets("camera", None, fields)?)?;
        self.inner.set_camera(scene.inner.camera.clone());
        self.scene = scene;
        Ok(())
    }

    /// Changes light `index` (`position`, `intensity`, … as in the scene file);
    /// only that light's pre-pass is built again.
    #[pyo3(signature = (index, **fields))]
    fn set_light(&mut self, index: usize, fields: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
        let scene = self.changed(overrides::sets(&format!("lights.{index}"), None, fields)?)?;
        let light = scene.inner.lights.get(index).cloned().ok_or_else(|| {
            PyValueError::new_err(format!(
                "light {index}: the scene has {} lights",
                scene.inner.lights.len()
            ))
        })?;
        self.inner.set_light(index, light).py_err()?;
        self.scene = scene;
        Ok(())
    }

    /// Changes the shadow settings: `method`, `map_resolution`, `light_points`, …
    /// (the keys of `shadows.*`).
    #[pyo3(signature = (**fields))]
    fn set_shadows(&mut self, fields: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
        let scene = self.changed(overrides::sets("shadows", None, fields)?)?;
        self.inner.set_shadows(scene.inner.shadows.clone());
        self.scene = scene;
        Ok(())
    }

    /// Forces `filter` on every texture (or none: each texture's own), as the
    /// viewer's f key does; the scene's textures are built again, and with them the
    /// renderer.
    #[pyo3(signature = (filter))]
    fn set_texture_filter(&mut self, filter: Option<String>) -> PyResult<()> {
        let names: Vec<String> = self
            .scene
            .inner
            .textures
            .iter()
            .map(|t| t.name.clone())
            .collect();
        let sets: Vec<String> = match &filter {
            Some(f) => names
                .iter()
                .map(|n| format!("textures.{n}.filter=\"{f}\""))
                .collect(),
            None => Vec::new(),
        };
        let scene = self.scene.with_sets(&sets)?;
        let mut renderer = Renderer::make(scene);
        renderer.texture_filter = filter;
        *self = renderer;
        Ok(())
    }

    /// The texture filter forced on every texture, if any.
    #[getter]
    fn texture_filter(&self) -> Option<String> {
        self.texture_filter.clone()
    }

    /// Renders a frame with the buffers named in `aovs` (`"all"` for every one this
    /// scene makes). The GIL is released while it renders; Ctrl-C stops it.
    #[pyo3(signature = (aovs = Vec::new()))]
    fn render(&self, py: Python<'_>, aovs: Vec<String>) -> PyResult<Frame> {
        let buffers = aovs;
        let wanted: Vec<String> = if buffers.iter().any(|b| b == "all") {
            self.inner
                .available_buffers()
                .py_err()?
                .into_iter()
                .map(|b| b.name)
                .collect()
        } else {
            buffers
        };
        self.stop.store(false, Ordering::Relaxed);
        let renderer = &self.inner;
        let stop = &self.stop;
        let frame = std::thread::scope(|s| -> PyResult<lumiere::Frame> {
            let worker = s.spawn(move || renderer.render_with_buffers(&wanted));
            while !worker.is_finished() {
                py.detach(|| std::thread::sleep(Duration::from_millis(10)));
                if let Err(interrupt) = py.check_signals() {
                    stop.store(true, Ordering::Relaxed);
                    let _ = py.detach(|| worker.join());
                    return Err(interrupt);
                }
            }
            match worker.join() {
                Ok(result) => result.map_err(to_py),
                Err(_) => Err(crate::errors::Error::new_err(
                    "the render failed inside lumiere (a defect: please report it)",
                )),
            }
        })?;
        Ok(Frame {
            image: frame.image,
            buffers: frame.buffers,
            exposure: self.scene.inner.render.exposure,
        })
    }

    fn __repr__(&self) -> String {
        let p = self.inner.prepasses();
        format!(
            "Renderer({}, {} light pre-passes built)",
            self.scene.__repr__(),
            p.light_shadows
        )
    }
}

/// A rendered frame: the linear radiance image and the buffers asked for.
#[pyclass(module = "lumiere", frozen)]
pub struct Frame {
    image: Image,
    buffers: Vec<Buffer>,
    exposure: f32,
}

#[pymethods]
impl Frame {
    /// Linear radiance, float32, height x width x 3.
    #[getter]
    fn image<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        image_to_array(py, &self.image)
    }

    /// Width in pixels.
    #[getter]
    fn width(&self) -> u32 {
        self.image.width
    }

    /// Height in pixels.
    #[getter]
    fn height(&self) -> u32 {
        self.image.height
    }

    /// The scene's exposure (what `srgb()` uses by default).
    #[getter]
    fn exposure(&self) -> f32 {
        self.exposure
    }

    /// The names of the buffers this frame holds.
    fn buffers(&self) -> Vec<String> {
        self.buffers.iter().map(|b| b.name.clone()).collect()
    }

    /// The image as a PNG shows it: 8-bit sRGB after the exposure, uint8
    /// height x width x 3.
    #[pyo3(signature = (exposure = None))]
    fn srgb<'py>(&self, py: Python<'py>, exposure: Option<f32>) -> PyResult<Bound<'py, PyAny>> {
        let exposure = exposure.unwrap_or(self.exposure);
        if !(exposure.is_finite() && exposure > 0.0) {
            return Err(PyValueError::new_err(format!(
                "exposure {exposure}: must be a positive number"
            )));
        }
        let bytes = self.image.to_srgb8(exposure);
        let (w, h) = (self.image.width as usize, self.image.height as usize);
        Ok(numpy::ndarray::Array3::from_shape_vec((h, w, 3), bytes)
            .expect("sized")
            .into_pyarray_any(py))
    }

    fn __getitem__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        match self.buffers.iter().find(|b| b.name == name) {
            Some(b) => Ok(buffer_to_array(py, b)),
            None => Err(PyKeyError::new_err(format!(
                "this frame has no buffer `{name}`; it has: {}",
                self.buffers().join(", ")
            ))),
        }
    }

    fn __contains__(&self, name: &str) -> bool {
        self.buffers.iter().any(|b| b.name == name)
    }

    fn __repr__(&self) -> String {
        format!(
            "Frame({}x{}, buffers [{}])",
            self.image.width,
            self.image.height,
            self.buffers().join(", ")
        )
    }
}

trait IntoAny {
    fn into_pyarray_any(self, py: Python<'_>) -> Bound<'_, PyAny>;
}

impl IntoAny for numpy::ndarray::Array3<u8> {
    fn into_pyarray_any(self, py: Python<'_>) -> Bound<'_, PyAny> {
        use numpy::IntoPyArray;
        self.into_pyarray(py).into_any()
    }
}
