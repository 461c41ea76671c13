//! The scene file as written in TOML (documented key by key in docs/scene-format.md).
//! Unknown keys are errors; values are checked when the scene is built.

use super::ShadingMode;
use serde::Deserialize;
use std::collections::BTreeMap;

pub type Vec3File = [f64; 3];

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    pub camera: CameraFile,
    #[serde(default)]
    pub render: RenderFile,
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialFile>,
    #[serde(default)]
    pub lights: Vec<LightFile>,
    #[serde(default)]
    pub objects: Vec<ObjectFile>,
    #[serde(default)]
    pub shadows: ShadowsFile,
}

/// `[shadows]`: which method, and the shadow map's settings.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShadowsFile {
    #[serde(default)]
    pub method: crate::shadow::ShadowMethod,
    /// Shadow map: texels along each side of each cube face.
    #[serde(default = "map_resolution")]
    pub map_resolution: u32,
    /// Shadow map: depth bias in texels (of the map at the sample's distance).
    #[serde(default = "map_bias")]
    pub map_bias: f64,
    /// Shadow map: percentage-closer filtering kernel (k × k texels; 1 = off).
    #[serde(default = "pcf")]
    pub pcf: u32,
    /// Shadow map: Williams's original post-pass (shadow applied to the finished
    /// image) instead of a lookup in the light model.
    #[serde(default)]
    pub post_pass: bool,
}

impl Default for ShadowsFile {
    fn default() -> Self {
        ShadowsFile {
            method: Default::default(),
            map_resolution: map_resolution(),
            map_bias: map_bias(),
            pcf: pcf(),
            post_pass: false,
        }
    }
}

fn map_resolution() -> u32 {
    1024
}
fn map_bias() -> f64 {
    1.5
}
fn pcf() -> u32 {
    1
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraFile {
    pub eye: Vec3File,
    pub look_at: Vec3File,
    #[serde(default = "y_up")]
    pub up: Vec3File,
    pub fov_y: f64,
    pub width: u32,
    pub height: u32,
    pub near: Option<f64>,
}

fn y_up() -> Vec3File {
    [0.0, 1.0, 0.0]
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderFile {
    #[serde(default = "phong")]
    pub shading: ShadingMode,
    #[serde(default = "one")]
    pub exposure: f64,
    #[serde(default = "one_sample")]
    pub supersample: u32,
    #[serde(default)]
    pub background: Vec3File,
}

impl Default for RenderFile {
    fn default() -> Self {
        RenderFile {
            shading: phong(),
            exposure: one(),
            supersample: one_sample(),
            background: [0.0; 3],
        }
    }
}

fn phong() -> ShadingMode {
    ShadingMode::Phong
}
fn one() -> f64 {
    1.0
}
fn one_sample() -> u32 {
    1
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialFile {
    #[serde(default)]
    pub diffuse: Vec3File,
    #[serde(default)]
    pub specular: Vec3File,
    #[serde(default = "one")]
    pub exponent: f64,
    #[serde(default)]
    pub emission: Vec3File,
}

#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum LightFile {
    Point {
        position: Vec3File,
        intensity: Vec3File,
    },
    Area {
        vertices: Vec<Vec3File>,
        radiance: Vec3File,
    },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ShapeKind {
    Obj,
    Polygon,
    Quad,
    Box,
    Sphere,
    Cylinder,
}

/// One object. Which of the optional keys apply depends on `shape`; a key that does
/// not apply is an error (checked in `build`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectFile {
    pub shape: ShapeKind,
    pub name: Option<String>,
    pub material: Option<String>,
    #[serde(default)]
    pub transform: Vec<TransformStep>,
    pub shading: Option<ShadingMode>,
    /// Use interpolated vertex normals (sphere, cylinder, OBJ with normals).
    pub smooth: Option<bool>,
    /// obj: path of the OBJ file, relative to the scene file.
    pub file: Option<String>,
    /// polygon: its vertices, counter-clockwise seen from the front.
    pub vertices: Option<Vec<Vec3File>>,
    /// sphere, cylinder: segments around the axis.
    pub resolution: Option<u32>,
    /// cylinder: close the ends with discs.
    pub caps: Option<bool>,
}

/// One step of an object's transform; steps apply in the order written.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "lowercase", deny_unknown_fields)]
pub enum TransformStep {
    Translate(Vec3File),
    Scale(Scale),
    Rotate { axis: Vec3File, degrees: f64 },
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum Scale {
    Uniform(f64),
    PerAxis(Vec3File),
}
