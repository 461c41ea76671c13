//! The scene file as written in TOML (documented key by key in docs/scene-format.md).
//! Unknown keys are errors; values are checked when the scene is built.

use super::{SamplePattern, ShadingMode};
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
    #[serde(default)]
    pub textures: BTreeMap<String, TextureFile>,
    /// Present: the scene is lit by a radiosity solution instead of its lights.
    pub radiosity: Option<RadiosityFile>,
    /// Present: a participating medium fills the scene (or a box of it).
    pub medium: Option<MediumFile>,
    /// Present: global illumination (Whitted ray tracing, the two-pass method,
    /// Rushmeier & Torrance).
    pub global: Option<GlobalFile>,
    #[serde(default)]
    pub environments: BTreeMap<String, EnvironmentFile>,
}

/// `[environments.NAME]`: an environment map, from an image, six faces, a procedural
/// environment, or a capture of the scene itself.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentFile {
    /// One image (PNG sRGB, PFM or EXR linear): a latitude-longitude map, a sphere
    /// map, or a cube map's horizontal cross.
    pub image: Option<String>,
    /// Six images, one per cube face.
    pub faces: Option<CubeFacesFile>,
    pub procedural: Option<crate::texture::environment::sky::ProceduralEnvironment>,
    /// The world centre a capture renders the six faces from.
    pub capture: Option<Vec3File>,
    /// Objects (by name) a capture leaves out: the reflector itself, at least.
    #[serde(default)]
    pub hide: Vec<String>,
    pub layout: Option<crate::texture::environment::Layout>,
    /// Procedural and capture: a cube face's side, a sphere map's side or a
    /// latitude-longitude map's height, in texels.
    pub resolution: Option<u32>,
    #[serde(default)]
    pub filter: crate::texture::Filter,
}

/// The six faces of a cube map, each a square image of one size.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CubeFacesFile {
    pub px: String,
    pub nx: String,
    pub py: String,
    pub ny: String,
    pub pz: String,
    pub nz: String,
}

/// `[medium]`: a homogeneous participating medium and how its light is computed.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MediumFile {
    pub extinction: f64,
    #[serde(default = "albedo")]
    pub albedo: f64,
    #[serde(default = "isotropic")]
    pub phase: crate::settings::PhaseFunction,
    #[serde(default)]
    pub g: f64,
    /// The box the medium fills; absent: everywhere.
    pub extent: Option<ExtentFile>,
    #[serde(default)]
    pub method: crate::settings::MediumMethod,
    #[serde(default = "nodes")]
    pub nodes: u32,
    pub march_step: Option<f64>,
    #[serde(default = "max_march_steps")]
    pub max_march_steps: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtentFile {
    pub min: Vec3File,
    pub max: Vec3File,
}

fn max_march_steps() -> f64 {
    crate::settings::MAX_MARCH_STEPS
}

fn albedo() -> f64 {
    1.0
}
fn isotropic() -> crate::settings::PhaseFunction {
    crate::settings::PhaseFunction::Isotropic
}
fn nodes() -> u32 {
    8
}

/// `[radiosity]`: solver, form factors, meshing, stopping and display.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RadiosityFile {
    #[serde(default)]
    pub solver: crate::settings::Solver,
    #[serde(default)]
    pub form_factors: crate::settings::FormFactorMethod,
    #[serde(default = "hemicube_resolution")]
    pub resolution: u32,
    /// Longest patch side, in scene units (absent: each polygon is one patch).
    pub patch_size: Option<f64>,
    /// Longest element side (absent: each patch is one element).
    pub element_size: Option<f64>,
    #[serde(default = "gathering_tolerance")]
    pub tolerance: f64,
    #[serde(default = "unshot_fraction")]
    pub unshot: f64,
    #[serde(default = "max_steps")]
    pub max_steps: usize,
    #[serde(default)]
    pub ambient: bool,
    #[serde(default)]
    pub display: crate::settings::Display,
    #[serde(default = "max_memory_mb")]
    pub max_memory_mb: u64,
    /// Gathering: cut elements differing from a neighbour by more than this
    /// fraction of the largest reflected radiosity (absent: no adaptive subdivision).
    pub subdivide: Option<f64>,
    #[serde(default = "subdivision_levels")]
    pub subdivision_levels: u32,
}

