//! The visible-surface buffer: what the scan-line pass found at each sample.

use super::project::UvGradient;
use glam::{DVec2, DVec3, Vec3};
use std::sync::Arc;

/// `Sample::polygon` where no polygon is seen.
pub const NO_POLYGON: u32 = u32::MAX;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Id of the visible polygon (its index in the scene), or `NO_POLYGON`.
    pub polygon: u32,
    /// Id of the drawn piece of it: the polygon id itself, or a radiosity element.
    pub element: u32,
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
        element: NO_POLYGON,
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

/// The visible surface of a band of rows of the sample grid (the whole grid is one
/// band): `height` rows from row `first_row`.
#[derive(Clone, Debug)]
pub struct VisibleSurface {
    pub width: u32,
    pub height: u32,
    /// The grid row of the band's first row.
    pub first_row: u32,
    /// Row-major, the band's first row first.
    pub samples: Vec<Sample>,
    /// Per polygon id, how its texture coordinates vary across the screen (`None` for
    /// polygons not in view); the frame's, shared by its bands.
    pub uv_gradients: Arc<[Option<UvGradient>]>,
}

impl VisibleSurface {
    /// The sample at column `x` of grid row `y` (a row of this band).
    pub fn at(&self, x: u32, y: u32) -> &Sample {
        &self.samples[((y - self.first_row) * self.width + x) as usize]
    }

    /// The grid position (column, row) of sample `k` of this band.
    pub fn position_of(&self, k: usize) -> (u32, u32) {
        (
            k as u32 % self.width,
            k as u32 / self.width + self.first_row,
        )
    }

    /// The grid rows of this band.
    pub fn rows(&self) -> std::ops::Range<u32> {
        self.first_row..self.first_row + self.height
    }

    /// The footprint of sample `k` in the texture: [∂(u, v)/∂x, ∂(u, v)/∂y], exact
    /// for the polygon's interpolation (zero for an empty sample).
    pub fn uv_derivatives(&self, k: usize) -> [DVec2; 2] {
        let s = &self.samples[k];
        match self.uv_gradients.get(s.polygon as usize) {
            Some(Some(g)) => {
                let (x, y) = self.position_of(k);
                g.derivatives(x as f64 + 0.5, y as f64 + 0.5, s.uv)
            }
            _ => [DVec2::ZERO; 2],
        }
    }
}
