//! The scan-line sweep: G. S. Watkins, "A Real-Time Visible Surface Algorithm", PhD
//! thesis, University of Utah, 1970; W. J. Bouknight, "A procedure for generation of
//! three-dimensional half-toned computer graphics presentations", CACM 13(9), 1970.
//!
//! For every row: merge the edge-table bucket into the active edge list (AEL), drop
//! finished edges, re-sort by x (insertion sort: the list is nearly sorted already),
//! and walk it left to right. Each crossing toggles its polygon in or out of the
//! "inside" set; between two crossings lies a span whose set is constant. A span with
//! one polygon shows it; with several, each candidate's depth is evaluated at the
//! span's two end samples: if one polygon is nearest at both ends it is nearest over
//! the whole span (planes can only swap order where they intersect); otherwise the
//! span is split where the two winners' depths cross, and each part is decided again
//! (Watkins' subdivision for interpenetrating polygons).
//!
//! Choices left open: depths are compared at sample centres, not at the span's real
//! ends (the samples are what is displayed, and it makes the result equal a z-buffer
//! sample for sample); equal depths go to the polygon given first. A frame is swept in
//! bands of rows (the caller's, for memory) and each band in groups of `BAND_ROWS`
//! on parallel threads; a group's AEL starts from the edge table exactly as a full
//! sweep would have it (see `edge_table`), so no result depends on the cut.

use super::edge_table::{Crossing, EdgeTable, FIXED_ONE, first_pixel_at_or_after};
use super::project::UvGradient;
use super::project::{ATTRIBUTES, Attributes, UV};
use super::{NO_POLYGON, Sample, ScreenPolygon, VisibleSurface};
use glam::{DVec2, DVec3, Vec3};
use rayon::prelude::*;
use std::ops::Range;
use std::sync::Arc;
use wide::f64x4;

pub(super) const BAND_ROWS: u32 = 8;

/// The visible surface at every sample of a `width × height` grid.
pub fn rasterize(polygons: &[ScreenPolygon], width: u32, height: u32) -> VisibleSurface {
    let table = EdgeTable::build(polygons, height);
    let gradients = uv_gradients(polygons);
    rasterize_rows(polygons, &table, width, 0..height, gradients, Vec::new())
}

/// The visible surface on rows `rows` of the grid whose edge table is `table`: one
/// band of a frame. `uv_gradients` is the frame's (`uv_gradients`), shared by its
/// bands. `reuse` is memory to write the samples into (an earlier band's, so that
/// a frame's bands do not each fault in fresh pages), or an empty vector.
pub fn rasterize_rows(
    polygons: &[ScreenPolygon],
    table: &EdgeTable,
    width: u32,
    rows: Range<u32>,
    uv_gradients: Arc<[Option<UvGradient>]>,
    reuse: Vec<Sample>,
) -> VisibleSurface {
    let first_row = rows.start;
    let height = rows.len() as u32;
    let samples = sweep::<_, _, true>(
        polygons,
        table,
        width,
        rows,
        reuse,
        Sample::EMPTY,
        |p, depth, a, z| {
            // Affine texture coordinates are stepped as they are, not over z.
            let uv_z = if p.affine_uv { 1.0 } else { z };
            Sample {
                polygon: p.id,
                element: p.element,
                depth,
                position: DVec3::new(a[0], a[1], a[2]) * z,
                normal: DVec3::new(a[3], a[4], a[5]).normalize_or_zero().as_vec3(),
                uv: DVec2::new(a[UV] * uv_z, a[UV + 1] * uv_z),
                color: Vec3::new((a[8] * z) as f32, (a[9] * z) as f32, (a[10] * z) as f32),
            }
        },
    );
    VisibleSurface {
        width,
        height,
        first_row,
        samples,
        uv_gradients,
    }
}

/// Per polygon id, how its texture coordinates vary across the screen (`None` for
/// ids not among `polygons`).
pub fn uv_gradients(polygons: &[ScreenPolygon]) -> Arc<[Option<UvGradient>]> {
    let mut gradients = Vec::new();
    for p in polygons {
        let id = p.id as usize;
        if gradients.len() <= id {
            gradients.resize(id + 1, None);
        }
        gradients[id] = Some(p.uv_gradient());
    }
    gradients.into()
}

/// The depth (eye distance along the view axis) of the nearest polygon at every
/// sample, infinity where none: the image a depth-buffer pass would hold.
pub fn rasterize_depth(polygons: &[ScreenPolygon], width: u32, height: u32) -> Vec<f32> {
    let table = EdgeTable::build(polygons, height);
    sweep::<_, _, false>(
        polygons,
        &table,
        width,
        0..height,
        Vec::new(),
        f32::INFINITY,
        |_, depth, _, _| depth as f32,
    )
}

