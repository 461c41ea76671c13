//! Pass 2 of Jensen's photon-map method (H. W. Jensen, "Global illumination using
//! photon maps", Rendering Techniques '96): rays from the eye, and at each visible
//! point the light split by where it comes from, each part by the tool that
//! finds it best:
//!
//! - the direct light exactly: the light model's exact unshadowed light (Lambert's
//!   formula over an emitter) times the share of it stratified shadow rays find
//!   clear (`local::lights_at`, as the ray tracer's);
//! - caustics (light that came from the lamps by specular bounces only) from the
//!   caustic map, read directly with the cone filter;
//! - the indirect diffuse light by a final gather (Ward's stratified hemisphere,
//!   `final_gather::gather_hemisphere`) whose rays read the global map's radiance
//!   estimate where they land, through Ward's irradiance cache; the map's blur is
//!   one bounce away and averages out over the hemisphere;
//! - specular reflection and refraction by rays, Whitted's way (the mirror and
//!   transmitted rays weighted by the coefficients, Fresnel's at glass), which
//!   show the lamps and what they meet.
//!
//! Choices left open, made here: a gather ray that meets a mirror or glass goes
//! on by the same specular rays to the depth limit and reads the global map where
//! it lands, without the emission it may find (that light is a caustic, in the
//! caustic map); Phong's lobe gets the direct light only; the cone filter's
//! constant is 1.1, as in Jensen's book; n × n eye rays a pixel, stratified.

use super::final_gather::{Gathered, Strata, gather_hemisphere};
use super::irradiance_cache::{Gatherer, IrradianceCache};
use super::local::{background, lights_at, reflectance_at};
use super::path_tracing::specular_coefficients;
use super::photon_map::PhotonMap;
use super::precomputed_irradiance::PrecomputedIrradiance;
use super::traced_scene::{Facing, Leaving, SurfaceHit, TracedScene};
use super::whitted::{reflected_direction, refracted_direction};
use crate::geometry::bvh::Aabb;
use crate::geometry::sampling::Stream;
use crate::image_io::Image;
use crate::raster::View;
use crate::scene::Scene;
use crate::settings::{FinalGatherSettings, GlobalSettings};
use crate::texture::environment::EnvironmentMap;
use glam::{DVec3, Vec3};
use rayon::prelude::*;
use std::f32::consts::PI;

/// Jensen's cone filter constant (his book's 1.1).
pub const CONE: f64 = 1.1;

/// The two maps of pass 1, and Christensen's irradiance precomputed over the
/// global one where asked.
pub struct PhotonMaps {
    pub global: PhotonMap,
    pub caustic: PhotonMap,
    pub precomputed: Option<PrecomputedIrradiance>,
}

/// The final gather over the global map.
pub struct PhotonGather<'a> {
    scene: &'a Scene,
    traced: &'a TracedScene,
    global: &'a PhotonMap,
    precomputed: Option<&'a PrecomputedIrradiance>,
    nearest: usize,
    settings: FinalGatherSettings,
    strata: Strata,
    bounds: Aabb,
    depth: u32,
}

