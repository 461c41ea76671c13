//! The five kinds of light: their unshadowed light against closed forms and
//! quadrature, and their sampling (for soft shadows by rays, Cook, Porter &
//! Carpenter 1984) against the exact irradiance.

use glam::{DVec2, DVec3, Vec3};
use lumiere::geometry::sampling::Stream;
use lumiere::scene::{
    DistantLight, Light, PointLight, PolygonLight, Reflectance, SphereLight, SpotDistribution,
    SpotLight,
};
use lumiere::shading::lambert_contour::projected_solid_angle;
use lumiere::shading::light_model::{SurfacePoint, reflected};
use lumiere::shading::sphere_form_factor;
use std::f64::consts::PI;

/// An L of area 3 in the plane y = 2, facing down: [0,2]×[0,1] ∪ [0,1]×[0,2] in (x, z).
fn l_shape() -> Vec<DVec3> {
    [
        (0.0, 0.0),
        (0.0, 2.0),
        (1.0, 2.0),
        (1.0, 1.0),
        (2.0, 1.0),
        (2.0, 0.0),
    ]
    .iter()
    .map(|&(x, z)| DVec3::new(x, 2.0, z))
    .collect()
}

fn l_light() -> PolygonLight {
    PolygonLight::new(l_shape(), DVec3::NEG_Y, Vec3::ONE, 0, None)
}

fn sphere_light(centre: DVec3, radius: f64) -> SphereLight {
    SphereLight {
        centre,
        radius,
        radiance: Vec3::ONE,
        name: None,
    }
}

/// Mean of weight × max(0, cos at the receiver) over an n × n jittered set.
fn estimate(light: &Light, p: DVec3, n: DVec3, side: usize, seed: u64) -> f64 {
    let points = Stream::new(seed, 0).jittered(side);
    let sum: f64 = points
        .iter()
        .filter_map(|&u| light.sample(p, u))
        .map(|s| s.weight * n.dot((s.point - p).normalize()).max(0.0))
        .sum();
    sum / points.len() as f64
}

fn inside(p: DVec3, t: [DVec3; 3]) -> bool {
    let n = (t[1] - t[0]).cross(t[2] - t[0]);
    (0..3).all(|i| (t[(i + 1) % 3] - t[i]).cross(p - t[i]).dot(n) >= -1e-12)
}

#[test]
fn polygon_samples_are_uniform_by_area() {
    let light = l_light();
    assert_eq!(light.triangles.len(), 4);
    let area = |t: &[DVec3; 3]| 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
    assert!((light.triangles.iter().map(area).sum::<f64>() - 3.0).abs() < 1e-12);
    let mut stream = Stream::new(3, 0);
    let count = 200_000;
    let mut hits = [0usize; 4];
    let mut mean = DVec3::ZERO;
    for _ in 0..count {
        let u = DVec2::new(stream.next_f64(), stream.next_f64());
        let p = light.point_at(u);
        let k = light
            .triangles
            .iter()
            .position(|t| inside(p, *t))
            .expect("a sample inside the polygon");
        hits[k] += 1;
        mean += p;
    }
    for (t, &h) in light.triangles.iter().zip(&hits) {
        let share = area(t) / 3.0;
        let fraction = h as f64 / count as f64;
        assert!((fraction - share).abs() < 0.004, "{fraction} vs {share}");
    }
    // The area centroid of the L: (2 × (1, ½) + 1 × (½, 1½)) / 3 in (x, z).
    let mean = mean / count as f64;
    let centroid = DVec3::new(2.5 / 3.0, 2.0, 2.5 / 3.0);
    assert!((mean - centroid).length() < 0.005, "{mean}");
    // Stratified: a jittered set puts the area shares in each triangle almost exactly.
    let points = Stream::new(4, 0).jittered(64);
    let mut hits = [0usize; 4];
    for &u in &points {
        let p = light.point_at(u);
        hits[light.triangles.iter().position(|t| inside(p, *t)).unwrap()] += 1;
    }
    for (t, &h) in light.triangles.iter().zip(&hits) {
        let share = area(t) / 3.0;
        assert!((h as f64 / 4096.0 - share).abs() < 2.0 / 64.0, "{h}");
    }
}

/// Root-mean-square relative error of the estimate over `seeds` jittered sets.
fn rms_error(light: &Light, p: DVec3, n: DVec3, exact: f64, side: usize) -> f64 {
    let seeds = 16;
    let sum: f64 = (0..seeds)
        .map(|seed| ((estimate(light, p, n, side, seed) - exact) / exact).powi(2))
        .sum();
    (sum / seeds as f64).sqrt()
}

