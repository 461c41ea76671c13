//! Bump mapping: J. F. Blinn, "Simulation of wrinkled surfaces", Computer Graphics
//! (SIGGRAPH '78) 12(3):286–292, 1978.
//!
//! The surface O(u, v) is lit with the normal of its displaced copy
//! O' = O + B(u, v) N/|N| without moving any geometry. With N = O_u × O_v and the
//! course's frame A = N × O_v, B = N × O_u, dropping the term in B itself (B small):
//!
//!   N' = N + D,   D = (B_u A − B_v B) / |N|.
//!
//! The course writes D = B_u A − B_v B, without the division by |N|. That is the normal
//! of O + B N (displacement along the unnormalised normal), so the bump height would
//! depend on the parameterisation's speed. We follow the paper: dividing by |N| makes
//! N' the first-order normal of the surface displaced by B along the unit normal,
//! i.e. the bump height B is a distance in scene units. D lies in the tangent plane
//! and is built from O_u, O_v, so the wrinkles stay attached to the surface when it
//! moves. The silhouette is unchanged: only normals move, which is the method's limit.

use glam::{DVec2, DVec3};

/// The perturbed unit normal. `normal` is the unit shading normal (for a smooth mesh,
/// the interpolated vertex normal standing in for N/|N|), `tangents` are O_u and O_v,
/// `slope` is (B_u, B_v). Falls back to `normal` where the frame is degenerate (O_u or
/// O_v zero: the poles of a sphere).
pub fn perturb(normal: DVec3, tangents: [DVec3; 2], slope: DVec2) -> DVec3 {
    let [o_u, o_v] = tangents;
    let length = o_u.cross(o_v).length();
    if length.is_nan() || length <= 1e-300 || slope == DVec2::ZERO {
        return normal;
    }
    // N = |N| n̂, so A/|N| = n̂ × O_v and B/|N| = n̂ × O_u.
    let a = normal.cross(o_v);
    let b = normal.cross(o_u);
    let d = slope.x * a - slope.y * b;
    let perturbed = normal * length + d;
    perturbed.normalize_or(normal)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exact plane case of ALGORITHMS.md: O = (u, v, 0), B = a u + b v gives the
    /// normal of the plane z = a u + b v, since the dropped term is zero.
    #[test]
    fn linear_height_on_a_plane_is_exact() {
        let (a, b) = (0.3, -0.7);
        let n = perturb(DVec3::Z, [DVec3::X, DVec3::Y], DVec2::new(a, b));
        let exact = DVec3::new(-a, -b, 1.0).normalize();
        assert!((n - exact).length() < 1e-15);
    }

    #[test]
    fn constant_height_leaves_the_normal() {
        assert_eq!(
            perturb(DVec3::Y, [DVec3::X, DVec3::Z], DVec2::ZERO),
            DVec3::Y
        );
    }
}
