//! The integrators: the ways a frame is lit, siblings over one visible-surface pass
//! and one shading pass (as pbrt's integrators are over one film), in a registry of
//! the shadow methods' shape. Each integrator, in its own file, declares what it is
//! (`Declaration`: its name, the scene keys it reads, the buffers it makes, its
//! role) and owns its view-independent state (`Kept`: a radiosity solution, a second
//! pass, the scene as rays see it); the renderer keeps one `Kept` and knows no
//! method's state.
//!
//! Two roles, each its own trait, so that no method answers for a role it lacks:
//! - `ScanLine`: the scan-line pass draws its polygons (the scene's, or a radiosity
//!   solution's elements) and it shades the visible samples band by band;
//! - `OwnFrame`: it makes its frame itself (Whitted's rays through the pixels).
//!
//! Adding an integrator: its file, one variant of `Integrator` and one line in
//! `INTEGRATORS` and `declaration`, and, when the scene file chooses it by
//! `[global] method`, one variant of `settings::GlobalMethod`; the compiler names
//! each match that must learn of it.

mod direct;
mod path_tracing;
mod photon_map;
mod radiosity;
mod ray_tracing;
mod rushmeier_torrance;
mod solution;
mod two_pass;

pub(super) use direct::DirectLighting;
pub(super) use solution::CACHE_RECORDS;

use super::output::Frame;
use crate::error::{Error, Result};
use crate::image_io::Buffer;
use crate::radiosity::Solution;
use crate::raster::{ScreenPolygon, View, Visibility, VisibleSurface};
use crate::scene::Scene;
use crate::settings::GlobalMethod;
use crate::shading::FrameShading;
use glam::Vec3;
use std::sync::Arc;

pub use super::output::BufferInfo;

/// Per scene environment, its map as a frame shows it (`None`: not shown).
pub type EnvironmentMaps = Arc<[Option<Arc<crate::texture::environment::EnvironmentMap>>]>;

/// Every integrator.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Integrator {
    /// The scan-line renderer's own lighting: every light, weighted per sample by
    /// its visibility (shadows).
    Direct,
    /// A view-independent diffuse radiosity solution drawn through its elements.
    Radiosity,
    /// Wallace, Cohen & Greenberg 1987: radiosity through planar mirrors, then rays
    /// off specular surfaces reading it.
    TwoPass,
    /// Rushmeier & Torrance 1990: the two-pass method through panes and
    /// translucent panels.
    RushmeierTorrance,
    /// Whitted 1980: recursive rays from the eye.
    RayTracing,
    /// Kajiya 1986: the rendering equation by path tracing.
    PathTracing,
    /// Jensen 1996: photon maps read by a final gather and directly.
    PhotonMap,
}

/// Every integrator, in the order lists show them.
pub const INTEGRATORS: [Integrator; 7] = [
    Integrator::Direct,
    Integrator::Radiosity,
    Integrator::TwoPass,
    Integrator::RushmeierTorrance,
    Integrator::RayTracing,
    Integrator::PathTracing,
    Integrator::PhotonMap,
];

/// The registry: what `integrator` declares of itself.
pub fn declaration(integrator: Integrator) -> &'static Declaration {
    match integrator {
        Integrator::Direct => &direct::DECLARATION,
        Integrator::Radiosity => &radiosity::DECLARATION,
        Integrator::TwoPass => &two_pass::DECLARATION,
        Integrator::RushmeierTorrance => &rushmeier_torrance::DECLARATION,
        Integrator::RayTracing => &ray_tracing::DECLARATION,
        Integrator::PathTracing => &path_tracing::DECLARATION,
        Integrator::PhotonMap => &photon_map::DECLARATION,
    }
}

