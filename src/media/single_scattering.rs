//! Single scattering in a homogeneous medium along a viewing ray: N. L. Max,
//! "Atmospheric illumination and shadows", SIGGRAPH '86; for spot lights T. Nishita,
//! Y. Miyawaki, E. Nakamae, "A shading model for atmospheric scattering considering
//! luminous intensity distribution of light sources", SIGGRAPH '87 21(4):303–310.
//!
//! Along the ray x(t) = eye + t ω, the radiance reaching the eye is the surface's
//! radiance times the transmittance e^(−σ_t D) plus the light scattered towards the
//! eye on the way:
//!
//!   L_s = ∫ σ_s p(θ(t)) E(t) e^(−σ_t t) dt over the lit parts of [0, D],
//!
//! E(t) the light's irradiance at x(t) on a surface facing it, θ the angle between
//! the light's travel and the direction towards the eye. Distances in the medium
//! count only inside its extent (a box, or everywhere).
//!
//! - Distant light: θ is constant, and E is the sun's irradiance attenuated on its
//!   way through the medium to x(t), as a point light's is: inside a box, along its
//!   path s(t) from where it entered the box. s(t) is the least of three linear
//!   functions of t (the distances back to the faces the light comes in by), so
//!   e^(−σ_t ((t − entry) + s(t))) is an exponential of a linear function between
//!   the t where the least changes, each piece integrated in closed form. A medium
//!   filling all space leaves the sun unattenuated (Max's convention: on an infinite
//!   way in it would absorb it all), so there L_s = σ_s p E (e^(−σ_t a) −
//!   e^(−σ_t b)) / σ_t over each lit interval [a, b].
//! - Point and spot lights: E(t) = I f(θ_spot) e^(−σ_t r_m) / r², r the distance to
//!   the light and r_m its part inside the medium; a spot's cone bounds the lit parts
//!   too (the cone's intervals on the ray, from its quadric). The integral is taken by
//!   Gauss–Legendre quadrature (`nodes` points) on pieces of each lit interval: cut at
//!   the ray's closest approach to the light, then in lengths growing geometrically
//!   from the closest-approach distance h (the integrand falls as 1/(h² + s²) there).

use crate::scene::{Light, Reach};
use crate::settings::{MediumSettings, PhaseFunction};
use glam::{DVec3, Vec3};
use std::f64::consts::PI;

/// The phase function at cos θ, θ the angle between the light's travel and the
/// direction scattered towards the eye.
pub fn phase(medium: &MediumSettings, cos_theta: f64) -> f64 {
    match medium.phase {
        PhaseFunction::Isotropic => 1.0 / (4.0 * PI),
        PhaseFunction::Rayleigh => 3.0 / (16.0 * PI) * (1.0 + cos_theta * cos_theta),
        PhaseFunction::HenyeyGreenstein => {
            let g = medium.g;
            (1.0 - g * g) / (4.0 * PI * (1.0 + g * g - 2.0 * g * cos_theta).powf(1.5))
        }
    }
}

