//! The rendering equation solved by path tracing: J. T. Kajiya, "The rendering
//! equation", Computer Graphics (SIGGRAPH '86) 20(4):143–150, August 1986.
//!
//! Kajiya wrote the light passing between surfaces as one integral equation (the
//! light leaving a point is its emission plus the integral, over every other
//! surface point, of the light arriving from there times the reflectance, with a
//! geometry term and a visibility term) and showed that every earlier method
//! solves it with some transport left out. He solved it whole by Monte Carlo,
//! "path tracing": from the eye, one path a sample, never branching (against
//! distributed ray tracing's tree, whose later generations cost most and matter
//! least), and at every vertex:
//!
//! - the emission the path meets, counted on the eye ray and after a specular
//!   bounce only (mirror, refraction, pane), where no shadow ray could have found
//!   the light, so that no light is counted twice;
//! - the direct light: a shadow ray to a point chosen on the light (by area,
//!   converted to solid angle by cos θ_light / r²: `Light::sample`), times the
//!   BRDF and cos θ;
//! - one continuing ray by his importance choices: the kind of reflection
//!   (Lambert's, Phong's lobe, the mirror, refraction) drawn at random in
//!   proportion to its reflectance, then a direction in proportion to the BRDF
//!   times the cosine, the path's weight multiplied by f cos θ / pdf over the
//!   kind's probability.
//!
//! The pixel is stratified: n × n paths, one in each cell of the pixel's grid
//! (Kajiya's "hierarchical sampling" of the pixel).
//!
//! Left open by the paper, chosen here:
//! - How a path ends. The reflectances' probabilities leave 1 − Σ p for
//!   absorption, where the path ends: Russian roulette (Arvo & Kirk 1990), a later
//!   addition. Kajiya's figures stop at a fixed depth, which loses the light of
//!   longer paths; roulette keeps the estimate unbiased, which a ground truth needs.
//!   `global.depth` still caps the surfaces a path meets (1,000 when not set: a
//!   safeguard under reflectances near 1; 1 gives direct light alone).
//! - Every light is sampled at each vertex, one point each (not one light drawn).
//! - Only the pixel is stratified; the lights' points and the directions draw
//!   independent numbers.
//! - Glass (a material with an index of refraction): Fresnel's exact reflectance F
//!   draws reflection or refraction, tinted by `mirror` (white when 0) and
//!   `transmittance`. The radiance's change by (η₂/η₁)² across the surface is left
//!   out: it cancels on every path that leaves the glass it entered, the only ones
//!   that carry light (no light sits inside glass). Without an index, `mirror` and
//!   a pane's `transmittance` (straight through) are constant coefficients.
//! - A sphere light is seen on the eye ray and after a specular bounce (black
//!   where it does not emit), but blocks no shadow ray, as in the rest of lumiere.
//! - A ray that leaves the scene brings back the backdrop or the background colour,
//!   as Whitted's rays do.

use super::local::{background, reflectance_at};
use super::traced_scene::{Facing, Leaving, SurfaceHit, TracedScene};
use super::whitted::{reflected_direction, refracted_direction};
use crate::geometry::sampling::{Stream, cosine_weighted, phong_lobe};
use crate::image_io::Image;
use crate::raster::View;
use crate::scene::{Light, Material, Reach, Reflectance, Scene};
use crate::settings::GlobalSettings;
use crate::shading::light_model::{SurfacePoint, specular_brdf};
use crate::shading::optics::fresnel;
use crate::texture::environment::EnvironmentMap;
use glam::{DVec2, DVec3, Vec3};
use rayon::prelude::*;

/// A path tracer over one scene.
pub struct PathTracer<'a> {
    scene: &'a Scene,
    traced: &'a TracedScene,
    /// The most surfaces a path meets.
    depth: u32,
    /// n: n × n paths a pixel.
    samples: u32,
    seed: u64,
    backdrop: Option<&'a EnvironmentMap>,
}

/// What one path brought back.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PathSample {
    pub radiance: Vec3,
    /// The surfaces it met (0: it left the scene at once).
    pub vertices: u32,
}

