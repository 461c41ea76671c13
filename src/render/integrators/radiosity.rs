//! Radiosity: a view-independent diffuse solution (`crate::radiosity`: Goral et
//! al.'s gathering, Cohen et al.'s shooting), solved once and drawn through its
//! elements by the scan-line pass. Chosen by a `[radiosity]` table without
//! `[global]`.

use super::solution::{KeptSolution, SolutionLighting, lights_beside_the_solution};
use super::{Declaration, Integrator, Kept, Lighting, ReadsSolution, Role};
use crate::error::Result;
use crate::radiosity::Solution;
use crate::scene::Scene;
use std::sync::Arc;

pub static DECLARATION: Declaration = Declaration {
    integrator: Integrator::Radiosity,
    name: "radiosity",
    global_method: None,
    entry: "radiosity-gathering",
    keys: &["radiosity"],
    buffers: &["element", "radiosity", "hemicube-*"],
    role: Role::ScanLine,
    direct_lights: lights_beside_the_solution,
    check: super::nothing_to_check,
    kept: || Box::new(KeptRadiosity(KeptSolution::new())),
};

/// The solution, kept between frames.
struct KeptRadiosity(KeptSolution);

impl Kept for KeptRadiosity {
    fn lighting(&self, scene: &Scene) -> Result<Lighting> {
        let solution = self.0.get(scene, &|_| {})?;
        Ok(Lighting::ScanLine(Arc::new(SolutionLighting {
            solution,
            second: None,
            gather: None,
        })))
    }

    fn solution(&self) -> Option<&dyn ReadsSolution> {
        Some(self)
    }

    fn caches_swept(&self) -> usize {
        0
    }
}

impl ReadsSolution for KeptRadiosity {
    fn hand_over(&self, scene: &Scene, solution: Arc<Solution>) {
        self.0.hand_over(scene, solution, &|_| {});
    }

    fn has_solution(&self) -> bool {
        self.0.is_kept()
    }

    fn forget(&self) {
        self.0.forget();
    }

    fn solved(&self) -> usize {
        self.0.solved()
    }
}
