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
use super::point_lanes::Lanes;
use super::textured::{polygon_tangents, textured_point};
use crate::geometry::lambert_contour::projected_solid_angle;
use crate::geometry::polygon::centroid;
use crate::raster::{LightVisibility, Sample, View, Visibility, VisiblePart, VisibleSurface};
use crate::scene::{
    EnvironmentSource, Light, Material, Polygon, Reflectance, Scene, ShadingMode, Vertex,
};
use crate::texture::environment::EnvironmentMap;
use glam::{DVec3, Vec3};
use rayon::prelude::*;
use std::sync::Arc;

/// In Williams's post-pass, what a shadowed pixel keeps of a light's radiance.
pub const POST_PASS_SHADE: f32 = 0.25;

/// Samples shaded one after the other by one thread: enough to make the parallel
/// split's cost vanish, few enough to share a band between both cores evenly.
const SAMPLES_PER_TASK: usize = 4096;

/// What shading reads of a polygon at each of its samples, looked up once a frame
/// (the scene reaches them through the polygon's object and material).
struct PolygonLook<'a> {
    material: &'a Material,
    mode: ShadingMode,
    /// The geometric normal, which tells the front from the back.
    normal: DVec3,
}

impl PolygonLook<'_> {
    /// Phong-shaded, untextured, without environment: the common case, shaded in
    /// a loop of its own.
    fn plain_phong(&self) -> bool {
        self.mode == ShadingMode::Phong
            && !self.material.is_textured()
            && self.material.environment.is_none()
    }

    /// What the polygon emits towards the eye: its front alone shows emission.
    fn emitted(&self, front: bool) -> Vec3 {
        if front {
            self.material.emission
        } else {
            Vec3::ZERO
        }
    }
}

