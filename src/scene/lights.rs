//! Lights: five kinds, each knowing its geometry and how to be sampled.
//!
//! | kind | emits | given by |
//! |---|---|---|
//! | point | radiant intensity I (W/sr), all directions | position |
//! | distant | irradiance E on a surface facing it | the direction light travels |
//! | polygon | radiance L, one-sided Lambertian | a planar polygon of the scene |
//! | sphere | radiance L, Lambertian | centre and radius |
//! | spot | intensity I(θ) = I f(θ) inside a cone | position, axis, half-angle, f |
//!
//! A polygon light is also a polygon of the scene: the camera sees it and it casts
//! shadows like any other. A sphere light, like a point light, is not drawn and
//! casts no shadow of its own: it is a luminaire, not an object (put a sphere object
//! around it to see one).
//!
//! Sampling serves methods that estimate a light's irradiance by casting rays to
//! points on it (soft shadows: R. L. Cook, T. Porter, L. Carpenter, "Distributed ray
//! tracing", SIGGRAPH '84): see `Light::sample`.

use crate::geometry::polygon::{area, centroid, triangulate};
use crate::geometry::sampling::{cosine_weighted, uniform_cone};
use glam::{DVec2, DVec3, Vec3};
use std::f64::consts::{PI, TAU};

/// An isotropic point light with inverse-square falloff.
#[derive(Clone, Debug)]
pub struct PointLight {
    /// Where it is.
    pub position: DVec3,
    /// Radiant intensity (W/sr per RGB channel).
    pub intensity: Vec3,
    /// Its name in the scene file, if it has one.
    pub name: Option<String>,
}

/// Parallel light from far away (the sun), as Mitsuba's `directional` emitter.
#[derive(Clone, Debug)]
pub struct DistantLight {
    /// Unit direction in which the light travels (from the light into the scene).
    pub direction: DVec3,
    /// Irradiance on a surface facing the light (W/m² per channel).
    pub irradiance: Vec3,
    /// Its name in the scene file, if it has one.
    pub name: Option<String>,
}

/// A one-sided Lambertian emitter over a planar polygon, convex or concave. It is also
/// a polygon of the scene (`polygon`), so the camera sees it with its radiance.
#[derive(Clone, Debug)]
pub struct PolygonLight {
    /// Its corners, counter-clockwise seen from the emitting side.
    pub vertices: Vec<DVec3>,
    /// Unit normal, on the emitting side.
    pub normal: DVec3,
    /// Centroid of the vertices and area of the polygon.
    pub centre: DVec3,
    /// Its area.
    pub area: f64,
    /// Emitted radiance, the same in every direction of the emitting side.
    pub radiance: Vec3,
    /// The scene polygon it is (an index into `Scene::polygons`).
    pub polygon: usize,
    /// Its name in the scene file, if it has one.
    pub name: Option<String>,
    /// The polygon cut into triangles (ear clipping), for sampling by area.
    pub triangles: Vec<[DVec3; 3]>,
    /// Running sums of the triangles' areas over the total: triangle k owns
    /// [cumulative[k − 1], cumulative[k]) of [0, 1).
    cumulative: Vec<f64>,
}

impl PolygonLight {
    /// A polygon light of `polygon`, its centre, area and triangles computed.
    pub fn new(
        vertices: Vec<DVec3>,
        normal: DVec3,
        radiance: Vec3,
        polygon: usize,
        name: Option<String>,
    ) -> PolygonLight {
        let triangles: Vec<[DVec3; 3]> = triangulate(&vertices)
            .into_iter()
            .map(|t| t.map(|k| vertices[k]))
            .collect();
        let areas: Vec<f64> = triangles.iter().map(|t| area(t)).collect();
        let total: f64 = areas.iter().sum();
        let mut sum = 0.0;
        let mut cumulative: Vec<f64> = areas
            .iter()
            .map(|a| {
                sum += a;
                sum / total
            })
            .collect();
        if let Some(last) = cumulative.last_mut() {
            *last = 1.0;
        }
        PolygonLight {
            centre: centroid(&vertices),
            area: area(&vertices),
            vertices,
            normal,
            radiance,
            polygon,
            name,
            triangles,
            cumulative,
        }
    }