/// The part [t0, t1] of the ray origin + t·direction (unit) inside the medium,
/// within [lo, hi]; `None` when it misses.
pub fn inside(
    medium: &MediumSettings,
    origin: DVec3,
    direction: DVec3,
    lo: f64,
    hi: f64,
) -> Option<(f64, f64)> {
    let Some((min, max)) = medium.extent else {
        return (lo < hi).then_some((lo, hi));
    };
    let (mut t0, mut t1) = (lo, hi);
    for axis in 0..3 {
        let (o, d) = (origin[axis], direction[axis]);
        if d == 0.0 {
            if o < min[axis] || o > max[axis] {
                return None;
            }
            continue;
        }
        let (a, b) = ((min[axis] - o) / d, (max[axis] - o) / d);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    (t0 < t1).then_some((t0, t1))
}

/// Whether point `x` is in the medium.
pub fn holds(medium: &MediumSettings, x: DVec3) -> bool {
    medium
        .extent
        .is_none_or(|(min, max)| (0..3).all(|i| x[i] >= min[i] && x[i] <= max[i]))
}

/// The length of [0, t] of the ray inside the medium.
fn medium_length(medium: &MediumSettings, origin: DVec3, direction: DVec3, t: f64) -> f64 {
    inside(medium, origin, direction, 0.0, t).map_or(0.0, |(a, b)| b - a)
}

/// How far the sun's light, travelling along `travel` (unit), has gone through the
/// medium to reach `x`: from where it entered the box; 0 in a medium filling all
/// space (see the module's account).
pub fn sun_path(medium: &MediumSettings, x: DVec3, travel: DVec3) -> f64 {
    if medium.extent.is_none() {
        return 0.0;
    }
    medium_length(medium, x, -travel, f64::INFINITY)
}

/// ∫ e^(−σ_t ((t − entry) + s(t))) dt over [a, b] (inside the box), s(t) the sun's
/// path to eye + t·direction: s = min over the axes the light crosses of A_i + B_i t,
/// linear between the t where two of them meet.
fn sunlit_integral(
    medium: &MediumSettings,
    eye: DVec3,
    direction: DVec3,
    travel: DVec3,
    (a, b): (f64, f64),
    entry: f64,
) -> f64 {
    let k = medium.extinction;
    let Some((min, max)) = medium.extent else {
        return if k > 0.0 {
            ((-k * (a - entry)).exp() - (-k * (b - entry)).exp()) / k
        } else {
            b - a
        };
    };
    if k == 0.0 {
        return b - a;
    }
    // Back towards the sun, w = −travel: the face of axis i the light came in by.
    // At most three lines and three crossings: fixed arrays, no allocation per
    // viewing ray.
    let (mut lines, mut n) = ([(0.0, 0.0); 3], 0);
    for i in (0..3).filter(|&i| travel[i] != 0.0) {
        let w = -travel[i];
        let face = if w > 0.0 { max[i] } else { min[i] };
        lines[n] = ((face - eye[i]) / w, -direction[i] / w);
        n += 1;
    }
    let lines = &lines[..n];
    let (mut cuts, mut m) = ([a, b, 0.0, 0.0, 0.0], 2);
    for (i, &(ai, bi)) in lines.iter().enumerate() {
        for &(aj, bj) in &lines[i + 1..] {
            if bi != bj {
                let t = (aj - ai) / (bi - bj);
                if t > a && t < b {
                    cuts[m] = t;
                    m += 1;
                }
            }
        }
    }
    let cuts = &mut cuts[..m];
    cuts.sort_by(f64::total_cmp);
    let mut total = 0.0;
    for piece in cuts.windows(2) {
        let (p, q) = (piece[0], piece[1]);
        let middle = 0.5 * (p + q);
        let (line_a, line_b) = lines
            .iter()
            .copied()
            .min_by(|x, y| (x.0 + x.1 * middle).total_cmp(&(y.0 + y.1 * middle)))
            .unwrap_or((0.0, 0.0));
        // e^(−k((t − entry) + A + B t)) from p to q.
        let rate = k * (1.0 + line_b);
        let start = (-k * (p - entry + line_a + line_b * p)).exp();
        total += if rate.abs() * (q - p) > 1e-12 {
            start * -(-rate * (q - p)).exp_m1() / rate
        } else {
            start * (q - p)
        };
    }
    total
}

/// The transmittance of the first `distance` of the ray.
pub fn transmittance(
    medium: &MediumSettings,
    origin: DVec3,
    direction: DVec3,
    distance: f64,
) -> f64 {
    (-medium.extinction * medium_length(medium, origin, direction, distance)).exp()
}

/// A medium with its quadrature rule.
pub struct Scattering<'a> {
    pub medium: &'a MediumSettings,
    rule: (Vec<f64>, Vec<f64>),
}

