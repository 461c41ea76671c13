//! A point light sees all around: methods that look from it (shadow maps, shadow
//! polygons) split its view into the six 90° frusta of a cube, ±x, ±y, ±z.

use crate::raster::View;
use crate::scene::{Camera, Scene};
use glam::DVec3;

/// Each face's view axis and the up vector of its image.
pub const FACES: [(DVec3, DVec3); 6] = [
    (DVec3::X, DVec3::Y),
    (DVec3::NEG_X, DVec3::Y),
    (DVec3::Y, DVec3::Z),
    (DVec3::NEG_Y, DVec3::Z),
    (DVec3::Z, DVec3::Y),
    (DVec3::NEG_Z, DVec3::Y),
];

/// The light's view through one face, on a `resolution²` grid.
pub fn face_view(scene: &Scene, light: DVec3, (axis, up): (DVec3, DVec3), resolution: u32) -> View {
    let camera = Camera {
        eye: light,
        look_at: light + axis,
        up,
        fov_y: 90.0,
        width: resolution,
        height: resolution,
        near: 1e-6 * scene_extent(scene).max(1e-9),
    };
    View::new(&camera, resolution, resolution)
}

/// The index in `FACES` of the face whose frustum holds direction `d`.
pub fn face_of(d: DVec3) -> usize {
    let a = d.abs();
    if a.x >= a.y && a.x >= a.z {
        if d.x > 0.0 { 0 } else { 1 }
    } else if a.y >= a.z {
        if d.y > 0.0 { 2 } else { 3 }
    } else if d.z > 0.0 {
        4
    } else {
        5
    }
}

/// The diagonal of the scene's bounding box.
fn scene_extent(scene: &Scene) -> f64 {
    let b = crate::geometry::bvh::Aabb::of(scene.polygons.iter().flat_map(|p| p.positions()));
    (b.max - b.min).length()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_direction_falls_in_the_face_it_faces() {
        for (k, &(axis, _)) in FACES.iter().enumerate() {
            assert_eq!(face_of(axis + 0.3 * axis.any_orthonormal_vector()), k);
        }
    }
}