    /// A point uniformly distributed over the polygon's area for uniform `u`: the
    /// triangle is chosen by area with `u.x`, which is then stretched back to [0, 1)
    /// within that triangle's share, so a stratified `u` stays stratified; inside the
    /// triangle, barycentrics (1 − √s, t √s) (the square-root warp, uniform by area).
    pub fn point_at(&self, u: DVec2) -> DVec3 {
        let k = self
            .cumulative
            .partition_point(|&c| c <= u.x)
            .min(self.triangles.len() - 1);
        let low = if k == 0 { 0.0 } else { self.cumulative[k - 1] };
        let share = self.cumulative[k] - low;
        let s = if share > 0.0 {
            ((u.x - low) / share).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let [a, b, c] = self.triangles[k];
        let root = s.sqrt();
        let (wa, wb) = (1.0 - root, u.y * root);
        a * wa + b * wb + c * (1.0 - wa - wb)
    }
}

/// A uniform Lambertian sphere. Not drawn by the camera and casting no shadow of its
/// own, like a point light.
#[derive(Clone, Debug)]
pub struct SphereLight {
    /// Its centre.
    pub centre: DVec3,
    /// Its radius.
    pub radius: f64,
    /// Radiance leaving every point of the sphere in every outward direction.
    pub radiance: Vec3,
    /// Its name in the scene file, if it has one.
    pub name: Option<String>,
}

/// How a spot light's intensity falls off from its axis: f(θ), θ the angle from the
/// axis (f = 0 beyond the cone whatever the distribution says).
#[derive(Clone, Debug, PartialEq)]
pub enum SpotDistribution {
    /// f(θ) = cosᵖ θ (p = 0: a uniform cone).
    CosinePower(f64),
    /// (θ in radians, f) pairs with increasing angles, interpolated linearly and
    /// clamped to the first and last factors outside them. (The scene file gives the
    /// angles in degrees.)
    Table(Vec<(f64, f64)>),
}

/// A point light shining into a cone: intensity I f(θ) for θ ≤ the cone's half-angle,
/// zero beyond.
#[derive(Clone, Debug)]
pub struct SpotLight {
    /// Where it is.
    pub position: DVec3,
    /// Unit direction the spot points to.
    pub axis: DVec3,
    /// Half-angle of the cone, radians (degrees in the scene file), in (0, π/2].
    pub cone_angle: f64,
    /// Radiant intensity on the axis (W/sr per channel).
    pub intensity: Vec3,
    /// How intensity falls off from the axis inside the cone.
    pub distribution: SpotDistribution,
    /// Its name in the scene file, if it has one.
    pub name: Option<String>,
}

impl SpotLight {
    /// f(θ): the intensity at angle θ (radians) from the axis over the intensity on
    /// the axis.
    pub fn factor(&self, theta: f64) -> f64 {
        if theta > self.cone_angle {
            return 0.0;
        }
        match &self.distribution {
            SpotDistribution::CosinePower(p) => theta.cos().max(0.0).powf(*p),
            SpotDistribution::Table(table) => interpolate(table, theta),
        }
    }

