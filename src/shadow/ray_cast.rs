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

use super::per_sample;
use crate::raster::{View, VisibleSurface};
use crate::scene::ray_queries::SceneRays;
use crate::scene::{Polygon, Scene};
use glam::DVec3;

/// The scene's polygons in a hierarchy, ready for segment queries.
pub struct Occluders<'a>(SceneRays<'a>);

impl<'a> Occluders<'a> {
    pub fn new(polygons: &'a [Polygon]) -> Occluders<'a> {
        Occluders(SceneRays::new(polygons))
    }

    /// Whether a polygon other than `receiver` meets the segment strictly between
    /// `from` and `to`.
    pub fn blocked(&self, from: DVec3, to: DVec3, receiver: Option<u32>) -> bool {
        self.0.any_hit(from, to, receiver.as_slice())
    }
}

/// The visibility of the point light at `light` for every sample.
pub fn visibility(scene: &Scene, view: &View, surface: &VisibleSurface, light: DVec3) -> Vec<f32> {
    let occluders = Occluders::new(&scene.polygons);
    per_sample(scene, view, surface, light, |_, polygon, position| {
        !occluders.blocked(position, light, Some(polygon))
    })
}
