//! Property tests of the rasterizer's geometric core: fill rule, clipping, depth.

use crate::support;

use glam::DVec3;
use lumiere::geometry::polygon::area;
use lumiere::geometry::sutherland_hodgman::clip;
use lumiere::raster::covered_samples;
use proptest::prelude::*;
use support::{origin_view, screen_polygon};

const W: u32 = 80;
const H: u32 = 64;

/// A jittered n × n grid of vertices over [-2, 2]² at depth 5, each cell split along a
/// random diagonal: a triangle mesh whose outline is the grid's boundary. (Random
/// depths per vertex would let the projected mesh fold over itself; cells that the
/// jitter makes non-convex can fold too, and the test rejects those meshes.)
fn mesh() -> impl Strategy<Value = (usize, Vec<DVec3>, Vec<bool>)> {
    (2usize..7).prop_flat_map(|n| {
        let count = (n + 1) * (n + 1);
        (
            Just(n),
            prop::collection::vec((-0.3..0.3f64, -0.3..0.3f64), count),
            prop::collection::vec(any::<bool>(), n * n),
        )
            .prop_map(|(n, jitter, diagonals)| {
                let cell = 4.0 / n as f64;
                let points = jitter
                    .iter()
                    .enumerate()
                    .map(|(k, &(jx, jy))| {
                        let (i, j) = (k % (n + 1), k / (n + 1));
                        // Boundary vertices stay on the square's sides.
                        let jx = if i == 0 || i == n { 0.0 } else { jx * cell };
                        let jy = if j == 0 || j == n { 0.0 } else { jy * cell };
                        DVec3::new(
                            -2.0 + i as f64 * cell + jx,
                            -2.0 + j as f64 * cell + jy,
                            -5.0,
                        )
                    })
                    .collect();
                (n, points, diagonals)
            })
    })
}

