//! Photon maps: H. W. Jensen, "Global illumination using photon maps", Rendering
//! Techniques '96 (Eurographics Workshop on Rendering), 21–30, 1996.
//!
//! Pass 1 of Jensen's two-pass method, which replaced the radiosity mesh by a
//! density estimate. Photons leave the lights, each light's share in proportion to
//! its power, and are followed through the scene:
//!
//! - at every surface with a diffuse part a photon is stored (its position, its
//!   direction of travel and its power) in the global map;
//! - then it goes on by Russian roulette: reflected diffusely, specularly or
//!   transmitted with the probability of that part's reflectance, absorbed with
//!   the rest; its power divided by the part's chance (Kajiya's importance choice,
//!   `path_tracing::scatter`), so it stays the same for a grey surface;
//! - the caustic map holds, from a second, separate shooting, only the photons that
//!   reached a diffuse surface after specular bounces alone (L S+ D paths), read
//!   directly in pass 2, where a final gather could not find them.
//!
//! Each map is a balanced kd-tree (`geometry::kd_tree`). The radiance estimate at x
//! takes the k photons nearest it, r the distance of the farthest, and reads
//! L ≈ Σ f ΔΦ_p / (π r²) over the disc of radius r (photons arriving from behind
//! the surface left out); for caustics Jensen's cone filter weights each photon by
//! w_p = 1 − d_p / (c r) and divides by 1 − 2/(3c), c ≥ 1, sharpening the edges the
//! disc blurs.
//!
//! Choices left open, made here: a photon's power is the light's over all the
//! photons emitted for its map (those that left the scene or were absorbed
//! before a diffuse surface count), so that shooting until the map holds N
//! photons is unbiased; a map is shot in rounds of photons, each photon's numbers
//! from its own stream, until it holds its count (the same photons on any number
//! of threads). Jensen aimed caustic photons at the specular objects with a
//! projection map; here they leave the lights as the global ones do and only
//! those of L S+ D paths are kept, which costs shooting time only (the caustic
//! shooting stops after 256 photons emitted per one asked). A scene without a
//! mirror, refraction or pane has no caustic map.

use super::local::reflectance_at;
use super::path_tracing::scatter;
use super::traced_scene::{Leaving, TracedScene};
use crate::geometry::bvh::Aabb;
use crate::geometry::kd_tree::{KdTree, Neighbour};
use crate::geometry::sampling::Stream;
use crate::scene::Scene;
use glam::{DVec3, Vec3};
use rayon::prelude::*;
use std::f64::consts::PI;

/// What a photon carries to where it is stored.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Photon {
    /// Unit direction of travel as it arrived.
    pub direction: DVec3,
    /// The unit normal of the surface it was stored on, on the side it arrived
    /// at (what Christensen's precomputed irradiance is estimated with).
    pub normal: DVec3,
    /// Its power, per band.
    pub power: Vec3,
}

/// Photons in a balanced kd-tree.
pub struct PhotonMap {
    tree: KdTree<Photon>,
    /// Photons emitted to fill it.
    pub emitted: u64,
}

/// Which photons a shooting keeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapKind {
    /// Every photon at every diffuse surface.
    Global,
    /// Photons at the first diffuse surface after specular bounces only.
    Caustic,
}

/// The most bounces a photon is followed: a safeguard, roulette ends it first.
const MAX_BOUNCES: u32 = 1000;
/// Photons emitted a round, a quarter of those asked (at least 1,024).
const ROUNDS: u64 = 4;
/// The caustic shooting gives up after this many photons emitted per one asked.
const CAUSTIC_PATIENCE: u64 = 256;

impl PhotonMap {
    /// The map of stored photons (their positions and what they carry), `emitted`
    /// having been shot to fill it.
    pub fn new(photons: Vec<(DVec3, Photon)>, emitted: u64) -> PhotonMap {
        PhotonMap {
            tree: KdTree::build(photons),
            emitted,
        }
    }

    /// The stored photons.
    pub fn photons(&self) -> &[(DVec3, Photon)] {
        self.tree.items()
    }

    pub fn len(&self) -> usize {
        self.tree.len()
    }

    pub fn is_empty(&self) -> bool {
        self.tree.is_empty()
    }

    /// Jensen's estimate of the irradiance at `x` on a surface of unit `normal`
    /// (on the side looked at): the power of the `k` nearest photons arriving on
    /// that side over the disc π r², r the distance of the farthest of the k.
    /// A Lambertian surface of reflectance ρ reflects ρ/π times it.
    pub fn irradiance(&self, x: DVec3, normal: DVec3, k: usize) -> Vec3 {
        self.estimate(x, normal, k, None)
    }

    /// The estimate with Jensen's cone filter of constant `cone` (≥ 1): each
    /// photon at distance d weighted by 1 − d / (cone r), the sum divided by
    /// 1 − 2 / (3 cone).
    pub fn irradiance_cone(&self, x: DVec3, normal: DVec3, k: usize, cone: f64) -> Vec3 {
        self.estimate(x, normal, k, Some(cone))
    }

