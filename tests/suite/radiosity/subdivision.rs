//! Adaptive subdivision (Cohen, Greenberg, Immel & Brock 1986, step 6): the refined
//! mesh keeps its area and draws through its T-vertices, and the refined solution
//! approaches the uniformly fine one with fewer elements.

use glam::{DVec3, Vec3};
use lumiere::load_scene;
use lumiere::radiosity::{Division, Mesh, Settings, Solver, solve};
use lumiere::scene::{Scene, scene_from_table, tables};
use proptest::prelude::*;

/// The gathering entry at 64², with elements of `element` mm in patches of 140 mm.
fn cornell(element: f64, subdivide: Option<f64>) -> (Scene, Settings) {
    let mut sets = vec![
        "camera.width=64".to_string(),
        "camera.height=64".to_string(),
        "radiosity.patch_size=140.0".to_string(),
        format!("radiosity.element_size={element:?}"),
        "radiosity.subdivision_levels=1".to_string(),
    ];
    if let Some(t) = subdivide {
        sets.push(format!("radiosity.subdivide={t:?}"));
    }
    let scene = load_scene("radiosity-gathering", &sets).unwrap();
    let settings = scene.radiosity.clone().unwrap();
    (scene, settings)
}

fn mean_difference(a: &[Vec3], b: &[Vec3]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).abs().element_sum() as f64)
        .sum::<f64>()
        / a.len() as f64
}

#[test]
fn refining_where_neighbours_differ_approaches_the_fine_mesh_with_fewer_elements() {
    let (scene, coarse) = cornell(70.0, None);
    let (_, fine) = cornell(35.0, None);
    let (_, adaptive) = cornell(70.0, Some(0.05));
    let count = |s: &Settings| {
        solve(&scene, s, &mut |_, _| {})
            .unwrap()
            .mesh
            .elements
            .len()
    };
    let (n_coarse, n_fine, n_adaptive) = (count(&coarse), count(&fine), count(&adaptive));
    assert!(
        n_coarse < n_adaptive && n_adaptive < n_fine,
        "elements: coarse {n_coarse}, adaptive {n_adaptive}, fine {n_fine}"
    );
    let image = |s: &Settings| {
        let mut scene = scene.clone();
        scene.radiosity = Some(s.clone());
        lumiere::render(&scene).unwrap().pixels
    };
    let reference = image(&fine);
    let (before, after) = (
        mean_difference(&image(&coarse), &reference),
        mean_difference(&image(&adaptive), &reference),
    );
    eprintln!("mean |coarse - fine| {before:.5}, |adaptive - fine| {after:.5}");
    assert!(after < 0.5 * before, "{after} against {before}");
}

#[test]
fn a_threshold_no_neighbours_exceed_changes_nothing() {
    let (scene, plain) = cornell(70.0, None);
    let (_, loose) = cornell(70.0, Some(10.0));
    let a = solve(&scene, &plain, &mut |_, _| {}).unwrap();
    let b = solve(&scene, &loose, &mut |_, _| {}).unwrap();
    assert_eq!(a.elements, b.elements);
    assert!(b.summary.contains("cut [] elements"), "{}", b.summary);
}

#[test]
fn subdivision_belongs_to_gathering() {
    let (scene, mut settings) = cornell(70.0, Some(0.05));
    settings.solver = Solver::Shooting;
    let error = solve(&scene, &settings, &mut |_, _| {}).err().unwrap();
    assert!(error.to_string().contains("gathering"), "{error}");
}

/// One polygon scene: `corners` (3 or 4, planar) as the only object.
fn polygon_scene(corners: &[DVec3]) -> Scene {
    let vertices: Vec<[f64; 3]> = corners.iter().map(|c| c.to_array()).collect();
    let text = format!(
        "{}[materials.m]\ndiffuse = [0.5, 0.5, 0.5]\nemission = [1.0, 1.0, 1.0]\n\
         [[objects]]\nshape = \"polygon\"\nname = \"p\"\nmaterial = \"m\"\nvertices = {vertices:?}\n",
        crate::support::camera([0.0, 0.0, 9.0], [0.0, 0.0, 0.0], 40.0, 8, 8)
    );
    let table = tables::parse(&text, "test scene").unwrap();
    scene_from_table(table, &lumiere::catalogue::resources()).unwrap()
}

