//! Adaptive subdivision, step 6 of Cohen, Greenberg, Immel & Brock (IEEE CG&A 1986):
//! after the patch system is solved and the elements have gathered from it, elements
//! whose radiosity differs from a neighbour's by more than a threshold are cut into
//! four; only the new elements get hemi-cubes (element-to-patch factors), and each
//! gathers once from the unchanged patch radiosities (step 5). Repeated for a given
//! number of levels, this puts small elements where shading varies (shadow edges)
//! and leaves large ones where it does not.
//!
//! Choices where the paper leaves details open: two elements are neighbours when
//! their outlines share a vertex (corners and T-vertices, so diagonal neighbours
//! count); they differ by the largest band difference, measured against the largest
//! radiosity of any element that emits nothing; both elements of a differing pair
//! are cut; the patch factors and patch solution are not recomputed (the paper
//! reuses the patch solution).

use super::form_factors::Estimator;
use super::mesh::Mesh;
use super::receivers::Receivers;
use glam::DVec3;
use rayon::prelude::*;

pub use crate::settings::Subdivision;

/// A refined solution: the mesh, every element's radiosity, and how many elements
/// each round cut.
pub struct Refined {
    pub mesh: Mesh,
    pub elements: Vec<DVec3>,
    pub cut: Vec<usize>,
}

/// Refines `mesh`, whose elements have radiosities `elements`, against the patch
/// radiosities `patches`.
pub fn refine(
    mut mesh: Mesh,
    mut elements: Vec<DVec3>,
    patches: &[DVec3],
    estimator: &Estimator,
    subdivision: Subdivision,
) -> Refined {
    let reference = elements
        .iter()
        .zip(&mesh.elements)
        .filter(|(_, e)| mesh.patches[e.patch].emission.max_element() <= 0.0)
        .map(|(b, _)| b.max_element())
        .fold(0.0, f64::max);
    let limit = subdivision.threshold * reference;
    let receivers = Receivers::patches(&mesh);
    let mut cut = Vec::new();
    for _ in 0..subdivision.levels {
        let marked = differing(&mesh, &elements, limit);
        let count = marked.iter().filter(|&&m| m).count();
        if count == 0 {
            break;
        }
        cut.push(count);
        let (finer, origin) = mesh.refine(&marked);
        elements = origin
            .par_iter()
            .enumerate()
            .map(|(e, from)| match *from {
                Ok(old) => elements[old],
                Err(_) => {
                    let element = &finer.elements[e];
                    let patch = &finer.patches[element.patch];
                    let own = element.patch;
                    let row =
                        estimator.factors(element.centre, patch.normal, &receivers, &|j| j == own);
                    let gathered: DVec3 = row.iter().zip(patches).map(|(&f, b)| *b * f).sum();
                    patch.emission.as_dvec3() + patch.reflectance.as_dvec3() * gathered
                }
            })
            .collect();
        mesh = finer;
    }
    Refined {
        mesh,
        elements,
        cut,
    }
}

/// The elements that differ from a neighbour by more than `limit` in some band.
pub fn differing(mesh: &Mesh, elements: &[DVec3], limit: f64) -> Vec<bool> {
    let mut marked = vec![false; elements.len()];
    for users in mesh.vertex_elements() {
        for (k, &a) in users.iter().enumerate() {
            for &b in &users[k + 1..] {
                let (a, b) = (a as usize, b as usize);
                if (elements[a] - elements[b]).abs().max_element() > limit {
                    marked[a] = true;
                    marked[b] = true;
                }
            }
        }
    }
    marked
}