    /// f(θ) towards `point` (0 at the light itself).
    pub fn factor_towards(&self, point: DVec3) -> f64 {
        let d = (point - self.position).normalize_or_zero();
        if d == DVec3::ZERO {
            return 0.0;
        }
        self.factor(d.dot(self.axis).clamp(-1.0, 1.0).acos())
    }
}

/// Piecewise-linear interpolation in a table of increasing abscissae, clamped.
fn interpolate(table: &[(f64, f64)], x: f64) -> f64 {
    let Some(&(x0, f0)) = table.first() else {
        return 0.0;
    };
    if x <= x0 {
        return f0;
    }
    for pair in table.windows(2) {
        let ((a, fa), (b, fb)) = (pair[0], pair[1]);
        if x <= b {
            return fa + (fb - fa) * (x - a) / (b - a);
        }
    }
    table[table.len() - 1].1
}

#[derive(Clone, Debug)]
/// A light of the scene.
pub enum Light {
    /// An isotropic point light.
    Point(PointLight),
    /// Parallel light from far away.
    Distant(DistantLight),
    /// An emitting polygon.
    Polygon(PolygonLight),
    /// An emitting sphere.
    Sphere(SphereLight),
    /// A spot light.
    Spot(SpotLight),
}

/// How a light reaches the scene, for the methods that need only its geometry (hard
/// shadows, light volumes, media, the tracer's shadow rays): each asks this one
/// match, not the light's kind.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reach {
    /// From a point (point and spot lights), with its radiant intensity (a spot's
    /// on its axis: `Light::cone_factor` gives the rest).
    Point { at: DVec3, intensity: Vec3 },
    /// From a direction (distant lights): the unit direction light travels, and the
    /// irradiance of a surface facing it.
    Direction { direction: DVec3, irradiance: Vec3 },
    /// From an extended emitter (polygon and sphere lights), of this radiance:
    /// sampled (`Light::sample`, whose weights are per unit radiance).
    Extended { radiance: Vec3 },
}

/// One point on (or, for a distant light, towards) a light, seen from a receiver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// The point on (or towards) the light.
    pub point: DVec3,
    /// The estimator's weight: see `Light::sample`.
    pub weight: f64,
}

/// How far towards a distant light its sample point lies, in scene units: beyond any
/// scene lumiere renders, so a shadow segment to it crosses everything in the way.
pub const DISTANT_REACH: f64 = 1e7;

/// The kinds of light, as the scene file's `type` names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LightKind {
    /// `type = "point"`.
    Point,
    /// `type = "distant"`.
    Distant,
    /// `type = "polygon"` (an emitting material on a polygon).
    Polygon,
    /// `type = "sphere"`.
    Sphere,
    /// `type = "spot"`.
    Spot,
}

impl LightKind {
    /// Every kind, in the order messages list them.
    pub const ALL: [LightKind; 5] = [
        LightKind::Point,
        LightKind::Spot,
        LightKind::Distant,
        LightKind::Sphere,
        LightKind::Polygon,
    ];

    /// The name the scene file writes.
    pub fn name(self) -> &'static str {
        match self {
            LightKind::Point => "point",
            LightKind::Distant => "distant",
            LightKind::Polygon => "polygon",
            LightKind::Sphere => "sphere",
            LightKind::Spot => "spot",
        }
    }
}

impl std::fmt::Display for LightKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl Light {
    /// Its kind.
    pub fn kind(&self) -> LightKind {
        match self {
            Light::Point(_) => LightKind::Point,
            Light::Distant(_) => LightKind::Distant,
            Light::Polygon(_) => LightKind::Polygon,
            Light::Sphere(_) => LightKind::Sphere,
            Light::Spot(_) => LightKind::Spot,
        }
    }

    /// Its name in the scene file, if it has one.
    pub fn name(&self) -> Option<&str> {
        match self {
            Light::Point(l) => l.name.as_deref(),
            Light::Distant(l) => l.name.as_deref(),
            Light::Polygon(l) => l.name.as_deref(),
            Light::Sphere(l) => l.name.as_deref(),
            Light::Spot(l) => l.name.as_deref(),
        }
    }

    /// How messages name light number `index` of the scene: "light 2 (spot `key`)".
    pub fn label(&self, index: usize) -> String {
        match self.name() {
            Some(name) => format!("light {index} ({} `{name}`)", self.kind()),
            None => format!("light {index} ({})", self.kind()),
        }
    }

