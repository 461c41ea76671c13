//! One frame: clip and project, the scan-line visible-surface pass, the visibility
//! terms, shading, and the box filter down to pixels.

use crate::output::Image;
use crate::raster::{ToPrepare, View, VisibleSurface, prepare, rasterize, sample_view};
use crate::scene::Scene;
use crate::shading::{shade, vertex_colors};
use crate::shadow::Visibility;
use crate::texture::Interpolation;
use anyhow::Result;
use glam::Vec3;

/// The visible surface of `scene` on its sample grid (pixels × supersample).
pub fn visible_surface(scene: &Scene) -> (View, VisibleSurface) {
    let view = sample_view(scene);
    let colors = vertex_colors(scene, &view);
    let polygons = prepare(
        &view,
        scene
            .polygons
            .iter()
            .zip(&colors)
            .enumerate()
            .map(|(id, (p, c))| ToPrepare {
                id: id as u32,
                element: id as u32,
                vertices: &p.vertices,
                colors: c,
                affine_uv: scene.materials[p.material].interpolation == Interpolation::Affine,
            }),
    );
    let surface = rasterize(&polygons, view.width, view.height);
    (view, surface)
}

/// In Williams's post-pass, what a shadowed pixel keeps of its radiance.
pub const POST_PASS_SHADE: f32 = 0.25;

/// Linear radiance image of `scene`: its radiosity solution when it has
/// `[radiosity]` settings, else its lights, shadowed by the scene's shadow method.
pub fn render(scene: &Scene) -> Result<Image> {
    if let Some(settings) = &scene.radiosity {
        return crate::radiosity::render(scene, settings);
    }
    let (view, surface) = visible_surface(scene);
    let visibility = Visibility::compute(scene, &view, &surface, scene.shadows.method);
    let radiance = if scene.shadows.post_pass {
        // Williams 1978 as first published: the image is shaded without shadows,
        // then every pixel the map finds in shadow is darkened, highlights included
        // (the "veil" on highlights the course points out).
        let mut radiance = shade(scene, &view, &surface, &Visibility::none());
        for (k, r) in radiance.iter_mut().enumerate() {
            let lit = visibility.mean(k);
            *r *= lit + (1.0 - lit) * POST_PASS_SHADE;
        }
        radiance
    } else {
        shade(scene, &view, &surface, &visibility)
    };
    Ok(to_pixels(scene, &view, radiance))
}

/// The visibility term of the first light, white where lit, black in shadow, grey
/// where partly lit (`--aov shadow`); empty samples are black.
pub fn shadow_aov(scene: &Scene) -> Image {
    let (view, surface) = visible_surface(scene);
    let visibility = Visibility::compute(scene, &view, &surface, scene.shadows.method);
    let values = (0..surface.samples.len())
        .map(|k| {
            let lit = if surface.samples[k].is_empty() {
                0.0
            } else {
                visibility.of(0, k)
            };
            Vec3::splat(lit)
        })
        .collect();
    to_pixels(scene, &view, values)
}

pub fn to_pixels(scene: &Scene, view: &View, samples: Vec<Vec3>) -> Image {
    Image {
        width: view.width,
        height: view.height,
        pixels: samples,
    }
    .downsample(scene.render.supersample)
}
