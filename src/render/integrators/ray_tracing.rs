//! Whitted's ray tracer (`global::whitted`: T. Whitted, "An improved illumination
//! model for shaded display", CACM 23(6), 1980), which makes its frame with rays
//! through the pixels' corners, split where they differ, instead of the scan-line
//! pass. Chosen by `[global] method = "ray-tracing"`.

use super::{
    BufferInfo, Declaration, EnvironmentMaps, Frame, Integrator, Kept, Lighting, OwnFrame,
    ReadsSolution, Role,
};
use crate::error::{Error, Result};
use crate::global::TracedScene;
use crate::global::whitted::Whitted;
use crate::image_io::{Buffer, BufferData};
use crate::raster::View;
use crate::scene::Scene;
use crate::settings::ShadowMethod;
use crate::settings::{GlobalMethod, GlobalSettings};
use crate::texture::environment::EnvironmentMap;
use std::sync::{Arc, Mutex};

/// The buffer a ray-traced frame gives, and what it holds.
pub const RAYS: (&str, &str) = (
    "rays",
    "rays traced per pixel (eye, reflected and refracted; colour-mapped): where Whitted's adaptive subdivision split the pixel, and how deep its trees went",
);

pub static DECLARATION: Declaration = Declaration {
    integrator: Integrator::RayTracing,
    name: "ray-tracing",
    global_method: Some(GlobalMethod::RayTracing),
    entry: "ray-tracing",
    keys: &[
        "global.depth",
        "global.threshold",
        "global.subdivisions",
        "global.contrast",
        "global.weights",
        "global.analytic_spheres",
        "global.ambient",
    ],
    buffers: &[RAYS.0],
    role: Role::OwnFrame,
    direct_lights: no_light,
    check: refuse_shadow_method,
    kept: || Box::new(KeptTracedScene::new(|traced| Arc::new(Tracer { traced }))),
};

/// A tracer adds every light itself, with its own shadow rays.
pub(super) fn no_light(scene: &Scene) -> Vec<bool> {
    vec![false; scene.lights.len()]
}

/// Refuses a shadow method, which a tracer's shadow rays would replace.
pub(super) fn refuse_shadow_method(scene: &Scene) -> Result<()> {
    let method = scene.shadows.method;
    if method == ShadowMethod::None {
        return Ok(());
    }
    let global = scene
        .global
        .as_ref()
        .map_or("ray-tracing", |g| g.method.name());
    Err(Error::invalid(
        "shadows.method",
        format!(
            "shadows.method = \"{}\": {} (global.method = \"{global}\") casts its own shadow rays and would ignore it; leave it out, or remove [global]",
            method.name(),
            global.replace('-', " ")
        ),
    ))
}

/// What a frame made by rays starts from: its `[global]` settings, the backdrop
/// its escaping rays see, and the view.
pub(super) struct RayFrame<'a> {
    pub settings: &'a GlobalSettings,
    pub backdrop: Option<Arc<EnvironmentMap>>,
    pub view: View,
}

/// The start of a frame made by rays, once the buffers `wanted` are found among
/// those it `makes`.
pub(super) fn ray_frame<'a>(
    scene: &'a Scene,
    environments: &EnvironmentMaps,
    wanted: &[String],
    makes: &[&str],
) -> Result<RayFrame<'a>> {
    if let Some(name) = wanted.iter().find(|w| !makes.contains(&w.as_str())) {
        return Err(Error::UnknownBuffer {
            name: name.clone(),
            known: makes.iter().map(|m| m.to_string()).collect(),
        });
    }
    let Some(settings) = &scene.global else {
        return Err(Error::invalid(
            "global.method",
            "a frame made by rays reads its settings from [global]",
        ));
    };
    Ok(RayFrame {
        settings,
        backdrop: scene
            .render
            .backdrop
            .and_then(|b| environments.get(b).cloned().flatten()),
        view: View::new(&scene.camera, scene.camera.width, scene.camera.height),
    })
}

/// The scene as rays see it, built once (geometry never changes), and the frame
/// maker over it.
pub(super) struct KeptTracedScene {
    frame: Mutex<Option<Arc<dyn OwnFrame>>>,
    over: fn(Arc<TracedScene>) -> Arc<dyn OwnFrame>,
}

impl KeptTracedScene {
    pub(super) fn new(over: fn(Arc<TracedScene>) -> Arc<dyn OwnFrame>) -> KeptTracedScene {
        KeptTracedScene {
            frame: Mutex::new(None),
            over,
        }
    }
}

impl Kept for KeptTracedScene {
    fn lighting(&self, scene: &Scene) -> Result<Lighting> {
        let mut slot = self.frame.lock().expect("no poisoned lock");
        let analytic = scene.global.as_ref().is_none_or(|g| g.analytic_spheres);
        let frame =
            slot.get_or_insert_with(|| (self.over)(Arc::new(TracedScene::new(scene, analytic))));
        Ok(Lighting::OwnFrame(frame.clone()))
    }

    fn solution(&self) -> Option<&dyn ReadsSolution> {
        None
    }

    fn caches_swept(&self) -> usize {
        0
    }
}

/// Whitted's tracer over the scene as rays see it.
struct Tracer {
    traced: Arc<TracedScene>,
}

impl OwnFrame for Tracer {
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
        } = ray_frame(scene, environments, wanted, &[RAYS.0])?;
        let tracer = Whitted::new(scene, &self.traced, settings, backdrop.as_deref());
        let (image, rays) = tracer.render(&view);
        let buffers = if wanted.is_empty() {
            Vec::new()
        } else {
            vec![Buffer {
                name: RAYS.0.into(),
                width: image.width,
                height: image.height,
                data: BufferData::Counts(
                    rays.iter()
                        .map(|&r| r.min(i32::MAX as u32) as i32)
                        .collect(),
                ),
            }]
        };
        Ok(Frame { image, buffers })
    }

    fn buffers(&self) -> Vec<BufferInfo> {
        let (name, description) = RAYS;
        vec![BufferInfo {
            name: name.into(),
            description: description.into(),
        }]
    }
}
