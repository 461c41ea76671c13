//! The final gather: the view pass over a view-independent radiosity solution, as
//! in K. Reichert, "A two-pass radiosity method driven by lights and viewer
//! position", M.S. thesis, Cornell University, 1992, and D. Lischinski, F. Tampieri,
//! D. P. Greenberg, "Combining hierarchical radiosity and discontinuity meshing",
//! SIGGRAPH '93. The solution is not displayed as it is: at a visible point, the
//! irradiance it sends there is gathered again, so the point's light is no longer
//! limited by the mesh (indirect light interpolated across elements, contact
//! shadows one element wide), only the light arriving from farther surfaces is read
//! from it, where errors are averaged over the hemisphere.
//!
//! The gather casts rays, Ward's way (G. J. Ward, F. M. Rubinstein, R. D. Clear, "A
//! ray tracing solution for diffuse interreflection", SIGGRAPH '88): the hemisphere
//! over the point cut into M × N strata of equal projected solid angle (θ_j with
//! sin²θ from j/M to (j + 1)/M, φ_k from 2πk/N to 2π(k + 1)/N, N ≈ πM), one jittered
//! ray in each, so that each ray's radiance counts π/(MN) of the irradiance and the
//! cosine weight is in the directions themselves. A ray reads where it lands the
//! radiance the solution's surface reflects, (B − E)/π: its emission is left out,
//! because the direct light is computed exactly by the shading pass beside this.
//! Rays that leave the scene read nothing (the solution holds no light from beyond
//! it). A ray that meets a mirror or a pane goes on, as the second pass's rays do,
//! and brings back the emission of a lamp it finds beyond: the light mirrors throw,
//! which the exact direct light does not see (our choice: the papers gather in
//! diffuse scenes).
//!
//! From the same rays come G. J. Ward, P. S. Heckbert's gradients ("Irradiance
//! gradients", Eurographics Rendering Workshop 1992), which the irradiance cache
//! interpolates with: the rotational gradient (how E changes as the normal turns)
//! and the translational one (as the point moves), from the radiance differences of
//! neighbouring strata across their shared walls and the distance to the nearer
//! surface seen there. Choices left open: each ray's own θ and φ weight the
//! rotational gradient (not its stratum's centre); a wall between azimuthal strata
//! counts the change of projected solid angle its displacement makes,
//! ∫cos θ dθ = sin θ_j+ − sin θ_j−, exactly (tests check both against finite
//! differences of a closed form).

use super::local::{diffuse_texture_scale, reflectance_at};
use super::solution_radiance::SolutionRadiance;
use super::traced_scene::{Leaving, SurfaceHit, TracedScene};
use crate::geometry::bvh::Aabb;
use crate::geometry::sampling::Stream;
use crate::radiosity::Solution;
use crate::scene::{Light, Reach, Reflectance, Scene};
use crate::settings::FinalGatherSettings;
use crate::shading::light_model::{SurfacePoint, reflected};
use glam::{DVec2, DVec3, Vec3};
use std::f64::consts::PI;
use std::sync::Arc;

/// A colour per world axis: the gradient of an RGB irradiance.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Gradient(pub [Vec3; 3]);

impl Gradient {
    /// The change along `d`: Σ_axis d_axis × gradient_axis.
    pub fn along(&self, d: DVec3) -> Vec3 {
        self.0[0] * d.x as f32 + self.0[1] * d.y as f32 + self.0[2] * d.z as f32
    }

    fn add(&mut self, direction: DVec3, value: Vec3) {
        self.0[0] += value * direction.x as f32;
        self.0[1] += value * direction.y as f32;
        self.0[2] += value * direction.z as f32;
    }

    fn scale(&mut self, factor: f64) {
        for axis in &mut self.0 {
            *axis *= factor as f32;
        }
    }
}

/// Ward's M × N strata of the hemisphere for about `rays` rays: N ≈ πM.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Strata {
    pub m: usize,
    pub n: usize,
}

impl Strata {
    pub fn for_rays(rays: u32) -> Strata {
        let m = ((rays as f64 / PI).sqrt().round() as usize).max(1);
        let n = ((rays as f64 / m as f64).round() as usize).max(1);
        Strata { m, n }
    }

    pub fn rays(&self) -> usize {
        self.m * self.n
    }
}

