//! Every method's settings as plain enums and structs: what a scene file, the command
//! line or an embedding program chooses. A leaf of the crate: it imports nothing from
//! it, so the scene can store settings and the methods can read them without either
//! depending on the other.

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
    /// How colour varies across a polygon.
    pub shading: ShadingMode,
    /// Radiance is multiplied by this before sRGB encoding (PNG output only).
    pub exposure: f32,
    /// Samples per pixel along each axis (N × N, box filtered).
    pub supersample: u32,
    /// Where a pixel's N × N samples lie.
    pub sample_pattern: SamplePattern,
    /// Radiance of pixels where no surface is seen.
    pub background: glam::Vec3,
    /// An environment (index into `Scene::environments`) shown there instead.
    pub backdrop: Option<usize>,
    /// Whether environments are looked up at all (off: mirrors show their local
    /// shading only, the backdrop is the background colour; for comparisons).
    pub environments: bool,
    /// Pixel rows per band of the frame (0: chosen from a memory budget). The image
    /// does not depend on it; memory grows with it.
    pub band_rows: u32,
}

/// Where a pixel's N × N samples lie (`[render] sample_pattern`, `--sample-pattern`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum SamplePattern {
    /// A regular N × N grid: the scan-line pass runs once on a grid N times finer
    /// than the pixels.
    #[default]
    Regular,
    /// N² samples on a rotated grid, one in each of the N² columns and rows of
    /// sub-pixel cells (n-rooks): the frame made N² times with its projection
    /// shifted by each sample's offset, and the frames averaged (Haeberli & Akeley's
    /// accumulation buffer). An edge near the horizontal or the vertical is seen at
    /// N² + 1 levels of coverage instead of N + 1.
    RotatedGrid,
}

/// How shadows are computed (`[shadows] method`, `--shadows`).
///
/// Each method declares what it handles, its name, its buffers, its budget and its
/// warnings in its own file; `shadow::method` reaches them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum ShadowMethod {
    /// No shadows: every light reaches every point.
    #[default]
    None,
    /// Appel 1968: the segment from each visible point to the light, tested against
    /// the scene through a bounding volume hierarchy; for extended lights, stratified
    /// samples over the emitter (Cook, Porter & Carpenter 1984).
    RayCast,
    /// Bouknight & Kelley 1970: shadow polygons projected onto each receiver in a
    /// pre-pass, span segments classified against them during scan-out.
    Scanline,
    /// Atherton, Weiler & Greenberg 1978: the polygons the light sees, found by
    /// Weiler-Atherton hidden-surface removal, attached as lit detail polygons.
    ShadowPolygons,
    /// Williams 1978: depth images from the light, compared per visible point.
    ShadowMap,
    /// Crow 1977: volumes bounded by quads through the silhouette edges, entered
    /// as invisible surfaces in the scan-line pass and counted along each span in
    /// front of the visible surface.
    ShadowVolumes,
    /// Heidmann 1991: the same volumes, each quad drawn on its own into a count
    /// (stencil) buffer where it lies in front of the visible depth.
    StencilShadowVolumes,
    /// Nishita & Nakamae 1983: umbra and penumbra polygons cut onto each receiver
    /// from the light's vertices; in the penumbra, the exact visible part of a
    /// polygonal light (the light minus the occluders projected onto it).
    UmbraPenumbra,
    /// Brotman & Badler 1984: the light replaced by n random points, one set of
    /// Crow's volumes each, the points hidden counted per sample.
    SoftShadowVolumes,
    /// A spherical light cut into hexagonal cells, one shadow ray per cell, at the
    /// cell's centre or jittered inside it (Cook 1986).
    JitteredSoftShadows,
}

