//! Soft shadows with shadow volumes: L. S. Brotman, N. I. Badler, "Generating soft
//! shadows with a depth buffer algorithm", IEEE Computer Graphics and Applications
//! 4(10):5–14, October 1984.
//!
//! The extended light is replaced by n points chosen at random over its area (one
//! seeded stream: every pixel uses the same points), each carrying 1/n of its
//! power. For each point, Crow's shadow volumes are built (`shadow_volumes`) and
//! counted along every pixel's line of sight against the depth the visible-surface
//! pass left; after each point's count, the pixel's `blocked` counter grows by one
//! where that count is positive. The level of shadow is blocked/n, so the penumbra
//! has n + 1 levels and at small n shows as n offset copies of the hard shadow.
//!
//! Shading variant (the paper's two readings: the visible fraction times the
//! unshadowed light, or the sum over the unblocked points): the sum over the
//! unblocked points of their own contributions (each point 1/n of the light's power,
//! with its cosines and distance to the sample), divided by the same sum over all n
//! points, times the exact unshadowed irradiance (Lambert's contour formula). A sample
//! no point is hidden from is lit exactly, points below its horizon bring nothing,
//! and the points' quadrature error falls on the penumbra only. The `blocked` buffer
//! holds the paper's count itself. A point below a sample's horizon counts as blocked
//! (Crow's self-shadow rule), as `shadow-volumes` has it: with n = 1 at the light's
//! centre this method is `shadow-volumes` bit for bit.
//!
//! Point and spot lights are one point already: their shadow is Crow's. Scene keys:
//! `[shadows] method = "soft-shadow-volumes"`, `light_points = n`, `seed`.

use super::shadow_volumes::ShadowVolumes;
use super::stencil_shadow_volumes::CountBuffer;
use super::{BandShadows, FrameShadows, LightShadows, faces_away};
use crate::geometry::sampling::Stream;
use crate::raster::{LightVisibility, View, VisibleSurface};
use crate::scene::LightKind;
use crate::scene::{Light, Scene};
use crate::settings::ShadowMethod;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::sync::Arc;

/// The registry's entry: polygon lights by points, and lights at a point.
pub(crate) static METHOD: super::Method = super::Method {
    method: ShadowMethod::SoftShadowVolumes,
    name: "soft-shadow-volumes",
    entry: Some("soft-shadow-volumes"),
    handles: "a soft-shadow method for polygon lights (and point and spot lights)",
    lights: &[LightKind::Point, LightKind::Spot, LightKind::Polygon],
    counts: Some(super::CountBuffer {
        prefix: "blocked",
        description: "points of light {l} hidden from each visible point (Brotman & Badler's count; colour-mapped)",
    }),
    budget: super::no_budget,
    warnings: super::no_warnings,
    prepare: |scene, index, settings, _| {
        let light = &scene.lights[index];
        let (n, seed) = (settings.light_points, settings.seed);
        let soft = SoftShadowVolumes::new(scene, light, index, n, seed).expect("checked");
        Some(Arc::new(soft))
    },
};

/// The pre-pass: one set of Crow's volumes per point of the light.
pub struct SoftShadowVolumes {
    points: Vec<ShadowVolumes>,
    /// The emitting side of a polygon light (its points' cosine).
    emitter: Option<DVec3>,
}

impl SoftShadowVolumes {
    /// `n` points at random over light `index` (stream `index` of `seed`); `None`
    /// for a light the method cannot shadow (distant, sphere).
    pub fn new(scene: &Scene, light: &Light, index: usize, n: u32, seed: u64) -> Option<Self> {
        let points = match light {
            Light::Point(_) | Light::Spot(_) => vec![light.position().expect("point-like")],
            Light::Polygon(l) => {
                let mut stream = Stream::new(seed, index as u64);
                (0..n)
                    .map(|_| {
                        let u = DVec2::new(stream.next_f64(), stream.next_f64());
                        l.point_at(u)
                    })
                    .collect()
            }
            Light::Distant(_) | Light::Sphere(_) => return None,
        };
        Some(SoftShadowVolumes::at_points(scene, light, &points))
    }

