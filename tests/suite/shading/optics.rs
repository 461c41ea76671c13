//! Phase functions and Fresnel's reflectance against oracles that share nothing
//! with the code: quadrature over the sphere written here, textbook values, and the
//! transmitted power computed from the transmitted amplitudes.

use lumiere::media::single_scattering::phase;
use lumiere::settings::{MediumMethod, MediumSettings, PhaseFunction};
use lumiere::shading::optics::{fresnel, schlick};
use std::f64::consts::PI;

fn medium(phase: PhaseFunction, g: f64) -> MediumSettings {
    MediumSettings {
        extinction: 1.0,
        albedo: 1.0,
        phase,
        g,
        extent: None,
        method: MediumMethod::RayMarching,
        nodes: 8,
        march_step: 0.1,
        max_march_steps: 1e9,
    }
}

/// ∫ f(cos θ) dω over the sphere: 2π ∫₋₁¹ f(μ) dμ by composite Simpson in μ.
fn over_sphere(f: impl Fn(f64) -> f64) -> f64 {
    let n = 200_000;
    let h = 2.0 / n as f64;
    let sum: f64 = (0..=n)
        .map(|k| {
            let w = if k == 0 || k == n {
                1.0
            } else if k % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * f(-1.0 + k as f64 * h)
        })
        .sum();
    2.0 * PI * sum * h / 3.0
}

/// Every phase function is a probability density over the sphere (integrates to
/// 1), and Henyey–Greenstein's mean cosine is its g (Rayleigh's and the isotropic
/// one's is 0).
#[test]
fn phase_functions_are_densities_with_their_mean_cosines() {
    let cases = [
        (PhaseFunction::Isotropic, 0.0, 0.0),
        (PhaseFunction::Rayleigh, 0.0, 0.0),
        (PhaseFunction::HenyeyGreenstein, 0.0, 0.0),
        (PhaseFunction::HenyeyGreenstein, 0.3, 0.3),
        (PhaseFunction::HenyeyGreenstein, -0.6, -0.6),
        (PhaseFunction::HenyeyGreenstein, 0.9, 0.9),
    ];
    for (kind, g, mean) in cases {
        let m = medium(kind, g);
        let total = over_sphere(|mu| phase(&m, mu));
        assert!((total - 1.0).abs() < 1e-6, "{kind:?} g = {g}: ∫ = {total}");
        let mean_cosine = over_sphere(|mu| mu * phase(&m, mu));
        assert!(
            (mean_cosine - mean).abs() < 1e-6,
            "{kind:?} g = {g}: mean cosine {mean_cosine}"
        );
    }
}

/// The closed forms at tabulated angles: Rayleigh 3/(16π)(1 + cos²θ) is 3/(8π) =
/// 0.119366… forward and backward and 3/(16π) = 0.059683… at 90°; Henyey–Greenstein
/// with g = 0.5 is 0.75/(4π · 0.125) = 0.477465 forward and 0.75/(4π · 3.375) =
/// 0.017684 backward and 0.75/(4π · 1.25^1.5) = 0.042706 at 90°; the isotropic
/// one 1/(4π) = 0.0795775.
#[test]
fn phase_functions_match_their_tabulated_values() {
    let table = [
        (PhaseFunction::Rayleigh, 0.0, 1.0, 0.119_366_207_3),
        (PhaseFunction::Rayleigh, 0.0, -1.0, 0.119_366_207_3),
        (PhaseFunction::Rayleigh, 0.0, 0.0, 0.059_683_103_7),
        (PhaseFunction::HenyeyGreenstein, 0.5, 1.0, 0.477_464_829_3),
        (PhaseFunction::HenyeyGreenstein, 0.5, -1.0, 0.017_683_882_6),
        (PhaseFunction::HenyeyGreenstein, 0.5, 0.0, 0.042_705_752_6),
        (PhaseFunction::Isotropic, 0.0, 0.3, 0.079_577_471_5),
    ];
    for (kind, g, cos_theta, expected) in table {
        let got = phase(&medium(kind, g), cos_theta);
        assert!(
            (got - expected).abs() < 1e-9,
            "{kind:?} g = {g} at cos θ = {cos_theta}: {got}, table {expected}"
        );
    }
}

