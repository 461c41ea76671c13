//! Shadows: every method answers, for one light, how much of it reaches each visible
//! sample (`raster::LightVisibility`: a fraction, or the visible part of an extended
//! emitter), so shading never needs to know how shadows are made and methods can be
//! compared sample by sample.
//!
//! A method works in three stages, so that a renderer can keep what does not depend
//! on the view: `prepare` builds its view-independent pre-pass for one light (the
//! shadow map, the shadow polygons, the volumes' quads), `LightShadows::frame` what
//! depends on the view (projections onto the screen), and `FrameShadows::band`
//! answers for the visible samples of one band of rows.
//!
//! Shared rule (Appel's "self-shadow"), on by default (`[shadows] self_shadow`): a
//! sample whose surface, on the side the eye sees, faces away from a point light is
//! shadowed by every method, so that methods compared sample by sample differ only
//! in how they find the cast shadows. Off, each method answers there on its own
//! (a shadow map's acne on the dark side, a volume's terminator). Spot lights are point lights with a
//! directional intensity: every hard-shadow method shadows them from their position.
//! Ray casting also samples extended lights, and shadow volumes also shadow distant
//! lights. The soft-shadow methods shadow polygon lights (`umbra_penumbra` exactly,
//! `soft_shadow_volumes` by points) or sphere lights (`jittered_soft_shadows`);
//! `light_volumes` cuts viewing rays, not visible samples, for the medium. A method
//! asked for a light it cannot handle refuses it (`Unsupported`), naming both:
//! nothing is silently unshadowed.

mod cone_tree;
pub mod cube_faces;
mod depth_image;
pub mod jittered_soft_shadows;
pub mod light_volumes;
pub mod percentage_closer;
pub mod ray_cast;
mod receivers;
pub mod scanline_shadows;
pub mod shadow_map;
pub mod shadow_polygon_areas;
pub mod shadow_polygons;
pub mod shadow_volumes;
pub mod soft_shadow_volumes;
pub mod stencil_shadow_volumes;
pub mod umbra_penumbra;
mod unshadowed;

use crate::error::OverBudget;
use crate::image_io::Buffer;
use crate::raster::{LightVisibility, View, Visibility, VisibleSurface};
use crate::scene::{LightKind, Scene};
use crate::settings::ShadowSettings;
use glam::DVec3;
use rayon::prelude::*;
use std::sync::Arc;

pub use crate::error::Unsupported;
pub use crate::settings::ShadowMethod;
pub use ray_cast::SceneOccluders;

/// One light's view-independent shadow pre-pass.
pub trait LightShadows: Send + Sync {
    /// What this light's shadows need of one view.
    fn frame<'a>(&'a self, scene: &'a Scene, view: &'a View) -> Box<dyn FrameShadows + 'a>;

    /// View-independent buffers the pre-pass made (a shadow map's faces), named
    /// with `prefix`.
    fn buffers(&self, _prefix: &str) -> Vec<Buffer> {
        Vec::new()
    }
}

/// One light's shadows in one view.
pub trait FrameShadows: Send + Sync {
    /// The light's visibility at every sample of `band`.
    fn band(&self, band: &VisibleSurface) -> BandShadows;
}

/// What a method found on one band: the visibility, and the shadow-volume count per
/// sample for the methods that count.
pub struct BandShadows {
    pub visibility: LightVisibility,
    pub counts: Option<Vec<i32>>,
}

impl BandShadows {
    fn fraction(values: Vec<f32>) -> BandShadows {
        BandShadows {
            visibility: LightVisibility::Fraction(values),
            counts: None,
        }
    }
}

/// Scene-wide work shared by the lights' pre-passes: the occluders' hierarchy, built
/// on first use.
pub trait SharedWork {
    fn occluders(&self) -> Arc<SceneOccluders>;
}

/// What a shadow method declares of itself, in its own file: the registry's entry.
/// Renderer, buffers, error messages, scene checks and the viewer ask it.
pub struct Method {
    pub method: ShadowMethod,
    /// The name the scene file and the command line use.
    pub name: &'static str,
    /// The catalogue entry that shows it (`None`: no shadows to show).
    pub entry: Option<&'static str>,
    /// What it is, for the refusal of a light it cannot shadow.
    pub handles: &'static str,
    /// The lights it shadows; it refuses the others.
    pub lights: &'static [LightKind],
    /// The per-sample count buffer it makes, if any.
    pub counts: Option<CountBuffer>,
    /// Refuses, before any work, settings whose pre-passes would exceed
    /// `shadows.max_memory_mb`.
    pub budget: fn(&Scene) -> Result<(), Box<OverBudget>>,
    /// What a user should know of this scene under this method (one line each).
    pub warnings: fn(&Scene) -> Vec<String>,
    /// Its view-independent pre-pass for light `index` (`None`: casts no shadows).
    pub prepare: Prepare,
}

/// A method's pre-pass builder: scene, light index, settings, shared work.
pub type Prepare =
    fn(&Scene, usize, &ShadowSettings, &dyn SharedWork) -> Option<Arc<dyn LightShadows>>;

/// A per-sample count buffer, named `{prefix}-{light}`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CountBuffer {
    pub prefix: &'static str,
    /// What it holds; `{l}` stands for the light's index.
    pub description: &'static str,
}

impl CountBuffer {
    pub fn name(&self, light: usize) -> String {
        format!("{}-{light}", self.prefix)
    }

    pub fn describe(&self, light: usize) -> String {
        self.description.replace("{l}", &light.to_string())
    }
}

/// No budget: the method's pre-pass grows with the scene, which has its own.
fn no_budget(_: &Scene) -> Result<(), Box<OverBudget>> {
    Ok(())
}

