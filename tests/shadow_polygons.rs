//! Atherton, Weiler & Greenberg's shadow polygons against ray casting, point by point
//! on every polygon, in the cases Weiler & Atherton's hidden-surface recursion exists
//! for: a preliminary depth sort that is wrong, interpenetrating polygons and cyclic
//! overlap; and on random triangles, interpenetrating or not.

mod common;

use common::scene_from_text;
use glam::{DVec2, DVec3};
use lumiere::Scene;
use lumiere::internals::scene::ray_queries::segment_meets_polygon;
use lumiere::internals::shadow::shadow_polygon_areas::receiver_shadows;
use lumiere::internals::shadow::shadow_polygons::{DetailPolygon, lit_polygons};
use proptest::prelude::*;

/// A scene of the given polygons, each its own object, and one point light.
fn scene_of(polygons: &[Vec<DVec3>], light: DVec3) -> Scene {
    let mut text = format!(
        "[camera]\neye = [0.0, 20.0, 0.5]\nlook_at = [0.0, 0.0, 0.0]\nfov_y = 40.0\nwidth = 16\nheight = 16\n\
         [materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\
         [[lights]]\ntype = \"point\"\nposition = [{}, {}, {}]\nintensity = [1.0, 1.0, 1.0]\n",
        light.x, light.y, light.z
    );
    for (i, p) in polygons.iter().enumerate() {
        let vertices: Vec<String> = p
            .iter()
            .map(|v| format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z))
            .collect();
        text += &format!(
            "[[objects]]\nshape = \"polygon\"\nname = \"p{i}\"\nmaterial = \"grey\"\nvertices = [{}]\n",
            vertices.join(", ")
        );
    }
    scene_from_text(&text, &[])
}

/// Whether `p`, on the plane of polygon `normal`, lies inside the detail polygons
/// (even-odd over all their contours, seen along the normal's largest axis).
fn inside_details(details: &[DetailPolygon], normal: DVec3, p: DVec3) -> bool {
    let a = normal.abs();
    let flat = |q: DVec3| {
        if a.x >= a.y && a.x >= a.z {
            DVec2::new(q.y, q.z)
        } else if a.y >= a.z {
            DVec2::new(q.z, q.x)
        } else {
            DVec2::new(q.x, q.y)
        }
    };
    let q = flat(p);
    let mut inside = false;
    for (contour, _) in details.iter().flat_map(|d| &d.contours) {
        for (i, a) in contour.iter().enumerate() {
            let (a, b) = (flat(*a), flat(contour[(i + 1) % contour.len()]));
            if (a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y) {
                inside = !inside;
            }
        }
    }
    inside
}

/// Points on a grid over each polygon's fan triangles (offsets that fall on no
/// outline), as (polygon, point).
fn grid(scene: &Scene, n: usize) -> Vec<(usize, DVec3)> {
    let mut points = Vec::new();
    for (id, polygon) in scene.polygons.iter().enumerate() {
        let v: Vec<DVec3> = polygon.positions().collect();
        for k in 1..v.len() - 1 {
            let (a, b, c) = (v[0], v[k], v[k + 1]);
            for i in 0..n {
                for j in 0..n {
                    let (s, t) = ((i as f64 + 0.373) / n as f64, (j as f64 + 0.619) / n as f64);
                    if s + t < 1.0 {
                        points.push((id, a + s * (b - a) + t * (c - a)));
                    }
                }
            }
        }
    }
    points
}

/// The grid points whose polygon the shadow polygons call lit where ray casting
/// finds another polygon on the way to the light, or the other way round.
fn disagreements(scene: &Scene, light: DVec3, n: usize) -> (usize, Vec<(usize, DVec3)>) {
    let lit = lit_polygons(scene, light);
    let points = grid(scene, n);
    let wrong = points
        .iter()
        .filter(|&&(id, p)| {
            let by_details = inside_details(&lit[id], scene.polygons[id].normal, p);
            let by_rays = !scene
                .polygons
                .iter()
                .enumerate()
                .any(|(other, q)| other != id && segment_meets_polygon(p, light, q));
            by_details != by_rays
        })
        .copied()
        .collect();
    (points.len(), wrong)
}

fn assert_agree(polygons: &[Vec<DVec3>], light: DVec3) -> Scene {
    let scene = scene_of(polygons, light);
    let (checked, wrong) = disagreements(&scene, light, 40);
    assert!(checked > 1000);
    assert!(
        wrong.is_empty(),
        "{} of {checked} points disagree with ray casting, first {:?}",
        wrong.len(),
        &wrong[..wrong.len().min(4)]
    );
    scene
}

fn quad(corners: [[f64; 3]; 4]) -> Vec<DVec3> {
    corners.iter().map(|&c| DVec3::from_array(c)).collect()
}

