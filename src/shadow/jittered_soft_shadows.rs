//! Soft shadows from a spherical light by one shadow ray per hexagonal cell, at the
//! cell's centre or jittered inside it: the course's construction of antialiased
//! soft shadows, on the principle of R. L. Cook, T. Porter, L. Carpenter,
//! "Distributed ray tracing", SIGGRAPH '84 (rays to points spread over the light)
//! and R. L. Cook, "Stochastic sampling in computer graphics", ACM Transactions on
//! Graphics 5(1):51–72, 1986 (jitter turns aliasing into noise).
//!
//! Seen from a shading point x, the sphere (centre C, radius r, at distance D) is a
//! disc: its outline circle, centred at C − r²/D along the direction to x with
//! radius r √(1 − r²/D²) (the exact silhouette, not the disc through C). The disc is
//! tiled by regular hexagons in K rings around a centre cell (1, 7, 19, 37, 61 …
//! = 1 + 3K(K + 1) cells), pointy-top, circumradius h = R/(1.5K + ½), for which
//! the rings cover the disc (the innermost notches of the outer ring lie (1.5K + ½)h
//! from the centre for odd K, and √((1.5K + ½)² + ¾) h for even K, so for even K a
//! few per cent larger cells would still cover it). One shadow ray goes to each cell:
//!
//! - regular: to the centre of every cell whose centre lies in the disc, all with
//!   equal weight; every pixel uses the same points, so the visible fraction takes at
//!   most N + 1 values and the penumbra shows as bands, copies of the occluder's
//!   outline;
//! - jittered: to a uniform point of the cell's part inside the disc, fresh per
//!   pixel (the pixel's stream of the seed), weighted by that part's exact area, so
//!   the estimate's mean is the visible share of the disc's area; the bands become
//!   noise, and full light and umbra stay exact, every ray agreeing there.
//!
//! The fraction of the weight whose ray reaches the disc scales the exact
//! unshadowed irradiance (the sphere's form factor), so the weights are each ray's
//! share of that irradiance, not of the disc's area: a cell's weight (its area, or
//! 1 on the regular grid) times cos θ at x (zero below x's horizon, on the side the
//! eye sees) times cos α / ρ², the solid angle a unit of the disc's area subtends
//! at its distance ρ. The course weighs the cells by area alone; that share is the
//! irradiance's only as r/D → 0 and counts the part of the disc below the horizon
//! as light the receiver gets, so a sphere near or across a receiver's plane came
//! out too dark or too bright (measured in tests/suite/shadow/soft_ray_casting.rs). A ray is blocked
//! by any polygon between x and its point (the receiver itself excepted); sphere
//! lights cast no shadow of their own. Scene keys: `[shadows] method = "jittered-soft-shadows"`,
//! `rings`, `sampling = "regular" | "jittered"`, `seed`.

use super::{BandShadows, FrameShadows, LightShadows, SceneOccluders};
use crate::geometry::disc::area_inside;
use crate::geometry::sampling::Stream;
use crate::raster::{View, VisibleSurface};
use crate::scene::{Light, LightKind};
use crate::scene::{Scene, SphereLight};
use crate::settings::CellSampling;
use crate::settings::ShadowMethod;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::sync::Arc;

/// The registry's entry: sphere lights.
pub(crate) static METHOD: super::Method = super::Method {
    method: ShadowMethod::JitteredSoftShadows,
    name: "jittered-soft-shadows",
    entry: Some("jittered-soft-shadows"),
    handles: "a soft-shadow method for sphere lights",
    lights: &[LightKind::Sphere],
    counts: None,
    budget: super::no_budget,
    warnings: super::no_warnings,
    prepare: |scene, index, settings, shared| {
        let Light::Sphere(sphere) = &scene.lights[index] else {
            unreachable!("checked")
        };
        Some(Arc::new(JitteredSoftShadows::new(
            shared.occluders(),
            sphere.clone(),
            index,
            settings.rings,
            settings.sampling,
            settings.seed,
        )))
    },
};

/// One hexagonal cell of the unit disc's tiling.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    pub centre: DVec2,
    /// The area of the cell inside the unit disc.
    pub area: f64,
}

/// The hexagonal cells of `rings` rings meeting the unit disc, and their
/// circumradius.
pub fn cells(rings: u32) -> (Vec<Cell>, f64) {
    let k = rings as i64;
    let h = 1.0 / (1.5 * rings as f64 + 0.5);
    let mut cells = Vec::new();
    for r in -k..=k {
        for q in -k..=k {
            if (q + r).abs() > k {
                continue;
            }
            let centre = DVec2::new(3f64.sqrt() * (q as f64 + 0.5 * r as f64), 1.5 * r as f64) * h;
            let area = area_inside(&hexagon(centre, h), DVec2::ZERO, 1.0);
            // A hexagon wholly outside the disc leaves a rounding residue of its area.
            if area > 1e-12 * h * h {
                cells.push(Cell { centre, area });
            }
        }
    }
    (cells, h)
}

/// A pointy-top regular hexagon, counter-clockwise.
pub fn hexagon(centre: DVec2, h: f64) -> [DVec2; 6] {
    std::array::from_fn(|i| {
        let angle = (30.0 + 60.0 * i as f64).to_radians();
        centre + DVec2::new(angle.cos(), angle.sin()) * h
    })
}

