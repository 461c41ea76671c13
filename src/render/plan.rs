//! The frame plan: everything a frame needs that is not the scene, decided and
//! built by the renderer before the frame starts. The frame, its buffers, its medium
//! and the ray-traced path read it and never reach back: which integrator runs,
//! which lights are shadowed and by what, which environments are shown, what the
//! medium marches against, which element's hemi-cube is shown.

pub use super::integrators::EnvironmentMaps;
use super::integrators::{Declaration, ScanLine};
use crate::shadow::{LightShadows, SceneOccluders};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

pub struct FramePlan {
    /// How the frame is lit: the integrator, and what it declares of itself.
    pub integrator: Arc<dyn ScanLine>,
    pub declared: &'static Declaration,
    /// Per light, whether shading adds it directly (and so whether it is shadowed).
    pub direct: Vec<bool>,
    /// Per light, its shadow pre-pass (`None`: not added directly, or unshadowed).
    pub shadows: Vec<Option<Arc<dyn LightShadows>>>,
    /// The scene's environments as this frame shows them.
    pub environments: EnvironmentMaps,
    /// The occluders' hierarchy, when a medium is ray-marched against it.
    pub occluders: Option<Arc<SceneOccluders>>,
    /// The radiosity element whose hemi-cube item buffers the `hemicube-*` buffers
    /// show.
    pub hemicube_element: usize,
    /// Told the fraction of the frame done after each band, if anyone asked.
    pub progress: Option<Progress>,
    /// Read before each band: once set, the frame ends with `Error::Stopped`.
    pub stop: Option<Arc<AtomicBool>>,
}

impl FramePlan {
    /// Whether the frame was asked to stop.
    pub fn stopped(&self) -> bool {
        self.stop
            .as_ref()
            .is_some_and(|s| s.load(Ordering::Relaxed))
    }
}

/// A watcher of a frame's progress: called with the fraction of its rows done.
pub type Progress = Arc<dyn Fn(f64) + Send + Sync>;
