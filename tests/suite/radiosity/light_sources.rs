//! Point, spot, distant and sphere lights shot into the radiosity solution, against
//! closed forms written here: each element's received radiosity ρ I cos θ / r²
//! (and the spot's, the sun's, the sphere's), nothing behind a blocker; a closed
//! room lit by a point light holds ρ/(1 − ρ) of the light's power 4πI after every
//! bounce, with either solver; and where nothing can bounce (a lone floor), the
//! rendered image is the direct light alone, with radiosity or without (the
//! display does not count the lights' direct light twice).

use crate::support;

use glam::{DVec3, Vec3};
use lumiere::radiosity;
use lumiere::{Renderer, Scene};
use std::f64::consts::PI;
use support::{error_line, polygon, scene_from_text, unit_cube_walls};

fn camera() -> String {
    support::camera([0.5, 1.6, -0.5], [0.5, 0.0, 0.5], 50.0, 24, 24)
}

fn rectangle(a: DVec3, b: DVec3) -> [DVec3; 4] {
    if a.y == b.y {
        [a, DVec3::new(b.x, a.y, a.z), b, DVec3::new(a.x, a.y, b.z)]
    } else if a.x == b.x {
        [a, DVec3::new(a.x, b.y, a.z), b, DVec3::new(a.x, a.y, b.z)]
    } else {
        [a, DVec3::new(b.x, a.y, a.z), b, DVec3::new(a.x, b.y, a.z)]
    }
}

/// A unit floor (ρ = 0.5) facing up under `light`, with a blocker (facing down)
/// over [0.1, 0.4]² at height 0.5, meshed into 1/8-unit elements.
fn floor_scene(light: &str, radiosity: &str) -> Scene {
    let mut text = format!(
        "{}[radiosity]\n{radiosity}\n\n[materials.floor]\ndiffuse = [0.5, 0.25, 0.125]\n\n[[lights]]\n{light}\n\n",
        camera()
    );
    text += &polygon(
        "floor",
        "floor",
        rectangle(DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0)),
        DVec3::Y,
    );
    text += &polygon(
        "blocker",
        "floor",
        rectangle(DVec3::new(0.1, 0.5, 0.1), DVec3::new(0.4, 0.5, 0.4)),
        -DVec3::Y,
    );
    scene_from_text(&text, &[])
}

const MESH: &str = "element_size = 0.125\npatch_size = 0.25";

/// Whether the segment from `p` to `light` crosses the blocker.
fn behind_blocker(p: DVec3, light: DVec3) -> bool {
    if (p.y - 0.5) * (light.y - 0.5) >= 0.0 {
        return false;
    }
    let t = (0.5 - p.y) / (light.y - p.y);
    let x = p + (light - p) * t;
    (0.1..=0.4).contains(&x.x) && (0.1..=0.4).contains(&x.z)
}

/// The floor's elements: centre and received radiosity (red band over ρ_red).
fn floor_elements(scene: &Scene) -> Vec<(DVec3, Vec3)> {
    let settings = scene.radiosity.clone().unwrap();
    let mesh = radiosity::mesh(scene, &settings).unwrap_or_else(|e| panic!("{}", error_line(&e)));
    mesh.elements
        .iter()
        .filter(|e| mesh.patches[e.patch].polygon == 0)
        .map(|e| (e.centre, e.received))
        .collect()
}

#[test]
fn a_point_light_gives_each_element_rho_i_cos_over_r_squared_at_its_centre() {
    let light = DVec3::new(0.6, 1.0, 0.55);
    let scene = floor_scene(
        "type = \"point\"\nposition = [0.6, 1.0, 0.55]\nintensity = [2.0, 2.0, 2.0]",
        MESH,
    );
    let elements = floor_elements(&scene);
    assert_eq!(elements.len(), 64);
    let mut shadowed = 0;
    for (centre, received) in elements {
        let d = light - centre;
        let expected = if behind_blocker(centre, light) {
            shadowed += 1;
            0.0
        } else {
            2.0 * d.y / d.length().powi(3)
        };
        for (band, rho) in [0.5, 0.25, 0.125].into_iter().enumerate() {
            let want = rho * expected;
            let got = received[band] as f64;
            assert!(
                (got - want).abs() <= 1e-6 * want.max(1e-3),
                "{centre}: {got} against {want}"
            );
        }
    }
    assert!(shadowed >= 4, "the blocker shadows {shadowed} elements");
}