/// What one gather found at a point: the irradiance, its gradients, and the
/// distances its rays travelled.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Gathered {
    pub irradiance: Vec3,
    pub rotational: Gradient,
    pub translational: Gradient,
    /// Ward's R: the harmonic mean of the distances to the surfaces the rays met
    /// (infinite if none was met).
    pub harmonic_distance: f64,
}

/// One ray of a gather: the radiance it brought and how far it went.
#[derive(Clone, Copy)]
struct Sample {
    radiance: Vec3,
    distance: f64,
}

/// Gathers over the hemisphere of unit `normal` at `position` with `strata`, the
/// rays drawn from `stream`, `radiance` reading what each ray brings back from
/// the surface it meets (zero where it meets none).
pub fn gather_hemisphere(
    traced: &TracedScene,
    position: DVec3,
    normal: DVec3,
    leaving: Leaving,
    strata: Strata,
    stream: &mut Stream,
    mut radiance: impl FnMut(&SurfaceHit, DVec3) -> Vec3,
) -> Gathered {
    let Strata { m, n } = strata;
    let (t1, t2) = normal.any_orthonormal_pair();
    let in_world = |sin: f64, cos: f64, phi: f64| {
        t1 * (sin * phi.cos()) + t2 * (sin * phi.sin()) + normal * cos
    };
    let mut samples = Vec::with_capacity(m * n);
    let mut irradiance = Vec3::ZERO;
    let mut rotational = Gradient::default();
    let mut inverse_distances = 0.0;
    for j in 0..m {
        for k in 0..n {
            let sin2 = (j as f64 + stream.next_f64()) / m as f64;
            let phi = 2.0 * PI * (k as f64 + stream.next_f64()) / n as f64;
            let (sin, cos) = (sin2.sqrt(), (1.0 - sin2).max(0.0).sqrt());
            let direction = in_world(sin, cos, phi);
            let sample = match traced.closest(position, direction, f64::INFINITY, leaving) {
                Some(hit) => Sample {
                    radiance: radiance(&hit, direction),
                    distance: hit.t,
                },
                None => Sample {
                    radiance: Vec3::ZERO,
                    distance: f64::INFINITY,
                },
            };
            irradiance += sample.radiance;
            inverse_distances += 1.0 / sample.distance;
            // Turning the normal about axis a by α changes this ray's cos θ by
            // α a·(n × d) = α sin θ a·w, w the horizontal direction at φ + π/2;
            // relative to the cos θ its sampling density holds: tan θ.
            if cos > 0.0 {
                let w = in_world(1.0, 0.0, phi + 0.5 * PI);
                rotational.add(w, sample.radiance * (sin / cos) as f32);
            }
            samples.push(sample);
        }
    }
    let per_ray = PI / (m * n) as f64;
    rotational.scale(per_ray);
    Gathered {
        irradiance: irradiance * per_ray as f32,
        rotational,
        translational: translational(&samples, strata, t1, t2),
        harmonic_distance: (m * n) as f64 / inverse_distances,
    }
}

/// Ward & Heckbert's translational gradient from the strata's radiances (row j of
/// N in `samples`) and distances. Moving the point shifts what each wall between
/// neighbouring strata shows; the change is the radiance difference across the
/// wall times the projected solid angle the wall sweeps, over the distance of the
/// nearer of the two surfaces (the one whose edge moves).
fn translational(samples: &[Sample], strata: Strata, t1: DVec3, t2: DVec3) -> Gradient {
    let Strata { m, n } = strata;
    let horizontal = |phi: f64| t1 * phi.cos() + t2 * phi.sin();
    let sin_at = |j: usize| (j as f64 / m as f64).sqrt();
    let mut gradient = Gradient::default();
    for k in 0..n {
        // Walls between rows j − 1 and j, at sin²θ = j/M: moving by δ along the
        // stratum's centre direction u_k turns them by δ cos θ/R in θ, sweeping
        // (2π/N) sin θ cos²θ δ/R of projected solid angle.
        let u = horizontal(2.0 * PI * (k as f64 + 0.5) / n as f64);
        for j in 1..m {
            let (here, below) = (samples[j * n + k], samples[(j - 1) * n + k]);
            let r = here.distance.min(below.distance);
            if r.is_finite() && r > 0.0 {
                let sin = sin_at(j);
                let cos2 = 1.0 - sin * sin;
                let weight = 2.0 * PI / n as f64 * sin * cos2 / r;
                gradient.add(u, (here.radiance - below.radiance) * weight as f32);
            }
        }
        // The wall between strata k − 1 and k, at φ = 2πk/N: moving by δ across it
        // (v_k−, towards k) turns it by δ/(R sin θ) in φ, sweeping
        // ∫cos θ sin θ dθ/(sin θ) δ/R = (sin θ_j+ − sin θ_j−) δ/R.
        let v = horizontal(2.0 * PI * k as f64 / n as f64 + 0.5 * PI);
        let previous = (k + n - 1) % n;
        for j in 0..m {
            let (here, before) = (samples[j * n + k], samples[j * n + previous]);
            let r = here.distance.min(before.distance);
            if r.is_finite() && r > 0.0 && n > 1 {
                let weight = (sin_at(j + 1) - sin_at(j)) / r;
                gradient.add(v, (here.radiance - before.radiance) * weight as f32);
            }
        }
    }
    gradient
}

