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
    /// ζ and attributes over z at the first row, and per row.
    pub zeta: f64,
    pub dzeta: f64,
    pub attributes: Attributes,
    pub dattributes: Attributes,
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

    /// The attributes over z `rows` rows below the first row (evaluated, not
    /// stepped: the same value whichever row a sweep started from).
    pub fn attributes_at(&self, rows: u32) -> Attributes {
        let k = rows as f64;
        let mut attributes = self.attributes;
        for (a, d) in attributes.iter_mut().zip(self.dattributes) {
            *a += k * d;
        }
        attributes
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
    /// Edge indices sorted by first row (stable): the buckets, end to end.
    by_first_row: Vec<u32>,
}

impl EdgeTable {
    pub fn build(polygons: &[ScreenPolygon], height: u32) -> EdgeTable {
        let mut edges = Vec::new();
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
                let mut attributes = [0.0; ATTRIBUTES];
                let mut dattributes = [0.0; ATTRIBUTES];
                for k in 0..ATTRIBUTES {
                    let (p, q) = (top.attributes_over_z[k], bottom.attributes_over_z[k]);
                    attributes[k] = p + (q - p) * t;
                    dattributes[k] = (q - p) / span;
                }
                edges.push(Edge {
                    polygon: index as u32,
                    first_row: first as u32,
                    last_row: last as u32,
                    x: to_fixed(x),
                    dx: to_fixed(dxdy.clamp(-MAX_DX, MAX_DX)),
                    zeta: top.zeta + (bottom.zeta - top.zeta) * t,
                    dzeta: (bottom.zeta - top.zeta) / span,
                    attributes,
                    dattributes,
                });
            }
        }
        let mut by_first_row: Vec<u32> = (0..edges.len() as u32).collect();
        by_first_row.sort_by_key(|&k| edges[k as usize].first_row);
        EdgeTable {
            edges,
            by_first_row,
        }
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
