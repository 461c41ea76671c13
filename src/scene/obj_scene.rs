//! A Wavefront OBJ file opened on its own (the viewer's "open a scene"): a scene
//! table around it, as glTF files get one. The model keeps its MTL materials
//! (a grey Lambertian where it names none); the camera frames it from +z, as a
//! glTF file without a camera is framed; one point light sits above and behind
//! the eye, bright enough that a white surface facing it at the model's centre
//! shows about radiance 1/π of unit irradiance (intensity = distance²). These are
//! choices of ours: an OBJ file has no camera or lights.

use super::gltf::framing;
use super::obj;
use super::resources::Resources;
use crate::error::Result;
use glam::DVec3;
use std::path::Path;
use toml::{Table, Value};

/// The scene table of the OBJ file `path`, and what the scene should say of it.
pub fn table(path: &str, files: &dyn Resources) -> Result<(Table, Vec<String>)> {
    let model = obj::load(files, Path::new(path), true)?;
    let (mut low, mut high) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for vertex in model.faces.iter().flatten() {
        low = low.min(vertex.position);
        high = high.max(vertex.position);
    }
    let camera = framing(low, high);
    let eye = vec3(&camera["eye"]);
    let look_at = vec3(&camera["look_at"]);
    let distance = (eye - look_at).length();
    let light = eye + DVec3::Y * distance * 0.5;
    let intensity = (light - look_at).length_squared();
    let mut warnings = vec![format!(
        "obj: {path} has no camera or light: framed from +z, one point light above the eye (set camera.eye, lights.0.position to move them)"
    )];
    let mut object = Table::new();
    object.insert("shape".into(), "obj".into());
    object.insert("name".into(), "model".into());
    object.insert("file".into(), path.into());
    let mut table = Table::new();
    if model.face_materials.iter().any(Option::is_none) {
        object.insert("material".into(), "grey".into());
        let mut grey = Table::new();
        grey.insert("diffuse".into(), array([0.7, 0.7, 0.7]));
        let mut materials = Table::new();
        materials.insert("grey".into(), Value::Table(grey));
        table.insert("materials".into(), Value::Table(materials));
        warnings.push(format!(
            "obj: {path} names no material for some faces: every face is grey"
        ));
    }
    let mut point = Table::new();
    point.insert("type".into(), "point".into());
    point.insert("position".into(), array(light.to_array()));
    point.insert("intensity".into(), array([intensity; 3]));
    let mut render = Table::new();
    render.insert("shading".into(), "phong".into());
    table.insert("camera".into(), Value::Table(camera));
    table.insert("render".into(), Value::Table(render));
    table.insert("lights".into(), Value::Array(vec![Value::Table(point)]));
    table.insert("objects".into(), Value::Array(vec![Value::Table(object)]));
    Ok((table, warnings))
}

fn vec3(value: &Value) -> DVec3 {
    let float = |k: usize| value[k].as_float().expect("framing writes floats");
    DVec3::new(float(0), float(1), float(2))
}

fn array<const N: usize>(values: [f64; N]) -> Value {
    Value::Array(values.map(Value::Float).to_vec())
}
