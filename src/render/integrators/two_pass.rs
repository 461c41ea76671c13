//! The two-pass method of J. R. Wallace, M. F. Cohen & D. P. Greenberg, "A
//! two-pass solution to the rendering equation", SIGGRAPH '87: pass 1 a radiosity
//! solution extended through planar mirrors (`crate::radiosity`'s windows), pass 2
//! rays from the eye off specular surfaces reading it (`global::two_pass`), drawn
//! by the scan-line pass; with Reichert's final gather through Ward's irradiance
//! cache when `[global.final_gather]` asks. Chosen by `[global] method =
//! "two-pass"`; its state serves Rushmeier & Torrance's method too.

use super::solution::{KeptSolution, SolutionLighting, lights_beside_the_solution};
use super::{Declaration, Integrator, Kept, Lighting, ReadsSolution, Role};
use crate::error::{Error, Result};
use crate::global::TracedScene;
use crate::global::final_gather::FinalGather;
use crate::global::irradiance_cache::{IrradianceCache, ViewGather};
use crate::global::two_pass::SecondPass;
use crate::radiosity::Solution;
use crate::raster::View;
use crate::scene::{Camera, Scene};
use crate::settings::GlobalMethod;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// The `[global]` keys the two-pass methods read (beside `[radiosity]`).
pub const KEYS: &[&str] = &[
    "radiosity",
    "global.depth",
    "global.threshold",
    "global.window_depth",
    "global.frustum_resolution",
    "global.mechanisms",
    "global.exact_direct",
    "global.final_gather",
];

/// Their buffers.
pub const BUFFERS: &[&str] = &["element", "radiosity", "hemicube-*", super::CACHE_RECORDS];

pub static DECLARATION: Declaration = Declaration {
    integrator: Integrator::TwoPass,
    name: "two-pass",
    global_method: Some(GlobalMethod::TwoPass),
    entry: "two-pass",
    keys: KEYS,
    buffers: BUFFERS,
    role: Role::ScanLine,
    direct_lights: lights_beside_the_solution,
    check,
    kept: || Box::new(KeptTwoPass::new()),
};

/// Refuses a scene without `[radiosity]`, and transmitting materials: the
/// two-pass method follows planar mirrors only.
fn check(scene: &Scene) -> Result<()> {
    needs_a_solution(scene, DECLARATION.name)?;
    match scene
        .materials
        .iter()
        .find(|m| m.transmittance.max_element() > 0.0 || m.translucence.max_element() > 0.0)
    {
        Some(m) => Err(Error::invalid(
            format!("materials.{}", m.name),
            format!(
                "materials.{}: the two-pass method (Wallace et al. 1987) follows mirrors; transmission (transmittance, translucence) is Rushmeier & Torrance's: set global.method = \"rushmeier-torrance\"",
                m.name
            ),
        )),
        None => Ok(()),
    }
}

/// Refuses a scene without the `[radiosity]` table method `name`'s second pass reads.
pub fn needs_a_solution(scene: &Scene, name: &str) -> Result<()> {
    match scene.radiosity {
        Some(_) => Ok(()),
        None => Err(Error::Radiosity(format!(
            "global.method = \"{name}\" reads a radiosity solution in its second pass: add a [radiosity] table"
        ))),
    }
}

/// The solution, the scene as the second pass's rays see it, the second pass, the
/// final gather and the irradiance cache last swept.
pub struct KeptTwoPass {
    solution: KeptSolution,
    /// Rays read the solution on its mesh: spheres stay polygons here.
    traced: Mutex<Option<Arc<TracedScene>>>,
    /// The final gather over the whole solution (made with it, before its direct
    /// part is taken out for display).
    final_gather: Mutex<Option<Arc<FinalGather>>>,
    second: Mutex<Option<Arc<SecondPass>>>,
    /// The irradiance cache last swept, and the camera, supersampling and gather
    /// it was swept for: frames from the same view reuse it.
    view_gather: Mutex<Option<(Camera, u32, Arc<ViewGather>)>>,
    swept: AtomicUsize,
}

