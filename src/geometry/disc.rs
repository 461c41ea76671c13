//! The area of a polygon inside a disc, exactly: the polygon is a sum of signed
//! triangles (centre, a, b) over its edges, and each triangle's part inside the disc
//! is a triangle where its edge runs inside the circle and a circular sector where
//! it runs outside, the edge cut where it crosses the circle.

use glam::DVec2;

/// Signed area of polygon ∩ disc (centre `centre`, radius `radius`): positive for a
/// counter-clockwise polygon.
pub fn area_inside(polygon: &[DVec2], centre: DVec2, radius: f64) -> f64 {
    let r2 = radius * radius;
    let mut sum = 0.0;
    for (i, &a) in polygon.iter().enumerate() {
        let (a, b) = (a - centre, polygon[(i + 1) % polygon.len()] - centre);
        let d = b - a;
        let (qa, qb, qc) = (d.dot(d), a.dot(d), a.dot(a) - r2);
        let mut cuts = [0.0, 1.0, 1.0, 1.0];
        let mut count = 1;
        let discriminant = qb * qb - qa * qc;
        if qa > 0.0 && discriminant > 0.0 {
            let root = discriminant.sqrt();
            for t in [(-qb - root) / qa, (-qb + root) / qa] {
                if t > 0.0 && t < 1.0 {
                    cuts[count] = t;
                    count += 1;
                }
            }
        }
        cuts[count] = 1.0;
        for w in cuts[..=count].windows(2) {
            let (p, q) = (a + d * w[0], a + d * w[1]);
            let mid = a + d * (0.5 * (w[0] + w[1]));
            sum += if mid.length_squared() <= r2 {
                0.5 * p.perp_dot(q)
            } else {
                0.5 * r2 * p.perp_dot(q).atan2(p.dot(q))
            };
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn square(half: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(-half, -half),
            DVec2::new(half, -half),
            DVec2::new(half, half),
            DVec2::new(-half, half),
        ]
    }

    #[test]
    fn inside_outside_and_half() {
        // A small square inside: its area; a large one around: the disc's.
        assert!((area_inside(&square(0.5), DVec2::ZERO, 1.0) - 1.0).abs() < 1e-12);
        assert!((area_inside(&square(5.0), DVec2::ZERO, 1.0) - PI).abs() < 1e-12);
        // The half-plane x > 0 as a big rectangle: half the disc.
        let right = [
            DVec2::new(0.0, -5.0),
            DVec2::new(5.0, -5.0),
            DVec2::new(5.0, 5.0),
            DVec2::new(0.0, 5.0),
        ];
        assert!((area_inside(&right, DVec2::ZERO, 1.0) - PI / 2.0).abs() < 1e-12);
        // Far away: nothing; clockwise: negative.
        assert!(area_inside(&square(0.5), DVec2::new(9.0, 0.0), 1.0).abs() < 1e-12);
        let mut cw = square(0.5);
        cw.reverse();
        assert!((area_inside(&cw, DVec2::ZERO, 1.0) + 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_chord_cuts_a_circular_segment() {
        // Everything beyond x = a: the segment r² acos(a/r) − a √(r² − a²).
        let (r, a) = (2.0, 0.7);
        let beyond = [
            DVec2::new(a, -9.0),
            DVec2::new(9.0, -9.0),
            DVec2::new(9.0, 9.0),
            DVec2::new(a, 9.0),
        ];
        let segment = r * r * (a / r).acos() - a * (r * r - a * a).sqrt();
        assert!((area_inside(&beyond, DVec2::new(0.0, 0.0), r) - segment).abs() < 1e-12);
    }
}
