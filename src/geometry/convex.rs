//! Convex polygons in a plane: the convex hull of points (A. M. Andrew, "Another
//! efficient algorithm for convex hulls in two dimensions", Information Processing
//! Letters 9(5), 1979: the monotone chain) and the intersection of two convex
//! polygons (Sutherland–Hodgman against each edge of the clip polygon in turn), and
//! a convex polygon less convex holes, as convex pieces. All keep polygons
//! counter-clockwise.

use super::plane::bounds;
use super::sutherland_hodgman::clip;
use super::weiler_atherton::contour_area;
use glam::DVec2;

/// The convex hull of `points`, counter-clockwise, without collinear points; fewer
/// than three points when they are all on a line.
pub fn hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut sorted: Vec<DVec2> = points.iter().copied().filter(|p| p.is_finite()).collect();
    sorted.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    sorted.dedup();
    if sorted.len() < 3 {
        return sorted;
    }
    let turn = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut chain: Vec<DVec2> = Vec::with_capacity(2 * sorted.len());
    for pass in 0..2 {
        let start = chain.len();
        let points: Box<dyn Iterator<Item = &DVec2>> = if pass == 0 {
            Box::new(sorted.iter())
        } else {
            Box::new(sorted.iter().rev())
        };
        for &p in points {
            while chain.len() >= start + 2
                && turn(chain[chain.len() - 2], chain[chain.len() - 1], p) <= 0.0
            {
                chain.pop();
            }
            chain.push(p);
        }
        chain.pop(); // the last point starts the other chain
    }
    // Nearly collinear points can round to a left turn in both chains, which then
    // both keep the middle one: keep it once.
    let mut once: Vec<DVec2> = Vec::with_capacity(chain.len());
    for p in chain {
        if !once.contains(&p) {
            once.push(p);
        }
    }
    once
}

/// `subject ∩ window` for a convex, counter-clockwise `window` (the subject may be
/// any polygon); empty when they do not overlap.
pub fn intersect(subject: &[DVec2], window: &[DVec2]) -> Vec<DVec2> {
    let mut out = subject.to_vec();
    for (i, &a) in window.iter().enumerate() {
        let b = window[(i + 1) % window.len()];
        let edge = b - a;
        out = clip(&out, |p| edge.perp_dot(*p - a));
        if out.len() < 3 {
            return Vec::new();
        }
    }
    if contour_area(&out) > 0.0 {
        out
    } else {
        Vec::new()
    }
}

/// Whether a polygon is convex and counter-clockwise (collinear corners allowed).
pub fn is_convex_ccw(polygon: &[DVec2]) -> bool {
    let n = polygon.len();
    n >= 3
        && (0..n).all(|i| {
            let (a, b, c) = (polygon[i], polygon[(i + 1) % n], polygon[(i + 2) % n]);
            (b - a).perp_dot(c - b) >= 0.0
        })
}

/// A convex polygon less convex holes, as disjoint convex polygons: each hole is
/// taken from every piece it overlaps by cutting the piece along the hole's edges in
/// turn (the part outside the first edge's line, then of the rest the part outside
/// the second's, …), each cut a Sutherland–Hodgman clip. Exact like Weiler–Atherton
/// subtraction, and without its topology: holes sharing edges (a mesh's faces seen
/// from one point) need no perturbation.
pub fn subtract(piece: &[DVec2], holes: &[Vec<DVec2>]) -> Vec<Vec<DVec2>> {
    let mut pieces = vec![piece.to_vec()];
    for hole in holes {
        let (lo, hi) = bounds(hole);
        let mut next = Vec::with_capacity(pieces.len());
        for p in pieces {
            let (plo, phi) = bounds(&p);
            if plo.x >= hi.x || plo.y >= hi.y || phi.x <= lo.x || phi.y <= lo.y {
                next.push(p);
                continue;
            }
            let mut rest = p;
            for (i, &a) in hole.iter().enumerate() {
                let edge = hole[(i + 1) % hole.len()] - a;
                if edge == DVec2::ZERO {
                    continue; // a repeated corner (clipping leaves them): no side to cut
                }
                let outside = clip(&rest, |q| -edge.perp_dot(*q - a));
                if outside.len() >= 3 && contour_area(&outside) > 0.0 {
                    next.push(outside);
                }
                rest = clip(&rest, |q| edge.perp_dot(*q - a));
                if rest.len() < 3 {
                    break;
                }
            }
        }
        pieces = next;
        if pieces.is_empty() {
            break;
        }
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x0: f64, y0: f64, size: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(x0, y0),
            DVec2::new(x0 + size, y0),
            DVec2::new(x0 + size, y0 + size),
            DVec2::new(x0, y0 + size),
        ]
    }

    #[test]
    fn hull_of_a_square_and_inner_points() {
        let mut points = square(0.0, 0.0, 2.0);
        points.extend([
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.5, 1.5),
        ]);
        let h = hull(&points);
        assert_eq!(h.len(), 4);
        assert!((contour_area(&h) - 4.0).abs() < 1e-12);
        assert!(is_convex_ccw(&h));
    }

    #[test]
    fn overlapping_squares_meet_in_a_square() {
        let i = intersect(&square(0.0, 0.0, 2.0), &square(1.0, 1.0, 2.0));
        assert!((contour_area(&i) - 1.0).abs() < 1e-12);
        assert!(intersect(&square(0.0, 0.0, 1.0), &square(2.0, 2.0, 1.0)).is_empty());
    }
}