impl KeptTwoPass {
    pub fn new() -> KeptTwoPass {
        KeptTwoPass {
            solution: KeptSolution::new(),
            traced: Mutex::new(None),
            final_gather: Mutex::new(None),
            second: Mutex::new(None),
            view_gather: Mutex::new(None),
            swept: AtomicUsize::new(0),
        }
    }

    /// The scene as rays see it, built once (geometry never changes).
    fn traced(&self, scene: &Scene) -> Arc<TracedScene> {
        let mut slot = self.traced.lock().expect("no poisoned lock");
        slot.get_or_insert_with(|| Arc::new(TracedScene::new(scene, false)))
            .clone()
    }

    /// Makes the final gather `[global.final_gather]` asks for over `whole`.
    fn gather_over(&self, scene: &Scene, whole: &Solution) {
        let gather = scene
            .global
            .as_ref()
            .and_then(|g| g.final_gather)
            .map(|settings| Arc::new(FinalGather::new(scene, whole, self.traced(scene), settings)));
        *self.final_gather.lock().expect("no poisoned lock") = gather;
    }

    /// The irradiance cache of `gather` for the camera: swept the first time a
    /// frame asks, again only when the camera, the sampling or the gather changes.
    fn view_gather(&self, scene: &Scene, gather: Arc<FinalGather>) -> Arc<ViewGather> {
        let mut slot = self.view_gather.lock().expect("no poisoned lock");
        let samples = scene.render.supersample;
        if let Some((camera, n, kept)) = slot.as_ref()
            && *camera == scene.camera
            && *n == samples
            && Arc::ptr_eq(&kept.gather, &gather)
        {
            return kept.clone();
        }
        let camera = &scene.camera;
        let view = View::new(camera, camera.width, camera.height);
        let cache = IrradianceCache::sweep(scene, gather.as_ref(), &view);
        self.swept.fetch_add(1, Ordering::Relaxed);
        let made = Arc::new(ViewGather { gather, cache });
        *slot = Some((camera.clone(), samples, made.clone()));
        made
    }
}

impl Kept for KeptTwoPass {
    fn lighting(&self, scene: &Scene) -> Result<Lighting> {
        let Some(settings) = &scene.global else {
            return Err(Error::Radiosity(
                "the two-pass methods read their settings from [global]".into(),
            ));
        };
        let solution = self
            .solution
            .get(scene, &|whole| self.gather_over(scene, whole))?;
        let second = {
            let mut slot = self.second.lock().expect("no poisoned lock");
            slot.get_or_insert_with(|| {
                Arc::new(SecondPass::new(
                    scene,
                    &solution,
                    self.traced(scene),
                    settings.clone(),
                    lights_beside_the_solution(scene),
                ))
            })
            .clone()
        };
        let gather = self.final_gather.lock().expect("no poisoned lock").clone();
        let gather = gather.map(|gather| self.view_gather(scene, gather));
        Ok(Lighting::ScanLine(Arc::new(SolutionLighting {
            solution,
            second: Some(second),
            gather,
        })))
    }

    fn solution(&self) -> Option<&dyn ReadsSolution> {
        Some(self)
    }

    fn caches_swept(&self) -> usize {
        self.swept.load(Ordering::Relaxed)
    }
}

impl ReadsSolution for KeptTwoPass {
    fn hand_over(&self, scene: &Scene, solution: Arc<Solution>) {
        self.solution
            .hand_over(scene, solution, &|whole| self.gather_over(scene, whole));
        *self.second.lock().expect("no poisoned lock") = None;
    }

    fn has_solution(&self) -> bool {
        self.solution.is_kept()
    }

    fn forget(&self) {
        self.solution.forget();
        *self.final_gather.lock().expect("no poisoned lock") = None;
        *self.second.lock().expect("no poisoned lock") = None;
        *self.view_gather.lock().expect("no poisoned lock") = None;
    }

    fn solved(&self) -> usize {
        self.solution.solved()
    }
}