impl<'a> Scattering<'a> {
    pub fn new(medium: &'a MediumSettings) -> Scattering<'a> {
        Scattering {
            medium,
            rule: gauss_legendre(medium.nodes),
        }
    }

    /// The light scattered towards the eye from `light` along the ray eye +
    /// t·direction (unit) over its lit intervals (already cut to the ray's visible
    /// length).
    pub fn inscattered(
        &self,
        light: &Light,
        eye: DVec3,
        direction: DVec3,
        lit: &[[f64; 2]],
    ) -> Vec3 {
        inscattered(self.medium, &self.rule, light, eye, direction, lit)
    }
}

fn inscattered(
    medium: &MediumSettings,
    rule: &(Vec<f64>, Vec<f64>),
    light: &Light,
    eye: DVec3,
    direction: DVec3,
    lit: &[[f64; 2]],
) -> Vec3 {
    let sigma_s = medium.scattering();
    if sigma_s == 0.0 {
        return Vec3::ZERO;
    }
    let mut total = 0.0;
    let colour = match light.reach() {
        Reach::Direction {
            direction: sun,
            irradiance,
        } => {
            let p = phase(medium, sun.dot(-direction));
            for &[a, b] in lit {
                if let Some((a, b)) = inside(medium, eye, direction, a, b) {
                    // Entry: where the ray enters the medium.
                    let entry = inside(medium, eye, direction, 0.0, b).map_or(0.0, |(e, _)| e);
                    total += sunlit_integral(medium, eye, direction, sun, (a, b), entry);
                }
            }
            total *= sigma_s * p;
            irradiance
        }
        Reach::Point { at, intensity } => {
            for &[a, b] in lit {
                let Some((a, b)) = inside(medium, eye, direction, a, b) else {
                    continue;
                };
                for (a, b) in within_cone(light, eye, direction, a, b) {
                    total += integrate(a, b, eye, direction, at, rule, |t| {
                        point_integrand(medium, light, at, eye, direction, t)
                    });
                }
            }
            total *= sigma_s;
            intensity
        }
        Reach::Extended { .. } => return Vec3::ZERO,
    };
    colour * total as f32
}

/// The integrand but σ_s and the light's colour, at distance t along the ray.
pub fn point_integrand(
    medium: &MediumSettings,
    light: &Light,
    at: DVec3,
    eye: DVec3,
    direction: DVec3,
    t: f64,
) -> f64 {
    let x = eye + direction * t;
    let to_light = at - x;
    let r2 = to_light.length_squared();
    if r2 == 0.0 {
        return 0.0;
    }
    let r = r2.sqrt();
    let travel = -to_light / r;
    let spot = light.cone_factor(x);
    let towards_light = medium_length(medium, x, to_light / r, r);
    let along_ray = medium_length(medium, eye, direction, t);
    phase(medium, travel.dot(-direction))
        * spot
        * (-medium.extinction * (towards_light + along_ray)).exp()
        / r2
}

/// The parts of [a, b] of the ray inside a spot light's cone (all of it for a point
/// light): the interval cut at the roots of the cone's quadric and of its apex plane,
/// each piece kept when its middle is inside.
fn within_cone(light: &Light, eye: DVec3, direction: DVec3, a: f64, b: f64) -> Vec<(f64, f64)> {
    let Light::Spot(spot) = light else {
        return vec![(a, b)];
    };
    let o = eye - spot.position;
    let (axis, c2) = (spot.axis, spot.cone_angle.cos().powi(2));
    let (oa, da) = (o.dot(axis), direction.dot(axis));
    // (o·A + t d·A)² − cos²α |o + t d|² = 0
    let q2 = da * da - c2;
    let q1 = 2.0 * (oa * da - c2 * o.dot(direction));
    let q0 = oa * oa - c2 * o.length_squared();
    let mut cuts = vec![a, b];
    if q2.abs() > 1e-15 {
        let disc = q1 * q1 - 4.0 * q2 * q0;
        if disc >= 0.0 {
            let root = disc.sqrt();
            cuts.extend([(-q1 - root) / (2.0 * q2), (-q1 + root) / (2.0 * q2)]);
        }
    } else if q1 != 0.0 {
        cuts.push(-q0 / q1);
    }
    if da != 0.0 {
        cuts.push(-oa / da);
    }
    cuts.retain(|t| *t >= a && *t <= b);
    cuts.sort_by(f64::total_cmp);
    let inside_cone = |t: f64| {
        let v = o + direction * t;
        let along = v.dot(axis);
        along > 0.0 && along * along >= c2 * v.length_squared()
    };
    cuts.windows(2)
        .filter(|w| w[1] > w[0] && inside_cone(0.5 * (w[0] + w[1])))
        .map(|w| (w[0], w[1]))
        .collect()
}

/// ∫ f over [a, b] by Gauss–Legendre on pieces: cut at the ray's closest approach to
/// `light`, then at distances h, 2h, 4h … from it (h the closest distance, at least
/// a millionth of the interval).
pub fn integrate(
    a: f64,
    b: f64,
    eye: DVec3,
    direction: DVec3,
    light: DVec3,
    rule: &(Vec<f64>, Vec<f64>),
    f: impl Fn(f64) -> f64,
) -> f64 {
    let closest = (light - eye).dot(direction);
    let h = ((light - eye) - direction * closest)
        .length()
        .max(1e-6 * (b - a));
    let mut cuts = vec![a, b];
    if closest > a && closest < b {
        cuts.push(closest);
    }
    let mut step = h;
    while step < (b - a) {
        for t in [closest - step, closest + step] {
            if t > a && t < b {
                cuts.push(t);
            }
        }
        step *= 2.0;
    }
    cuts.sort_by(f64::total_cmp);
    let (x, w) = rule;
    cuts.windows(2)
        .map(|piece| {
            let (lo, hi) = (piece[0], piece[1]);
            let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            x.iter()
                .zip(w)
                .map(|(xi, wi)| wi * f(mid + half * xi))
                .sum::<f64>()
                * half
        })
        .sum()
}

/// Gauss–Legendre nodes and weights on [−1, 1]: the roots of P_n by Newton's method
/// from Chebyshev's estimates, weights 2 / ((1 − x²) P_n'(x)²).
pub fn gauss_legendre(n: u32) -> (Vec<f64>, Vec<f64>) {
    let n = n.max(1) as usize;
    let (mut xs, mut ws) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for i in 0..n {
        let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut derivative = 0.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let (pn, pn1) = if n == 1 { (x, 1.0) } else { (p1, p0) };
            derivative = n as f64 * (x * pn - pn1) / (x * x - 1.0);
            if n == 1 {
                derivative = 1.0;
            }
            let dx = pn / derivative;
            x -= dx;
            if dx.abs() < 1e-15 {
                break;
            }
        }
        xs.push(x);
        ws.push(2.0 / ((1.0 - x * x) * derivative * derivative));
    }
    (xs, ws)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        for n in [1u32, 2, 5, 8, 16] {
            let (x, w) = gauss_legendre(n);
            assert!((w.iter().sum::<f64>() - 2.0).abs() < 1e-12, "{n}");
            // Exact for degree 2n − 1: ∫ x^(2n−2) = 2 / (2n − 1).
            let k = 2 * n as i32 - 2;
            let integral: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(k)).sum();
            assert!(
                (integral - 2.0 / (k as f64 + 1.0)).abs() < 1e-12,
                "{n}: {integral}"
            );
        }
    }
}