fn hemicube_resolution() -> u32 {
    128
}
fn gathering_tolerance() -> f64 {
    1e-6
}
fn unshot_fraction() -> f64 {
    0.01
}
fn max_steps() -> usize {
    100_000
}
fn max_memory_mb() -> u64 {
    4096
}
/// The largest memory budget a scene may set (1 TiB, in MiB): above it a budget
/// stops being a limit and its count of bytes would overflow.
pub const MAX_MEMORY_BUDGET_MB: u64 = 1 << 20;
fn subdivision_levels() -> u32 {
    2
}

/// `[global]`: the global-illumination method and its settings. Every key but
/// `method` is optional, so that the keys a file set can be told from the defaults
/// (each integrator declares the keys it reads; the others are refused).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GlobalFile {
    pub method: crate::settings::GlobalMethod,
    /// Absent: 5 (the path tracer: 1,000).
    pub depth: Option<u32>,
    /// Absent: 4 (the path tracer's 4 x 4 paths a pixel).
    pub samples: Option<u32>,
    /// Absent: 200,000 (the photon map's global map).
    pub photons: Option<u32>,
    /// Absent: 100,000 (the photon map's caustic map).
    pub caustic_photons: Option<u32>,
    /// Absent: 100 (photons in a global estimate).
    pub nearest: Option<u32>,
    /// Absent: 80 (photons in a caustic estimate).
    pub caustic_nearest: Option<u32>,
    /// Absent: false (Jensen's estimate at every gather ray's end).
    pub precomputed_irradiance: Option<bool>,
    /// Absent: 10⁻³.
    pub threshold: Option<f64>,
    /// Absent: 2.
    pub subdivisions: Option<u32>,
    /// Absent: 0.05.
    pub contrast: Option<f64>,
    /// Absent: constant.
    pub weights: Option<crate::settings::SpecularWeights>,
    /// Absent: 2 (the two-pass methods' mirror-of-mirror levels).
    pub window_depth: Option<u32>,
    /// Absent: 10 (the two-pass methods' reflection frustum, cells a side).
    pub frustum_resolution: Option<u32>,
    /// Absent: all four.
    pub mechanisms: Option<Vec<MechanismFile>>,
    /// Absent: false.
    pub exact_direct: Option<bool>,
    /// Absent: true.
    pub analytic_spheres: Option<bool>,
    /// Absent: black.
    pub ambient: Option<Vec3File>,
    pub final_gather: Option<FinalGatherFile>,
}

impl GlobalFile {
    /// The keys the file set besides `method`, as `global.<key>`.
    pub fn keys_set(&self) -> Vec<&'static str> {
        let GlobalFile {
            method: _,
            depth,
            samples,
            photons,
            caustic_photons,
            nearest,
            caustic_nearest,
            precomputed_irradiance,
            threshold,
            subdivisions,
            contrast,
            weights,
            window_depth,
            frustum_resolution,
            mechanisms,
            exact_direct,
            analytic_spheres,
            ambient,
            final_gather,
        } = self;
        [
            ("global.depth", depth.is_some()),
            ("global.samples", samples.is_some()),
            ("global.photons", photons.is_some()),
            ("global.caustic_photons", caustic_photons.is_some()),
            ("global.nearest", nearest.is_some()),
            ("global.caustic_nearest", caustic_nearest.is_some()),
            (
                "global.precomputed_irradiance",
                precomputed_irradiance.is_some(),
            ),
            ("global.threshold", threshold.is_some()),
            ("global.subdivisions", subdivisions.is_some()),
            ("global.contrast", contrast.is_some()),
            ("global.weights", weights.is_some()),
            ("global.window_depth", window_depth.is_some()),
            ("global.frustum_resolution", frustum_resolution.is_some()),
            ("global.mechanisms", mechanisms.is_some()),
            ("global.exact_direct", exact_direct.is_some()),
            ("global.analytic_spheres", analytic_spheres.is_some()),
            ("global.ambient", ambient.is_some()),
            ("global.final_gather", final_gather.is_some()),
        ]
        .into_iter()
        .filter_map(|(key, set)| set.then_some(key))
        .collect()
    }
}