/// A large tilted quad reaches nearer the light (at 0.5) than a small quad above
/// its middle (at 2), so the preliminary sort puts it first although the small one
/// hides part of it: the small quad's piece becomes the clip polygon of a window
/// within the large quad's.
#[test]
fn a_wrong_preliminary_sort_is_corrected_by_the_recursion() {
    let light = DVec3::new(0.0, 5.0, 0.0);
    let tilted = |x: f64, z: f64| [x, 2.25 + 0.375 * (x + z), z];
    let big = quad([
        tilted(-3.0, -3.0),
        tilted(-3.0, 3.0),
        tilted(3.0, 3.0),
        tilted(3.0, -3.0),
    ]);
    let small = quad([
        [-1.0, 3.0, -1.0],
        [-1.0, 3.0, 0.0],
        [0.0, 3.0, 0.0],
        [0.0, 3.0, -1.0],
    ]);
    let scene = assert_agree(&[big, small], light);
    // The small quad is wholly lit; the big one loses the small one's shadow.
    let receivers = receiver_shadows(&scene, light);
    assert!((receivers[1].lit_area - 1.0).abs() < 1e-9);
    assert!(receivers[0].shadowed_area > 1.0);
}

/// Two quads crossing along x = 0, a plane through the light: each is lit on its
/// upper half and nowhere else, 2·√1.04 of its area, as the two halves of the
/// light's view are separated by that plane.
#[test]
fn interpenetrating_quads_are_split_where_their_depths_cross() {
    let light = DVec3::new(0.0, 10.0, 0.0);
    let rising = quad([
        [-1.0, 0.8, -1.0],
        [-1.0, 0.8, 1.0],
        [1.0, 1.2, 1.0],
        [1.0, 1.2, -1.0],
    ]);
    let falling = quad([
        [-1.0, 1.2, -1.0],
        [-1.0, 1.2, 1.0],
        [1.0, 0.8, 1.0],
        [1.0, 0.8, -1.0],
    ]);
    let scene = assert_agree(&[rising, falling], light);
    let half = 2.0 * 1.04f64.sqrt();
    for r in receiver_shadows(&scene, light) {
        assert!(
            (r.lit_area - half).abs() < 1e-6 * half,
            "{}: lit {} (expected {half})",
            r.object,
            r.lit_area
        );
    }
}

/// Three sticks, each lying over the next and under the one before (no two of
/// them interpenetrate): no depth order of the three exists, and no list sorted
/// once could be drawn in order; the windows within windows resolve each overlap
/// in its own window.
#[test]
fn cyclic_overlap_of_three_sticks() {
    let light = DVec3::new(0.1, 30.0, 0.2);
    let stick = |angle: f64| {
        // A stick along direction `angle`, rising from y = 1 to y = 2 along its
        // length, its centre line passing at 0.8 from the origin.
        let (d, n) = (
            DVec3::new(angle.cos(), 0.0, angle.sin()),
            DVec3::new(-angle.sin(), 0.0, angle.cos()),
        );
        let (c, w) = (n * 0.8, 0.25);
        let at = |s: f64, t: f64| {
            let p = c + d * s + n * t;
            p + DVec3::Y * (1.5 + 0.5 * s / 2.5)
        };
        vec![at(-2.5, -w), at(-2.5, w), at(2.5, w), at(2.5, -w)]
    };
    let sticks: Vec<Vec<DVec3>> = (0..3)
        .map(|k| stick(k as f64 * std::f64::consts::TAU / 3.0))
        .collect();
    let ground = quad([
        [-6.0, 0.0, -6.0],
        [-6.0, 0.0, 6.0],
        [6.0, 0.0, 6.0],
        [6.0, 0.0, -6.0],
    ]);
    let mut all = sticks;
    all.push(ground);
    let scene = assert_agree(&all, light);
    // Each stick is shadowed somewhere by the one above it: a cycle.
    let receivers = receiver_shadows(&scene, light);
    for r in &receivers[..3] {
        assert!(r.shadowed_area > 0.01, "{}: {}", r.object, r.shadowed_area);
    }
}

fn triangle() -> impl Strategy<Value = Vec<DVec3>> {
    prop::collection::vec((-2.0..2.0f64, 0.2..3.0f64, -2.0..2.0f64), 3).prop_filter_map(
        "a triangle with area",
        |v| {
            let p: Vec<DVec3> = v.iter().map(|&(x, y, z)| DVec3::new(x, y, z)).collect();
            ((p[1] - p[0]).cross(p[2] - p[0]).length() > 0.05).then_some(p)
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// Random triangles over a ground, free to interpenetrate, under a light inside
    /// their box or above it: the shadow polygons agree with ray casting at every
    /// grid point.
    #[test]
    fn random_triangles_agree_with_ray_casting(
        triangles in prop::collection::vec(triangle(), 2..7),
        light in (-1.0..1.0f64, 2.0..6.0f64, -1.0..1.0f64),
    ) {
        let light = DVec3::new(light.0, light.1, light.2);
        let mut polygons = triangles;
        polygons.push(quad([
            [-4.0, 0.0, -4.0],
            [-4.0, 0.0, 4.0],
            [4.0, 0.0, 4.0],
            [4.0, 0.0, -4.0],
        ]));
        let scene = scene_of(&polygons, light);
        let (checked, wrong) = disagreements(&scene, light, 24);
        prop_assert!(
            wrong.is_empty(),
            "{} of {checked} points disagree, first {:?}",
            wrong.len(),
            &wrong[..wrong.len().min(4)]
        );
    }
}
