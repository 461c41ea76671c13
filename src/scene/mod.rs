//! Scenes: the in-memory model every pass reads, and how it is built from files.
//!
//! A scene is a flat list of planar polygons (each knowing its object and material),
//! a camera, lights and render settings. Polygon ids are indices into that list: the
//! visible-surface buffer, the shadow methods and the radiosity mesher all speak of
//! polygons by these ids.

mod build;
mod environments;
pub mod file;
pub mod global_settings;
pub mod gltf;
mod light_settings;
pub mod lights;
mod materials;
mod medium_settings;
mod obj;
pub mod obj_scene;
mod radiosity_settings;
pub mod ray_queries;
pub mod resources;
mod shadow_settings;
pub(crate) mod shapes;
pub mod tables;
mod textures;
mod transform;
mod validate;
pub use validate::MAX_SIDE;

pub use build::scene_from_table;
pub use lights::{
    DistantLight, Emitted, Light, LightKind, LightSample, PointLight, PolygonLight, Reach,
    SphereLight, SpotDistribution, SpotLight,
};

use crate::texture::environment::EnvironmentMap;
use crate::texture::mapping::Mapping;
use crate::texture::{Interpolation, Texture};
use glam::{DMat4, DVec2, DVec3, Vec3};
use std::sync::Arc;

pub use crate::settings::{RenderSettings, SamplePattern, ShadingMode, ShadowSettings};

/// A camera as the scene file gives it: a pinhole looking from `eye` to `look_at`.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// The centre of projection.
    pub eye: DVec3,
    /// The point looked at, in the middle of the image.
    pub look_at: DVec3,
    /// Which way is up in the image.
    pub up: DVec3,
    /// Vertical field of view in degrees.
    pub fov_y: f64,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Distance of the near clipping plane along the view direction.
    pub near: f64,
}

/// A surface's reflectance and emission (linear RGB), and the textures on it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Material {
    /// Its name in the scene file (`[materials.NAME]`) or the MTL file.
    pub name: String,
    /// Lambertian reflectance ρ: radiance ρ/π × irradiance.
    pub diffuse: Vec3,
    /// Phong specular reflectance and exponent (energy-normalised lobe, see shading).
    pub specular: Vec3,
    /// The Phong exponent.
    pub exponent: f32,
    /// Emitted radiance, one-sided along the polygon's normal.
    pub emission: Vec3,
    /// Indices into `Scene::textures`: colours multiplying `diffuse` and `specular`.
    pub diffuse_texture: Option<usize>,
    /// Index into `Scene::textures`: a colour multiplying `specular`.
    pub specular_texture: Option<usize>,
    /// A bump map (Blinn 1978).
    pub bump: Option<Bump>,
    /// A two-part mapping giving the texture coordinates (else the mesh's own).
    pub mapping: Option<Mapping>,
    /// How textures are filtered (nearest, bilinear, mip-mapped, summed-area).
    pub interpolation: Interpolation,
    /// Reflection coefficient k_r of the environment seen in the mirror direction
    /// (Blinn & Newell); with `ior`, a tint of Fresnel's reflection.
    pub mirror: Vec3,
    /// The two-pass methods' glossy mirror: the exponent n of the lobe cosⁿ about
    /// the mirror direction that pass 2's reflection frustum weighs (`None`: an
    /// ideal mirror, one ray).
    pub gloss: Option<f64>,
    /// Index of refraction of the material (the outside is vacuum, 1).
    pub ior: Option<f64>,
    /// What the environment seen in the refracted direction is multiplied by; for
    /// ray tracing and radiosity's first pass, the specular transmittance τ_s
    /// (without `ior`: a thin pane, light passes straight through).
    pub transmittance: Vec3,
    /// Diffuse transmittance τ_d of a translucent panel (Rushmeier & Torrance).
    pub translucence: Vec3,
    /// Index into `Scene::environments` of the map reflections and refractions read.
    pub environment: Option<usize>,
}

