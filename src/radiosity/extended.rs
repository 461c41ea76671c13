//! Radiosity with specular and translucent surfaces, the first pass of the
//! two-pass method: H. E. Rushmeier, K. E. Torrance, "Extending the radiosity
//! method to include specularly reflecting and translucent materials", ACM TOG
//! 9(1):1–27, 1990 (mirrors as in Wallace, Cohen & Greenberg 1987).
//!
//! In intensities I = B/π, the course's chain of equations for the diffuse
//! intensity of patch i:
//!
//!   I_i = I_e,i + ρ_d,i Σ_j { I_j F_ij + τ_s,j Σ_k I_k T_f,ijk + ρ_s,j Σ_k I_k F_f,ijk }
//!               + τ_d,i Σ_j { I_j T_ij + τ_s,j Σ_k I_k T_b,ijk + ρ_s,j Σ_k I_k F_b,ijk }
//!
//! F_ij: the ordinary factors from i's front hemisphere; T_ij: the same from its
//! back hemisphere (a second, back-facing hemi-cube, for translucent patches; for
//! a panel of two faces n and m it equals F_mj, the course's "T_nj = F_mj"); T_f,ijk
//! and F_f,ijk: from the front hemisphere to k through pane j or by mirror j
//! (`windows`), T_b,ijk and F_b,ijk the same from the back. Specular surfaces keep
//! no view-independent intensity of their own beyond their diffuse part: they only
//! redirect light into these extended factors. Multiplying by π gives the same
//! equations in radiosities, which is what is solved (B = πI, E = π I_e).
//!
//! As in gathering: per element, its terms to every patch (one hemi-cube at its
//! centre, two for a translucent one); patch terms by area weighting; the patch
//! system by Gauss–Seidel per band; element radiosities by one gathering step.
//! Each of the four transfer mechanisms can be left out: diffuse-diffuse drops
//! F_ij and T_ij, specular-diffuse the window terms.

use super::form_factors::Estimator;
use super::gathering::{Gathered, gauss_seidel};
use super::mesh::Mesh;
use super::receivers::Receivers;
use super::windows::{Follow, PointFactors, Windows};
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::settings::Mechanisms;
use glam::DVec3;
use rayon::prelude::*;
// std's Instant natively; in a browser (where std's panics) the page's clock.
use web_time::Instant;

/// One element's terms towards every patch (own patch left at zero in F and T).
#[derive(Clone, Debug, Default)]
pub struct ElementTerms {
    /// F_ij.
    pub f: Vec<f32>,
    /// Σ_j ρ_s,j F_f,ijk per patch k (paths whose first window is a mirror).
    pub f_f: Vec<(u32, DVec3)>,
    /// Σ_j τ_s,j T_f,ijk per patch k (paths whose first window is a pane).
    pub t_f: Vec<(u32, DVec3)>,
    /// T_ij, for a translucent element.
    pub t: Option<Vec<f32>>,
    pub f_b: Vec<(u32, DVec3)>,
    pub t_b: Vec<(u32, DVec3)>,
}

/// The extended pass-1 settings.
#[derive(Clone, Copy, Debug)]
pub struct Extension {
    pub follow: Follow,
    pub window_depth: u32,
    pub mechanisms: Mechanisms,
}

/// Diffuse transmittance τ_d of each patch (its polygon's material).
fn translucence(scene: &Scene, mesh: &Mesh) -> Vec<DVec3> {
    mesh.patches
        .iter()
        .map(|p| {
            let polygon = &scene.polygons[p.polygon];
            scene.materials[polygon.material].translucence.as_dvec3()
        })
        .collect()
}

/// Every element's terms.
pub fn element_terms(
    scene: &Scene,
    mesh: &Mesh,
    estimator: &Estimator,
    extension: Extension,
) -> Result<Vec<ElementTerms>> {
    let patches = Receivers::patches(mesh);
    let windows = if extension.mechanisms.specular_diffuse {
        Windows::find(
            scene,
            mesh,
            &patches,
            extension.follow,
            extension.window_depth,
        )?
    } else {
        Windows::find(
            scene,
            mesh,
            &patches,
            Follow {
                mirrors: false,
                panes: false,
            },
            0,
        )?
    };
    let hemicube = match estimator {
        Estimator::Hemicube(h) => Some(h),
        _ if windows.is_empty() => None,
        Estimator::Nusselt(_) | Estimator::Analytic(_) => {
            return Err(Error::Radiosity(
                "mirrors and panes are followed through the hemi-cube (virtual environments): use radiosity.form_factors = \"hemicube\"".into(),
            ));
        }
    };
    let tau = translucence(scene, mesh);
    let dd = extension.mechanisms.diffuse_diffuse;
    let object = |p: usize| scene.polygons[mesh.patches[p].polygon].object;
    // The front hemi-cube leaves out the element's own patch; the back one its whole
    // object, so that a panel's other face (coincident, or a thickness away) does
    // not hide what lies behind it: T_nj = F_mj for the faces n and m of a panel.
    let from = |centre: DVec3, normal: DVec3, own: usize, back: bool| -> PointFactors {
        let skip = |j: usize| {
            if back {
                object(j) == object(own)
            } else {
                j == own
            }
        };
        match hemicube {
            Some(h) if !windows.is_empty() => windows.factors(h, centre, normal, &patches, &skip),
            _ => PointFactors {
                direct: estimator.factors(centre, normal, &patches, &skip),
                ..Default::default()
            },
        }
    };
    let n = mesh.patches.len();
    Ok(mesh
        .elements
        .par_iter()
        .map(|e| {
            let normal = mesh.patches[e.patch].normal;
            let direct = |f: Vec<f64>| -> Vec<f32> {
                if dd {
                    f.into_iter().map(|f| f as f32).collect()
                } else {
                    vec![0.0; n]
                }
            };
            let front = from(e.centre, normal, e.patch, false);
            let mut terms = ElementTerms {
                f: direct(front.direct),
                f_f: front.mirrored,
                t_f: front.transmitted,
                ..Default::default()
            };
            if tau[e.patch].max_element() > 0.0 {
                let back = from(e.centre, -normal, e.patch, true);
                terms.t = Some(direct(back.direct));
                terms.f_b = back.mirrored;
                terms.t_b = back.transmitted;
            }
            terms
        })
        .collect())
}

