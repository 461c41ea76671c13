//! The geometric core on degenerate input: repeated and collinear vertices, polygons
//! of no area, coincident polygons, coordinates from 1e-9 to 1e9. Sutherland–Hodgman,
//! Weiler–Atherton, the scan-line pass, Crow's silhouettes and the hemi-cube never
//! panic on them, and their identities hold: clipped parts add up to the whole, a
//! polygon of no area covers no sample, a repeated vertex changes no coverage,
//! silhouettes of closed objects close up, form factors are non-negative and sum to
//! at most one.

use crate::support;

use glam::{DVec2, DVec3};
use lumiere::geometry::polygon::area;
use lumiere::geometry::{sutherland_hodgman, weiler_atherton};
use lumiere::raster::covered_samples;
use proptest::prelude::*;
use support::{origin_view, screen_polygon};

/// A star-shaped polygon around the origin in [-1, 1]² (n vertices, the i-th at an
/// angle within 0.4 of a step past i steps of 2π/n, so that no gap reaches π and
/// the outline is simple), made degenerate in one of the ways a user's data can be:
/// a vertex repeated, collinear vertices inserted, flattened to a segment (no
/// area), or collapsed to a point.
fn degenerate_contour() -> impl Strategy<Value = Vec<DVec2>> {
    (
        prop::collection::vec((0.0..0.4f64, 0.2..1.0f64), 3..9),
        0usize..5,
        0usize..9,
    )
        .prop_map(|(points, how, at)| {
            let step = std::f64::consts::TAU / points.len() as f64;
            let mut c: Vec<DVec2> = points
                .iter()
                .enumerate()
                .map(|(i, &(jitter, r))| {
                    let a = (i as f64 + jitter) * step;
                    DVec2::new(r * a.cos(), r * a.sin())
                })
                .collect();
            let k = at % c.len();
            match how {
                0 => c.insert(k, c[k]),
                1 => {
                    let (a, b) = (c[k], c[(k + 1) % c.len()]);
                    c.insert(k + 1, a.lerp(b, 0.5));
                    c.insert(k + 1, a.lerp(b, 0.25));
                }
                2 => c.iter_mut().for_each(|p| p.y = 0.3 * p.x),
                3 => c.iter_mut().for_each(|p| *p = DVec2::new(0.1, 0.2)),
                _ => {}
            }
            c
        })
}

/// A scale from 1e-9 to 1e9.
fn scale() -> impl Strategy<Value = f64> {
    (-9i32..=9).prop_map(|k| 10f64.powi(k))
}

fn scaled(c: &[DVec2], s: f64, offset: DVec2) -> Vec<DVec2> {
    c.iter().map(|&p| p * s + offset * s).collect()
}

