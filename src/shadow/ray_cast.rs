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
use crate::raster::{View, VisibleSurface};
use crate::scene::ray_queries::SceneRays;
use crate::scene::{Light, Polygon, Scene};
use glam::DVec3;
use std::sync::Arc;

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

/// The scene's polygons and their hierarchy, owned, so that a renderer can keep them
/// between frames and share them between lights.
pub type SceneOccluders = SceneRays<'static>;

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
                    !occluders.any_hit(position, at, &[polygon])
                })
            }
            Light::Area(_) => unreachable!("refused by `prepare`"),
        };
        BandShadows::fraction(fractions)
    }
}