    /// Where a point-like light (point, spot) sits; `None` for lights with extent or
    /// at infinity.
    pub fn position(&self) -> Option<DVec3> {
        match self.reach() {
            Reach::Point { at, .. } => Some(at),
            Reach::Direction { .. } | Reach::Extended { .. } => None,
        }
    }

    /// How it reaches the scene: from a point, a direction or an extended emitter.
    pub fn reach(&self) -> Reach {
        match self {
            Light::Point(l) => Reach::Point {
                at: l.position,
                intensity: l.intensity,
            },
            Light::Spot(l) => Reach::Point {
                at: l.position,
                intensity: l.intensity,
            },
            Light::Distant(l) => Reach::Direction {
                direction: l.direction,
                irradiance: l.irradiance,
            },
            Light::Polygon(l) => Reach::Extended {
                radiance: l.radiance,
            },
            Light::Sphere(l) => Reach::Extended {
                radiance: l.radiance,
            },
        }
    }

    /// The scene polygon the light is, when it is one (a polygon light: rays that
    /// reach the emitter are not blocked by it).
    pub fn emitter_polygon(&self) -> Option<usize> {
        match self {
            Light::Polygon(l) => Some(l.polygon),
            Light::Point(_) | Light::Distant(_) | Light::Sphere(_) | Light::Spot(_) => None,
        }
    }

    /// The light moved by `offset`, for the lights that sit somewhere (`None`: a
    /// distant light has no place, a polygon light is a polygon of the scene).
    pub fn moved(&self, offset: DVec3) -> Option<Light> {
        let mut light = self.clone();
        match &mut light {
            Light::Point(l) => l.position += offset,
            Light::Spot(l) => l.position += offset,
            Light::Sphere(l) => l.centre += offset,
            Light::Distant(_) | Light::Polygon(_) => return None,
        }
        Some(light)
    }

    /// The light in a scene whose polygons were renumbered by `renumbered` (old id
    /// to new; `None`: left out, and a polygon light with it).
    pub fn renumbered(&self, renumbered: &[Option<usize>]) -> Option<Light> {
        match self {
            Light::Polygon(l) => renumbered[l.polygon].map(|polygon| {
                let mut l = l.clone();
                l.polygon = polygon;
                Light::Polygon(l)
            }),
            Light::Point(_) | Light::Distant(_) | Light::Sphere(_) | Light::Spot(_) => {
                Some(self.clone())
            }
        }
    }

    /// The fraction of its intensity a point light sends towards `point`: a spot's
    /// cone factor, 1 for the others.
    pub fn cone_factor(&self, point: DVec3) -> f64 {
        match self {
            Light::Spot(l) => l.factor_towards(point),
            Light::Point(_) | Light::Distant(_) | Light::Polygon(_) | Light::Sphere(_) => 1.0,
        }
    }

    /// One sample of the light seen from a receiver at `from`, for `u` in [0, 1)².
    ///
    /// For a receiver with unit normal n, the mean over uniform `u` of
    /// `weight × max(0, n · (point − from)/|point − from|)` is the light's irradiance
    /// at `from` per unit of its emission (when nothing is in the way):
    ///
    /// - polygon (per unit radiance): a point uniform over the area, weight
    ///   A cos θ_light / d² (1/pdf times the geometric term);
    /// - sphere (per unit radiance): a direction uniform in the cone the sphere
    ///   subtends from `from`, the point where it first meets the sphere, weight the
    ///   cone's solid angle 2π(1 − cos α), sin α = r/d;
    /// - point (per unit intensity): the light's position, weight 1/d², whatever `u`;
    /// - spot (per unit on-axis intensity): its position, weight f(θ)/d²;
    /// - distant (per unit irradiance): the point `DISTANT_REACH` back along the
    ///   light's travel from `from`, weight 1.
    ///
    /// `None`: this sample brings nothing (behind a one-sided polygon, outside a
    /// spot's cone, `from` on a point light or inside a sphere light, which emits
    /// outwards only); it counts as zero in the mean.
    pub fn sample(&self, from: DVec3, u: DVec2) -> Option<LightSample> {
        let at = |point: DVec3, weight: f64| {
            (weight > 0.0 && weight.is_finite()).then_some(LightSample { point, weight })
        };
        match self {
            Light::Point(l) => at(l.position, 1.0 / (l.position - from).length_squared()),
            Light::Spot(l) => at(
                l.position,
                l.factor_towards(from) / (l.position - from).length_squared(),
            ),
            Light::Distant(l) => at(from - l.direction * DISTANT_REACH, 1.0),
            Light::Polygon(l) => {
                let point = l.point_at(u);
                let d = from - point;
                let r2 = d.length_squared();
                let cos_light = l.normal.dot(d) / r2.sqrt();
                at(point, l.area * cos_light / r2)
            }
            Light::Sphere(l) => {
                sphere_sample(l.centre, l.radius, from, u).and_then(|(p, w)| at(p, w))
            }
        }
    }
}

