//! Measures of planar polygons in 3D: Newell's normal, area, planarity, and their
//! triangulation by ear clipping.

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

/// Triangles covering a planar simple polygon (convex or concave), as index triples
/// into `vertices`, each counter-clockwise like the polygon: ear clipping (G. H.
/// Meisters, "Polygons have ears", Amer. Math. Monthly 82(6), 1975). An ear is a
/// convex corner whose triangle holds no other remaining vertex, even on its sides; cutting it off
/// leaves a simple polygon with one vertex fewer. O(n³) at worst, meant for the few
/// vertices of an emitter. Degenerate input (no ear found, from rounding) falls back
/// to cutting the most convex corner, so n − 2 triangles always come out.
pub fn triangulate(vertices: &[DVec3]) -> Vec<[usize; 3]> {
    let n = newell_normal(vertices);
    let mut remaining: Vec<usize> = (0..vertices.len()).collect();
    let mut triangles = Vec::with_capacity(vertices.len().saturating_sub(2));
    let turn = |a: usize, b: usize, c: usize| {
        (vertices[b] - vertices[a])
            .cross(vertices[c] - vertices[b])
            .dot(n)
    };
    while remaining.len() > 3 {
        let count = remaining.len();
        let corner = |k: usize| {
            (
                remaining[(k + count - 1) % count],
                remaining[k],
                remaining[(k + 1) % count],
            )
        };
        let is_ear = |k: usize| {
            let (a, b, c) = corner(k);
            turn(a, b, c) >= 0.0
                && remaining.iter().all(|&v| {
                    v == a
                        || v == b
                        || v == c
                        || !inside_or_on(vertices[v], [vertices[a], vertices[b], vertices[c]], n)
                })
        };
        let ear = (0..count).find(|&k| is_ear(k)).unwrap_or_else(|| {
            (0..count)
                .max_by(|&i, &j| {
                    let (a, b, c) = corner(i);
                    let (d, e, f) = corner(j);
                    turn(a, b, c).total_cmp(&turn(d, e, f))
                })
                .expect("more than three vertices remain")
        });
        let (a, b, c) = corner(ear);
        triangles.push([a, b, c]);
        remaining.remove(ear);
    }
    if remaining.len() == 3 {
        triangles.push([remaining[0], remaining[1], remaining[2]]);
    }
    triangles
}

/// Whether `p` lies inside the triangle `t` (counter-clockwise about `n`) or on its
/// sides, and is not one of its corners. A vertex on the side of a candidate ear
/// blocks it: the cut would pass through that vertex and split the rest of the
/// polygon into two pieces joined at a point.
fn inside_or_on(p: DVec3, t: [DVec3; 3], n: DVec3) -> bool {
    !t.contains(&p) && (0..3).all(|i| (t[(i + 1) % 3] - t[i]).cross(p - t[i]).dot(n) >= 0.0)
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

    #[test]
    fn ear_clipping_covers_a_concave_polygon() {
        // An L: six corners, one reflex; a fan from corner 0 would leave the polygon.
        let l = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ];
        for shift in 0..l.len() {
            let mut rotated = l.to_vec();
            rotated.rotate_left(shift);
            let triangles = triangulate(&rotated);
            assert_eq!(triangles.len(), 4);
            let mut total = 0.0;
            for t in &triangles {
                let corners = t.map(|k| rotated[k]);
                let signed = 0.5 * newell_normal(&corners).z;
                assert!(signed >= 0.0, "a clockwise triangle {t:?}");
                total += signed;
            }
            assert!((total - 3.0).abs() < 1e-12, "{total}");
        }
    }
}
