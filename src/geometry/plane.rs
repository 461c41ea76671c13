//! Work in a plane: a frame with two axes in it, to turn points of a 3D plane into
//! 2D coordinates and back, and the bounding box of 2D points.

use glam::{DVec2, DVec3};

/// A plane with two unit axes in it (u × v = normal), for 2D work on it.
#[derive(Clone, Copy, Debug)]
pub struct PlaneFrame {
    /// The point at (0, 0).
    pub origin: DVec3,
    /// The plane's unit normal.
    pub normal: DVec3,
    /// The first axis.
    pub u: DVec3,
    /// The second axis, normal × u.
    pub v: DVec3,
}

impl PlaneFrame {
    /// The plane through `origin` with unit `normal`; its axes are glam's
    /// `any_orthonormal_pair` of the normal (any pair would do: the 2D work done in
    /// the frame does not depend on the choice).
    pub fn new(origin: DVec3, normal: DVec3) -> PlaneFrame {
        let (u, _) = normal.any_orthonormal_pair();
        PlaneFrame {
            origin,
            normal,
            u,
            v: normal.cross(u),
        }
    }

    /// The coordinates of `p` (projected onto the plane along the normal).
    pub fn coords(&self, p: DVec3) -> DVec2 {
        let d = p - self.origin;
        DVec2::new(d.dot(self.u), d.dot(self.v))
    }

    /// The point of the plane at coordinates `q`.
    pub fn point(&self, q: DVec2) -> DVec3 {
        self.origin + self.u * q.x + self.v * q.y
    }
}

/// The smallest and largest coordinates of `points` (infinite bounds, inside out,
/// for none).
pub fn bounds<'a>(points: impl IntoIterator<Item = &'a DVec2>) -> (DVec2, DVec2) {
    points.into_iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), q| (lo.min(*q), hi.max(*q)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_of_the_plane_goes_to_its_coordinates_and_back() {
        let normal = DVec3::new(1.0, -2.0, 0.5).normalize();
        let frame = PlaneFrame::new(DVec3::new(0.3, 1.0, -2.0), normal);
        assert!((frame.u.cross(frame.v) - normal).length() < 1e-12);
        assert!(frame.u.dot(normal).abs() < 1e-12 && (frame.u.length() - 1.0).abs() < 1e-12);
        let q = DVec2::new(-0.7, 2.5);
        let p = frame.point(q);
        assert!((frame.coords(p) - q).length() < 1e-12);
        // A point off the plane keeps the coordinates of its foot.
        assert!((frame.coords(p + 3.0 * normal) - q).length() < 1e-12);
    }

    #[test]
    fn bounds_enclose_every_point_and_touch_the_extremes() {
        let points = [
            DVec2::new(1.0, -1.0),
            DVec2::new(-2.0, 0.5),
            DVec2::new(0.0, 3.0),
        ];
        assert_eq!(
            bounds(&points),
            (DVec2::new(-2.0, -1.0), DVec2::new(1.0, 3.0))
        );
        let (lo, hi) = bounds(&[]);
        assert!(lo.x > hi.x, "no points: an empty box");
    }
}
