//! The shading pass: per sample of the visible-surface buffer, the radiance towards
//! the eye, each light's contribution weighted by its visibility term.
//!
//! Surfaces are two-sided for reflection (the normal is turned towards the eye) and
//! one-sided for emission (an emitter shows its radiance from the front only).
//! Flat: one radiance per polygon, at its centroid with its geometric normal.
//! Gouraud: radiance at the vertices, interpolated by the scan-line pass (the
//! visibility term then weighs the interpolated total, since vertex radiance is not
//! kept per light). Phong: the light model at every sample with the interpolated
//! normal.

use super::light_model::{SurfacePoint, reflected};
use super::textured::{polygon_tangents, textured_point};
use crate::geometry::polygon::centroid;
use crate::raster::{View, VisibleSurface};
use crate::scene::{Polygon, Scene, ShadingMode, Vertex};
use crate::shadow::Visibility;
use glam::{DVec3, Vec3};
use rayon::prelude::*;

/// Linear radiance of every sample of `surface`.
pub fn shade(
    scene: &Scene,
    view: &View,
    surface: &VisibleSurface,
    visibility: &Visibility,
) -> Vec<Vec3> {
    let flat: Vec<Option<Vec3>> = scene
        .polygons
        .par_iter()
        .enumerate()
        .map(|(id, p)| {
            (scene.shading_of(id) == ShadingMode::Flat).then(|| flat_radiance(scene, view, p))
        })
        .collect();
    let tangents = polygon_tangents(scene);
    surface
        .samples
        .par_iter()
        .enumerate()
        .map(|(k, s)| {
            if s.is_empty() {
                return scene.render.background;
            }
            let id = s.polygon as usize;
            let polygon = &scene.polygons[id];
            let material = &scene.materials[polygon.material];
            let to_eye = (view.eye - s.position).normalize();
            let front = polygon.normal.dot(to_eye) > 0.0;
            let emitted = if front { material.emission } else { Vec3::ZERO };
            let lit = match scene.shading_of(id) {
                ShadingMode::Flat => flat[id].unwrap_or_default() * visibility.mean(k),
                ShadingMode::Gouraud => s.color * visibility.mean(k),
                ShadingMode::Phong => {
                    let (reflectance, n) = if material.is_textured() {
                        textured_point(scene, view.eye, surface, k, &tangents)
                    } else {
                        (material.reflectance(), s.normal.as_dvec3())
                    };
                    let point = SurfacePoint {
                        position: s.position,
                        normal: if front { n } else { -n },
                        to_eye,
                    };
                    scene
                        .lights
                        .iter()
                        .enumerate()
                        .map(|(l, light)| {
                            reflected(&point, &reflectance, light) * visibility.of(l, k)
                        })
                        .sum()
                }
            };
            emitted + lit
        })
        .collect()
}

/// Unshadowed radiance leaving a point towards the eye, from every light.
fn radiance_at(
    scene: &Scene,
    polygon: &Polygon,
    position: DVec3,
    normal: DVec3,
    eye: DVec3,
) -> Vec3 {
    let to_eye = (eye - position).normalize();
    let side = if polygon.normal.dot(to_eye) >= 0.0 {
        1.0
    } else {
        -1.0
    };
    let point = SurfacePoint {
        position,
        normal: normal * side,
        to_eye,
    };
    let reflectance = scene.materials[polygon.material].reflectance();
    scene
        .lights
        .iter()
        .map(|l| reflected(&point, &reflectance, l))
        .sum()
}

fn flat_radiance(scene: &Scene, view: &View, polygon: &Polygon) -> Vec3 {
    let c = centroid(&polygon.positions().collect::<Vec<_>>());
    radiance_at(scene, polygon, c, polygon.normal, view.eye)
}

/// Per polygon, the radiance at its vertices for Gouraud-shaded polygons (empty
/// for the others): the colours the scan-line pass interpolates.
pub fn vertex_colors(scene: &Scene, view: &View) -> Vec<Vec<Vec3>> {
    scene
        .polygons
        .par_iter()
        .enumerate()
        .map(|(id, p)| {
            if scene.shading_of(id) != ShadingMode::Gouraud {
                return Vec::new();
            }
            p.vertices
                .iter()
                .map(|v: &Vertex| radiance_at(scene, p, v.position, v.normal, view.eye))
                .collect()
        })
        .collect()
}
