//! The light model: how much radiance one light sends towards the eye from a point.
//!
//! Diffuse: Lambert, radiance ρ/π × irradiance. Specular: Phong's cosine lobe
//! (B. T. Phong, "Illumination for computer generated pictures", CACM 18(6), 1975) in
//! its energy-normalised form f = k_s (e + 2)/(2π) cosᵉ α (R. R. Lewis, 1994), α the
//! angle between the mirror direction of the light and the eye, so a material never
//! reflects more than it receives and images compare with a physically based
//! renderer's.
//!
//! - Point lights: irradiance I cos θ / r².
//! - Spot lights: the same with I(θ) = I f(θ), θ from the spot's axis.
//! - Distant lights: irradiance E cos θ, θ from the direction the light comes from.
//! - Polygon lights: the diffuse part is exact (Lambert's contour formula); the
//!   specular part treats the emitter as a point at its centroid with intensity
//!   L A cos θ_light, an approximation.
//! - Sphere lights: the diffuse part is exact, the sphere partly below the
//!   receiver's horizon included (`sphere_form_factor`); the specular part treats
//!   the sphere as a point at its centre with intensity L π r², an approximation.

use super::lambert_contour::projected_solid_angle;
use super::sphere_form_factor;
use crate::scene::{DistantLight, Light, PolygonLight, Reflectance, SphereLight};
use glam::{DVec3, Vec3};
use std::f32::consts::PI;

/// A surface point being shaded: position, unit shading normal on the eye's side,
/// unit direction to the eye.
#[derive(Clone, Copy, Debug)]
pub struct SurfacePoint {
    pub position: DVec3,
    pub normal: DVec3,
    pub to_eye: DVec3,
}

/// Radiance towards the eye due to `light`, ignoring anything in between.
#[inline(always)]
pub fn reflected(point: &SurfacePoint, material: &Reflectance, light: &Light) -> Vec3 {
    match light {
        Light::Point(l) => {
            let d = l.position - point.position;
            point_contribution(point, material, d, l.intensity)
        }
        Light::Spot(l) => {
            let factor = l.factor_towards(point.position);
            if factor == 0.0 {
                return Vec3::ZERO;
            }
            let d = l.position - point.position;
            point_contribution(point, material, d, l.intensity * factor as f32)
        }
        Light::Distant(l) => distant_contribution(point, material, l),
        Light::Polygon(l) => polygon_contribution(point, material, l),
        Light::Sphere(l) => sphere_contribution(point, material, l),
    }
}

/// Light from a point source at offset `d` with intensity `intensity`.
#[inline(always)]
fn point_contribution(
    point: &SurfacePoint,
    material: &Reflectance,
    d: DVec3,
    intensity: Vec3,
) -> Vec3 {
    let r2 = d.length_squared();
    let l = d / r2.sqrt();
    let cos = point.normal.dot(l);
    // Not lit from this side, or the light sits on the point: no direction (NaN or
    // infinity; two comparisons say it, where `is_finite` costs a dozen
    // instructions in the hottest line of the renderer).
    if !(cos > 0.0 && cos < f64::INFINITY) {
        return Vec3::ZERO;
    }
    let irradiance = intensity * (cos / r2) as f32;
    (material.diffuse / PI + specular_brdf(point, material, l)) * irradiance
}

/// Phong's energy-normalised lobe, the BRDF f = k_s (e + 2)/(2π) cosᵉ α for light
/// arriving along unit `l`.
#[inline(always)]
pub fn specular_brdf(point: &SurfacePoint, material: &Reflectance, l: DVec3) -> Vec3 {
    if material.specular == Vec3::ZERO {
        return Vec3::ZERO;
    }
    let mirror = 2.0 * point.normal.dot(l) * point.normal - l;
    let cos_alpha = mirror.dot(point.to_eye).max(0.0) as f32;
    let e = material.exponent;
    material.specular * (e + 2.0) / (2.0 * PI) * cos_alpha.powf(e)
}

fn polygon_contribution(
    point: &SurfacePoint,
    material: &Reflectance,
    light: &PolygonLight,
) -> Vec3 {
    let c = light.centre;
    // One-sided emitter: points behind its plane get nothing.
    if (point.position - c).dot(light.normal) <= 0.0 {
        return Vec3::ZERO;
    }
    let phi = projected_solid_angle(point.position, point.normal, &light.vertices) as f32;
    let mut radiance = material.diffuse / PI * light.radiance * phi;
    if material.specular != Vec3::ZERO {
        let d = c - point.position;
        let cos_light = (-d.normalize()).dot(light.normal).max(0.0);
        let intensity = light.radiance * (light.area * cos_light) as f32;
        let cos = point.normal.dot(d.normalize());
        if cos > 0.0 {
            let irradiance = intensity * (cos / d.length_squared()) as f32;
            radiance += specular_brdf(point, material, d.normalize()) * irradiance;
        }
    }
    radiance
}

fn distant_contribution(
    point: &SurfacePoint,
    material: &Reflectance,
    light: &DistantLight,
) -> Vec3 {
    let l = -light.direction;
    let cos = point.normal.dot(l);
    if cos <= 0.0 {
        return Vec3::ZERO;
    }
    (material.diffuse / PI + specular_brdf(point, material, l)) * light.irradiance * cos as f32
}

fn sphere_contribution(point: &SurfacePoint, material: &Reflectance, light: &SphereLight) -> Vec3 {
    let phi = sphere_form_factor::projected_solid_angle(
        point.position,
        point.normal,
        light.centre,
        light.radius,
    ) as f32;
    let mut radiance = material.diffuse / PI * light.radiance * phi;
    if material.specular != Vec3::ZERO && phi > 0.0 {
        let d = light.centre - point.position;
        let l = d.normalize();
        let cos = point.normal.dot(l);
        if cos > 0.0 {
            let intensity = light.radiance * (std::f64::consts::PI * light.radius.powi(2)) as f32;
            let irradiance = intensity * (cos / d.length_squared()) as f32;
            radiance += specular_brdf(point, material, l) * irradiance;
        }
    }
    radiance
}
