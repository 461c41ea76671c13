//! Progressive radiosity shot a few steps at a time, between the viewer's messages
//! (the course's "observation des états intermédiaires"): each call shoots for a
//! bounded time and hands back the state to display, so the picture brightens step
//! by step, can be paused, and shot one step at a time. No thread: the same code
//! runs in a browser's worker, where none can start.

use crate::error::Result;
use crate::radiosity::receivers::Receivers;
use crate::radiosity::{self, Estimator, Mesh, Settings, Shooting, Solution};
use crate::scene::Scene;
use web_time::{Duration, Instant};

/// A shooting solve under way.
pub struct SteppedShooting {
    scene: Scene,
    settings: Settings,
    mesh: Mesh,
    elements: Receivers,
    state: Shooting,
    /// Paused: only the steps asked for are shot.
    pub paused: bool,
    steps_asked: usize,
    finished: bool,
}

impl SteppedShooting {
    pub fn start(scene: Scene, settings: Settings) -> Result<SteppedShooting> {
        let mesh = radiosity::mesh(&scene, &settings)?;
        let elements = Receivers::elements(&mesh);
        let state = Shooting::start(&mesh);
        Ok(SteppedShooting {
            scene,
            settings,
            mesh,
            elements,
            state,
            paused: false,
            steps_asked: 0,
            finished: false,
        })
    }

    /// Whether a call to [`SteppedShooting::advance`] would shoot.
    pub fn has_work(&self) -> bool {
        !self.finished && (!self.paused || self.steps_asked > 0)
    }

    /// One more step while paused.
    pub fn ask_step(&mut self) {
        self.steps_asked += 1;
    }

    /// Shoots for about `budget` (one step at least, one only while paused), and
    /// returns the state to display.
    pub fn advance(&mut self, budget: Duration) -> Solution {
        let estimator = Estimator::new(
            self.settings.form_factors,
            self.settings.resolution,
            &self.scene,
        );
        let start = Instant::now();
        while self.has_work() {
            let done = self.state.steps >= self.settings.max_steps
                || self.state.unshot_fraction(&self.mesh) <= self.settings.unshot
                || !self.state.step(&self.mesh, &self.elements, &estimator);
            if done {
                self.finished = true;
            }
            if self.paused {
                self.steps_asked = self.steps_asked.saturating_sub(1);
                break;
            }
            if start.elapsed() >= budget {
                break;
            }
        }
        self.solution()
    }

    /// The state now, as the renderer displays a solution.
    pub fn solution(&self) -> Solution {
        Solution {
            mesh: self.mesh.clone(),
            elements: self.state.displayed(&self.mesh, self.settings.ambient),
            direct: Some(self.state.direct.clone()),
            display: self.settings.display,
            summary: format!(
                "shooting: step {}, {:.2}% unshot{}",
                self.state.steps,
                100.0 * self.state.unshot_fraction(&self.mesh),
                if self.finished {
                    ", done"
                } else if self.paused {
                    ", paused"
                } else {
                    ""
                }
            ),
        }
    }
}
