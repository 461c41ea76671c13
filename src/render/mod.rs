//! Rendering: the integrators (the ways a frame is lit) over one visible-surface pass
//! and one shading pass, the renderer that keeps view-independent work between
//! frames, and the frame's named buffers.
//!
//! A frame: the integrator's polygons (the scene's, or a radiosity solution's
//! elements) are clipped, projected and entered in one edge table; the frame is then
//! made in bands of rows, so that memory does not grow with the image's height or its
//! supersampling. Per band: the scan-line pass gives the visible samples, each
//! shadowed light's method gives its visibility, shading gives radiance, and the box
//! filter gives the band's pixels (and the buffers asked for take their rows).

mod accumulation;
mod buffers;
pub mod capture;
mod frame;
pub mod integrators;
mod medium;
mod output;
mod plan;
mod renderer;

pub use frame::band_rows;
pub use integrators::Integrator;
pub use output::{BufferInfo, Frame};
pub use plan::EnvironmentMaps;
pub use renderer::{Prepasses, Renderer, capture_cube};

use crate::error::Result;
use crate::image_io::Image;
use crate::raster::{View, VisibleSurface, sample_view};
use crate::scene::Scene;

/// Linear radiance image of `scene` (its radiosity solution when it has `[radiosity]`
/// settings, else its lights), shadowed by the scene's shadow method.
pub fn render(scene: &Scene) -> Result<Image> {
    Renderer::new(scene.clone()).render()
}

/// The visible surface of `scene` on its whole sample grid (pixels × supersample), as
/// the direct-lighting integrator draws it.
pub fn visible_surface(scene: &Scene) -> (View, VisibleSurface) {
    let view = sample_view(scene);
    let direct = vec![true; scene.lights.len()];
    let polygons =
        integrators::ScanLine::draw_list(&integrators::DirectLighting, scene, &view, &direct);
    let surface = crate::raster::rasterize(&polygons, view.width, view.height);
    (view, surface)
}
