//! A frame made by Whitted's ray tracer instead of the scan-line pass: eye rays
//! through the pixels' corners, split where they differ (see `global::whitted`).

use super::renderer::{Rendered, Renderer};
use crate::global::whitted::Whitted;
use crate::output::{Buffer, BufferData};
use crate::raster::View;
use crate::settings::GlobalSettings;
use crate::{Error, Result};

/// The buffer a ray-traced frame gives, and what it holds.
pub const RAYS: (&str, &str) = (
    "rays",
    "rays traced per pixel (eye, reflected and refracted; colour-mapped): where Whitted's adaptive subdivision split the pixel, and how deep its trees went",
);

pub(super) fn render(
    renderer: &Renderer,
    settings: &GlobalSettings,
    wanted: &[String],
) -> Result<Rendered> {
    if let Some(name) = wanted.iter().find(|w| *w != RAYS.0) {
        return Err(Error::UnknownBuffer {
            name: name.clone(),
            known: vec![RAYS.0.to_string()],
        });
    }
    let scene = renderer.scene();
    let traced = renderer.traced_scene(settings.analytic_spheres);
    let maps = renderer.environment_maps()?;
    let backdrop = scene
        .render
        .backdrop
        .and_then(|b| maps.get(b).cloned().flatten());
    let view = View::new(&scene.camera, scene.camera.width, scene.camera.height);
    let tracer = Whitted::new(scene, &traced, settings, backdrop.as_deref());
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
    Ok(Rendered { image, buffers })
}
