//! The eye frame of a pinhole camera and its projection to the screen.

use crate::scene::Camera;
use glam::{DVec2, DVec3, DVec4};

/// A camera ready for projection onto a grid of `width × height` samples.
///
/// Eye coordinates: x to the right of the image, y up, z the distance along the view
/// direction (positive in front of the eye; the right-handed eye frame's −z).
#[derive(Clone, Debug)]
pub struct View {
    pub eye: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    pub forward: DVec3,
    /// Distance from the eye to the image plane, in samples.
    pub focal: f64,
    pub width: u32,
    pub height: u32,
    /// Where the view axis meets the screen, in samples: the image centre for a
    /// camera; off centre for a hemicube's half-height side faces.
    pub centre: DVec2,
    pub near: f64,
}

impl View {
    /// The camera's view of a `width × height` sample grid (its own size times the
    /// supersampling factor, for instance). The camera must have been validated.
    pub fn new(camera: &Camera, width: u32, height: u32) -> View {
        let forward = (camera.look_at - camera.eye).normalize();
        let right = forward.cross(camera.up).normalize();
        let up = right.cross(forward);
        let focal = 0.5 * height as f64 / (0.5 * camera.fov_y.to_radians()).tan();
        View {
            eye: camera.eye,
            right,
            up,
            forward,
            focal,
            width,
            height,
            centre: DVec2::new(0.5 * width as f64, 0.5 * height as f64),
            near: camera.near,
        }
    }

    pub fn to_eye(&self, world: DVec3) -> DVec3 {
        let d = world - self.eye;
        DVec3::new(d.dot(self.right), d.dot(self.up), d.dot(self.forward))
    }

    /// Screen position of an eye-space point in front of the eye.
    pub fn project(&self, eye: DVec3) -> (f64, f64) {
        (
            self.centre.x + self.focal * eye.x / eye.z,
            self.centre.y - self.focal * eye.y / eye.z,
        )
    }

    /// World direction (not normalised) of the ray through screen point (x, y).
    pub fn ray(&self, x: f64, y: f64) -> DVec3 {
        self.forward * self.focal + self.right * (x - self.centre.x) + self.up * (self.centre.y - y)
    }

    /// The eye ray through screen point (x, y) as (origin, direction): the inverse of
    /// `project`. The direction is scaled so that origin + t·direction lies at eye
    /// depth z = t, the depth the visible-surface buffer stores; a query over
    /// t ≥ `near` sees what the scan-line pass sees after clipping to the near plane.
    pub fn ray_through(&self, x: f64, y: f64) -> (DVec3, DVec3) {
        (self.eye, self.ray(x, y) / self.focal)
    }

    /// Whether eye-space points lie all outside one plane of `frustum` (this view's
    /// `frustum()`, computed once by the caller): the trivial reject of a polygon.
    pub fn rejects(frustum: &[DVec4; 5], eye: &[DVec3]) -> bool {
        frustum
            .iter()
            .any(|f| eye.iter().all(|e| f.truncate().dot(*e) + f.w < 0.0))
    }

    /// The view frustum as eye-space half-spaces a·p + d ≥ 0: near, left, right, top,
    /// bottom. The side planes pass through the eye, so clipping against them in eye
    /// space is exact.
    pub fn frustum(&self) -> [DVec4; 5] {
        let (c, f) = (self.centre, self.focal);
        let (w, h) = (self.width as f64, self.height as f64);
        [
            DVec4::new(0.0, 0.0, 1.0, -self.near),
            DVec4::new(f, 0.0, c.x, 0.0),
            DVec4::new(-f, 0.0, w - c.x, 0.0),
            DVec4::new(0.0, -f, c.y, 0.0),
            DVec4::new(0.0, f, h - c.y, 0.0),
        ]
    }
}
