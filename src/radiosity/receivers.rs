//! What a form-factor estimate looks at: a list of planar polygons (the patches, or
//! the elements), each one receiver. Estimates from a point return one factor per
//! receiver.

use super::mesh::Mesh;
use crate::geometry::bvh::{Aabb, Bvh};
use crate::scene::{Polygon, Vertex};
use glam::{DVec2, DVec3};

pub struct Receivers {
    pub polygons: Vec<Polygon>,
    pub centres: Vec<DVec3>,
    pub areas: Vec<f64>,
    /// The patch each receiver belongs to (itself, for patches).
    pub patch: Vec<usize>,
    bvh: Bvh,
}

impl Receivers {
    /// Every patch of the mesh, whole.
    pub fn patches(mesh: &Mesh) -> Receivers {
        let polygons = mesh
            .patches
            .iter()
            .map(|p| polygon(&p.corners, p.normal))
            .collect();
        Receivers::new(
            polygons,
            mesh.patches.iter().map(|p| p.centre).collect(),
            mesh.patches.iter().map(|p| p.area).collect(),
            (0..mesh.patches.len()).collect(),
        )
    }

    /// Every element of the mesh.
    pub fn elements(mesh: &Mesh) -> Receivers {
        let polygons = (0..mesh.elements.len())
            .map(|e| {
                let normal = mesh.patches[mesh.elements[e].patch].normal;
                polygon(&mesh.element_corners(e), normal)
            })
            .collect();
        Receivers::new(
            polygons,
            mesh.elements.iter().map(|e| e.centre).collect(),
            mesh.elements.iter().map(|e| e.area).collect(),
            mesh.elements.iter().map(|e| e.patch).collect(),
        )
    }

    fn new(
        polygons: Vec<Polygon>,
        centres: Vec<DVec3>,
        areas: Vec<f64>,
        patch: Vec<usize>,
    ) -> Receivers {
        let boxes: Vec<Aabb> = polygons.iter().map(|p| Aabb::of(p.positions())).collect();
        Receivers {
            bvh: Bvh::build(&boxes),
            polygons,
            centres,
            areas,
            patch,
        }
    }

    pub fn len(&self) -> usize {
        self.polygons.len()
    }

    pub fn is_empty(&self) -> bool {
        self.polygons.is_empty()
    }

    /// Whether receiver `r` can receive from `p`: `p` is in front of its plane.
    pub fn faces(&self, r: usize, p: DVec3) -> bool {
        (p - self.centres[r]).dot(self.polygons[r].normal) > 0.0
    }

    /// The receivers in a hierarchy of boxes, for rays.
    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }
}

/// A bare polygon (no shading attributes) for the receiver lists.
fn polygon(corners: &[DVec3], normal: DVec3) -> Polygon {
    Polygon {
        vertices: corners
            .iter()
            .map(|&position| Vertex {
                position,
                normal,
                uv: DVec2::ZERO,
            })
            .collect(),
        normal,
        material: 0,
        object: 0,
    }
}
