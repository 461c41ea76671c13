//! Watkins's scan-line visible-surface pass on its own, as a frame runs it: the
//! scene's polygons clipped, projected and put in the edge table once, then swept
//! band by band into one reused buffer. `lumiere bench` times it beside whole
//! renders, to tell the pass's share of a frame.

use crate::raster::{self, EdgeTable, Sample, ScreenPolygon, UvGradient};
use crate::render::band_rows;
use crate::scene::Scene;
use std::sync::Arc;

/// The pass prepared for one scene and camera.
pub struct VisibleSurfacePass {
    polygons: Vec<ScreenPolygon>,
    table: EdgeTable,
    gradients: Arc<[Option<UvGradient>]>,
    width: u32,
    height: u32,
    band: u32,
    memory: Vec<Sample>,
}

impl VisibleSurfacePass {
    /// Clips and projects `scene`'s polygons for its camera and sample grid and
    /// builds the edge table.
    pub fn prepare(scene: &Scene) -> VisibleSurfacePass {
        let view = raster::sample_view(scene);
        let polygons = raster::screen_polygons(scene, &view);
        let table = EdgeTable::build(&polygons, view.height);
        let gradients = raster::uv_gradients(&polygons);
        VisibleSurfacePass {
            polygons,
            table,
            gradients,
            width: view.width,
            height: view.height,
            band: band_rows(scene) * scene.render.supersample,
            memory: Vec::new(),
        }
    }

    /// The samples one sweep finds the visible surface of (pixels × supersample²).
    pub fn samples(&self) -> u64 {
        self.width as u64 * self.height as u64
    }

    /// One sweep over every band of the sample grid.
    pub fn sweep(&mut self) {
        for first in (0..self.height).step_by(self.band as usize) {
            let rows = first..(first + self.band).min(self.height);
            let swept = raster::rasterize_rows(
                &self.polygons,
                &self.table,
                self.width,
                rows,
                self.gradients.clone(),
                std::mem::take(&mut self.memory),
            );
            self.memory = std::hint::black_box(swept).samples;
        }
    }
}
