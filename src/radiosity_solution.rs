//! A radiosity solution made outside a frame and handed to a `Renderer`
//! (`Renderer::set_radiosity_solution`), so that it is not solved again: solved as
//! the scene's `[radiosity]` settings say, with progressive shooting's intermediate
//! states observed step by step (the course's observation of a solve converging:
//! `lumiere render --frames`, the gallery's animations and plots).

use crate::error::Result;
use crate::radiosity::{self, Display, Mesh, Shooting};
use crate::scene::Scene;
use crate::settings::RadiositySettings;

pub use crate::radiosity::Solution;

/// Progressive shooting after one of its steps.
pub struct ShootingStep<'a> {
    mesh: &'a Mesh,
    state: &'a Shooting,
    ambient: bool,
    display: Display,
}

impl ShootingStep<'_> {
    /// The steps taken so far (one patch shot a step).
    pub fn steps(&self) -> usize {
        self.state.steps
    }

    /// The share of the emitted power not shot yet.
    pub fn unshot_fraction(&self) -> f64 {
        self.state.unshot_fraction(self.mesh)
    }

    /// The solution as it stands, the ambient term added where the settings ask,
    /// with `summary` for its terminal line: a `Renderer` draws it like any other.
    pub fn snapshot(&self, summary: String) -> Solution {
        Solution {
            mesh: self.mesh.clone(),
            elements: self.state.displayed(self.mesh, self.ambient),
            direct: None,
            display: self.display,
            summary,
        }
    }
}

/// Solves `scene`'s radiosity with `settings`; `observe` sees progressive shooting
/// after each step (it is not called when gathering).
pub fn solve(
    scene: &Scene,
    settings: &RadiositySettings,
    observe: &mut dyn FnMut(&ShootingStep),
) -> Result<Solution> {
    radiosity::solve(scene, settings, &mut |mesh, state| {
        observe(&ShootingStep {
            mesh,
            state,
            ambient: settings.ambient,
            display: settings.display,
        })
    })
}

/// How many elements the mesh of `settings` cuts `scene` into, before any adaptive
/// subdivision, counted without building it.
pub fn element_count(scene: &Scene, settings: &RadiositySettings) -> u64 {
    Mesh::count(scene, settings.patches, settings.elements).elements
}

/// How many elements `scene`'s mesh for `settings` has once built (what a solve
/// starts from), without preparing any form-factor estimate.
pub fn meshed_element_count(scene: &Scene, settings: &RadiositySettings) -> Result<usize> {
    Ok(radiosity::mesh(scene, settings)?.elements.len())
}

/// Gathering watched converging: Gauss–Seidel on the patch-to-patch matrix of
/// `settings`'s mesh in colour band `band` (0 red, 1 green, 2 blue), the residual
/// power Σ_i A_i |E_i + ρ_i Σ_j F_ij B_j − B_i| after each sweep as a share of the
/// emitted power, until the sweep changes no radiosity by more than `tolerance`
/// of the largest; with the number of patches.
pub fn gathering_residuals(
    scene: &Scene,
    settings: &RadiositySettings,
    band: usize,
    tolerance: f64,
) -> Result<(usize, Vec<f64>)> {
    use crate::radiosity::Estimator;
    use crate::radiosity::form_factors::patch_factors;
    use crate::radiosity::gathering::gauss_seidel_observed;
    let mesh = radiosity::mesh(scene, settings)?;
    let estimator = Estimator::new(settings.form_factors, settings.resolution, scene);
    let factors = patch_factors(&mesh, &estimator.element_to_patch(&mesh));
    let of_band = |v: glam::Vec3| v[band.min(2)] as f64;
    let emission: Vec<f64> = mesh.patches.iter().map(|p| of_band(p.emission)).collect();
    let reflectance: Vec<f64> = mesh
        .patches
        .iter()
        .map(|p| of_band(p.reflectance))
        .collect();
    let area: Vec<f64> = mesh.patches.iter().map(|p| p.area).collect();
    let emitted: f64 = area.iter().zip(&emission).map(|(a, e)| a * e).sum();
    let mut residuals = Vec::new();
    gauss_seidel_observed(&factors, &emission, &reflectance, tolerance, &mut |b| {
        let residual: f64 = (0..b.len())
            .map(|i| {
                let gathered: f64 = factors[i].iter().zip(b).map(|(f, b)| f * b).sum();
                area[i] * (emission[i] + reflectance[i] * gathered - b[i]).abs()
            })
            .sum();
        residuals.push(residual / emitted);
    });
    Ok((mesh.patches.len(), residuals))
}

/// The two solvers of one radiosity scene, ready to be timed apart from meshing:
/// `lumiere bench --radiosity-elements`.
pub struct SolverTrial<'a> {
    mesh: Mesh,
    estimator: crate::radiosity::Estimator<'a>,
    settings: RadiositySettings,
}

impl<'a> SolverTrial<'a> {
    /// Meshes `scene` as `settings` say.
    pub fn prepare(scene: &'a Scene, settings: &RadiositySettings) -> Result<SolverTrial<'a>> {
        let mesh = radiosity::mesh(scene, settings)?;
        let estimator =
            crate::radiosity::Estimator::new(settings.form_factors, settings.resolution, scene);
        Ok(SolverTrial {
            mesh,
            estimator,
            settings: settings.clone(),
        })
    }

    /// The mesh's patches and elements.
    pub fn size(&self) -> (usize, usize) {
        (self.mesh.patches.len(), self.mesh.elements.len())
    }

    /// Progressive shooting to the settings' unshot fraction (or step limit): the
    /// steps it took.
    pub fn shoot(&self) -> usize {
        let stop = radiosity::Stop {
            unshot: self.settings.unshot,
            max_steps: self.settings.max_steps,
        };
        let mut state = Shooting::start(&self.mesh);
        state.run(&self.mesh, &self.estimator, stop, &mut |_| {});
        state.steps
    }

    /// Gathering: the time its form factors took, and its Gauss–Seidel solve's.
    pub fn gather(&self) -> Result<(std::time::Duration, std::time::Duration)> {
        let g = crate::radiosity::gathering::gather(
            &self.mesh,
            &self.estimator,
            self.settings.tolerance,
            self.settings.memory_budget,
        )?;
        Ok((g.form_factor_time, g.solve_time))
    }
}
