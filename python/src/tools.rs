//! The command line's instruments as functions: comparing images, exporting
//! scenes, form factors, shadow polygons' areas, reading and writing images.

use crate::arrays::{array_to_image, image_to_array};
use crate::errors::IntoPy;
use crate::scene::Scene;
use lumiere::export::{Format, Options};
use lumiere::form_factors::{FormFactorMethod, polygon_form_factors};
use lumiere::shadow_polygons::receiver_shadows;
use lumiere::{FlipRange, Image, Light};
use numpy::IntoPyArray;
use numpy::ndarray::Array2;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use std::path::PathBuf;

/// An image from an array (H x W x 3) or a file path (PNG, PFM, EXR).
fn image_of(value: &Bound<'_, PyAny>, name: &str) -> PyResult<Image> {
    if value.is_instance_of::<PyString>() || value.hasattr("__fspath__")? {
        let path: PathBuf = value.extract()?;
        return lumiere::read_image(&path).py_err();
    }
    array_to_image(value, name)
}

/// How far two images are apart, as `lumiere compare --json` says it.
#[pyfunction]
#[pyo3(signature = (a, b, exposure = 1.0, flip = None, ppd = None, border = 0))]
pub fn compare<'py>(
    py: Python<'py>,
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    exposure: f32,
    flip: Option<&str>,
    ppd: Option<f32>,
    border: u32,
) -> PyResult<Bound<'py, PyDict>> {
    if !(exposure.is_finite() && exposure > 0.0) {
        return Err(PyValueError::new_err(format!(
            "exposure {exposure}: must be a positive number"
        )));
    }
    let (a, b) = (image_of(a, "a")?, image_of(b, "b")?);
    let c = lumiere::compare_images(&a, &b, exposure).py_err()?;
    let d = PyDict::new(py);
    d.set_item("rmse", c.rmse)?;
    d.set_item("psnr", c.psnr)?;
    d.set_item("max_difference", c.max_difference)?;
    d.set_item("differing_share", c.differing_share)?;
    let f = lumiere::fuzzy_match(&a, &b, exposure, border).py_err()?;
    let fuzzy = PyDict::new(py);
    fuzzy.set_item("differing_pixels", f.differing_pixels)?;
    fuzzy.set_item("largest_pixel_delta", f.largest_pixel_delta)?;
    fuzzy.set_item("border", f.border)?;
    d.set_item("fuzzy", fuzzy)?;
    if let Some(range) = flip {
        let range = match range {
            "ldr" => FlipRange::Ldr,
            "hdr" => FlipRange::Hdr {
                start: None,
                stop: None,
                exposures: None,
            },
            other => {
                return Err(PyValueError::new_err(format!(
                    "flip {other:?}: \"ldr\" or \"hdr\""
                )));
            }
        };
        let scaled = |i: &Image| Image {
            pixels: i.pixels.iter().map(|p| *p * exposure).collect(),
            ..i.clone()
        };
        let ppd = ppd.unwrap_or_else(lumiere::default_pixels_per_degree);
        let result = py
            .detach(|| lumiere::flip(&scaled(&a), &scaled(&b), range, ppd))
            .py_err()?;
        let v = PyDict::new(py);
        v.set_item("mean", result.mean)?;
        for p in [50.0, 95.0, 99.0, 100.0] {
            v.set_item(format!("p{p}"), result.percentile(p))?;
        }
        v.set_item("pixels_per_degree", ppd)?;
        let (w, h) = (a.width as usize, a.height as usize);
        v.set_item(
            "map",
            Array2::from_shape_vec((h, w), result.map)
                .expect("sized")
                .into_pyarray(py),
        )?;
        d.set_item("flip", v)?;
    }
    Ok(d)
}

/// Writes `scene` for another renderer (`"pov"`, `"mitsuba"`, `"gltf"`, `"obj"`);
/// returns what the format could not hold, a line each.
#[pyfunction(name = "export")]
pub fn export_scene(scene: &Scene, format: &str, path: PathBuf) -> PyResult<Vec<String>> {
    let format = match format {
        "pov" => Format::Pov,
        "mitsuba" => Format::Mitsuba,
        "gltf" => Format::Gltf,
        "obj" => Format::Obj,
        other => {
            return Err(PyValueError::new_err(format!(
                "format {other:?}: one of \"pov\", \"mitsuba\", \"gltf\", \"obj\""
            )));
        }
    };
    lumiere::export::export(&scene.inner, &Options::new(format), &path).py_err()
}

