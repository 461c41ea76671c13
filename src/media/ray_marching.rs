//! The reference for single scattering: march along each viewing ray in equal steps
//! (the midpoint of each), cast a shadow ray to the light from every step that lies
//! in the medium (and in a spot light's cone), and sum σ_s p E e^(−σ_t t) over the
//! lit ones. It needs no shadow volumes and converges to the integral as the step
//! shrinks; light volumes must agree with it.

use super::single_scattering::{holds, phase, point_integrand, sun_path, transmittance};
use crate::scene::ray_queries::SceneRays;
use crate::scene::{Light, Reach};
use crate::settings::MediumSettings;
use glam::{DVec3, Vec3};

/// The in-scattered radiance from `light` along eye + t·direction (unit), t in
/// [0, end], by steps of `step`; `reach` is how far back a distant light's shadow
/// rays go.
#[allow(clippy::too_many_arguments)]
pub fn inscattered(
    medium: &MediumSettings,
    rays: &SceneRays,
    light: &Light,
    eye: DVec3,
    direction: DVec3,
    end: f64,
    step: f64,
    reach: f64,
) -> Vec3 {
    let sigma_s = medium.scattering();
    if sigma_s == 0.0 || end <= 0.0 {
        return Vec3::ZERO;
    }
    let steps = (end / step).ceil().max(1.0) as usize;
    let h = end / steps as f64;
    let mut total = 0.0;
    let source = light.reach();
    for i in 0..steps {
        let t = (i as f64 + 0.5) * h;
        let x = eye + direction * t;
        if !holds(medium, x) {
            continue;
        }
        let term = match source {
            Reach::Direction { direction: sun, .. } => {
                if rays.any_hit(x, x - sun * reach, &[]) {
                    continue;
                }
                let along = transmittance(medium, eye, direction, t);
                let way_in = (-medium.extinction * sun_path(medium, x, sun)).exp();
                phase(medium, sun.dot(-direction)) * along * way_in
            }
            Reach::Point { at, .. } => {
                if rays.any_hit(x, at, &[]) {
                    continue;
                }
                point_integrand(medium, light, at, eye, direction, t)
            }
            Reach::Extended { .. } => return Vec3::ZERO,
        };
        total += term * h;
    }
    let colour = match source {
        Reach::Direction { irradiance, .. } => irradiance,
        Reach::Point { intensity, .. } => intensity,
        Reach::Extended { .. } => Vec3::ZERO,
    };
    colour * (sigma_s * total) as f32
}