fn assert_converges(name: &str, light: &Light, p: DVec3, n: DVec3, exact: f64) {
    let errors: Vec<f64> = [4, 16, 64]
        .iter()
        .map(|&side| rms_error(light, p, n, exact, side))
        .collect();
    let shown: Vec<String> = errors.iter().map(|e| format!("{e:.2e}")).collect();
    println!(
        "{name}: exact {exact:.6}, rms relative error at n = 4, 16, 64: {}",
        shown.join(", ")
    );
    assert!(
        errors[0] > errors[1] && errors[1] > errors[2],
        "{name}: {errors:?}"
    );
    assert!(errors[2] < 0.01, "{name}: {errors:?}");
}

#[test]
fn polygon_sampling_converges_to_lamberts_formula() {
    let light = l_light();
    let vertices = light.vertices.clone();
    let light = Light::Polygon(light);
    let receivers = [
        (DVec3::new(1.0, 0.0, 1.0), DVec3::Y),
        (
            DVec3::new(3.0, 0.5, -1.0),
            DVec3::new(-0.3, 1.0, 0.2).normalize(),
        ),
        // Tilted so part of the emitter lies below the receiver's horizon.
        (
            DVec3::new(0.5, 1.5, 0.5),
            DVec3::new(1.0, 0.3, 0.0).normalize(),
        ),
    ];
    for (k, (p, n)) in receivers.into_iter().enumerate() {
        let exact = projected_solid_angle(p, n, &vertices);
        assert_converges(&format!("polygon, receiver {k}"), &light, p, n, exact);
    }
    // Behind the one-sided emitter: nothing.
    assert!(
        light
            .sample(DVec3::new(1.0, 3.0, 1.0), DVec2::splat(0.5))
            .is_none()
    );
}

/// Φ of a sphere by quadrature over its surface: ∫ cos θ_r cos θ_s / d² dA over the
/// cap facing `p` (cos θ_s ≥ 0), midpoint rule in (θ, φ) about the axis to `p`.
fn sphere_quadrature(p: DVec3, n: DVec3, centre: DVec3, radius: f64, steps: usize) -> f64 {
    let axis = (p - centre).normalize();
    let (a, b) = axis.any_orthonormal_pair();
    let theta_max = (radius / (p - centre).length()).acos();
    let (dt, dp) = (theta_max / steps as f64, 2.0 * PI / (2 * steps) as f64);
    let mut sum = 0.0;
    for i in 0..steps {
        let theta = (i as f64 + 0.5) * dt;
        let (st, ct) = theta.sin_cos();
        for j in 0..2 * steps {
            let phi = (j as f64 + 0.5) * dp;
            let normal = a * (st * phi.cos()) + b * (st * phi.sin()) + axis * ct;
            let q = centre + normal * radius;
            let r = q - p;
            let r2 = r.length_squared();
            let cos_r = (n.dot(r) / r2.sqrt()).max(0.0);
            let cos_s = (-normal.dot(r) / r2.sqrt()).max(0.0);
            sum += cos_r * cos_s / r2 * radius * radius * st * dt * dp;
        }
    }
    sum
}

/// Receiver normals at angle φ from the direction to the centre (in the x-y plane).
fn tilted(phi_degrees: f64) -> DVec3 {
    let phi = phi_degrees.to_radians();
    DVec3::new(phi.sin(), phi.cos(), 0.0)
}

#[test]
fn sphere_closed_form_matches_quadrature_at_every_tilt() {
    for h in [1.2, 2.0, 10.0] {
        let centre = DVec3::new(0.0, h, 0.0);
        let alpha = (1.0 / h).asin().to_degrees();
        let mut worst: f64 = 0.0;
        for phi in [0.0, 30.0, 60.0, 75.0, 90.0, 105.0, 115.0, 130.0, 150.0] {
            let n = tilted(phi);
            let exact = sphere_form_factor::projected_solid_angle(DVec3::ZERO, n, centre, 1.0);
            let numeric = sphere_quadrature(DVec3::ZERO, n, centre, 1.0, 1000);
            if phi >= 90.0 + alpha {
                assert_eq!(exact, 0.0, "H {h}, φ {phi}");
            }
            let error = (exact - numeric).abs();
            worst = worst.max(error / exact.max(1e-12));
            assert!(
                error <= 1e-5 * exact.max(1e-3),
                "H {h}, φ {phi}: {exact} vs {numeric}"
            );
        }
        println!("sphere H = {h} (α = {alpha:.1}°): worst relative difference {worst:.1e}");
    }
}

