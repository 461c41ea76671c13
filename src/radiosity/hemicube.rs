//! The hemi-cube: M. F. Cohen, D. P. Greenberg, "The hemi-cube: a radiosity solution
//! for complex environments", SIGGRAPH '85.
//!
//! Nusselt's analog says that the form factor from a point to a surface depends only
//! on the surface's projection onto the hemisphere around the point, so any surface
//! enclosing the point will do: half a cube, whose faces are image planes. The top
//! face (z = 1, x, y ∈ [−1, 1]) has R × R cells, the four sides (x = ±1 or y = ±1,
//! z ∈ [0, 1]) R × R/2; a cell of area ΔA = (2/R)² at (x, y, 1) carries the delta
//! form factor ΔA / (π (x² + y² + 1)²), one at height z on a side z ΔA / (π (u² + z²
//! + 1)²) with u its position across the side. The tables are computed once.
//!
//! For a point, every receiver is rasterized onto the five faces by the project's own
//! scan-line pass with a 90° perspective from the point (the side faces' views end at
//! the horizon: geometry below the tangent plane is clipped away), keeping in each
//! cell the id of the nearest receiver: an item buffer. The factor to receiver j is
//! the sum of the delta form factors of the cells that show j.
//!
//! Choices left open: the faces' orientation about the normal is any fixed
//! orthonormal pair (glam's `any_orthonormal_pair`); a receiver seen from behind
//! still hides what lies beyond it but receives nothing (surfaces are one-sided); the
//! full tables are stored rather than the paper's one-eighth and one-half by symmetry.

use super::receivers::Receivers;
use crate::raster::{NO_POLYGON, RasterVertex, ScreenPolygon, View, rasterize_ids};
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// Item-buffer id of a receiver seen from behind.
pub const BACK: u32 = u32::MAX - 1;

/// A hemi-cube of a given resolution and its delta form-factor tables.
#[derive(Clone, Debug)]
pub struct Hemicube {
    resolution: u32,
    /// Top face, row-major R × R, row 0 at +y.
    top: Vec<f64>,
    /// A side face, row-major R × R/2, row 0 at z = 1 (the rim), the last at the
    /// horizon.
    side: Vec<f64>,
}

impl Hemicube {
    /// `resolution` cells along the top face (even, at least 2).
    pub fn new(resolution: u32) -> Hemicube {
        let r = resolution.max(2) & !1;
        let cell = 2.0 / r as f64;
        let da = cell * cell;
        let centre = |k: u32| -1.0 + (k as f64 + 0.5) * cell;
        let top = (0..r)
            .flat_map(|j| (0..r).map(move |i| (i, j)))
            .map(|(i, j)| {
                let (x, y) = (centre(i), -centre(j));
                da / (std::f64::consts::PI * (x * x + y * y + 1.0).powi(2))
            })
            .collect();
        let side = (0..r / 2)
            .flat_map(|j| (0..r).map(move |i| (i, j)))
            .map(|(i, j)| {
                let (u, z) = (centre(i), 1.0 - (j as f64 + 0.5) * cell);
                z * da / (std::f64::consts::PI * (u * u + z * z + 1.0).powi(2))
            })
            .collect();
        Hemicube {
            resolution: r,
            top,
            side,
        }
    }

    /// Sums of the delta form factors: the top face's and one side's.
    pub fn face_sums(&self) -> (f64, f64) {
        (self.top.iter().sum(), self.side.iter().sum())
    }

    /// The delta form factors of face `face` (0 the top, 1 to 4 the sides), row-major
    /// as its item buffer.
    pub(crate) fn deltas(&self, face: usize) -> &[f64] {
        if face == 0 { &self.top } else { &self.side }
    }

    /// The five faces' views from `centre` with the top face along `normal`.
    pub(crate) fn views(&self, centre: DVec3, normal: DVec3) -> [View; 5] {
        let (t, b) = normal.any_orthonormal_pair();
        let r = self.resolution;
        let half = r as f64 / 2.0;
        let view = |forward: DVec3, up: DVec3, height: u32, centre_y: f64| View {
            eye: centre,
            right: forward.cross(up),
            up,
            forward,
            focal: half,
            width: r,
            height,
            centre: DVec2::new(half, centre_y),
            // Receivers touch the point only at the patch's own edges, which the
            // tangent plane already hides; a tiny near plane keeps ζ finite.
            near: 1e-9,
        };
        [
            view(normal, b, r, half),
            view(t, normal, r / 2, half),
            view(-t, normal, r / 2, half),
            view(b, normal, r / 2, half),
            view(-b, normal, r / 2, half),
        ]
    }

    /// F from the point `centre` (unit normal `normal`) to every receiver; receivers
    /// for which `skip` holds are not drawn (the patch's own pieces).
    pub fn factors(
        &self,
        centre: DVec3,
        normal: DVec3,
        receivers: &Receivers,
        skip: &(dyn Fn(usize) -> bool + Sync),
    ) -> Vec<f64> {
        let buffers: Vec<Vec<u32>> = self
            .views(centre, normal)
            .par_iter()
            .map(|view| self.item_buffer(view, receivers, skip))
            .collect();
        let mut factors = vec![0.0; receivers.len()];
        for (face, ids) in buffers.iter().enumerate() {
            let table = if face == 0 { &self.top } else { &self.side };
            for (&id, &delta) in ids.iter().zip(table) {
                if id != NO_POLYGON && id != BACK {
                    factors[id as usize] += delta;
                }
            }
        }
        factors
    }

    /// The item buffers of the five faces from `centre` (top face along `normal`):
    /// the nearest receiver at every cell, `NO_POLYGON` where none and `BACK` where a
    /// receiver is seen from behind; with each face's name and size.
    pub fn faces(
        &self,
        centre: DVec3,
        normal: DVec3,
        receivers: &Receivers,
        skip: &(dyn Fn(usize) -> bool + Sync),
    ) -> Vec<(&'static str, u32, u32, Vec<u32>)> {
        const NAMES: [&str; 5] = ["top", "side1", "side2", "side3", "side4"];
        self.views(centre, normal)
            .iter()
            .zip(NAMES)
            .map(|(view, name)| {
                let ids = self.item_buffer(view, receivers, skip);
                (name, view.width, view.height, ids)
            })
            .collect()
    }

    /// The nearest receiver at every cell of one face.
    pub fn item_buffer(
        &self,
        view: &View,
        receivers: &Receivers,
        skip: &(dyn Fn(usize) -> bool + Sync),
    ) -> Vec<u32> {
        let frustum = view.frustum();
        let polygons: Vec<ScreenPolygon> = (0..receivers.len())
            .filter(|&r| !skip(r))
            .filter_map(|r| {
                let polygon = &receivers.polygons[r];
                let eye: Vec<DVec3> = polygon.positions().map(|p| view.to_eye(p)).collect();
                if View::rejects(&frustum, &eye) {
                    return None;
                }
                let id = if receivers.faces(r, view.eye) {
                    r as u32
                } else {
                    BACK
                };
                let vertices = eye
                    .into_iter()
                    .map(|eye| RasterVertex {
                        eye,
                        attributes: [0.0; crate::raster::ATTRIBUTES],
                    })
                    .collect();
                ScreenPolygon::new(view, id, vertices)
            })
            .collect();
        rasterize_ids(&polygons, view.width, view.height)
    }
}