impl Integrator {
    /// The integrator `scene` chooses: `[global] method`, else radiosity when the
    /// scene has `[radiosity]`, else direct lighting.
    pub fn of(scene: &Scene) -> Integrator {
        match (&scene.global, &scene.radiosity) {
            (Some(g), _) => match g.method {
                GlobalMethod::RayTracing => Integrator::RayTracing,
                GlobalMethod::TwoPass => Integrator::TwoPass,
                GlobalMethod::RushmeierTorrance => Integrator::RushmeierTorrance,
                GlobalMethod::PathTracing => Integrator::PathTracing,
                GlobalMethod::PhotonMap => Integrator::PhotonMap,
            },
            (None, Some(_)) => Integrator::Radiosity,
            (None, None) => Integrator::Direct,
        }
    }

    /// Its name in messages and buffer lists.
    pub fn name(self) -> &'static str {
        declaration(self).name
    }
}

/// What an integrator declares of itself, in its own file: the registry's entry.
/// The renderer, the buffers, the scene checks and the viewer ask it.
pub struct Declaration {
    pub integrator: Integrator,
    /// Its name in messages and buffer lists (the `[global] method` value for those
    /// chosen by it).
    pub name: &'static str,
    /// The `[global] method` that chooses it (`None`: chosen by the tables a
    /// scene has, see `Integrator::of`).
    pub global_method: Option<GlobalMethod>,
    /// The catalogue entry that shows it.
    pub entry: &'static str,
    /// The scene keys it reads: the `[radiosity]` table as `radiosity`, the
    /// `[global]` keys as `global.<key>` (`method` aside). A `[global]` key the
    /// scene sets, or a `[radiosity]` table it has, that the integrator does not
    /// read is refused before any work.
    pub keys: &'static [&'static str],
    /// The buffers it makes beyond the scan-line frame's own (a name ending in `*`
    /// stands for a family: `hemicube-*`).
    pub buffers: &'static [&'static str],
    pub role: Role,
    /// Per light, whether shading adds it directly (and so whether the shadow
    /// method shadows it).
    pub direct_lights: fn(&Scene) -> Vec<bool>,
    /// Refuses, before any work, a scene it cannot render (beside the keys).
    pub check: fn(&Scene) -> Result<()>,
    /// Its view-independent state for one renderer, empty.
    pub kept: fn() -> Box<dyn Kept>,
}

/// How an integrator makes a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// Over the scan-line pass, band by band (`ScanLine`).
    ScanLine,
    /// By itself (`OwnFrame`).
    OwnFrame,
}

/// An integrator's view-independent state for one renderer, built the first time a
/// frame needs it and kept between frames.
pub trait Kept: Send + Sync {
    /// What the next frame needs of it.
    fn lighting(&self, scene: &Scene) -> Result<Lighting>;

    /// The radiosity solution it reads, when it reads one.
    fn solution(&self) -> Option<&dyn ReadsSolution>;

    /// Irradiance caches swept so far (view-dependent passes over its solution).
    fn caches_swept(&self) -> usize;
}

/// The state of an integrator that reads a radiosity solution.
pub trait ReadsSolution {
    /// Hands it a solution of the scene (solved elsewhere, with progress shown),
    /// so that it is not solved again.
    fn hand_over(&self, scene: &Scene, solution: Arc<Solution>);

    /// Whether a solution is kept (solved, or handed over).
    fn has_solution(&self) -> bool;

    /// Drops the solution and what was made from it: a light it holds moved (the
    /// point, spot, distant and sphere lights are shot into it).
    fn forget(&self);

    /// Solutions it solved itself.
    fn solved(&self) -> usize;
}

/// What one frame needs of an integrator, by role.
pub enum Lighting {
    ScanLine(Arc<dyn ScanLine>),
    OwnFrame(Arc<dyn OwnFrame>),
}

/// An integrator over the scan-line pass.
pub trait ScanLine: Send + Sync {
    /// The polygons the scan-line pass draws, on `view`'s screen, with the vertex
    /// colours of the lights `direct` selects (Gouraud shading).
    fn draw_list(&self, scene: &Scene, view: &View, direct: &[bool]) -> Vec<ScreenPolygon>;