#[test]
fn sphere_sampling_converges_to_the_closed_form() {
    let centre = DVec3::new(0.0, 2.0, 0.0);
    let light = Light::Sphere(sphere_light(centre, 1.0));
    for phi in [0.0, 45.0, 70.0, 90.0, 110.0] {
        let n = tilted(phi);
        let exact = sphere_form_factor::projected_solid_angle(DVec3::ZERO, n, centre, 1.0);
        assert_converges(
            &format!("sphere, φ = {phi}°"),
            &light,
            DVec3::ZERO,
            n,
            exact,
        );
    }
    // The points lie on the sphere, on the side facing the receiver.
    for u in Stream::new(9, 0).jittered(8) {
        let s = light.sample(DVec3::ZERO, u).unwrap();
        assert!(((s.point - centre).length() - 1.0).abs() < 1e-12);
        assert!((s.point - centre).dot(-centre) >= -1e-12);
    }
    // Inside the sphere: nothing (it emits outwards).
    assert!(light.sample(centre, DVec2::splat(0.5)).is_none());
}

/// For every kind, the light model's diffuse radiance is ρ/π times the irradiance the
/// samples estimate (exactly for the point-like kinds, to 1% at 64² for the others).
#[test]
fn samples_agree_with_the_light_model_for_every_kind() {
    let white = Reflectance {
        diffuse: Vec3::ONE,
        specular: Vec3::ZERO,
        exponent: 1.0,
    };
    let p = DVec3::new(0.7, 0.0, 0.4);
    let n = DVec3::new(0.1, 1.0, -0.2).normalize();
    let point = SurfacePoint {
        position: p,
        normal: n,
        to_eye: DVec3::Y,
    };
    let lights = [
        (
            Light::Point(PointLight {
                position: DVec3::new(0.0, 3.0, 1.0),
                intensity: Vec3::splat(5.0),
                name: None,
            }),
            5.0,
        ),
        (
            Light::Spot(SpotLight {
                position: DVec3::new(0.0, 3.0, 0.0),
                axis: DVec3::NEG_Y,
                cone_angle: 40f64.to_radians(),
                intensity: Vec3::splat(5.0),
                distribution: SpotDistribution::CosinePower(4.0),
                name: None,
            }),
            5.0,
        ),
        (
            Light::Distant(DistantLight {
                direction: DVec3::new(0.3, -1.0, 0.2).normalize(),
                irradiance: Vec3::splat(2.0),
                name: None,
            }),
            2.0,
        ),
        (Light::Polygon(l_light()), 1.0),
        (
            Light::Sphere(sphere_light(DVec3::new(-1.0, 1.5, 0.0), 0.5)),
            1.0,
        ),
    ];
    for (light, emission) in lights {
        let model = reflected(&point, &white, &light).x as f64 * PI;
        let sampled = emission * estimate(&light, p, n, 64, 1);
        let tolerance = match light {
            Light::Polygon(_) | Light::Sphere(_) => 0.01,
            _ => 1e-6,
        };
        println!("{}: model {model:.6}, sampled {sampled:.6}", light.kind());
        assert!(model > 0.0, "{}", light.kind());
        assert!(
            (model - sampled).abs() <= tolerance * model,
            "{}: {model} vs {sampled}",
            light.kind()
        );
    }
}

