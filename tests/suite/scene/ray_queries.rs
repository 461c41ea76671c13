//! Ray queries on the scene: the hierarchy answers like a loop over every polygon,
//! and an eye ray through a sample centre sees what the scan-line pass saw there.

use crate::support;

use glam::{DVec2, DVec3};
use lumiere::load_scene;
use lumiere::raster::screen_polygons;
use lumiere::raster::{ScreenPolygon, View};
use lumiere::render::visible_surface;
use lumiere::scene::ray_queries::{SceneRays, ray_meets_polygon, segment_meets_polygon};
use lumiere::scene::{Polygon, Vertex};
use lumiere::texture::Interpolation;
use proptest::prelude::*;
use support::vertex;

fn point() -> impl Strategy<Value = DVec3> {
    (-5.0..5.0f64, -5.0..5.0f64, -5.0..5.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn unit() -> impl Strategy<Value = DVec3> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
        .prop_filter("not too short", |(x, y, z)| x * x + y * y + z * z > 1e-2)
        .prop_map(|(x, y, z)| DVec3::new(x, y, z).normalize())
}

/// Texture coordinates that are an affine function of the position, so the value
/// at any point of any planar polygon is known without interpolating.
fn affine_uv(p: DVec3) -> DVec2 {
    DVec2::new(
        0.3 * p.x - 0.7 * p.y + 0.2 * p.z + 1.0,
        0.5 * p.z + 0.1 * p.x - 2.0,
    )
}

/// A triangle (`fourth` = None) or a planar convex quad (a trapezoid: the fourth
/// corner on the parallel to a→b through c), with random shading normals.
fn polygon(corners: [DVec3; 3], fourth: Option<f64>, normals: [DVec3; 4]) -> Option<Polygon> {
    let normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
    if normal.length() < 1e-6 {
        return None;
    }
    let mut positions = corners.to_vec();
    if let Some(s) = fourth {
        positions.push(corners[2] + (corners[0] - corners[1]) * s);
    }
    Some(Polygon {
        vertices: positions
            .iter()
            .zip(normals)
            .map(|(&position, n)| Vertex {
                position,
                normal: n,
                uv: affine_uv(position),
            })
            .collect(),
        normal: normal.normalize(),
        material: 0,
        object: 0,
    })
}

fn polygons() -> impl Strategy<Value = Vec<Polygon>> {
    prop::collection::vec(
        (
            [point(), point(), point()],
            prop::option::of(0.2..1.8f64),
            [unit(), unit(), unit(), unit()],
        ),
        1..60,
    )
    .prop_map(|v| {
        v.into_iter()
            .filter_map(|(c, f, n)| polygon(c, f, n))
            .collect()
    })
}

/// The nearest polygon met in [t_min, t_max] by testing every one; ties to the
/// smaller id.
fn brute_closest(
    polygons: &[Polygon],
    origin: DVec3,
    direction: DVec3,
    (t_min, t_max): (f64, f64),
    skip: &[u32],
) -> Option<(u32, f64)> {
    let mut best: Option<(u32, f64)> = None;
    for (i, p) in polygons.iter().enumerate() {
        if skip.contains(&(i as u32)) {
            continue;
        }
        if let Some(t) = ray_meets_polygon(origin, direction, p)
            && (t_min..=t_max).contains(&t)
            && best.is_none_or(|b| t < b.1)
        {
            best = Some((i as u32, t));
        }
    }
    best
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// The hierarchy changes the cost of a closest-hit query, never its answer; the
    /// attributes at the hit are the interpolation of the polygon's vertices.
    #[test]
    fn closest_hit_equals_testing_every_polygon(
        polygons in polygons(),
        rays in prop::collection::vec(
            (point(), unit(), prop::option::of(0.0..4.0f64), prop::option::of(1.0..12.0f64)),
            40,
        ),
        skip in prop::collection::vec(0u32..60, 0..4),
    ) {
        let scene = SceneRays::new(&polygons);
        for (k, (origin, direction, t_min, t_max)) in rays.into_iter().enumerate() {
            // Directions of varied length: t is in the direction's units.
            let direction = direction * (0.5 + (k % 4) as f64);
            let range = (t_min.unwrap_or(0.0), t_max.unwrap_or(f64::INFINITY));
            let skip = if k % 2 == 0 { &skip[..] } else { &[] };
            let brute = brute_closest(&polygons, origin, direction, range, skip);
            let hit = scene.closest_hit(origin, direction, range.0, range.1, skip);
            prop_assert_eq!(hit.map(|h| h.polygon), brute.map(|b| b.0));
            let (Some(hit), Some((_, t))) = (hit, brute) else { continue };
            prop_assert!((hit.t - t).abs() <= 1e-9 * t.abs().max(1e-300));
            prop_assert!((hit.position - (origin + direction * t)).length() <= 1e-9 * hit.position.length().max(1.0));
            let p = &polygons[hit.polygon as usize];
            prop_assert_eq!(hit.geometric_normal, p.normal);
            prop_assert!((hit.normal.length() - 1.0).abs() < 1e-12);
            let uv = affine_uv(hit.position);
            prop_assert!((hit.uv - uv).length() < 1e-9 * uv.length().max(1.0), "{:?} vs {:?}", hit.uv, uv);
        }
    }

    /// `any_hit` is the shadow test: any polygon not skipped on the open segment.
    #[test]
    fn any_hit_equals_testing_every_polygon(
        polygons in polygons(),
        segments in prop::collection::vec((point(), point()), 40),
        skip in prop::collection::vec(0u32..60, 0..4),
    ) {
        let scene = SceneRays::new(&polygons);
        for (k, (a, b)) in segments.into_iter().enumerate() {
            let skip = if k % 2 == 0 { &skip[..] } else { &[] };
            let brute = polygons
                .iter()
                .enumerate()
                .any(|(i, p)| !skip.contains(&(i as u32)) && segment_meets_polygon(a, b, p));
            prop_assert_eq!(scene.any_hit(a, b, skip), brute);
        }
    }
}

/// An owned hierarchy can be kept between frames and shared between threads.
#[test]
fn owned_scene_rays_are_send_and_sync() {
    fn shareable<T: Send + Sync + 'static>(_: &T) {}
    let polygon = Polygon {
        vertices: [DVec3::ZERO, DVec3::X, DVec3::Y]
            .into_iter()
            .map(vertex)
            .collect(),
        normal: DVec3::Z,
        material: 0,
        object: 0,
    };
    let rays = SceneRays::owned(vec![polygon]);
    shareable(&rays);
    let hit = rays
        .closest_hit(
            DVec3::new(0.2, 0.2, 1.0),
            DVec3::NEG_Z,
            0.0,
            f64::INFINITY,
            &[],
        )
        .unwrap();
    assert_eq!((hit.polygon, hit.t), (0, 1.0));
    assert!(rays.any_hit(DVec3::new(0.2, 0.2, 1.0), DVec3::new(0.2, 0.2, -1.0), &[]));
    assert!(!rays.any_hit(DVec3::new(0.2, 0.2, 1.0), DVec3::new(0.2, 0.2, -1.0), &[0]));
}

/// Distance in samples from (x, y) to the nearest edge of `p`'s screen image.
fn distance_to_edges(p: &ScreenPolygon, x: f64, y: f64) -> f64 {
    let n = p.vertices.len();
    (0..n)
        .map(|i| {
            let (a, b) = (&p.vertices[i], &p.vertices[(i + 1) % n]);
            let (dx, dy) = (b.x - a.x, b.y - a.y);
            let t = (((x - a.x) * dx + (y - a.y) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
            ((a.x + t * dx - x).powi(2) + (a.y + t * dy - y).powi(2)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Whether the polygon's normals, and its texture coordinates, are affine over its
/// plane: each vertex's is what the first fan triangle's barycentric coordinates give.
fn affine_attributes(p: &Polygon) -> (bool, bool) {
    let v = &p.vertices;
    let (a, b, c) = (v[0].position, v[1].position, v[2].position);
    let area = (b - a).cross(c - a).dot(p.normal);
    let weights = |q: DVec3| {
        [
            (c - b).cross(q - b).dot(p.normal) / area,
            (a - c).cross(q - c).dot(p.normal) / area,
            (b - a).cross(q - a).dot(p.normal) / area,
        ]
    };
    let normals = v.iter().all(|q| {
        let w = weights(q.position);
        let n = v[0].normal * w[0] + v[1].normal * w[1] + v[2].normal * w[2];
        (n - q.normal).length() < 1e-9
    });
    let uvs = v.iter().all(|q| {
        let w = weights(q.position);
        let uv = v[0].uv * w[0] + v[1].uv * w[1] + v[2].uv * w[2];
        (uv - q.uv).length() < 1e-9 * q.uv.length().max(1.0)
    });
    (normals, uvs)
}

/// What the comparison of one entry found.
#[derive(Debug, Default)]
struct Agreement {
    samples: usize,
    hits: usize,
    /// Samples whose ray and buffer disagree on the polygon (or on whether one is seen).
    mismatches: usize,
    /// The largest distance, in samples, from a mismatched sample to an edge of either
    /// polygon.
    worst_mismatch_distance: f64,
    /// Largest normal and (relative) uv differences, on polygons whose attributes are
    /// affine and on the others.
    affine_normal: f64,
    affine_uv: f64,
    non_affine_normal: f64,
    non_affine_uv: f64,
}

/// Eye rays through every sample centre of `id` at `size × size` against its
/// visible-surface buffer.
fn eye_rays_against_the_buffer(id: &str, size: u32) -> Agreement {
    let scene = load_scene(
        id,
        &[
            format!("camera.width={size}"),
            format!("camera.height={size}"),
        ],
    )
    .unwrap();
    let (view, surface): (View, _) = visible_surface(&scene);
    let screen: Vec<Option<ScreenPolygon>> = {
        let mut all = vec![None; scene.polygons.len()];
        for p in screen_polygons(&scene, &view) {
            let id = p.id as usize;
            all[id] = Some(p);
        }
        all
    };
    let near_edge = |id: u32, x: f64, y: f64| {
        screen
            .get(id as usize)
            .and_then(|p| p.as_ref())
            .map_or(f64::INFINITY, |p| distance_to_edges(p, x, y))
    };
    let rays = SceneRays::new(&scene.polygons);
    let mut found = Agreement::default();
    for (k, s) in surface.samples.iter().enumerate() {
        let (x, y) = (
            (k as u32 % view.width) as f64 + 0.5,
            (k as u32 / view.width) as f64 + 0.5,
        );
        let (origin, direction) = view.ray_through(x, y);
        let hit = rays.closest_hit(origin, direction, view.near, f64::INFINITY, &[]);
        found.samples += 1;
        if hit.map(|h| h.polygon) != (!s.is_empty()).then_some(s.polygon) {
            let d = [hit.map(|h| h.polygon), (!s.is_empty()).then_some(s.polygon)]
                .into_iter()
                .flatten()
                .map(|id| near_edge(id, x, y))
                .fold(f64::INFINITY, f64::min);
            found.mismatches += 1;
            found.worst_mismatch_distance = found.worst_mismatch_distance.max(d);
            assert!(
                d < 1e-6,
                "{id}: sample ({x}, {y}): ray meets {:?}, buffer has {} ({d} samples from an edge)",
                hit.map(|h| h.polygon),
                s.polygon
            );
            continue;
        }
        let Some(hit) = hit else { continue };
        found.hits += 1;
        let polygon = &scene.polygons[hit.polygon as usize];
        assert!(
            (hit.position - s.position).length() <= 1e-6 * s.position.length(),
            "{id}: sample {k}: {} vs {}",
            hit.position,
            s.position
        );
        assert!((hit.t - s.depth).abs() <= 1e-6 * s.depth);
        let normal = (hit.normal - s.normal.as_dvec3()).length();
        let perspective = scene.materials[polygon.material].interpolation != Interpolation::Affine;
        let uv = (hit.uv - s.uv).length() / s.uv.length().max(1.0);
        // Where the attributes are affine both interpolations are exact (the buffer's
        // normal is f32); elsewhere they may part inside the polygon, never by more
        // than the vertices' own spread.
        let (affine_normals, affine_uvs) = affine_attributes(polygon);
        if affine_normals {
            found.affine_normal = found.affine_normal.max(normal);
            assert!(normal < 1e-6, "{id}: sample {k}: normal off by {normal}");
        } else {
            found.non_affine_normal = found.non_affine_normal.max(normal);
            assert!(normal < 0.1, "{id}: sample {k}: normal off by {normal}");
        }
        if !perspective {
            continue;
        }
        if affine_uvs {
            found.affine_uv = found.affine_uv.max(uv);
            assert!(uv < 1e-6, "{id}: sample {k}: uv off by {uv}");
        } else {
            found.non_affine_uv = found.non_affine_uv.max(uv);
            assert!(uv < 0.1, "{id}: sample {k}: uv off by {uv}");
        }
    }
    found
}

const SIZE: u32 = 128;

#[test]
fn eye_rays_see_the_cornell_box_as_the_scan_line_pass_does() {
    let found = eye_rays_against_the_buffer("cornell-box", SIZE);
    println!("cornell-box: {found:?}");
    assert!(found.hits > found.samples * 9 / 10);
}

#[test]
fn eye_rays_see_the_curved_scene_as_the_scan_line_pass_does() {
    let found = eye_rays_against_the_buffer("ray-cast-shadows-curved", SIZE);
    println!("ray-cast-shadows-curved: {found:?}");
    assert!(found.hits > found.samples * 6 / 10);
}

/// A concave polygon (a U, whose fan from vertex 0 has a triangle wound the wrong
/// way): rays into its arms meet it with the exact affine texture coordinates, rays
/// into its notch miss it.
#[test]
fn concave_polygons_interpolate_inside_and_are_missed_in_their_notch() {
    let corners = [
        (0.0, 0.0),
        (3.0, 0.0),
        (3.0, 2.0),
        (2.0, 2.0),
        (2.0, 1.0),
        (1.0, 1.0),
        (1.0, 2.0),
        (0.0, 2.0),
    ];
    let u = Polygon {
        vertices: corners
            .iter()
            .map(|&(x, y)| {
                let position = DVec3::new(x, y, 0.0);
                Vertex {
                    position,
                    normal: DVec3::Z,
                    uv: affine_uv(position),
                }
            })
            .collect(),
        normal: DVec3::Z,
        material: 0,
        object: 0,
    };
    let rays = SceneRays::new(std::slice::from_ref(&u));
    for i in 0..30 {
        for j in 0..20 {
            let (x, y) = (0.05 + 0.1 * i as f64, 0.05 + 0.1 * j as f64);
            let hit = rays.closest_hit(DVec3::new(x, y, 2.0), DVec3::NEG_Z, 0.0, 10.0, &[]);
            let in_notch = (1.0..2.0).contains(&x) && y > 1.0;
            assert_eq!(hit.is_none(), in_notch, "({x}, {y})");
            if let Some(hit) = hit {
                assert!((hit.uv - affine_uv(hit.position)).length() < 1e-12);
                assert_eq!(hit.normal, DVec3::Z);
            }
        }
    }
}
