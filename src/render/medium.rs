//! The frame's participating medium: each direct light's shadow volumes put on the
//! screen once (Max's light volumes), or the scene's hierarchy for ray marching, and
//! per band the medium applied to the shaded radiance.

use super::plan::FramePlan;
use crate::media::{self, Lighting};
use crate::raster::{LitIntervals, View, VisibleSurface};
use crate::scene::Scene;
use crate::settings::MediumMethod;
use crate::shadow::light_volumes::{LightVolumes, VolumesOnScreen};
use glam::Vec3;
use std::sync::Arc;

/// The view-independent part: the lights' volumes (light volumes) or the scene's
/// hierarchy (ray marching); nothing when there is no medium or it is empty.
pub(super) struct MediumWork {
    volumes: Vec<Option<LightVolumes>>,
    rays: Option<Arc<crate::shadow::SceneOccluders>>,
    reach: f64,
    step: f64,
}

impl MediumWork {
    pub(super) fn new(scene: &Scene, plan: &FramePlan) -> Option<MediumWork> {
        let direct = &plan.direct;
        let medium = scene.medium.as_ref().filter(|m| m.extinction > 0.0)?;
        let volumes: Vec<Option<LightVolumes>> = scene
            .lights
            .iter()
            .zip(direct)
            .map(|(light, &direct)| direct.then(|| LightVolumes::new(scene, light)).flatten())
            .collect();
        let size = scene_size(scene);
        let (rays, step) = match medium.method {
            MediumMethod::LightVolumes => (None, 0.0),
            MediumMethod::RayMarching => (
                Some(plan.occluders.clone().expect("planned for ray marching")),
                march_step(medium, size),
            ),
        };
        Some(MediumWork {
            volumes,
            rays,
            reach: 4.0 * size,
            step,
        })
    }

    /// The volumes on this view's screen.
    pub(super) fn frame<'a>(
        &'a self,
        scene: &Scene,
        view: &'a View,
    ) -> Vec<Option<VolumesOnScreen<'a>>> {
        if self.rays.is_some() {
            return Vec::new();
        }
        self.volumes
            .iter()
            .map(|v| v.as_ref().map(|v| v.frame(scene, view)))
            .collect()
    }

    /// The medium applied to one band's radiance; the in-scattered radiance alone
    /// and, per light, the lit intervals found.
    pub(super) fn apply(
        &self,
        scene: &Scene,
        view: &View,
        on_screen: &[Option<VolumesOnScreen>],
        band: &VisibleSurface,
        radiance: &mut [Vec3],
    ) -> (Vec<Vec3>, Vec<Option<LitIntervals>>) {
        match &self.rays {
            Some(rays) => {
                let lighting = Lighting::Marching {
                    rays,
                    step: self.step,
                };
                let added = media::apply(scene, view, band, radiance, &lighting, self.reach);
                (added, Vec::new())
            }
            None => {
                let lit: Vec<Option<LitIntervals>> = on_screen
                    .iter()
                    .map(|v| v.as_ref().map(|v| v.band(band, self.reach)))
                    .collect();
                let lighting = Lighting::Intervals(&lit);
                let added = media::apply(scene, view, band, radiance, &lighting, self.reach);
                (added, lit)
            }
        }
    }
}

/// The diagonal of the box around the scene's polygons and the eye.
fn scene_size(scene: &Scene) -> f64 {
    let bounds = crate::geometry::bvh::Aabb::of(
        scene
            .polygons
            .iter()
            .flat_map(|p| p.positions())
            .chain([scene.camera.eye]),
    );
    (bounds.max - bounds.min).length().max(1e-9)
}

/// Ray marching's step: the scene's, or a 500th of its size.
fn march_step(medium: &crate::settings::MediumSettings, size: f64) -> f64 {
    if medium.march_step > 0.0 {
        medium.march_step
    } else {
        size / 500.0
    }
}

/// Refuses, before any work, a march whose steps would exceed
/// `medium.max_march_steps`: a viewing ray is taken to cross about the scene's size,
/// with a shadow ray per light at each step.
pub(super) fn check_march(scene: &Scene) -> crate::error::Result<()> {
    let Some(medium) = scene
        .medium
        .as_ref()
        .filter(|m| m.extinction > 0.0 && m.method == MediumMethod::RayMarching)
    else {
        return Ok(());
    };
    let size = scene_size(scene);
    let step = march_step(medium, size);
    let side = f64::from(scene.render.supersample);
    let samples = f64::from(scene.camera.width) * f64::from(scene.camera.height) * side * side;
    let lights = scene.lights.len().max(1) as f64;
    let steps = samples * lights * (size / step);
    crate::error::ensure_valid!(
        steps <= medium.max_march_steps,
        "medium.march_step",
        "medium.march_step = {step:e} would take about {steps:.1e} steps ({samples} samples x {lights} light(s) x {:.1e} steps across the scene's {size:.3e}), more than medium.max_march_steps = {:e} allows; use a step of at least {:.3e}",
        size / step,
        medium.max_march_steps,
        step * steps / medium.max_march_steps
    );
    Ok(())
}
