//! Central projection of a polygon onto a plane: the shadow a point light throws of
//! a polygon onto a receiver's plane, and, turned around, an occluder seen from a
//! receiving point on a light's plane (Nishita & Nakamae's visible part of an area
//! light). Only the part of the polygon strictly between the centre and the plane
//! projects: a point beyond the plane is not in the way, and a point level with the
//! centre would project to infinity.

use super::sutherland_hodgman::clip;
use glam::DVec3;

/// How far short of the centre's own distance to the plane the slab stops (a
/// relative 1e-6: points nearer the centre's level project farther than any
/// scene's size).
pub const SHORT_OF_CENTRE: f64 = 1.0 - 1e-6;

/// The part of `polygon` between `centre` and the plane through `origin` with normal
/// `normal`, projected from `centre` onto that plane; `None` when the centre lies in
/// the plane or nothing of the polygon is between them.
pub fn onto_plane(
    polygon: &[DVec3],
    centre: DVec3,
    origin: DVec3,
    normal: DVec3,
) -> Option<Vec<DVec3>> {
    // Signed distance to the plane, positive on the centre's side.
    let side = normal.dot(centre - origin).signum();
    let distance = |p: DVec3| (p - origin).dot(normal) * side;
    let centre_distance = distance(centre);
    if centre_distance <= 0.0 || !polygon.iter().any(|&v| distance(v) > 0.0) {
        return None;
    }
    let between = clip(polygon, |v| distance(*v));
    let between = clip(&between, |v| {
        centre_distance * SHORT_OF_CENTRE - distance(*v)
    });
    if between.len() < 3 {
        return None;
    }
    Some(
        between
            .iter()
            .map(|&v| centre + (v - centre) * (centre_distance / (centre_distance - distance(v))))
            .collect(),
    )
}

/// The projection from `centre` of one point strictly between it and the plane.
pub fn point_onto_plane(p: DVec3, centre: DVec3, origin: DVec3, normal: DVec3) -> DVec3 {
    let side = normal.dot(centre - origin).signum();
    let distance = |q: DVec3| (q - origin).dot(normal) * side;
    let centre_distance = distance(centre);
    centre + (p - centre) * (centre_distance / (centre_distance - distance(p)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_halfway_doubles() {
        let square = [
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(1.0, 1.0, -1.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(-1.0, 1.0, 1.0),
        ];
        let shadow =
            onto_plane(&square, DVec3::new(0.0, 2.0, 0.0), DVec3::ZERO, DVec3::Y).expect("between");
        for (s, v) in shadow.iter().zip(&square) {
            assert!((*s - DVec3::new(2.0 * v.x, 0.0, 2.0 * v.z)).length() < 1e-12);
        }
        // Beyond the plane, or above the centre: nothing.
        let below: Vec<DVec3> = square.iter().map(|v| *v - DVec3::Y * 3.0).collect();
        assert!(onto_plane(&below, DVec3::new(0.0, 2.0, 0.0), DVec3::ZERO, DVec3::Y).is_none());
        let above: Vec<DVec3> = square.iter().map(|v| *v + DVec3::Y * 3.0).collect();
        assert!(onto_plane(&above, DVec3::new(0.0, 2.0, 0.0), DVec3::ZERO, DVec3::Y).is_none());
    }
}
