//! Progressive refinement: M. F. Cohen, S. E. Chen, J. R. Wallace, D. P. Greenberg,
//! "A progressive refinement approach to fast radiosity image generation",
//! SIGGRAPH '88.
//!
//! Every patch starts with its emission as unshot radiosity ΔB. Each step takes the
//! patch i with the most unshot power ΔB_i A_i, puts one hemi-cube (or other
//! estimate) at its centre looking at every element, and shoots: each element e of
//! another patch j gets Δ = ρ_e ΔB_i F_ie A_i / A_e (the reciprocal of e's factor to
//! i), added to its radiosity and, area-weighted, to j's unshot radiosity; then
//! ΔB_i = 0. No matrix is stored. The solve stops when the unshot power is a given
//! fraction of the emitted power, or after a number of steps.
//!
//! The ambient term (display only, never shot): with F*_j = A_j / Σ A, the mean
//! reflectance ρ̄ = Σ ρ_j A_j / Σ A and R = 1 / (1 − ρ̄), Ambient = R Σ_j ΔB_j F*_j,
//! and each element is displayed as B_e + ρ_e Ambient.
//!
//! Choice left open: "most unshot power" compares the sum of the three bands.

use super::form_factors::Estimator;
use super::mesh::Mesh;
use super::receivers::Receivers;
use glam::Vec3;

/// The state after some steps.
#[derive(Clone, Debug)]
pub struct Shooting {
    /// Radiosity of every element.
    pub elements: Vec<Vec3>,
    /// Unshot radiosity of every patch.
    pub unshot: Vec<Vec3>,
    /// Per element, the radiosity it received straight from the emitters' own
    /// emission (their first shots): the direct part of `elements`, less E.
    pub direct: Vec<Vec3>,
    /// Per patch, whether its emission has been shot.
    emission_shot: Vec<bool>,
    /// The power the solve started with, bands summed (`Mesh::source_power`).
    source_power: f64,
    /// Steps taken.
    pub steps: usize,
}

/// When to stop shooting.
#[derive(Clone, Copy, Debug)]
pub struct Stop {
    /// Unshot power as a fraction of the emitted power.
    pub unshot: f64,
    pub max_steps: usize,
}

impl Shooting {
    /// Every element at its emission and what the lights shot into it gave it
    /// (`light_sources`: their shots come first), every patch's emission and
    /// received light unshot.
    pub fn start(mesh: &Mesh) -> Shooting {
        Shooting {
            elements: mesh
                .elements
                .iter()
                .map(|e| mesh.patches[e.patch].emission + e.received)
                .collect(),
            unshot: mesh.patch_sources(),
            direct: mesh.elements.iter().map(|e| e.received).collect(),
            emission_shot: vec![false; mesh.patches.len()],
            source_power: mesh.source_power().element_sum() as f64,
            steps: 0,
        }
    }

    /// Total unshot power per band, Σ ΔB_i A_i.
    pub fn unshot_power(&self, mesh: &Mesh) -> Vec3 {
        self.unshot
            .iter()
            .zip(&mesh.patches)
            .map(|(u, p)| *u * p.area as f32)
            .sum()
    }

    /// Unshot power over the power the solve started with (bands summed).
    pub fn unshot_fraction(&self, mesh: &Mesh) -> f64 {
        if self.source_power == 0.0 {
            return 0.0;
        }
        self.unshot_power(mesh).element_sum() as f64 / self.source_power
    }

    /// One step: the patch with the most unshot power shoots. Returns false when
    /// nothing is left to shoot.
    pub fn step(&mut self, mesh: &Mesh, elements: &Receivers, estimator: &Estimator) -> bool {
        let Some((i, _)) = self
            .unshot
            .iter()
            .zip(&mesh.patches)
            .map(|(u, p)| u.element_sum() as f64 * p.area)
            .enumerate()
            .filter(|&(_, power)| power > 0.0)
            .max_by(|a, b| a.1.total_cmp(&b.1))
        else {
            return false;
        };
        let shooter = &mesh.patches[i];
        let shot = self.unshot[i];
        // Its first shot carries its emission: what that brings is direct light.
        let emitted = if self.emission_shot[i] {
            Vec3::ZERO
        } else {
            shooter.emission
        };
        self.emission_shot[i] = true;
        let factors = estimator.factors(shooter.centre, shooter.normal, elements, &|e| {
            elements.patch[e] == i
        });
        for (e, f) in factors.into_iter().enumerate() {
            if f == 0.0 {
                continue;
            }
            let element = &mesh.elements[e];
            let receiver = &mesh.patches[element.patch];
            let spread = (f * shooter.area / element.area) as f32;
            let delta = receiver.reflectance * shot * spread;
            self.elements[e] += delta;
            self.direct[e] += receiver.reflectance * emitted * spread;
            self.unshot[element.patch] += delta * (element.area / receiver.area) as f32;
        }
        self.unshot[i] = Vec3::ZERO;
        self.steps += 1;
        true
    }

    /// Shoots until `stop`, calling `observe` after every step.
    pub fn run(
        &mut self,
        mesh: &Mesh,
        estimator: &Estimator,
        stop: Stop,
        observe: &mut dyn FnMut(&Shooting),
    ) {
        let elements = Receivers::elements(mesh);
        while self.steps < stop.max_steps
            && self.unshot_fraction(mesh) > stop.unshot
            && self.step(mesh, &elements, estimator)
        {
            observe(self);
        }
    }

    /// The radiosities to display: with `ambient`, the course's ambient term added.
    pub fn displayed(&self, mesh: &Mesh, ambient: bool) -> Vec<Vec3> {
        if !ambient {
            return self.elements.clone();
        }
        let a = ambient_term(mesh, &self.unshot);
        self.elements
            .iter()
            .zip(&mesh.elements)
            .map(|(b, e)| *b + mesh.patches[e.patch].reflectance * a)
            .collect()
    }
}

/// Ambient = R Σ_j ΔB_j F*_j with F*_j = A_j / Σ A and R = 1 / (1 − ρ̄).
pub fn ambient_term(mesh: &Mesh, unshot: &[Vec3]) -> Vec3 {
    let total: f64 = mesh.patches.iter().map(|p| p.area).sum();
    let mean_reflectance: Vec3 = mesh
        .patches
        .iter()
        .map(|p| p.reflectance * (p.area / total) as f32)
        .sum();
    let interreflection = Vec3::ONE / (Vec3::ONE - mean_reflectance);
    let estimated: Vec3 = unshot
        .iter()
        .zip(&mesh.patches)
        .map(|(u, p)| *u * (p.area / total) as f32)
        .sum();
    interreflection * estimated
}