/// A frame of paths: each pixel's mean, the variance of that mean, and the mean
/// number of surfaces its paths met.
pub struct PathFrame {
    pub image: Image,
    /// Per pixel and band: the sample variance of its paths over their number, the
    /// variance of the pixel's value (0 for one path, which cannot tell). The
    /// stratified pixel makes it an overestimate.
    pub variance: Vec<Vec3>,
    pub vertices: Vec<f32>,
}

/// How a path goes on from a vertex.
pub(crate) struct Bounce {
    pub direction: DVec3,
    /// f cos θ / pdf over the kind's probability.
    pub weight: Vec3,
    /// A mirror, refraction or a pane: the light the next ray meets is counted.
    pub specular: bool,
}

/// A surface's specular coefficients for a ray along `direction` meeting it from
/// outside (`front`) or inside: the mirror's and the transmitted ray's, with the
/// indices of the medium left and entered. Glass (an `ior`): Fresnel's F tinted
/// by `mirror` (white when 0) and 1 − F by `transmittance`; else the constants.
pub(crate) fn specular_coefficients(
    material: &Material,
    normal: DVec3,
    direction: DVec3,
    front: bool,
) -> (Vec3, Vec3, f64, f64) {
    let (eta1, eta2) = match material.ior {
        Some(ior) if front => (1.0, ior),
        Some(ior) => (ior, 1.0),
        None => (1.0, 1.0),
    };
    let (mirror, transmitted) = match material.ior {
        Some(_) => {
            let f = fresnel(normal.dot(-direction), eta1, eta2) as f32;
            let tint = if material.mirror == Vec3::ZERO {
                Vec3::ONE
            } else {
                material.mirror
            };
            (tint * f, material.transmittance * (1.0 - f))
        }
        None => (material.mirror, material.transmittance),
    };
    (mirror, transmitted, eta1, eta2)
}