fn distance_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
    (a + (b - a) * t - p).length()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// Whatever is marked, over three rounds: the elements of every patch still add
    /// up to its area, every cut element's four children to its area, every point
    /// an outline adds between two corners lies on that side, and every element
    /// corner lying on a side is in the outline (no T-vertex left out to crack the
    /// shading).
    #[test]
    fn refinement_keeps_areas_and_puts_t_vertices_on_the_sides(
        quad in any::<bool>(),
        jitter in prop::collection::vec(-0.3..0.3f64, 8),
        n in 1u32..4,
        marks in prop::collection::vec(prop::collection::vec(any::<bool>(), 400), 3),
    ) {
        // A convex planar polygon in z = 0 (a jittered square, or a triangle).
        let mut corners = vec![
            DVec3::new(0.0 + jitter[0], 0.0 + jitter[1], 0.0),
            DVec3::new(2.0 + jitter[2], 0.0 + jitter[3], 0.0),
            DVec3::new(2.0 + jitter[4], 2.0 + jitter[5], 0.0),
            DVec3::new(0.0 + jitter[6], 2.0 + jitter[7], 0.0),
        ];
        if !quad {
            corners.pop();
        }
        let scene = polygon_scene(&corners);
        let mut mesh = Mesh::build(&scene, Division::Whole, Division::Count(n)).unwrap();
        let whole: f64 = mesh.patches.iter().map(|p| p.area).sum();
        for round in &marks {
            let marked: Vec<bool> = (0..mesh.elements.len()).map(|e| round[e % round.len()]).collect();
            let (finer, origin) = mesh.refine(&marked);
            for (e, from) in origin.iter().enumerate() {
                if let Err(parent) = from {
                    let siblings: f64 = origin
                        .iter()
                        .enumerate()
                        .filter(|(_, f)| *f == from)
                        .map(|(k, _)| finer.elements[k].area)
                        .sum();
                    prop_assert!((siblings - mesh.elements[*parent].area).abs() < 1e-12 * whole);
                    prop_assert_eq!(finer.elements[e].patch, mesh.elements[*parent].patch);
                }
            }
            mesh = finer;
            for p in &mesh.patches {
                let sum: f64 = mesh.elements[p.elements.clone()].iter().map(|e| e.area).sum();
                prop_assert!((sum - p.area).abs() < 1e-12 * whole);
            }
            for e in 0..mesh.elements.len() {
                let c = &mesh.elements[e].corners;
                let outline = mesh.outline(e);
                prop_assert_eq!(outline[0], c[0]);
                let mut side = 0;
                for &v in &outline[1..] {
                    if side + 1 < c.len() && v == c[side + 1] {
                        side += 1;
                        continue;
                    }
                    let (a, b) = (mesh.vertices[c[side] as usize], mesh.vertices[c[(side + 1) % c.len()] as usize]);
                    prop_assert!(distance_to_segment(mesh.vertices[v as usize], a, b) < 1e-12);
                }
                prop_assert_eq!(side + 1, c.len());
                let used: std::collections::HashSet<u32> =
                    mesh.elements.iter().flat_map(|x| x.corners.iter().copied()).collect();
                for &v in &used {
                    let p = mesh.vertices[v as usize];
                    let on_side = (0..c.len()).any(|k| {
                        let (a, b) = (c[k], c[(k + 1) % c.len()]);
                        v != a && v != b && distance_to_segment(p, mesh.vertices[a as usize], mesh.vertices[b as usize]) < 1e-12
                    });
                    prop_assert!(!on_side || outline.contains(&v), "vertex {} missing from element {}", v, e);
                }
            }
        }
    }
}
