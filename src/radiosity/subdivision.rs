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
use super::mesh::{Mesh, MeshCounts};
use super::receivers::Receivers;
use crate::error::OverBudget;
use crate::error::{Error, Result};
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
/// radiosities `patches`. Before each level is cut, the memory the finer mesh and
/// the coarser one it is cut from hold together is estimated and checked against
/// `budget` bytes: the number of elements can grow fourfold a level.
pub fn refine(
    mut mesh: Mesh,
    mut elements: Vec<DVec3>,
    patches: &[DVec3],
    estimator: &Estimator,
    subdivision: Subdivision,
    budget: u64,
) -> Result<Refined> {
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
        check_level(&mesh, count, cut.len(), subdivision, budget)?;
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
    Ok(Refined {
        mesh,
        elements,
        cut,
    })
}

/// Refuses a level that would cut `count` elements of `mesh` into four if the
/// finer mesh, beside the one it is cut from, would need more than `budget` bytes.
/// Each cut element gives three more elements and at most five more vertices (its
/// edges' midpoints and, for a quadrilateral, its centre).
fn check_level(
    mesh: &Mesh,
    count: usize,
    level: usize,
    subdivision: Subdivision,
    budget: u64,
) -> Result<()> {
    let now = MeshCounts {
        patches: mesh.patches.len() as u64,
        elements: mesh.elements.len() as u64,
        vertices: mesh.vertices.len() as u64,
    };
    let count = count as u64;
    let finer = MeshCounts {
        patches: now.patches,
        elements: now.elements.saturating_add(count.saturating_mul(3)),
        vertices: now.vertices.saturating_add(count.saturating_mul(5)),
    };
    let needed = now.bytes().saturating_add(finer.bytes());
    if needed <= budget && finer.vertices <= u32::MAX as u64 {
        return Ok(());
    }
    Err(Error::OverBudget(Box::new(OverBudget {
        key: "radiosity.subdivide".into(),
        value: subdivision.threshold.to_string(),
        what: format!(
            "level {level} of adaptive subdivision (cutting {count} of {} elements into four)",
            now.elements
        ),
        needed,
        budget,
        budget_key: "radiosity.max_memory_mb".into(),
        suggestion: "use a larger subdivide threshold or fewer subdivision_levels, or raise radiosity.max_memory_mb".into(),
    })))
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