impl<'a> PhotonGather<'a> {
    pub fn new(
        scene: &'a Scene,
        traced: &'a TracedScene,
        maps: &'a PhotonMaps,
        settings: &GlobalSettings,
        gather: FinalGatherSettings,
    ) -> PhotonGather<'a> {
        PhotonGather {
            scene,
            traced,
            global: &maps.global,
            precomputed: maps.precomputed.as_ref(),
            nearest: settings.photons.nearest as usize,
            settings: gather,
            strata: Strata::for_rays(gather.rays),
            bounds: Aabb::of(scene.polygons.iter().flat_map(|p| p.positions())),
            depth: settings.depth,
        }
    }

    /// The gather at `position` (unit `normal` on the side seen), leaving the
    /// surface `leaving`, its rays from stream `stream`.
    pub fn gather_from(
        &self,
        position: DVec3,
        normal: DVec3,
        leaving: Leaving,
        stream: u64,
    ) -> Gathered {
        let mut rays = Stream::new(GATHER_SEED, stream);
        let mut choices = Stream::new(CHOICE_SEED, stream);
        gather_hemisphere(
            self.traced,
            position,
            normal,
            leaving,
            self.strata,
            &mut rays,
            |hit, direction| self.read(hit, direction, &mut choices),
        )
    }

    /// The radiance a gather ray along `direction` brings back from `hit`: the
    /// global map's estimate there for its diffuse part; off a mirror or through
    /// glass, one of the specular rays, drawn in proportion to its weight (the
    /// weight over the chance: no tree of rays under every gather ray), to the
    /// depth limit.
    fn read(&self, hit: &SurfaceHit, direction: DVec3, choices: &mut Stream) -> Vec3 {
        let mut radiance = Vec3::ZERO;
        let mut weight = Vec3::ONE;
        let (mut hit, mut direction) = (*hit, direction);
        for depth in 1.. {
            let material = &self.scene.materials[hit.material];
            let Facing { front, normal, .. } = hit.facing(direction);
            let reflectance = reflectance_at(self.scene, &hit, -direction);
            if reflectance.diffuse.max_element() > 0.0 {
                let irradiance = self
                    .precomputed
                    .and_then(|p| p.irradiance(hit.position, normal))
                    .unwrap_or_else(|| self.global.irradiance(hit.position, normal, self.nearest));
                radiance += weight * reflectance.diffuse / PI * irradiance;
            }
            if depth > self.depth {
                break;
            }
            let rays = specular_rays(material, normal, direction, front);
            let total: f32 = rays.iter().map(|(k, _)| k.max_element()).sum();
            if total <= 0.0 {
                break;
            }
            let mut u = choices.next_f64() as f32 * total;
            let Some((k, onward)) = rays.into_iter().find(|(k, _)| {
                u -= k.max_element();
                u < 0.0
            }) else {
                break;
            };
            weight *= k * (total / k.max_element());
            let Some(next) =
                self.traced
                    .closest(hit.position, onward, f64::INFINITY, hit.leaving())
            else {
                break;
            };
            (hit, direction) = (next, onward);
        }
        radiance
    }
}

impl Gatherer for PhotonGather<'_> {
    fn traced(&self) -> &TracedScene {
        self.traced
    }

    fn settings(&self) -> FinalGatherSettings {
        self.settings
    }

    fn bounds(&self) -> Aabb {
        self.bounds
    }

    fn gather(
        &self,
        _scene: &Scene,
        polygon: u32,
        position: DVec3,
        normal: DVec3,
        stream: u64,
    ) -> Gathered {
        self.gather_from(position, normal, Leaving::Polygon(polygon), stream)
    }
}

/// The mirror and transmitted rays from a surface, with their weights (none where
/// a weight is 0 or glass reflects totally).
fn specular_rays(
    material: &crate::scene::Material,
    normal: DVec3,
    direction: DVec3,
    front: bool,
) -> Vec<(Vec3, DVec3)> {
    let (mirror, transmitted, eta1, eta2) =
        specular_coefficients(material, normal, direction, front);
    let mut rays = Vec::new();
    if mirror.max_element() > 0.0 {
        rays.push((mirror, reflected_direction(direction, normal)));
    }
    if transmitted.max_element() > 0.0 {
        let onward = match material.ior {
            Some(_) => refracted_direction(direction, normal, eta2 / eta1),
            None => Some(direction),
        };
        if let Some(onward) = onward {
            rays.push((transmitted, onward));
        }
    }
    rays
}

/// Pass 2 over the maps.
pub struct PhotonRenderer<'a> {
    scene: &'a Scene,
    traced: &'a TracedScene,
    maps: &'a PhotonMaps,
    gather: PhotonGather<'a>,
    cache: IrradianceCache,
    samples: u32,
    caustic_nearest: usize,
    depth: u32,
    backdrop: Option<&'a EnvironmentMap>,
    lit: Vec<bool>,
}

/// A frame of pass 2: the image, and per pixel the global map read directly at
/// the first visible point (what the final gather keeps out of sight).
pub struct PhotonFrame {
    pub image: Image,
    pub photons: Vec<Vec3>,
}

