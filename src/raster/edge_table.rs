//! Watkins' edge table: every non-horizontal polygon edge, bucketed by the first
//! scan line it crosses, with its x there and its increment per row.
//!
//! x is kept in 32.32 fixed point so that stepping x += Δx row by row is exact: k
//! steps land on x₀ + kΔx bit for bit, so a band of rows can start anywhere and
//! still see the same crossings as a sweep from the top (the result depends neither
//! on how the frame is cut into bands nor on how rows are shared between threads).
//! Depth ζ and the attributes over z are evaluated at each row from the edge's first
//! row (not stepped), for the same reason. An edge is entered with its endpoints in a
//! canonical order, so the two polygons sharing an edge get identical crossings.
//!
//! The table keeps its edges in the order the polygons gave them (the tie-break of
//! the active list's sort) and, beside them, their indices sorted by first row: a
//! row's bucket is a range of that list, so the table's size does not grow with the
//! frame's height.
//!
//! The attributes over z, 22 numbers an edge, are kept beside the edges rather than
//! in them: a table built for coverage alone (the shadow or detail polygons on a
//! receiver, which only say where they lie) leaves them out, and a receiver holding
//! a million shadow polygons then takes 48 bytes an edge instead of 224.

use super::ScreenPolygon;
use super::project::{ATTRIBUTES, Attributes};

/// 1.0 in the fixed-point x.
pub const FIXED_ONE: i64 = 1 << 32;
/// |Δx| is capped so that x stays far from overflow; an edge steeper than this
/// crosses a single row, where Δx is never used.
const MAX_DX: f64 = (1u64 << 24) as f64;

#[derive(Clone, Debug)]
pub struct Edge {
    /// Index of the owning polygon in the list given to `EdgeTable::build`.
    pub polygon: u32,
    pub first_row: u32,
    pub last_row: u32,
    /// x at the first row's centre, and per row, in 32.32 fixed point.
    pub x: i64,
    pub dx: i64,
    /// ζ at the first row, and per row.
    pub zeta: f64,
    pub dzeta: f64,
}

/// An edge's attributes over z at its first row, and per row.
#[derive(Clone, Debug)]
struct EdgeAttributes {
    at_first_row: Attributes,
    per_row: Attributes,
}

impl Edge {
    /// The edge's crossing `rows` rows below its first: exactly `rows` applications
    /// of the increment for x.
    pub fn crossing(&self, rows: u32) -> Crossing {
        Crossing {
            polygon: self.polygon,
            last_row: self.last_row,
            x: self.x + rows as i64 * self.dx,
            dx: self.dx,
        }
    }

    /// ζ `rows` rows below the first row (evaluated, like the attributes).
    pub fn zeta_at(&self, rows: u32) -> f64 {
        self.zeta + rows as f64 * self.dzeta
    }
}

/// What the active edge list keeps of an edge on the current row: small, so that
/// keeping the list sorted moves little memory. Depth and attributes stay in the
/// table.
#[derive(Clone, Copy, Debug)]
pub struct Crossing {
    pub polygon: u32,
    pub last_row: u32,
    pub x: i64,
    pub dx: i64,
}

impl Crossing {
    pub fn step(&mut self) {
        self.x += self.dx;
    }
}

pub struct EdgeTable {
    pub edges: Vec<Edge>,
    /// The attributes of each edge, by index; empty for a table of coverage alone.
    attributes: Vec<EdgeAttributes>,
    /// Edge indices sorted by first row (stable): the buckets, end to end.
    by_first_row: Vec<u32>,
}

impl EdgeTable {
    pub fn build(polygons: &[ScreenPolygon], height: u32) -> EdgeTable {
        EdgeTable::with(polygons, height, true)
    }

    /// A table of where the polygons lie, without their attributes: for sweeps that
    /// only ask which polygons cover a span (`spans_inside`), not what they carry.
    pub fn coverage(polygons: &[ScreenPolygon], height: u32) -> EdgeTable {
        EdgeTable::with(polygons, height, false)
    }

