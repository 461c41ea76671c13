//! The object-space methods (Bouknight & Kelley's shadow polygons, Atherton, Weiler
//! & Greenberg's lit detail polygons) attach polygons to each receiver; in one frame,
//! those of a receiver are projected onto the screen and entered in an edge table
//! the first time a band shows the receiver, then swept on the rows of each band.

use crate::raster::{EdgeTable, ScreenPolygon, VisibleSurface, spans_inside};
use std::ops::Range;
use std::sync::OnceLock;

/// One receiver's polygons on the screen, with their edge table.
pub struct Projected {
    table: EdgeTable,
    /// Each polygon's id, by its place in the table's list: a polygon that does
    /// not reach the screen leaves no place, so places and ids differ after it.
    ids: Vec<u32>,
}

/// Per receiver, its polygons on this frame's screen, built on first use.
pub struct ReceiverScreens<F> {
    slots: Vec<OnceLock<Option<Projected>>>,
    height: u32,
    project: F,
}

impl<F: Fn(usize) -> Vec<ScreenPolygon> + Sync> ReceiverScreens<F> {
    /// `project(r)` gives receiver r's polygons on a screen `height` rows high.
    pub fn new(receivers: usize, height: u32, project: F) -> ReceiverScreens<F> {
        ReceiverScreens {
            slots: (0..receivers).map(|_| OnceLock::new()).collect(),
            height,
            project,
        }
    }

    /// Calls `f(row, first, last, inside)` for every span of `band`'s rows that
    /// receiver `r`'s polygons cover, row by row, with the ids of the polygons
    /// covering it.
    pub fn spans(&self, r: usize, band: &VisibleSurface, f: impl FnMut(u32, u32, u32, &[u32])) {
        self.spans_on(r, band.width, band.rows(), f)
    }

    /// As `spans`, on rows `rows` of a screen `width` samples wide.
    pub fn spans_on(
        &self,
        r: usize,
        width: u32,
        rows: Range<u32>,
        mut f: impl FnMut(u32, u32, u32, &[u32]),
    ) {
        let projected = self.slots[r].get_or_init(|| {
            let polygons = (self.project)(r);
            (!polygons.is_empty()).then(|| Projected {
                table: EdgeTable::coverage(&polygons, self.height),
                ids: polygons.iter().map(|p| p.id).collect(),
            })
        });
        if let Some(p) = projected {
            let mut ids = Vec::new();
            spans_inside(&p.table, width, rows, |row, first, last, places| {
                ids.clear();
                ids.extend(places.iter().map(|&i| p.ids[i as usize]));
                f(row, first, last, &ids)
            });
        }
    }
}

/// The receivers (polygon ids) visible somewhere in `band`, ascending.
pub fn seen_in(band: &VisibleSurface, polygons: usize) -> Vec<usize> {
    let mut seen = vec![false; polygons];
    for s in band.samples.iter().filter(|s| !s.is_empty()) {
        seen[s.polygon as usize] = true;
    }
    (0..polygons).filter(|&r| seen[r]).collect()
}