#[test]
fn spot_distant_and_sphere_lights_give_their_closed_forms() {
    // A spot pointing straight down, f(θ) = cos⁴ θ inside 25°.
    let spot = DVec3::new(0.5, 1.0, 0.5);
    let scene = floor_scene(
        "type = \"spot\"\nposition = [0.5, 1.0, 0.5]\naxis = [0.0, -1.0, 0.0]\ncone_angle = 25.0\ncosine_power = 4.0\nintensity = [3.0, 3.0, 3.0]",
        MESH,
    );
    let mut inside = 0;
    for (centre, received) in floor_elements(&scene) {
        let d = spot - centre;
        let cos = d.y / d.length();
        let expected = if behind_blocker(centre, spot) || cos < 25f64.to_radians().cos() {
            0.0
        } else {
            inside += 1;
            0.5 * 3.0 * cos.powi(4) * cos / d.length_squared()
        };
        let got = received.x as f64;
        assert!(
            (got - expected).abs() <= 1e-6 * expected.max(1e-3),
            "spot at {centre}: {got} against {expected}"
        );
    }
    assert!(inside > 10 && inside < 60, "{inside} elements in the cone");
    // The sun, slanting: E cos θ, the blocker's shadow cast along its direction.
    let scene = floor_scene(
        "type = \"distant\"\ndirection = [0.6, -0.8, 0.0]\nirradiance = [1.5, 1.5, 1.5]",
        MESH,
    );
    let mut shadowed = 0;
    for (centre, received) in floor_elements(&scene) {
        let far = centre + DVec3::new(-0.6, 0.8, 0.0) * 10.0;
        let expected = if behind_blocker(centre, far) {
            shadowed += 1;
            0.0
        } else {
            0.5 * 1.5 * 0.8
        };
        let got = received.x as f64;
        assert!(
            (got - expected).abs() <= 1e-6,
            "sun at {centre}: {got} against {expected}"
        );
    }
    assert!(shadowed >= 4, "{shadowed}");
    // A sphere wholly above every element's horizon, away from the blocker's
    // shadow: H = π L sin²α cos θ_c, sin α = r/d, θ_c towards its centre.
    let (centre, radius, radiance) = (DVec3::new(0.8, 0.9, 0.8), 0.15, 4.0);
    let scene = floor_scene(
        "type = \"sphere\"\ncentre = [0.8, 0.9, 0.8]\nradius = 0.15\nradiance = [4.0, 4.0, 4.0]",
        MESH,
    );
    let mut worst: f64 = 0.0;
    for (p, received) in floor_elements(&scene) {
        if p.x < 0.5 || p.z < 0.5 {
            continue;
        }
        let d = centre - p;
        let expected = 0.5 * PI * radiance * (radius / d.length()).powi(2) * d.y / d.length();
        worst = worst.max((received.x as f64 - expected).abs() / expected);
    }
    // 8 × 8 jittered rays over the cone: the estimate is unbiased, its error a
    // fraction of a percent.
    assert!(worst < 0.01, "sphere: worst relative error {worst}");
}

/// The unit cube's walls facing in (ρ = 0.5), a point light of intensity 1 at
/// its centre.
fn lit_cube(solver: &str) -> Scene {
    let mut text = format!(
        "{}[radiosity]\nsolver = \"{solver}\"\nresolution = 128\nelement_size = 0.125\npatch_size = 0.25\ntolerance = 1e-9\nunshot = 1e-5\nmax_steps = 100000\n\n[materials.wall]\ndiffuse = [0.5, 0.5, 0.5]\n\n[[lights]]\ntype = \"point\"\nposition = [0.5, 0.5, 0.5]\nintensity = [1.0, 1.0, 1.0]\n\n",
        camera()
    );
    text += &unit_cube_walls("wall");
    scene_from_text(&text, &[])
}

