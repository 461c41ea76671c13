//! Participating media: a homogeneous medium's single scattering along each viewing
//! ray, from the lit intervals the shadow layer finds (`shadow::light_volumes`, Max
//! 1986) or by the ray-marching reference, and the surfaces' light attenuated on
//! its way to the eye.

pub mod ray_marching;
pub mod single_scattering;

use crate::raster::{LitIntervals, View, VisibleSurface};
use crate::scene::Scene;
use crate::scene::ray_queries::SceneRays;
use glam::{DVec3, Vec3};
use rayon::prelude::*;
use single_scattering::{Scattering, transmittance};

/// How each light's in-scattering along a ray is found.
pub enum Lighting<'a> {
    /// Per light, its lit intervals over the band's samples (`None`: not scattered).
    Intervals(&'a [Option<LitIntervals>]),
    /// Ray marching with shadow rays through `rays`, steps of `step`.
    Marching { rays: &'a SceneRays<'a>, step: f64 },
}

/// Sample `k`'s viewing ray: its unit direction and its length to the visible
/// surface (`reach` when it meets none).
pub fn viewing_ray(view: &View, band: &VisibleSurface, k: usize, reach: f64) -> (DVec3, f64) {
    let (x, y) = band.position_of(k);
    let ray = view.ray(x as f64 + 0.5, y as f64 + 0.5);
    let s = &band.samples[k];
    let length = if s.is_empty() {
        reach
    } else {
        s.depth * (ray.length() / view.focal)
    };
    (ray.normalize(), length)
}

/// The medium applied to a band's radiance: each sample's radiance attenuated along
/// its viewing ray and the light scattered into the ray added; returns the
/// in-scattered radiance alone.
pub fn apply(
    scene: &Scene,
    view: &View,
    band: &VisibleSurface,
    radiance: &mut [Vec3],
    lighting: &Lighting,
    reach: f64,
) -> Vec<Vec3> {
    let Some(medium) = &scene.medium else {
        return vec![Vec3::ZERO; radiance.len()];
    };
    let scattering = Scattering::new(medium);
    radiance
        .par_iter_mut()
        .enumerate()
        .map(|(k, pixel)| {
            let (direction, length) = viewing_ray(view, band, k, reach);
            let mut inscattered = Vec3::ZERO;
            for (l, light) in scene.lights.iter().enumerate() {
                inscattered += match lighting {
                    Lighting::Intervals(per_light) => match &per_light[l] {
                        Some(lit) => scattering.inscattered(light, view.eye, direction, lit.of(k)),
                        None => Vec3::ZERO,
                    },
                    Lighting::Marching { rays, step } => ray_marching::inscattered(
                        medium, rays, light, view.eye, direction, length, *step, reach,
                    ),
                };
            }
            let t = transmittance(medium, view.eye, direction, length) as f32;
            *pixel = *pixel * t + inscattered;
            inscattered
        })
        .collect()
}