/// How shadows are made (`[shadows]` in the scene file).
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowSettings {
    /// The method.
    pub method: ShadowMethod,
    /// Shadow map: texels along each side of each cube face.
    pub map_resolution: u32,
    /// Shadow map: depth bias in slope-scaled texels.
    pub map_bias: f64,
    /// Shadow map: how its depth tests are filtered.
    pub map_filter: MapFilter,
    /// Shadow map, box filter: the kernel's side k (k × k texels).
    pub pcf: u32,
    /// Shadow map: Reeves, Salesin & Cook's filter.
    pub percentage_closer: PercentageCloser,
    /// Shadow map: Williams's post-pass, applied to the finished image.
    pub post_pass: bool,
    /// Appel's self-shadow rule: a sample whose surface faces away from the light is
    /// dark whatever the method finds (off: each method's own answer shows).
    pub self_shadow: bool,
    /// Ray casting under an extended light: N × N stratified samples over the emitter.
    pub light_samples: u32,
    /// Soft shadow volumes: the number of points the light is replaced by.
    pub light_points: u32,
    /// Jittered soft shadows: rings of hexagonal cells around the centre cell.
    pub rings: u32,
    /// Jittered soft shadows: cell centres, or a random point in each cell.
    pub sampling: CellSampling,
    /// The seed of the stochastic methods' streams (soft shadow volumes' points,
    /// jittered cells).
    pub seed: u64,
    /// The memory the lights' pre-passes may take, in MiB (a method with a budget,
    /// the shadow map, refuses settings beyond it before any work).
    pub max_memory_mb: u64,
}

/// How a shadow map's depth tests are filtered (`[shadows] map_filter`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MapFilter {
    /// Williams 1978: one test, against the texel the point falls in.
    #[default]
    None,
    /// A fixed k × k box of texels around that texel, the fraction that passes: a
    /// function of the texel index alone, so its result is constant over a texel.
    Box,
    /// Reeves, Salesin & Cook 1987: jittered points over the sample's footprint in
    /// the map, each with its own random bias; the fraction that passes.
    PercentageCloser,
}

/// Reeves, Salesin & Cook's percentage-closer filter (`pcf_samples`, `pcf_bias`,
/// `pcf_scale`, `pcf_min_size`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PercentageCloser {
    /// Points per sample, a square number: √N × √N strata, one jittered point each.
    pub samples: u32,
    /// Each point's bias, uniform in [min, max], in slope-scaled texels.
    pub bias: [f64; 2],
    /// The footprint's sides are multiplied by this, about its centre (soft edges).
    pub scale: f64,
    /// Then each side is widened to at least this many texels.
    pub min_size: f64,
}

impl Default for PercentageCloser {
    fn default() -> Self {
        PercentageCloser {
            samples: 16,
            bias: [1.0, 2.0],
            scale: 1.0,
            min_size: 0.0,
        }
    }
}

/// Where a jittered soft shadow's ray meets its hexagonal cell.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum CellSampling {
    /// The cell's centre, the same for every pixel: the penumbra in bands.
    Regular,
    /// A random point of the cell, fresh per pixel: the bands become noise.
    #[default]
    Jittered,
}

/// How a texture is sampled.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Filter {
    /// Point sampling of the full-resolution image: the texel under the sample.
    Nearest,
    /// Bilinear interpolation in the full-resolution image.
    Bilinear,
    /// Bilinear in the mip-map level nearest the footprint's size.
    MipNearest,
    /// Bilinear in the two levels bracketing the footprint, blended (Williams 1983).
    #[default]
    Trilinear,
    /// Mean over the footprint's bounding box by a summed-area table (Crow 1984).
    SummedArea,
}

impl Filter {
    /// The filter's name in a scene file.
    pub fn name(self) -> &'static str {
        match self {
            Filter::Nearest => "nearest",
            Filter::Bilinear => "bilinear",
            Filter::MipNearest => "mip-nearest",
            Filter::Trilinear => "trilinear",
            Filter::SummedArea => "summed-area",
        }
    }
}

/// Which radiosity solver.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Solver {
    /// The full system by Gauss–Seidel (Goral et al. 1984, Cohen & Greenberg 1985).
    Gathering,
    /// Progressive refinement (Cohen, Chen, Wallace & Greenberg 1988).
    #[default]
    Shooting,
}

