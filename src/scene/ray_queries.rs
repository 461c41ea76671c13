//! Ray queries on the scene's polygons, over a bounding volume hierarchy built by the
//! surface area heuristic (MacDonald & Booth 1990, binned as in Wald 2007; see
//! `geometry::bvh`). Two questions:
//!
//! - `any_hit`: does any polygon meet the segment strictly between two points? (Appel's
//!   shadow test, and the visibility term of form factors.) Hits within a relative
//!   1e-9 of either end are ignored, so a polygon touching an end (a neighbour, a
//!   coincident polygon, the light itself) does not count; a polygon seen edge-on
//!   does not block.
//! - `closest_hit`: which polygon does a ray meet first, where, and with which
//!   interpolated attributes (shading normal, texture coordinates)? What an eye ray
//!   sees, or a reflected or refracted ray.
//!
//! The hierarchy changes the cost of a query, never its answer: both equal a loop
//! over every polygon (see `tests/suite/scene/ray_queries.rs`).

use super::Polygon;
use crate::geometry::bvh::{Aabb, Bvh};
use glam::{DVec2, DVec3};
use std::borrow::Cow;

/// Parametric margin at both ends of a segment in `any_hit`.
const END_MARGIN: f64 = 1e-9;

/// The scene's polygons in a hierarchy, ready for segment and ray queries. Borrowing
/// (`SceneRays::new`) for one pass, or owning (`SceneRays::owned`, `'static`, `Send +
/// Sync`) to be kept between frames.
pub struct SceneRays<'a> {
    polygons: Cow<'a, [Polygon]>,
    bvh: Bvh,
}

/// Where a ray first meets the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Id of the polygon (its index in the scene).
    pub polygon: u32,
    /// Ray parameter: the point is origin + t·direction.
    pub t: f64,
    pub position: DVec3,
    /// The polygon's unit normal.
    pub geometric_normal: DVec3,
    /// Interpolated shading normal (unit length).
    pub normal: DVec3,
    /// Interpolated texture coordinates.
    pub uv: DVec2,
}

impl<'a> SceneRays<'a> {
    /// A hierarchy over borrowed polygons.
    pub fn new(polygons: &'a [Polygon]) -> SceneRays<'a> {
        SceneRays::build(Cow::Borrowed(polygons))
    }

    fn build(polygons: Cow<'a, [Polygon]>) -> SceneRays<'a> {
        let boxes: Vec<Aabb> = polygons.iter().map(|p| Aabb::of(p.positions())).collect();
        SceneRays {
            bvh: Bvh::build(&boxes),
            polygons,
        }
    }

    pub fn polygons(&self) -> &[Polygon] {
        &self.polygons
    }

    /// Whether a polygon not in `skip` meets the segment strictly between `from` and
    /// `to` (see the module comment for "strictly").
    pub fn any_hit(&self, from: DVec3, to: DVec3, skip: &[u32]) -> bool {
        self.bvh.any_on_segment(from, to, |i| {
            !skip.contains(&i) && segment_meets_polygon(from, to, &self.polygons[i as usize])
        })
    }

    /// The first polygon not in `skip` that the ray origin + t·direction meets for t
    /// in [t_min, t_max] (`direction` need not be unit; `t` is in its units). A
    /// polygon seen edge-on is not met. Of polygons met at the same t (a shared edge)
    /// the one with the smaller id is returned.
    pub fn closest_hit(
        &self,
        origin: DVec3,
        direction: DVec3,
        t_min: f64,
        t_max: f64,
        skip: &[u32],
    ) -> Option<Hit> {
        let (polygon, t) = self
            .bvh
            .closest_on_ray(origin, direction, t_min, t_max, |i| {
                if skip.contains(&i) {
                    return None;
                }
                ray_meets_polygon(origin, direction, &self.polygons[i as usize])
            })?;
        let p = &self.polygons[polygon as usize];
        let position = origin + direction * t;
        let (normal, uv) = interpolate(p, position);
        Some(Hit {
            polygon,
            t,
            position,
            geometric_normal: p.normal,
            normal,
            uv,
        })
    }
}

impl SceneRays<'static> {
    /// A hierarchy owning its polygons.
    pub fn owned(polygons: Vec<Polygon>) -> SceneRays<'static> {
        SceneRays::build(Cow::Owned(polygons))
    }
}

/// The parameter t where the ray origin + t·direction crosses the polygon's plane at
/// a point inside the polygon; `None` if it does not, or lies in the plane.
pub fn ray_meets_polygon(origin: DVec3, direction: DVec3, polygon: &Polygon) -> Option<f64> {
    let n = polygon.normal;
    let across = direction.dot(n);
    if across == 0.0 {
        return None; // edge-on
    }
    let t = (polygon.vertices[0].position - origin).dot(n) / across;
    (t.is_finite() && contains(polygon, origin + direction * t)).then_some(t)
}

