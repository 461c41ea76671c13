//! Light volumes (Max 1986) against what they must equal: the plain render when the
//! medium is empty, the closed form under a distant light with nothing in the way, a
//! fine numerical integral under a point light, and the ray-marched reference on the
//! catalogue's scenes; an occluder never brightens a pixel, a denser absorbing medium
//! never brightens what is seen through it.

use crate::support::{self, render};

use glam::{DVec3, Vec3};
use lumiere::media::single_scattering::{Scattering, phase, point_integrand};
use lumiere::render::visible_surface;
use lumiere::shadow::light_volumes::LightVolumes;
use lumiere::{Image, Scene, load_scene};

fn scene_with(spec: &str, sets: &[&str]) -> Scene {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    load_scene(spec, &sets).unwrap_or_else(|e| panic!("{}", support::error_line(&e)))
}

fn scene_file(text: &str, sets: &[&str]) -> Scene {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    support::scene_from_text(text, &sets)
}

#[test]
fn an_empty_medium_changes_nothing() {
    for id in [
        "light-volumes-cornell",
        "light-volumes-spot",
        "light-volumes-blinds",
    ] {
        let small = ["camera.width=48", "camera.height=36"];
        let plain = {
            let mut s = scene_with(id, &small);
            s.medium = None;
            render(&s)
        };
        let empty = render(&scene_with(
            id,
            &[&small[..], &["medium.extinction=0"]].concat(),
        ));
        assert_eq!(plain.pixels, empty.pixels, "{id}");
        let foggy = render(&scene_with(id, &small));
        assert_ne!(
            plain.pixels, foggy.pixels,
            "{id}: the medium changes nothing"
        );
    }
}

fn open_sun() -> String {
    support::camera([0.0, 1.0, 6.0], [0.0, 0.0, 0.0], 40.0, 40, 30)
        + r#"[materials.grey]
diffuse = [0.5, 0.5, 0.5]

[medium]
extinction = 0.2
albedo = 0.7
phase = "henyey-greenstein"
g = 0.4

[[lights]]
type = "distant"
direction = [0.3, -1.0, -0.2]
irradiance = [2.0, 3.0, 4.0]

[[objects]]
shape = "quad"
name = "floor"
material = "grey"
transform = [{ scale = 100.0 }]
"#
}

/// A distant light, nothing in the way: every viewing ray is lit over its whole
/// length D, and the in-scattered light is σ_s p(α) E (1 − e^(−σ_t D)) / σ_t.
#[test]
fn under_an_open_sky_the_closed_form() {
    let scene = scene_file(&open_sun(), &[]);
    let medium = scene.medium.clone().unwrap();
    let (view, surface) = visible_surface(&scene);
    let volumes = LightVolumes::new(&scene, &scene.lights[0]).unwrap();
    let lit = volumes.frame(&scene, &view).band(&surface, 1e3);
    let lumiere::Light::Distant(sun) = &scene.lights[0] else {
        panic!("a distant light");
    };
    let scattering = Scattering::new(&medium);
    let mut checked = 0;
    for k in 0..surface.samples.len() {
        let (direction, length) = lumiere::media::viewing_ray(&view, &surface, k, 1e3);
        assert_eq!(lit.of(k), &[[0.0, length]], "sample {k}");
        let found = scattering.inscattered(&scene.lights[0], view.eye, direction, lit.of(k));
        let (st, ss) = (medium.extinction, medium.scattering());
        let p = phase(&medium, sun.direction.dot(-direction));
        let expected = sun.irradiance * (ss * p * (1.0 - (-st * length).exp()) / st) as f32;
        let error = (found - expected).abs().max_element() / expected.max_element();
        assert!(error < 1e-6, "sample {k}: {found} against {expected}");
        checked += 1;
    }
    assert!(checked > 1000);
}

