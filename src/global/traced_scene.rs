//! The scene as rays see it: its polygons in a bounding volume hierarchy, and the
//! built-in spheres as quadrics (the unit sphere under each object's transform, an
//! ellipsoid where the scale is not uniform), which Whitted intersected exactly.
//!
//! Rays from a surface do not meet the polygon they leave (a planar polygon cannot
//! be met again) and, on a quadric, start `margin` along the ray, Whitted's ε
//! against self-intersection speckle.

use crate::geometry::bvh::Aabb;
use crate::scene::ray_queries::SceneRays;
use crate::scene::{Polygon, Scene};
use glam::{DMat3, DMat4, DVec2, DVec3};

/// What a ray meets first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHit {
    pub t: f64,
    pub position: DVec3,
    /// Outward unit normal of the surface (a polygon's own normal).
    pub geometric_normal: DVec3,
    /// Interpolated (polygon) or exact (sphere) unit shading normal, outward.
    pub normal: DVec3,
    pub uv: DVec2,
    pub material: usize,
    pub object: usize,
    /// The scene polygon met; `None` on a quadric.
    pub polygon: Option<u32>,
}

/// Which surface a ray leaves, so that it does not meet it again at once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Leaving {
    Eye,
    Polygon(u32),
    Sphere(usize),
}

/// A surface as a ray meets it: from outside (its front) or inside, and its
/// normals on the side the ray comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Facing {
    pub front: bool,
    /// The shading normal, or the geometric one where the interpolated normal faces
    /// away from the ray (near a smooth mesh's silhouette, where the mirror and
    /// Snell laws would break).
    pub normal: DVec3,
    /// The surface's own normal.
    pub geometric: DVec3,
}

impl SurfaceHit {
    /// How a ray along `direction` meets this surface.
    pub fn facing(&self, direction: DVec3) -> Facing {
        let front = direction.dot(self.geometric_normal) < 0.0;
        let side = if front { 1.0 } else { -1.0 };
        let geometric = self.geometric_normal * side;
        let normal = match self.normal * side {
            n if n.dot(direction) < 0.0 => n,
            _ => geometric,
        };
        Facing {
            front,
            normal,
            geometric,
        }
    }

    pub fn leaving(&self) -> Leaving {
        match self.polygon {
            Some(p) => Leaving::Polygon(p),
            None => Leaving::Sphere(self.object),
        }
    }
}

/// A built-in sphere as a quadric.
#[derive(Clone, Debug)]
struct Quadric {
    to_object: DMat4,
    /// Inverse transpose of the linear part: normals to the world.
    normal_to_world: DMat3,
    object: usize,
    material: usize,
}

pub struct TracedScene {
    /// Every polygon but the analytic spheres'.
    rays: SceneRays<'static>,
    /// Scene id of each polygon in `rays`.
    ids: Vec<u32>,
    quadrics: Vec<Quadric>,
    /// Ray parameter (in scene units along unit directions) below which a quadric
    /// hit from its own surface is ignored.
    margin: f64,
}

impl TracedScene {
    /// The scene for rays; with `analytic_spheres`, built-in spheres as quadrics.
    pub fn new(scene: &Scene, analytic_spheres: bool) -> TracedScene {
        let analytic = |p: &Polygon| analytic_spheres && scene.objects[p.object].sphere;
        let mut quadrics: Vec<Quadric> = Vec::new();
        for p in scene.polygons.iter().filter(|p| analytic(p)) {
            if quadrics.iter().all(|q| q.object != p.object) {
                let frame = &scene.objects[p.object].frame;
                quadrics.push(Quadric {
                    to_object: frame.to_object,
                    normal_to_world: DMat3::from_mat4(frame.to_object).transpose(),
                    object: p.object,
                    material: p.material,
                });
            }
        }
        let (ids, polygons): (Vec<u32>, Vec<Polygon>) = scene
            .polygons
            .iter()
            .enumerate()
            .filter(|(_, p)| !analytic(p))
            .map(|(i, p)| (i as u32, p.clone()))
            .unzip();
        let bounds = Aabb::of(scene.polygons.iter().flat_map(|p| p.positions()));
        let size = (bounds.max - bounds.min).length().max(1e-12);
        TracedScene {
            rays: SceneRays::owned(polygons),
            ids,
            quadrics,
            margin: 1e-9 * size.max(1.0),
        }
    }