/// A photon leaving a light: where, which way, and its power's estimator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emitted {
    pub origin: DVec3,
    /// Unit direction of travel.
    pub direction: DVec3,
    /// Emitted radiance times cos θ over the density of (origin, direction): its
    /// mean over uniform `u` is the light's power, so N photons of power
    /// `weight / N` carry it.
    pub weight: Vec3,
}

impl Light {
    /// The power the light sends into a scene bounded by the sphere (`centre`,
    /// `radius`), per band: π A L (a polygon, one-sided), 4π² r² L (a sphere),
    /// 4π I (a point), I times the cone's solid angle (a spot: the most its
    /// distribution sends), E π R² (a distant light, over the scene's disc).
    pub fn power(&self, radius: f64) -> Vec3 {
        let solid = |cos_alpha: f64| TAU * (1.0 - cos_alpha);
        match self {
            Light::Polygon(l) => l.radiance * (PI * l.area) as f32,
            Light::Sphere(l) => l.radiance * (4.0 * PI * PI * l.radius * l.radius) as f32,
            Light::Point(l) => l.intensity * (4.0 * PI) as f32,
            Light::Spot(l) => l.intensity * solid(l.cone_angle.cos()) as f32,
            Light::Distant(l) => l.irradiance * (PI * radius * radius) as f32,
        }
    }

    /// One photon from the light into a scene bounded by the sphere (`centre`,
    /// `radius`), for `u` uniform in [0, 1)⁴: a point uniform over an emitter's
    /// area and a direction by the cosine about its normal; a point light's
    /// direction uniform over the sphere, a spot's over its cone (weighted by its
    /// distribution); a distant light's photons uniform over the disc across the
    /// scene, entering along its direction. `None`: a spot's direction outside
    /// its distribution.
    pub fn emit(&self, centre: DVec3, radius: f64, u: [f64; 4]) -> Option<Emitted> {
        let emitted = |origin: DVec3, direction: DVec3, weight: Vec3| {
            (weight.max_element() > 0.0).then_some(Emitted {
                origin,
                direction,
                weight,
            })
        };
        match self {
            Light::Polygon(l) => {
                let origin = l.point_at(DVec2::new(u[0], u[1]));
                let direction = cosine_weighted(l.normal, u[2], u[3]);
                emitted(origin, direction, self.power(radius))
            }
            Light::Sphere(l) => {
                let normal = uniform_cone(DVec3::Z, -1.0, u[0], u[1]);
                let origin = l.centre + normal * l.radius;
                let direction = cosine_weighted(normal, u[2], u[3]);
                emitted(origin, direction, self.power(radius))
            }
            Light::Point(l) => {
                let direction = uniform_cone(DVec3::Z, -1.0, u[2], u[3]);
                emitted(l.position, direction, self.power(radius))
            }
            Light::Spot(l) => {
                let direction = uniform_cone(l.axis, l.cone_angle.cos(), u[2], u[3]);
                let factor = l.factor(direction.dot(l.axis).clamp(-1.0, 1.0).acos());
                emitted(l.position, direction, self.power(radius) * factor as f32)
            }
            Light::Distant(l) => {
                // A point uniform on the disc of radius R across the light's
                // travel, beyond the scene's sphere.
                let (a, b) = l.direction.any_orthonormal_pair();
                let r = radius * u[0].sqrt();
                let phi = TAU * u[1];
                let origin =
                    centre - l.direction * (2.0 * radius) + (a * phi.cos() + b * phi.sin()) * r;
                emitted(origin, l.direction, self.power(radius))
            }
        }
    }
}

