//! Shadow volumes counted in a buffer: T. Heidmann, "Real shadows, real time", IRIS
//! Universe no. 18, pp. 28–31, Silicon Graphics, 1991 (after Crow 1977, and the
//! per-pixel counters of Brotman & Badler 1984).
//!
//! The visible-surface pass runs first and leaves its depths. Crow's quads are then
//! drawn one by one, with no part in visibility, into a count (stencil) buffer: where
//! a quad lies in front of the visible depth its sample's count goes up by one if
//! it faces the eye (entering a volume) and down by one if it faces away (leaving
//! it). The counts equal Crow's counts along each span (`shadow_volumes`) sample for
//! sample; what differs is where the counting happens, after the pass instead of
//! inside it.
//!
//! Choices: Heidmann's stencil starts at zero ("z-pass"), which inverts the shadows
//! when the eye stands inside a volume; here the buffer starts at Crow's eye count,
//! so both formulations answer alike everywhere. The quads are swept in an edge
//! table of their own and each counts at a sample when it is nearer than the visible
//! surface by a relative 1e-9, Crow's rule. Brotman & Badler's soft shadow volumes
//! count their points' volumes this way. Scene key:
//! `[shadows] method = "stencil-shadow-volumes"`.

use super::shadow_volumes::{Counting, Source};
use super::shadow_volumes::{ShadowVolumes, eye_count_except, on_screen};
use super::{BandShadows, FrameShadows};
use crate::raster::{EdgeTable, ScreenPolygon, View, VisibleSurface, spans_inside};
use crate::scene::LightKind;
use crate::scene::Scene;
use crate::settings::ShadowMethod;
use rayon::prelude::*;
use std::sync::Arc;

/// The registry's entry: Crow's volumes, counted in a buffer.
pub(crate) static METHOD: super::Method = super::Method {
    method: ShadowMethod::StencilShadowVolumes,
    name: "stencil-shadow-volumes",
    entry: Some("stencil-shadow-volumes"),
    handles: "a hard-shadow method for point, spot and distant lights",
    lights: &[LightKind::Point, LightKind::Spot, LightKind::Distant],
    counts: Some(super::shadow_volumes::COUNTS),
    budget: super::no_budget,
    warnings: super::shadow_volumes::leak_warnings,
    prepare: |scene, index, _, _| {
        let source = Source::of(&scene.lights[index]);
        Some(Arc::new(ShadowVolumes::from_source(
            scene,
            source,
            Counting::Stencil,
        )))
    },
};

/// One light's volumes on a view's screen, ready to be drawn into a count buffer.
pub struct CountBuffer<'a> {
    volumes: &'a ShadowVolumes,
    scene: &'a Scene,
    view: &'a View,
    screens: Vec<ScreenPolygon>,
    table: EdgeTable,
    /// Per screen quad, +1 entering a volume, −1 leaving it.
    steps: Vec<i32>,
    /// The number of volumes containing the eye.
    start: i32,
}

/// Rows counted by one task.
const GROUP_ROWS: usize = 8;

impl ShadowVolumes {
    /// The quads on this view's screen, in an edge table, and the eye's count.
    pub fn count_buffer<'a>(&'a self, scene: &'a Scene, view: &'a View) -> CountBuffer<'a> {
        let (screens, steps) = on_screen(&self.quads, view);
        CountBuffer {
            volumes: self,
            scene,
            view,
            table: EdgeTable::build(&screens, view.height),
            screens,
            steps,
            start: eye_count_except(scene, view.eye, self.source, self.emitter),
        }
    }
}

impl FrameShadows for CountBuffer<'_> {
    fn band(&self, band: &VisibleSurface) -> BandShadows {
        let counts = self.counts(band);
        self.volumes
            .shadows_from(self.scene, self.view, band, counts)
    }
}

impl CountBuffer<'_> {
    /// The count buffer of `band`: every quad drawn where it lies in front of the
    /// visible depth (its spans found by the scan-line sweep of the quads alone).
    pub fn counts(&self, band: &VisibleSurface) -> Vec<i32> {
        let width = band.width as usize;
        let mut counts = vec![self.start; band.samples.len()];
        counts
            .par_chunks_mut(width * GROUP_ROWS)
            .enumerate()
            .for_each(|(group, counts)| {
                let first = band.first_row + (group * GROUP_ROWS) as u32;
                let rows = first..first + (counts.len() / width) as u32;
                spans_inside(&self.table, band.width, rows, |row, a, b, inside| {
                    let local = (row - first) as usize * width;
                    let band_row = (row - band.first_row) as usize * width;
                    for &q in inside {
                        let plane = self.screens[q as usize].plane;
                        for x in a..=b {
                            let sample_zeta = 1.0 / band.samples[band_row + x as usize].depth;
                            let quad_zeta = plane.zeta(x as f64 + 0.5, row as f64 + 0.5);
                            if quad_zeta > sample_zeta * (1.0 + 1e-9) {
                                counts[local + x as usize] += self.steps[q as usize];
                            }
                        }
                    }
                });
            });
        counts
    }
}