    fn with(polygons: &[ScreenPolygon], height: u32, with_attributes: bool) -> EdgeTable {
        let corners = polygons.iter().map(|p| p.vertices.len()).sum();
        let mut edges = Vec::with_capacity(corners);
        let mut attributes = Vec::with_capacity(if with_attributes { corners } else { 0 });
        for (index, polygon) in polygons.iter().enumerate() {
            let n = polygon.vertices.len();
            for i in 0..n {
                let (a, b) = (&polygon.vertices[i], &polygon.vertices[(i + 1) % n]);
                if a.y == b.y {
                    continue; // horizontal edges cross no row
                }
                let (top, bottom) = if (a.y, a.x) < (b.y, b.x) {
                    (a, b)
                } else {
                    (b, a)
                };
                // Rows whose centre j + 0.5 lies in [top.y, bottom.y).
                let first = (top.y - 0.5).ceil().max(0.0);
                let last = ((bottom.y - 0.5).ceil() - 1.0).min(height as f64 - 1.0);
                if last < first {
                    continue;
                }
                let span = bottom.y - top.y;
                let t = (first + 0.5 - top.y) / span;
                let dxdy = (bottom.x - top.x) / span;
                let x = top.x + (first + 0.5 - top.y) * dxdy;
                if with_attributes {
                    let mut at_first_row = [0.0; ATTRIBUTES];
                    let mut per_row = [0.0; ATTRIBUTES];
                    for k in 0..ATTRIBUTES {
                        let (p, q) = (top.attributes_over_z[k], bottom.attributes_over_z[k]);
                        at_first_row[k] = p + (q - p) * t;
                        per_row[k] = (q - p) / span;
                    }
                    attributes.push(EdgeAttributes {
                        at_first_row,
                        per_row,
                    });
                }
                edges.push(Edge {
                    polygon: index as u32,
                    first_row: first as u32,
                    last_row: last as u32,
                    x: to_fixed(x),
                    dx: to_fixed(dxdy.clamp(-MAX_DX, MAX_DX)),
                    zeta: top.zeta + (bottom.zeta - top.zeta) * t,
                    dzeta: (bottom.zeta - top.zeta) / span,
                });
            }
        }
        let mut by_first_row: Vec<u32> = (0..edges.len() as u32).collect();
        by_first_row.sort_by_key(|&k| edges[k as usize].first_row);
        EdgeTable {
            edges,
            attributes,
            by_first_row,
        }
    }

    /// Edge `k`'s attributes over z `rows` rows below its first row (evaluated, not
    /// stepped: the same value whichever row a sweep started from). Only for a
    /// table built with them.
    pub fn attributes_at(&self, k: usize, rows: u32) -> Attributes {
        let edge = &self.attributes[k];
        let rows = rows as f64;
        let mut attributes = edge.at_first_row;
        for (a, d) in attributes.iter_mut().zip(edge.per_row) {
            *a += rows * d;
        }
        attributes
    }

    /// The edges whose first row is `row`, in the order their polygons gave them.
    pub fn bucket(&self, row: u32) -> &[u32] {
        let first_row = |k: &u32| self.edges[*k as usize].first_row;
        let start = self.by_first_row.partition_point(|k| first_row(k) < row);
        let end = self.by_first_row.partition_point(|k| first_row(k) <= row);
        &self.by_first_row[start..end]
    }

    /// The first and last rows any edge crosses, `None` for an empty table.
    pub fn rows(&self) -> Option<(u32, u32)> {
        let first = self.edges.iter().map(|e| e.first_row).min()?;
        let last = self.edges.iter().map(|e| e.last_row).max()?;
        Some((first, last))
    }
}

fn to_fixed(x: f64) -> i64 {
    (x * FIXED_ONE as f64).round() as i64
}

/// The first pixel whose centre is at or right of the fixed-point x: ceil(x − ½).
pub fn first_pixel_at_or_after(x: i64) -> i64 {
    let shifted = x - FIXED_ONE / 2;
    -((-shifted) >> 32)
}