/// What element `q`'s terms gather from patch radiosities `b`: (front, back)
/// irradiance-like sums Σ_j F_qj B_j + Σ_k (ρ_s F_f + τ_s T_f)_qk B_k and the same
/// from behind.
fn gathered(terms: &ElementTerms, b: &[DVec3]) -> (DVec3, DVec3) {
    let dense = |row: &[f32]| -> DVec3 { row.iter().zip(b).map(|(&f, b)| *b * f as f64).sum() };
    let sparse =
        |list: &[(u32, DVec3)]| -> DVec3 { list.iter().map(|(k, w)| *w * b[*k as usize]).sum() };
    let front = dense(&terms.f) + sparse(&terms.f_f) + sparse(&terms.t_f);
    let back = match &terms.t {
        Some(t) => dense(t) + sparse(&terms.f_b) + sparse(&terms.t_b),
        None => DVec3::ZERO,
    };
    (front, back)
}

/// Memory of the terms' dense parts and the three per-band patch matrices.
pub fn bytes_for(elements: u64, translucent: u64, patches: u64) -> u64 {
    elements
        .saturating_add(translucent)
        .saturating_mul(patches)
        .saturating_mul(4)
        .saturating_add(patches.saturating_mul(patches).saturating_mul(24))
}

/// Solves the extended system: the gathering solution with the chain's terms.
pub fn gather(
    scene: &Scene,
    mesh: &Mesh,
    estimator: &Estimator,
    extension: Extension,
    tolerance: f64,
    memory_budget: u64,
) -> Result<Gathered> {
    let tau = translucence(scene, mesh);
    let translucent = mesh
        .elements
        .iter()
        .filter(|e| tau[e.patch].max_element() > 0.0)
        .count() as u64;
    let n = mesh.patches.len();
    let needed = bytes_for(mesh.elements.len() as u64, translucent, n as u64);
    if needed > memory_budget {
        return Err(Error::Memory {
            elements: mesh.elements.len(),
            patches: n,
            needed,
            budget: memory_budget,
        });
    }
    let start = Instant::now();
    let terms = element_terms(scene, mesh, estimator, extension)?;
    // Patch rows by area weighting, per band: K_ij = ρ_d,i (front terms) + τ_d,i (back).
    let rows: Vec<Vec<DVec3>> = mesh
        .patches
        .par_iter()
        .enumerate()
        .map(|(i, p)| {
            let rho = p.reflectance.as_dvec3();
            let mut row = vec![DVec3::ZERO; n];
            for q in p.elements.clone() {
                let a = mesh.elements[q].area / p.area;
                let t = &terms[q];
                for (k, &f) in t.f.iter().enumerate() {
                    row[k] += rho * (a * f as f64);
                }
                for (k, w) in t.f_f.iter().chain(&t.t_f) {
                    row[*k as usize] += rho * *w * a;
                }
                if let Some(back) = &t.t {
                    for (k, &f) in back.iter().enumerate() {
                        row[k] += tau[i] * (a * f as f64);
                    }
                    for (k, w) in t.f_b.iter().chain(&t.t_b) {
                        row[*k as usize] += tau[i] * *w * a;
                    }
                }
            }
            row
        })
        .collect();
    let form_factor_time = start.elapsed();
    let start = Instant::now();
    let mut patches = vec![DVec3::ZERO; n];
    let mut sweeps = [0; 3];
    let ones = vec![1.0; n];
    let sources = mesh.patch_sources();
    for band in 0..3 {
        let matrix: Vec<Vec<f64>> = rows
            .iter()
            .map(|row| row.iter().map(|k| k[band]).collect())
            .collect();
        let emission: Vec<f64> = sources.iter().map(|s| s[band] as f64).collect();
        let (b, sweeps_taken) = gauss_seidel(&matrix, &emission, &ones, tolerance);
        sweeps[band] = sweeps_taken;
        for (p, value) in patches.iter_mut().zip(b) {
            p[band] = value;
        }
    }
    let elements = mesh
        .elements
        .iter()
        .zip(&terms)
        .map(|(e, t)| {
            let p = &mesh.patches[e.patch];
            let (front, back) = gathered(t, &patches);
            p.emission.as_dvec3()
                + e.received.as_dvec3()
                + p.reflectance.as_dvec3() * front
                + tau[e.patch] * back
        })
        .collect();
    Ok(Gathered {
        patch_factors: Vec::new(),
        element_factors: terms.into_iter().map(|t| t.f).collect(),
        patches,
        elements,
        sweeps,
        form_factor_time,
        solve_time: start.elapsed(),
    })
}