    /// The light replaced by the given points (tests place them by hand).
    pub fn at_points(scene: &Scene, light: &Light, points: &[DVec3]) -> SoftShadowVolumes {
        let emitter = match light {
            Light::Polygon(l) => Some(l.normal),
            Light::Point(_) | Light::Distant(_) | Light::Sphere(_) | Light::Spot(_) => None,
        };
        // A point of a polygon light lies on the light's own polygon, which casts no
        // volume from it.
        let volumes = |p: DVec3| match light {
            Light::Polygon(l) => ShadowVolumes::on_emitter(scene, p, l.polygon),
            Light::Point(_) | Light::Distant(_) | Light::Sphere(_) | Light::Spot(_) => {
                ShadowVolumes::new(scene, p)
            }
        };
        SoftShadowVolumes {
            points: points.par_iter().map(|&p| volumes(p)).collect(),
            emitter,
        }
    }
}

impl LightShadows for SoftShadowVolumes {
    fn frame<'a>(&'a self, scene: &'a Scene, view: &'a View) -> Box<dyn FrameShadows + 'a> {
        Box::new(SoftFrame {
            method: self,
            scene,
            view,
            frames: self
                .points
                .iter()
                .map(|p| p.count_buffer(scene, view))
                .collect(),
        })
    }
}

struct SoftFrame<'a> {
    method: &'a SoftShadowVolumes,
    scene: &'a Scene,
    view: &'a View,
    frames: Vec<CountBuffer<'a>>,
}

impl FrameShadows for SoftFrame<'_> {
    fn band(&self, band: &VisibleSurface) -> BandShadows {
        let len = band.samples.len();
        let mut blocked = vec![0i32; len];
        let mut clear = vec![0f64; len];
        let mut total = vec![0f64; len];
        for (volumes, frame) in self.method.points.iter().zip(&self.frames) {
            let at = volumes.light();
            let counts = frame.counts(band);
            band.samples
                .par_iter()
                .zip(&counts)
                .zip(blocked.par_iter_mut())
                .zip(clear.par_iter_mut().zip(total.par_iter_mut()))
                .for_each(|(((s, &count), blocked), (clear, total))| {
                    if s.is_empty() {
                        *blocked += 1;
                        return;
                    }
                    let hidden =
                        count > 0 || faces_away(self.scene, self.view, s.polygon, s.position, at);
                    let w = self.weight(s.polygon, s.position, at);
                    *total += w;
                    if hidden {
                        *blocked += 1;
                    } else {
                        *clear += w;
                    }
                });
        }
        // A sample no point shines on (behind the emitter's plane, or below its own
        // horizon: every weight zero, and so for an empty sample) gets nothing; the
        // unweighted fraction of points it sees would call it lit and hide a wrong
        // sign.
        let visibility = (0..len)
            .map(|k| {
                if total[k] > 0.0 {
                    (clear[k] / total[k]) as f32
                } else {
                    0.0
                }
            })
            .collect();
        BandShadows {
            visibility: LightVisibility::Fraction(visibility),
            counts: Some(blocked),
        }
    }
}

impl SoftFrame<'_> {
    /// A point's contribution to the irradiance at a sample, but for the light's
    /// radiance and area: cos θ_light cos θ_sample / d² (1 for a point light).
    fn weight(&self, polygon: u32, position: DVec3, at: DVec3) -> f64 {
        let Some(normal) = self.method.emitter else {
            return 1.0;
        };
        let mut n = self.scene.polygons[polygon as usize].normal;
        if n.dot(self.view.eye - position) < 0.0 {
            n = -n;
        }
        let d = at - position;
        let r2 = d.length_squared();
        let w = n.dot(d).max(0.0) * normal.dot(-d).max(0.0) / (r2 * r2);
        if w.is_finite() { w } else { 0.0 }
    }
}
