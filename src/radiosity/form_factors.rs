//! The three ways to estimate form factors from a point, behind one interface, and
//! the patch-to-patch matrix they give when averaged over each patch's elements.

use super::analytic::Analytic;
use super::hemicube::Hemicube;
use super::mesh::Mesh;
use super::nusselt::Nusselt;
use super::receivers::Receivers;
use crate::scene::Scene;
use crate::scene::ray_queries::SceneRays;
use glam::DVec3;
use rayon::prelude::*;

pub use crate::settings::FormFactorMethod;

/// A form-factor estimator ready to use.
pub enum Estimator<'a> {
    Hemicube(Hemicube),
    Nusselt(Nusselt),
    Analytic(Analytic<'a>),
}

impl<'a> Estimator<'a> {
    /// `resolution` is the hemi-cube's top-face cells per side, or the Nusselt
    /// grid's; the analytic method has none.
    pub fn new(method: FormFactorMethod, resolution: u32, scene: &'a Scene) -> Estimator<'a> {
        match method {
            FormFactorMethod::Hemicube => Estimator::Hemicube(Hemicube::new(resolution)),
            FormFactorMethod::Nusselt => Estimator::Nusselt(Nusselt { resolution }),
            FormFactorMethod::Analytic => Estimator::Analytic(Analytic {
                occluders: SceneRays::new(&scene.polygons),
            }),
        }
    }

    /// F from the point `centre` (unit normal `normal`) to every receiver, those
    /// for which `skip` holds left at zero.
    pub fn factors(
        &self,
        centre: DVec3,
        normal: DVec3,
        receivers: &Receivers,
        skip: &(dyn Fn(usize) -> bool + Sync),
    ) -> Vec<f64> {
        match self {
            Estimator::Hemicube(h) => h.factors(centre, normal, receivers, skip),
            Estimator::Nusselt(n) => n.factors(centre, normal, receivers, skip),
            Estimator::Analytic(a) => a.factors(centre, normal, receivers, skip),
        }
    }

    /// Per element, its factors to every patch (its own patch left at zero): the
    /// element-to-patch factors of substructuring, one estimate at each element's
    /// centre. Row-major, elements × patches.
    pub fn element_to_patch(&self, mesh: &Mesh) -> Vec<Vec<f32>> {
        let patches = Receivers::patches(mesh);
        mesh.elements
            .par_iter()
            .map(|e| {
                let normal = mesh.patches[e.patch].normal;
                let own = e.patch;
                self.factors(e.centre, normal, &patches, &|j| j == own)
                    .into_iter()
                    .map(|f| f as f32)
                    .collect()
            })
            .collect()
    }
}

/// Patch-to-patch factors from element-to-patch ones, by area weighting:
/// F_ij = (1/A_i) Σ_q A_iq F_(iq)j.
pub fn patch_factors(mesh: &Mesh, element_rows: &[Vec<f32>]) -> Vec<Vec<f64>> {
    mesh.patches
        .par_iter()
        .map(|p| {
            let mut row = vec![0.0; mesh.patches.len()];
            for e in p.elements.clone() {
                let a = mesh.elements[e].area / p.area;
                for (f, &fe) in row.iter_mut().zip(&element_rows[e]) {
                    *f += a * fe as f64;
                }
            }
            row
        })
        .collect()
}

/// One patch of a [`PatchMatrix`]: a whole polygon.
#[derive(Clone, Debug)]
pub struct MatrixPatch {
    /// The polygon's index in the scene's polygons.
    pub polygon: usize,
    /// Its area, in the scene's units squared.
    pub area: f64,
}

/// The form factors between a scene's polygons, each polygon one patch.
#[derive(Clone, Debug)]
pub struct PatchMatrix {
    /// The patches, in the order of the rows and columns.
    pub patches: Vec<MatrixPatch>,
    /// F_ij: row i from patch i, column j to patch j.
    pub factors: Vec<Vec<f64>>,
    /// What meshing the scene left out, one sentence each.
    pub warnings: Vec<String>,
}

/// F_ij between every pair of `scene`'s polygons by `method` at `resolution`: each
/// source polygon cut into `elements` × `elements` elements, one estimate at each
/// element's centre, area-averaged into its patch's row (the analytic method
/// integrates over the receiving patch from those points).
pub fn polygon_form_factors(
    scene: &Scene,
    method: crate::settings::FormFactorMethod,
    resolution: u32,
    elements: u32,
) -> crate::error::Result<PatchMatrix> {
    use crate::settings::Division;
    let mesh = Mesh::build(scene, Division::Whole, Division::Count(elements))?;
    let estimator = Estimator::new(method, resolution, scene);
    let factors = patch_factors(&mesh, &estimator.element_to_patch(&mesh));
    let patches = mesh
        .patches
        .iter()
        .map(|p| MatrixPatch {
            polygon: p.polygon,
            area: p.area,
        })
        .collect();
    Ok(PatchMatrix {
        patches,
        factors,
        warnings: mesh.warnings,
    })
}
