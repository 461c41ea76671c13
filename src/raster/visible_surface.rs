//! The visible-surface buffer: what the scan-line pass found at each sample.

use glam::{DVec3, Vec2, Vec3};

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
    pub uv: Vec2,
    /// Interpolated vertex colour (Gouraud shading's radiance).
    pub color: Vec3,
}

impl Sample {
    pub const EMPTY: Sample = Sample {
        polygon: NO_POLYGON,
        depth: f64::INFINITY,
        position: DVec3::ZERO,
        normal: Vec3::ZERO,
        uv: Vec2::ZERO,
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
}

impl VisibleSurface {
    pub fn at(&self, x: u32, y: u32) -> &Sample {
        &self.samples[(y * self.width + x) as usize]
    }
}