fn coverage(points: &[Vec<DVec3>]) -> Vec<u32> {
    let view = origin_view(W, H);
    let mut count = vec![0u32; (W * H) as usize];
    for (k, p) in points.iter().enumerate() {
        let polygon = screen_polygon(&view, k as u32, p).expect("in view");
        for (x, y) in covered_samples(&polygon, W, H) {
            count[(y * W + x) as usize] += 1;
        }
    }
    count
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Triangles sharing edges cover every sample inside the mesh exactly once, and
    /// none outside it: the per-sample count of the triangles equals the coverage of
    /// the mesh's outline polygon.
    #[test]
    fn a_mesh_covers_each_sample_exactly_once((n, points, diagonals) in mesh()) {
        let at = |i: usize, j: usize| points[j * (n + 1) + i];
        let mut triangles = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                if diagonals[j * n + i] {
                    triangles.push(vec![a, b, c]);
                    triangles.push(vec![a, c, d]);
                } else {
                    triangles.push(vec![a, b, d]);
                    triangles.push(vec![b, c, d]);
                }
            }
        }
        // Jitter can make a cell non-convex, and the diagonal across its reflex
        // corner then folds one triangle over the other: such a mesh is no tiling.
        prop_assume!(triangles.iter().all(|t| (t[1] - t[0]).cross(t[2] - t[0]).z > 0.0));
        let mut outline: Vec<DVec3> = (0..n).map(|i| at(i, 0)).collect();
        outline.extend((0..n).map(|j| at(n, j)));
        outline.extend((0..n).map(|i| at(n - i, n)));
        outline.extend((0..n).map(|j| at(0, n - j)));
        let mesh = coverage(&triangles);
        let inside = coverage(&[outline]);
        prop_assert!(inside.contains(&1));
        if let Some(k) = (0..mesh.len()).find(|&k| mesh[k] != inside[k]) {
            prop_assert!(false, "sample ({}, {}) covered {} times, the outline {}", k as u32 % W, k as u32 / W, mesh[k], inside[k]);
        }
    }

    /// Sutherland–Hodgman against any plane: what is kept and what is cut off add up
    /// to the whole area, kept vertices are inside, and clipping again changes nothing.
    #[test]
    fn clipping_keeps_area(
        corners in prop::collection::vec(0.0..std::f64::consts::TAU, 3..9),
        radii in (0.5..3.0f64, 0.5..3.0f64),
        plane in ((-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64), -2.0..2.0f64),
    ) {
        // A convex polygon: points of an ellipse in order of angle, tilted in 3D.
        let mut angles = corners.clone();
        angles.sort_by(f64::total_cmp);
        angles.dedup();
        prop_assume!(angles.len() >= 3);
        let polygon: Vec<DVec3> = angles
            .iter()
            .map(|a| DVec3::new(radii.0 * a.cos(), radii.1 * a.sin(), 0.3 * a.cos() + 0.2 * a.sin()))
            .collect();
        let normal = DVec3::new(plane.0.0, plane.0.1, plane.0.2);
        prop_assume!(normal.length() > 0.1);
        let d = |v: &DVec3| v.dot(normal) - plane.1;
        let kept = clip(&polygon, d);
        let cut = clip(&polygon, |v| -d(v));
        let measure = |p: &[DVec3]| if p.len() < 3 { 0.0 } else { area(p) };
        prop_assert!((measure(&kept) + measure(&cut) - area(&polygon)).abs() < 1e-9 * area(&polygon));
        prop_assert!(kept.iter().all(|v| d(v) >= -1e-9));
        let again = clip(&kept, d);
        prop_assert!((measure(&again) - measure(&kept)).abs() < 1e-12 * area(&polygon).max(1.0));
    }

    /// Triangles crossing the near plane: every projected vertex lies on or beyond it,
    /// and the clipped triangle keeps exactly its area beyond the plane.
    #[test]
    fn near_plane_clipping_keeps_what_is_beyond(t in prop::collection::vec((-0.3..0.3f64, -0.3..0.3f64, -2.0..0.5f64), 3)) {
        let view = origin_view(W, H);
        let points: Vec<DVec3> = t.iter().map(|&(x, y, z)| DVec3::new(x * 0.01, y * 0.01, z)).collect();
        let beyond = |p: &DVec3| -p.z - view.near;
        let whole = area(&points);
        prop_assume!(whole > 1e-9);
        let kept = clip(&points, beyond);
        let cut = clip(&points, |p| -beyond(p));
        let measure = |p: &[DVec3]| if p.len() < 3 { 0.0 } else { area(p) };
        prop_assert!((measure(&kept) + measure(&cut) - whole).abs() < 1e-9 * whole);
        if let Some(polygon) = screen_polygon(&view, 0, &points) {
            for v in &polygon.vertices {
                prop_assert!(1.0 / v.zeta >= view.near * (1.0 - 1e-12));
            }
        }
    }

    /// The depth plane passes through every vertex exactly (ζ = 1/z at the vertex),
    /// and a polygon covers no sample outside its bounding box.
    #[test]
    fn depth_is_exact_at_vertices_and_coverage_stays_in_the_box(
        t in prop::collection::vec((-3.0..3.0f64, -3.0..3.0f64, -9.0..-2.0f64), 3)
    ) {
        let view = origin_view(W, H);
        let points: Vec<DVec3> = t.iter().map(|&(x, y, z)| DVec3::new(x, y, z)).collect();
        let Some(polygon) = screen_polygon(&view, 0, &points) else { return Ok(()); };
        for v in &polygon.vertices {
            let zeta = polygon.plane.zeta(v.x, v.y);
            prop_assert!((zeta - v.zeta).abs() <= 1e-9 * v.zeta, "{zeta} vs {}", v.zeta);
        }
        let (x0, x1) = polygon.vertices.iter().fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v.x), b.max(v.x)));
        let (y0, y1) = polygon.vertices.iter().fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v.y), b.max(v.y)));
        for (x, y) in covered_samples(&polygon, W, H) {
            let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
            prop_assert!(cx >= x0 - 1e-6 && cx <= x1 + 1e-6 && cy >= y0 && cy < y1);
        }
    }
}

mod bvh {
    use glam::DVec3;
    use lumiere::scene::ray_queries::SceneRays;
    use lumiere::scene::ray_queries::segment_meets_polygon;
    use lumiere::scene::{Polygon, Vertex};
    use proptest::prelude::*;