/// Whether the segment a→b crosses the polygon's plane strictly inside the segment,
/// at a point inside the polygon.
pub fn segment_meets_polygon(a: DVec3, b: DVec3, polygon: &Polygon) -> bool {
    let n = polygon.normal;
    let origin = polygon.vertices[0].position;
    let (da, db) = ((a - origin).dot(n), (b - origin).dot(n));
    if da * db >= 0.0 {
        return false; // both on one side, or one end on the plane
    }
    let t = da / (da - db);
    if !(END_MARGIN..=1.0 - END_MARGIN).contains(&t) {
        return false;
    }
    let hit = a + (b - a) * t;
    contains(polygon, hit)
}

/// Crossing-number test of a point of the polygon's plane, in the projection that
/// drops the normal's largest axis.
pub fn contains(polygon: &Polygon, p: DVec3) -> bool {
    let n = polygon.normal.abs();
    let drop = if n.x >= n.y && n.x >= n.z {
        0
    } else if n.y >= n.z {
        1
    } else {
        2
    };
    let flat = |v: DVec3| match drop {
        0 => DVec2::new(v.y, v.z),
        1 => DVec2::new(v.z, v.x),
        _ => DVec2::new(v.x, v.y),
    };
    let q = flat(p);
    let mut inside = false;
    let count = polygon.vertices.len();
    for i in 0..count {
        let (a, b) = (
            flat(polygon.vertices[i].position),
            flat(polygon.vertices[(i + 1) % count].position),
        );
        if (a.y > q.y) != (b.y > q.y) {
            let x = a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if x > q.x {
                inside = !inside;
            }
        }
    }
    inside
}

/// The shading normal (unit) and texture coordinates at a point `p` of the polygon,
/// by barycentric coordinates in a fan triangle (vertex 0, i, i + 1).
///
/// This is exact for triangles, and equals the scan-line pass's interpolation
/// wherever the attributes are affine over the polygon's plane (a parallelogram, any
/// flat-shaded polygon's normal): there every fan triangle gives the same values.
/// Elsewhere (a sphere's trapezoids with radial normals) the scan-line pass's
/// edge-and-span interpolation and the fan's differ a little inside the polygon,
/// agreeing on its edges.
///
/// Which triangle: fan triangles wound like the polygon (counter-clockwise about its
/// normal) tile a convex polygon; on a concave one, triangles wound the other way
/// cancel parts of them, and a point inside the polygon lies in at least one
/// counter-clockwise triangle. So the first counter-clockwise triangle, in fan order,
/// whose barycentric coordinates are all ≥ 0 is taken; if rounding leaves none (a
/// point on an edge), the counter-clockwise triangle with the largest smallest
/// coordinate, the one the point is nearest to being inside. Triangles of zero area
/// are passed over; a polygon with none left gives vertex 0's attributes.
pub fn interpolate(polygon: &Polygon, p: DVec3) -> (DVec3, DVec2) {
    let v = &polygon.vertices;
    let n = polygon.normal;
    let Some((i, w)) = fan_weights(v.len(), |k| v[k].position, n, p) else {
        return (v[0].normal, v[0].uv);
    };
    let (v0, v1, v2) = (&v[0], &v[i], &v[i + 1]);
    let normal = v0.normal * w[0] + v1.normal * w[1] + v2.normal * w[2];
    let uv = v0.uv * w[0] + v1.uv * w[1] + v2.uv * w[2];
    (normal.normalize_or(n), uv)
}

/// The fan triangle (vertex 0, i, i + 1) of a planar polygon of `count` vertices at
/// `position(k)` (unit normal `n`) that holds `p`, chosen as `interpolate` explains, and `p`'s barycentric coordinates in
/// it; `None` when every fan triangle has zero area.
pub fn fan_weights(
    count: usize,
    position: impl Fn(usize) -> DVec3,
    n: DVec3,
    p: DVec3,
) -> Option<(usize, [f64; 3])> {
    if count == 0 {
        return None;
    }
    let a = position(0);
    let mut best: Option<(f64, usize, [f64; 3])> = None;
    for i in 1..count.saturating_sub(1) {
        let (b, c) = (position(i), position(i + 1));
        let area = (b - a).cross(c - a).dot(n);
        if area <= 0.0 {
            continue;
        }
        let w = [
            (c - b).cross(p - b).dot(n) / area,
            (a - c).cross(p - c).dot(n) / area,
            (b - a).cross(p - a).dot(n) / area,
        ];
        let least = w[0].min(w[1]).min(w[2]);
        if least >= 0.0 {
            best = Some((least, i, w));
            break;
        }
        if best.is_none_or(|(l, _, _)| least > l) {
            best = Some((least, i, w));
        }
    }
    best.map(|(_, i, w)| (i, w))
}