/// How form factors are estimated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum FormFactorMethod {
    /// Cohen & Greenberg 1985: item buffers on the five faces of a hemi-cube.
    #[default]
    Hemicube,
    /// The Nusselt analog: the covered fraction of the hemisphere's base disc.
    Nusselt,
    /// Lambert's exact point-to-polygon factor, with an occlusion test.
    Analytic,
}

/// How element radiosities are drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Display {
    /// Vertex radiosities interpolated across each element (Gouraud 1971).
    #[default]
    Gouraud,
    /// One radiosity per element.
    Flat,
}

/// How finely to cut: the polygon (or patch) whole, pieces no longer than a size
/// along each side, or a fixed number of pieces along each side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Division {
    /// The polygon whole.
    Whole,
    /// Pieces no longer than this along each side.
    Size(f64),
    /// This many pieces along each side.
    Count(u32),
}

/// When to cut elements adaptively: a neighbour difference above `threshold` times
/// the largest reflected radiosity, for at most `levels` rounds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Subdivision {
    /// The difference, a fraction of the largest reflected radiosity.
    pub threshold: f64,
    /// The most rounds of cutting.
    pub levels: u32,
}

/// A scene's `[radiosity]` settings.
#[derive(Clone, Debug, PartialEq)]
pub struct RadiositySettings {
    /// Gathering (Gauss–Seidel) or shooting.
    pub solver: Solver,
    /// How form factors are estimated.
    pub form_factors: FormFactorMethod,
    /// Hemi-cube top-face cells per side (Nusselt: base-grid cells per side).
    pub resolution: u32,
    /// How polygons are cut into patches (shooters).
    pub patches: Division,
    /// How patches are cut into elements (receivers).
    pub elements: Division,
    /// Gathering: Gauss–Seidel stops when no radiosity changes by more than this
    /// fraction of the largest.
    pub tolerance: f64,
    /// Shooting: stop when the unshot power is this fraction of the emitted power.
    pub unshot: f64,
    /// Shooting: stop after this many steps.
    pub max_steps: usize,
    /// Shooting: display with the ambient term.
    pub ambient: bool,
    /// Flat or Gouraud-interpolated radiosities.
    pub display: Display,
    /// Gathering: the most memory its stored form factors may take, in bytes.
    pub memory_budget: u64,
    /// Gathering: adaptive subdivision of the elements after the solve.
    pub subdivision: Option<Subdivision>,
}

/// How light scatters in a participating medium: the share of light scattered by an
/// angle θ between its travel and the direction towards the eye, per steradian.
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PhaseFunction {
    /// 1/(4π) in every direction.
    Isotropic,
    /// 3/(16π) (1 + cos²θ): small particles, the sky's molecules.
    Rayleigh,
    /// (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}), forward for g > 0 (haze, fog).
    HenyeyGreenstein,
}

/// How the medium's single scattering is computed (`[medium] method`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MediumMethod {
    /// Max 1986: each viewing ray cut into lit and dark intervals by the shadow
    /// volumes' polygons it crosses; in-scattering integrated over the lit ones.
    #[default]
    LightVolumes,
    /// The reference: steps along each viewing ray with a shadow ray at each.
    RayMarching,
}

/// A homogeneous participating medium (`[medium]`).
#[derive(Clone, Debug, PartialEq)]
pub struct MediumSettings {
    /// Extinction coefficient σ_t, per scene unit of length.
    pub extinction: f64,
    /// Scattering albedo σ_s / σ_t, in [0, 1].
    pub albedo: f64,
    /// The phase function.
    pub phase: PhaseFunction,
    /// Henyey–Greenstein's asymmetry g, in (−1, 1).
    pub g: f64,
    /// The box the medium fills (min, max corners); `None`: everywhere.
    pub extent: Option<([f64; 3], [f64; 3])>,
    /// Ray marching or Max's lit intervals.
    pub method: MediumMethod,
    /// Light volumes under point and spot lights: Gauss–Legendre nodes per piece of
    /// a lit interval.
    pub nodes: u32,
    /// Ray marching: the step length, in scene units.
    pub march_step: f64,
    /// Ray marching: the most steps a frame may take (summed over its samples, a
    /// shadow ray per light each), estimated before the march and refused beyond.
    pub max_march_steps: f64,
}

