//! The Nusselt analog, counted: the course's \[SIEG84\] method (R. Siegel, J. R.
//! Howell, *Thermal Radiation Heat Transfer*, 1981 / 1984).
//!
//! The form factor from a point to a surface equals the fraction of the unit disc
//! (the base of the unit hemisphere around the point) covered by the surface's
//! projection, first onto the hemisphere (central projection) and then onto the base
//! (orthographic). Counted numerically: the base square [−1, 1]² is cut into an
//! N × N grid; each cell centre inside the disc is lifted onto the hemisphere, and
//! the ray from the point through it finds the nearest receiver, which gets the
//! cell. F_j is the number of cells receiver j gets over the number inside the disc.
//!
//! Choice left open: the disc is sampled at the centres of a regular grid (not at
//! random), so the estimate is deterministic and converges as N grows.

use super::receivers::Receivers;
use crate::scene::ray_queries::contains;
use glam::DVec3;

#[derive(Clone, Debug)]
pub struct Nusselt {
    /// Cells along each side of the base square.
    pub resolution: u32,
}

impl Nusselt {
    /// F from the point `centre` (unit normal `normal`) to every receiver; receivers
    /// for which `skip` holds are ignored.
    pub fn factors(
        &self,
        centre: DVec3,
        normal: DVec3,
        receivers: &Receivers,
        skip: &(dyn Fn(usize) -> bool + Sync),
    ) -> Vec<f64> {
        let (t, b) = normal.any_orthonormal_pair();
        let n = self.resolution.max(1);
        let cell = 2.0 / n as f64;
        let reach = receivers_extent(receivers);
        let mut counts = vec![0u64; receivers.len()];
        let mut inside = 0u64;
        for j in 0..n {
            for i in 0..n {
                let (x, y) = (
                    -1.0 + (i as f64 + 0.5) * cell,
                    -1.0 + (j as f64 + 0.5) * cell,
                );
                let rho2 = x * x + y * y;
                if rho2 >= 1.0 {
                    continue;
                }
                inside += 1;
                let direction = t * x + b * y + normal * (1.0 - rho2).sqrt();
                if let Some(r) = nearest(receivers, centre, direction * reach, skip)
                    && receivers.faces(r, centre)
                {
                    counts[r] += 1;
                }
            }
        }
        counts
            .into_iter()
            .map(|c| c as f64 / inside.max(1) as f64)
            .collect()
    }
}

/// The diagonal of the receivers' bounding box: no ray needs to go further.
fn receivers_extent(receivers: &Receivers) -> f64 {
    let b = crate::geometry::bvh::Aabb::of(receivers.polygons.iter().flat_map(|p| p.positions()));
    2.0 * (b.max - b.min).length()
}

/// The receiver the segment from `from` along `offset` meets first.
fn nearest(
    receivers: &Receivers,
    from: DVec3,
    offset: DVec3,
    skip: &(dyn Fn(usize) -> bool + Sync),
) -> Option<usize> {
    let mut best: Option<(f64, usize)> = None;
    receivers.bvh().any_on_segment(from, from + offset, |r| {
        let r = r as usize;
        if skip(r) {
            return false;
        }
        let polygon = &receivers.polygons[r];
        let n = polygon.normal;
        let denominator = offset.dot(n);
        if denominator == 0.0 {
            return false;
        }
        let s = (polygon.vertices[0].position - from).dot(n) / denominator;
        if s > 1e-12
            && s <= 1.0
            && best.is_none_or(|(b, _)| s < b)
            && contains(polygon, from + offset * s)
        {
            best = Some((s, r));
        }
        false
    });
    best.map(|(_, r)| r)
}
