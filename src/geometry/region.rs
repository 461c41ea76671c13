//! Regions of the plane as Weiler–Atherton clipping takes and gives them: lists of
//! contours, outer ones counter-clockwise, holes clockwise.

use glam::DVec2;

/// A region: outer contours counter-clockwise, holes clockwise.
pub type Region = Vec<Vec<DVec2>>;

/// Signed area of a contour (positive counter-clockwise).
pub fn contour_area(c: &[DVec2]) -> f64 {
    let mut twice = 0.0;
    for (i, a) in c.iter().enumerate() {
        let b = c[(i + 1) % c.len()];
        twice += a.perp_dot(b);
    }
    0.5 * twice
}

/// Area of a region: its outer contours less its holes.
pub fn area(region: &Region) -> f64 {
    region.iter().map(|c| contour_area(c)).sum()
}
