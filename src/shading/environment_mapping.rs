//! Reflection and refraction mapping: J. F. Blinn, M. E. Newell, "Texture and
//! reflection in computer generated images", CACM 19(10):542–547, 1976; cube maps
//! after N. Greene, "Environment mapping and other applications of world
//! projections", IEEE CG&A 6(11):21–29, 1986.
//!
//! Everything around the object is taken to be infinitely far away, so what a mirror
//! shows at a point depends on the direction of the reflected eye ray alone: per
//! visible sample, N and V (surface to eye) in world space give R = 2(N·V)N − V, and
//! the environment map is read at R. Nothing is traced through the scene. The
//! intensity is Blinn and Newell's I = I_local + k_r T(R), k_r the material's
//! `mirror`.
//!
//! Refraction mapping reads the map at Snell's refracted direction instead, through
//! one interface only (the ray is taken never to leave the object); beyond the critical
//! angle, total internal reflection reads R. A material with an index of refraction
//! weighs the two by Schlick's approximation to Fresnel's reflectance, F for the
//! reflection (tinted by `mirror` when given) and (1 − F) × `transmittance` for the
//! refraction: the course's water.
//!
//! Filtering (Blinn and Newell mapped the pixel's corners and averaged the map between
//! them): R is computed again at the next sample along x and along y, on the same
//! polygon's plane with its interpolated normal there, and the two differences are
//! the lookup's footprint (a ray differential by finite differences). Bump mapping
//! perturbs the centre's direction, not the footprint. The terms are evaluated per
//! sample in every shading mode (flat with the polygon's normal).

use crate::raster::{View, VisibleSurface};
use crate::scene::ray_queries::interpolate;
use crate::scene::{Material, Polygon};
use crate::texture::environment::EnvironmentMap;
use glam::{DVec3, Vec3};

use super::optics::{reflect, refract, schlick};

/// What one sample of a mirror or refracting surface needs.
pub struct EnvironmentSample<'a> {
    pub view: &'a View,
    pub band: &'a VisibleSurface,
    pub k: usize,
    pub polygon: &'a Polygon,
    pub material: &'a Material,
    /// The normal the local shading used (interpolated, bumped), not yet turned.
    pub normal: DVec3,
    /// Whether the footprint takes the polygon's normal (flat shading) or the
    /// interpolated one.
    pub flat: bool,
    /// Whether the sample shows its polygon's front.
    pub front: bool,
}

/// Which direction a lookup takes at a point.
#[derive(Clone, Copy)]
enum Ray {
    Reflected,
    Refracted { eta: f64 },
}

/// The turned normal and the unit direction to the eye at the sample and at the
/// next samples along x and y on the polygon's plane (`None` where it is seen
/// edge-on): what every lookup's footprint is made of, found once per sample.
struct Neighbourhood {
    centre: Option<(DVec3, DVec3)>,
    next: [Option<(DVec3, DVec3)>; 2],
}

impl EnvironmentSample<'_> {
    /// The radiance the environment adds at the sample: k_r T(R), or Fresnel's blend
    /// of T(R) and T(T) for a material with an index of refraction.
    pub fn radiance(&self, map: &EnvironmentMap) -> Vec3 {
        let (n, to_eye) = self.normal_and_eye();
        let around = self.neighbourhood();
        let lookup = |ray: Ray| {
            let d = direction(ray, n, to_eye).normalize();
            map.lookup(d, footprint(&around, ray))
        };
        let m = self.material;
        let Some(ior) = m.ior else {
            return m.mirror * lookup(Ray::Reflected);
        };
        // From outside (vacuum, 1) into the material at its front; out of it behind.
        let (eta1, eta2) = if self.front { (1.0, ior) } else { (ior, 1.0) };
        let fresnel = schlick(n.dot(to_eye).clamp(0.0, 1.0), eta1, eta2) as f32;
        let tint = if m.mirror == Vec3::ZERO {
            Vec3::ONE
        } else {
            m.mirror
        };
        let mut radiance = tint * fresnel * lookup(Ray::Reflected);
        if m.transmittance != Vec3::ZERO {
            let refracted = lookup(Ray::Refracted { eta: eta1 / eta2 });
            radiance += m.transmittance * (1.0 - fresnel) * refracted;
        }
        radiance
    }

    /// The mip-map level λ the mirror-direction lookup reads (`None` for filters
    /// without levels).
    pub fn reflected_level(&self, map: &EnvironmentMap) -> Option<f64> {
        let (n, to_eye) = self.normal_and_eye();
        let d = direction(Ray::Reflected, n, to_eye).normalize();
        map.level(d, footprint(&self.neighbourhood(), Ray::Reflected))
    }

    /// The normal turned towards the eye, and the unit direction to the eye.
    fn normal_and_eye(&self) -> (DVec3, DVec3) {
        let s = &self.band.samples[self.k];
        let n = if self.front {
            self.normal
        } else {
            -self.normal
        };
        (n, (self.view.eye - s.position).normalize())
    }

    fn neighbourhood(&self) -> Neighbourhood {
        let s = &self.band.samples[self.k];
        let (x, y) = self.band.position_of(self.k);
        let at = |px: f64, py: f64| -> Option<(DVec3, DVec3)> {
            let (origin, d) = self.view.ray_through(px, py);
            let across = d.dot(self.polygon.normal);
            if across.abs() < 1e-12 {
                return None;
            }
            let t = (s.position - origin).dot(self.polygon.normal) / across;
            let point = origin + d * t;
            let normal = if self.flat {
                self.polygon.normal
            } else {
                interpolate(self.polygon, point).0
            };
            let n = if self.front { normal } else { -normal };
            Some((n, (self.view.eye - point).normalize()))
        };
        let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
        Neighbourhood {
            centre: at(cx, cy),
            next: [at(cx + 1.0, cy), at(cx, cy + 1.0)],
        }
    }
}

/// The lookup direction at a point with turned normal `n`.
fn direction(ray: Ray, n: DVec3, to_eye: DVec3) -> DVec3 {
    let reflected = reflect(to_eye, n);
    match ray {
        Ray::Reflected => reflected,
        Ray::Refracted { eta } => refract(-to_eye, n, eta).unwrap_or(reflected),
    }
}

/// The offsets from the direction `ray` takes at the sample to those it takes at the
/// next samples along x and y (zero where the plane is seen edge-on).
fn footprint(around: &Neighbourhood, ray: Ray) -> [DVec3; 2] {
    let along = |p: &Option<(DVec3, DVec3)>| p.map(|(n, v)| direction(ray, n, v).normalize());
    let Some(centre) = along(&around.centre) else {
        return [DVec3::ZERO; 2];
    };
    around
        .next
        .map(|p| along(&p).map_or(DVec3::ZERO, |d| d - centre))
}

/// The backdrop's radiance at sample `k` of `band`: the environment in the eye ray's
/// direction, its footprint the next samples' rays.
pub fn backdrop(map: &EnvironmentMap, view: &View, band: &VisibleSurface, k: usize) -> Vec3 {
    let (x, y) = band.position_of(k);
    let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
    let d = view.ray(cx, cy).normalize();
    let step = |px: f64, py: f64| view.ray(px, py).normalize() - d;
    map.lookup(d, [step(cx + 1.0, cy), step(cx, cy + 1.0)])
}
