//! A radiosity solution read anywhere on the scene's polygons, as the second pass's
//! rays and the final gather's read it where they land: the element holding the
//! point found through a grid over its polygon's plane, and the element's vertex
//! values interpolated over its fan triangles (Gouraud on the screen interpolates
//! along edges and spans; both agree on the element's edges).

use crate::radiosity::{Display, Mesh, display};
use crate::scene::ray_queries::{contains, fan_weights};
use crate::scene::{Polygon, Scene, Vertex};
use glam::{DVec2, DVec3, Vec3};

/// The radiance B/π of a solution (or of any per-element radiosity on its mesh)
/// leaving the front of the scene's polygons.
pub struct SolutionRadiance {
    /// Per scene polygon, its elements on a grid.
    grids: Vec<ElementGrid>,
    outlines: Vec<Polygon>,
    colors: Vec<Vec<Vec3>>,
}

/// The elements of one polygon, bucketed by the cells of a grid over its plane
/// their bounds overlap: a lookup tests the few elements of one cell, not all.
#[derive(Default)]
struct ElementGrid {
    origin: DVec3,
    u: DVec3,
    v: DVec3,
    low: DVec2,
    cell: DVec2,
    side: usize,
    cells: Vec<Vec<u32>>,
    elements: Vec<u32>,
}

impl ElementGrid {
    fn new(polygon: &Polygon, elements: Vec<u32>, outlines: &[Polygon]) -> ElementGrid {
        let origin = polygon.vertices[0].position;
        let n = polygon.normal;
        let edge = polygon.vertices[1 % polygon.vertices.len()].position - origin;
        let u = (edge - n * edge.dot(n)).normalize_or(n.any_orthonormal_vector());
        let v = n.cross(u);
        let flat = |p: DVec3| DVec2::new((p - origin).dot(u), (p - origin).dot(v));
        let bounds: Vec<(DVec2, DVec2)> = elements
            .iter()
            .map(|&e| {
                outlines[e as usize].vertices.iter().fold(
                    (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
                    |(lo, hi), vertex| {
                        (lo.min(flat(vertex.position)), hi.max(flat(vertex.position)))
                    },
                )
            })
            .collect();
        let (low, high) = bounds.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), b| (lo.min(b.0), hi.max(b.1)),
        );
        // About one element a cell.
        let side = (elements.len() as f64).sqrt().ceil().max(1.0) as usize;
        let cell = ((high - low) / side as f64).max(DVec2::splat(f64::MIN_POSITIVE));
        let mut cells = vec![Vec::new(); side * side];
        let index = |x: f64, size: f64, lo: f64| {
            (((x - lo) / size).floor().max(0.0) as usize).min(side - 1)
        };
        for (&e, (lo, hi)) in elements.iter().zip(&bounds) {
            if !lo.x.is_finite() {
                continue;
            }
            for y in index(lo.y, cell.y, low.y)..=index(hi.y, cell.y, low.y) {
                for x in index(lo.x, cell.x, low.x)..=index(hi.x, cell.x, low.x) {
                    cells[y * side + x].push(e);
                }
            }
        }
        ElementGrid {
            origin,
            u,
            v,
            low,
            cell,
            side,
            cells,
            elements,
        }
    }

    /// The elements whose bounds may hold `p` (all of them if `p` is off the grid).
    fn near(&self, p: DVec3) -> &[u32] {
        if self.cells.is_empty() {
            return &self.elements;
        }
        let d = p - self.origin;
        let at = (DVec2::new(d.dot(self.u), d.dot(self.v)) - self.low) / self.cell;
        let inside = |x: f64| x >= 0.0 && x < self.side as f64;
        if !(inside(at.x) && inside(at.y)) {
            return &self.elements;
        }
        &self.cells[at.y as usize * self.side + at.x as usize]
    }
}

impl SolutionRadiance {
    /// The radiance of per-element radiosities `elements` on `mesh`, drawn as
    /// `display` draws them.
    pub fn new(
        scene: &Scene,
        mesh: &Mesh,
        elements: &[Vec3],
        display: Display,
    ) -> SolutionRadiance {
        let pieces = display::element_polygons(scene, mesh, elements, display);
        let mut of_polygon = vec![Vec::new(); scene.polygons.len()];
        let mut outlines = Vec::with_capacity(pieces.len());
        let mut colors = Vec::with_capacity(pieces.len());
        for (e, piece) in pieces.into_iter().enumerate() {
            of_polygon[piece.polygon].push(e as u32);
            let normal = scene.polygons[piece.polygon].normal;
            outlines.push(Polygon {
                vertices: piece
                    .vertices
                    .iter()
                    .map(|v| Vertex {
                        position: v.position,
                        ..*v
                    })
                    .collect(),
                normal,
                material: 0,
                object: 0,
            });
            colors.push(piece.colors);
        }
        let grids = of_polygon
            .into_iter()
            .enumerate()
            .map(|(p, elements)| {
                if elements.is_empty() {
                    ElementGrid::default()
                } else {
                    ElementGrid::new(&scene.polygons[p], elements, &outlines)
                }
            })
            .collect();
        SolutionRadiance {
            grids,
            outlines,
            colors,
        }
    }

    /// Radiance leaving the front of polygon `polygon` at `position`.
    pub fn at(&self, polygon: u32, position: DVec3) -> Vec3 {
        let grid = &self.grids[polygon as usize];
        let near = grid.near(position);
        let Some(&e) = near
            .iter()
            .find(|&&e| contains(&self.outlines[e as usize], position))
            .or_else(|| {
                // On an edge, where rounding leaves the point in no element: the
                // nearest element by its first corner is close enough.
                let candidates = if near.is_empty() {
                    &grid.elements
                } else {
                    near
                };
                candidates.iter().min_by(|&&a, &&b| {
                    let d = |e: u32| {
                        (self.outlines[e as usize].vertices[0].position - position).length()
                    };
                    d(a).total_cmp(&d(b))
                })
            })
        else {
            return Vec3::ZERO;
        };
        let outline = &self.outlines[e as usize];
        let colors = &self.colors[e as usize];
        let v = &outline.vertices;
        match fan_weights(v.len(), |k| v[k].position, outline.normal, position) {
            Some((i, w)) => {
                (colors[0] * w[0] as f32 + colors[i] * w[1] as f32 + colors[i + 1] * w[2] as f32)
                    .max(Vec3::ZERO)
            }
            None => colors[0],
        }
    }
}
