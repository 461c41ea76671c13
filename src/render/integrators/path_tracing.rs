//! Kajiya's path tracer (`global::path_tracing`: J. T. Kajiya, "The rendering
//! equation", SIGGRAPH '86), which makes its frame with n × n paths through each
//! pixel instead of the scan-line pass. Chosen by `[global] method =
//! "path-tracing"`; the ground truth the other global methods are measured against.

use super::ray_tracing::{KeptTracedScene, RayFrame, no_light, ray_frame, refuse_shadow_method};
use super::{BufferInfo, Declaration, EnvironmentMaps, Frame, Integrator, OwnFrame, Role};
use crate::error::Result;
use crate::global::TracedScene;
use crate::global::path_tracing::PathTracer;
use crate::image_io::{Buffer, BufferData};
use crate::scene::Scene;
use crate::settings::GlobalMethod;
use std::sync::Arc;

/// The buffers a path-traced frame gives, and what they hold.
pub const BUFFERS: [(&str, &str); 2] = [
    (
        "path-length",
        "surfaces each path met, the mean over the pixel's paths (0: they left the scene at once)",
    ),
    (
        "variance",
        "per band, the variance of the pixel's value: its paths' sample variance over their number (an overestimate under the stratified pixel; 0 with one path)",
    ),
];

pub static DECLARATION: Declaration = Declaration {
    integrator: Integrator::PathTracing,
    name: "path-tracing",
    global_method: Some(GlobalMethod::PathTracing),
    entry: "path-tracing",
    keys: &["global.depth", "global.samples", "global.analytic_spheres"],
    buffers: &[BUFFERS[0].0, BUFFERS[1].0],
    role: Role::OwnFrame,
    direct_lights: no_light,
    check: refuse_shadow_method,
    kept: || Box::new(KeptTracedScene::new(|traced| Arc::new(Paths { traced }))),
};

/// Kajiya's paths over the scene as rays see it.
struct Paths {
    traced: Arc<TracedScene>,
}

impl OwnFrame for Paths {
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
        } = ray_frame(scene, environments, wanted, &[BUFFERS[0].0, BUFFERS[1].0])?;
        let tracer = PathTracer::new(scene, &self.traced, settings, backdrop.as_deref());
        let frame = tracer.render(&view);
        let (width, height) = (frame.image.width, frame.image.height);
        let buffers = wanted
            .iter()
            .map(|name| Buffer {
                name: name.clone(),
                width,
                height,
                data: if name == BUFFERS[0].0 {
                    BufferData::Values {
                        channels: 1,
                        data: frame.vertices.clone(),
                    }
                } else {
                    BufferData::Values {
                        channels: 3,
                        data: frame.variance.iter().flat_map(|v| v.to_array()).collect(),
                    }
                },
            })
            .collect();
        Ok(Frame {
            image: frame.image,
            buffers,
        })
    }

    fn buffers(&self) -> Vec<BufferInfo> {
        BUFFERS
            .iter()
            .map(|(name, description)| BufferInfo {
                name: (*name).into(),
                description: (*description).into(),
            })
            .collect()
    }
}
