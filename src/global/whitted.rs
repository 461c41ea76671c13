//! Recursive ray tracing: T. Whitted, "An improved illumination model for shaded
//! display", Communications of the ACM 23(6):343–349, June 1980.
//!
//! For each pixel a tree of rays: the eye ray finds the visible surface; there a
//! shadow ray goes to each light, and a reflected and a refracted ray are spawned
//! and recurse. The intensity is Whitted's
//!
//!   I = I_a + k_d Σ_j (N·L_j) + k_s S + k_t T,
//!
//! written in this project's units: the ambient radiance I_a times ρ_d, each
//! light's reflected radiance (Lambert and the normalised Phong highlight of the
//! light model, which stands in for the highlights a reflected ray cannot find on
//! a point light) where its shadow ray is clear, and the radiance S and T the
//! reflected and refracted rays bring back, weighted by k_s (`mirror`) and k_t
//! (`transmittance`).
//!
//! Directions in Whitted's own form (V the incident direction, N the unit normal on
//! the side the ray comes from): V′ = V/|V·N|, R = V′ + 2N, and
//! P = k_f (N + V′) − N with k_f = (k_n² |V′|² − |V′ + N|²)^(−1/2), k_n the index of
//! the medium entered over that of the medium left; a non-positive radicand is
//! total internal reflection and spawns no transmitted ray. A material without an
//! index of refraction is a thin pane: its transmitted ray goes straight on.
//!
//! A ray is not spawned beyond the depth limit, or when the product of the
//! coefficients along its path falls below the threshold. A ray that leaves the
//! scene returns the backdrop (an environment) or the background colour.
//!
//! Antialiasing, Whitted's: rays go through the pixels' corners; where the four
//! corners of a square differ by more than the contrast, the square is split into
//! four and the new corners traced, down to a limit; each square's intensity is the
//! mean of its corners, and the pixel the area-weighted mean of its squares.
//! Whitted guards small objects the corners might straddle with bounding spheres:
//! a square is also split while the bounding sphere of an object that none of its
//! corners' rays met projects onto it and is smaller than it. (Here the sphere
//! about the object's vertices, projected as a disc of radius f r / z around its
//! centre's projection; the paper leaves both open.)
//!
//! Choices left open by the paper, made here: k_s and k_t are constants, as in
//! Whitted's images, or (`weights = "fresnel"`) scaled by Fresnel's exact
//! reflectance F and 1 − F; shadow rays are blocked by transparent objects as by
//! opaque ones (no light through glass: the method has no caustics); a ray inside an
//! object leaves it into vacuum (no nested media); under an extended light the
//! shadow ray becomes N × N stratified rays over the emitter (`shadows.light_samples`).

use super::local::{background, lights_at, reflectance_at};
use super::traced_scene::{Leaving, SurfaceHit, TracedScene};
use crate::image_io::Image;
use crate::raster::View;
use crate::scene::Scene;
use crate::settings::{GlobalSettings, SpecularWeights};
use crate::shading::optics::fresnel;
use crate::texture::environment::EnvironmentMap;
use glam::{DVec3, Vec3};
use rayon::prelude::*;

/// Whitted's reflected direction of the incident direction `v` about the unit
/// normal `n` on the incident side: V′ = V/|V·N|, R = V′ + 2N, normalised.
pub fn reflected_direction(v: DVec3, n: DVec3) -> DVec3 {
    let v1 = v / v.dot(n).abs();
    (v1 + 2.0 * n).normalize()
}

/// Whitted's refracted direction of `v` through the unit normal `n` on the incident
/// side, for k_n = η₂/η₁: P = k_f (N + V′) − N with
/// k_f = (k_n² |V′|² − |V′ + N|²)^(−1/2), normalised; `None` for total internal
/// reflection (a non-positive radicand).
pub fn refracted_direction(v: DVec3, n: DVec3, k_n: f64) -> Option<DVec3> {
    let v1 = v / v.dot(n).abs();
    let radicand = k_n * k_n * v1.length_squared() - (v1 + n).length_squared();
    // Not positive (or not a number, for a ray exactly in the surface): no
    // transmitted ray.
    if radicand.is_nan() || radicand <= 0.0 {
        return None;
    }
    let k_f = 1.0 / radicand.sqrt();
    Some((k_f * (n + v1) - n).normalize())
}

