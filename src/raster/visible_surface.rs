//! The visible-surface buffer: what the scan-line pass found at each sample.

use super::project::UvGradient;
use glam::{DVec2, DVec3, Vec3};

/// `Sample::polygon` where no polygon is seen.
pub const NO_POLYGON: u32 = u32::MAX;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Id of the visible polygon (its index in the scene), or `NO_POLYGON`.
    pub polygon: u32,
    /// Eye-space distance along the view direction.
    pub depth: f64,
    /// World position of the visible point.
    pub position: DVec3,
    /// Interpolated shading normal (unit length).
    pub normal: Vec3,
    /// Texture coordinates, interpolated as the polygon's material asks.
    pub uv: DVec2,
    /// Interpolated vertex colour (Gouraud shading's radiance).
    pub color: Vec3,
}

impl Sample {
    pub const EMPTY: Sample = Sample {
        polygon: NO_POLYGON,
        depth: f64::INFINITY,
        position: DVec3::ZERO,
        normal: Vec3::ZERO,
        uv: DVec2::ZERO,
        color: Vec3::ZERO,
    };

    pub fn is_empty(&self) -> bool {
        self.polygon == NO_POLYGON
    }
}

#[derive(Clone, Debug)]
pub struct VisibleSurface {
    pub width: u32,
    pub height: u32,
    /// Row-major, row 0 at the top.
    pub samples: Vec<Sample>,
    /// Per polygon id, how its texture coordinates vary across the screen (`None` for
    /// polygons not in view).
    pub uv_gradients: Vec<Option<UvGradient>>,
}

impl VisibleSurface {
    pub fn at(&self, x: u32, y: u32) -> &Sample {
        &self.samples[(y * self.width + x) as usize]
    }

    /// The footprint of sample `k` in the texture: [∂(u, v)/∂x, ∂(u, v)/∂y], exact
    /// for the polygon's interpolation (zero for an empty sample).
    pub fn uv_derivatives(&self, k: usize) -> [DVec2; 2] {
        let s = &self.samples[k];
        match self.uv_gradients.get(s.polygon as usize) {
            Some(Some(g)) => {
                let (x, y) = (k as u32 % self.width, k as u32 / self.width);
                g.derivatives(x as f64 + 0.5, y as f64 + 0.5, s.uv)
            }
            _ => [DVec2::ZERO; 2],
        }
    }
}
