//! The sphere map: the surroundings as a perfect mirror ball shows them to a distant
//! (orthographic) camera, after Miller & Hoffman's photographs of a chrome ball
//! ("Illumination and reflection maps", SIGGRAPH '84 course notes).
//!
//! The ball is seen from +z (the camera looks down −z, image right = +x, image top =
//! +y). A direction R reflected towards the camera at the ball's point with normal n
//! satisfies n ∝ R + (0, 0, 1), so with m = 2√(R_x² + R_y² + (R_z + 1)²):
//!
//!   u = R_x/m + ½,   v = R_y/m + ½.
//!
//! The whole sphere of directions fits in the inscribed disc; the direction straight
//! behind the ball, −z, is the whole rim (the layout's singularity, where a footprint
//! is as large as the map). Texels outside the disc hold that direction's value.

use glam::{DVec2, DVec3};

/// (u, v) of a direction (need not be unit); −z itself goes to the rim at +x.
pub fn uv(d: DVec3) -> DVec2 {
    let r = d.normalize();
    let m = 2.0 * (r.x * r.x + r.y * r.y + (r.z + 1.0) * (r.z + 1.0)).sqrt();
    if m < 1e-12 {
        return DVec2::new(1.0, 0.5);
    }
    DVec2::new(r.x / m + 0.5, r.y / m + 0.5)
}

/// The unit direction of (u, v): the ball's normal there (points outside the disc are
/// taken on its rim), and the view (0, 0, 1) reflected about it.
pub fn direction(uv: DVec2) -> DVec3 {
    let mut p = DVec2::new(2.0 * uv.x - 1.0, 2.0 * uv.y - 1.0);
    if p.length_squared() > 1.0 {
        p = p.normalize();
    }
    let n = DVec3::new(p.x, p.y, (1.0 - p.length_squared()).max(0.0).sqrt());
    (2.0 * n.z * n - DVec3::Z).normalize()
}

/// The change in (u, v) from `d` to `d + offset`.
pub fn uv_step(d: DVec3, offset: DVec3) -> DVec2 {
    let d = d.normalize();
    uv(d + offset) - uv(d)
}