impl<'a> PathTracer<'a> {
    pub fn new(
        scene: &'a Scene,
        traced: &'a TracedScene,
        settings: &GlobalSettings,
        backdrop: Option<&'a EnvironmentMap>,
    ) -> PathTracer<'a> {
        PathTracer {
            scene,
            traced,
            depth: settings.depth,
            samples: settings.samples,
            seed: scene.shadows.seed,
            backdrop,
        }
    }

    /// One path from `origin` along unit `direction`, its numbers from `stream`.
    pub fn path(&self, origin: DVec3, direction: DVec3, stream: &mut Stream) -> PathSample {
        let (mut origin, mut direction) = (origin, direction);
        let mut leaving = Leaving::Eye;
        let mut throughput = Vec3::ONE;
        let mut radiance = Vec3::ZERO;
        let mut counts_emission = true;
        let mut vertices = 0;
        loop {
            let hit = self
                .traced
                .closest(origin, direction, f64::INFINITY, leaving);
            if counts_emission {
                let nearest = hit.map_or(f64::INFINITY, |h| h.t);
                if let Some(seen) = self.sphere_light_seen(origin, direction, nearest) {
                    radiance += throughput * seen;
                    break;
                }
            }
            let Some(hit) = hit else {
                radiance += throughput * background(self.scene, self.backdrop, direction);
                break;
            };
            vertices += 1;
            let material = &self.scene.materials[hit.material];
            let facing = hit.facing(direction);
            let Facing {
                front,
                normal,
                geometric,
            } = facing;
            if front && counts_emission {
                radiance += throughput * material.emission;
            }
            let to_eye = -direction;
            let reflectance = reflectance_at(self.scene, &hit, to_eye);
            radiance +=
                throughput * self.direct(&hit, normal, geometric, to_eye, &reflectance, stream);
            if vertices >= self.depth {
                break;
            }
            let Some(bounce) = scatter(material, &reflectance, &facing, direction, stream) else {
                break;
            };
            throughput *= bounce.weight;
            if throughput == Vec3::ZERO {
                break;
            }
            counts_emission = bounce.specular;
            origin = hit.position;
            direction = bounce.direction;
            leaving = hit.leaving();
        }
        PathSample { radiance, vertices }
    }

    /// The direct light at a vertex: one shadow ray to a point on each light,
    /// times the BRDF (Lambert's and Phong's; the mirror and refraction find lights
    /// by the path itself) and cos θ. `normal` is the shading normal and
    /// `geometric` the surface's, both on the side the path comes from.
    fn direct(
        &self,
        hit: &SurfaceHit,
        normal: DVec3,
        geometric: DVec3,
        to_eye: DVec3,
        reflectance: &Reflectance,
        stream: &mut Stream,
    ) -> Vec3 {
        if reflectance.diffuse == Vec3::ZERO && reflectance.specular == Vec3::ZERO {
            return Vec3::ZERO;
        }
        let point = SurfacePoint {
            position: hit.position,
            normal,
            to_eye,
        };
        let mut total = Vec3::ZERO;
        for light in &self.scene.lights {
            let u = DVec2::new(stream.next_f64(), stream.next_f64());
            let Some(sample) = light.sample(hit.position, u) else {
                continue;
            };
            let d = sample.point - hit.position;
            let l = d / d.length();
            let cos = normal.dot(l);
            // Lit from the side the path is on, by the shading and the true surface.
            if !(cos > 0.0 && geometric.dot(l) > 0.0) {
                continue;
            }
            let emitter = light.emitter_polygon().map(|p| p as u32);
            if self
                .traced
                .blocked(hit.position, sample.point, hit.leaving(), emitter)
            {
                continue;
            }
            let f =
                reflectance.diffuse / std::f32::consts::PI + specular_brdf(&point, reflectance, l);
            total += f * emission(light) * (sample.weight * cos) as f32;
        }
        total
    }

    /// The radiance of the nearest sphere light the ray meets before `limit`, seen
    /// from outside (`None`: none is met).
    fn sphere_light_seen(&self, origin: DVec3, direction: DVec3, limit: f64) -> Option<Vec3> {
        let mut nearest: Option<(f64, Vec3)> = None;
        for light in &self.scene.lights {
            let Light::Sphere(sphere) = light else {
                continue;
            };
            let o = origin - sphere.centre;
            let c = o.length_squared() - sphere.radius * sphere.radius;
            // From inside (or on) the sphere: it emits outwards only.
            if c <= 0.0 {
                continue;
            }
            let half_b = o.dot(direction);
            let discriminant = half_b * half_b - c;
            if half_b >= 0.0 || discriminant < 0.0 {
                continue;
            }
            let t = -half_b - discriminant.sqrt();
            if t > 0.0 && t < limit && nearest.is_none_or(|(best, _)| t < best) {
                nearest = Some((t, sphere.radiance));
            }
        }
        nearest.map(|(_, radiance)| radiance)
    }

    /// The pixel (i, j) of `view`: the mean of its n × n paths, the variance of
    /// that mean, and the mean number of surfaces they met.
    pub fn pixel(&self, view: &View, i: u32, j: u32) -> (Vec3, Vec3, f32) {
        let index = j as u64 * view.width as u64 + i as u64;
        let mut stream = Stream::new(self.seed, index);
        let cells = stream.jittered(self.samples as usize);
        // Welford's running mean and sum of squared deviations, in double precision.
        let mut mean = DVec3::ZERO;
        let mut squares = DVec3::ZERO;
        let mut vertices = 0u64;
        for (k, cell) in cells.iter().enumerate() {
            let (origin, direction) = view.ray_through(i as f64 + cell.x, j as f64 + cell.y);
            let sample = self.path(origin, direction.normalize(), &mut stream);
            let x = sample.radiance.as_dvec3();
            let delta = x - mean;
            mean += delta / (k + 1) as f64;
            squares += delta * (x - mean);
            vertices += sample.vertices as u64;
        }
        let count = cells.len() as f64;
        let variance = if cells.len() > 1 {
            squares / ((count - 1.0) * count)
        } else {
            DVec3::ZERO
        };
        (
            mean.as_vec3(),
            variance.as_vec3(),
            (vertices as f64 / count) as f32,
        )
    }

    /// The frame, rows in parallel; the same on any number of threads (each
    /// pixel's numbers come from its own stream).
    pub fn render(&self, view: &View) -> PathFrame {
        let (width, height) = (view.width, view.height);
        let rows: Vec<Vec<(Vec3, Vec3, f32)>> = (0..height)
            .into_par_iter()
            .map(|j| (0..width).map(|i| self.pixel(view, i, j)).collect())
            .collect();
        let size = width as usize * height as usize;
        let mut frame = PathFrame {
            image: Image {
                width,
                height,
                pixels: Vec::with_capacity(size),
            },
            variance: Vec::with_capacity(size),
            vertices: Vec::with_capacity(size),
        };
        for (mean, variance, vertices) in rows.into_iter().flatten() {
            frame.image.pixels.push(mean);
            frame.variance.push(variance);
            frame.vertices.push(vertices);
        }
        frame
    }
}