#[test]
fn spot_light_model() {
    let white = Reflectance {
        diffuse: Vec3::ONE,
        specular: Vec3::ZERO,
        exponent: 1.0,
    };
    let spot = |distribution| {
        Light::Spot(SpotLight {
            position: DVec3::new(0.0, 2.0, 0.0),
            axis: DVec3::NEG_Y,
            cone_angle: 30f64.to_radians(),
            intensity: Vec3::splat(PI as f32),
            distribution,
            name: None,
        })
    };
    // At angle θ from the axis on the floor: E = I f(θ) cos θ / r², r = 2 / cos θ.
    let at = |light: &Light, degrees: f64| {
        let x = 2.0 * degrees.to_radians().tan();
        let point = SurfacePoint {
            position: DVec3::new(x, 0.0, 0.0),
            normal: DVec3::Y,
            to_eye: DVec3::Y,
        };
        reflected(&point, &white, light).x as f64
    };
    let expected = |f: f64, degrees: f64| {
        let c = degrees.to_radians().cos();
        f * c * c * c / 4.0
    };
    let cosine = spot(SpotDistribution::CosinePower(3.0));
    for degrees in [0.0f64, 15.0, 29.0] {
        let f = degrees.to_radians().cos().powi(3);
        let v = at(&cosine, degrees);
        assert!((v - expected(f, degrees)).abs() < 1e-6, "{degrees}: {v}");
    }
    assert_eq!(at(&cosine, 31.0), 0.0);
    let table = spot(SpotDistribution::Table(vec![
        (0.0, 1.0),
        (20f64.to_radians(), 0.7),
        (30f64.to_radians(), 0.0),
    ]));
    for (degrees, f) in [(0.0, 1.0), (10.0, 0.85), (20.0, 0.7), (25.0, 0.35)] {
        let v = at(&table, degrees);
        assert!((v - expected(f, degrees)).abs() < 1e-6, "{degrees}: {v}");
    }
    assert_eq!(at(&table, 35.0), 0.0);
}

#[test]
fn distant_light_model() {
    let white = Reflectance {
        diffuse: Vec3::ONE,
        specular: Vec3::ZERO,
        exponent: 1.0,
    };
    let light = Light::Distant(DistantLight {
        direction: DVec3::NEG_Y,
        irradiance: Vec3::splat(PI as f32),
        name: None,
    });
    for degrees in [0.0, 30.0, 60.0, 89.0, 91.0, 180.0] {
        let point = SurfacePoint {
            position: DVec3::new(5.0, -3.0, 2.0),
            normal: tilted(degrees),
            to_eye: DVec3::Y,
        };
        let v = reflected(&point, &white, &light).x as f64;
        let expected = degrees.to_radians().cos().max(0.0);
        assert!((v - expected).abs() < 1e-6, "{degrees}: {v}");
    }
}

/// The specular albedo of Phong's normalised lobe, ∫ f_s cos θ_o dω_o over the
/// hemisphere as a fraction of k_s, for light arriving at `incidence` degrees from
/// the normal: by the midpoint
/// rule in (θ_o, φ_o), each direction's radiance taken from the light model under a
/// distant light of unit irradiance.
fn specular_albedo(exponent: f32, incidence: f64) -> f64 {
    let gloss = Reflectance {
        diffuse: Vec3::ZERO,
        specular: Vec3::splat(0.5),
        exponent,
    };
    let light = Light::Distant(DistantLight {
        direction: -tilted(incidence),
        irradiance: Vec3::ONE,
        name: None,
    });
    let cos_incidence = incidence.to_radians().cos();
    let (steps, turns) = (2000, 400);
    let (dt, dp) = (PI / 2.0 / steps as f64, 2.0 * PI / turns as f64);
    let mut sum = 0.0;
    for i in 0..steps {
        let theta = (i as f64 + 0.5) * dt;
        let (st, ct) = theta.sin_cos();
        for j in 0..turns {
            let phi = (j as f64 + 0.5) * dp;
            let point = SurfacePoint {
                position: DVec3::ZERO,
                normal: DVec3::Y,
                to_eye: DVec3::new(st * phi.cos(), ct, st * phi.sin()),
            };
            // Radiance = f_s · E cos θ_i: divide out the incident cosine.
            let f = reflected(&point, &gloss, &light).x as f64 / cos_incidence;
            sum += f * ct * st * dt * dp;
        }
    }
    sum / 0.5
}

/// Phong's lobe normalised by (e + 2)/(2π) reflects exactly k_s of the light that
/// arrives along the normal, whatever the exponent, and less at oblique incidence
/// (part of the lobe falls below the horizon): the material never reflects more
/// than it receives.
#[test]
fn the_normalised_phong_lobe_reflects_k_s_at_normal_incidence() {
    for e in [1.0, 5.0, 20.0, 100.0] {
        let (albedo, oblique) = (specular_albedo(e, 0.0), specular_albedo(e, 60.0));
        println!("exponent {e}: specular albedo {albedo:.6} of k_s, {oblique:.6} at 60°");
        assert!((albedo - 1.0).abs() < 1e-5, "exponent {e}: {albedo}");
        assert!(oblique < 1.0, "exponent {e} at 60°: {oblique}");
    }
}
