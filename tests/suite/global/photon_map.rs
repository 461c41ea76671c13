//! Jensen's photon maps (src/global/photon_map.rs, src/geometry/kd_tree.rs): the
//! kd-tree's nearest photons against a brute-force search, the radiance estimate
//! against the closed form of a point light over a plane (and its caustic through a
//! mirror, with the cone filter), and the power the photons carry against the
//! light's.

use crate::support::{camera, polygon, scene_from_text, unit_cube_walls};
use glam::DVec3;
use lumiere::geometry::kd_tree::{KdTree, Neighbour};
use lumiere::global::TracedScene;
use lumiere::global::photon_map::{MapKind, shoot};
use lumiere::global::photon_rendering::CONE;
use lumiere::global::precomputed_irradiance::{EVERY, PrecomputedIrradiance};
use proptest::prelude::*;

proptest! {
    /// The k nearest found by the tree are the k nearest of all: their distances
    /// are the k smallest a brute-force search finds.
    #[test]
    fn the_tree_finds_the_k_nearest(
        points in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), 1..300),
        query in (-1.5f64..1.5, -1.5f64..1.5, -1.5f64..1.5),
        k in 1usize..40,
    ) {
        let items = indexed(&points);
        let q = DVec3::new(query.0, query.1, query.2);
        let mut brute: Vec<f64> = items.iter().map(|(p, _)| p.distance_squared(q)).collect();
        brute.sort_by(f64::total_cmp);
        brute.truncate(k);
        let tree = KdTree::build(items);
        let mut found: Vec<Neighbour> = Vec::new();
        tree.nearest(q, k, &mut found);
        let mut distances: Vec<f64> = found.iter().map(|n| n.distance2).collect();
        distances.sort_by(f64::total_cmp);
        prop_assert_eq!(&distances, &brute);
        for n in &found {
            prop_assert_eq!(tree.items()[n.index].0.distance_squared(q), n.distance2);
        }
    }

    /// The nearest point whose payload is accepted (here: an index of 1 modulo
    /// `modulus`) is the nearest such point of all; none when none is.
    #[test]
    fn the_tree_finds_the_nearest_accepted(
        points in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), 1..300),
        query in (-1.5f64..1.5, -1.5f64..1.5, -1.5f64..1.5),
        modulus in 1usize..5,
    ) {
        let items = indexed(&points);
        let q = DVec3::new(query.0, query.1, query.2);
        let accept = |i: &usize| i % modulus == 1 % modulus;
        let brute = items
            .iter()
            .filter(|(_, i)| accept(i))
            .map(|(p, _)| p.distance_squared(q))
            .min_by(f64::total_cmp);
        let tree = KdTree::build(items);
        let found = tree.nearest_where(q, accept);
        prop_assert_eq!(found.map(|n| n.distance2), brute);
        if let Some(n) = found {
            prop_assert!(accept(&tree.items()[n.index].1));
        }
    }
}

/// The points with their indices as payloads.
fn indexed(points: &[(f64, f64, f64)]) -> Vec<(DVec3, usize)> {
    points
        .iter()
        .enumerate()
        .map(|(i, &(x, y, z))| (DVec3::new(x, y, z), i))
        .collect()
}

/// A floor (ρ = 0.5, 8 x 8) under a point light of intensity I at height h, with
/// `above` added to the scene text.
fn floor_under_a_point_light(above: &str) -> lumiere::Scene {
    let mut text = camera([0.0, 3.0, -3.0], [0.0, 0.0, 0.0], 40.0, 8, 8);
    text += "[global]\nmethod = \"photon-map\"\n\n\
             [materials.floor]\ndiffuse = [0.5, 0.5, 0.5]\n\n\
             [[lights]]\ntype = \"point\"\nposition = [0.0, 1.0, 0.0]\nintensity = [2.0, 2.0, 2.0]\n\n";
    let s = 4.0;
    text += &polygon(
        "floor",
        "floor",
        [
            DVec3::new(-s, 0.0, -s),
            DVec3::new(s, 0.0, -s),
            DVec3::new(s, 0.0, s),
            DVec3::new(-s, 0.0, s),
        ],
        DVec3::Y,
    );
    text += above;
    scene_from_text(&text, &[])
}

/// Points on the floor about (x, 0, z): a ring of eight at 0.1, so the density
/// estimate's noise (1/√k each) averages down.
fn ring(x: f64, z: f64) -> Vec<DVec3> {
    (0..8)
        .map(|k| {
            let a = k as f64 * std::f64::consts::FRAC_PI_4;
            DVec3::new(x + 0.1 * a.cos(), 0.0, z + 0.1 * a.sin())
        })
        .collect()
}

/// The mean over `points` of an estimate over its exact value.
fn mean_ratio(
    points: &[DVec3],
    estimate: impl Fn(DVec3) -> f64,
    exact: impl Fn(DVec3) -> f64,
) -> f64 {
    points.iter().map(|&p| estimate(p) / exact(p)).sum::<f64>() / points.len() as f64
}

/// The global map's estimate on the floor against I cos θ / d², the light's
/// irradiance (the floor's photons of the first bounce are all there is: what
/// it reflects leaves the scene); 1,000 photons an estimate, each 3% noisy,
/// averaged over eight points.
#[test]
fn the_estimate_under_a_point_light_is_its_irradiance() {
    let scene = floor_under_a_point_light("");
    let traced = TracedScene::new(&scene, true);
    let map = shoot(&scene, &traced, MapKind::Global, 1_000_000, 1);
    assert!(map.len() >= 1_000_000);
    let exact = |at: DVec3| {
        let d2 = at.distance_squared(DVec3::Y);
        2.0 * (1.0 / d2.sqrt()) / d2
    };
    for x in [0.0, 0.5, 1.0] {
        let points = ring(x, 0.2);
        let ratio = mean_ratio(
            &points,
            |at| map.irradiance(at, DVec3::Y, 1000).x as f64,
            exact,
        );
        assert!(
            (ratio - 1.0).abs() < 0.02,
            "about ({x}, 0, 0.2): estimate / (I cos / d^2) = {ratio:.4}"
        );
        // Photons arriving from the other side do not count.
        assert_eq!(map.irradiance(points[0], -DVec3::Y, 1000).x, 0.0);
    }
}