/// A uniform point of the hexagon at `centre` with circumradius `h`: one of its six
/// triangles about the centre, then a uniform point of it.
fn point_in_hexagon(corners: &[DVec2; 6], centre: DVec2, stream: &mut Stream) -> DVec2 {
    let i = ((stream.next_f64() * 6.0) as usize).min(5);
    let (a, b) = (corners[i], corners[(i + 1) % 6]);
    let (s, t) = (stream.next_f64().sqrt(), stream.next_f64());
    centre + (a - centre) * (s * (1.0 - t)) + (b - centre) * (s * t)
}

/// The pre-pass: the scene's hierarchy and the cells of the unit disc.
pub struct JitteredSoftShadows {
    occluders: Arc<SceneOccluders>,
    light: SphereLight,
    /// The light's index: with the seed, the streams' generator.
    index: usize,
    cells: Vec<Cell>,
    /// A cell's corners about its centre.
    corners: [DVec2; 6],
    sampling: CellSampling,
    seed: u64,
}

impl JitteredSoftShadows {
    pub fn new(
        occluders: Arc<SceneOccluders>,
        light: SphereLight,
        index: usize,
        rings: u32,
        sampling: CellSampling,
        seed: u64,
    ) -> JitteredSoftShadows {
        let (mut cells, h) = cells(rings);
        if sampling == CellSampling::Regular {
            cells.retain(|c| c.centre.length() <= 1.0);
        }
        JitteredSoftShadows {
            occluders,
            light,
            index,
            cells,
            corners: hexagon(DVec2::ZERO, h),
            sampling,
            seed,
        }
    }

    /// How many rays each sample casts.
    pub fn rays(&self) -> usize {
        self.cells.len()
    }

    /// The visible share of the light's irradiance at `x` on polygon `polygon` with
    /// unit normal `normal` (on the eye's side), its cells sampled from `stream`.
    pub fn fraction(&self, x: DVec3, normal: DVec3, polygon: u32, stream: &mut Stream) -> f64 {
        let to_x = x - self.light.centre;
        let distance = to_x.length();
        let r = self.light.radius;
        if distance <= r {
            return 0.0;
        }
        let d = to_x / distance;
        let centre = self.light.centre + d * (r * r / distance);
        let radius = r * (1.0 - (r / distance).powi(2)).sqrt();
        let (t1, t2) = d.any_orthonormal_pair();
        let (mut seen, mut total) = (0.0, 0.0);
        for cell in &self.cells {
            let (at, weight) = match self.sampling {
                CellSampling::Regular => (cell.centre, 1.0),
                CellSampling::Jittered => (self.jittered_point(cell, stream), cell.area),
            };
            let target = centre + (t1 * at.x + t2 * at.y) * radius;
            let ray = target - x;
            let rho2 = ray.length_squared();
            let cos_x = normal.dot(ray);
            if cos_x <= 0.0 {
                continue; // below the horizon: no irradiance to share
            }
            // cos θ cos α / ρ², with cos θ = n·ray/ρ and cos α = −d·ray/ρ.
            let weight = weight * cos_x * -d.dot(ray) / (rho2 * rho2);
            total += weight;
            if !self.occluders.any_hit(x, target, &[polygon]) {
                seen += weight;
            }
        }
        if total > 0.0 { seen / total } else { 0.0 }
    }

    /// A uniform point of the cell's part inside the unit disc: a uniform point of
    /// the hexagon, drawn again while it falls outside the disc (a rim cell keeps at
    /// least a sliver inside; after many misses, the cell's centre pulled onto the
    /// disc).
    fn jittered_point(&self, cell: &Cell, stream: &mut Stream) -> DVec2 {
        let corners = self.corners.map(|c| cell.centre + c);
        for _ in 0..256 {
            let p = point_in_hexagon(&corners, cell.centre, stream);
            if p.length_squared() <= 1.0 {
                return p;
            }
        }
        cell.centre.clamp_length_max(1.0)
    }
}

impl LightShadows for JitteredSoftShadows {
    fn frame<'a>(&'a self, scene: &'a Scene, view: &'a View) -> Box<dyn FrameShadows + 'a> {
        Box::new(JitteredFrame {
            method: self,
            scene,
            eye: view.eye,
        })
    }
}

struct JitteredFrame<'a> {
    method: &'a JitteredSoftShadows,
    scene: &'a Scene,
    eye: DVec3,
}

impl FrameShadows for JitteredFrame<'_> {
    fn band(&self, band: &VisibleSurface) -> BandShadows {
        let m = self.method;
        let fractions = (0..band.samples.len())
            .into_par_iter()
            .map(|k| {
                let s = &band.samples[k];
                if s.is_empty() {
                    return 0.0;
                }
                let (x, y) = band.position_of(k);
                let pixel = y as u64 * band.width as u64 + x as u64;
                let mut stream = Stream::new(m.seed ^ (m.index as u64).rotate_left(32), pixel);
                // The geometric normal on the eye's side: the horizon the light model
                // clips the sphere's cap to.
                let n = self.scene.polygons[s.polygon as usize].normal;
                let n = if n.dot(self.eye - s.position) < 0.0 {
                    -n
                } else {
                    n
                };
                m.fraction(s.position, n, s.polygon, &mut stream) as f32
            })
            .collect();
        BandShadows::fraction(fractions)
    }
}
