//! Point, spot, distant and sphere lights shot into the solution.
//!
//! A radiosity solution knows emitting polygons; lights without an area for a
//! hemi-cube to stand on (a point, a spot, the sun, a sphere) shoot once, before the
//! patches do, by rays: each element receives the irradiance H_e the light gives at
//! its centre, seen by shadow rays, as the ray-traced progressive radiosity of
//! J. R. Wallace, K. A. Elmquist, E. A. Haines, "A ray tracing algorithm for
//! progressive radiosity", SIGGRAPH '89, delivers a source's light to receiving
//! points. ρ_e H_e is then the element's own radiosity before any interreflection:
//! gathering takes it as a source term beside E, shooting as unshot radiosity, and
//! both count it in the solution's direct part.
//!
//! - point and spot: H = I(θ) cos θ / r², one shadow ray;
//! - distant: H = E cos θ, one shadow ray towards it;
//! - sphere: N × N jittered rays over the cone it subtends (`shadows.light_samples`),
//!   each weighted by its share of the unoccluded irradiance (`Light::sample`).
//!
//! Choices left open: the element's centre stands for the element (as the
//! hemi-cube at a patch centre stands for the patch); light a mirror sends on, or
//! a pane lets through, from these lights is not followed (the virtual-environment
//! windows of the two-pass first pass are built for polygons).

use super::mesh::Mesh;
use crate::geometry::sampling::Stream;
use crate::scene::ray_queries::SceneRays;
use crate::scene::{Light, Scene};
use glam::{DVec2, DVec3, Vec3};
use rayon::prelude::*;

/// The seed of the sphere lights' sample streams (one stream per element).
const SEED: u64 = 0x0073_6869_6e65;

/// Whether `scene` has a light the solution takes by `shine` (every kind but the
/// polygon, whose emitting polygon is meshed as a patch).
pub fn any(scene: &Scene) -> bool {
    scene.lights.iter().any(|l| !matches!(l, Light::Polygon(_)))
}

/// Sets every element's `received` to ρ_e H_e from the scene's point, spot,
/// distant and sphere lights.
pub fn shine(scene: &Scene, mesh: &mut Mesh) {
    if !any(scene) {
        return;
    }
    let rays = SceneRays::new(&scene.polygons);
    let side = scene.shadows.light_samples as usize;
    let received: Vec<Vec3> = mesh
        .elements
        .par_iter()
        .enumerate()
        .map(|(e, element)| {
            let patch = &mesh.patches[element.patch];
            let point = Receiver {
                position: element.centre,
                normal: patch.normal,
                polygon: patch.polygon as u32,
            };
            let mut stream = Stream::new(SEED, e as u64);
            let irradiance: Vec3 = scene
                .lights
                .iter()
                .map(|light| point.irradiance(&rays, light, side, &mut stream))
                .sum();
            patch.reflectance * irradiance
        })
        .collect();
    for (element, r) in mesh.elements.iter_mut().zip(received) {
        element.received = r;
    }
}

/// An element's centre, its front normal, and its polygon (which its shadow rays
/// leave).
struct Receiver {
    position: DVec3,
    normal: DVec3,
    polygon: u32,
}

impl Receiver {
    /// The irradiance `light` gives the receiver's front, through what the
    /// polygons let pass (zero for a polygon light: the mesh holds it).
    fn irradiance(
        &self,
        rays: &SceneRays,
        light: &Light,
        side: usize,
        stream: &mut Stream,
    ) -> Vec3 {
        let (emission, points) = match light {
            Light::Polygon(_) => return Vec3::ZERO,
            Light::Point(l) => (l.intensity, vec![DVec2::ZERO]),
            Light::Spot(l) => (l.intensity, vec![DVec2::ZERO]),
            Light::Distant(l) => (l.irradiance, vec![DVec2::ZERO]),
            Light::Sphere(l) => (l.radiance, stream.jittered(side)),
        };
        let count = points.len() as f64;
        let mut sum = 0.0;
        for u in points {
            let Some(sample) = light.sample(self.position, u) else {
                continue;
            };
            let d = sample.point - self.position;
            let cos = self.normal.dot(d) / d.length();
            if cos.is_nan()
                || cos <= 0.0
                || rays.any_hit(self.position, sample.point, &[self.polygon])
            {
                continue;
            }
            sum += sample.weight * cos;
        }
        emission * (sum / count) as f32
    }
}
