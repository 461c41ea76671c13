//! Shadows by casting a ray to the light: A. Appel, "Some techniques for shading
//! machine renderings of solids", AFIPS SJCC 1968, pp. 37–45.
//!
//! For each visible point, the segment from the point to the light is tested against
//! every other polygon of the scene; any hit strictly between them puts the point in
//! shadow. Appel tested against every polygon; here a bounding volume hierarchy (SAH)
//! prunes the polygons a segment cannot meet, which changes the cost, not the
//! answer. This is the reference the other hard-shadow methods are checked against.
//!
//! Choices: the receiving polygon is not tested (a planar polygon cannot shadow
//! itself); hits within a relative 1e-9 of either end are ignored, so a polygon
//! touching the point (a neighbour, a coincident polygon) or the light does not count;
//! a polygon seen edge-on from the point casts no shadow. Scene key:
//! `[shadows] method = "ray-cast"`.

use super::{BandShadows, FrameShadows, LightShadows, per_sample};
use crate::geometry::bvh::{Aabb, Bvh};
use crate::raster::{View, VisibleSurface};
use crate::scene::{Light, Polygon, Scene};
use glam::{DVec2, DVec3};
use std::sync::Arc;

/// Parametric margin at both ends of a shadow segment.
const END_MARGIN: f64 = 1e-9;

/// The scene's polygons in a hierarchy, ready for segment queries.
pub struct Occluders<'a> {
    polygons: &'a [Polygon],
    bvh: Bvh,
}

impl<'a> Occluders<'a> {
    pub fn new(polygons: &'a [Polygon]) -> Occluders<'a> {
        let boxes: Vec<Aabb> = polygons.iter().map(|p| Aabb::of(p.positions())).collect();
        Occluders {
            polygons,
            bvh: Bvh::build(&boxes),
        }
    }

    /// Whether a polygon other than `receiver` meets the segment strictly between
    /// `from` and `to`.
    pub fn blocked(&self, from: DVec3, to: DVec3, receiver: Option<u32>) -> bool {
        self.bvh.any_on_segment(from, to, |i| {
            Some(i) != receiver && segment_meets_polygon(from, to, &self.polygons[i as usize])
        })
    }
}

/// The scene's polygons and their hierarchy, owned, so that a renderer can keep
/// them between frames and share them between lights.
pub struct SceneOccluders {
    polygons: Vec<Polygon>,
    bvh: Bvh,
}

impl SceneOccluders {
    pub fn new(polygons: &[Polygon]) -> SceneOccluders {
        let boxes: Vec<Aabb> = polygons.iter().map(|p| Aabb::of(p.positions())).collect();
        SceneOccluders {
            polygons: polygons.to_vec(),
            bvh: Bvh::build(&boxes),
        }
    }

    /// Whether a polygon not in `skip` meets the segment strictly between `from`
    /// and `to`.
    pub fn blocked(&self, from: DVec3, to: DVec3, skip: &[u32]) -> bool {
        self.bvh.any_on_segment(from, to, |i| {
            !skip.contains(&i) && segment_meets_polygon(from, to, &self.polygons[i as usize])
        })
    }
}

/// Ray casting's pre-pass for one light: the scene's hierarchy (shared by all lights)
/// and the light.
pub struct RayCast {
    occluders: Arc<SceneOccluders>,
    light: Light,
}

impl RayCast {
    pub fn new(occluders: Arc<SceneOccluders>, light: Light) -> RayCast {
        RayCast { occluders, light }
    }
}

impl LightShadows for RayCast {
    fn frame<'a>(&'a self, scene: &'a Scene, view: &'a View) -> Box<dyn FrameShadows + 'a> {
        Box::new(RayCastFrame {
            cast: self,
            scene,
            view,
        })
    }
}

struct RayCastFrame<'a> {
    cast: &'a RayCast,
    scene: &'a Scene,
    view: &'a View,
}

impl FrameShadows for RayCastFrame<'_> {
    fn band(&self, band: &VisibleSurface) -> BandShadows {
        let occluders = &self.cast.occluders;
        let fractions = match &self.cast.light {
            Light::Point(l) => {
                let at = l.position;
                per_sample(self.scene, self.view, band, at, |_, polygon, position| {
                    !occluders.blocked(position, at, &[polygon])
                })
            }
            Light::Area(_) => unreachable!("refused by `prepare`"),
        };
        BandShadows::fraction(fractions)
    }
}

/// The visibility of the point light at `light` for every sample.
pub fn visibility(scene: &Scene, view: &View, surface: &VisibleSurface, light: DVec3) -> Vec<f32> {
    let occluders = Occluders::new(&scene.polygons);
    per_sample(scene, view, surface, light, |_, polygon, position| {
        !occluders.blocked(position, light, Some(polygon))
    })
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