/// Nothing to warn of.
fn no_warnings(_: &Scene) -> Vec<String> {
    Vec::new()
}

/// Every shadow method, in the order lists show them.
pub const METHODS: [ShadowMethod; 10] = [
    ShadowMethod::None,
    ShadowMethod::RayCast,
    ShadowMethod::Scanline,
    ShadowMethod::ShadowPolygons,
    ShadowMethod::ShadowVolumes,
    ShadowMethod::StencilShadowVolumes,
    ShadowMethod::ShadowMap,
    ShadowMethod::UmbraPenumbra,
    ShadowMethod::SoftShadowVolumes,
    ShadowMethod::JitteredSoftShadows,
];

/// The registry: what `method` declares of itself.
pub fn method(method: ShadowMethod) -> &'static Method {
    match method {
        ShadowMethod::None => &unshadowed::METHOD,
        ShadowMethod::RayCast => &ray_cast::METHOD,
        ShadowMethod::Scanline => &scanline_shadows::METHOD,
        ShadowMethod::ShadowPolygons => &shadow_polygons::METHOD,
        ShadowMethod::ShadowMap => &shadow_map::METHOD,
        ShadowMethod::ShadowVolumes => &shadow_volumes::METHOD,
        ShadowMethod::StencilShadowVolumes => &stencil_shadow_volumes::METHOD,
        ShadowMethod::UmbraPenumbra => &umbra_penumbra::METHOD,
        ShadowMethod::SoftShadowVolumes => &soft_shadow_volumes::METHOD,
        ShadowMethod::JitteredSoftShadows => &jittered_soft_shadows::METHOD,
    }
}

impl ShadowMethod {
    /// The name the scene file and the command line use.
    pub fn name(self) -> &'static str {
        method(self).name
    }
}

/// Whether `method` can shadow light `index` of `scene` (before any work is done).
pub fn check(scene: &Scene, index: usize, method: ShadowMethod) -> Result<(), Unsupported> {
    let declared = self::method(method);
    let light = &scene.lights[index];
    match declared.lights.contains(&light.kind()) {
        true => Ok(()),
        false => Err(Unsupported {
            method,
            name: declared.name,
            handles: declared.handles,
            light: light.label(index),
        }),
    }
}

/// Builds `method`'s pre-pass for light `index` of `scene`; `None` when the method
/// casts no shadows.
pub fn prepare(
    scene: &Scene,
    index: usize,
    settings: &ShadowSettings,
    shared: &dyn SharedWork,
) -> Result<Option<Arc<dyn LightShadows>>, Unsupported> {
    check(scene, index, settings.method)?;
    Ok((method(settings.method).prepare)(
        scene, index, settings, shared,
    ))
}

/// Scene-wide work built afresh for one call (the renderer keeps its own).
struct FreshWork<'a>(&'a Scene);

impl SharedWork for FreshWork<'_> {
    fn occluders(&self) -> Arc<SceneOccluders> {
        Arc::new(SceneOccluders::owned(self.0.polygons.clone()))
    }
}

/// Light `index`'s shadows by `settings` on a whole visible-surface buffer, its
/// pre-pass built afresh, with the method's counts; `None` when the method casts no
/// shadows (for tests and one-off measurements).
pub fn light_band(
    scene: &Scene,
    view: &View,
    surface: &VisibleSurface,
    settings: &ShadowSettings,
    index: usize,
) -> Result<Option<BandShadows>, Unsupported> {
    let shadows = prepare(scene, index, settings, &FreshWork(scene))?;
    Ok(shadows.map(|s| s.frame(scene, view).band(surface)))
}

/// Every light's visibility on a whole visible-surface buffer by `method`, each
/// pre-pass built afresh (for tests and one-off measurements; renders go through
/// the renderer, which keeps pre-passes between frames).
pub fn visibility(
    scene: &Scene,
    view: &View,
    surface: &VisibleSurface,
    settings: &ShadowSettings,
) -> Result<Visibility, Unsupported> {
    let mut per_light = Vec::new();
    for index in 0..scene.lights.len() {
        let band = light_band(scene, view, surface, settings, index)?;
        per_light.push(band.map(|b| b.visibility));
    }
    Ok(Visibility { per_light })
}

/// As `visibility`, with the scene's shadow settings but `method`.
pub fn compute(
    scene: &Scene,
    view: &View,
    surface: &VisibleSurface,
    method: ShadowMethod,
) -> Result<Visibility, Unsupported> {
    let settings = ShadowSettings {
        method,
        ..scene.shadows.clone()
    };
    visibility(scene, view, surface, &settings)
}

/// Whether the sample's surface, on the side the eye sees, faces away from the light
/// (or the light lies in its plane): self-shadowed, when the scene keeps Appel's rule
/// (`[shadows] self_shadow`; off, never).
pub fn faces_away(scene: &Scene, view: &View, polygon: u32, position: DVec3, light: DVec3) -> bool {
    if !scene.shadows.self_shadow {
        return false;
    }
    let n = scene.polygons[polygon as usize].normal;
    let eye_side = n.dot(view.eye - position);
    let light_side = n.dot(light - position);
    eye_side * light_side <= 0.0
}

/// Per sample: 0 where empty or self-shadowed, else `lit(k, polygon, position)`.
pub fn per_sample(
    scene: &Scene,
    view: &View,
    surface: &VisibleSurface,
    light: DVec3,
    lit: impl Fn(usize, u32, DVec3) -> bool + Sync,
) -> Vec<f32> {
    surface
        .samples
        .par_iter()
        .enumerate()
        .map(|(k, s)| {
            let visible = !s.is_empty()
                && !faces_away(scene, view, s.polygon, s.position, light)
                && lit(k, s.polygon, s.position);
            if visible { 1.0 } else { 0.0 }
        })
        .collect()
}