/// A point light, nothing in the way: the Gauss–Legendre pieces against a composite
/// Simpson rule with a million steps, on rays passing close to and far from it.
#[test]
fn under_a_point_light_the_quadrature_matches_a_fine_integral() {
    let text = open_sun().replace(
        "type = \"distant\"\ndirection = [0.3, -1.0, -0.2]\nirradiance = [2.0, 3.0, 4.0]",
        "type = \"point\"\nposition = [0.2, 1.0, 0.5]\nintensity = [1.0, 1.0, 1.0]",
    );
    let scene = scene_file(&text, &[]);
    let medium = scene.medium.clone().unwrap();
    let light = &scene.lights[0];
    let at = light.position().unwrap();
    let scattering = Scattering::new(&medium);
    let eye = DVec3::new(0.0, 1.0, 6.0);
    for target in [
        DVec3::new(0.2, 1.0, 0.4),
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(3.0, 0.0, -2.0),
        DVec3::new(-1.0, 0.5, 0.5),
    ] {
        let d = target - eye;
        let (length, direction) = (d.length(), d.normalize());
        let found = scattering
            .inscattered(light, eye, direction, &[[0.0, length]])
            .x as f64;
        let steps = 1_000_000;
        let h = length / steps as f64;
        let f = |t: f64| point_integrand(&medium, light, at, eye, direction, t);
        let mut sum = f(0.0) + f(length);
        for i in 1..steps {
            sum += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
        }
        let reference = medium.scattering() * sum * h / 3.0;
        let error = (found - reference).abs() / reference;
        assert!(
            error < 1e-4,
            "towards {target}: {found} against {reference} ({error:e})"
        );
    }
}

/// Relative RMSE of two images (over the second's mean).
fn relative_rmse(a: &Image, b: &Image) -> f64 {
    let n = a.pixels.len() as f64 * 3.0;
    let squared: f64 = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .map(|(p, q)| (*p - *q).length_squared() as f64)
        .sum();
    let mean: f64 = b
        .pixels
        .iter()
        .map(|p| (p.x + p.y + p.z) as f64)
        .sum::<f64>()
        / n;
    (squared / n).sqrt() / mean
}

/// Light volumes against ray marching on the catalogue's scenes: the difference
/// shrinks as the march's step does, and is below 1% (relative RMSE) at the fine one.
#[test]
fn light_volumes_agree_with_ray_marching() {
    for (id, coarse, fine) in [
        ("light-volumes-cornell", "12.0", "1.5"),
        ("light-volumes-spot", "0.05", "0.005"),
        ("light-volumes-blinds", "0.05", "0.01"),
    ] {
        let small = ["camera.width=64", "camera.height=48"];
        let volumes = render(&scene_with(id, &small));
        let marched = |step: &str| {
            let set = format!("medium.march_step={step}");
            let sets = [&small[..], &["medium.method=\"ray-marching\"", &set]].concat();
            relative_rmse(&volumes, &render(&scene_with(id, &sets)))
        };
        let (far, near) = (marched(coarse), marched(fine));
        eprintln!(
            "{id}: relative RMSE against ray marching {far:.5} (step {coarse}), {near:.5} (step {fine})"
        );
        assert!(near < far, "{id}: {near} at step {fine}, {far} at {coarse}");
        assert!(near < 0.01, "{id}: {near}");
    }
}

/// Putting the ball into the spot's beam never brightens a pixel, except where the
/// ball itself is seen in front of the beam.
#[test]
fn an_occluder_never_brightens_a_pixel() {
    let small = ["camera.width=64", "camera.height=48"];
    let scene = scene_with("light-volumes-spot", &small);
    let with = render(&scene);
    let ball = scene.objects.iter().position(|o| o.name == "ball").unwrap();
    let mut open = scene.clone();
    open.polygons.retain(|p| p.object != ball);
    let without = render(&open);
    let (_, surface) = visible_surface(&scene);
    let mut darker = 0;
    for (k, s) in surface.samples.iter().enumerate() {
        let on_ball = !s.is_empty() && scene.polygons[s.polygon as usize].object == ball;
        let (a, b) = (with.pixels[k], without.pixels[k]);
        if !on_ball {
            assert!(
                (a - b).max_element() <= 1e-6 * b.max_element().max(1e-3),
                "pixel {k}: {a} with the ball, {b} without"
            );
            darker += (a.max_element() < 0.99 * b.max_element()) as usize;
        }
    }
    assert!(
        darker > 50,
        "{darker} pixels darkened by the ball's shadow shaft"
    );
}

