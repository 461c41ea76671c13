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
use super::{BandShadows, FrameShadows, LightShadows, per_sample};
use crate::output::{Buffer, BufferData};
use crate::raster::{View, VisibleSurface, rasterize_depth, screen_polygons};
use crate::scene::Scene;
use glam::DVec3;
use rayon::prelude::*;

/// One face of the cube: its view from the light and its depth image.
pub struct Face {
    pub view: View,
    pub depth: Vec<f32>,
}

/// The six depth images around a point light, and how the second pass reads them.
pub struct CubeShadowMap {
    pub light: DVec3,
    pub resolution: u32,
    pub faces: Vec<Face>,
    /// Depth bias, in slope-scaled texels.
    pub bias: f64,
    /// Percentage-closer kernel size (1: a single texel).
    pub pcf: u32,
}

/// The faces' names in buffer names, in `FACES` order.
pub const FACE_NAMES: [&str; 6] = ["px", "nx", "py", "ny", "pz", "nz"];

/// Largest tan θ the slope-scaled bias follows.
const MAX_SLOPE: f64 = 50.0;

impl CubeShadowMap {
    /// The first pass: depth images of the scene from `light`. The six faces are
    /// built in parallel: each face's projection and edge table are serial, and
    /// overlapping them halves the pass on two cores.
    pub fn build(
        scene: &Scene,
        light: DVec3,
        resolution: u32,
        bias: f64,
        pcf: u32,
    ) -> CubeShadowMap {
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
            bias,
            pcf,
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

impl LightShadows for CubeShadowMap {
    fn frame<'a>(&'a self, scene: &'a Scene, view: &'a View) -> Box<dyn FrameShadows + 'a> {
        Box::new(MapFrame {
            map: self,
            scene,
            view,
        })
    }

    fn buffers(&self, prefix: &str) -> Vec<Buffer> {
        self.faces
            .iter()
            .zip(FACE_NAMES)
            .map(|(face, name)| Buffer {
                name: format!("{prefix}-{name}"),
                width: self.resolution,
                height: self.resolution,
                data: BufferData::Values {
                    channels: 1,
                    data: face.depth.clone(),
                },
            })
            .collect()
    }
}

struct MapFrame<'a> {
    map: &'a CubeShadowMap,
    scene: &'a Scene,
    view: &'a View,
}

impl FrameShadows for MapFrame<'_> {
    fn band(&self, band: &VisibleSurface) -> BandShadows {
        let map = self.map;
        let lit = per_sample(self.scene, self.view, band, map.light, |_, _, _| true);
        BandShadows::fraction(
            band.samples
                .par_iter()
                .zip(lit)
                .map(|(sample, self_lit)| {
                    if self_lit == 0.0 {
                        0.0
                    } else {
                        let n = self.scene.polygons[sample.polygon as usize].normal;
                        map.lookup(sample.position, n, map.bias, map.pcf)
                    }
                })
                .collect(),
        )
    }
}