/// Fresnel's reflectance against the textbook's figures: 4.0 % for glass (n = 1.5)
/// and 2.04 % for water (n = 1.333) at normal incidence, from either side; total
/// reflection past the critical angle from inside (41.81° for glass, 48.61° for
/// water) and none just before it; 1 at grazing incidence.
#[test]
fn fresnel_matches_the_textbook_figures() {
    let at = |degrees: f64| degrees.to_radians().cos();
    let table = [
        (1.0, 1.5, 0.0, 0.04),
        (1.5, 1.0, 0.0, 0.04),
        (1.0, 1.333, 0.0, 0.020_37),
        (1.5, 1.0, 41.9, 1.0),
        (1.333, 1.0, 48.7, 1.0),
        (1.0, 1.5, 90.0, 1.0),
    ];
    for (eta1, eta2, degrees, expected) in table {
        let got = fresnel(at(degrees), eta1, eta2);
        assert!(
            (got - expected).abs() < 5e-5,
            "{eta1} → {eta2} at {degrees}°: {got}, table {expected}"
        );
    }
    assert!(fresnel(at(41.7), 1.5, 1.0) < 1.0);
    assert!(fresnel(at(48.5), 1.333, 1.0) < 1.0);
}

/// Between those, Fresnel's own sine and tangent laws, R_s = sin²(θ₁ − θ₂) /
/// sin²(θ₁ + θ₂) and R_p = tan²(θ₁ − θ₂) / tan²(θ₁ + θ₂), written with the angles
/// rather than the cosines; R_p vanishes at Brewster's angle, atan(η₂/η₁) (56.31°
/// for glass), leaving half of R_s.
#[test]
fn fresnel_follows_the_sine_and_tangent_laws() {
    for (eta1, eta2) in [(1.0, 1.5), (1.5, 1.0), (1.0, 1.333), (1.0, 2.4)] {
        for k in 1..90 {
            let theta1 = (k as f64).to_radians();
            let sin2 = eta1 / eta2 * theta1.sin();
            if sin2 >= 1.0 {
                continue;
            }
            let theta2 = sin2.asin();
            let rs = ((theta1 - theta2).sin() / (theta1 + theta2).sin()).powi(2);
            let rp = ((theta1 - theta2).tan() / (theta1 + theta2).tan()).powi(2);
            let got = fresnel(theta1.cos(), eta1, eta2);
            assert!(
                (got - 0.5 * (rs + rp)).abs() < 1e-12,
                "{eta1} → {eta2} at {k}°: {got} against {}",
                0.5 * (rs + rp)
            );
        }
    }
    let brewster = 1.5f64.atan();
    let theta2 = (brewster.sin() / 1.5).asin();
    let rs = ((brewster - theta2).sin() / (brewster + theta2).sin()).powi(2);
    assert!((fresnel(brewster.cos(), 1.0, 1.5) - 0.5 * rs).abs() < 1e-12);
}

/// Reflected and transmitted power add up to the incident: T computed here from
/// the transmitted amplitudes (t_s = 2η₁cos θ₁ / (η₁cos θ₁ + η₂cos θ₂), t_p =
/// 2η₁cos θ₁ / (η₂cos θ₁ + η₁cos θ₂), each power scaled by η₂cos θ₂ / η₁cos θ₁),
/// not as 1 − F.
#[test]
fn fresnel_reflected_and_transmitted_power_add_up() {
    for (eta1, eta2) in [
        (1.0, 1.5),
        (1.5, 1.0),
        (1.0, 1.333),
        (1.333, 1.0),
        (1.0, 2.4),
    ] {
        for k in 0..90 {
            let theta1 = (k as f64).to_radians();
            let sin2 = eta1 / eta2 * theta1.sin();
            if sin2 >= 1.0 {
                continue;
            }
            let (c1, c2) = (theta1.cos(), (1.0 - sin2 * sin2).sqrt());
            let ts = 2.0 * eta1 * c1 / (eta1 * c1 + eta2 * c2);
            let tp = 2.0 * eta1 * c1 / (eta2 * c1 + eta1 * c2);
            let scale = eta2 * c2 / (eta1 * c1);
            let transmitted = 0.5 * scale * (ts * ts + tp * tp);
            let reflected = fresnel(c1, eta1, eta2);
            assert!(
                (reflected + transmitted - 1.0).abs() < 1e-12,
                "{eta1} → {eta2} at {k}°: R {reflected} + T {transmitted}"
            );
        }
    }
}