    fn point() -> impl Strategy<Value = DVec3> {
        (-5.0..5.0f64, -5.0..5.0f64, -5.0..5.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    fn polygon(corners: [DVec3; 3]) -> Option<Polygon> {
        let normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
        (normal.length() > 1e-6).then(|| Polygon {
            vertices: corners
                .iter()
                .map(|&position| Vertex {
                    position,
                    normal: normal.normalize(),
                    uv: Default::default(),
                })
                .collect(),
            normal: normal.normalize(),
            material: 0,
            object: 0,
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// The hierarchy changes the cost of a shadow query, never its answer.
        #[test]
        fn the_hierarchy_answers_like_testing_every_polygon(
            triangles in prop::collection::vec([point(), point(), point()], 1..60),
            segments in prop::collection::vec((point(), point()), 40),
        ) {
            let polygons: Vec<Polygon> = triangles.into_iter().filter_map(polygon).collect();
            let occluders = SceneRays::new(&polygons);
            for (a, b) in segments {
                let brute = polygons.iter().any(|p| segment_meets_polygon(a, b, p));
                prop_assert_eq!(occluders.any_hit(a, b, &[]), brute);
            }
        }
    }
}

mod weiler_atherton {
    use glam::DVec2;
    use lumiere::geometry::sutherland_hodgman;
    use lumiere::geometry::weiler_atherton::{Region, area, clip, contour_area};
    use proptest::prelude::*;

    /// A star-shaped (so simple, possibly concave) polygon: n spokes around a centre
    /// at evenly spaced angles jittered by less than half a step, so no angular gap
    /// reaches π (which could make the outline cross itself).
    fn star() -> impl Strategy<Value = Vec<DVec2>> {
        (
            (-1.0..1.0f64, -1.0..1.0f64),
            prop::collection::vec((0.0..0.45f64, 0.3..2.0f64), 3..10),
        )
            .prop_map(|((cx, cy), spokes)| {
                let step = std::f64::consts::TAU / spokes.len() as f64;
                spokes
                    .iter()
                    .enumerate()
                    .map(|(i, &(jitter, r))| {
                        let angle = (i as f64 + jitter) * step;
                        DVec2::new(cx + r * angle.cos(), cy + r * angle.sin())
                    })
                    .collect()
            })
    }

    fn convex() -> impl Strategy<Value = Vec<DVec2>> {
        star()
            .prop_map(|p| hull(&p))
            .prop_filter("a polygon", |p| p.len() >= 3)
    }

    /// Convex hull (monotone chain), counter-clockwise.
    fn hull(points: &[DVec2]) -> Vec<DVec2> {
        let mut p = points.to_vec();
        p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        let chain = |points: &mut dyn Iterator<Item = DVec2>| {
            let mut h: Vec<DVec2> = Vec::new();
            for q in points {
                while h.len() >= 2
                    && (h[h.len() - 1] - h[h.len() - 2]).perp_dot(q - h[h.len() - 2]) <= 0.0
                {
                    h.pop();
                }
                h.push(q);
            }
            h.pop();
            h
        };
        let mut lower = chain(&mut p.iter().copied());
        lower.extend(chain(&mut p.iter().rev().copied()));
        lower
    }

    /// No two edges of a contour cross, except neighbours at their shared vertex.
    fn simple(contour: &[DVec2]) -> bool {
        let n = contour.len();
        for i in 0..n {
            for j in i + 2..n {
                if i == 0 && j == n - 1 {
                    continue;
                }
                let (p0, p1) = (contour[i], contour[(i + 1) % n]);
                let (q0, q1) = (contour[j], contour[(j + 1) % n]);
                let (r, s) = (p1 - p0, q1 - q0);
                let d = r.perp_dot(s);
                if d != 0.0 {
                    let t = (q0 - p0).perp_dot(s) / d;
                    let u = (q0 - p0).perp_dot(r) / d;
                    if t > 1e-9 && t < 1.0 - 1e-9 && u > 1e-9 && u < 1.0 - 1e-9 {
                        return false;
                    }
                }
            }
        }
        true
    }

    fn check_identity(a: &Region, b: &Region) -> Result<(Region, Region), TestCaseError> {
        let (inside, outside) = clip(a, b);
        let whole = area(a);
        prop_assert!(
            (area(&inside) + area(&outside) - whole).abs() <= 1e-8 * whole.abs().max(1.0),
            "{} + {} != {}",
            area(&inside),
            area(&outside),
            whole
        );
        prop_assert!(area(&inside) >= -1e-9 && area(&outside) >= -1e-9);
        Ok((inside, outside))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        /// area(A ∩ B) + area(A − B) = area(A), and every result contour is simple.
        #[test]
        fn inside_and_outside_add_up(a in star(), b in star()) {
            let (inside, outside) = check_identity(&vec![a], &vec![b])?;
            for c in inside.iter().chain(&outside) {
                prop_assert!(simple(c), "a result contour crosses itself");
            }
        }

        /// With a convex clip polygon, A ∩ B equals Sutherland–Hodgman's result
        /// (an independent method) up to the perturbation.
        #[test]
        fn agrees_with_sutherland_hodgman_on_convex_clips(a in star(), b in convex()) {
            let (inside, _) = clip(&vec![a.clone()], &vec![b.clone()]);
            let mut reference = a.clone();
            for i in 0..b.len() {
                let (p, q) = (b[i], b[(i + 1) % b.len()]);
                reference = sutherland_hodgman::clip(&reference, |v: &DVec2| (q - p).perp_dot(*v - p));
            }
            let expected = if reference.len() >= 3 { contour_area(&reference) } else { 0.0 };
            prop_assert!((area(&inside) - expected).abs() <= 1e-6, "{} vs {}", area(&inside), expected);
        }

        /// A region with a hole: the identity holds and the hole stays out of A ∩ B.
        #[test]
        fn regions_with_holes(b in star()) {
            let square = |h: f64| vec![DVec2::new(-h, -h), DVec2::new(h, -h), DVec2::new(h, h), DVec2::new(-h, h)];
            let mut hole = square(0.5);
            hole.reverse();
            let a: Region = vec![square(1.5), hole];
            check_identity(&a, &vec![b])?;
        }
    }

    fn square(x: f64, y: f64, side: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(x, y),
            DVec2::new(x + side, y),
            DVec2::new(x + side, y + side),
            DVec2::new(x, y + side),
        ]
    }

    /// Shared edges, collinear overlapping edges, a vertex on an edge, coincident
    /// polygons, a clip inside the subject: no panic, and the areas add up.
    #[test]
    fn degenerate_cases_keep_the_identity() {
        let a = square(0.0, 0.0, 2.0);
        let cases = [
            ("shared edge", square(2.0, 0.0, 2.0)),
            ("collinear overlap", square(1.0, 2.0, 2.0)),
            (
                "vertex on an edge",
                vec![
                    DVec2::new(1.0, 2.0),
                    DVec2::new(2.0, 3.0),
                    DVec2::new(0.0, 3.0),
                ],
            ),
            ("coincident", square(0.0, 0.0, 2.0)),
            ("inside", square(0.5, 0.5, 1.0)),
            ("containing", square(-1.0, -1.0, 4.0)),
            ("disjoint", square(5.0, 5.0, 1.0)),
        ];
        for (name, b) in cases {
            let (inside, outside) = clip(&vec![a.clone()], &vec![b.clone()]);
            let sum = area(&inside) + area(&outside);
            assert!(
                (sum - 4.0).abs() < 1e-8,
                "{name}: {} + {}",
                area(&inside),
                area(&outside)
            );
        }
        let (inside, outside) = clip(&vec![a.clone()], &vec![square(0.5, 0.5, 1.0)]);
        assert!((area(&inside) - 1.0).abs() < 1e-8 && (area(&outside) - 3.0).abs() < 1e-8);
        let (inside, _) = clip(&vec![a.clone()], &vec![a.clone()]);
        assert!((area(&inside) - 4.0).abs() < 1e-8);
    }
}
