//! Scan-out with invisible surfaces: the visible-surface sweep of `watkins`, handing
//! each row's resolved pieces to a caller while the row is swept, as the shadow
//! methods that work "during scan-out" (Crow 1977's name for the family) need.
//!
//! The polygons of one edge table are of two kinds: the first `visible` take part in
//! visibility and are resolved by depth exactly as `rasterize` resolves them; the
//! others are invisible surfaces (Crow's shadow polygons) that cut the spans and are
//! reported with each piece they cover, but are never drawn. A row's pieces are
//! maximal runs of one visible polygon within one span, left to right, so a caller
//! sees the same visible polygon at every sample as the frame's own pass.

use super::ScreenPolygon;
use super::edge_table::EdgeTable;
use super::watkins::{BAND_ROWS, Inside, Sweep, resolve_runs};
use rayon::prelude::*;
use std::ops::Range;

/// Samples `first..=last` of a row, where polygon `visible` (an index into the swept
/// list) is nearest, covered by the invisible surfaces `invisible` (a range of the
/// row's `ScanRow::ids`).
#[derive(Clone, Debug)]
pub struct Piece {
    pub first: u32,
    pub last: u32,
    pub visible: u32,
    pub invisible: Range<usize>,
}

/// One row of the scan-out: its pieces, left to right, and the invisible surfaces
/// (indices into the swept list) they refer to.
pub struct ScanRow<'a> {
    pub row: u32,
    pub pieces: &'a [Piece],
    pub ids: &'a [u32],
}

impl ScanRow<'_> {
    /// The invisible surfaces covering `piece`.
    pub fn invisible(&self, piece: &Piece) -> &[u32] {
        &self.ids[piece.invisible.clone()]
    }
}

/// Sweeps rows `rows` of `table` (built from `polygons`, the first `visible` of which
/// are visible) and calls `per_row(state, row, out)` for each row, `out` being the
/// row's `width` samples, filled with `empty` beforehand. Rows are swept in groups on
/// parallel threads; each group gets its own `state` from `init(group's rows)`.
#[allow(clippy::too_many_arguments)]
pub fn scan_out<S, T, I, F>(
    polygons: &[ScreenPolygon],
    visible: usize,
    table: &EdgeTable,
    width: u32,
    rows: Range<u32>,
    empty: S,
    init: I,
    per_row: F,
) -> Vec<S>
where
    S: Copy + Send + Sync,
    I: Fn(Range<u32>) -> T + Sync,
    F: Fn(&mut T, &ScanRow, &mut [S]) + Sync,
{
    let mut samples = vec![empty; width as usize * rows.len()];
    samples
        .par_chunks_mut((width * BAND_ROWS) as usize)
        .enumerate()
        .for_each(|(group, out)| {
            let first = rows.start + group as u32 * BAND_ROWS;
            let last = first + (out.len() / width as usize) as u32;
            let mut state = init(first..last);
            let mut sweep = Sweep::starting_at(table, first);
            let (mut pieces, mut ids, mut candidates) = (Vec::new(), Vec::new(), Vec::new());
            for out_row in out.chunks_mut(width as usize) {
                pieces.clear();
                ids.clear();
                let y = sweep.row as f64 + 0.5;
                sweep.for_each_span(width, |i0, i1, inside, _| {
                    candidates.clear();
                    let start = ids.len();
                    for c in inside {
                        if (c.polygon as usize) < visible {
                            candidates.push(*c);
                        } else {
                            ids.push(c.polygon);
                        }
                    }
                    if candidates.is_empty() {
                        ids.truncate(start);
                        return;
                    }
                    let covering = start..ids.len();
                    resolve_runs(i0, i1, &candidates, y, polygons, |c: Inside, a, b| {
                        pieces.push(Piece {
                            first: a as u32,
                            last: b as u32,
                            visible: c.polygon,
                            invisible: covering.clone(),
                        })
                    });
                });
                let row = ScanRow {
                    row: sweep.row,
                    pieces: &pieces,
                    ids: &ids,
                };
                per_row(&mut state, &row, out_row);
                sweep.next_row();
            }
        });
    samples
}