/// Shoelace area of a list of points, zero for fewer than three.
fn measure(points: &[DVec3]) -> f64 {
    if points.len() < 3 { 0.0 } else { area(points) }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(192))]

    /// Sutherland–Hodgman: the parts on either side of any plane add up to the
    /// polygon's area, at every scale.
    #[test]
    fn clipping_by_a_plane_keeps_the_area(
        contour in degenerate_contour(),
        s in scale(),
        plane in ((-1.0..1.0f64, -1.0..1.0f64), -0.5..0.5f64),
    ) {
        let polygon: Vec<DVec3> = contour.iter().map(|p| (p.extend(0.0)) * s).collect();
        let normal = DVec3::new(plane.0.0, plane.0.1, 0.0);
        prop_assume!(normal.length() > 0.1);
        let d = |v: &DVec3| v.dot(normal) - plane.1 * s;
        let kept = sutherland_hodgman::clip(&polygon, d);
        let cut = sutherland_hodgman::clip(&polygon, |v| -d(v));
        let whole = measure(&polygon).abs();
        let sum = measure(&kept).abs() + measure(&cut).abs();
        prop_assert!((sum - whole).abs() <= 1e-9 * s * s, "{sum} vs {whole} at scale {s}");
        prop_assert!(kept.iter().chain(&cut).all(|v| v.is_finite()));
    }

    /// Weiler–Atherton: A ∩ B and A − B add up to A, for degenerate operands, for
    /// an operand clipped by itself (coincident polygons) and at every scale.
    #[test]
    fn inside_and_outside_add_up_on_degenerate_operands(
        a in degenerate_contour(),
        b in degenerate_contour(),
        s in scale(),
        shift in (-0.5..0.5f64, -0.5..0.5f64),
        coincident in any::<bool>(),
    ) {
        let orient = |c: Vec<DVec2>| {
            let mut c = c;
            if weiler_atherton::contour_area(&c) < 0.0 {
                c.reverse();
            }
            c
        };
        let a = orient(scaled(&a, s, DVec2::ZERO));
        let b = if coincident { a.clone() } else { orient(scaled(&b, s, DVec2::new(shift.0, shift.1))) };
        let (inside, outside) = weiler_atherton::clip(&vec![a.clone()], &vec![b.clone()]);
        let whole = weiler_atherton::contour_area(&a);
        let parts = weiler_atherton::area(&inside) + weiler_atherton::area(&outside);
        let size = s * s;
        prop_assert!((parts - whole).abs() <= 1e-6 * size, "{parts} vs {whole} at scale {s}");
        prop_assert!(weiler_atherton::area(&inside) <= whole.min(weiler_atherton::contour_area(&b)) + 1e-6 * size);
        if coincident {
            prop_assert!((weiler_atherton::area(&inside) - whole).abs() <= 1e-6 * size);
        }
    }

    /// The scan-line pass: a polygon of no area covers no sample, and a repeated or
    /// collinear vertex changes no sample's coverage; nothing panics at any depth
    /// scale.
    #[test]
    fn degenerate_polygons_cover_what_their_area_says(
        contour in degenerate_contour(),
        depth in (-3i32..=6).prop_map(|k| 10f64.powi(k)),
    ) {
        let view = origin_view(48, 40);
        // Seen at `depth`, the polygon spans about the same part of the image.
        let points: Vec<DVec3> = contour.iter().map(|p| DVec3::new(p.x * 0.4 * depth, p.y * 0.4 * depth, -depth)).collect();
        let Some(polygon) = screen_polygon(&view, 0, &points) else { return Ok(()); };
        let covered = covered_samples(&polygon, 48, 40);
        if measure(&points).abs() <= 1e-12 * depth * depth {
            prop_assert!(covered.is_empty(), "{} samples covered by a polygon of no area", covered.len());
        }
        // The same outline without repeated points covers the same samples.
        let mut simple: Vec<DVec3> = points.clone();
        simple.dedup();
        while simple.len() > 1 && simple[0] == simple[simple.len() - 1] {
            simple.pop();
        }
        if let Some(p) = screen_polygon(&view, 0, &simple) {
            prop_assert_eq!(covered_samples(&p, 48, 40), covered);
        }
    }
}

mod scenes {
    use glam::DVec3;
    use lumiere::Scene;
    use lumiere::radiosity::hemicube::Hemicube;
    use lumiere::radiosity::mesh::Mesh;
    use lumiere::radiosity::receivers::Receivers;
    use lumiere::settings::Division;
    use lumiere::shadow::shadow_volumes::{Source, quads_from};
    use proptest::prelude::*;
    use std::collections::HashMap;

    /// A scene at scale `s`: a box scaled flat along y by `flatten` (1 is a cube,
    /// 1e-12 a box whose top and bottom nearly coincide and whose sides have almost
    /// no area), a sphere, and two coincident quads. A flatten of 0 is refused in
    /// one line (a zero scale), never a panic: `None` then.
    fn scene(s: f64, flatten: f64, light: DVec3) -> Option<Scene> {
        let loaded = load(s, flatten, light);
        if flatten == 0.0 {
            let Err(e) = loaded else {
                panic!("a zero scale is refused")
            };
            let line = crate::support::error_line(&e);
            assert!(
                line.contains(
                    "objects[0]: transform[0].scale: a scale must be finite and not zero"
                ),
                "{line}"
            );
            return None;
        }
        Some(loaded.unwrap_or_else(|e| {
            panic!(
                "scale {s}, flatten {flatten}: {}",
                crate::support::error_line(&e)
            )
        }))
    }

