//! Direct lighting: the scan-line renderer's own. The scene's polygons are drawn
//! with their vertex colours (Gouraud) and every sample is lit by every light,
//! weighted by its visibility (the shadow method's).

use super::{Declaration, Integrator, Kept, Lighting, ReadsSolution, Role, ScanLine};
use crate::error::Result;
use crate::image_io::Buffer;
use crate::raster::{ScreenPolygon, ToPrepare, View, Visibility, VisibleSurface, prepare};
use crate::scene::Scene;
use crate::shading::{FrameShading, vertex_colors};
use crate::texture::Interpolation;
use glam::Vec3;
use std::sync::Arc;

pub static DECLARATION: Declaration = Declaration {
    integrator: Integrator::Direct,
    name: "direct",
    global_method: None,
    entry: "cornell-box-point",
    keys: &[],
    buffers: &[],
    role: Role::ScanLine,
    direct_lights: every_light,
    check: super::nothing_to_check,
    kept: || Box::new(Nothing),
};

/// Every light is added directly.
fn every_light(scene: &Scene) -> Vec<bool> {
    vec![true; scene.lights.len()]
}

/// Direct lighting keeps nothing between frames (the shadows are the renderer's).
struct Nothing;

impl Kept for Nothing {
    fn lighting(&self, _: &Scene) -> Result<Lighting> {
        Ok(Lighting::ScanLine(Arc::new(DirectLighting)))
    }

    fn solution(&self) -> Option<&dyn ReadsSolution> {
        None
    }

    fn caches_swept(&self) -> usize {
        0
    }
}

/// The scene's polygons, lit by the lights.
pub struct DirectLighting;

impl ScanLine for DirectLighting {
    fn draw_list(&self, scene: &Scene, view: &View, direct: &[bool]) -> Vec<ScreenPolygon> {
        let colors = vertex_colors(scene, view, direct);
        prepare(
            view,
            scene
                .polygons
                .iter()
                .zip(&colors)
                .enumerate()
                .map(|(id, (p, c))| ToPrepare {
                    id: id as u32,
                    element: id as u32,
                    vertices: &p.vertices,
                    colors: c,
                    affine_uv: scene.materials[p.material].interpolation == Interpolation::Affine,
                }),
        )
    }

    /// Light by light when several lights are shadowed: each is weighted by its
    /// own visibility.
    fn gouraud_per_light(&self, scene: &Scene, _: &[bool], shadowed: bool) -> bool {
        super::gouraud_shaded(scene) && shadowed && scene.lights.len() > 1
    }

    fn light_draw_list(&self, scene: &Scene, view: &View, l: usize) -> Vec<ScreenPolygon> {
        let only: Vec<bool> = (0..scene.lights.len()).map(|m| m == l).collect();
        self.draw_list(scene, view, &only)
    }

    fn shade_band(
        &self,
        shading: &FrameShading,
        _: &Scene,
        band: &VisibleSurface,
        visibility: &Visibility,
        gouraud: &[Vec<Vec3>],
    ) -> Vec<Vec3> {
        shading.shade_band(band, visibility, gouraud)
    }

    fn element_radiosity(&self, _: u32) -> Option<Vec3> {
        None
    }

    fn buffers(&self, _: &Scene, _: usize) -> Vec<Buffer> {
        Vec::new()
    }
}
