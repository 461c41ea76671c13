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

use super::{BandShadows, FrameShadows, LightShadows, faces_away, per_sample};
use crate::geometry::bvh::Aabb;
use crate::geometry::sampling::Stream;
use crate::raster::{NO_POLYGON, View, VisibleSurface};
use crate::scene::LightKind;
use crate::scene::ray_queries::SceneRays;
use crate::scene::{Light, Reach, Scene};
use crate::settings::ShadowMethod;
use rayon::prelude::*;
use std::sync::Arc;

/// The registry's entry: every light, extended ones by stratified samples.
pub(crate) static METHOD: super::Method = super::Method {
    method: ShadowMethod::RayCast,
    name: "ray-cast",
    entry: Some("ray-cast-shadows"),
    handles: "a method for every light",
    lights: &LightKind::ALL,
    counts: None,
    budget: super::no_budget,
    warnings: super::no_warnings,
    prepare: |scene, index, settings, shared| {
        Some(Arc::new(RayCast::new(
            shared.occluders(),
            scene.lights[index].clone(),
            index,
            settings.light_samples,
        )))
    },
};

/// The scene's polygons and their hierarchy, owned, so that a renderer can keep them
/// between frames and share them between lights.
pub type SceneOccluders = SceneRays<'static>;

/// Ray casting's pre-pass for one light: the scene's hierarchy (shared by all lights)
/// and the light.
pub struct RayCast {
    occluders: Arc<SceneOccluders>,
    light: Light,
    /// The light's index: the seed of its sample streams.
    index: usize,
    /// N × N stratified samples over an extended light.
    samples: u32,
    /// How far back along a distant light's travel its shadow rays go: beyond the
    /// scene.
    reach: f64,
}

impl RayCast {
    pub fn new(
        occluders: Arc<SceneOccluders>,
        light: Light,
        index: usize,
        samples: u32,
    ) -> RayCast {
        let bounds = Aabb::of(occluders.polygons().iter().flat_map(|p| p.positions()));
        let diagonal = (bounds.max - bounds.min).length();
        RayCast {
            occluders,
            light,
            index,
            samples,
            reach: 4.0 * diagonal.max(1.0),
        }
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
        let fractions = match self.cast.light.reach() {
            Reach::Point { at, .. } => {
                per_sample(self.scene, self.view, band, at, |_, polygon, position| {
                    !occluders.any_hit(position, at, &[polygon])
                })
            }
            Reach::Direction { direction, .. } => {
                let back = -direction * self.cast.reach;
                (0..band.samples.len())
                    .into_par_iter()
                    .map(|k| {
                        let s = &band.samples[k];
                        let lit = !s.is_empty()
                            && !faces_away(
                                self.scene,
                                self.view,
                                s.polygon,
                                s.position,
                                s.position + back,
                            )
                            && !occluders.any_hit(s.position, s.position + back, &[s.polygon]);
                        if lit { 1.0 } else { 0.0 }
                    })
                    .collect()
            }
            Reach::Extended { .. } => (0..band.samples.len())
                .into_par_iter()
                .map(|k| self.extended(band, k))
                .collect(),
        };
        BandShadows::fraction(fractions)
    }
}

impl RayCastFrame<'_> {
    /// The visible share of an extended light at sample `k` (Cook, Porter & Carpenter
    /// 1984): N × N jittered samples over the emitter, from a stream seeded by the
    /// light and the sample's place on the grid (the same whatever the band or the
    /// thread), each weighted by its share of the unoccluded irradiance; the share of
    /// that weight whose segment is clear. Shading multiplies the exact unoccluded
    /// irradiance (Lambert's contour formula, the sphere's form factor) by it, so lit
    /// regions are exact and the penumbra converges as N grows. A sample no part of
    /// the light reaches keeps the exact value (weight 1): it has no evidence of an
    /// occluder.
    fn extended(&self, band: &VisibleSurface, k: usize) -> f32 {
        let s = &band.samples[k];
        if s.is_empty() {
            return 0.0;
        }
        let cast = self.cast;
        let (x, y) = band.position_of(k);
        let mut stream = Stream::new(cast.index as u64, y as u64 * band.width as u64 + x as u64);
        let mut n = self.scene.polygons[s.polygon as usize].normal;
        if n.dot(self.view.eye - s.position) < 0.0 {
            n = -n;
        }
        let emitter = cast
            .light
            .emitter_polygon()
            .map_or(NO_POLYGON, |p| p as u32);
        let (mut total, mut clear) = (0.0, 0.0);
        for u in stream.jittered(cast.samples as usize) {
            let Some(sample) = cast.light.sample(s.position, u) else {
                continue;
            };
            let d = sample.point - s.position;
            let w = sample.weight * n.dot(d).max(0.0) / d.length();
            if w <= 0.0 || !w.is_finite() {
                continue;
            }
            total += w;
            if !cast
                .occluders
                .any_hit(s.position, sample.point, &[s.polygon, emitter])
            {
                clear += w;
            }
        }
        if total > 0.0 {
            (clear / total) as f32
        } else {
            1.0
        }
    }
}