    fn estimate(&self, x: DVec3, normal: DVec3, k: usize, cone: Option<f64>) -> Vec3 {
        if self.tree.is_empty() || k == 0 {
            return Vec3::ZERO;
        }
        let mut found: Vec<Neighbour> = Vec::with_capacity(k);
        self.tree.nearest(x, k, &mut found);
        let r2 = found.iter().map(|n| n.distance2).fold(0.0, f64::max);
        if r2 <= 0.0 {
            return Vec3::ZERO;
        }
        let r = r2.sqrt();
        let items = self.tree.items();
        let mut sum = Vec3::ZERO;
        for n in &found {
            let photon = &items[n.index].1;
            // Arriving on the side looked at: travelling against the normal.
            if photon.direction.dot(normal) >= 0.0 {
                continue;
            }
            let weight = match cone {
                Some(c) => 1.0 - n.distance2.sqrt() / (c * r),
                None => 1.0,
            };
            sum += photon.power * weight as f32;
        }
        let normalisation = match cone {
            Some(c) => 1.0 - 2.0 / (3.0 * c),
            None => 1.0,
        };
        sum / (normalisation * PI * r2) as f32
    }
}

/// Shoots photons from the scene's lights until `kind`'s map holds `count` of them
/// (stream `seed`), and makes the map.
pub fn shoot(
    scene: &Scene,
    traced: &TracedScene,
    kind: MapKind,
    count: u32,
    seed: u64,
) -> PhotonMap {
    let sphere = bounding_sphere(scene);
    let powers: Vec<f64> = scene
        .lights
        .iter()
        .map(|l| l.power(sphere.1).max_element().max(0.0) as f64)
        .collect();
    let total: f64 = powers.iter().sum();
    let has_specular = scene.materials.iter().any(|m| {
        m.mirror.max_element() > 0.0 || m.transmittance.max_element() > 0.0 || m.ior.is_some()
    });
    if count == 0 || total <= 0.0 || (kind == MapKind::Caustic && !has_specular) {
        return PhotonMap::new(Vec::new(), 0);
    }
    let round = (count as u64 / ROUNDS).max(1024);
    let limit = match kind {
        MapKind::Global => u64::MAX,
        MapKind::Caustic => count as u64 * CAUSTIC_PATIENCE,
    };
    let mut stored: Vec<(DVec3, Photon)> = Vec::new();
    let mut emitted = 0u64;
    while stored.len() < count as usize && emitted < limit {
        let batch: Vec<(DVec3, Photon)> = (emitted..emitted + round)
            .into_par_iter()
            .flat_map_iter(|i| {
                let mut stream = Stream::new(seed, i);
                trace_photon(scene, traced, kind, sphere, (&powers, total), &mut stream)
            })
            .collect();
        stored.extend(batch);
        emitted += round;
    }
    // Each photon carried its light's power over the chance of its light; over
    // all those emitted, the mean is the lights' power.
    let scale = 1.0 / emitted as f32;
    for (_, photon) in &mut stored {
        photon.power *= scale;
    }
    PhotonMap::new(stored, emitted)
}

/// The centre and radius of a sphere about the scene's polygons.
pub fn bounding_sphere(scene: &Scene) -> (DVec3, f64) {
    let bounds = Aabb::of(scene.polygons.iter().flat_map(|p| p.positions()));
    let centre = 0.5 * (bounds.min + bounds.max);
    (centre, 0.5 * (bounds.max - bounds.min).length())
}

/// One photon's path, the photons it leaves in `kind`'s map (their power not yet
/// divided by the number emitted).
fn trace_photon(
    scene: &Scene,
    traced: &TracedScene,
    kind: MapKind,
    (centre, radius): (DVec3, f64),
    (powers, total): (&[f64], f64),
    stream: &mut Stream,
) -> Vec<(DVec3, Photon)> {
    let mut kept = Vec::new();
    // The light, drawn in proportion to its power.
    let u = stream.next_f64() * total;
    let mut below = 0.0;
    let Some(l) = (0..powers.len()).find(|&l| {
        below += powers[l];
        powers[l] > 0.0 && u < below
    }) else {
        return kept;
    };
    let light = &scene.lights[l];
    let numbers = [
        stream.next_f64(),
        stream.next_f64(),
        stream.next_f64(),
        stream.next_f64(),
    ];
    let Some(emitted) = light.emit(centre, radius, numbers) else {
        return kept;
    };
    let mut power = emitted.weight * (total / powers[l]) as f32;
    let (mut origin, mut direction) = (emitted.origin, emitted.direction);
    let mut leaving = match light.emitter_polygon() {
        Some(p) => Leaving::Polygon(p as u32),
        None => Leaving::Eye,
    };
    let mut specular_only = true;
    for bounce in 0..MAX_BOUNCES {
        let Some(hit) = traced.closest(origin, direction, f64::INFINITY, leaving) else {
            break;
        };
        let material = &scene.materials[hit.material];
        let facing = hit.facing(direction);
        let reflectance = reflectance_at(scene, &hit, -direction);
        if reflectance.diffuse.max_element() > 0.0 {
            let photon = Photon {
                direction,
                normal: facing.normal,
                power,
            };
            match kind {
                MapKind::Global => kept.push((hit.position, photon)),
                MapKind::Caustic => {
                    if specular_only && bounce > 0 {
                        kept.push((hit.position, photon));
                    }
                    break;
                }
            }
        }
        let Some(next) = scatter(material, &reflectance, &facing, direction, stream) else {
            break;
        };
        specular_only &= next.specular;
        if kind == MapKind::Caustic && !specular_only {
            break;
        }
        power *= next.weight;
        if power == Vec3::ZERO {
            break;
        }
        origin = hit.position;
        direction = next.direction;
        leaving = hit.leaving();
    }
    kept
}