/// The patch-to-patch form factors of `scene`, each polygon a patch: (names,
/// areas, factors) with factors[i, j] the share of i's energy reaching j.
#[pyfunction]
#[pyo3(signature = (scene, method = "hemicube", resolution = 128, elements = 1))]
pub fn form_factors<'py>(
    py: Python<'py>,
    scene: &Scene,
    method: &str,
    resolution: u32,
    elements: u32,
) -> PyResult<(Vec<String>, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let method = match method {
        "hemicube" => FormFactorMethod::Hemicube,
        "nusselt" => FormFactorMethod::Nusselt,
        "analytic" => FormFactorMethod::Analytic,
        other => {
            return Err(PyValueError::new_err(format!(
                "method {other:?}: one of \"hemicube\", \"nusselt\", \"analytic\""
            )));
        }
    };
    if !(2..=4096).contains(&resolution) || !(1..=256).contains(&elements) {
        return Err(PyValueError::new_err(format!(
            "resolution {resolution} (2 to 4096) or elements {elements} (1 to 256) out of range"
        )));
    }
    let s = &scene.inner;
    let matrix = py
        .detach(|| polygon_form_factors(s, method, resolution, elements))
        .py_err()?;
    let names = matrix
        .patches
        .iter()
        .map(|p| {
            format!(
                "{}#{}",
                s.objects[s.polygons[p.polygon].object].name, p.polygon
            )
        })
        .collect();
    let areas: Vec<f64> = matrix.patches.iter().map(|p| p.area).collect();
    let n = matrix.factors.len();
    let flat: Vec<f64> = matrix.factors.into_iter().flatten().collect();
    Ok((
        names,
        areas.into_pyarray(py).into_any(),
        Array2::from_shape_vec((n, n), flat)
            .map_err(|e| PyValueError::new_err(e.to_string()))?
            .into_pyarray(py)
            .into_any(),
    ))
}

/// Every polygon's lit and shadowed area under point (or spot) light `light`,
/// as `lumiere shadow-polygons --json` gives them: a dict per polygon.
#[pyfunction]
#[pyo3(signature = (scene, light = 0))]
pub fn shadow_polygons<'py>(
    py: Python<'py>,
    scene: &Scene,
    light: usize,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let position = match scene.inner.lights.get(light) {
        Some(Light::Point(p)) => p.position,
        Some(Light::Spot(s)) => s.position,
        Some(_) => {
            return Err(PyValueError::new_err(format!(
                "light {light}: shadow polygons are cast from a point or spot light"
            )));
        }
        None => {
            return Err(PyValueError::new_err(format!(
                "light {light}: the scene has {} lights",
                scene.inner.lights.len()
            )));
        }
    };
    let receivers = py.detach(|| receiver_shadows(&scene.inner, position));
    receivers
        .into_iter()
        .map(|r| {
            let d = PyDict::new(py);
            d.set_item("polygon", r.polygon)?;
            d.set_item("object", r.object)?;
            d.set_item("area", r.area)?;
            d.set_item("lit_area", r.lit_area)?;
            d.set_item("shadowed_area", r.shadowed_area)?;
            Ok(d)
        })
        .collect()
}

/// An image file (PNG, PFM, EXR) as linear float32 H x W x 3.
#[pyfunction]
pub fn read_image<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyAny>> {
    Ok(image_to_array(py, &lumiere::read_image(&path).py_err()?))
}

/// Writes an H x W x 3 array of linear radiance as PNG (sRGB after `exposure`),
/// PFM or EXR, by extension; whole or not at all.
#[pyfunction]
#[pyo3(signature = (image, path, exposure = 1.0))]
pub fn write_image(image: &Bound<'_, PyAny>, path: PathBuf, exposure: f32) -> PyResult<()> {
    if !(exposure.is_finite() && exposure > 0.0) {
        return Err(PyTypeError::new_err(format!(
            "exposure {exposure}: must be a positive number"
        )));
    }
    let image = array_to_image(image, "image")?;
    lumiere::write_image(&image, &path, exposure).py_err()
}