/// The default for `medium.max_march_steps`: about three minutes on two cores (a
/// step with its shadow ray costs about 0.2 µs of one core in the Cornell box).
pub const MAX_MARCH_STEPS: f64 = 1e9;

impl MediumSettings {
    /// The scattering coefficient σ_s.
    pub fn scattering(&self) -> f64 {
        self.extinction * self.albedo
    }
}

/// Which global-illumination method lights the frame (`[global] method`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum GlobalMethod {
    /// Whitted 1980: recursive rays from the eye, a shadow ray per light.
    RayTracing,
    /// Wallace, Cohen & Greenberg 1987: radiosity extended through planar mirrors
    /// (pass 1), then reflected rays from the eye reading it (pass 2).
    TwoPass,
    /// Rushmeier & Torrance 1990: pass 1 extended to specular transmission through
    /// thin panes and diffuse transmission through translucent panels.
    RushmeierTorrance,
    /// Kajiya 1986: the rendering equation by path tracing, one path a sample, the
    /// lights sampled at every vertex.
    PathTracing,
    /// Jensen 1996: photons shot from the lights into a global and a caustic map,
    /// read by a final gather and directly.
    PhotonMap,
}

impl GlobalMethod {
    /// Whether the method's second pass reads a radiosity solution (the two-pass
    /// methods do; ray tracing reads none).
    pub fn reads_radiosity(self) -> bool {
        match self {
            GlobalMethod::RayTracing | GlobalMethod::PathTracing | GlobalMethod::PhotonMap => false,
            GlobalMethod::TwoPass | GlobalMethod::RushmeierTorrance => true,
        }
    }

    /// Whether the method antialiases its frame itself (Whitted's adaptive
    /// subdivision, the path tracer's samples over the pixel), so that
    /// `render.supersample` must stay 1.
    pub fn antialiases_itself(self) -> bool {
        match self {
            GlobalMethod::RayTracing | GlobalMethod::PathTracing | GlobalMethod::PhotonMap => true,
            GlobalMethod::TwoPass | GlobalMethod::RushmeierTorrance => false,
        }
    }

    /// Whether the method gathers a glossy mirror's reflection (the two-pass
    /// methods' reflection frustum), so that a material's `gloss` is read.
    pub fn reads_gloss(self) -> bool {
        match self {
            GlobalMethod::RayTracing | GlobalMethod::PathTracing | GlobalMethod::PhotonMap => false,
            GlobalMethod::TwoPass | GlobalMethod::RushmeierTorrance => true,
        }
    }

    /// The name the scene file uses.
    pub fn name(self) -> &'static str {
        match self {
            GlobalMethod::RayTracing => "ray-tracing",
            GlobalMethod::TwoPass => "two-pass",
            GlobalMethod::RushmeierTorrance => "rushmeier-torrance",
            GlobalMethod::PathTracing => "path-tracing",
            GlobalMethod::PhotonMap => "photon-map",
        }
    }
}

/// The four ways light passes between two surfaces (Wallace et al. 1987), each on
/// or off.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mechanisms {
    /// Ordinary radiosity: light leaving a diffuse surface lights a diffuse one.
    pub diffuse_diffuse: bool,
    /// Pass 1's factors through mirrors and panes (a lamp's light thrown by a mirror).
    pub specular_diffuse: bool,
    /// Pass 2's rays from the eye off a specular surface onto a diffuse one.
    pub diffuse_specular: bool,
    /// Pass 2's rays continuing from one specular surface to another.
    pub specular_specular: bool,
}

impl Mechanisms {
    /// Every mechanism.
    pub const ALL: Mechanisms = Mechanisms {
        diffuse_diffuse: true,
        specular_diffuse: true,
        diffuse_specular: true,
        specular_specular: true,
    };
}