/// A purely absorbing medium: the denser, the darker everything seen through it.
#[test]
fn a_denser_absorbing_medium_never_brightens() {
    let small = ["camera.width=48", "camera.height=36", "medium.albedo=0"];
    let mut previous: Option<Vec<Vec3>> = None;
    for density in ["0.0005", "0.001", "0.002"] {
        let set = format!("medium.extinction={density}");
        let image = render(&scene_with(
            "light-volumes-cornell",
            &[&small[..], &[&set]].concat(),
        ));
        if let Some(before) = &previous {
            for (a, b) in image.pixels.iter().zip(before) {
                assert!(a.cmple(*b + Vec3::splat(1e-7)).all(), "{a} after {b}");
            }
        }
        previous = Some(image.pixels);
    }
}

/// Crow's volumes for a distant light (prisms along its travel) shadow the surfaces
/// exactly: the blinds' sunlit floor and walls equal ray casting sample for sample.
#[test]
fn under_the_sun_shadow_volumes_are_ray_casting() {
    let scene = scene_with(
        "light-volumes-blinds",
        &["camera.width=128", "camera.height=96"],
    );
    let (view, surface) = visible_surface(&scene);
    let fractions = |method| match lumiere::shadow::compute(&scene, &view, &surface, method)
        .unwrap()
        .per_light
        .remove(0)
    {
        Some(lumiere::raster::LightVisibility::Fraction(f)) => f,
        _ => panic!("a fraction"),
    };
    let crow = fractions(lumiere::settings::ShadowMethod::ShadowVolumes);
    let cast = fractions(lumiere::settings::ShadowMethod::RayCast);
    let lit = cast.iter().filter(|&&v| v == 1.0).count();
    let differing = crow.iter().zip(&cast).filter(|(a, b)| a != b).count();
    assert!(lit > 100, "{lit} sunlit samples");
    assert_eq!(differing, 0, "{differing} samples differ from ray casting");
}

