//! Shadow depth maps: L. Williams, "Casting curved shadows on curved surfaces",
//! Computer Graphics (SIGGRAPH '78) 12(3):270–274, 1978; percentage-closer filtering:
//! W. T. Reeves, D. H. Salesin, R. L. Cook, "Rendering antialiased shadows with depth
//! maps", Computer Graphics (SIGGRAPH '87) 21(4):283–291, 1987.
//!
//! First pass: the scene is rendered from the light into a depth image by the
//! project's own scan-line rasterizer. A point light sees all around, so it gets six
//! 90° frusta, the faces of a cube (±x, ±y, ±z). Second pass: each visible point is
//! transformed into the light's frame (the cube face its direction falls in), its
//! depth along that face's axis is compared with the depth stored in the texel it
//! lands in, and it is in shadow when it lies farther than the stored depth plus a
//! bias. With percentage-closer filtering the comparison is made against each texel
//! of a k × k neighbourhood and the fraction that passes is the visibility.
//!
//! Choices (Williams leaves the bias open): the bias is measured in texels and
//! slope-scaled, `map_bias` × (1 + tan θ) × the size of one texel at the point's
//! distance (2z/resolution for a 90° face), θ the angle between the surface normal
//! and the light: a surface the light grazes changes depth by tan θ texels from one
//! texel to the next, which a constant bias cannot absorb. tan θ is capped at 50, so
//! surfaces seen almost edge-on from the light keep some acne: the method's limit.
//! PCF neighbourhoods stop at the face's border (clamped). Williams's
//! original applied the shadow to the finished image (`post_pass`, see `render`);
//! the default looks the map up inside the light model. Scene keys:
//! `[shadows] method = "shadow-map"`, `map_resolution`, `map_bias`, `pcf`, `post_pass`.

use super::cube_faces::{FACES, face_of, face_view};
use super::per_sample;
use crate::raster::{View, VisibleSurface, rasterize_depth, screen_polygons};
use crate::scene::Scene;
use glam::DVec3;
use rayon::prelude::*;

/// One face of the cube: its view from the light and its depth image.
pub struct Face {
    pub view: View,
    pub depth: Vec<f32>,
}

/// The six depth images around a point light.
pub struct CubeShadowMap {
    pub light: DVec3,
    pub resolution: u32,
    pub faces: Vec<Face>,
}

/// Largest tan θ the slope-scaled bias follows.
const MAX_SLOPE: f64 = 50.0;

impl CubeShadowMap {
    /// The first pass: depth images of the scene from `light`. The six faces are
    /// built in parallel: each face's projection and edge table are serial, and
    /// overlapping them halves the pass on two cores.
    pub fn build(scene: &Scene, light: DVec3, resolution: u32) -> CubeShadowMap {
        let faces = FACES
            .par_iter()
            .map(|&face| {
                let view = face_view(scene, light, face, resolution);
                let depth = rasterize_depth(&screen_polygons(scene, &view), resolution, resolution);
                Face { view, depth }
            })
            .collect();
        CubeShadowMap {
            light,
            resolution,
            faces,
        }
    }

    /// The second pass at one point with unit normal `n`: the fraction of the
    /// `kernel × kernel` texels around the point's texel whose stored depth is not
    /// nearer than the point's depth less the bias (`bias` in slope-scaled texels).
    pub fn lookup(&self, p: DVec3, n: DVec3, bias: f64, kernel: u32) -> f32 {
        let face = &self.faces[face_of(p - self.light)];
        let eye = face.view.to_eye(p);
        let (x, y) = face.view.project(eye);
        let size = self.resolution as i64;
        let texel_at = |v: f64| (v.floor() as i64).clamp(0, size - 1);
        let (i, j) = (texel_at(x), texel_at(y));
        let texel = 2.0 * eye.z / self.resolution as f64;
        let cos = n.dot((self.light - p).normalize()).abs().max(1e-12);
        let tan = ((1.0 - cos * cos).sqrt() / cos).min(MAX_SLOPE);
        let depth = eye.z - bias * (1.0 + tan) * texel;
        let r = (kernel / 2) as i64;
        let mut passed = 0;
        for dj in -r..=r {
            for di in -r..=r {
                let (u, v) = ((i + di).clamp(0, size - 1), (j + dj).clamp(0, size - 1));
                passed += (depth <= face.depth[(v * size + u) as usize] as f64) as u32;
            }
        }
        passed as f32 / (kernel * kernel) as f32
    }
}

/// The visibility of the point light at `light` for every sample.
pub fn visibility(scene: &Scene, view: &View, surface: &VisibleSurface, light: DVec3) -> Vec<f32> {
    let s = &scene.shadows;
    let map = CubeShadowMap::build(scene, light, s.map_resolution);
    let lit = per_sample(scene, view, surface, light, |_, _, _| true);
    surface
        .samples
        .par_iter()
        .zip(lit)
        .map(|(sample, self_lit)| {
            if self_lit == 0.0 {
                0.0
            } else {
                let n = scene.polygons[sample.polygon as usize].normal;
                map.lookup(sample.position, n, s.map_bias, s.pcf)
            }
        })
        .collect()
}