    /// Whether Gouraud shading must interpolate each direct light on its own: when
    /// lights are weighted differently, or when the samples' interpolated colour is
    /// not the lights'.
    fn gouraud_per_light(&self, scene: &Scene, direct: &[bool], shadowed: bool) -> bool;

    /// The drawn polygons again, coloured by light `l`'s unshadowed vertex radiance
    /// alone (for Gouraud shading light by light).
    fn light_draw_list(&self, scene: &Scene, view: &View, l: usize) -> Vec<ScreenPolygon>;

    /// The radiance of every sample of `band`.
    fn shade_band(
        &self,
        shading: &FrameShading,
        scene: &Scene,
        band: &VisibleSurface,
        visibility: &Visibility,
        gouraud: &[Vec<Vec3>],
    ) -> Vec<Vec3>;

    /// The radiosity of drawn element `element` (the `radiosity` buffer), where the
    /// elements drawn hold one (`None`: they are the scene's polygons).
    fn element_radiosity(&self, element: u32) -> Option<Vec3>;

    /// The whole-frame buffers it made (hemi-cube item buffers, the irradiance
    /// cache's records), the hemi-cube's at element `hemicube_element`.
    fn buffers(&self, scene: &Scene, hemicube_element: usize) -> Vec<Buffer>;
}

/// An integrator that makes its frame itself.
pub trait OwnFrame: Send + Sync {
    /// The frame, with the buffers named in `wanted`.
    fn render(
        &self,
        scene: &Scene,
        environments: &EnvironmentMaps,
        wanted: &[String],
    ) -> Result<Frame>;

    /// The buffers its frames can give.
    fn buffers(&self) -> Vec<BufferInfo>;
}

/// Whether `declared` lists `name` among its buffers (or a family holding it).
pub fn declares_buffer(declared: &Declaration, name: &str) -> bool {
    declared.buffers.iter().any(|b| match b.strip_suffix('*') {
        Some(family) => name.starts_with(family),
        None => *b == name,
    })
}

/// Refuses a scene key `declared` does not read: a `[global]` key set, or a
/// `[radiosity]` table, that its integrator would ignore.
pub fn check_keys(scene: &Scene, declared: &Declaration) -> Result<()> {
    let mut set: Vec<&str> = scene
        .global
        .as_ref()
        .map(|g| g.keys_set.clone())
        .unwrap_or_default();
    if scene.radiosity.is_some() {
        set.push("radiosity");
    }
    let Some(key) = set.into_iter().find(|k| !declared.keys.contains(k)) else {
        return Ok(());
    };
    let readers: Vec<&str> = INTEGRATORS
        .iter()
        .map(|&i| declaration(i))
        .filter(|d| d.keys.contains(&key))
        .map(|d| d.name)
        .collect();
    let shown = if key == "radiosity" {
        "[radiosity]"
    } else {
        key
    };
    let chosen_by = match declared.global_method {
        Some(m) => format!(" (global.method = \"{}\")", m.name()),
        None => String::new(),
    };
    Err(Error::invalid(
        key,
        format!(
            "{shown} is read by {}; {}{chosen_by} would ignore it: leave it out",
            readers.join(", "),
            declared.name,
        ),
    ))
}

/// Per light, whether `scene`'s integrator adds it directly.
pub fn direct_lights(scene: &Scene) -> Vec<bool> {
    (declaration(Integrator::of(scene)).direct_lights)(scene)
}

/// Whether any polygon of `scene` is Gouraud-shaded.
fn gouraud_shaded(scene: &Scene) -> bool {
    (0..scene.polygons.len()).any(|p| scene.shading_of(p) == crate::scene::ShadingMode::Gouraud)
}

/// No check beside the keys.
fn nothing_to_check(_: &Scene) -> Result<()> {
    Ok(())
}