/// Whitted's weights of the reflected and transmitted rays.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpecularWeights {
    /// The material's k_s (`mirror`) and k_t (`transmittance`) as constants, as
    /// Whitted's images used them.
    #[default]
    Constant,
    /// k_s and k_t scaled by Fresnel's reflectance of an unpolarised dielectric
    /// interface, F and 1 − F (exact formulas, not Schlick's approximation).
    Fresnel,
}

/// A scene's `[global]` settings.
#[derive(Clone, Debug, PartialEq)]
pub struct GlobalSettings {
    /// Whitted's ray tracing or a two-pass method.
    pub method: GlobalMethod,
    /// Longest chain of reflected and refracted rays from the eye (the path
    /// tracer: the most bounces a path takes).
    pub depth: u32,
    /// The path tracer and the photon map: paths per pixel, n × n (stratified over
    /// the pixel).
    pub samples: u32,
    /// The photon map's photons and their estimates.
    pub photons: PhotonSettings,
    /// A ray is not spawned when the product of the coefficients along its path
    /// falls below this (each band's largest).
    pub threshold: f64,
    /// Whitted's adaptive antialiasing: how many times a pixel may be split into
    /// four where its corners differ (0: the mean of the four corners).
    pub subdivisions: u32,
    /// Corners differ when a displayed channel (exposure applied, clamped to
    /// [0, 1]) differs by more than this.
    pub contrast: f64,
    /// Constant or Fresnel weights.
    pub weights: SpecularWeights,
    /// Pass 1: mirror-of-mirror (and pane) paths followed to this depth.
    pub window_depth: u32,
    /// Pass 2: cells along each side of the reflection frustum a glossy surface
    /// (a material's `gloss`) gathers its reflection through.
    pub frustum_resolution: u32,
    /// The transfer mechanisms pass 2 follows.
    pub mechanisms: Mechanisms,
    /// Pass 2: direct light from emitting polygons computed per sample (the
    /// shadow method's exact visible part, Lambert's formula) instead of read from
    /// the radiosity mesh; the mesh supplies the indirect light only.
    pub exact_direct: bool,
    /// Ray tracing: built-in spheres intersected as quadrics, not as their polygons.
    pub analytic_spheres: bool,
    /// Whitted's ambient term I_a (radiance per unit diffuse reflectance).
    pub ambient: glam::Vec3,
    /// Pass 2: the indirect light gathered from the solution at every visible
    /// point instead of read from the mesh (`None`: read from the mesh).
    pub final_gather: Option<FinalGatherSettings>,
    /// The keys the scene file set besides `method` (`global.depth`, ...): the
    /// renderer refuses those its integrator does not read.
    pub keys_set: Vec<&'static str>,
}

/// Jensen's photon maps (`[global] photons`, `caustic_photons`, `nearest`,
/// `caustic_nearest`, `precomputed_irradiance`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhotonSettings {
    /// Photons the global map holds.
    pub global: u32,
    /// Photons the caustic map holds.
    pub caustic: u32,
    /// Photons in the global map's radiance estimate (k).
    pub nearest: u32,
    /// Photons in the caustic map's radiance estimate.
    pub caustic_nearest: u32,
    /// Christensen 1999: the final gather reads irradiance precomputed at a
    /// fraction of the photons instead of estimating it at each ray's end.
    pub precomputed_irradiance: bool,
}

/// The final gather over a radiosity solution (`[global.final_gather]`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FinalGatherSettings {
    /// Rays per gather, cut into Ward's M × N strata of the hemisphere (N ≈ πM).
    pub rays: u32,
    /// Ward's accuracy a of the irradiance cache: a record serves a point while
    /// its error estimate ε stays under a (0: no cache, every sample gathers).
    pub error: f64,
    /// Ward's R is kept at least this fraction of the scene's size...
    pub min_spacing: f64,
    /// ...and at most this one.
    pub max_spacing: f64,
    /// Ward & Heckbert's gradients in the cache's interpolation.
    pub gradients: bool,
    /// Where a gather's ray lands, the polygon lights' direct light computed
    /// there (a shadow ray per light) instead of read from the mesh, which then
    /// supplies only the light that bounced more than once.
    pub direct_at_hits: bool,
}
