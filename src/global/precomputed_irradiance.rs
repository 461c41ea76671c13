//! Precomputed irradiance (P. H. Christensen, "Faster photon map global
//! illumination", Journal of Graphics Tools 4(3):1–10, 1999): a variant of
//! Jensen's photon map kept beside it, chosen by `[global] precomputed_irradiance
//! = true`.
//!
//! Jensen's final gather reads the global map's radiance estimate at every
//! gather ray's end: a search for the k nearest photons each time, almost all of
//! pass 2's work. Christensen noticed that the estimate a gather ray needs is
//! smooth and that the photons themselves sit where it is needed. So, once the
//! map is built, the irradiance estimate is computed at a fraction of the
//! photons' positions (with the normal of the surface each was stored on) and
//! kept in a second balanced kd-tree; a gather ray then reads the irradiance of
//! the nearest of those points whose normal agrees with the surface's (their dot
//! product above 0.9), one small search instead of a k-nearest estimate.
//!
//! Chosen here where the paper leaves it open: every fourth photon is a point
//! (his example); the search is for the nearest point whose normal agrees, however
//! far (the kd-tree skips the others as it goes), and where no point's does the
//! full estimate is made there;
//! irradiance is kept, not radiance, so the reflectance (a texture's too) is read
//! at the gather ray's own end.

use super::photon_map::PhotonMap;
use crate::geometry::kd_tree::KdTree;
use glam::{DVec3, Vec3};
use rayon::prelude::*;

/// One photon in this many carries a precomputed irradiance.
pub const EVERY: usize = 4;
/// A point serves a surface whose normal is within this cosine of its own.
pub const NORMAL_AGREEMENT: f64 = 0.9;

/// Irradiance estimates at a fraction of a map's photons, in a kd-tree.
pub struct PrecomputedIrradiance {
    tree: KdTree<(DVec3, Vec3)>,
}

impl PrecomputedIrradiance {
    /// The estimate of `map` with `k` photons at every `EVERY`th photon's position,
    /// on the side of the surface it arrived at.
    pub fn new(map: &PhotonMap, k: usize) -> PrecomputedIrradiance {
        let points = map
            .photons()
            .par_iter()
            .step_by(EVERY)
            .map(|(position, photon)| {
                (
                    *position,
                    (photon.normal, map.irradiance(*position, photon.normal, k)),
                )
            })
            .collect();
        PrecomputedIrradiance {
            tree: KdTree::build(points),
        }
    }

    /// Points held.
    pub fn len(&self) -> usize {
        self.tree.len()
    }

    pub fn is_empty(&self) -> bool {
        self.tree.is_empty()
    }

    /// The irradiance of the nearest point to `x` whose normal agrees with unit
    /// `normal`; `None` when no point's does.
    pub fn irradiance(&self, x: DVec3, normal: DVec3) -> Option<Vec3> {
        let found = self
            .tree
            .nearest_where(x, |(n, _)| n.dot(normal) > NORMAL_AGREEMENT)?;
        Some(self.tree.items()[found.index].1.1)
    }
}
