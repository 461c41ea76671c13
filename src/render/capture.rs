//! Environment maps made by rendering: Greene's cube map "rendered by any ordinary
//! renderer", here lumiere's own. Six square frames with 90° fields of view from the
//! capture point, along ±x, ±y, ±z with the cube map's face cameras
//! (`texture::environment::cube_map`), of the scene without the hidden objects (the
//! reflector itself, which an environment map cannot show: an object does not
//! reflect itself).
//!
//! Inside a capture, captured environments are not shown (a mirror shows its local
//! shading only), so captures never recurse; loaded and procedural environments are.
//! A hidden polygon light is hidden with its light.

use crate::scene::{Camera, Scene};
use crate::texture::environment::cube_map;
use glam::DVec3;

/// The scene as the capture sees it: the hidden objects' polygons (and their
/// lights) left out, polygon ids renumbered.
pub fn without_objects(scene: &Scene, hidden: &[usize]) -> Scene {
    let mut renumbered = vec![None; scene.polygons.len()];
    let mut kept = Vec::with_capacity(scene.polygons.len());
    for (id, p) in scene.polygons.iter().enumerate() {
        if !hidden.contains(&p.object) {
            renumbered[id] = Some(kept.len());
            kept.push(p.clone());
        }
    }
    let lights = scene
        .lights
        .iter()
        .filter_map(|light| light.renumbered(&renumbered))
        .collect();
    Scene {
        polygons: kept,
        lights,
        warnings: Vec::new(),
        ..scene.clone()
    }
}

/// The cube face cameras at `at`, `size` texels a side, in face storage order.
pub fn face_cameras(at: DVec3, size: u32, near: f64) -> Vec<Camera> {
    (0..6)
        .map(|face| {
            let [forward, up, _] = cube_map::face_frame(face);
            Camera {
                eye: at,
                look_at: at + forward,
                up,
                fov_y: 90.0,
                width: size,
                height: size,
                near,
            }
        })
        .collect()
}
