//! Checks on values a user writes: finite vectors, sane sizes, a usable camera.

use super::Camera;
use super::file::{CameraFile, Vec3File};
use crate::error::ensure_valid;
use crate::error::{Error, Result};
use glam::DVec3;

/// Largest width or height accepted.
pub const MAX_SIDE: u32 = 16_384;
/// Largest number of samples (pixels × supersample²) in one render; each costs
/// about 80 bytes in the visible-surface buffer.
pub const MAX_SAMPLES: u64 = 1 << 26;

pub fn vec3(what: &str, v: Vec3File) -> Result<DVec3> {
    ensure_valid!(
        v.iter().all(|x| x.is_finite()),
        what,
        "{what} must be finite numbers, got {v:?}"
    );
    Ok(DVec3::from(v))
}

/// The largest coordinate a scene holds, in scene units. Areas, squared distances
/// and form factors multiply coordinates together: beyond this they would leave
/// floating point, and a polygon be called empty or a light infinitely far.
pub const MAX_COORDINATE: f64 = 1e12;

/// A point of the scene: finite, within ±`MAX_COORDINATE`.
pub fn position(what: &str, v: Vec3File) -> Result<DVec3> {
    let p = vec3(what, v)?;
    ensure_valid!(
        p.abs().max_element() <= MAX_COORDINATE,
        what,
        "{what} = {v:?} lies beyond ±{MAX_COORDINATE:e}, the largest coordinate a scene holds (areas and distances would leave floating point)"
    );
    Ok(p)
}

/// A direction: finite, not zero; returned as a unit vector.
pub fn direction(what: &str, v: Vec3File) -> Result<DVec3> {
    let d = vec3(what, v)?.normalize_or_zero();
    ensure_valid!(d != DVec3::ZERO, what, "{what} must not be zero, got {v:?}");
    Ok(d)
}

pub fn colour(what: &str, v: Vec3File) -> Result<glam::Vec3> {
    let c = vec3(what, v)?;
    ensure_valid!(
        c.min_element() >= 0.0,
        what,
        "{what} must not be negative, got {v:?}"
    );
    // Radiance is kept in 32-bit floats: larger values would become infinite.
    ensure_valid!(
        c.as_vec3().is_finite(),
        what,
        "{what} must be at most {:e} (a 32-bit float), got {v:?}",
        f32::MAX
    );
    Ok(c.as_vec3())
}

pub fn image_size(width: u32, height: u32, supersample: u32) -> Result<()> {
    for (name, side) in [("width", width), ("height", height)] {
        ensure_valid!(
            (1..=MAX_SIDE).contains(&side),
            format!("camera.{name}"),
            "image {name} must be between 1 and {MAX_SIDE}, got {side}"
        );
    }
    ensure_valid!(
        (1..=16).contains(&supersample),
        "render.supersample",
        "supersample must be between 1 and 16, got {supersample}"
    );
    let samples = width as u64 * height as u64 * (supersample as u64).pow(2);
    if samples > MAX_SAMPLES {
        return Err(Error::Scene(format!(
            "{width}x{height} with supersample {supersample} is {samples} samples, more than the {MAX_SAMPLES} one render takes"
        )));
    }
    Ok(())
}

pub fn camera(c: &CameraFile) -> Result<Camera> {
    let eye = vec3("camera.eye", c.eye)?;
    let look_at = vec3("camera.look_at", c.look_at)?;
    let up = vec3("camera.up", c.up)?;
    let view = look_at - eye;
    ensure_valid!(
        view.length() > 0.0,
        "camera.look_at",
        "camera.eye and camera.look_at are the same point"
    );
    ensure_valid!(up.length() > 0.0, "camera.up", "camera.up must not be zero");
    if view.normalize().cross(up.normalize()).length() < 1e-9 {
        return Err(Error::invalid(
            "camera.up",
            "camera.up is parallel to the view direction (eye to look_at)",
        ));
    }
    ensure_valid!(
        c.fov_y.is_finite() && c.fov_y > 0.0 && c.fov_y < 180.0,
        "camera.fov_y",
        "camera.fov_y must be strictly between 0 and 180 degrees, got {}",
        c.fov_y
    );
    let near = c.near.unwrap_or(1e-3 * view.length());
    ensure_valid!(
        near.is_finite() && near > 0.0,
        "camera.near",
        "camera.near must be positive, got {near}"
    );
    let side = |name: &str, n: i64| -> Result<u32> {
        let key = format!("camera.{name}");
        ensure_valid!(
            (1..=MAX_SIDE as i64).contains(&n),
            &key,
            "{key} must be between 1 and {MAX_SIDE}, got {n}"
        );
        Ok(n as u32)
    };
    Ok(Camera {
        eye,
        look_at,
        up,
        fov_y: c.fov_y,
        width: side("width", c.width)?,
        height: side("height", c.height)?,
        near,
    })
}
