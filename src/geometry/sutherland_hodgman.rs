//! Sutherland–Hodgman re-entrant polygon clipping.
//!
//! I. E. Sutherland, G. W. Hodgman, "Reentrant polygon clipping", CACM 17(1):32–42,
//! 1974. The subject polygon is clipped against one boundary plane at a time; each
//! stage's output is the next stage's input. Walking the edges S→P: both inside,
//! emit P; leaving, emit the intersection; both outside, nothing; entering, emit the
//! intersection then P. Every vertex attribute is interpolated with the same t.
//!
//! Choice left open by the paper: the intersection is always computed from the inside
//! vertex towards the outside one, so two polygons sharing an edge get bit-identical
//! clipped vertices on it whichever direction they walk it (no cracks after clipping).

/// A vertex that can be interpolated along an edge.
pub trait Lerp: Clone {
    /// The point `self + t (other − self)`, attributes included.
    fn lerp(&self, other: &Self, t: f64) -> Self;
}

impl Lerp for glam::DVec3 {
    fn lerp(&self, other: &Self, t: f64) -> Self {
        *self + (*other - *self) * t
    }
}

impl Lerp for glam::DVec2 {
    fn lerp(&self, other: &Self, t: f64) -> Self {
        *self + (*other - *self) * t
    }
}

/// Clips `polygon` to the half-space `distance(v) >= 0`. The result may be empty;
/// a concave polygon that the plane cuts in several pieces comes back as one polygon
/// joined by zero-area bridges along the plane (the method's known limit).
pub fn clip<V: Lerp>(polygon: &[V], distance: impl Fn(&V) -> f64) -> Vec<V> {
    let mut out = Vec::with_capacity(polygon.len() + 2);
    let Some(last) = polygon.last() else {
        return out;
    };
    let mut s = last;
    let mut ds = distance(s);
    for p in polygon {
        let dp = distance(p);
        match (ds >= 0.0, dp >= 0.0) {
            (true, true) => out.push(p.clone()),
            (true, false) => out.push(s.lerp(p, ds / (ds - dp))),
            (false, true) => {
                out.push(p.lerp(s, dp / (dp - ds)));
                out.push(p.clone());
            }
            (false, false) => {}
        }
        s = p;
        ds = dp;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::polygon::area;
    use glam::DVec3;

    fn square() -> Vec<DVec3> {
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 2.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ]
    }

    #[test]
    fn halving_a_square_halves_its_area() {
        let half = clip(&square(), |v| 1.0 - v.x);
        assert!((area(&half) - 2.0).abs() < 1e-12);
        assert!(half.iter().all(|v| v.x <= 1.0));
    }

    #[test]
    fn all_outside_gives_nothing_all_inside_gives_the_same() {
        assert!(clip(&square(), |v| v.x - 5.0).is_empty());
        assert_eq!(clip(&square(), |v| v.x + 5.0), square());
    }

    #[test]
    fn shared_edge_clips_to_identical_points_both_ways() {
        let a = DVec3::new(0.1, -3.0, 0.7);
        let b = DVec3::new(1.3, 2.0, -0.2);
        let plane = |v: &DVec3| v.y;
        let forward = clip(&[a, b, DVec3::new(5.0, 1.0, 0.0)], plane);
        let backward = clip(&[b, a, DVec3::new(-5.0, 1.0, 0.0)], plane);
        let on_plane = |poly: &[DVec3]| poly.iter().copied().find(|v| v.y == 0.0 && v.x < 1.3);
        assert_eq!(on_plane(&forward), on_plane(&backward));
    }
}