    /// The first surface the ray origin + t·direction (unit direction) meets for t
    /// in (0, t_max], not counting the surface it leaves.
    pub fn closest(
        &self,
        origin: DVec3,
        direction: DVec3,
        t_max: f64,
        leaving: Leaving,
    ) -> Option<SurfaceHit> {
        let skip = match leaving {
            Leaving::Polygon(p) => self.local(p),
            Leaving::Eye | Leaving::Sphere(_) => None,
        };
        let skip: &[u32] = match &skip {
            Some(p) => std::slice::from_ref(p),
            None => &[],
        };
        let mut best = self
            .rays
            .closest_hit(origin, direction, 0.0, t_max, skip)
            .map(|h| {
                let polygon = &self.rays.polygons()[h.polygon as usize];
                SurfaceHit {
                    t: h.t,
                    position: h.position,
                    geometric_normal: h.geometric_normal,
                    normal: h.normal,
                    uv: h.uv,
                    material: polygon.material,
                    object: polygon.object,
                    polygon: Some(self.ids[h.polygon as usize]),
                }
            });
        for (q, quadric) in self.quadrics.iter().enumerate() {
            let from_surface = leaving == Leaving::Sphere(quadric.object);
            let limit = best.map_or(t_max, |b| b.t);
            if let Some(t) = quadric.meets(origin, direction, from_surface, self.margin, limit) {
                best = Some(self.quadric_hit(q, origin + direction * t, t));
            }
        }
        best
    }

    /// Whether anything but the surface `leaving` (and the polygon `emitter`, a
    /// light's own) lies strictly between `from` and `to`: Whitted's shadow ray.
    pub fn blocked(&self, from: DVec3, to: DVec3, leaving: Leaving, emitter: Option<u32>) -> bool {
        let mut skip: Vec<u32> = Vec::with_capacity(2);
        if let Leaving::Polygon(p) = leaving {
            skip.extend(self.local(p));
        }
        if let Some(e) = emitter {
            skip.extend(self.local(e));
        }
        if self.rays.any_hit(from, to, &skip) {
            return true;
        }
        let d = to - from;
        let length = d.length();
        if length == 0.0 {
            return false;
        }
        let direction = d / length;
        self.quadrics.iter().any(|q| {
            let from_surface = leaving == Leaving::Sphere(q.object);
            q.meets(
                from,
                direction,
                from_surface,
                self.margin,
                length * (1.0 - 1e-9),
            )
            .is_some()
        })
    }

    /// The index in `rays` of scene polygon `p` (it is absent if it is a quadric's).
    fn local(&self, p: u32) -> Option<u32> {
        self.ids.binary_search(&p).ok().map(|i| i as u32)
    }

    fn quadric_hit(&self, q: usize, position: DVec3, t: f64) -> SurfaceHit {
        let quadric = &self.quadrics[q];
        let local = quadric.to_object.transform_point3(position);
        let normal = (quadric.normal_to_world * local).normalize();
        // The built-in sphere's own coordinates, as its polygons carry them (see
        // `scene::shapes::sphere`): φ = atan2(−z, x) around y, θ = acos y.
        let u = (-local.z).atan2(local.x).rem_euclid(std::f64::consts::TAU) / std::f64::consts::TAU;
        let v = 1.0 - local.y.clamp(-1.0, 1.0).acos() / std::f64::consts::PI;
        SurfaceHit {
            t,
            position,
            geometric_normal: normal,
            normal,
            uv: DVec2::new(u, v),
            material: quadric.material,
            object: quadric.object,
            polygon: None,
        }
    }
}

impl Quadric {
    /// The nearest t in (margin or 0, limit) where the ray meets the sphere; from
    /// its own surface the root at the origin is passed over.
    fn meets(
        &self,
        origin: DVec3,
        direction: DVec3,
        from_surface: bool,
        margin: f64,
        limit: f64,
    ) -> Option<f64> {
        let o = self.to_object.transform_point3(origin);
        let d = self.to_object.transform_vector3(direction);
        // |o + t d|² = 1.
        let a = d.length_squared();
        let half_b = o.dot(d);
        let c = o.length_squared() - 1.0;
        let discriminant = half_b * half_b - a * c;
        if discriminant < 0.0 || a == 0.0 {
            return None;
        }
        let root = discriminant.sqrt();
        // The two roots without cancellation.
        let q = -(half_b + root.copysign(half_b));
        let (mut t0, mut t1) = (q / a, c / q);
        if t0 > t1 {
            std::mem::swap(&mut t0, &mut t1);
        }
        let low = if from_surface { margin } else { 0.0 };
        // From its own surface, the root at the origin sits within rounding of 0
        // (below `margin`): the other is the one to keep.
        [t0, t1]
            .into_iter()
            .find(|&t| t.is_finite() && t > low && t < limit)
    }
}