    fn load(s: f64, flatten: f64, light: DVec3) -> lumiere::Result<Scene> {
        let text = format!(
            "{}[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\
             [[lights]]\ntype = \"point\"\nposition = [{lx:?}, {ly:?}, {lz:?}]\nintensity = [1.0, 1.0, 1.0]\n\
             [[objects]]\nshape = \"box\"\nname = \"box\"\nmaterial = \"grey\"\ntransform = [{{ scale = [{s:?}, {fy:?}, {s:?}] }}]\n\
             [[objects]]\nshape = \"sphere\"\nname = \"ball\"\nmaterial = \"grey\"\nresolution = 8\ntransform = [{{ scale = {h:?} }}, {{ translate = [{t:?}, 0.0, 0.0] }}]\n\
             [[objects]]\nshape = \"quad\"\nname = \"floor\"\nmaterial = \"grey\"\ntransform = [{{ scale = {q:?} }}, {{ translate = [0.0, {d:?}, 0.0] }}]\n\
             [[objects]]\nshape = \"quad\"\nname = \"floor again\"\nmaterial = \"grey\"\ntransform = [{{ scale = {q:?} }}, {{ translate = [0.0, {d:?}, 0.0] }}]\n",
            crate::support::camera([0.0, 3.0 * s, 5.0 * s], [0.0, 0.0, 0.0], 40.0, 24, 24),
            lx = light.x * s,
            ly = light.y * s,
            lz = light.z * s,
            fy = s * flatten,
            h = 0.5 * s,
            t = 1.5 * s,
            q = 6.0 * s,
            d = -s,
        );
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("scene.toml");
        std::fs::write(&path, text).unwrap();
        lumiere::load_scene(path.to_str().unwrap(), &[])
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// Crow's silhouettes: the silhouette edges of each closed object, seen from
        /// the light, form closed loops (as many leave each vertex as arrive), at
        /// every scale and with faces of no area dropped; every quad is finite.
        #[test]
        fn silhouettes_of_closed_objects_close_up(
            s in (-9i32..=9).prop_map(|k| 10f64.powi(k)),
            flatten in prop_oneof![Just(1.0), Just(0.0), Just(1e-12), 0.01..2.0f64],
            light in (-2.0..2.0f64, 2.0..5.0f64, -2.0..2.0f64),
        ) {
            let light = DVec3::new(light.0, light.1, light.2);
            let Some(scene) = scene(s, flatten, light) else { return Ok(()); };
            let quads = quads_from(&scene, Source::Point(light * s));
            prop_assert!(quads.iter().all(|q| q.corners.iter().all(|c| c.is_finite()) && q.outward.is_finite()));
            // Loops, per vertex by its exact bits; the quads of the lone, two-sided
            // floor close up too.
            let mut balance: HashMap<[u64; 3], i32> = HashMap::new();
            let bits = |p: DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
            for q in &quads {
                *balance.entry(bits(q.corners[0])).or_default() += 1;
                *balance.entry(bits(q.corners[1])).or_default() -= 1;
            }
            prop_assert!(balance.values().all(|&b| b == 0), "open silhouette at scale {s}, flatten {flatten}");
        }

        /// The hemi-cube from every patch of such a scene: factors finite and
        /// non-negative, summing to at most one, at every scale.
        #[test]
        fn hemicube_factors_stay_a_partition(
            s in (-9i32..=9).prop_map(|k| 10f64.powi(k)),
            flatten in prop_oneof![Just(1.0), Just(0.0), Just(1e-12)],
        ) {
            let Some(scene) = scene(s, flatten, DVec3::new(0.5, 3.0, 0.5)) else { return Ok(()); };
            let mesh = Mesh::build(&scene, Division::Whole, Division::Whole).unwrap();
            let receivers = Receivers::patches(&mesh);
            let hemicube = Hemicube::new(32);
            for (i, patch) in mesh.patches.iter().enumerate() {
                let row = hemicube.factors(patch.centre, patch.normal, &receivers, &|j| j == i);
                prop_assert!(row.iter().all(|f| f.is_finite() && *f >= 0.0));
                let sum: f64 = row.iter().sum();
                prop_assert!(sum <= 1.0 + 1e-9, "patch {i} at scale {s}: {sum}");
            }
        }
    }
}
