//! The viewer's camera: an orbit around the scene camera's look-at point (yaw and
//! pitch about its up axis, and a distance), so that the mouse turns the view
//! about what the scene looks at.

use crate::scene::Camera;
use glam::DVec3;

#[derive(Clone, Debug)]
pub struct Orbit {
    base: Camera,
    /// The scene camera's offset from its target, in the orbit's frame.
    yaw: f64,
    pitch: f64,
    distance: f64,
}

/// Pitch stays short of the poles, where the up axis would be the view axis.
const MAX_PITCH: f64 = 1.5;

impl Orbit {
    pub fn new(camera: Camera) -> Orbit {
        let (yaw, pitch, distance) = angles(&camera);
        Orbit {
            base: camera,
            yaw,
            pitch,
            distance,
        }
    }

    /// Its yaw, pitch and distance.
    pub fn state(&self) -> [f64; 3] {
        [self.yaw, self.pitch, self.distance]
    }

    /// Turns to `yaw` and `pitch` (radians, the scene camera's yaw being 0) at
    /// `distance` from the target; pitch is kept short of the poles, the distance
    /// positive.
    pub fn set(&mut self, yaw: f64, pitch: f64, distance: f64) {
        if yaw.is_finite() {
            self.yaw = yaw;
        }
        if pitch.is_finite() {
            self.pitch = pitch.clamp(-MAX_PITCH, MAX_PITCH);
        }
        if distance.is_finite() {
            self.distance = distance.max(1e-6);
        }
    }

    /// The camera now, at `width` × `height`.
    pub fn camera(&self, width: u32, height: u32) -> Camera {
        let (up, forward, side) = frame(&self.base);
        let direction = (up * self.pitch.sin()
            + (forward * self.yaw.cos() + side * self.yaw.sin()) * self.pitch.cos())
        .normalize();
        Camera {
            eye: self.base.look_at + direction * self.distance,
            width,
            height,
            ..self.base.clone()
        }
    }
}

/// The orbit's frame: the scene camera's up axis, and two axes across it (the
/// second towards the scene camera's eye).
fn frame(camera: &Camera) -> (DVec3, DVec3, DVec3) {
    let up = camera.up.normalize();
    let to_eye = camera.eye - camera.look_at;
    let mut forward = to_eye - up * to_eye.dot(up);
    if forward.length_squared() < 1e-18 {
        forward = up.any_orthonormal_vector();
    }
    let forward = forward.normalize();
    (up, forward, up.cross(forward))
}

/// The scene camera's own yaw (0: its eye lies along the frame's second axis),
/// pitch and distance.
fn angles(camera: &Camera) -> (f64, f64, f64) {
    let (up, _, _) = frame(camera);
    let to_eye = camera.eye - camera.look_at;
    let distance = to_eye.length().max(1e-6);
    let pitch = (to_eye.dot(up) / distance).clamp(-1.0, 1.0).asin();
    (0.0, pitch.clamp(-MAX_PITCH, MAX_PITCH), distance)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera(eye: DVec3) -> Camera {
        Camera {
            eye,
            look_at: DVec3::new(1.0, 2.0, 3.0),
            up: DVec3::Y,
            fov_y: 40.0,
            width: 64,
            height: 48,
            near: 0.01,
        }
    }

    #[test]
    fn an_unturned_orbit_is_the_scene_camera() {
        let scene = camera(DVec3::new(4.0, 5.0, 9.0));
        let view = Orbit::new(scene.clone()).camera(64, 48);
        assert!((view.eye - scene.eye).length() < 1e-9, "{:?}", view.eye);
        assert_eq!(view.look_at, scene.look_at);
    }

    #[test]
    fn turning_keeps_the_distance_and_a_full_turn_comes_back() {
        let scene = camera(DVec3::new(4.0, 5.0, 9.0));
        let mut orbit = Orbit::new(scene.clone());
        let distance = (scene.eye - scene.look_at).length();
        let [yaw, pitch, _] = orbit.state();
        orbit.set(yaw + 1.0, pitch + 0.3, distance);
        let turned = orbit.camera(64, 48);
        assert!(((turned.eye - scene.look_at).length() - distance).abs() < 1e-9);
        assert!((turned.eye - scene.eye).length() > 0.1);
        orbit.set(yaw + 2.0 * std::f64::consts::PI, pitch, distance);
        assert!((orbit.camera(64, 48).eye - scene.eye).length() < 1e-9);
        orbit.set(yaw, pitch, distance / 2.0);
        let near = orbit.camera(64, 48);
        assert!(((near.eye - scene.look_at).length() - distance / 2.0).abs() < 1e-9);
    }
}