impl<'a> PhotonRenderer<'a> {
    /// Pass 2 for `view`: the irradiance cache is swept over it first.
    pub fn new(
        scene: &'a Scene,
        traced: &'a TracedScene,
        maps: &'a PhotonMaps,
        settings: &GlobalSettings,
        gather: FinalGatherSettings,
        view: &View,
        backdrop: Option<&'a EnvironmentMap>,
    ) -> PhotonRenderer<'a> {
        let gather = PhotonGather::new(scene, traced, maps, settings, gather);
        let cache = IrradianceCache::sweep(scene, &gather, view);
        PhotonRenderer {
            scene,
            traced,
            maps,
            gather,
            cache,
            samples: settings.samples,
            caustic_nearest: settings.photons.caustic_nearest as usize,
            depth: settings.depth,
            backdrop,
            lit: vec![true; scene.lights.len()],
        }
    }

    /// The radiance along the ray from `origin` (leaving `leaving`), `depth`
    /// specular bounces from the eye; `index` numbers the point for its streams.
    fn radiance(
        &self,
        origin: DVec3,
        direction: DVec3,
        leaving: Leaving,
        depth: u32,
        index: u64,
    ) -> Vec3 {
        let Some(hit) = self
            .traced
            .closest(origin, direction, f64::INFINITY, leaving)
        else {
            return background(self.scene, self.backdrop, direction);
        };
        let material = &self.scene.materials[hit.material];
        let Facing { front, normal, .. } = hit.facing(direction);
        let to_eye = -direction;
        let reflectance = reflectance_at(self.scene, &hit, to_eye);
        let mut radiance = if front { material.emission } else { Vec3::ZERO };
        radiance += lights_at(
            self.scene,
            self.traced,
            hit.position,
            normal,
            to_eye,
            &reflectance,
            hit.leaving(),
            &self.lit,
            index,
        );
        if reflectance.diffuse.max_element() > 0.0 {
            let caustic =
                self.maps
                    .caustic
                    .irradiance_cone(hit.position, normal, self.caustic_nearest, CONE);
            let indirect = self
                .cache
                .irradiance(hit.position, normal)
                .unwrap_or_else(|| {
                    self.gather
                        .gather_from(hit.position, normal, hit.leaving(), index)
                        .irradiance
                });
            radiance += reflectance.diffuse / PI * (caustic + indirect);
        }
        if depth < self.depth {
            let rays = specular_rays(material, normal, direction, front);
            for (b, (k, onward)) in rays.into_iter().enumerate() {
                // The point's own numbers for its shadow rays: the low bits of the
                // sample's index count the bounces.
                let deeper = index + 1 + b as u64 + 2 * depth as u64;
                radiance +=
                    k * self.radiance(hit.position, onward, hit.leaving(), depth + 1, deeper);
            }
        }
        radiance
    }

    /// The global map's reflected radiance at the first point the ray meets.
    fn photons_seen(&self, origin: DVec3, direction: DVec3) -> Vec3 {
        let Some(hit) = self
            .traced
            .closest(origin, direction, f64::INFINITY, Leaving::Eye)
        else {
            return Vec3::ZERO;
        };
        let normal = hit.facing(direction).normal;
        let reflectance = reflectance_at(self.scene, &hit, -direction);
        reflectance.diffuse / PI
            * self
                .maps
                .global
                .irradiance(hit.position, normal, self.gather.nearest)
    }

    /// The frame: n × n eye rays a pixel, rows in parallel (each pixel's numbers
    /// its own, so the same on any number of threads); with `photons`, the global
    /// map seen directly as well.
    pub fn render(&self, view: &View, seed: u64, photons: bool) -> PhotonFrame {
        let (width, height) = (view.width, view.height);
        let n = self.samples as usize;
        let rows: Vec<Vec<(Vec3, Vec3)>> = (0..height)
            .into_par_iter()
            .map(|j| {
                (0..width)
                    .map(|i| {
                        let pixel = j as u64 * width as u64 + i as u64;
                        let mut stream = Stream::new(seed, pixel);
                        let cells = stream.jittered(n);
                        let (mut sum, mut seen) = (Vec3::ZERO, Vec3::ZERO);
                        for (s, cell) in cells.iter().enumerate() {
                            let (origin, direction) =
                                view.ray_through(i as f64 + cell.x, j as f64 + cell.y);
                            let direction = direction.normalize();
                            let index = (pixel * cells.len() as u64 + s as u64) << 8;
                            sum += self.radiance(origin, direction, Leaving::Eye, 0, index);
                            if photons {
                                seen += self.photons_seen(origin, direction);
                            }
                        }
                        let count = cells.len() as f32;
                        (sum / count, seen / count)
                    })
                    .collect()
            })
            .collect();
        let mut frame = PhotonFrame {
            image: Image {
                width,
                height,
                pixels: Vec::with_capacity(width as usize * height as usize),
            },
            photons: Vec::new(),
        };
        for (value, seen) in rows.into_iter().flatten() {
            frame.image.pixels.push(value);
            if photons {
                frame.photons.push(seen);
            }
        }
        frame
    }
}

/// The seed of the gathers' streams.
const GATHER_SEED: u64 = 0x7068_6f74_6f6e;
/// The seed of the gather rays' choices at specular surfaces.
const CHOICE_SEED: u64 = 0x6368_6f69_6365;