/// What shading needs of one frame, computed once for all its bands.
pub struct FrameShading<'a> {
    scene: &'a Scene,
    view: &'a View,
    /// Per flat-shaded polygon, its radiance from each light.
    flat: Vec<Option<Vec<Vec3>>>,
    tangents: Vec<Option<Vec<[DVec3; 2]>>>,
    /// Per scene environment, its map (`None`: a capture nobody has made).
    environments: Vec<Option<Arc<EnvironmentMap>>>,
    /// Per polygon, its material, shading mode and normal.
    looks: Vec<PolygonLook<'a>>,
    /// The lights this pass adds, in the scene's order (an integrator may light with
    /// the others itself).
    added: Vec<usize>,
    /// Whether every light this pass adds is a point light (the lanes' case).
    points_only: bool,
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
        let looks = (0..scene.polygons.len())
            .map(|id| PolygonLook {
                material: scene.material_of(id),
                mode: scene.shading_of(id),
                normal: scene.polygons[id].normal,
            })
            .collect();
        let added: Vec<usize> = (0..lights).filter(|&l| direct[l]).collect();
        let points_only = added
            .iter()
            .all(|&l| matches!(scene.lights[l], Light::Point(_)));
        FrameShading {
            scene,
            view,
            flat,
            tangents: polygon_tangents(scene),
            environments,
            looks,
            added,
            points_only,
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
        let mut radiance = vec![Vec3::ZERO; band.samples.len()];
        radiance
            .par_chunks_mut(SAMPLES_PER_TASK)
            .enumerate()
            .for_each(|(task, chunk)| {
                let first = task * SAMPLES_PER_TASK;
                let samples = &band.samples[first..first + chunk.len()];
                // Runs of one polygon: what it fixes is looked up once per run.
                let mut done = 0;
                for run in samples.chunk_by(|a, b| a.polygon == b.polygon) {
                    let out = &mut chunk[done..done + run.len()];
                    let k = first + done;
                    match self.looks.get(run[0].polygon as usize) {
                        Some(look) if look.plain_phong() => {
                            self.shade_plain_phong(band, k, run, look, out, visibility)
                        }
                        _ => {
                            for (i, r) in out.iter_mut().enumerate() {
                                *r = self.shade_sample(band, k + i, visibility, gouraud);
                            }
                        }
                    }
                    done += run.len();
                }
            });
        radiance
    }

    /// `shade_sample` over `run`, samples `first..` of one polygon, Phong-shaded,
    /// untextured and without environment (`out`: their radiance). Never inlined: the
    /// hottest loop of a frame is compiled as a function of its own, not inside
    /// whatever rayon consumer the task closure lands in, where the inliner's choice
    /// followed the module layout (moving modules cost 7% more instructions and
    /// 15-20% more time).
    #[inline(never)]
    fn shade_plain_phong(
        &self,
        band: &VisibleSurface,
        first: usize,
        run: &[Sample],
        look: &PolygonLook,
        out: &mut [Vec3],
        visibility: &Visibility,
    ) {
        let reflectance = look.material.reflectance();
        // Only Phong's lobe reads the direction to the eye: without it, its square
        // root and division are left out (the radiance is the same, bit for bit).
        let glossy = reflectance.specular != Vec3::ZERO;
        let mut done = 0;
        if !glossy && self.points_only {
            done = run.len() / 4 * 4;
            self.shade_lambert_lanes(
                band,
                first,
                &run[..done],
                look,
                &mut out[..done],
                visibility,
            );
        }
        for (i, (s, r)) in run.iter().zip(out.iter_mut()).enumerate().skip(done) {
            let (_, to_eye, front) = self.seen(s);
            let point = SurfacePoint {
                position: s.position,
                normal: eye_side(s.normal.as_dvec3(), front),
                to_eye: if glossy { to_eye.normalize() } else { to_eye },
            };
            let lit = self.phong(&point, &reflectance, band, first + i, visibility);
            // The environment's share is zero; adding it keeps the sum's rounding.
            *r = look.emitted(front) + lit + Vec3::ZERO;
        }
    }

    /// `shade_plain_phong` for a Lambertian polygon under point lights alone, four
    /// samples at a time (`run` a multiple of four long): the lights' arithmetic in
    /// lanes (`point_lanes`), the rest as the scalar model does it, so the radiance
    /// is the same bit for bit.
    fn shade_lambert_lanes(
        &self,
        band: &VisibleSurface,
        first: usize,
        run: &[Sample],
        look: &PolygonLook,
        out: &mut [Vec3],
        visibility: &Visibility,
    ) {
        // The scalar model's (ρ/π + its zero specular lobe), once.
        let diffuse = look.material.diffuse / std::f32::consts::PI + Vec3::ZERO;
        for (c, (four, radiance)) in run.chunks_exact(4).zip(out.chunks_exact_mut(4)).enumerate() {
            let k = first + 4 * c;
            let mut front = [false; 4];
            let points: [(DVec3, DVec3); 4] = std::array::from_fn(|i| {
                let s = &four[i];
                front[i] = self.seen(s).2;
                (s.position, eye_side(s.normal.as_dvec3(), front[i]))
            });
            let lanes = Lanes::new(&points);
            let mut lit = [Vec3::ZERO; 4];
            for &l in &self.added {
                let Light::Point(light) = &self.scene.lights[l] else {
                    unreachable!("points_only: every added light is a point");
                };
                let factors = lanes.point_factors(light.position);
                for i in 0..4 {
                    let weight = self.weight(band, k + i, l, visibility, points[i].1);
                    let reflected = match factors[i] {
                        Some(t) => diffuse * (light.intensity * t as f32),
                        None => Vec3::ZERO,
                    };
                    lit[i] += reflected * weight;
                }
            }
            for i in 0..4 {
                radiance[i] = look.emitted(front[i]) + lit[i] + Vec3::ZERO;
            }
        }
    }

    /// The light model at `point` for every light this pass adds, each weighted by
    /// its visibility at sample `k`.
    #[inline(always)]
    fn phong(
        &self,
        point: &SurfacePoint,
        reflectance: &Reflectance,
        band: &VisibleSurface,
        k: usize,
        visibility: &Visibility,
    ) -> Vec3 {
        let mut lit = Vec3::ZERO;
        for &l in &self.added {
            let light = &self.scene.lights[l];
            let weight = self.weight(band, k, l, visibility, point.normal);
            lit += reflected(point, reflectance, light) * weight;
        }
        lit
    }

    /// The radiance of sample `k`: emission, every light this pass adds, and the
    /// environment.
    fn shade_sample(
        &self,
        band: &VisibleSurface,
        k: usize,
        visibility: &Visibility,
        gouraud: &[Vec<Vec3>],
    ) -> Vec3 {
        let s = &band.samples[k];
        if s.is_empty() {
            return self.background(band, k);
        }
        let (look, to_eye, front) = self.seen(s);
        let environment = if look.material.environment.is_some() {
            self.environment(band, k)
        } else {
            Vec3::ZERO
        };
        let lit = self.lit_from(band, k, look, to_eye, front, visibility, gouraud);
        look.emitted(front) + lit + environment
    }

    /// Whether sample `k` shows the front of its polygon.
    pub fn front(&self, band: &VisibleSurface, k: usize) -> bool {
        self.seen(&band.samples[k]).2
    }

    /// The polygon sample `s` shows, the direction from it to the eye (not
    /// normalised), and whether it is the polygon's front.
    fn seen(&self, s: &Sample) -> (&PolygonLook<'a>, DVec3, bool) {
        let look = &self.looks[s.polygon as usize];
        let to_eye = self.view.eye - s.position;
        (look, to_eye, look.normal.dot(to_eye) > 0.0)
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
        let (look, to_eye, front) = self.seen(&band.samples[k]);
        self.lit_from(band, k, look, to_eye, front, visibility, gouraud)
    }

    /// `lit` at a sample whose polygon, unnormalised direction to the eye and side
    /// are known.
    #[allow(clippy::too_many_arguments)]
    fn lit_from(
        &self,
        band: &VisibleSurface,
        k: usize,
        look: &PolygonLook,
        to_eye: DVec3,
        front: bool,
        visibility: &Visibility,
        gouraud: &[Vec<Vec3>],
    ) -> Vec3 {
        let scene = self.scene;
        let s = &band.samples[k];
        // Flat and Gouraud shading have no normal at the sample: the share of an
        // extended light is taken over the polygon's hemisphere on the eye's side.
        let geometric = if front { look.normal } else { -look.normal };
        let weight = |l: usize| self.weight(band, k, l, visibility, geometric);
        let added = self.added.iter().copied();
        match look.mode {
            ShadingMode::Flat => {
                let flat = self.flat[s.polygon as usize]
                    .as_ref()
                    .expect("flat radiance of a flat polygon");
                added.map(|l| flat[l] * weight(l)).sum()
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
            ShadingMode::Gouraud => added.map(|l| gouraud[l][k] * weight(l)).sum(),
            ShadingMode::Phong => {
                let (reflectance, n) = if look.material.is_textured() {
                    textured_point(scene, self.view.eye, band, k, &self.tangents)
                } else {
                    (look.material.reflectance(), s.normal.as_dvec3())
                };
                let point = surface_point(s, n, to_eye, front);
                self.phong(&point, &reflectance, band, k, visibility)
            }
        }
    }

    /// What a diffuse texture multiplies the material's diffuse reflectance by at
    /// sample `k` (`None` without one).
    pub fn diffuse_texture_scale(&self, band: &VisibleSurface, k: usize) -> Option<Vec3> {
        let material = self.scene.material_of(band.samples[k].polygon as usize);
        material.diffuse_texture?;
        let (reflectance, _) = textured_point(self.scene, self.view.eye, band, k, &self.tangents);
        Some(material.diffuse_scale(reflectance.diffuse))
    }

    /// Light `l`'s weight at sample `k`, shaded with unit `normal` (on the eye's
    /// side): its visibility, or Williams's post-pass darkening.
    #[inline(always)]
    fn weight(
        &self,
        band: &VisibleSurface,
        k: usize,
        l: usize,
        visibility: &Visibility,
        normal: DVec3,
    ) -> f32 {
        let v = match visibility.of(l) {
            None => return 1.0,
            Some(LightVisibility::Fraction(f)) => f[k],
            Some(LightVisibility::Emitter(parts)) => match &parts[k] {
                None => 1.0,
                Some(part) => self.visible_ratio(band, k, l, part, normal),
            },
        };
        if self.scene.shadows.post_pass {
            v + (1.0 - v) * POST_PASS_SHADE
        } else {
            v
        }
    }

    /// The share of a polygon light's projected solid angle that its visible part
    /// keeps, seen from sample `k` through the hemisphere of `n`, the normal the
    /// light model shades it with (interpolated or bumped, turned to the eye), so
    /// that share times the unshadowed irradiance is the visible part's own. Where
    /// the receiver's plane cuts the light, that hemisphere holds the part of the
    /// light on the eye's side, whichever side the light's centre is on.
    fn visible_ratio(
        &self,
        band: &VisibleSurface,
        k: usize,
        l: usize,
        part: &VisiblePart,
        n: DVec3,
    ) -> f32 {
        let Light::Polygon(light) = &self.scene.lights[l] else {
            return 1.0;
        };
        let s = &band.samples[k];
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

/// The point sample `s` shows, with shading normal `n` turned to the eye's side and
/// the unit direction to the eye (`to_eye` unnormalised).
#[inline(always)]
fn surface_point(s: &Sample, n: DVec3, to_eye: DVec3, front: bool) -> SurfacePoint {
    SurfacePoint {
        position: s.position,
        normal: eye_side(n, front),
        to_eye: to_eye.normalize(),
    }
}

/// Unit normal `n` turned to the eye's side of a polygon seen from the `front` or
/// from behind.
#[inline(always)]
fn eye_side(n: DVec3, front: bool) -> DVec3 {
    if front { n } else { -n }
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
