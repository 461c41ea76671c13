//! Shadows: every method answers, for one point light, how much of it reaches each
//! visible sample (0 shadowed, 1 lit, between for partial), so shading never needs to
//! know how shadows are made and methods can be compared sample by sample.
//!
//! Shared rule (Appel's "self-shadow"): a sample whose surface, on the side the eye
//! sees, faces away from the light is shadowed by every method; the methods differ in
//! how they find the cast shadows. Spot lights are shadowed as point lights at their
//! position; distant, polygon and sphere lights are not shadowed by these hard-shadow
//! methods.

pub mod cube_faces;
pub mod ray_cast;
pub mod scanline_shadows;
pub mod shadow_map;
pub mod shadow_polygon_areas;
pub mod shadow_polygons;
pub mod shadow_volumes;

use crate::raster::{View, VisibleSurface};
use crate::scene::Scene;
use glam::DVec3;
use rayon::prelude::*;

/// How shadows are computed (`[shadows] method`, `--shadows`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum ShadowMethod {
    /// No shadows: every light reaches every point.
    #[default]
    None,
    /// Appel 1968: the segment from each visible point to the light, tested against
    /// the scene through a bounding volume hierarchy.
    RayCast,
    /// Bouknight & Kelley 1970: shadow polygons projected onto each receiver in a
    /// pre-pass, span segments classified against them during scan-out.
    Scanline,
    /// Atherton, Weiler & Greenberg 1978: the polygons the light sees, found by
    /// Weiler-Atherton hidden-surface removal, attached as lit detail polygons.
    ShadowPolygons,
    /// Williams 1978: depth images from the light, compared per visible point.
    ShadowMap,
    /// Crow 1977: volumes bounded by quads through the silhouette edges, counted
    /// along each pixel's line of sight.
    ShadowVolumes,
}

/// The visibility terms of one render: per light, per sample of the visible-surface
/// buffer. A light without a buffer is wholly visible everywhere.
#[derive(Clone, Debug, Default)]
pub struct Visibility {
    pub per_light: Vec<Option<Vec<f32>>>,
}

impl Visibility {
    /// Every light fully visible at every sample (no shadows).
    pub fn none() -> Visibility {
        Visibility::default()
    }

    /// The visibility of every point light by `method`.
    pub fn compute(
        scene: &Scene,
        view: &View,
        surface: &VisibleSurface,
        method: ShadowMethod,
    ) -> Visibility {
        if method == ShadowMethod::None {
            return Visibility::none();
        }
        let per_light = scene
            .lights
            .iter()
            .map(|light| {
                // Point-like lights (point, spot) only; the others stay unshadowed.
                let at = light.position()?;
                Some(match method {
                    ShadowMethod::None => unreachable!("handled above"),
                    ShadowMethod::RayCast => ray_cast::visibility(scene, view, surface, at),
                    ShadowMethod::Scanline => {
                        scanline_shadows::visibility(scene, view, surface, at)
                    }
                    ShadowMethod::ShadowMap => shadow_map::visibility(scene, view, surface, at),
                    ShadowMethod::ShadowPolygons => {
                        shadow_polygons::visibility(scene, view, surface, at)
                    }
                    ShadowMethod::ShadowVolumes => {
                        shadow_volumes::visibility(scene, view, surface, at)
                    }
                })
            })
            .collect();
        Visibility { per_light }
    }

    /// Visibility of light `light` at sample `k`.
    pub fn of(&self, light: usize, k: usize) -> f32 {
        match self.per_light.get(light) {
            Some(Some(buffer)) => buffer[k],
            _ => 1.0,
        }
    }

    /// Mean visibility of all lights at sample `k` (for modes that shade per vertex
    /// or per polygon and so cannot weigh lights one by one).
    pub fn mean(&self, k: usize) -> f32 {
        let count = self.per_light.len();
        if count == 0 {
            return 1.0;
        }
        (0..count).map(|l| self.of(l, k)).sum::<f32>() / count as f32
    }
}

/// Whether the sample's surface, on the side the eye sees, faces away from the light
/// (or the light lies in its plane): self-shadowed.
pub fn faces_away(scene: &Scene, view: &View, polygon: u32, position: DVec3, light: DVec3) -> bool {
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