/// A direction uniform over the cone of directions in which the sphere is seen from
/// `from` (cos θ uniform in [cos α, 1], the azimuth uniform), the point where that
/// direction first meets the sphere, and the cone's solid angle; `None` from inside.
fn sphere_sample(centre: DVec3, radius: f64, from: DVec3, u: DVec2) -> Option<(DVec3, f64)> {
    let to_centre = centre - from;
    let d = to_centre.length();
    if d <= radius {
        return None;
    }
    let w = to_centre / d;
    // 1 − cos α written as sin²α / (1 + cos α): no cancellation for small spheres.
    let sin2 = (radius / d).powi(2);
    let one_minus_cos = sin2 / (1.0 + (1.0 - sin2).sqrt());
    let cos = 1.0 - u.x * one_minus_cos;
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    let (a, b) = w.any_orthonormal_pair();
    let direction = a * (sin * phi.cos()) + b * (sin * phi.sin()) + w * cos;
    // |from + t dir − centre|² = r²: t² − 2t (dir · to_centre) + d² − r² = 0, the
    // nearer root (the discriminant is ≥ 0 inside the cone, up to rounding).
    let along = direction.dot(to_centre);
    let t = along - (along * along - (d * d - radius * radius)).max(0.0).sqrt();
    Some((from + direction * t, 2.0 * PI * one_minus_cos))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spot(distribution: SpotDistribution) -> SpotLight {
        SpotLight {
            position: DVec3::ZERO,
            axis: DVec3::NEG_Y,
            cone_angle: 30f64.to_radians(),
            intensity: Vec3::ONE,
            distribution,
            name: None,
        }
    }

    #[test]
    fn spot_factors() {
        let uniform = spot(SpotDistribution::CosinePower(0.0));
        assert_eq!(uniform.factor(0.0), 1.0);
        assert_eq!(uniform.factor(29f64.to_radians()), 1.0);
        assert_eq!(uniform.factor(31f64.to_radians()), 0.0);
        let cosine = spot(SpotDistribution::CosinePower(3.0));
        let t = 20f64.to_radians();
        assert!((cosine.factor(t) - t.cos().powi(3)).abs() < 1e-15);
        let table = spot(SpotDistribution::Table(vec![
            (0.0, 1.0),
            (20f64.to_radians(), 0.7),
            (25f64.to_radians(), 0.2),
        ]));
        assert!((table.factor(10f64.to_radians()) - 0.85).abs() < 1e-12);
        assert!((table.factor(22f64.to_radians()) - 0.5).abs() < 1e-12);
        // Clamped past the table's end, cut at the cone.
        assert_eq!(table.factor(28f64.to_radians()), 0.2);
        assert_eq!(table.factor(31f64.to_radians()), 0.0);
        let below = DVec3::new(0.0, -2.0, 2.0 * 10f64.to_radians().tan());
        assert!((table.factor_towards(below) - 0.85).abs() < 1e-12);
    }

    #[test]
    fn labels_and_kinds() {
        let mut l = spot(SpotDistribution::CosinePower(1.0));
        assert_eq!(Light::Spot(l.clone()).label(2), "light 2 (spot)");
        l.name = Some("key".into());
        let light = Light::Spot(l);
        assert_eq!(light.label(2), "light 2 (spot `key`)");
        assert_eq!(light.kind(), LightKind::Spot);
        assert_eq!(light.position(), Some(DVec3::ZERO));
    }
}