/// The final gather over one radiosity solution.
pub struct FinalGather {
    traced: Arc<TracedScene>,
    /// What the solution's surfaces reflect, (B − E)/π; with `direct_at_hits`,
    /// without the part they received straight from the emitters, (B − E − D)/π.
    reflected: SolutionRadiance,
    /// The lights whose direct light is computed where rays land, when the
    /// settings ask it: all of them (the solution holds every light).
    lights: Vec<Light>,
    pub settings: FinalGatherSettings,
    /// How many mirrors and panes a gather ray goes on through (the second
    /// pass's `depth`).
    depth: u32,
    pub strata: Strata,
    /// The scene's bounds: the cache's octree covers them, and its spacings are
    /// fractions of their diagonal.
    pub bounds: Aabb,
}

impl FinalGather {
    /// The scene its rays are cast in.
    pub fn traced(&self) -> &TracedScene {
        &self.traced
    }

    /// The scene's size: its bounding box's diagonal.
    pub fn scene_size(&self) -> f64 {
        (self.bounds.max - self.bounds.min).length()
    }

    /// The gather over `solution` (the whole solution, its direct part included:
    /// what a surface received straight from the lamp is indirect light for the
    /// points it lights).
    pub fn new(
        scene: &Scene,
        solution: &Solution,
        traced: Arc<TracedScene>,
        settings: FinalGatherSettings,
    ) -> FinalGather {
        let mesh = &solution.mesh;
        let direct = solution.direct.as_ref().filter(|_| settings.direct_at_hits);
        let reflected: Vec<Vec3> = mesh
            .elements
            .iter()
            .zip(&solution.elements)
            .enumerate()
            .map(|(i, (e, b))| {
                let received = direct.map_or(Vec3::ZERO, |d| d[i]);
                (*b - mesh.patches[e.patch].emission - received).max(Vec3::ZERO)
            })
            .collect();
        let lights = scene
            .lights
            .iter()
            .filter(|_| direct.is_some())
            .cloned()
            .collect();
        FinalGather {
            traced,
            reflected: SolutionRadiance::new(scene, mesh, &reflected, solution.display),
            lights,
            strata: Strata::for_rays(settings.rays),
            settings,
            bounds: Aabb::of(scene.polygons.iter().flat_map(|p| p.positions())),
            depth: scene.global.as_ref().map_or(0, |g| g.depth),
        }
    }

    /// The gather at `position` on polygon `polygon`, unit `normal` on the side it
    /// is seen from, its rays drawn from stream `stream`.
    pub fn gather(
        &self,
        scene: &Scene,
        polygon: u32,
        position: DVec3,
        normal: DVec3,
        stream: u64,
    ) -> Gathered {
        let mut stream = Stream::new(GATHER_SEED, stream);
        let mut lights = Stream::new(LIGHT_SEED, stream.next_u64());
        gather_hemisphere(
            &self.traced,
            position,
            normal,
            Leaving::Polygon(polygon),
            self.strata,
            &mut stream,
            |hit, direction| self.brought(scene, hit, direction, 1, &mut lights),
        )
    }