/// What a light's sample weight multiplies: a point light's intensity, a distant
/// light's irradiance, an extended light's radiance (see `Light::sample`).
fn emission(light: &Light) -> Vec3 {
    match light.reach() {
        Reach::Point { intensity, .. } => intensity,
        Reach::Direction { irradiance, .. } => irradiance,
        Reach::Extended { radiance } => radiance,
    }
}

/// Kajiya's importance choice at a vertex: the kind of reflection drawn in
/// proportion to its reflectance (each kind's largest band), the rest of the unit
/// interval absorbing the path (`None`), then its direction. `direction` is the
/// incoming ray's, `facing` how it meets the surface.
pub(crate) fn scatter(
    material: &Material,
    reflectance: &Reflectance,
    facing: &Facing,
    direction: DVec3,
    stream: &mut Stream,
) -> Option<Bounce> {
    let &Facing {
        front,
        normal,
        geometric,
    } = facing;
    let (mirror, transmitted, eta1, eta2) =
        specular_coefficients(material, normal, direction, front);
    let kinds = [
        reflectance.diffuse,
        reflectance.specular,
        mirror,
        transmitted,
    ];
    let mut chances = kinds.map(|k| k.max_element().max(0.0) as f64);
    // Reflectances summing past 1 (a white surface with a mirror coat) share the
    // unit interval in proportion; nothing is absorbed then.
    let sum: f64 = chances.iter().sum();
    if sum > 1.0 {
        chances = chances.map(|c| c / sum);
    }
    let u = stream.next_f64();
    let mut below = 0.0;
    let kind = (0..4).find(|&k| {
        below += chances[k];
        chances[k] > 0.0 && u < below
    })?;
    let weight = kinds[kind] / chances[kind] as f32;
    let bounce = match kind {
        0 => {
            let d = cosine_weighted(normal, stream.next_f64(), stream.next_f64());
            Bounce {
                direction: d,
                // ρ/π cos θ over the pdf cos θ/π.
                weight,
                specular: false,
            }
        }
        1 => {
            let e = reflectance.exponent as f64;
            let r = reflected_direction(direction, normal);
            let d = phong_lobe(r, e, stream.next_f64(), stream.next_f64());
            let cos = normal.dot(d);
            if cos <= 0.0 {
                return None;
            }
            Bounce {
                direction: d,
                // k_s (e + 2)/(2π) cosᵉ α cos θ over the pdf (e + 1)/(2π) cosᵉ α.
                weight: weight * ((e + 2.0) / (e + 1.0) * cos) as f32,
                specular: false,
            }
        }
        2 => Bounce {
            direction: reflected_direction(direction, normal),
            weight,
            specular: true,
        },
        _ => {
            let d = match material.ior {
                Some(_) => refracted_direction(direction, normal, eta2 / eta1)?,
                None => direction,
            };
            return Some(Bounce {
                direction: d,
                weight,
                specular: true,
            });
        }
    };
    // A reflection that would leave through the surface (an interpolated normal
    // tilted past the true one) is absorbed.
    (geometric.dot(bounce.direction) > 0.0).then_some(bounce)
}
