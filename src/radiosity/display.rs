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
use crate::output::Image;
use crate::raster::{ToPrepare, prepare, rasterize, sample_view};
use crate::scene::{Scene, Vertex};
use glam::{DVec2, Vec3};
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

/// The scene's camera view of the elements with radiosities `elements`.
pub fn image(scene: &Scene, mesh: &Mesh, elements: &[Vec3], display: Display) -> Image {
    let view = sample_view(scene);
    let at_vertices = vertex_radiosities(mesh, elements);
    let to_radiance = 1.0 / std::f32::consts::PI;
    let polygons: Vec<(Vec<Vertex>, Vec<Vec3>)> = mesh
        .elements
        .par_iter()
        .enumerate()
        .map(|(e, element)| {
            let normal = mesh.patches[element.patch].normal;
            let outline = mesh.outline(e);
            let vertices = outline
                .iter()
                .map(|&v| Vertex {
                    position: mesh.vertices[v as usize],
                    normal,
                    uv: DVec2::ZERO,
                })
                .collect();
            let colors = outline
                .iter()
                .map(|&v| match display {
                    Display::Gouraud => at_vertices[v as usize] * to_radiance,
                    Display::Flat => elements[e] * to_radiance,
                })
                .collect();
            (vertices, colors)
        })
        .collect();
    let screen = prepare(
        &view,
        polygons
            .iter()
            .enumerate()
            .map(|(id, (vertices, colors))| ToPrepare {
                id: id as u32,
                element: id as u32,
                vertices,
                colors,
                affine_uv: false,
            }),
    );
    let surface = rasterize(&screen, view.width, view.height);
    let radiance = surface
        .samples
        .par_iter()
        .map(|s| {
            if s.is_empty() {
                return scene.render.background;
            }
            let element = &mesh.elements[s.polygon as usize];
            let front = mesh.patches[element.patch]
                .normal
                .dot(view.eye - s.position)
                > 0.0;
            // Radiosity leaves the front only; a surface seen from behind is black.
            if front { s.color } else { Vec3::ZERO }
        })
        .collect();
    Image {
        width: view.width,
        height: view.height,
        pixels: radiance,
    }
    .downsample(scene.render.supersample)
}
