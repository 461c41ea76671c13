//! The latitude-longitude map of Blinn & Newell (1976), indexed by the course's
//! formula: for a unit direction R in the map's frame,
//!
//!   u = (1 + atan2(R_y, R_x)/π)/2,   v = (R_z + 1)/2.
//!
//! v is linear in R_z, not in the latitude: the cylindrical equal-area layout (each
//! row of texels covers the same solid angle), as the course writes it. Blinn and
//! Newell indexed by the spherical angles themselves; we keep the course's formula and
//! build every map with it, so lookup and map agree.
//!
//! The map's frame in world coordinates (y up): X = −z (the centre column, u = ½, is
//! what a camera looking down −z faces), Y = −x, Z = +y (the top row, v = 1, is the
//! zenith), right-handed. u grows from −X (the seam, u = 0 and 1, behind that camera)
//! through Y = −x: seen from inside, the picture runs leftwards, so it is the mirror
//! image of a photographic panorama (flip one horizontally to use it here).

use glam::{DVec2, DVec3};
use std::f64::consts::PI;

/// A world direction in the map's frame.
fn to_map(d: DVec3) -> DVec3 {
    DVec3::new(-d.z, -d.x, d.y)
}

fn from_map(m: DVec3) -> DVec3 {
    DVec3::new(-m.y, m.z, -m.x)
}

/// (u, v) of a direction (need not be unit).
pub fn uv(d: DVec3) -> DVec2 {
    let r = to_map(d.normalize());
    DVec2::new(
        (1.0 + r.y.atan2(r.x) / PI) / 2.0,
        (r.z.clamp(-1.0, 1.0) + 1.0) / 2.0,
    )
}

/// The unit direction of (u, v): the formula's inverse.
pub fn direction(uv: DVec2) -> DVec3 {
    let phi = PI * (2.0 * uv.x - 1.0);
    let z = (2.0 * uv.y - 1.0).clamp(-1.0, 1.0);
    let r = (1.0 - z * z).sqrt();
    from_map(DVec3::new(r * phi.cos(), r * phi.sin(), z))
}

/// The change in (u, v) from `d` to `d + offset`, the longitude difference taken the
/// short way round the seam.
pub fn uv_step(d: DVec3, offset: DVec3) -> DVec2 {
    let d = d.normalize();
    let step = uv(d + offset) - uv(d);
    DVec2::new(step.x - step.x.round(), step.y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frame_is_right_handed_and_the_axes_land_where_documented() {
        let (x, y, z) = (from_map(DVec3::X), from_map(DVec3::Y), from_map(DVec3::Z));
        assert!((x.cross(y) - z).length() < 1e-12);
        assert!((uv(DVec3::NEG_Z) - DVec2::new(0.5, 0.5)).length() < 1e-12);
        assert!((uv(DVec3::Y).y - 1.0).abs() < 1e-12);
        assert!((uv(DVec3::NEG_X) - DVec2::new(0.75, 0.5)).length() < 1e-12);
    }
}