#[test]
fn a_closed_room_lit_by_a_point_light_holds_rho_over_one_minus_rho_of_its_power() {
    // Σ A_i B_i = ρ Σ A_i H_i + ρ Σ_i A_i Σ_j F_ij B_j = ρ Φ + ρ Σ_j A_j B_j (closure
    // and reciprocity), so Σ A B = ρ Φ / (1 − ρ) with Φ = 4π I, all of it caught.
    let power = 4.0 * PI;
    let expected = 0.5 * power / (1.0 - 0.5);
    for solver in ["gathering", "shooting"] {
        let scene = lit_cube(solver);
        let settings = scene.radiosity.clone().unwrap();
        let mesh = radiosity::mesh(&scene, &settings).unwrap();
        // The lights' shots alone: the midpoint rule over 384 elements of Φ ρ.
        let caught: f64 = mesh
            .elements
            .iter()
            .map(|e| e.received.x as f64 * e.area)
            .sum();
        assert!(
            (caught / (0.5 * power) - 1.0).abs() < 0.01,
            "{solver}: the elements caught {caught} of ρΦ = {}",
            0.5 * power
        );
        let solution = radiosity::solve(&scene, &settings, &mut |_, _| {}).unwrap();
        let held: f64 = solution
            .elements
            .iter()
            .zip(&solution.mesh.elements)
            .map(|(b, e)| b.x as f64 * e.area)
            .sum();
        let direct: f64 = solution
            .direct
            .as_ref()
            .unwrap()
            .iter()
            .zip(&solution.mesh.elements)
            .map(|(d, e)| d.x as f64 * e.area)
            .sum();
        println!("{solver}: Σ A B = {held:.5}, expected {expected:.5}; direct {direct:.5}");
        // Hemi-cube factors are not exactly reciprocal, and the midpoint rule
        // above: 2% in all.
        assert!(
            (held / expected - 1.0).abs() < 0.02,
            "{solver}: Σ A B = {held} against ρΦ/(1 − ρ) = {expected}"
        );
        assert!(
            (direct / caught - 1.0).abs() < 1e-5,
            "{solver}: the direct part {direct} is not what the lights gave, {caught}"
        );
    }
}

fn pixels(scene: Scene) -> Vec<Vec3> {
    Renderer::new(scene)
        .render()
        .unwrap_or_else(|e| panic!("{}", error_line(&e)))
        .pixels
}

#[test]
fn where_nothing_bounces_the_image_is_the_direct_light_with_radiosity_or_without() {
    // A lone floor under a point light sees no other surface: the solution holds
    // only the light's direct part, which every sample computes itself. Drawn
    // without that part, the image equals the plain direct-light image.
    let text = |radiosity: bool| {
        let mut t = camera();
        if radiosity {
            t += "[radiosity]\nelement_size = 0.125\n\n";
        }
        t += "[shadows]\nmethod = \"ray-cast\"\n\n[materials.floor]\ndiffuse = [0.5, 0.5, 0.5]\n\n[[lights]]\ntype = \"point\"\nposition = [0.6, 1.0, 0.55]\nintensity = [2.0, 2.0, 2.0]\n\n";
        t += &polygon(
            "floor",
            "floor",
            rectangle(DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0)),
            DVec3::Y,
        );
        t
    };
    let with = pixels(scene_from_text(&text(true), &[]));
    let without = pixels(scene_from_text(&text(false), &[]));
    let lit = without.iter().filter(|p| p.x > 0.01).count();
    assert!(lit > 100, "{lit} lit pixels");
    for (k, (a, b)) in with.iter().zip(&without).enumerate() {
        assert!(
            (*a - *b).abs().max_element() <= 1e-6 * b.max_element().max(1.0),
            "pixel {k}: {a} with radiosity, {b} without"
        );
    }
}
