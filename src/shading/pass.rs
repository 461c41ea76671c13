//! The shading pass: per sample of a band of the visible-surface buffer, the radiance
//! towards the eye, each light's contribution weighted by its own visibility.
//!
//! Surfaces are two-sided for reflection (the normal is turned towards the eye) and
//! one-sided for emission (an emitter shows its radiance from the front only).
//! Flat: one radiance per polygon and light, at its centroid with its geometric
//! normal. Gouraud: radiance at the vertices, interpolated by the scan-line pass; with
//! several lights weighted differently, each light's vertex radiance is interpolated
//! on its own (by the same scan-line pass, once per light) so that each is weighted by
//! its own visibility. Phong: the light model at every sample with the interpolated
//! normal.
//!
//! A light's weight at a sample is its visibility: the fraction a method found, or,
//! for the visible part of an extended emitter, the ratio of its projected solid
//! angle to the whole emitter's (Lambert's contour formula on what remains), which
//! makes the diffuse irradiance exact; the specular part is scaled by the same ratio
//! (an approximation, as the specular part of extended lights already is). Williams's
//! post-pass (`post_pass`) darkens each light's contribution where its map finds
//! shadow instead: weight v + (1 − v) × `POST_PASS_SHADE`, highlights included.

use super::environment_mapping::{EnvironmentSample, backdrop};
use super::light_model::{SurfacePoint, reflected};
use super::textured::{polygon_tangents, textured_point};
use crate::geometry::lambert_contour::projected_solid_angle;
use crate::geometry::polygon::centroid;
use crate::raster::{LightVisibility, View, Visibility, VisiblePart, VisibleSurface};
use crate::scene::{EnvironmentSource, Light, Polygon, Scene, ShadingMode, Vertex};
use crate::texture::environment::EnvironmentMap;
use glam::{DVec3, Vec3};
use rayon::prelude::*;
use std::sync::Arc;

/// In Williams's post-pass, what a shadowed pixel keeps of a light's radiance.
pub const POST_PASS_SHADE: f32 = 0.25;

/// What shading needs of one frame, computed once for all its bands.
pub struct FrameShading<'a> {
    scene: &'a Scene,
    view: &'a View,
    /// Which lights this pass adds (an integrator may light with the others itself).
    direct: Vec<bool>,
    /// Per flat-shaded polygon, its radiance from each light.
    flat: Vec<Option<Vec<Vec3>>>,
    tangents: Vec<Option<Vec<[DVec3; 2]>>>,
    /// Per scene environment, its map (`None`: a capture nobody has made).
    environments: Vec<Option<Arc<EnvironmentMap>>>,
}

impl<'a> FrameShading<'a> {
    /// `direct[l]`: whether this pass adds light l.
    pub fn new(scene: &'a Scene, view: &'a View, direct: Vec<bool>) -> Self {
        let lights = scene.lights.len();
        let flat = scene
            .polygons
            .par_iter()
            .enumerate()
            .map(|(id, p)| {
                (scene.shading_of(id) == ShadingMode::Flat).then(|| {
                    let c = centroid(&p.positions().collect::<Vec<_>>());
                    (0..lights)
                        .map(|l| radiance_at(scene, p, c, p.normal, view.eye, l))
                        .collect()
                })
            })
            .collect();
        let environments = scene
            .environments
            .iter()
            .map(|e| match &e.source {
                _ if !scene.render.environments => None,
                EnvironmentSource::Map(map) => Some(map.clone()),
                EnvironmentSource::Capture(_) => None,
            })
            .collect();
        FrameShading {
            scene,
            view,
            direct,
            flat,
            tangents: polygon_tangents(scene),
            environments,
        }
    }

    /// The scene it shades.
    /// Where the frame is seen from.
    pub fn eye(&self) -> glam::DVec3 {
        self.view.eye
    }

