//! The view-dependent second pass of J. R. Wallace, M. F. Cohen, D. P. Greenberg,
//! "A two-pass solution to the rendering equation: a synthesis of ray tracing and
//! radiosity methods", SIGGRAPH '87, and the view pass of H. E. Rushmeier,
//! K. E. Torrance, "Extending the radiosity method to include specularly reflecting
//! and translucent materials", ACM TOG 9(1), 1990.
//!
//! The first pass (`radiosity::extended`) has put every path that ends on a diffuse
//! surface into the radiosity solution, the light mirrors throw onto walls included
//! (specular-diffuse). What is left depends on the eye: per visible sample, the
//! diffuse part is the solution's, interpolated (diffuse-diffuse); where the surface
//! is specular, a reflected ray (and, through a pane, a transmitted one) is followed
//! to the surface it meets and that surface's pass-1 radiance B/π read there
//! (diffuse-specular); a specular surface met that way sends the ray on
//! (specular-specular), to the depth limit:
//!
//!   I_pixel = I_d + ρ_s I(reflected) + τ_s I(transmitted).
//!
//! No double counting: pass 1 already holds the mirrored light on diffuse surfaces,
//! so pass 2 adds no mirror-reflected light-source illumination to them; lights the
//! solution does not hold (point, spot, distant, sphere) are added where rays land,
//! with shadow rays, as the shading pass adds them at visible samples.
//!
//! A glossy mirror (a material's `gloss`, the exponent n of its lobe cosⁿ about the
//! mirror direction) is seen through the paper's reflection frustum
//! (`reflection_frustum`): a ray through each of its cells, weighted by the lobe.
//! Pass 1 takes it for an ideal mirror (the virtual environment is the lobe's
//! centre), as the paper's first pass follows ideal mirrors only.
//!
//! Choices left open: the frustum is opened at the first reflection from the eye;
//! a glossy surface met by one of its rays reflects along its mirror direction
//! alone (frusta within frusta multiply the rays by N² at each level); panes are
//! thin (the transmitted ray goes straight on); where a ray lands the solution is read as `SolutionRadiance` reads
//! it, its reflected part scaled by the diffuse texture there, as the scan-line
//! pass scales it at samples.

use super::local::{diffuse_texture_scale, lights_at, reflectance_at};
use super::reflection_frustum::ReflectionFrustum;
use super::solution_radiance::SolutionRadiance;
use super::traced_scene::{Leaving, TracedScene};
use crate::geometry::sampling::Stream;
use crate::radiosity::Solution;
use crate::scene::Scene;
use crate::settings::GlobalSettings;
use glam::{DVec3, Vec3};
use std::f64::consts::TAU;
use std::sync::Arc;

/// The second pass over one solution.
pub struct SecondPass {
    traced: Arc<TracedScene>,
    radiance: SolutionRadiance,
    settings: GlobalSettings,
    /// The lights the solution does not hold, added where rays land.
    lit: Vec<bool>,
    /// Per material, the reflection frustum of a glossy mirror.
    frusta: Vec<Option<ReflectionFrustum>>,
}

/// The seed of the streams that turn each sample's reflection frustum.
const FRUSTUM_SEED: u64 = 0x0066_7275_7374_756d;

impl SecondPass {
    pub fn new(
        scene: &Scene,
        solution: &Solution,
        traced: Arc<TracedScene>,
        settings: GlobalSettings,
        lit: Vec<bool>,
    ) -> SecondPass {
        SecondPass {
            traced,
            radiance: SolutionRadiance::new(
                scene,
                &solution.mesh,
                &solution.elements,
                solution.display,
            ),
            frusta: scene
                .materials
                .iter()
                .map(|m| {
                    m.gloss
                        .map(|n| ReflectionFrustum::new(n, settings.frustum_resolution))
                })
                .collect(),
            settings,
            lit,
        }
    }

    /// ρ_s I(reflected) + τ_s I(transmitted) at a visible point of polygon
    /// `polygon` seen along unit `incident` (eye to point), `normal` the shading
    /// normal on the eye's side. Zero where the diffuse-specular mechanism is off.
    pub fn specular(
        &self,
        scene: &Scene,
        polygon: u32,
        position: DVec3,
        normal: DVec3,
        incident: DVec3,
        stream: u64,
    ) -> Vec3 {
        if !self.settings.mechanisms.diffuse_specular {
            return Vec3::ZERO;
        }
        self.bounce(
            scene,
            polygon,
            position,
            normal,
            incident,
            1,
            Vec3::ONE,
            stream,
        )
    }

