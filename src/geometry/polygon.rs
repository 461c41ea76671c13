//! Measures of planar polygons in 3D: Newell's normal, area, planarity.

use glam::DVec3;

/// Newell's method: the area-weighted normal of a polygon, robust for concave and
/// nearly degenerate polygons. Its length is twice the polygon's area; it points to
/// the side from which the vertices run counter-clockwise.
pub fn newell_normal(vertices: &[DVec3]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for (i, a) in vertices.iter().enumerate() {
        let b = vertices[(i + 1) % vertices.len()];
        n.x += (a.y - b.y) * (a.z + b.z);
        n.y += (a.z - b.z) * (a.x + b.x);
        n.z += (a.x - b.x) * (a.y + b.y);
    }
    n
}

/// Area of a planar polygon (any orientation).
pub fn area(vertices: &[DVec3]) -> f64 {
    0.5 * newell_normal(vertices).length()
}

/// Largest distance of a vertex from the polygon's mean plane, relative to the
/// polygon's size (its longest vertex distance from the centroid).
pub fn non_planarity(vertices: &[DVec3]) -> f64 {
    let n = newell_normal(vertices).normalize_or_zero();
    let c = centroid(vertices);
    let size = vertices
        .iter()
        .map(|v| (*v - c).length())
        .fold(0.0, f64::max);
    if size == 0.0 {
        return 0.0;
    }
    vertices
        .iter()
        .map(|v| (*v - c).dot(n).abs())
        .fold(0.0, f64::max)
        / size
}

/// Mean of the vertices (the centre a flat-shaded polygon is lit at).
pub fn centroid(vertices: &[DVec3]) -> DVec3 {
    vertices.iter().copied().sum::<DVec3>() / vertices.len() as f64
}

/// Signed area of a 2D polygon by the shoelace formula (positive counter-clockwise
/// in a y-up frame).
pub fn signed_area_2d(points: &[[f64; 2]]) -> f64 {
    let mut twice = 0.0;
    for (i, a) in points.iter().enumerate() {
        let b = points[(i + 1) % points.len()];
        twice += a[0] * b[1] - b[0] * a[1];
    }
    0.5 * twice
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_square_has_unit_area_and_up_normal() {
        let sq = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        assert_eq!(area(&sq), 1.0);
        assert_eq!(newell_normal(&sq).normalize(), DVec3::Z);
        assert_eq!(non_planarity(&sq), 0.0);
    }

    #[test]
    fn shoelace_is_signed() {
        let ccw = [[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]];
        let cw = [[0.0, 0.0], [0.0, 2.0], [2.0, 0.0]];
        assert_eq!(signed_area_2d(&ccw), 2.0);
        assert_eq!(signed_area_2d(&cw), -2.0);
    }
}
