//! A shadow map's depth image and a point's place in it: what Williams's test,
//! the box filter and Reeves, Salesin & Cook's percentage-closer filter all read.

use glam::DVec2;

/// A square depth image seen from the light: a face of the cube, or any image (the
/// tests build them by hand). Texel (i, j), row-major from the top, covers
/// [i, i + 1] × [j, j + 1] of map coordinates.
#[derive(Clone, Copy)]
pub struct DepthImage<'a> {
    pub size: u32,
    pub depth: &'a [f32],
}

impl DepthImage<'_> {
    /// Whether a point at `depth` (its bias taken off) is not behind texel (i, j);
    /// texels beyond the border are the border's.
    pub fn passes(&self, i: i64, j: i64, depth: f64) -> bool {
        let last = self.size as i64 - 1;
        let (i, j) = (i.clamp(0, last), j.clamp(0, last));
        depth <= self.depth[(j * self.size as i64 + i) as usize] as f64
    }

    /// The texel under map position `at` (the border's beyond it).
    pub fn texel(&self, at: DVec2) -> (i64, i64) {
        let last = self.size as i64 - 1;
        let index = |v: f64| (v.floor() as i64).clamp(0, last);
        (index(at.x), index(at.y))
    }

    /// The box filter: the fraction of the `kernel × kernel` texels centred on texel
    /// (i, j) that pass at `depth` (kernel 1: Williams's single test).
    pub fn box_filter(&self, (i, j): (i64, i64), kernel: u32, depth: f64) -> f32 {
        let r = (kernel / 2) as i64;
        let mut passed = 0;
        for dj in -r..=r {
            for di in -r..=r {
                passed += self.passes(i + di, j + dj, depth) as u32;
            }
        }
        passed as f32 / (kernel * kernel) as f32
    }
}

/// Where a point falls in the map, and its depth test.
#[derive(Clone, Copy, Debug)]
pub struct MapPoint {
    /// The cube face (index in `FACES`).
    pub face: usize,
    /// Its map position, in texels.
    pub at: DVec2,
    /// Its depth along the face's axis.
    pub depth: f64,
    /// 1 + tan θ: the slope scale of its bias.
    pub slope: f64,
    /// The size of one texel at its distance.
    pub texel: f64,
}

impl MapPoint {
    /// Its depth less a bias of `bias` slope-scaled texels.
    pub fn less(&self, bias: f64) -> f64 {
        self.depth - bias * self.slope * self.texel
    }
}