/// `[global.final_gather]`: the view pass gathers the indirect light from the
/// solution (Reichert 1992), through Ward's irradiance cache.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FinalGatherFile {
    #[serde(default = "gather_rays")]
    pub rays: u32,
    #[serde(default = "gather_error")]
    pub error: f64,
    #[serde(default = "gather_min_spacing")]
    pub min_spacing: f64,
    #[serde(default = "gather_max_spacing")]
    pub max_spacing: f64,
    #[serde(default = "yes")]
    pub gradients: bool,
    #[serde(default)]
    pub direct_at_hits: bool,
}

fn gather_rays() -> u32 {
    1024
}
fn gather_error() -> f64 {
    0.15
}
fn gather_min_spacing() -> f64 {
    0.005
}
fn gather_max_spacing() -> f64 {
    0.25
}

/// One of the four transfer mechanisms, as `[global] mechanisms` names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MechanismFile {
    DiffuseDiffuse,
    SpecularDiffuse,
    DiffuseSpecular,
    SpecularSpecular,
}

/// `[shadows]`: which method, and the shadow map's settings.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShadowsFile {
    #[serde(default)]
    pub method: crate::settings::ShadowMethod,
    /// Shadow map: texels along each side of each cube face.
    #[serde(default = "map_resolution")]
    pub map_resolution: u32,
    /// Shadow map: depth bias in texels (of the map at the sample's distance).
    #[serde(default = "map_bias")]
    pub map_bias: f64,
    /// Shadow map: `none`, `box` or `percentage-closer`; absent, `box` when `pcf`
    /// is above 1 (what `pcf` alone always meant), else `none`.
    #[serde(default)]
    pub map_filter: Option<crate::settings::MapFilter>,
    /// Shadow map, box filter: the kernel, k × k texels.
    #[serde(default = "pcf")]
    pub pcf: u32,
    /// Shadow map, percentage-closer filter: jittered points per sample (n²).
    #[serde(default = "pcf_samples")]
    pub pcf_samples: u32,
    /// Shadow map, percentage-closer filter: each point's bias range [min, max], in
    /// slope-scaled texels.
    #[serde(default = "pcf_bias")]
    pub pcf_bias: [f64; 2],
    /// Shadow map, percentage-closer filter: the footprint's scale.
    #[serde(default = "pcf_scale")]
    pub pcf_scale: f64,
    /// Shadow map, percentage-closer filter: the region's least side, in texels.
    #[serde(default)]
    pub pcf_min_size: f64,
    /// Shadow map: Williams's original post-pass (shadow applied to the finished
    /// image) instead of a lookup in the light model.
    #[serde(default)]
    pub post_pass: bool,
    /// Appel's self-shadow rule, shared by every method: a surface facing away from
    /// the light is dark whatever the method finds. Off, each method's own answer
    /// shows at the terminator.
    #[serde(default = "self_shadow")]
    pub self_shadow: bool,
    /// Ray casting under an extended light: N × N stratified samples over it.
    #[serde(default = "light_samples")]
    pub light_samples: u32,
    /// Shadow map: the most memory one light's map may take, in MiB.
    #[serde(default = "shadow_map_memory_mb")]
    pub max_memory_mb: u64,
    /// Soft shadow volumes: points the light is replaced by.
    #[serde(default = "light_points")]
    pub light_points: u32,
    /// Jittered soft shadows: rings of hexagonal cells (1 + 3K(K + 1) cells).
    #[serde(default = "rings")]
    pub rings: u32,
    /// Jittered soft shadows: `regular` (cell centres) or `jittered`.
    #[serde(default)]
    pub sampling: crate::settings::CellSampling,
    /// Seed of the stochastic shadow methods.
    #[serde(default)]
    pub seed: u64,
}

