//! Showing a radiosity solution: element radiosities averaged to the vertices they
//! share and drawn with Gouraud shading by the scan-line pass (or flat, one value
//! per element, for comparison). Pixels hold radiance B/π, the radiance of a
//! Lambertian surface of radiosity B, so the image compares with a physically based
//! renderer's.
//!
//! Choice left open (the paper's rule is uncertain): every vertex takes the plain
//! mean of the elements that share it, boundary vertices included (no extrapolation).
//! After adaptive subdivision an element is drawn through the midpoints its finer
//! neighbours put on its sides, which share their values (no Gouraud cracks).

use super::mesh::Mesh;
use crate::scene::ray_queries::interpolate;
use crate::scene::{Scene, Vertex};
use glam::Vec3;
use rayon::prelude::*;

pub use crate::settings::Display;

/// Per mesh vertex, the mean radiosity of the elements sharing it.
pub fn vertex_radiosities(mesh: &Mesh, elements: &[Vec3]) -> Vec<Vec3> {
    mesh.vertex_elements()
        .iter()
        .map(|users| {
            let sum: Vec3 = users.iter().map(|&e| elements[e as usize]).sum();
            sum / users.len().max(1) as f32
        })
        .collect()
}

/// An element ready for the scan-line pass: its polygon's id, its outline and the
/// radiance B/π to interpolate across it.
pub struct ElementPolygon {
    pub polygon: usize,
    pub vertices: Vec<Vertex>,
    pub colors: Vec<Vec3>,
}

/// The elements with radiosities `elements`, as the scan-line pass draws them: each
/// through its outline (with the midpoints finer neighbours put on its sides), its
/// vertices carrying its polygon's attributes there.
pub fn element_polygons(
    scene: &Scene,
    mesh: &Mesh,
    elements: &[Vec3],
    display: Display,
) -> Vec<ElementPolygon> {
    let at_vertices = vertex_radiosities(mesh, elements);
    let to_radiance = 1.0 / std::f32::consts::PI;
    mesh.elements
        .par_iter()
        .enumerate()
        .map(|(e, element)| {
            let patch = &mesh.patches[element.patch];
            let outline = mesh.outline(e);
            let polygon = &scene.polygons[patch.polygon];
            let vertices = outline
                .iter()
                .map(|&v| {
                    let position = mesh.vertices[v as usize];
                    let (normal, uv) = interpolate(polygon, position);
                    Vertex {
                        position,
                        normal,
                        uv,
                    }
                })
                .collect();
            let colors = outline
                .iter()
                .map(|&v| match display {
                    Display::Gouraud => at_vertices[v as usize] * to_radiance,
                    Display::Flat => elements[e] * to_radiance,
                })
                .collect();
            ElementPolygon {
                polygon: patch.polygon,
                vertices,
                colors,
            }
        })
        .collect()
}