/// Christensen's precomputed irradiance on the same floor against the same closed
/// form: the estimate of the 200 nearest photons at every fourth photon, read at
/// the nearest such point, averaged over a 9 x 9 grid of points (each estimate 7%
/// noisy, the grid's points apart by more than an estimate's disc); and nothing
/// for a surface facing the other way, whose normal no point shares.
#[test]
fn precomputed_irradiance_under_a_point_light_is_its_irradiance() {
    let scene = floor_under_a_point_light("");
    let traced = TracedScene::new(&scene, true);
    let map = shoot(&scene, &traced, MapKind::Global, 200_000, 1);
    let precomputed = PrecomputedIrradiance::new(&map, 200);
    assert_eq!(precomputed.len(), map.len().div_ceil(EVERY));
    let exact = |at: DVec3| {
        let d2 = at.distance_squared(DVec3::Y);
        2.0 * (1.0 / d2.sqrt()) / d2
    };
    let grid: Vec<DVec3> = (0..81)
        .map(|i| {
            DVec3::new(
                (i % 9) as f64 * 0.25 - 1.0,
                0.0,
                (i / 9) as f64 * 0.25 - 1.0,
            )
        })
        .collect();
    let ratio = mean_ratio(
        &grid,
        |at| precomputed.irradiance(at, DVec3::Y).unwrap().x as f64,
        exact,
    );
    assert!(
        (ratio - 1.0).abs() < 0.03,
        "precomputed / (I cos / d^2) = {ratio:.4}"
    );
    assert_eq!(precomputed.irradiance(grid[0], -DVec3::Y), None);
}

/// A mirror ceiling (reflectance 0.8) at height 2 over the floor: the caustic map
/// holds the photons the mirror throws down, the light of the lamp's image at
/// height 3 with intensity 0.8 I; read with the cone filter, whose normalisation
/// keeps a flat density's value, against 0.8 I cos θ′ / d′².
#[test]
fn the_caustic_of_a_mirror_is_the_lamps_image() {
    let mirror = "[materials.mirror]\nmirror = [0.8, 0.8, 0.8]\n\n".to_string()
        + &polygon(
            "mirror",
            "mirror",
            [
                DVec3::new(-20.0, 2.0, -20.0),
                DVec3::new(20.0, 2.0, -20.0),
                DVec3::new(20.0, 2.0, 20.0),
                DVec3::new(-20.0, 2.0, 20.0),
            ],
            -DVec3::Y,
        );
    let scene = floor_under_a_point_light(&mirror);
    let traced = TracedScene::new(&scene, true);
    let caustic = shoot(&scene, &traced, MapKind::Caustic, 1_000_000, 2);
    assert!(caustic.len() >= 1_000_000);
    let image = |at: DVec3| {
        let d2 = at.distance_squared(DVec3::new(0.0, 3.0, 0.0));
        0.8 * 2.0 * (3.0 / d2.sqrt()) / d2
    };
    for x in [0.0, 0.5] {
        let points = ring(x, 0.0);
        let ratio = mean_ratio(
            &points,
            |at| caustic.irradiance_cone(at, DVec3::Y, 1000, CONE).x as f64,
            image,
        );
        // Measured 0.978 at 0.5 (the blur of 1,000 photons over the slope):
        // without the filter's normalisation it would be 0.39.
        assert!(
            (ratio - 1.0).abs() < 0.03,
            "about ({x}, 0, 0): caustic / (0.8 I cos / d'^2) = {ratio:.4}"
        );
    }
}

/// Energy: inside a closed cube of albedo ρ lit by a point light, every emitted
/// photon lands, and each bounce is stored with its power kept (a grey surface's
/// roulette): the stored power is Φ (1 + ρ + ρ² + …) = 4π I / (1 − ρ).
#[test]
fn the_photons_carry_the_lights_power() {
    let rho = 0.5;
    let mut text = camera([0.5, 0.5, 0.5], [0.5, 0.5, 1.0], 40.0, 8, 8);
    text += &format!(
        "[global]\nmethod = \"photon-map\"\n\n[materials.wall]\ndiffuse = [{rho}, {rho}, {rho}]\n\n\
         [[lights]]\ntype = \"point\"\nposition = [0.55, 0.6, 0.65]\nintensity = [1.0, 1.0, 1.0]\n\n"
    );
    text += &unit_cube_walls("wall");
    let scene = scene_from_text(&text, &[]);
    let traced = TracedScene::new(&scene, true);
    let map = shoot(&scene, &traced, MapKind::Global, 200_000, 4);
    let stored: f64 = map.photons().iter().map(|(_, p)| p.power.x as f64).sum();
    let expected = 4.0 * std::f64::consts::PI / (1.0 - rho);
    assert!(
        (stored / expected - 1.0).abs() < 0.01,
        "stored power {stored:.4} against 4 pi I / (1 - rho) = {expected:.4}"
    );
    // No specular surface, no caustic map.
    assert!(shoot(&scene, &traced, MapKind::Caustic, 1000, 4).is_empty());
}