impl Default for ShadowsFile {
    fn default() -> Self {
        ShadowsFile {
            method: Default::default(),
            map_resolution: map_resolution(),
            map_bias: map_bias(),
            map_filter: None,
            pcf: pcf(),
            pcf_samples: pcf_samples(),
            pcf_bias: pcf_bias(),
            pcf_scale: pcf_scale(),
            pcf_min_size: 0.0,
            post_pass: false,
            self_shadow: self_shadow(),
            light_samples: light_samples(),
            max_memory_mb: shadow_map_memory_mb(),
            light_points: light_points(),
            rings: rings(),
            sampling: Default::default(),
            seed: 0,
        }
    }
}

fn shadow_map_memory_mb() -> u64 {
    1024
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
fn pcf_samples() -> u32 {
    crate::settings::PercentageCloser::default().samples
}
fn pcf_bias() -> [f64; 2] {
    crate::settings::PercentageCloser::default().bias
}
fn pcf_scale() -> f64 {
    crate::settings::PercentageCloser::default().scale
}
fn self_shadow() -> bool {
    true
}
fn light_samples() -> u32 {
    4
}
fn light_points() -> u32 {
    16
}
fn rings() -> u32 {
    3
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraFile {
    pub eye: Vec3File,
    pub look_at: Vec3File,
    #[serde(default = "y_up")]
    pub up: Vec3File,
    pub fov_y: f64,
    /// Signed, so that a negative size is refused with the real range
    /// (`validate::camera`), not the deserialiser's words for a u32.
    pub width: i64,
    pub height: i64,
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
    /// Where a pixel's samples lie: "regular" or "rotated-grid".
    #[serde(default)]
    pub sample_pattern: SamplePattern,
    #[serde(default)]
    pub background: Vec3File,
    /// Pixel rows per band of the frame; 0 chooses them from a memory budget.
    #[serde(default)]
    pub band_rows: u32,
    /// An environment shown where no surface is seen (instead of `background`).
    pub backdrop: Option<String>,
    /// Off: no environment is looked up (mirrors show their local shading only).
    #[serde(default = "yes")]
    pub environments: bool,
    /// The memory the scene's geometry may take, estimated before each object is
    /// added (MiB).
    #[serde(default = "max_memory_mb")]
    pub max_memory_mb: u64,
}

impl Default for RenderFile {
    fn default() -> Self {
        RenderFile {
            shading: phong(),
            exposure: one(),
            supersample: one_sample(),
            sample_pattern: SamplePattern::default(),
            background: [0.0; 3],
            band_rows: 0,
            backdrop: None,
            environments: true,
            max_memory_mb: max_memory_mb(),
        }
    }
}

fn phong() -> ShadingMode {
    ShadingMode::Phong
}
fn yes() -> bool {
    true
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
    /// Name of a texture multiplying `diffuse`.
    pub diffuse_texture: Option<String>,
    /// Name of a texture multiplying `specular`.
    pub specular_texture: Option<String>,
    /// Name of a texture read as a bump height (Blinn).
    pub bump_texture: Option<String>,
    /// The height, in scene units, of a bump texture value of 1.
    pub bump_height: Option<f64>,
    /// How texture coordinates are found inside polygons.
    #[serde(default)]
    pub interpolation: crate::texture::Interpolation,
    /// Where texture coordinates come from: a two-part mapping, or (absent) the
    /// mesh's own coordinates.
    pub mapping: Option<MappingFile>,
    /// Reflection coefficient k_r of the environment seen in the mirror direction.
    #[serde(default)]
    pub mirror: Vec3File,
    /// The two-pass methods: a glossy mirror, its reflection spread over the
    /// lobe cosⁿ about the mirror direction, n this exponent (absent: ideal).
    pub gloss: Option<f64>,
    /// Index of refraction: the surface reflects by Fresnel's weight and (with a
    /// transmittance) refracts.
    pub ior: Option<f64>,
    /// What the refracted environment is multiplied by; without `ior`, the
    /// specular transmittance of a thin pane (light passes straight through).
    #[serde(default)]
    pub transmittance: Vec3File,
    /// Diffuse transmittance τ_d: a translucent panel passes this share of the
    /// light reaching its back on, diffusely, from its front (Rushmeier & Torrance).
    #[serde(default)]
    pub translucence: Vec3File,
    /// The environment map the mirror and refracted directions look up.
    pub environment: Option<String>,
}

/// `[textures.NAME]`: an image file or a procedural pattern, and how it is sampled.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextureFile {
    /// PNG or JPEG file, relative to the scene file.
    pub image: Option<String>,
    pub procedural: Option<ProceduralKind>,
    /// Procedural: cells along each side of the unit square.
    pub cells: Option<u32>,
    /// Procedural: the two colours.
    pub colors: Option<[Vec3File; 2]>,
    /// Grid: line width in cell units.
    pub line: Option<f64>,
    /// Noise: the lattice's seed.
    pub seed: Option<u32>,
    /// Procedural: texels along each side when sampled into an image.
    pub resolution: Option<u32>,
    #[serde(default)]
    pub wrap: crate::texture::Wrap,
    #[serde(default)]
    pub filter: crate::texture::Filter,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ProceduralKind {
    Checkerboard,
    Grid,
    Noise,
}

/// A two-part mapping (Bier & Sloan): intermediate surface, projector and frame, in
/// the object's modelling coordinates.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MappingFile {
    pub surface: crate::texture::mapping::IntermediateSurface,
    #[serde(default)]
    pub projector: crate::texture::mapping::Projector,
    #[serde(default)]
    pub centre: Vec3File,
    #[serde(default = "y_up")]
    pub axis: Vec3File,
    #[serde(default = "x_axis")]
    pub reference: Vec3File,
    #[serde(default = "ones")]
    pub size: [f64; 2],
    #[serde(default = "one")]
    pub height: f64,
    #[serde(default = "one")]
    pub radius: f64,
    #[serde(default = "ones")]
    pub repeat: [f64; 2],
}

fn x_axis() -> Vec3File {
    [1.0, 0.0, 0.0]
}
fn ones() -> [f64; 2] {
    [1.0, 1.0]
}

/// `[[lights]]`: one light, its kind in `type`. Every kind takes an optional `name`
/// for messages.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum LightFile {
    Point {
        name: Option<String>,
        position: Vec3File,
        /// W/sr per channel.
        intensity: Vec3File,
    },
    /// Parallel light; `direction` is the way the light travels.
    Distant {
        name: Option<String>,
        direction: Vec3File,
        /// Irradiance on a surface facing the light.
        irradiance: Vec3File,
    },
    /// A one-sided Lambertian polygon, also added to the scene as an emissive polygon.
    #[serde(alias = "area")]
    Polygon {
        name: Option<String>,
        vertices: Vec<Vec3File>,
        radiance: Vec3File,
    },
    /// A Lambertian sphere (not drawn, casts no shadow).
    Sphere {
        name: Option<String>,
        centre: Vec3File,
        radius: f64,
        radiance: Vec3File,
    },
    Spot {
        name: Option<String>,
        position: Vec3File,
        /// Where the spot points.
        axis: Vec3File,
        /// Half-angle of the cone, in degrees.
        cone_angle: f64,
        /// W/sr per channel on the axis.
        intensity: Vec3File,
        /// f(θ) = cosᵖ θ (default 0: a uniform cone).
        cosine_power: Option<f64>,
        /// Or f(θ) as (degrees, factor) pairs, interpolated linearly.
        distribution: Option<Vec<[f64; 2]>>,
    },
}

impl LightFile {
    pub fn name(&self) -> Option<&str> {
        match self {
            LightFile::Point { name, .. }
            | LightFile::Distant { name, .. }
            | LightFile::Polygon { name, .. }
            | LightFile::Sphere { name, .. }
            | LightFile::Spot { name, .. } => name.as_deref(),
        }
    }
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
