//! Form factors from Lambert's contour formula (J. H. Lambert, *Photometria*, 1760):
//! the exact point-to-polygon factor F = Φ/π, Φ the receiver's projected solid angle
//! above the point's tangent plane (`geometry::lambert_contour`). It is the reference
//! the hemi-cube and Nusselt estimates are measured against.
//!
//! Occlusion: Lambert's formula knows nothing of what lies between, so the factor is
//! weighted by the fraction of a few points of the receiver (its centre, and the
//! points halfway from the centre to each corner) that the point sees through the
//! scene. Choice left open: this all-or-nothing-per-point test is exact for
//! unoccluded pairs (the test configurations) and an approximation in partial shadow.

use super::receivers::Receivers;
use crate::geometry::lambert_contour::form_factor;
use crate::scene::ray_queries::SceneRays;
use glam::DVec3;

pub struct Analytic<'a> {
    /// The scene's polygons, for the occlusion test.
    pub occluders: SceneRays<'a>,
}

impl Analytic<'_> {
    pub fn factors(
        &self,
        centre: DVec3,
        normal: DVec3,
        receivers: &Receivers,
        skip: &(dyn Fn(usize) -> bool + Sync),
    ) -> Vec<f64> {
        (0..receivers.len())
            .map(|r| {
                if skip(r) || !receivers.faces(r, centre) {
                    return 0.0;
                }
                let corners: Vec<DVec3> = receivers.polygons[r].positions().collect();
                let f = form_factor(centre, normal, &corners);
                if f == 0.0 {
                    return 0.0;
                }
                f * self.visible_fraction(centre, receivers.centres[r], &corners)
            })
            .collect()
    }

    fn visible_fraction(&self, from: DVec3, centre: DVec3, corners: &[DVec3]) -> f64 {
        let targets = std::iter::once(centre).chain(corners.iter().map(|&c| 0.5 * (c + centre)));
        let (mut seen, mut count) = (0, 0);
        for target in targets {
            count += 1;
            if !self.occluders.any_hit(from, target, &[]) {
                seen += 1;
            }
        }
        seen as f64 / count as f64
    }
}
