//! Jensen's photon map (`global::photon_map`, `global::photon_rendering`: H. W.
//! Jensen, "Global illumination using photon maps", 1996): pass 1 shoots photons
//! into a global and a caustic map, kept while the lights stay; pass 2 makes its
//! frame with rays from the eye. Chosen by `[global] method = "photon-map"`.

use super::ray_tracing::{RayFrame, no_light, ray_frame, refuse_shadow_method};
use super::{
    BufferInfo, Declaration, EnvironmentMaps, Frame, Integrator, Kept, Lighting, OwnFrame,
    ReadsSolution, Role,
};
use crate::error::{Error, Result};
use crate::global::TracedScene;
use crate::global::photon_map::{MapKind, shoot};
use crate::global::photon_rendering::{PhotonMaps, PhotonRenderer};
use crate::global::precomputed_irradiance::PrecomputedIrradiance;
use crate::image_io::{Buffer, BufferData};
use crate::scene::Scene;
use crate::scene::global_settings::default_final_gather;
use crate::settings::GlobalMethod;
use std::sync::{Arc, Mutex};

/// The buffer a photon-mapped frame gives, and what it holds.
pub const PHOTONS: (&str, &str) = (
    "photons",
    "the global photon map read directly at the first visible point (its radiance estimate from the nearest photons): the blurred light the final gather keeps one bounce away",
);

pub static DECLARATION: Declaration = Declaration {
    integrator: Integrator::PhotonMap,
    name: "photon-map",
    global_method: Some(GlobalMethod::PhotonMap),
    entry: "photon-map",
    keys: &[
        "global.depth",
        "global.samples",
        "global.analytic_spheres",
        "global.photons",
        "global.caustic_photons",
        "global.nearest",
        "global.caustic_nearest",
        "global.precomputed_irradiance",
        "global.final_gather",
    ],
    buffers: &[PHOTONS.0],
    role: Role::OwnFrame,
    direct_lights: no_light,
    check: refuse_shadow_method,
    kept: || {
        Box::new(KeptPhotons {
            traced: Mutex::new(None),
            maps: Mutex::new(None),
        })
    },
};

/// The scene as rays see it, and the maps shot for the lights they were shot
/// from (written out, the key a moved light changes).
struct KeptPhotons {
    traced: Mutex<Option<Arc<TracedScene>>>,
    maps: Mutex<Option<(String, Arc<PhotonMaps>)>>,
}

impl Kept for KeptPhotons {
    fn lighting(&self, scene: &Scene) -> Result<Lighting> {
        let Some(settings) = &scene.global else {
            return Err(Error::invalid(
                "global.method",
                "the photon map reads its settings from [global]",
            ));
        };
        let traced = self
            .traced
            .lock()
            .expect("no poisoned lock")
            .get_or_insert_with(|| Arc::new(TracedScene::new(scene, settings.analytic_spheres)))
            .clone();
        let key = format!(
            "{:?} {:?} {}",
            scene.lights, settings.photons, scene.shadows.seed
        );
        let mut slot = self.maps.lock().expect("no poisoned lock");
        let maps = match slot.as_ref() {
            Some((made_for, maps)) if *made_for == key => maps.clone(),
            _ => {
                let seed = scene.shadows.seed;
                let global = shoot(
                    scene,
                    &traced,
                    MapKind::Global,
                    settings.photons.global,
                    seed,
                );
                let precomputed = settings.photons.precomputed_irradiance.then(|| {
                    PrecomputedIrradiance::new(&global, settings.photons.nearest as usize)
                });
                let maps = Arc::new(PhotonMaps {
                    global,
                    precomputed,
                    caustic: shoot(
                        scene,
                        &traced,
                        MapKind::Caustic,
                        settings.photons.caustic,
                        seed ^ CAUSTIC_SEED,
                    ),
                });
                *slot = Some((key, maps.clone()));
                maps
            }
        };
        Ok(Lighting::OwnFrame(Arc::new(Photons { traced, maps })))
    }

    fn solution(&self) -> Option<&dyn ReadsSolution> {
        None
    }

    fn caches_swept(&self) -> usize {
        0
    }
}

/// The caustic shooting's streams, apart from the global one's.
const CAUSTIC_SEED: u64 = 0x0063_6175_7374_6963;

/// Pass 2 over the maps.
struct Photons {
    traced: Arc<TracedScene>,
    maps: Arc<PhotonMaps>,
}

impl OwnFrame for Photons {
    fn render(
        &self,
        scene: &Scene,
        environments: &EnvironmentMaps,
        wanted: &[String],
    ) -> Result<Frame> {
        let RayFrame {
            settings,
            backdrop,
            view,
        } = ray_frame(scene, environments, wanted, &[PHOTONS.0])?;
        let gather = settings.final_gather.unwrap_or_else(default_final_gather);
        let renderer = PhotonRenderer::new(
            scene,
            &self.traced,
            &self.maps,
            settings,
            gather,
            &view,
            backdrop.as_deref(),
        );
        let frame = renderer.render(&view, scene.shadows.seed, !wanted.is_empty());
        let (width, height) = (frame.image.width, frame.image.height);
        let buffers = if wanted.is_empty() {
            Vec::new()
        } else {
            vec![Buffer {
                name: PHOTONS.0.into(),
                width,
                height,
                data: BufferData::Values {
                    channels: 3,
                    data: frame.photons.iter().flat_map(|p| p.to_array()).collect(),
                },
            }]
        };
        Ok(Frame {
            image: frame.image,
            buffers,
        })
    }

    fn buffers(&self) -> Vec<BufferInfo> {
        let (name, description) = PHOTONS;
        vec![BufferInfo {
            name: name.into(),
            description: description.into(),
        }]
    }
}
