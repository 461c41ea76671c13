//! One frame, made in bands of rows.

use super::buffers::{FrameBuffers, MediumBand};
use super::medium::MediumWork;
use super::output::Frame;
use super::plan::FramePlan;
use crate::error::{Error, Result};
use crate::image_io::Image;
use crate::raster::{EdgeTable, Visibility, rasterize_rows, sample_view, uv_gradients};
use crate::scene::Scene;
use crate::shading::FrameShading;
use glam::DVec2;

/// Samples per band when the scene does not choose its band height: about 5 MB of
/// visible-surface buffer, which shading reads back while it is still in the cache
/// (2¹⁸ samples, 20 MB, measured about 5% slower on the point-lit box at 4 × 4).
const BAND_SAMPLES: u32 = 1 << 16;

/// The pixel rows of one band of `scene`'s frames: the scene's choice, or about
/// `BAND_SAMPLES` samples.
pub fn band_rows(scene: &Scene) -> u32 {
    let samples_per_row = scene.camera.width * scene.render.supersample.pow(2);
    match scene.render.band_rows {
        0 => (BAND_SAMPLES / samples_per_row.max(1)).max(1),
        rows => rows,
    }
}

/// `scene`'s scan-line frame as `plan` has it made, with the buffers in `wanted`.
pub(super) fn render_frame(scene: &Scene, plan: &FramePlan, wanted: &[String]) -> Result<Frame> {
    render_pass(scene, plan, wanted, Pass::WHOLE)
}

/// One of the frames a frame is averaged from (the accumulation buffer's passes).
#[derive(Clone, Copy, Debug)]
pub(super) struct Pass {
    /// Where this pass samples, from each sample's own position, in samples.
    pub shift: DVec2,
    /// This pass's number, and how many there are (for the progress told).
    pub number: usize,
    pub of: usize,
}

impl Pass {
    /// The frame made once, unshifted.
    const WHOLE: Pass = Pass {
        shift: DVec2::ZERO,
        number: 0,
        of: 1,
    };
}

/// `render_frame` for one pass: the view's projection shifted by `pass.shift`.
pub(super) fn render_pass(
    scene: &Scene,
    plan: &FramePlan,
    wanted: &[String],
    pass: Pass,
) -> Result<Frame> {
    let integrator = plan.integrator.as_ref();
    let direct = &plan.direct;
    let shadows = &plan.shadows;
    let mut buffers = FrameBuffers::new(scene, plan, wanted)?;

    let mut view = sample_view(scene);
    if pass.shift != DVec2::ZERO {
        // The sample at p sees what the unshifted view shows at p + shift.
        view.centre -= pass.shift;
    }
    let polygons = integrator.draw_list(scene, &view, direct);
    let table = EdgeTable::build(&polygons, view.height);
    let gradients = uv_gradients(&polygons);
    let frames: Vec<_> = shadows
        .iter()
        .map(|s| s.as_ref().map(|s| s.frame(scene, &view)))
        .collect();
    let shadowed = frames.iter().any(Option::is_some);
    let shading = FrameShading::new(scene, &view, direct.clone())
        .with_environments(plan.environments.to_vec());
    let medium = MediumWork::new(scene, plan);
    let volumes_on_screen = medium
        .as_ref()
        .map(|m| m.frame(scene, &view))
        .unwrap_or_default();
    // Gouraud light by light: each direct light's vertex radiance drawn on its own.
    let per_light: Vec<Option<_>> = if integrator.gouraud_per_light(scene, direct, shadowed) {
        (0..scene.lights.len())
            .map(|l| {
                direct[l].then(|| {
                    let polygons = integrator.light_draw_list(scene, &view, l);
                    let table = EdgeTable::build(&polygons, view.height);
                    (polygons, table)
                })
            })
            .collect()
    } else {
        Vec::new()
    };

    let n = scene.render.supersample;
    let (width, height) = (scene.camera.width, scene.camera.height);
    let band_rows = band_rows(scene);
    let mut pixels = Vec::with_capacity(width as usize * height as usize);
    // The visible-surface buffer, written again by every band.
    let mut samples = Vec::new();
    for first in (0..height).step_by(band_rows as usize) {
        let last = (first + band_rows).min(height);
        let rows = first * n..last * n;
        let band = rasterize_rows(
            &polygons,
            &table,
            view.width,
            rows,
            gradients.clone(),
            samples,
        );
        let mut counts = Vec::with_capacity(frames.len());
        let mut visibility = Visibility::none();
        for frame in &frames {
            let found = frame.as_ref().map(|f| f.band(&band));
            let (v, c) = match found {
                Some(b) => (Some(b.visibility), b.counts),
                None => (None, None),
            };
            visibility.per_light.push(v);
            counts.push(c);
        }
        let gouraud: Vec<Vec<glam::Vec3>> = per_light
            .iter()
            .map(|drawn| match drawn {
                Some((polygons, table)) => {
                    let rows = band.rows();
                    let no_memory = Vec::new();
                    rasterize_rows(
                        polygons,
                        table,
                        view.width,
                        rows,
                        gradients.clone(),
                        no_memory,
                    )
                    .samples
                    .iter()
                    .map(|s| s.color)
                    .collect()
                }
                None => Vec::new(),
            })
            .collect();
        let mut radiance = integrator.shade_band(&shading, scene, &band, &visibility, &gouraud);
        let medium_band = match &medium {
            Some(medium) => {
                let (inscattered, lit) =
                    medium.apply(scene, &view, &volumes_on_screen, &band, &mut radiance);
                MediumBand { inscattered, lit }
            }
            None => MediumBand::default(),
        };
        buffers.add_band(
            &band,
            &visibility,
            &counts,
            &medium_band,
            integrator,
            &shading,
        );
        let pixels_of_band = Image {
            width: view.width,
            height: band.height,
            pixels: radiance,
        }
        .downsample(n);
        pixels.extend(pixels_of_band.pixels);
        samples = band.samples;
        if let Some(progress) = &plan.progress {
            progress((pass.number as f64 + last as f64 / height as f64) / pass.of as f64);
        }
        if plan.stopped() {
            return Err(Error::Stopped);
        }
    }
    Ok(Frame {
        image: Image {
            width,
            height,
            pixels,
        },
        buffers: buffers.finish(),
    })
}
