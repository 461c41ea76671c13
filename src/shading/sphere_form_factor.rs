//! Irradiance from a uniform Lambertian sphere, exactly, on a tilted receiver: the
//! form factor from a differential planar element to a sphere.
//!
//! J. R. Howell, *A Catalog of Radiation Heat Transfer Configuration Factors*
//! (section B, factors from differential elements to finite areas: "differential
//! planar element to sphere", element tilted; also in Siegel & Howell, *Thermal
//! Radiation Heat Transfer*). With H = d/r (d the distance from the element to the
//! sphere's centre, r the radius) and φ the angle between the element's normal and
//! the direction to the centre, the sphere subtends a cone of half-angle α,
//! sin α = 1/H, and
//!
//! - wholly above the element's horizon (φ ≤ π/2 − α): F = cos φ / H²;
//! - wholly below (φ ≥ π/2 + α): F = 0;
//! - across the horizon, with X = √(H² − 1) and Y = −X cot φ, F is given below.
//!
//! ```text
//! F = ½ − (1/π) sin⁻¹(X / (H sin φ)) + 1/(π H²) [cos φ cos⁻¹ Y − X √(1 − H² cos² φ)]
//! ```
//!
//! The three pieces meet continuously at φ = π/2 ∓ α. The irradiance is E = π L F
//! for a sphere of radiance L. The formula is checked against quadrature over the
//! sphere in tests/suite/shading/lights.rs.

use std::f64::consts::PI;

/// F from a planar element to a sphere: `h` = distance to the centre over the
/// radius, `cos_phi` = cosine of the angle between the element's unit normal and
/// the direction to the centre. An element inside the sphere (h ≤ 1) gets nothing:
/// the sphere emits outwards.
pub fn form_factor(h: f64, cos_phi: f64) -> f64 {
    if h <= 1.0 {
        return 0.0;
    }
    let sin_alpha = 1.0 / h;
    if cos_phi >= sin_alpha {
        return cos_phi / (h * h);
    }
    if cos_phi <= -sin_alpha {
        return 0.0;
    }
    let sin_phi = (1.0 - cos_phi * cos_phi).max(0.0).sqrt();
    let x = (h * h - 1.0).sqrt();
    let y = -x * cos_phi / sin_phi;
    let f = 0.5 - (x / (h * sin_phi)).clamp(-1.0, 1.0).asin() / PI
        + (cos_phi * y.clamp(-1.0, 1.0).acos()
            - x * (1.0 - h * h * cos_phi * cos_phi).max(0.0).sqrt())
            / (PI * h * h);
    f.max(0.0)
}

/// Φ = π F, the cosine-weighted solid angle of a sphere (`centre`, `radius`) seen
/// from `p` with unit normal `n`; the irradiance is L Φ.
pub fn projected_solid_angle(
    p: glam::DVec3,
    n: glam::DVec3,
    centre: glam::DVec3,
    radius: f64,
) -> f64 {
    let d = centre - p;
    let distance = d.length();
    if distance <= radius {
        return 0.0;
    }
    PI * form_factor(distance / radius, n.dot(d) / distance)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pieces_meet_at_the_horizon() {
        for h in [1.01, 1.5, 3.0, 20.0] {
            let s: f64 = 1.0 / h;
            for c in [s, -s] {
                let eps = 1e-9;
                let (a, b) = (form_factor(h, c - eps), form_factor(h, c + eps));
                assert!((a - b).abs() < 1e-6, "h {h}, cos {c}: {a} vs {b}");
            }
        }
    }

    #[test]
    fn a_sphere_on_the_horizon_sends_little() {
        // φ = π/2: half the sphere above the plane; F ≈ 2/(3π H³) far away.
        let h = 100.0;
        let f = form_factor(h, 0.0);
        assert!(
            (f / (2.0 / (3.0 * PI * h * h * h)) - 1.0).abs() < 1e-3,
            "{f}"
        );
    }
}