/// Schlick's approximation: exact at normal and at grazing incidence, and close to
/// Fresnel's reflectance for glass from air between: the largest gap below 80° is
/// 0.0196, at 62°, and 0.036 at 85° (computed from the two formulas written out;
/// an exponent of 4 instead of 5, or F₀ from (η₁ − η₂)/η₂, lands far outside).
#[test]
fn schlick_stays_near_fresnel_for_glass() {
    for k in 0..=90 {
        let c = (k as f64).to_radians().cos();
        let (exact, approximate) = (fresnel(c, 1.0, 1.5), schlick(c, 1.0, 1.5));
        let bound = if k < 80 { 0.02 } else { 0.036 };
        assert!(
            (exact - approximate).abs() < bound,
            "{k}°: Fresnel {exact}, Schlick {approximate}"
        );
    }
    assert!((schlick(1.0, 1.0, 1.5) - 0.04).abs() < 1e-15);
    assert_eq!(schlick(0.0, 1.0, 1.5), 1.0);
}

/// The latitude-longitude map at latitudes away from the equator and the poles,
/// against the course's formula written out here for a world direction of
/// elevation e and azimuth a (measured from −z towards +x): (cos e sin a, sin e,
/// −cos e cos a) is at u = (1 − a/π)/2, v = (1 + sin e)/2. Then at the centres of an
/// 8 × 4 map's texels, the direction is that formula's inverse.
#[test]
fn latitude_longitude_follows_the_course_formula() {
    use glam::{DVec2, DVec3};
    use lumiere::texture::environment::lat_long;
    let world = |e: f64, a: f64| {
        let (e, a) = (e.to_radians(), a.to_radians());
        DVec3::new(e.cos() * a.sin(), e.sin(), -e.cos() * a.cos())
    };
    let table = [
        (30.0, 45.0, 0.375, 0.75),
        (-60.0, -120.0, 0.833_333_333_3, 0.066_987_298_1),
        (10.0, 170.0, 0.027_777_777_8, 0.586_824_088_8),
        (75.0, -10.0, 0.527_777_777_8, 0.982_962_913_1),
    ];
    for (e, a, u, v) in table {
        let got = lat_long::uv(world(e, a));
        assert!(
            (got - DVec2::new(u, v)).abs().max_element() < 1e-9,
            "e = {e}°, a = {a}°: {got}, formula ({u}, {v})"
        );
    }
    let (width, height) = (8, 4);
    for row in 0..height {
        for column in 0..width {
            let u = (column as f64 + 0.5) / width as f64;
            let v = (row as f64 + 0.5) / height as f64;
            let e = (2.0 * v - 1.0).asin().to_degrees();
            let a = 180.0 * (1.0 - 2.0 * u);
            let expected = world(e, a);
            let got = lat_long::direction(DVec2::new(u, v));
            assert!(
                (got - expected).length() < 1e-12,
                "texel ({column}, {row}): {got} against {expected}"
            );
        }
    }
}

/// A footprint's step in the latitude-longitude map is the longitude difference the
/// short way round: a hundredth of a turn either way, in the middle of the map or
/// across its seam, is ±0.01 in u (never 0.99).
#[test]
fn latitude_longitude_steps_go_the_short_way_round() {
    use glam::DVec2;
    use lumiere::texture::environment::lat_long::{direction, uv_step};
    for (from, to) in [(0.50, 0.49), (0.50, 0.51), (0.995, 0.005), (0.005, 0.995)] {
        let d = direction(DVec2::new(from, 0.4));
        let offset = direction(DVec2::new(to, 0.4)) - d;
        let step = uv_step(d, offset);
        let expected = (to - from + 0.5f64).rem_euclid(1.0) - 0.5;
        assert!(
            (step.x - expected).abs() < 1e-9 && step.y.abs() < 1e-9,
            "from u = {from} to {to}: {step}, expected {expected}"
        );
    }
}