    #[allow(clippy::too_many_arguments)]
    fn bounce(
        &self,
        scene: &Scene,
        polygon: u32,
        position: DVec3,
        normal: DVec3,
        incident: DVec3,
        depth: u32,
        weight: Vec3,
        stream: u64,
    ) -> Vec3 {
        let index = scene.polygons[polygon as usize].material;
        let material = &scene.materials[index];
        let threshold = self.settings.threshold as f32;
        let spawn = |k: Vec3| {
            k.max_element() > 0.0
                && (weight * k).max_element() >= threshold
                && depth <= self.settings.depth
        };
        let mut radiance = Vec3::ZERO;
        let (k_s, k_t) = (material.mirror, material.transmittance);
        if spawn(k_s) {
            let r = (incident - 2.0 * incident.dot(normal) * normal).normalize();
            let ray = |d: DVec3| self.ray(scene, position, d, polygon, depth, weight * k_s, stream);
            radiance += k_s
                * match &self.frusta[index] {
                    Some(frustum) if depth == 1 => {
                        let turn = Stream::new(FRUSTUM_SEED, stream).next_f64() * TAU;
                        frustum
                            .rays(r, turn)
                            // Below the horizon: nothing (the weight stays counted).
                            .filter(|(d, _)| d.dot(normal) > 0.0)
                            .map(|(d, w)| ray(d) * w as f32)
                            .sum()
                    }
                    _ => ray(r),
                };
        }
        if spawn(k_t) {
            radiance += k_t
                * self.ray(
                    scene,
                    position,
                    incident,
                    polygon,
                    depth,
                    weight * k_t,
                    stream,
                );
        }
        radiance
    }

    /// What a ray from a specular surface brings back: the pass-1 radiance where it
    /// lands, the lights the solution does not hold, and (specular-specular) what
    /// a specular surface there sends on.
    #[allow(clippy::too_many_arguments)]
    fn ray(
        &self,
        scene: &Scene,
        origin: DVec3,
        direction: DVec3,
        from: u32,
        depth: u32,
        weight: Vec3,
        stream: u64,
    ) -> Vec3 {
        let Some(hit) =
            self.traced
                .closest(origin, direction, f64::INFINITY, Leaving::Polygon(from))
        else {
            return scene.render.background;
        };
        let Some(polygon) = hit.polygon else {
            return Vec3::ZERO;
        };
        // Radiosity leaves the front only; but a thin pane transmits both ways, as
        // pass 1 has it: seen from behind, it passes on what lies beyond it.
        if direction.dot(hit.geometric_normal) >= 0.0 {
            let k_t = scene.materials[hit.material].transmittance;
            let threshold = self.settings.threshold as f32;
            if self.settings.mechanisms.specular_specular
                && k_t.max_element() > 0.0
                && (weight * k_t).max_element() >= threshold
                && depth < self.settings.depth
            {
                return k_t
                    * self.ray(
                        scene,
                        hit.position,
                        direction,
                        polygon,
                        depth + 1,
                        weight * k_t,
                        stream,
                    );
            }
            return Vec3::ZERO;
        }
        let to_eye = -direction;
        let mut radiance = self.radiance.at(polygon, hit.position);
        if let Some(scale) = diffuse_texture_scale(scene, &hit, to_eye) {
            let emitted = scene.materials[hit.material].emission;
            radiance = emitted + (radiance - emitted) * scale;
        }
        if self.lit.iter().any(|&l| l) {
            let reflectance = reflectance_at(scene, &hit, to_eye);
            radiance += lights_at(
                scene,
                &self.traced,
                hit.position,
                hit.normal,
                to_eye,
                &reflectance,
                hit.leaving(),
                &self.lit,
                stream,
            );
        }
        if self.settings.mechanisms.specular_specular {
            radiance += self.bounce(
                scene,
                polygon,
                hit.position,
                hit.normal,
                direction,
                depth + 1,
                weight,
                stream,
            );
        }
        radiance
    }
}
