//! Images and buffers as NumPy arrays, and arrays as images: radiance as float32
//! H × W × 3, ids as int64 (−1 where none), counts as int32, values as float32
//! H × W (one channel) or H × W × 3.

use lumiere::glam::Vec3;
use lumiere::{Buffer, BufferData, Image, NO_ID};
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

pub fn image_to_array<'py>(py: Python<'py>, image: &Image) -> Bound<'py, PyAny> {
    let (w, h) = (image.width as usize, image.height as usize);
    let data: Vec<f32> = image.pixels.iter().flat_map(|p| p.to_array()).collect();
    Array3::from_shape_vec((h, w, 3), data)
        .expect("an image's pixels fill its size")
        .into_pyarray(py)
        .into_any()
}

pub fn buffer_to_array<'py>(py: Python<'py>, buffer: &Buffer) -> Bound<'py, PyAny> {
    let (w, h) = (buffer.width as usize, buffer.height as usize);
    let shape = (h, w);
    match &buffer.data {
        BufferData::Ids(ids) => {
            let v: Vec<i64> = ids
                .iter()
                .map(|&i| if i == NO_ID { -1 } else { i as i64 })
                .collect();
            Array2::from_shape_vec(shape, v)
                .expect("sized")
                .into_pyarray(py)
                .into_any()
        }
        BufferData::Counts(c) => Array2::from_shape_vec(shape, c.clone())
            .expect("sized")
            .into_pyarray(py)
            .into_any(),
        BufferData::Values { channels: 1, data } => Array2::from_shape_vec(shape, data.clone())
            .expect("sized")
            .into_pyarray(py)
            .into_any(),
        BufferData::Values { channels, data } => {
            Array3::from_shape_vec((h, w, *channels), data.clone())
                .expect("sized")
                .into_pyarray(py)
                .into_any()
        }
    }
}

/// An H × W × 3 array of numbers (any float or integer dtype) as an image.
pub fn array_to_image(array: &Bound<'_, PyAny>, name: &str) -> PyResult<Image> {
    let np = array.py().import("numpy")?;
    let as_f32 = np
        .call_method1("asarray", (array, "float32"))
        .map_err(|e| PyTypeError::new_err(format!("{name}: not an array of numbers: {e}")))?;
    let view: PyReadonlyArrayDyn<f32> = as_f32.extract()?;
    let shape = view.shape().to_vec();
    if shape.len() != 3 || shape[2] != 3 {
        return Err(PyValueError::new_err(format!(
            "{name}: an image is an H x W x 3 array, not of shape {shape:?}"
        )));
    }
    let (h, w) = (shape[0], shape[1]);
    if h == 0 || w == 0 || h > u32::MAX as usize || w > u32::MAX as usize {
        return Err(PyValueError::new_err(format!(
            "{name}: {h} x {w} is not an image size"
        )));
    }
    let data = view.as_array();
    let pixels = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| Vec3::new(data[[y, x, 0]], data[[y, x, 1]], data[[y, x, 2]]))
        .collect();
    Ok(Image {
        width: w as u32,
        height: h as u32,
        pixels,
    })
}