/// A bump map: a texture read as a height, and the height of a value of 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bump {
    /// Index into `Scene::textures` of the height field.
    pub texture: usize,
    /// The height, in scene units, of a texture value of 1.
    pub height: f64,
}

impl Material {
    /// What a texture multiplies its diffuse reflectance by, per band, where the
    /// textured reflectance is `textured` (0 in a band it does not reflect).
    pub fn diffuse_scale(&self, textured: Vec3) -> Vec3 {
        let ratio = |t: f32, plain: f32| if plain > 0.0 { t / plain } else { 0.0 };
        Vec3::new(
            ratio(textured.x, self.diffuse.x),
            ratio(textured.y, self.diffuse.y),
            ratio(textured.z, self.diffuse.z),
        )
    }

    /// Whether it emits.
    pub fn is_emitter(&self) -> bool {
        self.emission.max_element() > 0.0
    }

    /// Whether it reflects or transmits specularly (a mirror, glass, a pane).
    pub fn is_specular(&self) -> bool {
        self.mirror.max_element() > 0.0 || self.transmittance.max_element() > 0.0
    }

    /// Whether it shows an environment (reflected or refracted).
    pub fn is_environment_mapped(&self) -> bool {
        self.environment.is_some()
    }

    /// Whether a texture or bump map is on it.
    pub fn is_textured(&self) -> bool {
        self.diffuse_texture.is_some() || self.specular_texture.is_some() || self.bump.is_some()
    }

    /// What the light model needs, before textures.
    pub fn reflectance(&self) -> Reflectance {
        Reflectance {
            diffuse: self.diffuse,
            specular: self.specular,
            exponent: self.exponent,
        }
    }
}

/// The reflectance at one surface point: a material's, textures applied.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reflectance {
    /// Lambertian reflectance ρ.
    pub diffuse: Vec3,
    /// Phong specular reflectance.
    pub specular: Vec3,
    /// The Phong exponent.
    pub exponent: f32,
}

/// A polygon vertex with the attributes the rasterizer interpolates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertex {
    /// Position in world coordinates.
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
    /// Its corners, counter-clockwise seen from the side the normal points to.
    pub vertices: Vec<Vertex>,
    /// Unit geometric normal (Newell).
    pub normal: DVec3,
    /// Index into `Scene::materials`.
    pub material: usize,
    /// Index into `Scene::objects` of the object it belongs to.
    pub object: usize,
}

impl Polygon {
    /// Its corners' positions.
    pub fn positions(&self) -> impl Iterator<Item = DVec3> + '_ {
        self.vertices.iter().map(|v| v.position)
    }
}

/// A named object: the polygons it owns are those whose `object` is its index.
#[derive(Clone, Debug)]
pub struct Object {
    /// Its name in the scene file (`name/part` for an OBJ file's parts).
    pub name: String,
    /// Shading mode of this object, overriding the render setting.
    pub shading: Option<ShadingMode>,
    /// Its modelling frame: texture mappings are given in it, so textures and bumps
    /// move with the object.
    pub frame: ObjectFrame,
    /// A built-in sphere: the unit sphere under `frame`, which a ray tracer may
    /// intersect as a quadric instead of its polygons.
    pub sphere: bool,
}

/// The transform between an object's modelling coordinates and the world.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectFrame {
    /// Modelling coordinates to world coordinates.
    pub to_world: DMat4,
    /// World coordinates to modelling coordinates.
    pub to_object: DMat4,
    /// Centroid of the object's vertices, in modelling coordinates (Bier and Sloan's
    /// centroid projector).
    pub centroid: DVec3,
    /// The analytic parameterisation behind a built-in sphere's or cylinder's own
    /// texture coordinates (for bump mapping's surface derivatives).
    pub own_mapping: Option<Mapping>,
}

