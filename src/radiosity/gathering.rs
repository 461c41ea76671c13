//! Gathering: the full matrix solution of Goral, Torrance, Greenberg & Battaile
//! (SIGGRAPH '84) with hemi-cube form factors (Cohen & Greenberg, SIGGRAPH '85),
//! substructured into patches and elements (Cohen, Greenberg, Immel & Brock 1986).
//!
//! 1. At every element's centre, one estimate of its factors to every patch
//!    (element-to-patch factors, M × n, stored).
//! 2. Patch factors by area weighting, F_ij = (1/A_i) Σ_q A_iq F_(iq)j.
//! 3. The patch system B_i = E_i + ρ_i Σ_j F_ij B_j solved by Gauss–Seidel, one band
//!    at a time, from B = E, until no radiosity changes by more than the tolerance
//!    (relative to the largest radiosity).
//! 4. Element radiosities by one gathering step from the patches:
//!    B_iq = E_iq + ρ_iq Σ_j F_(iq)j B_j.
//!
//! With one element per patch this is the plain patch method of section 13.

use super::form_factors::{Estimator, patch_factors};
use super::mesh::Mesh;
use crate::error::{Error, Result};
use glam::DVec3;
use std::time::Duration;
// std's Instant natively; in a browser (where std's panics) the page's clock.
use web_time::Instant;

/// The gathering solution and its parts, kept for checks.
pub struct Gathered {
    pub patch_factors: Vec<Vec<f64>>,
    pub element_factors: Vec<Vec<f32>>,
    /// Radiosities in double precision, so the substructuring identities can be
    /// checked to rounding.
    pub patches: Vec<DVec3>,
    pub elements: Vec<DVec3>,
    /// Gauss–Seidel sweeps per band.
    pub sweeps: [usize; 3],
    /// Time spent on the form factors, and on the solve.
    pub form_factor_time: Duration,
    pub solve_time: Duration,
}

/// Memory the stored factors need: M × n element factors (f32) and n × n patch
/// factors (f64).
pub fn matrix_bytes(mesh: &Mesh) -> u64 {
    matrix_bytes_for(mesh.elements.len() as u64, mesh.patches.len() as u64)
}

/// `matrix_bytes` for `m` elements and `n` patches (saturating).
pub fn matrix_bytes_for(m: u64, n: u64) -> u64 {
    m.saturating_mul(n)
        .saturating_mul(4)
        .saturating_add(n.saturating_mul(n).saturating_mul(8))
}

pub fn gather(
    mesh: &Mesh,
    estimator: &Estimator,
    tolerance: f64,
    memory_budget: u64,
) -> Result<Gathered> {
    let bytes = matrix_bytes(mesh);
    if bytes > memory_budget {
        return Err(Error::Memory {
            elements: mesh.elements.len(),
            patches: mesh.patches.len(),
            needed: bytes,
            budget: memory_budget,
        });
    }
    let start = Instant::now();
    let element_factors = estimator.element_to_patch(mesh);
    let patch_factors = patch_factors(mesh, &element_factors);
    let form_factor_time = start.elapsed();
    let start = Instant::now();
    let mut patches = vec![DVec3::ZERO; mesh.patches.len()];
    let mut sweeps = [0; 3];
    let sources = mesh.patch_sources();
    for band in 0..3 {
        let emission: Vec<f64> = sources.iter().map(|s| s[band] as f64).collect();
        let reflectance: Vec<f64> = mesh
            .patches
            .iter()
            .map(|p| p.reflectance[band] as f64)
            .collect();
        let (b, n) = gauss_seidel(&patch_factors, &emission, &reflectance, tolerance);
        sweeps[band] = n;
        for (p, value) in patches.iter_mut().zip(b) {
            p[band] = value;
        }
    }
    let elements = mesh
        .elements
        .iter()
        .zip(&element_factors)
        .map(|(e, row)| {
            let p = &mesh.patches[e.patch];
            let gathered: DVec3 = row.iter().zip(&patches).map(|(&f, b)| *b * f as f64).sum();
            p.emission.as_dvec3() + e.received.as_dvec3() + p.reflectance.as_dvec3() * gathered
        })
        .collect();
    Ok(Gathered {
        patch_factors,
        element_factors,
        patches,
        elements,
        sweeps,
        form_factor_time,
        solve_time: start.elapsed(),
    })
}

/// Solves B_i = E_i + ρ_i Σ_j F_ij B_j by Gauss–Seidel from B = E, newest values
/// used at once; stops when max |ΔB| ≤ tolerance × max B. Returns B and the number
/// of sweeps.
pub fn gauss_seidel(
    factors: &[Vec<f64>],
    emission: &[f64],
    reflectance: &[f64],
    tolerance: f64,
) -> (Vec<f64>, usize) {
    gauss_seidel_observed(factors, emission, reflectance, tolerance, &mut |_| {})
}

/// `gauss_seidel`, handing `observe` the radiosities after each sweep (to watch
/// the residual fall).
pub fn gauss_seidel_observed(
    factors: &[Vec<f64>],
    emission: &[f64],
    reflectance: &[f64],
    tolerance: f64,
    observe: &mut dyn FnMut(&[f64]),
) -> (Vec<f64>, usize) {
    let mut b = emission.to_vec();
    // Rows are diagonally dominant (ρ < 1, row sums ≤ 1): convergence is geometric;
    // the cap only guards against factors an estimate made too large.
    for sweep in 1..=10_000 {
        let mut change: f64 = 0.0;
        for i in 0..b.len() {
            let gathered: f64 = factors[i].iter().zip(&b).map(|(f, b)| f * b).sum();
            let new = emission[i] + reflectance[i] * gathered;
            change = change.max((new - b[i]).abs());
            b[i] = new;
        }
        observe(&b);
        let largest = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if change <= tolerance * largest {
            return (b, sweep);
        }
    }
    (b, 10_000)
}
