//! Percentage-closer filtering: W. T. Reeves, D. H. Salesin, R. L. Cook, "Rendering
//! antialiased shadows with depth maps", Computer Graphics (SIGGRAPH '87)
//! 21(4):283–291, 1987.
//!
//! A shadow test is binary, so averaging the map's depths before it means nothing;
//! Reeves et al. filter the tests' results instead. The sample's footprint, its
//! cell of the screen carried onto the surface and into the light's map, bounds a
//! region of the map; N points are placed in it, stratified and jittered; each
//! compares the sample's depth, less a bias of its own drawn at random between a
//! minimum and a maximum, with the depth stored where it falls; the fraction that
//! passes is the light's visibility. It estimates the share of the region's area
//! whose texels pass, so shadow edges are antialiased at the scale of the screen,
//! whatever the map's. The random bias turns the moiré of self-shadowing into
//! noise. Enlarging the region softens the edges (the look of a penumbra, not a
//! physical one).
//!
//! Choices the paper leaves open, ours:
//! - Footprint: the rays through the four corners of the sample's cell on the sample
//!   grid meet the plane of the sample's polygon; those points, in the map of the
//!   cube face the sample itself falls in, have a bounding rectangle (the paper's
//!   bounding box too).
//! - Grazing: the rectangle is clipped to the square of side `MAX_FOOTPRINT` texels
//!   centred on the sample's own map position; a corner whose ray misses the plane
//!   (parallel to it, or meeting it behind the eye) or whose point lies behind the
//!   light's face makes the footprint that whole square. The cap keeps a grazed
//!   sample's points near its own shadow, not spread hundreds of texels along the
//!   surface, at the price of some aliasing there.
//! - Enlargement: then `pcf_scale` multiplies the sides about the centre and
//!   `pcf_min_size` widens each side to at least that many texels.
//! - Points: √N × √N strata of the region, one uniform point in each; each reads the
//!   texel under it (no interpolation); beyond the face's border, the border texel.
//! - Bias: per point, uniform in [min, max] slope-scaled texels, the unit of
//!   `map_bias` (see `shadow_map`).
//! - Random numbers: one stream per sample, from the seed, the light and the
//!   sample's place on the whole grid; point k takes its numbers 3k to 3k + 2. The
//!   image does not depend on threads or bands.
//!
//! Scene keys: `[shadows] method = "shadow-map"`, `map_filter = "percentage-closer"`,
//! `pcf_samples = N`, `pcf_bias = [min, max]`, `pcf_scale`, `pcf_min_size`, `seed`.

use super::depth_image::{DepthImage, MapPoint};
use crate::geometry::sampling::Stream;
use crate::raster::View;
use crate::settings::PercentageCloser;
use glam::{DVec2, DVec3};

/// The widest a footprint may be, in texels along each axis of the map.
pub const MAX_FOOTPRINT: f64 = 16.0;

/// A rectangle of map coordinates, in texels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Region {
    pub min: DVec2,
    pub max: DVec2,
}

impl Region {
    /// Texel (i, j)'s square.
    pub fn texel(i: i64, j: i64) -> Region {
        let min = DVec2::new(i as f64, j as f64);
        Region {
            min,
            max: min + DVec2::ONE,
        }
    }

    /// The square of side `side` centred on `centre`.
    pub fn square(centre: DVec2, side: f64) -> Region {
        Region {
            min: centre - 0.5 * side,
            max: centre + 0.5 * side,
        }
    }

    pub fn size(&self) -> DVec2 {
        self.max - self.min
    }

    /// The sides multiplied by `scale`, then each widened to at least `min_size`,
    /// about the centre.
    pub fn enlarged(self, scale: f64, min_size: f64) -> Region {
        let half = (0.5 * scale * self.size()).max(DVec2::splat(0.5 * min_size));
        let centre = 0.5 * (self.min + self.max);
        Region {
            min: centre - half,
            max: centre + half,
        }
    }
}

/// The footprint in `light`'s map of cell (x, y) of the `eye` grid, on the plane
/// through `p` with normal `n`; `at` is `p`'s own map position.
pub fn footprint(
    eye: &View,
    (x, y): (u32, u32),
    p: DVec3,
    n: DVec3,
    light: &View,
    at: DVec2,
) -> Region {
    let cap = Region::square(at, MAX_FOOTPRINT);
    let (mut min, mut max) = (at, at);
    for (cx, cy) in [(x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)] {
        let (origin, direction) = eye.ray_through(cx as f64, cy as f64);
        let t = n.dot(p - origin) / n.dot(direction);
        if !(t.is_finite() && t > 0.0) {
            return cap;
        }
        let e = light.to_eye(origin + t * direction);
        if e.z <= 0.0 {
            return cap;
        }
        let (u, v) = light.project(e);
        min = min.min(DVec2::new(u, v));
        max = max.max(DVec2::new(u, v));
    }
    Region {
        min: min.max(cap.min),
        max: max.min(cap.max),
    }
}

/// Reeves's estimate for the point `at` of depth image `map`: the fraction of
/// `filter.samples` jittered points of `region` whose depth test passes, each with
/// its own bias, the random numbers drawn from `stream`.
pub fn percentage_closer(
    map: &DepthImage,
    at: &MapPoint,
    region: Region,
    filter: &PercentageCloser,
    stream: &mut Stream,
) -> f32 {
    let n = filter.samples.isqrt().max(1);
    let step = region.size() / n as f64;
    let [low, high] = filter.bias;
    let mut passed = 0;
    for j in 0..n {
        for i in 0..n {
            let x = region.min.x + (i as f64 + stream.next_f64()) * step.x;
            let y = region.min.y + (j as f64 + stream.next_f64()) * step.y;
            let bias = low + (high - low) * stream.next_f64();
            passed += map.passes(x.floor() as i64, y.floor() as i64, at.less(bias)) as u32;
        }
    }
    passed as f32 / (n * n) as f32
}
