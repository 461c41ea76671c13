//! Scenes: the in-memory model every pass reads, and how it is built from files.
//!
//! A scene is a flat list of planar polygons (each knowing its object and material),
//! a camera, lights and render settings. Polygon ids are indices into that list: the
//! visible-surface buffer, the shadow methods and the radiosity mesher all speak of
//! polygons by these ids.

mod build;
pub mod file;
mod materials;
mod obj;
pub mod resources;
mod shapes;
pub mod tables;
mod transform;
mod validate;

pub use build::scene_from_table;

use glam::{DVec2, DVec3, Vec3};

/// A camera as the scene file gives it: a pinhole looking from `eye` to `look_at`.
#[derive(Clone, Debug)]
pub struct Camera {
    pub eye: DVec3,
    pub look_at: DVec3,
    pub up: DVec3,
    /// Vertical field of view in degrees.
    pub fov_y: f64,
    pub width: u32,
    pub height: u32,
    /// Distance of the near clipping plane along the view direction.
    pub near: f64,
}

/// How a polygon's colour varies across it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ShadingMode {
    /// One radiance per polygon, computed at its centroid with its geometric normal.
    Flat,
    /// Radiance computed at the vertices and interpolated (Gouraud 1971).
    Gouraud,
    /// Normals interpolated and the light model evaluated per pixel (Phong 1975).
    Phong,
}

/// Settings of a render that are not geometry.
#[derive(Clone, Debug)]
pub struct RenderSettings {
    pub shading: ShadingMode,
    /// Radiance is multiplied by this before sRGB encoding (PNG output only).
    pub exposure: f32,
    /// Samples per pixel along each axis (N × N on a regular grid, box filtered).
    pub supersample: u32,
    /// Radiance of pixels where no surface is seen.
    pub background: Vec3,
}

/// How shadows are made (`[shadows]` in the scene file).
#[derive(Clone, Debug)]
pub struct ShadowSettings {
    pub method: crate::shadow::ShadowMethod,
    pub map_resolution: u32,
    pub map_bias: f64,
    pub pcf: u32,
    pub post_pass: bool,
}

/// A surface's reflectance and emission (linear RGB).
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    /// Lambertian reflectance ρ: radiance ρ/π × irradiance.
    pub diffuse: Vec3,
    /// Phong specular reflectance and exponent (energy-normalised lobe, see shading).
    pub specular: Vec3,
    pub exponent: f32,
    /// Emitted radiance, one-sided along the polygon's normal.
    pub emission: Vec3,
}

impl Material {
    pub fn is_emitter(&self) -> bool {
        self.emission.max_element() > 0.0
    }
}

/// A polygon vertex with the attributes the rasterizer interpolates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertex {
    pub position: DVec3,
    /// Shading normal (unit): the face normal for faceted objects, a vertex normal
    /// for smooth ones.
    pub normal: DVec3,
    /// Texture coordinates; (0, 0) is the texture's bottom-left corner.
    pub uv: DVec2,
}

/// A planar polygon of the scene. Vertices run counter-clockwise seen from the side
/// its normal points to.
#[derive(Clone, Debug)]
pub struct Polygon {
    pub vertices: Vec<Vertex>,
    /// Unit geometric normal (Newell).
    pub normal: DVec3,
    pub material: usize,
    pub object: usize,
}

impl Polygon {
    pub fn positions(&self) -> impl Iterator<Item = DVec3> + '_ {
        self.vertices.iter().map(|v| v.position)
    }
}

/// A named object: the polygons it owns are those whose `object` is its index.
#[derive(Clone, Debug)]
pub struct Object {
    pub name: String,
    /// Shading mode of this object, overriding the render setting.
    pub shading: Option<ShadingMode>,
}

/// An isotropic point light with inverse-square falloff.
#[derive(Clone, Debug)]
pub struct PointLight {
    pub position: DVec3,
    /// Radiant intensity (W/sr per RGB channel).
    pub intensity: Vec3,
}

/// A one-sided polygonal Lambertian emitter. It is also a polygon of the scene
/// (`polygon`), so the camera sees it with its radiance.
#[derive(Clone, Debug)]
pub struct AreaLight {
    pub vertices: Vec<DVec3>,
    pub normal: DVec3,
    /// Centroid of the vertices and area of the polygon.
    pub centre: DVec3,
    pub area: f64,
    pub radiance: Vec3,
    pub polygon: usize,
}

#[derive(Clone, Debug)]
pub enum Light {
    Point(PointLight),
    Area(AreaLight),
}

/// Everything a render needs.
#[derive(Clone, Debug)]
pub struct Scene {
    pub camera: Camera,
    pub render: RenderSettings,
    pub shadows: ShadowSettings,
    pub materials: Vec<Material>,
    pub objects: Vec<Object>,
    pub polygons: Vec<Polygon>,
    pub lights: Vec<Light>,
    /// Things the user should know that do not stop the render (dropped faces…).
    pub warnings: Vec<String>,
}

impl Scene {
    pub fn material_of(&self, polygon: usize) -> &Material {
        &self.materials[self.polygons[polygon].material]
    }

    pub fn shading_of(&self, polygon: usize) -> ShadingMode {
        self.objects[self.polygons[polygon].object]
            .shading
            .unwrap_or(self.render.shading)
    }
}