/// In a box of medium the sun's light is attenuated on its way in, as a point
/// light's is. Straight down onto a level ray at height 0.5 in a box 1 high, its
/// path in the box is 0.5 everywhere: σ_s p E e^(−σ_t 0.5) (1 − e^(−σ_t L)) / σ_t
/// over the ray's length L in the box. Slanting, its path changes faces along the
/// ray: against a composite Simpson rule over the ray with the path found by the
/// slab method at each step.
#[test]
fn in_a_box_the_sun_is_attenuated_on_its_way_in() {
    let boxed = open_sun().replace(
        "[medium]\n",
        "[medium]\nextent = { min = [-5.0, 0.0, -5.0], max = [5.0, 1.0, 5.0] }\n",
    );
    let (st, min, max) = (
        0.2f64,
        DVec3::new(-5.0, 0.0, -5.0),
        DVec3::new(5.0, 1.0, 5.0),
    );
    // Straight down, in closed form.
    let scene = scene_file(
        &boxed.replace(
            "direction = [0.3, -1.0, -0.2]",
            "direction = [0.0, -1.0, 0.0]",
        ),
        &[],
    );
    let medium = scene.medium.clone().unwrap();
    let ss = medium.scattering();
    let scattering = Scattering::new(&medium);
    let (eye, direction) = (DVec3::new(-10.0, 0.5, 0.0), DVec3::X);
    let found = scattering.inscattered(&scene.lights[0], eye, direction, &[[0.0, 20.0]]);
    let p = phase(&medium, 0.0);
    let expected = Vec3::new(2.0, 3.0, 4.0)
        * (ss * p * (-st * 0.5).exp() * (1.0 - (-st * 10.0).exp()) / st) as f32;
    let error = (found - expected).abs().max_element() / expected.max_element();
    assert!(error < 1e-6, "straight down: {found} against {expected}");

    // Slanting, by quadrature.
    let scene = scene_file(&boxed, &[]);
    let medium = scene.medium.clone().unwrap();
    let scattering = Scattering::new(&medium);
    let lumiere::Light::Distant(sun) = &scene.lights[0] else {
        panic!("a distant light");
    };
    let travel = sun.direction;
    let eye = DVec3::new(-8.0, 0.9, 3.0);
    let target = DVec3::new(8.0, 0.05, -4.0);
    let length = (target - eye).length();
    let direction = (target - eye) / length;
    let found = scattering.inscattered(&scene.lights[0], eye, direction, &[[0.0, length]]);
    let inside = |x: DVec3| (0..3).all(|i| x[i] >= min[i] && x[i] <= max[i]);
    // From x back towards the sun, where the light entered the box.
    let way_in = |x: DVec3| {
        (0..3)
            .filter(|&i| travel[i] != 0.0)
            .map(|i| {
                let (a, b) = ((min[i] - x[i]) / -travel[i], (max[i] - x[i]) / -travel[i]);
                a.max(b)
            })
            .fold(f64::INFINITY, f64::min)
    };
    let steps = 400_000;
    let h = length / steps as f64;
    let entry = (0..=steps)
        .map(|i| i as f64 * h)
        .find(|&t| inside(eye + direction * t))
        .unwrap();
    let f = |t: f64| {
        let x = eye + direction * t;
        if inside(x) {
            (-st * ((t - entry) + way_in(x))).exp()
        } else {
            0.0
        }
    };
    let simpson: f64 = (0..steps / 2)
        .map(|i| {
            let t = 2.0 * i as f64 * h;
            (f(t) + 4.0 * f(t + h) + f(t + 2.0 * h)) * h / 3.0
        })
        .sum();
    let p = phase(&medium, travel.dot(-direction));
    let expected = sun.irradiance * (medium.scattering() * p * simpson) as f32;
    let error = (found - expected).abs().max_element() / expected.max_element();
    eprintln!("slanting: {found} against {expected} (relative {error:e})");
    assert!(error < 1e-4, "slanting: {found} against {expected}");
}

/// The reference march: the midpoint rule over equal steps, every step counted.
/// Under an open-sky sun, with ten steps of h = 1 it is within the midpoint rule's
/// error (about (σ_t h)²/24, 0.2%) of the closed form σ_s p E (1 − e^(−σ_t D)) / σ_t;
/// leaving a step out costs a tenth.
#[test]
fn ray_marching_counts_every_step() {
    use lumiere::media::ray_marching;
    use lumiere::scene::ray_queries::SceneRays;
    let scene = scene_file(&open_sun(), &[]);
    let medium = scene.medium.clone().unwrap();
    let lumiere::Light::Distant(sun) = &scene.lights[0] else {
        panic!("a distant light");
    };
    let rays = SceneRays::new(&[]);
    let (eye, direction, length) = (DVec3::new(0.0, 1.0, 6.0), DVec3::new(0.6, 0.0, -0.8), 10.0);
    let marched = ray_marching::inscattered(
        &medium,
        &rays,
        &scene.lights[0],
        eye,
        direction,
        length,
        length / 10.0,
        1e3,
    );
    let (st, ss) = (medium.extinction, medium.scattering());
    let p = phase(&medium, sun.direction.dot(-direction));
    let expected = sun.irradiance * (ss * p * (1.0 - (-st * length).exp()) / st) as f32;
    let error = (marched - expected).abs().max_element() / expected.max_element();
    assert!(error < 5e-3, "{marched} against {expected}: {error}");
}
