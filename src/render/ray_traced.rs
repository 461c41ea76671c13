//! A frame made by Whitted's ray tracer instead of the scan-line pass: eye rays
//! through the pixels' corners, split where they differ (see `global::whitted`).

use super::buffers::RAYS;
use super::frame::Frame;
use super::plan::FramePlan;
use crate::error::{Error, Result};
use crate::global::TracedScene;
use crate::global::whitted::Whitted;
use crate::image_io::{Buffer, BufferData};
use crate::raster::View;
use crate::scene::Scene;
use crate::settings::GlobalSettings;

/// The frame of `scene` by Whitted's tracer over `traced`, with the `rays` buffer
/// if asked.
pub(super) fn render(
    scene: &Scene,
    plan: &FramePlan,
    traced: &TracedScene,
    settings: &GlobalSettings,
    wanted: &[String],
) -> Result<Frame> {
    if let Some(name) = wanted.iter().find(|w| *w != RAYS.0) {
        return Err(Error::UnknownBuffer {
            name: name.clone(),
            known: vec![RAYS.0.to_string()],
        });
    }
    let backdrop = scene
        .render
        .backdrop
        .and_then(|b| plan.environments.get(b).cloned().flatten());
    let view = View::new(&scene.camera, scene.camera.width, scene.camera.height);
    let tracer = Whitted::new(scene, traced, settings, backdrop.as_deref());
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