/// The id of the nearest polygon at every sample, `NO_POLYGON` where none: an item
/// buffer (Weghorst, Hooper & Greenberg 1984), as the hemicube uses it.
pub fn rasterize_ids(polygons: &[ScreenPolygon], width: u32, height: u32) -> Vec<u32> {
    let table = EdgeTable::build(polygons, height);
    sweep::<_, _, false>(
        polygons,
        &table,
        width,
        0..height,
        Vec::new(),
        NO_POLYGON,
        |p, _, _, _| p.id,
    )
}

/// The sweep of rows `rows`, writing `write(polygon, depth, attributes over z, z)` at
/// each sample where a polygon is visible and `empty` elsewhere, into `samples`
/// (resized; its contents are all overwritten); with `ATTRIBUTES_USED` false the
/// attributes are not stepped (a depth-only pass).
fn sweep<S: Copy + Send + Sync, W, const ATTRIBUTES_USED: bool>(
    polygons: &[ScreenPolygon],
    table: &EdgeTable,
    width: u32,
    rows: Range<u32>,
    mut samples: Vec<S>,
    empty: S,
    write: W,
) -> Vec<S>
where
    W: Fn(&ScreenPolygon, f64, &Attributes, f64) -> S + Sync,
{
    let len = width as usize * rows.len();
    samples.truncate(len);
    // Grown in parallel: the first touch of a large buffer costs as much as the sweep.
    let missing = len - samples.len();
    samples.par_extend(rayon::iter::repeat_n(empty, missing));
    samples
        .par_chunks_mut((width * BAND_ROWS) as usize)
        .enumerate()
        .for_each(|(group, group_rows)| {
            let mut sweep = Sweep::starting_at(table, rows.start + group as u32 * BAND_ROWS);
            for row in group_rows.chunks_mut(width as usize) {
                let y = sweep.row as f64 + 0.5;
                let row_index = sweep.row;
                // Each sample is written once: a span's, or `empty` between spans.
                let mut next = 0;
                sweep.for_each_span(width, |i0, i1, inside, active| {
                    row[next..i0 as usize].fill(empty);
                    next = i1 as usize + 1;
                    let span = Span {
                        y,
                        active,
                        table,
                        row: row_index,
                        polygons,
                        write: &write,
                    };
                    resolve_span::<S, W, ATTRIBUTES_USED>(i0, i1, inside, &span, row)
                });
                row[next..].fill(empty);
                sweep.next_row();
            }
        });
    samples
}

/// What resolving a span needs besides its pixel range: the row, the active edges,
/// the polygon table and what to write per sample.
struct Span<'a, W> {
    y: f64,
    active: &'a [(u32, Crossing)],
    table: &'a EdgeTable,
    row: u32,
    polygons: &'a [ScreenPolygon],
    write: &'a W,
}

/// The samples (x, y) one polygon covers, found by the same sweep (for tests of the
/// fill rule and for passes that need a polygon's footprint).
pub fn covered_samples(polygon: &ScreenPolygon, width: u32, height: u32) -> Vec<(u32, u32)> {
    let mut covered = Vec::new();
    covered_spans(
        std::slice::from_ref(polygon),
        width,
        height,
        |row, i0, i1| {
            covered.extend((i0..=i1).map(|i| (i, row)));
        },
    );
    covered
}

/// Calls `f(row, first, last)` for every span of samples covered by at least one of
/// `polygons`, row by row, left to right (the union of their footprints).
pub fn covered_spans(
    polygons: &[ScreenPolygon],
    width: u32,
    height: u32,
    mut f: impl FnMut(u32, u32, u32),
) {
    let table = EdgeTable::build(polygons, height);
    spans_inside(&table, width, 0..height, |row, i0, i1, _| f(row, i0, i1));
}

/// Calls `f(row, first, last, inside)` for every span of rows `rows` lying inside at
/// least one polygon of `table`, with the indices (in the list the table was built
/// from) of the polygons covering it: the scan-line pass's own view of a span, for
/// methods that count what covers a sample (Crow's shadow volumes).
pub fn spans_inside(
    table: &EdgeTable,
    width: u32,
    rows: Range<u32>,
    mut f: impl FnMut(u32, u32, u32, &[u32]),
) {
    let Some((first, last)) = table.rows() else {
        return;
    };
    let (first, last) = (first.max(rows.start), last.min(rows.end.saturating_sub(1)));
    if first > last {
        return;
    }
    let mut sweep = Sweep::starting_at(table, first);
    let mut ids = Vec::new();
    for _ in first..=last {
        let row = sweep.row;
        sweep.for_each_span(width, |i0, i1, inside, _| {
            ids.clear();
            ids.extend(inside.iter().map(|c| c.polygon));
            f(row, i0 as u32, i1 as u32, &ids)
        });
        sweep.next_row();
    }
}

