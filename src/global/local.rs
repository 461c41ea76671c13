//! The local terms at a point a ray has found: each light's reflected radiance
//! (the shading pass's light model) times the share of it a shadow ray finds clear,
//! and the textured reflectance there.

use super::traced_scene::{Leaving, SurfaceHit, TracedScene};
use crate::geometry::sampling::Stream;
use crate::scene::lights::DISTANT_REACH;
use crate::scene::{Light, Reach, Reflectance, Scene};
use crate::shading::light_model::{SurfacePoint, reflected};
use crate::texture::Interpolation;
use crate::texture::environment::EnvironmentMap;
use glam::{DVec2, DVec3, Vec3};

/// What a ray that leaves the scene along `direction` brings back: the backdrop
/// environment, or else the background colour.
pub fn background(scene: &Scene, backdrop: Option<&EnvironmentMap>, direction: DVec3) -> Vec3 {
    match backdrop {
        Some(map) => map.lookup(direction, [DVec3::ZERO; 2]),
        None => scene.render.background,
    }
}

/// The reflectance at a hit, its material's textures applied (unfiltered: level
/// 0 of a pyramid; Whitted antialiased by subdividing pixels instead).
pub fn reflectance_at(scene: &Scene, hit: &SurfaceHit, to_eye: DVec3) -> Reflectance {
    let material = &scene.materials[hit.material];
    let mut reflectance = material.reflectance();
    if !material.is_textured() {
        return reflectance;
    }
    let uv = match &material.mapping {
        Some(m) if material.interpolation == Interpolation::Exact || hit.polygon.is_none() => {
            let frame = &scene.objects[hit.object].frame;
            let point = frame.to_object.transform_point3(hit.position);
            let eye = frame.to_object.transform_point3(hit.position + to_eye);
            let normal = frame.normal_to_object(hit.normal).normalize_or_zero();
            m.uv(
                point,
                normal,
                frame.centroid,
                (eye - point).normalize_or_zero(),
            )
        }
        _ => hit.uv,
    };
    let colour = |t: Option<usize>| t.map(|t| scene.textures[t].color(uv, [DVec2::ZERO; 2]));
    if let Some(c) = colour(material.diffuse_texture) {
        reflectance.diffuse *= c;
    }
    if let Some(c) = colour(material.specular_texture) {
        reflectance.specular *= c;
    }
    reflectance
}

/// What a diffuse texture multiplies the material's diffuse reflectance by at a
/// hit, per band (`None` untextured): a solution solved with the plain reflectance
/// is scaled by it where rays land, as the scan-line pass scales it at samples.
pub fn diffuse_texture_scale(scene: &Scene, hit: &SurfaceHit, to_eye: DVec3) -> Option<Vec3> {
    let material = &scene.materials[hit.material];
    material.diffuse_texture?;
    Some(material.diffuse_scale(reflectance_at(scene, hit, to_eye).diffuse))
}

/// Radiance towards `to_eye` from the lights `lit` selects, each shadowed by rays:
/// one to a point, spot or distant light (Whitted), N × N stratified ones over an
/// extended light, weighted by their share of its unoccluded irradiance (as
/// `shadow::ray_cast` does). `normal` is the shading normal on the eye's side.
#[allow(clippy::too_many_arguments)]
pub fn lights_at(
    scene: &Scene,
    traced: &TracedScene,
    position: DVec3,
    normal: DVec3,
    to_eye: DVec3,
    reflectance: &Reflectance,
    leaving: Leaving,
    lit: &[bool],
    stream_index: u64,
) -> Vec3 {
    let point = SurfacePoint {
        position,
        normal,
        to_eye,
    };
    let mut total = Vec3::ZERO;
    for (l, light) in scene.lights.iter().enumerate() {
        if !lit[l] {
            continue;
        }
        let unshadowed = reflected(&point, reflectance, light);
        if unshadowed == Vec3::ZERO {
            continue;
        }
        let clear = match light.reach() {
            Reach::Point { at, .. } => {
                if traced.blocked(position, at, leaving, None) {
                    0.0
                } else {
                    1.0
                }
            }
            Reach::Direction { direction, .. } => {
                let far = position - direction * DISTANT_REACH;
                if traced.blocked(position, far, leaving, None) {
                    0.0
                } else {
                    1.0
                }
            }
            Reach::Extended { .. } => {
                let mut stream = Stream::new(l as u64, stream_index);
                extended_clear(scene, traced, light, position, normal, leaving, &mut stream)
            }
        };
        total += unshadowed * clear;
    }
    total
}

/// The share of an extended light's irradiance at `position` that reaches it.
fn extended_clear(
    scene: &Scene,
    traced: &TracedScene,
    light: &Light,
    position: DVec3,
    normal: DVec3,
    leaving: Leaving,
    stream: &mut Stream,
) -> f32 {
    let emitter = light.emitter_polygon().map(|p| p as u32);
    let (mut total, mut clear) = (0.0, 0.0);
    for u in stream.jittered(scene.shadows.light_samples as usize) {
        let Some(sample) = light.sample(position, u) else {
            continue;
        };
        let d = sample.point - position;
        let w = sample.weight * normal.dot(d).max(0.0) / d.length();
        if w <= 0.0 || !w.is_finite() {
            continue;
        }
        total += w;
        if !traced.blocked(position, sample.point, leaving, emitter) {
            clear += w;
        }
    }
    if total > 0.0 {
        (clear / total) as f32
    } else {
        1.0
    }
}
