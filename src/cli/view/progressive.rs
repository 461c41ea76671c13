//! Radiosity solved in the background while the viewer draws (the course's
//! "observation des états intermédiaires"): shooting hands over its state every
//! few steps, gathering its solution when done. Dropping the solve stops it.

use lumiere::Scene;
use lumiere::internals::radiosity::receivers::Receivers;
use lumiere::internals::radiosity::{self, Estimator, Settings, Shooting, Solution, Solver};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// States are handed over at most this often.
const EVERY: Duration = Duration::from_millis(150);

pub struct Progressive {
    newest: Arc<Mutex<Option<Solution>>>,
    stop: Arc<AtomicBool>,
    pause: Arc<AtomicBool>,
    /// Steps to take while paused.
    steps: Arc<AtomicUsize>,
    finished: Arc<AtomicBool>,
    /// What a failed solve said.
    failed: Arc<Mutex<Option<String>>>,
    /// Whether a state was ever handed over.
    started: bool,
}

impl Drop for Progressive {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
    }
}

impl Progressive {
    pub fn start(scene: Scene, settings: Settings) -> Progressive {
        let newest = Arc::new(Mutex::new(None));
        let stop = Arc::new(AtomicBool::new(false));
        let pause = Arc::new(AtomicBool::new(false));
        let steps = Arc::new(AtomicUsize::new(0));
        let finished = Arc::new(AtomicBool::new(false));
        let (n, s, p, f) = (
            newest.clone(),
            stop.clone(),
            pause.clone(),
            finished.clone(),
        );
        let k = steps.clone();
        let failed = Arc::new(Mutex::new(None));
        let e = failed.clone();
        std::thread::spawn(move || {
            let result = match settings.solver {
                Solver::Shooting => shoot(&scene, &settings, &n, &s, &p, &k),
                Solver::Gathering => radiosity::solve(&scene, &settings, &mut |_, _| {})
                    .map(|solution| *n.lock().expect("no poisoned lock") = Some(solution)),
            };
            if let Err(error) = result {
                *e.lock().expect("no poisoned lock") = Some(error.to_string());
            }
            f.store(true, Ordering::Relaxed);
        });
        Progressive {
            newest,
            stop,
            pause,
            steps,
            finished,
            failed,
            started: false,
        }
    }

    /// The state handed over since the last call.
    pub fn newest(&mut self) -> Option<Solution> {
        let state = self.newest.lock().expect("no poisoned lock").take();
        self.started |= state.is_some();
        state
    }

    /// The solve's error, once it has failed.
    pub fn failure(&self) -> anyhow::Result<()> {
        match self.failed.lock().expect("no poisoned lock").as_ref() {
            Some(e) => anyhow::bail!("{e}"),
            None => Ok(()),
        }
    }

    pub fn started(&self) -> bool {
        self.started
    }

    pub fn finished(&self) -> bool {
        self.finished.load(Ordering::Relaxed)
    }

    pub fn toggle_pause(&self) {
        self.pause.fetch_xor(true, Ordering::Relaxed);
    }

    /// One more step while paused (the course's step-by-step observation).
    pub fn step(&self) {
        self.steps.fetch_add(1, Ordering::Relaxed);
    }
}

/// Progressive refinement, step by step, handing over the displayed state.
fn shoot(
    scene: &Scene,
    settings: &Settings,
    newest: &Mutex<Option<Solution>>,
    stop: &AtomicBool,
    pause: &AtomicBool,
    steps: &AtomicUsize,
) -> lumiere::Result<()> {
    let mesh = radiosity::mesh(scene, settings)?;
    let estimator = Estimator::new(settings.form_factors, settings.resolution, scene);
    let elements = Receivers::elements(&mesh);
    let mut state = Shooting::start(&mesh);
    let mut last = Instant::now() - EVERY;
    let hand_over = |state: &Shooting| {
        *newest.lock().expect("no poisoned lock") = Some(Solution {
            mesh: mesh.clone(),
            elements: state.displayed(&mesh, settings.ambient),
            direct: Some(state.direct.clone()),
            display: settings.display,
            summary: format!(
                "shooting: step {}, {:.2}% unshot",
                state.steps,
                100.0 * state.unshot_fraction(&mesh)
            ),
        });
    };
    loop {
        if stop.load(Ordering::Relaxed) {
            return Ok(());
        }
        // Paused, it shoots only the steps asked for, and shows each.
        let paused = pause.load(Ordering::Relaxed);
        if paused
            && steps
                .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |n| n.checked_sub(1))
                .is_err()
        {
            std::thread::sleep(Duration::from_millis(20));
            continue;
        }
        let done = state.steps >= settings.max_steps
            || state.unshot_fraction(&mesh) <= settings.unshot
            || !state.step(&mesh, &elements, &estimator);
        if done || paused || last.elapsed() >= EVERY {
            hand_over(&state);
            last = Instant::now();
        }
        if done {
            return Ok(());
        }
    }
}
