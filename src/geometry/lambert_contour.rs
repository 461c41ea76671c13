//! Irradiance from a uniform Lambertian polygon, exactly: Lambert's contour formula.
//!
//! J. H. Lambert, *Photometria*, 1760; in graphics form: D. R. Baum, H. E. Rushmeier,
//! J. M. Winget, "Improving radiosity solutions through the use of analytically
//! determined form-factors", SIGGRAPH '89. For a polygon of radiance L seen from a
//! point p with unit normal n, the irradiance is E = L · Φ with the projected solid
//! angle
//!
//!   Φ = ½ Σᵢ θᵢ (Γᵢ · n),   Γᵢ = (rᵢ × rᵢ₊₁)/|rᵢ × rᵢ₊₁|,  θᵢ = ∠(rᵢ, rᵢ₊₁),
//!
//! rᵢ = vᵢ − p. The formula holds for a polygon wholly above p's tangent plane, so the
//! polygon is first clipped to that half-space (Sutherland–Hodgman). Φ/π is the
//! point-to-polygon form factor. The sign of the sum follows the polygon's winding as
//! seen from p; its magnitude is taken.

use crate::geometry::sutherland_hodgman::clip;
use glam::DVec3;

/// Φ, the cosine-weighted solid angle of `polygon` seen from `p` with unit normal `n`
/// (π for a polygon covering the whole hemisphere).
pub fn projected_solid_angle(p: DVec3, n: DVec3, polygon: &[DVec3]) -> f64 {
    let above = |v: &DVec3| (*v - p).dot(n);
    let clipped;
    let vertices = if polygon.iter().all(|v| above(v) >= 0.0) {
        polygon
    } else {
        clipped = clip(polygon, above);
        &clipped[..]
    };
    if vertices.len() < 3 {
        return 0.0;
    }
    // θᵢ = atan2(|rᵢ × rᵢ₊₁|, rᵢ · rᵢ₊₁) needs no unit vectors: both arguments scale
    // by |rᵢ| |rᵢ₊₁|, and Γᵢ is the normalised cross product either way. The angles
    // are taken four edges at a time (SIMD); padding edges have θ = atan2(0, 1) = 0.
    let count = vertices.len();
    let mut sum = 0.0;
    for chunk in (0..count).step_by(4) {
        let (mut sines, mut cosines, mut weights) = ([0.0; 4], [1.0; 4], [0.0; 4]);
        for lane in 0..4.min(count - chunk) {
            let i = chunk + lane;
            let (a, b) = (vertices[i] - p, vertices[(i + 1) % count] - p);
            let cross = a.cross(b);
            let sine = cross.length();
            if sine > 0.0 {
                sines[lane] = sine;
                cosines[lane] = a.dot(b);
                weights[lane] = cross.dot(n) / sine;
            }
        }
        let angles = wide::f64x4::from(sines).atan2(wide::f64x4::from(cosines));
        sum += (angles * wide::f64x4::from(weights)).reduce_add();
    }
    0.5 * sum.abs()
}

/// Point-to-polygon form factor F = Φ/π.
pub fn form_factor(p: DVec3, n: DVec3, polygon: &[DVec3]) -> f64 {
    projected_solid_angle(p, n, polygon) / std::f64::consts::PI
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn square(half: f64, height: f64) -> Vec<DVec3> {
        vec![
            DVec3::new(-half, -half, height),
            DVec3::new(half, -half, height),
            DVec3::new(half, half, height),
            DVec3::new(-half, half, height),
        ]
    }

    /// Closed form for a point under the corner of an a × b rectangle at height c
    /// (Howell's catalogue, configuration B-3), summed over four quadrants.
    fn centred_square_factor(half: f64, height: f64) -> f64 {
        let (x, y) = (half / height, half / height);
        let corner = 1.0 / (2.0 * PI)
            * (x / (1.0 + x * x).sqrt() * (y / (1.0 + x * x).sqrt()).atan()
                + y / (1.0 + y * y).sqrt() * (x / (1.0 + y * y).sqrt()).atan());
        4.0 * corner
    }

    #[test]
    fn matches_the_closed_form_for_squares() {
        for (half, height) in [(1.0, 1.0), (0.5, 2.0), (3.0, 0.25)] {
            let f = form_factor(DVec3::ZERO, DVec3::Z, &square(half, height));
            assert!(
                (f - centred_square_factor(half, height)).abs() < 1e-12,
                "{f}"
            );
        }
        // The shared reference value of the course notes: 2 × 2 square at height 1.
        let f = form_factor(DVec3::ZERO, DVec3::Z, &square(1.0, 1.0));
        assert!((f - 0.5541264).abs() < 5e-8, "{f}");
    }

    #[test]
    fn a_huge_polygon_fills_the_hemisphere() {
        let phi = projected_solid_angle(DVec3::ZERO, DVec3::Z, &square(1e7, 1e-3));
        assert!((phi - PI).abs() < 1e-6, "{phi}");
    }

    #[test]
    fn the_part_below_the_horizon_does_not_count() {
        // A square standing across the tangent plane: only its upper half counts.
        let standing = vec![
            DVec3::new(-1.0, 2.0, -1.0),
            DVec3::new(1.0, 2.0, -1.0),
            DVec3::new(1.0, 2.0, 1.0),
            DVec3::new(-1.0, 2.0, 1.0),
        ];
        let upper: Vec<DVec3> = vec![
            DVec3::new(-1.0, 2.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(1.0, 2.0, 1.0),
            DVec3::new(-1.0, 2.0, 1.0),
        ];
        let a = projected_solid_angle(DVec3::ZERO, DVec3::Z, &standing);
        let b = projected_solid_angle(DVec3::ZERO, DVec3::Z, &upper);
        assert!((a - b).abs() < 1e-12);
        assert!(a > 0.0);
    }
}