/// A ray tracer over one scene.
pub struct Whitted<'a> {
    scene: &'a Scene,
    traced: &'a TracedScene,
    settings: &'a GlobalSettings,
    backdrop: Option<&'a EnvironmentMap>,
    lit: Vec<bool>,
}

/// What one ray (and the tree under it) brought back.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Traced {
    pub radiance: Vec3,
    /// Rays traced: this one and its reflected and refracted descendants.
    pub rays: u32,
    /// The object this ray met first (`None`: it left the scene).
    pub object: Option<u32>,
}

/// An object's bounding sphere seen from the eye: its centre on the screen and its
/// radius there, in samples.
#[derive(Clone, Copy, Debug)]
struct Footprint {
    object: u32,
    centre: (f64, f64),
    radius: f64,
}

impl<'a> Whitted<'a> {
    pub fn new(
        scene: &'a Scene,
        traced: &'a TracedScene,
        settings: &'a GlobalSettings,
        backdrop: Option<&'a EnvironmentMap>,
    ) -> Whitted<'a> {
        Whitted {
            scene,
            traced,
            settings,
            backdrop,
            lit: vec![true; scene.lights.len()],
        }
    }

    /// The radiance the ray from `origin` along unit `direction` brings back.
    /// `stream` seeds the extended lights' shadow samples.
    pub fn trace(&self, origin: DVec3, direction: DVec3, stream: u64) -> Traced {
        self.ray(origin, direction, Leaving::Eye, 0, Vec3::ONE, stream)
    }

    fn ray(
        &self,
        origin: DVec3,
        direction: DVec3,
        leaving: Leaving,
        depth: u32,
        weight: Vec3,
        stream: u64,
    ) -> Traced {
        match self
            .traced
            .closest(origin, direction, f64::INFINITY, leaving)
        {
            Some(hit) => self.shade(&hit, direction, depth, weight, stream),
            None => Traced {
                radiance: background(self.scene, self.backdrop, direction),
                rays: 1,
                object: None,
            },
        }
    }

    /// I = I_a ρ_d + Σ lights (clear shadow rays) + k_s S + k_t T at a hit.
    fn shade(
        &self,
        hit: &SurfaceHit,
        direction: DVec3,
        depth: u32,
        weight: Vec3,
        stream: u64,
    ) -> Traced {
        let material = &self.scene.materials[hit.material];
        // Normals on the side the ray comes from (the geometric one where an
        // interpolated normal faces away, which would break Whitted's V' = V/|V·N|).
        let facing = hit.facing(direction);
        let (front, n) = (facing.front, facing.normal);
        let to_eye = -direction;
        let reflectance = reflectance_at(self.scene, hit, to_eye);
        let mut radiance = self.settings.ambient * reflectance.diffuse;
        if front {
            radiance += material.emission;
        }
        radiance += lights_at(
            self.scene,
            self.traced,
            hit.position,
            n,
            to_eye,
            &reflectance,
            hit.leaving(),
            &self.lit,
            stream,
        );
        let mut rays = 1;
        if depth >= self.settings.depth {
            return Traced {
                radiance,
                rays,
                object: Some(hit.object as u32),
            };
        }
        // Indices of the medium left and the medium entered.
        let (eta1, eta2) = match material.ior {
            Some(ior) if front => (1.0, ior),
            Some(ior) => (ior, 1.0),
            None => (1.0, 1.0),
        };
        let (mut k_s, mut k_t) = (material.mirror, material.transmittance);
        if self.settings.weights == SpecularWeights::Fresnel && material.ior.is_some() {
            let f = fresnel(n.dot(to_eye), eta1, eta2) as f32;
            let tint = if k_s == Vec3::ZERO { Vec3::ONE } else { k_s };
            (k_s, k_t) = (tint * f, k_t * (1.0 - f));
        }
        let threshold = self.settings.threshold as f32;
        let spawn = |k: Vec3| k.max_element() > 0.0 && (weight * k).max_element() >= threshold;
        if spawn(k_s) {
            let r = reflected_direction(direction, n);
            let s = self.ray(
                hit.position,
                r,
                hit.leaving(),
                depth + 1,
                weight * k_s,
                stream,
            );
            radiance += k_s * s.radiance;
            rays += s.rays;
        }
        if spawn(k_t) {
            let refracted = match material.ior {
                Some(_) => refracted_direction(direction, n, eta2 / eta1),
                None => Some(direction),
            };
            if let Some(p) = refracted {
                let t = self.ray(
                    hit.position,
                    p,
                    hit.leaving(),
                    depth + 1,
                    weight * k_t,
                    stream,
                );
                radiance += k_t * t.radiance;
                rays += t.rays;
            }
        }
        Traced {
            radiance,
            rays,
            object: Some(hit.object as u32),
        }
    }

    /// The eye ray through screen point (x, y) of `view`.
    pub fn through(&self, view: &View, x: f64, y: f64, stream: u64) -> Traced {
        let (origin, direction) = view.ray_through(x, y);
        self.trace(origin, direction.normalize(), stream)
    }

    /// The image, and the rays cast per pixel, by Whitted's adaptive subdivision of
    /// pixels from their corners.
    pub fn render(&self, view: &View) -> (Image, Vec<u32>) {
        let (width, height) = (view.width, view.height);
        let stride = width as u64 + 1;
        // The corners, each traced once and shared by the pixels around it.
        let corners: Vec<Vec<Traced>> = (0..=height)
            .into_par_iter()
            .map(|j| {
                (0..=width)
                    .map(|i| self.through(view, i as f64, j as f64, j as u64 * stride + i as u64))
                    .collect()
            })
            .collect();
        let exposure = self.scene.render.exposure;
        let footprints = self.footprints(view);
        let rows: Vec<Vec<(Vec3, u32)>> = (0..height)
            .into_par_iter()
            .map(|j| {
                (0..width)
                    .map(|i| {
                        let (i, j) = (i as usize, j as usize);
                        let c = [
                            corners[j][i],
                            corners[j][i + 1],
                            corners[j + 1][i],
                            corners[j + 1][i + 1],
                        ];
                        let square = Square {
                            x: i as f64,
                            y: j as f64,
                            size: 1.0,
                        };
                        let stream = (height as u64 + 1) * stride
                            + (j as u64 * width as u64 + i as u64) * 4096;
                        let guard = Guard {
                            footprints: &footprints,
                            exposure,
                        };
                        self.subdivide(view, square, c, 0, &guard, stream)
                    })
                    .collect()
            })
            .collect();
        let mut pixels = Vec::with_capacity(width as usize * height as usize);
        let mut rays = Vec::with_capacity(pixels.capacity());
        for row in rows {
            for (radiance, count) in row {
                pixels.push(radiance);
                rays.push(count);
            }
        }
        (
            Image {
                width,
                height,
                pixels,
            },
            rays,
        )
    }

    /// The mean intensity over a square from its corners (top-left, top-right,
    /// bottom-left, bottom-right), split into four while they differ; with the rays
    /// cast inside it (its corners' shared with neighbours counted in full once, at
    /// the top level, as the corners grid's share: one per pixel).
    fn subdivide(
        &self,
        view: &View,
        square: Square,
        c: [Traced; 4],
        level: u32,
        guard: &Guard,
        stream: u64,
    ) -> (Vec3, u32) {
        let mean = (c[0].radiance + c[1].radiance + c[2].radiance + c[3].radiance) / 4.0;
        let own = if level == 0 { c[0].rays } else { 0 };
        if level >= self.settings.subdivisions
            || !(self.differ(&c, guard.exposure) || missed_small_object(&square, &c, guard))
        {
            return (mean, own);
        }
        let h = square.size / 2.0;
        let (x, y) = (square.x, square.y);
        let at = |dx: f64, dy: f64, k: u64| self.through(view, x + dx, y + dy, stream + k);
        let base = 5 * (level as u64 + 1);
        let top = at(h, 0.0, base);
        let left = at(0.0, h, base + 1);
        let centre = at(h, h, base + 2);
        let right = at(2.0 * h, h, base + 3);
        let bottom = at(h, 2.0 * h, base + 4);
        let mut rays = own + top.rays + left.rays + centre.rays + right.rays + bottom.rays;
        let quarters = [
            (Square { x, y, size: h }, [c[0], top, left, centre]),
            (
                Square {
                    x: x + h,
                    y,
                    size: h,
                },
                [top, c[1], centre, right],
            ),
            (
                Square {
                    x,
                    y: y + h,
                    size: h,
                },
                [left, centre, c[2], bottom],
            ),
            (
                Square {
                    x: x + h,
                    y: y + h,
                    size: h,
                },
                [centre, right, bottom, c[3]],
            ),
        ];
        let mut total = Vec3::ZERO;
        for (q, (square, corners)) in quarters.into_iter().enumerate() {
            let (value, count) = self.subdivide(
                view,
                square,
                corners,
                level + 1,
                guard,
                stream.wrapping_mul(4).wrapping_add(q as u64),
            );
            total += value;
            rays += count;
        }
        (total / 4.0, rays)
    }

    /// The bounding sphere of every object wholly in front of the eye, projected.
    fn footprints(&self, view: &View) -> Vec<Footprint> {
        let mut points: Vec<Vec<DVec3>> = vec![Vec::new(); self.scene.objects.len()];
        for p in &self.scene.polygons {
            points[p.object].extend(p.positions());
        }
        points
            .iter()
            .enumerate()
            .filter(|(_, v)| !v.is_empty())
            .filter_map(|(object, v)| {
                let centre = v.iter().copied().sum::<DVec3>() / v.len() as f64;
                let radius = v.iter().map(|p| p.distance(centre)).fold(0.0, f64::max);
                let eye = view.to_eye(centre);
                (eye.z - radius > view.near).then(|| Footprint {
                    object: object as u32,
                    centre: view.project(eye),
                    radius: view.focal * radius / eye.z,
                })
            })
            .collect()
    }

    /// Whether a square's corners differ by more than the contrast in a displayed
    /// channel (exposure applied, clamped to [0, 1]).
    fn differ(&self, c: &[Traced; 4], exposure: f32) -> bool {
        let shown = |t: &Traced| (t.radiance * exposure).clamp(Vec3::ZERO, Vec3::ONE);
        let values = c.map(|t| shown(&t));
        let (low, high) = values
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(l, h), v| {
                (l.min(*v), h.max(*v))
            });
        (high - low).max_element() as f64 > self.settings.contrast
    }
}

/// What decides a split besides the corners' contrast.
struct Guard<'a> {
    footprints: &'a [Footprint],
    exposure: f32,
}

/// Whether an object smaller than `square` on the screen, whose bounding sphere's
/// disc overlaps it, was met by none of its corners' rays.
fn missed_small_object(square: &Square, c: &[Traced; 4], guard: &Guard) -> bool {
    guard.footprints.iter().any(|f| {
        let (x, y) = f.centre;
        2.0 * f.radius < square.size
            && x + f.radius > square.x
            && x - f.radius < square.x + square.size
            && y + f.radius > square.y
            && y - f.radius < square.y + square.size
            && c.iter().all(|t| t.object != Some(f.object))
    })
}

#[derive(Clone, Copy, Debug)]
struct Square {
    x: f64,
    y: f64,
    size: f64,
}