impl ObjectFrame {
    /// The world's own frame.
    pub fn identity() -> ObjectFrame {
        ObjectFrame {
            to_world: DMat4::IDENTITY,
            to_object: DMat4::IDENTITY,
            centroid: DVec3::ZERO,
            own_mapping: None,
        }
    }

    /// A world normal in modelling coordinates (by the inverse transpose).
    pub fn normal_to_object(&self, n: DVec3) -> DVec3 {
        glam::DMat3::from_mat4(self.to_world).transpose() * n
    }
}

/// Everything a render needs.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The pinhole camera.
    pub camera: Camera,
    /// Shading, supersampling, exposure and background.
    pub render: RenderSettings,
    /// The shadow method and its settings (`[shadows]`).
    pub shadows: ShadowSettings,
    /// Lit by a radiosity solution (`[radiosity]`) instead of the lights.
    pub radiosity: Option<crate::settings::RadiositySettings>,
    /// A participating medium (single scattering from the lights).
    pub medium: Option<crate::settings::MediumSettings>,
    /// Lit by a global-illumination method (`[global]`).
    pub global: Option<crate::settings::GlobalSettings>,
    /// The materials; polygons name them by index.
    pub materials: Vec<Material>,
    /// The objects; polygons name them by index.
    pub objects: Vec<Object>,
    /// Every polygon of the scene, lights' polygons included.
    pub polygons: Vec<Polygon>,
    /// The lights, in the scene file's order (`lights[i]`, buffers' `-i`).
    pub lights: Vec<Light>,
    /// Images textures read, loaded or generated once.
    pub textures: Vec<Arc<Texture>>,
    /// Environment maps, loaded or to be captured by the renderer.
    pub environments: Vec<Environment>,
    /// Things the user should know that do not stop the render (dropped faces…).
    pub warnings: Vec<String>,
}

/// The indices of the objects a scene file's `name` made: that object, or the parts
/// of an OBJ file it loaded (named `name/part`).
pub fn objects_named(objects: &[Object], name: &str) -> Vec<usize> {
    (0..objects.len())
        .filter(|&o| {
            let n = &objects[o].name;
            n == name
                || n.strip_prefix(name)
                    .is_some_and(|rest| rest.starts_with('/'))
        })
        .collect()
}

/// A named environment map of the scene.
#[derive(Clone, Debug)]
pub struct Environment {
    /// Its name in the scene file (`[environments.NAME]`).
    pub name: String,
    /// Where its texels come from.
    pub source: EnvironmentSource,
    /// Whether it is generated from a procedural environment (and so can be laid
    /// out in any layout), not read from images laid out one way.
    pub procedural: bool,
}

#[derive(Clone, Debug)]
/// Where an environment map comes from.
pub enum EnvironmentSource {
    /// Loaded or generated with the scene.
    Map(Arc<EnvironmentMap>),
    /// Six faces the renderer makes of the scene itself (Greene's "rendered by any
    /// ordinary renderer").
    Capture(Capture),
}

/// A cube map to render from a point of the scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Capture {
    /// The world centre the faces are rendered from.
    pub at: DVec3,
    /// Texels per face side.
    pub resolution: u32,
    /// Indices into `Scene::objects` left out of the faces.
    pub hide: Vec<usize>,
    /// How the captured faces are filtered when looked up.
    pub filter: crate::settings::Filter,
}

impl Scene {
    /// The indices of the objects a scene file's `name` made: that object, or the
    /// parts of an OBJ file it loaded (named `name/part`).
    pub fn objects_named(&self, name: &str) -> Vec<usize> {
        objects_named(&self.objects, name)
    }

    /// The material polygon `polygon` wears.
    pub fn material_of(&self, polygon: usize) -> &Material {
        &self.materials[self.polygons[polygon].material]
    }

    /// How polygon `polygon` is shaded: its object's mode, else the scene's.
    pub fn shading_of(&self, polygon: usize) -> ShadingMode {
        self.objects[self.polygons[polygon].object]
            .shading
            .unwrap_or(self.render.shading)
    }
}
