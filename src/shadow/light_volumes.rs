//! The lit and dark parts of every viewing ray: N. L. Max, "Atmospheric
//! illumination and shadows", Computer Graphics (SIGGRAPH '86) 20(4):117–124, 1986,
//! on F. C. Crow's shadow volumes (1977).
//!
//! Crow counts the shadow polygons in front of the visible surface to decide whether
//! the surface is in shadow. Max follows the count along the whole viewing ray: the
//! shadow polygons the ray crosses, each at its depth, sorted from the eye outwards,
//! +1 entering a volume (a polygon facing the eye) and −1 leaving it, starting from
//! the number of volumes that contain the eye. Where the count is zero the ray is lit;
//! the medium's in-scattering is integrated over those intervals only
//! (`media::single_scattering`). Point and spot lights' volumes are Crow's; a distant
//! light's are prisms, their quads extruded along its travel.
//!
//! Choices: the per-pixel sort is built (the reference the issue asks for), not Max's
//! scan planes through the eye and the light, in which shadow edges keep their depth
//! order from one ray to the next. A ray that meets no surface is followed as far as
//! the caller says (the frame: 4 diagonals of the scene's and the eye's bounds,
//! about where the quads end). Like Crow's
//! count, crossings between the eye and the near plane are not seen (the quads are
//! clipped there).

use super::shadow_volumes::{ShadowQuad, Source, eye_count_from, on_screen, quads_from, reach};
use crate::raster::{EdgeTable, LitIntervals, ScreenPolygon, View, VisibleSurface, spans_inside};
use crate::scene::{Light, Reach, Scene};
use rayon::prelude::*;

/// One light's shadow volumes, for its viewing rays.
pub struct LightVolumes {
    source: Source,
    quads: Vec<ShadowQuad>,
    reach: f64,
}

impl LightVolumes {
    /// `None` for a light with no volumes of its kind (polygon, sphere).
    pub fn new(scene: &Scene, light: &Light) -> Option<LightVolumes> {
        let source = match light.reach() {
            Reach::Point { at, .. } => Source::Point(at),
            Reach::Direction { direction, .. } => Source::Distant(direction),
            Reach::Extended { .. } => return None,
        };
        Some(LightVolumes {
            source,
            quads: quads_from(scene, source),
            reach: reach(scene, source),
        })
        .filter(|v| v.reach.is_finite())
    }

    /// The volumes on one view's screen.
    pub fn frame<'a>(&'a self, scene: &Scene, view: &'a View) -> VolumesOnScreen<'a> {
        let (screens, steps) = on_screen(&self.quads, view);
        VolumesOnScreen {
            view,
            table: EdgeTable::build(&screens, view.height),
            screens,
            steps,
            start: eye_count_from(scene, view.eye, self.source),
        }
    }

    /// How far the volumes reach from the scene (a ray that meets nothing should end
    /// before).
    pub fn reach(&self) -> f64 {
        self.reach
    }
}

/// One light's volumes in one view.
pub struct VolumesOnScreen<'a> {
    view: &'a View,
    screens: Vec<ScreenPolygon>,
    table: EdgeTable,
    steps: Vec<i32>,
    start: i32,
}

/// Rows done by one task.
const GROUP_ROWS: usize = 8;

impl VolumesOnScreen<'_> {
    /// Each sample's lit intervals: distances from the eye along its ray, up to its
    /// visible surface (or `ends`, for a ray that meets none).
    pub fn band(&self, band: &VisibleSurface, ends: f64) -> LitIntervals {
        let width = band.width as usize;
        let groups: Vec<(Vec<u32>, Vec<[f64; 2]>)> = band
            .samples
            .par_chunks(width * GROUP_ROWS)
            .enumerate()
            .map(|(group, samples)| {
                let first = band.first_row + (group * GROUP_ROWS) as u32;
                let rows = first..first + (samples.len() / width) as u32;
                // (column, depth, step) of every crossing in front of the surface.
                let mut crossings: Vec<Vec<(u32, f64, i32)>> = vec![Vec::new(); rows.len()];
                spans_inside(
                    &self.table,
                    band.width,
                    rows.clone(),
                    |row, a, b, inside| {
                        let local = (row - first) as usize;
                        for &q in inside {
                            let plane = self.screens[q as usize].plane;
                            for x in a..=b {
                                let s = &samples[local * width + x as usize];
                                let z = 1.0 / plane.zeta(x as f64 + 0.5, row as f64 + 0.5);
                                if z > 0.0 && (s.is_empty() || z < s.depth) {
                                    crossings[local].push((x, z, self.steps[q as usize]));
                                }
                            }
                        }
                    },
                );
                let (mut start, mut spans) = (Vec::with_capacity(samples.len()), Vec::new());
                for (local, row) in rows.enumerate() {
                    let list = &mut crossings[local];
                    list.sort_unstable_by(|p, q| p.0.cmp(&q.0).then(p.1.total_cmp(&q.1)));
                    let mut next = 0;
                    for x in 0..band.width {
                        let s = &samples[local * width + x as usize];
                        // Eye depth to distance along this sample's ray.
                        let scale = self.view.ray(x as f64 + 0.5, row as f64 + 0.5).length()
                            / self.view.focal;
                        let end = if s.is_empty() { ends } else { s.depth * scale };
                        start.push(spans.len() as u32);
                        let mut count = self.start;
                        let mut from = 0.0;
                        while next < list.len() && list[next].0 == x {
                            let (_, z, step) = list[next];
                            let t = (z * scale).min(end);
                            let lit_before = count <= 0;
                            count += step;
                            if lit_before && count > 0 && t > from {
                                spans.push([from, t]);
                            }
                            if !lit_before && count <= 0 {
                                from = t;
                            }
                            next += 1;
                        }
                        if count <= 0 && end > from {
                            spans.push([from, end]);
                        }
                    }
                }
                (start, spans)
            })
            .collect();
        let mut out = LitIntervals::default();
        for (start, spans) in groups {
            let offset = out.spans.len() as u32;
            out.start.extend(start.iter().map(|s| s + offset));
            out.spans.extend(spans);
        }
        out.start.push(out.spans.len() as u32);
        out
    }
}