/// A polygon inside the current span, with its own left and right crossings on this
/// row (indices into the AEL), between which its attributes are interpolated.
#[derive(Clone, Copy, Debug)]
pub(super) struct Inside {
    pub(super) polygon: u32,
    left: usize,
    right: usize,
}

pub(super) struct Sweep<'a> {
    table: &'a EdgeTable,
    pub(super) row: u32,
    /// Active edges with their edge-table index (the tie-break of the sort).
    active: Vec<(u32, Crossing)>,
}

impl<'a> Sweep<'a> {
    pub(super) fn starting_at(table: &'a EdgeTable, row: u32) -> Sweep<'a> {
        let active = table
            .edges
            .iter()
            .enumerate()
            .filter(|(_, e)| e.first_row < row && e.last_row >= row)
            .map(|(k, e)| (k as u32, e.crossing(row - e.first_row)))
            .collect();
        let mut sweep = Sweep { table, row, active };
        sweep.enter_row();
        sweep
    }

    /// Merges this row's bucket, drops finished edges, restores x order.
    fn enter_row(&mut self) {
        let row = self.row;
        self.active.retain(|(_, e)| e.last_row >= row);
        // The stepped list is nearly sorted (edges swap only where they cross):
        // insertion sort is linear there. The entering edges are sorted on their
        // own and merged in, rather than inserted one by one.
        insertion_sort(&mut self.active);
        let bucket = self.table.bucket(row);
        if bucket.is_empty() {
            return;
        }
        let mut entering: Vec<(u32, Crossing)> = bucket
            .iter()
            .map(|&k| (k, self.table.edges[k as usize].crossing(0)))
            .collect();
        entering.sort_unstable_by_key(sort_key);
        let mut merged = Vec::with_capacity(self.active.len() + entering.len());
        let (mut a, mut b) = (
            self.active.iter().peekable(),
            entering.into_iter().peekable(),
        );
        loop {
            match (a.peek(), b.peek()) {
                (Some(x), Some(y)) if sort_key(x) <= sort_key(y) => merged.push(*a.next().unwrap()),
                (_, Some(_)) => merged.push(b.next().unwrap()),
                (Some(_), None) => merged.push(*a.next().unwrap()),
                (None, None) => break,
            }
        }
        self.active = merged;
    }

    pub(super) fn next_row(&mut self) {
        for (_, e) in &mut self.active {
            e.step();
        }
        self.row += 1;
        self.enter_row();
    }

    /// Calls `f(first, last, inside, active)` for every span of this row that covers
    /// at least one sample and lies inside at least one polygon.
    pub(super) fn for_each_span(
        &self,
        width: u32,
        mut f: impl FnMut(i64, i64, &[Inside], &[(u32, Crossing)]),
    ) {
        let active = &self.active;
        // Pair each polygon's crossings in x order: 1st with 2nd, 3rd with 4th…
        let mut order: Vec<(u32, usize)> = active
            .iter()
            .enumerate()
            .map(|(k, (_, e))| (e.polygon, k))
            .collect();
        order.sort_unstable();
        let mut partner = vec![usize::MAX; active.len()];
        for pair in order.chunks_exact(2) {
            if pair[0].0 == pair[1].0 {
                partner[pair[0].1] = pair[1].1;
                partner[pair[1].1] = pair[0].1;
            }
        }
        let mut inside: Vec<Inside> = Vec::new();
        for k in 0..active.len() {
            match partner[k] {
                usize::MAX => continue,
                p if p > k => inside.push(Inside {
                    polygon: active[k].1.polygon,
                    left: k,
                    right: p,
                }),
                _ => inside.retain(|c| c.right != k),
            }
            if inside.is_empty() || k + 1 == active.len() {
                continue;
            }
            let first = first_pixel_at_or_after(active[k].1.x).max(0);
            let last = (first_pixel_at_or_after(active[k + 1].1.x) - 1).min(width as i64 - 1);
            if first <= last {
                f(first, last, &inside, active);
            }
        }
    }
}

/// The order of the active edge list: by x, ties by edge-table index.
fn sort_key((k, e): &(u32, Crossing)) -> (i64, u32) {
    (e.x, *k)
}

fn insertion_sort(active: &mut [(u32, Crossing)]) {
    for i in 1..active.len() {
        let mut j = i;
        while j > 0 && sort_key(&active[j - 1]) > sort_key(&active[j]) {
            active.swap(j - 1, j);
            j -= 1;
        }
    }
}

/// Decides the span [i0, i1] and writes its samples.
fn resolve_span<
    S,
    W: Fn(&ScreenPolygon, f64, &Attributes, f64) -> S,
    const ATTRIBUTES_USED: bool,
>(
    i0: i64,
    i1: i64,
    inside: &[Inside],
    span: &Span<W>,
    row: &mut [S],
) {
    resolve_runs(i0, i1, inside, span.y, span.polygons, |c, a, b| {
        fill_run::<S, W, ATTRIBUTES_USED>(&c, a, b, span, row)
    });
}

/// Decides which of `inside` is nearest over the span [i0, i1] of row centre `y`,
/// calling `run(candidate, first, last)` for each run of one winner: if one
/// candidate is nearest at both ends it is nearest over the whole run; otherwise the
/// run is split where the two winners' depths cross and each part decided again.
pub(super) fn resolve_runs(
    i0: i64,
    i1: i64,
    inside: &[Inside],
    y: f64,
    polygons: &[ScreenPolygon],
    mut run: impl FnMut(Inside, i64, i64),
) {
    if let [only] = inside {
        run(*only, i0, i1);
        return;
    }
    let mut pending = vec![(i0, i1)];
    while let Some((a, b)) = pending.pop() {
        let left = nearest(inside, a as f64 + 0.5, y, polygons);
        let right = nearest(inside, b as f64 + 0.5, y, polygons);
        if left.polygon == right.polygon || a == b {
            run(left, a, b);
            continue;
        }
        // Split where the two winners' depths cross along the row.
        let (p, q) = (
            polygons[left.polygon as usize].plane,
            polygons[right.polygon as usize].plane,
        );
        let crossing = -((p.b - q.b) * y + (p.c - q.c)) / (p.a - q.a);
        let split = if crossing.is_finite() {
            ((crossing - 0.5).floor() as i64).clamp(a, b - 1)
        } else {
            (a + b) / 2
        };
        pending.push((split + 1, b));
        pending.push((a, split));
    }
}

/// The candidate nearest the eye at (x, y): largest ζ, ties to the first given.
fn nearest(inside: &[Inside], x: f64, y: f64, polygons: &[ScreenPolygon]) -> Inside {
    let mut best = inside[0];
    let mut best_zeta = polygons[best.polygon as usize].plane.zeta(x, y);
    for &c in &inside[1..] {
        let zeta = polygons[c.polygon as usize].plane.zeta(x, y);
        if zeta > best_zeta || (zeta == best_zeta && c.polygon < best.polygon) {
            best = c;
            best_zeta = zeta;
        }
    }
    best
}

/// Writes samples i0..=i1 of the row with polygon `c`: ζ and the attributes over z
/// start at i0 (interpolated between the polygon's own crossings) and step by a
/// constant increment per pixel, as in Watkins; each sample divides by ζ for the
/// perspective-correct value and takes its depth from the polygon's plane.
fn fill_run<S, W: Fn(&ScreenPolygon, f64, &Attributes, f64) -> S, const ATTRIBUTES_USED: bool>(
    c: &Inside,
    i0: i64,
    i1: i64,
    span: &Span<W>,
    row: &mut [S],
) {
    let (l, r) = (&span.active[c.left].1, &span.active[c.right].1);
    let edge_of = |k: usize| &span.table.edges[span.active[k].0 as usize];
    let (le, re) = (edge_of(c.left), edge_of(c.right));
    let (l_zeta, r_zeta) = (
        le.zeta_at(span.row - le.first_row),
        re.zeta_at(span.row - re.first_row),
    );
    let attributes_of = |k: usize| {
        let index = span.active[k].0 as usize;
        let first_row = span.table.edges[index].first_row;
        span.table.attributes_at(index, span.row - first_row)
    };
    let (la, ra) = if ATTRIBUTES_USED {
        (attributes_of(c.left), attributes_of(c.right))
    } else {
        ([0.0; ATTRIBUTES], [0.0; ATTRIBUTES])
    };
    let (xl, xr) = (l.x as f64 / FIXED_ONE as f64, r.x as f64 / FIXED_ONE as f64);
    let per_pixel = if xr > xl { 1.0 / (xr - xl) } else { 0.0 };
    let t = (i0 as f64 + 0.5 - xl) * per_pixel;
    let dzeta = (r_zeta - l_zeta) * per_pixel;
    let mut zeta = l_zeta + (r_zeta - l_zeta) * t;
    let mut a = [0.0; ATTRIBUTES];
    let mut da = [0.0; ATTRIBUTES];
    for k in 0..ATTRIBUTES {
        da[k] = (ra[k] - la[k]) * per_pixel;
        a[k] = la[k] + (ra[k] - la[k]) * t;
    }
    let polygon = &span.polygons[c.polygon as usize];
    let mut i0 = i0;
    if ATTRIBUTES_USED {
        // Four samples at a time: ζ and the attributes stepped one sample after
        // another as below, the two divisions (the depth from the plane, z from
        // ζ) in the lanes of one register, the same IEEE-754 quotients bit for bit.
        let plane = polygon.plane;
        let (pa, pb, pc) = (
            f64x4::splat(plane.a),
            f64x4::splat(plane.b),
            f64x4::splat(plane.c),
        );
        let y = f64x4::splat(span.y);
        while i0 + 3 <= i1 {
            let mut xs = [0.0; 4];
            let mut zetas = [0.0; 4];
            let mut attributes = [[0.0; ATTRIBUTES]; 4];
            for lane in 0..4 {
                xs[lane] = (i0 + lane as i64) as f64 + 0.5;
                zetas[lane] = zeta;
                attributes[lane] = a;
                zeta += dzeta;
                for k in 0..ATTRIBUTES {
                    a[k] += da[k];
                }
            }
            // The plane's ζ as `Plane::zeta` sums it: a·x + b·y, then + c.
            let depth = (f64x4::ONE / (pa * f64x4::from(xs) + pb * y + pc)).to_array();
            let z = (f64x4::ONE / f64x4::from(zetas)).to_array();
            for lane in 0..4 {
                row[(i0 + lane as i64) as usize] =
                    (span.write)(polygon, depth[lane], &attributes[lane], z[lane]);
            }
            i0 += 4;
        }
    }
    for i in i0..=i1 {
        let x = i as f64 + 0.5;
        let depth = 1.0 / polygon.plane.zeta(x, span.y);
        row[i as usize] = (span.write)(polygon, depth, &a, 1.0 / zeta);
        if ATTRIBUTES_USED {
            zeta += dzeta;
            for k in 0..ATTRIBUTES {
                a[k] += da[k];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::View;
    use crate::scene::Camera;

    /// Spans filled four samples at a time give every sample the depth the plane
    /// gives its centre, 1/(a·x + b·y + c), bit for bit, whatever the run's length
    /// (the lanes and the scalar tail alike).
    #[test]
    fn every_sample_has_its_planes_depth_bit_for_bit() {
        let camera = Camera {
            eye: DVec3::ZERO,
            look_at: DVec3::NEG_Z,
            up: DVec3::Y,
            fov_y: 60.0,
            width: 61,
            height: 47,
            near: 0.01,
        };
        let view = View::new(&camera, 61, 47);
        let quads = [
            [
                (-1.0, -0.8, -2.0),
                (0.9, -0.7, -3.5),
                (0.6, 0.9, -4.0),
                (-0.9, 0.5, -2.5),
            ],
            [
                (-0.3, -0.3, -1.5),
                (0.3, -0.2, -1.6),
                (0.1, 0.4, -1.8),
                (-0.2, 0.2, -1.4),
            ],
        ];
        let polygons: Vec<ScreenPolygon> = quads
            .iter()
            .enumerate()
            .map(|(id, q)| {
                let points: Vec<DVec3> = q.iter().map(|&(x, y, z)| DVec3::new(x, y, z)).collect();
                ScreenPolygon::from_points(&view, id as u32, &points).unwrap()
            })
            .collect();
        let surface = rasterize(&polygons, 61, 47);
        let mut checked = [0; 2];
        for (k, s) in surface.samples.iter().enumerate() {
            if s.is_empty() {
                continue;
            }
            let (x, y) = ((k % 61) as f64 + 0.5, (k / 61) as f64 + 0.5);
            let plane = polygons[s.polygon as usize].plane;
            assert_eq!(
                s.depth.to_bits(),
                (1.0 / plane.zeta(x, y)).to_bits(),
                "sample {k}"
            );
            checked[s.polygon as usize] += 1;
        }
        assert!(checked[0] > 300 && checked[1] > 100, "{checked:?}");
    }
}