    /// What a gather ray brings back from `hit`: the radiance the solution's
    /// surface reflects there (with `direct_at_hits`, its direct light computed
    /// again); off a mirror or through a pane, what the ray goes on to meet, to the
    /// second pass's depth, emitters' emission included: the lamp seen in a mirror
    /// lights the point as the solution's mirrored factors had it light the mesh,
    /// and the exact direct light, which sees the lamp only straight on, leaves it
    /// out.
    fn brought(
        &self,
        scene: &Scene,
        hit: &SurfaceHit,
        direction: DVec3,
        depth: u32,
        lights: &mut Stream,
    ) -> Vec3 {
        // Radiosity leaves the front only.
        let Some(p) = hit.polygon else {
            return Vec3::ZERO;
        };
        if direction.dot(hit.geometric_normal) >= 0.0 {
            return Vec3::ZERO;
        }
        let reflected = self.reflected.at(p, hit.position);
        let mut radiance = match diffuse_texture_scale(scene, hit, -direction) {
            Some(scale) => reflected * scale,
            None => reflected,
        } + self.direct_at(scene, hit, direction, lights);
        if depth > self.depth {
            return radiance;
        }
        let material = &scene.materials[hit.material];
        let normal = hit.geometric_normal;
        let mirrored = direction - 2.0 * direction.dot(normal) * normal;
        for (k, onward) in [
            (material.mirror, mirrored),
            (material.transmittance, direction),
        ] {
            if k.max_element() <= 0.0 {
                continue;
            }
            let Some(next) =
                self.traced
                    .closest(hit.position, onward, f64::INFINITY, hit.leaving())
            else {
                continue;
            };
            let emitted = if onward.dot(next.geometric_normal) < 0.0 {
                scene.materials[next.material].emission
            } else {
                Vec3::ZERO
            };
            radiance += k * (emitted + self.brought(scene, &next, onward, depth + 1, lights));
        }
        radiance
    }

    /// The direct light a hit reflects back along the ray, from every light, each
    /// by one shadow ray (the gather's many rays average their noise). A point,
    /// spot or distant light is reached by its one ray exactly: its unshadowed
    /// light if the ray is clear. An extended light is sampled at one point, the
    /// sample weighted as irradiance, L × w cos θ with w its weight per unit
    /// radiance (`Light::sample`): the light is its exact unshadowed light
    /// (Lambert's formula) less ρ/π times that weighted sample when the ray is
    /// blocked, whose mean is ρ/π times the visible part's irradiance, exact where
    /// nothing is in the way (our choice: the blocked part as the estimate's
    /// control variate, rather than ρ/π L w cos θ alone when clear, whose weights
    /// grow without bound near the light's edges). One ray's visibility times the
    /// unshadowed light would converge to the visible share of the light's area
    /// instead, wrong in a penumbra.
    pub fn direct_at(
        &self,
        scene: &Scene,
        hit: &SurfaceHit,
        direction: DVec3,
        stream: &mut Stream,
    ) -> Vec3 {
        if self.lights.is_empty() {
            return Vec3::ZERO;
        }
        let reflectance = Reflectance {
            diffuse: reflectance_at(scene, hit, -direction).diffuse,
            specular: Vec3::ZERO,
            exponent: 1.0,
        };
        let normal = if hit.normal.dot(direction) > 0.0 {
            -hit.normal
        } else {
            hit.normal
        };
        let point = SurfacePoint {
            position: hit.position,
            normal,
            to_eye: -direction,
        };
        let mut total = Vec3::ZERO;
        for light in &self.lights {
            let u = DVec2::new(stream.next_f64(), stream.next_f64());
            let Some(sample) = light.sample(hit.position, u) else {
                continue;
            };
            let unshadowed = reflected(&point, &reflectance, light);
            let emitter = light.emitter_polygon().map(|p| p as u32);
            let clear = !self
                .traced
                .blocked(hit.position, sample.point, hit.leaving(), emitter);
            if clear {
                total += unshadowed;
                continue;
            }
            match light.reach() {
                // A point's or a direction's one ray is exact: blocked, no light.
                Reach::Point { .. } | Reach::Direction { .. } => {}
                // The blocked sample's irradiance, taken from the exact light.
                Reach::Extended { radiance } => {
                    let cos = normal.dot((sample.point - hit.position).normalize());
                    let blocked = (sample.weight * cos.max(0.0)) as f32;
                    total += unshadowed
                        - reflectance.diffuse / std::f32::consts::PI * radiance * blocked;
                }
            }
        }
        total
    }
}

/// The seed of the gathers' streams (each gather's stream is its sample's index).
const GATHER_SEED: u64 = 0x6761_7468_6572;
/// The seed of the shadow rays' streams at the gathers' hits.
const LIGHT_SEED: u64 = 0x6869_7473;