    pub fn scene(&self) -> &'a Scene {
        self.scene
    }

    /// The maps of the scene's environments, captures included (`None`: that
    /// environment is not shown, as inside a capture itself).
    pub fn with_environments(mut self, maps: Vec<Option<Arc<EnvironmentMap>>>) -> Self {
        self.environments = maps;
        self
    }

    /// The radiance where no surface is seen at sample `k`: the backdrop environment,
    /// or the background colour.
    pub fn background(&self, band: &VisibleSurface, k: usize) -> Vec3 {
        match self
            .scene
            .render
            .backdrop
            .and_then(|e| self.environments[e].as_ref())
        {
            Some(map) => backdrop(map, self.view, band, k),
            None => self.scene.render.background,
        }
    }

    /// The radiance the environment adds at sample `k` (reflection and refraction
    /// mapping; zero for materials without an environment).
    pub fn environment(&self, band: &VisibleSurface, k: usize) -> Vec3 {
        self.environment_sample(band, k)
            .map_or(Vec3::ZERO, |(sample, map)| sample.radiance(map))
    }

    /// The mip-map level λ of the mirror-direction lookup at sample `k` (`None`
    /// without an environment, or for filters without levels).
    pub fn environment_level(&self, band: &VisibleSurface, k: usize) -> Option<f64> {
        self.environment_sample(band, k)
            .and_then(|(sample, map)| sample.reflected_level(map))
    }

    fn environment_sample<'b>(
        &'b self,
        band: &'b VisibleSurface,
        k: usize,
    ) -> Option<(EnvironmentSample<'b>, &'b EnvironmentMap)> {
        let scene = self.scene;
        let s = &band.samples[k];
        if s.is_empty() {
            return None;
        }
        let id = s.polygon as usize;
        let material = scene.material_of(id);
        let map = material
            .environment
            .and_then(|e| self.environments[e].as_ref())?;
        let polygon = &scene.polygons[id];
        let flat = scene.shading_of(id) == ShadingMode::Flat;
        let normal = if flat {
            polygon.normal
        } else if material.bump.is_some() {
            textured_point(scene, self.view.eye, band, k, &self.tangents).1
        } else {
            s.normal.as_dvec3()
        };
        let sample = EnvironmentSample {
            view: self.view,
            band,
            k,
            polygon,
            material,
            normal,
            flat,
            front: self.front(band, k),
        };
        Some((sample, map.as_ref()))
    }

    /// The radiance of every sample of `band`: emission and every light this pass adds.
    /// `gouraud[l]`: light l's vertex radiance as the scan-line pass interpolated it
    /// over Gouraud-shaded polygons, when lights are interpolated one by one (empty
    /// when the interpolated total, the samples' own colour, serves).
    pub fn shade_band(
        &self,
        band: &VisibleSurface,
        visibility: &Visibility,
        gouraud: &[Vec<Vec3>],
    ) -> Vec<Vec3> {
        let scene = self.scene;
        (0..band.samples.len())
            .into_par_iter()
            .map(|k| {
                let s = &band.samples[k];
                if s.is_empty() {
                    return self.background(band, k);
                }
                let material = scene.material_of(s.polygon as usize);
                let emitted = if self.front(band, k) {
                    material.emission
                } else {
                    Vec3::ZERO
                };
                emitted + self.lit(band, k, visibility, gouraud) + self.environment(band, k)
            })
            .collect()
    }

    /// Whether sample `k` shows the front of its polygon.
    pub fn front(&self, band: &VisibleSurface, k: usize) -> bool {
        let s = &band.samples[k];
        let to_eye = self.view.eye - s.position;
        self.scene.polygons[s.polygon as usize].normal.dot(to_eye) > 0.0
    }

    /// The radiance the lights this pass adds reflect towards the eye at sample `k`,
    /// each weighted by its visibility (`gouraud` as for `shade_band`).
    pub fn lit(
        &self,
        band: &VisibleSurface,
        k: usize,
        visibility: &Visibility,
        gouraud: &[Vec<Vec3>],
    ) -> Vec3 {
        let scene = self.scene;
        let s = &band.samples[k];
        let id = s.polygon as usize;
        let weight = |l: usize| self.weight(band, k, l, visibility);
        let lights = 0..scene.lights.len();
        match scene.shading_of(id) {
            ShadingMode::Flat => {
                let flat = self.flat[id]
                    .as_ref()
                    .expect("flat radiance of a flat polygon");
                lights
                    .filter(|&l| self.direct[l])
                    .map(|l| flat[l] * weight(l))
                    .sum()
            }
            // One light, or none shadowed: the interpolated total.
            ShadingMode::Gouraud if gouraud.is_empty() => {
                s.color
                    * if scene.lights.is_empty() {
                        1.0
                    } else {
                        weight(0)
                    }
            }
            ShadingMode::Gouraud => lights
                .filter(|&l| self.direct[l])
                .map(|l| gouraud[l][k] * weight(l))
                .sum(),
            ShadingMode::Phong => {
                let material = scene.material_of(id);
                let (reflectance, n) = if material.is_textured() {
                    textured_point(scene, self.view.eye, band, k, &self.tangents)
                } else {
                    (material.reflectance(), s.normal.as_dvec3())
                };
                let to_eye = (self.view.eye - s.position).normalize();
                let point = SurfacePoint {
                    position: s.position,
                    normal: if self.front(band, k) { n } else { -n },
                    to_eye,
                };
                lights
                    .filter(|&l| self.direct[l])
                    .map(|l| reflected(&point, &reflectance, &scene.lights[l]) * weight(l))
                    .sum()
            }
        }
    }

    /// What a diffuse texture multiplies the material's diffuse reflectance by at
    /// sample `k` (`None` without one).
    pub fn diffuse_texture_scale(&self, band: &VisibleSurface, k: usize) -> Option<Vec3> {
        let material = self.scene.material_of(band.samples[k].polygon as usize);
        material.diffuse_texture?;
        let (reflectance, _) = textured_point(self.scene, self.view.eye, band, k, &self.tangents);
        let ratio = |textured: f32, plain: f32| if plain > 0.0 { textured / plain } else { 0.0 };
        Some(Vec3::new(
            ratio(reflectance.diffuse.x, material.diffuse.x),
            ratio(reflectance.diffuse.y, material.diffuse.y),
            ratio(reflectance.diffuse.z, material.diffuse.z),
        ))
    }

    /// Light `l`'s weight at sample `k`: its visibility, or Williams's post-pass
    /// darkening.
    fn weight(&self, band: &VisibleSurface, k: usize, l: usize, visibility: &Visibility) -> f32 {
        let v = match visibility.of(l) {
            None => return 1.0,
            Some(LightVisibility::Fraction(f)) => f[k],
            Some(LightVisibility::Emitter(parts)) => match &parts[k] {
                None => 1.0,
                Some(part) => self.visible_ratio(band, k, l, part),
            },
        };
        if self.scene.shadows.post_pass {
            v + (1.0 - v) * POST_PASS_SHADE
        } else {
            v
        }
    }

    /// The share of a polygon light's projected solid angle that its visible part
    /// keeps, seen from sample `k`.
    fn visible_ratio(&self, band: &VisibleSurface, k: usize, l: usize, part: &VisiblePart) -> f32 {
        let Light::Polygon(light) = &self.scene.lights[l] else {
            return 1.0;
        };
        let s = &band.samples[k];
        let mut n = self.scene.polygons[s.polygon as usize].normal;
        if n.dot(light.centre - s.position) < 0.0 {
            n = -n;
        }
        let whole = projected_solid_angle(s.position, n, &light.vertices);
        if whole <= 0.0 {
            return 0.0;
        }
        let seen: f64 = part
            .contours
            .iter()
            .map(|(contour, sign)| sign * projected_solid_angle(s.position, n, contour))
            .sum();
        (seen / whole).clamp(0.0, 1.0) as f32
    }
}

/// Unshadowed radiance leaving a point of `polygon` towards the eye, from light `l`.
pub fn radiance_at(
    scene: &Scene,
    polygon: &Polygon,
    position: DVec3,
    normal: DVec3,
    eye: DVec3,
    l: usize,
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
    reflected(&point, &reflectance, &scene.lights[l])
}

/// Per polygon, the radiance at its vertices for Gouraud-shaded polygons (empty
/// for the others) from the lights `direct` selects: the colours the scan-line pass
/// interpolates.
pub fn vertex_colors(scene: &Scene, view: &View, direct: &[bool]) -> Vec<Vec<Vec3>> {
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
                .map(|v: &Vertex| {
                    (0..scene.lights.len())
                        .filter(|&l| direct[l])
                        .map(|l| radiance_at(scene, p, v.position, v.normal, view.eye, l))
                        .sum()
                })
                .collect()
        })
        .collect()
}
