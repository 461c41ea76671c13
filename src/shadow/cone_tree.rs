//! A bounding hierarchy over cones of directions, so that the scan-line shadows'
//! pre-pass finds the casters whose extent on the light's sphere may overlap a
//! receiver's without testing every pair: the pairwise test stays the judge, the tree
//! only spares the pairs that certainly fail it (a cost, not a result).
//!
//! Each node bounds the axes of its cones (unit vectors) by a box in 3D and keeps the
//! widest half-angle among them. A cone of half-angle θ about `a` can overlap a cone
//! of the node only if some axis `c` in the box has angle(a, c) ≤ θ + widest; for
//! unit vectors a · c = 1 − |a − c|² / 2, so the box's nearest point to `a` bounds
//! that dot product from above. Nodes split at the median of their widest extent.

use glam::DVec3;

/// Cones per leaf: below this, testing each is cheaper than descending.
const LEAF: usize = 16;

/// Slack on the pruning test, far above the rounding of the pairwise test it guards
/// (its cosines are within a few 1e-16), so no pair that test accepts is pruned.
const SLACK: f64 = 1e-9;

struct Node {
    lo: DVec3,
    hi: DVec3,
    /// The widest half-angle of the node's cones.
    widest: f64,
    /// The node's cones: `order[first..last]`.
    first: u32,
    last: u32,
    /// Index of the second child; the first follows the node. None for a leaf.
    second: Option<u32>,
}

pub struct ConeTree {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

impl ConeTree {
    /// The tree over cones given as (axis, half-angle), axes of unit length.
    pub fn new(cones: &[(DVec3, f64)]) -> ConeTree {
        let mut tree = ConeTree {
            nodes: Vec::with_capacity(2 * cones.len() / LEAF + 1),
            order: (0..cones.len() as u32).collect(),
        };
        if !cones.is_empty() {
            tree.build(cones, 0, cones.len());
        }
        tree
    }

    fn build(&mut self, cones: &[(DVec3, f64)], first: usize, last: usize) {
        let members = &mut self.order[first..last];
        let (mut lo, mut hi, mut widest) = (DVec3::INFINITY, DVec3::NEG_INFINITY, 0.0f64);
        for &i in members.iter() {
            let (axis, half_angle) = cones[i as usize];
            lo = lo.min(axis);
            hi = hi.max(axis);
            widest = widest.max(half_angle);
        }
        let at = self.nodes.len();
        self.nodes.push(Node {
            lo,
            hi,
            widest,
            first: first as u32,
            last: last as u32,
            second: None,
        });
        if last - first <= LEAF {
            return;
        }
        let extent = hi - lo;
        let dimension = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        let middle = (last - first) / 2;
        members.select_nth_unstable_by(middle, |&a, &b| {
            cones[a as usize].0[dimension].total_cmp(&cones[b as usize].0[dimension])
        });
        self.build(cones, first, first + middle);
        let second = self.nodes.len() as u32;
        self.nodes[at].second = Some(second);
        self.build(cones, first + middle, last);
    }

    /// Calls `f(i)` for every cone i that may overlap the cone (axis, half-angle):
    /// every cone that overlaps it, and some that do not.
    pub fn candidates(&self, axis: DVec3, half_angle: f64, mut f: impl FnMut(u32)) {
        let mut stack = vec![0usize];
        while let Some(at) = stack.pop() {
            let Some(node) = self.nodes.get(at) else {
                continue;
            };
            if !self.may_overlap(node, axis, half_angle) {
                continue;
            }
            match node.second {
                None => self.order[node.first as usize..node.last as usize]
                    .iter()
                    .for_each(|&i| f(i)),
                Some(second) => {
                    stack.push(second as usize);
                    stack.push(at + 1);
                }
            }
        }
    }

    fn may_overlap(&self, node: &Node, axis: DVec3, half_angle: f64) -> bool {
        let reach = half_angle + node.widest;
        if reach >= std::f64::consts::PI {
            return true;
        }
        let nearest = axis.clamp(node.lo, node.hi);
        let greatest_dot = 1.0 - 0.5 * axis.distance_squared(nearest);
        greatest_dot >= reach.cos() - SLACK
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn direction(k: u32) -> DVec3 {
        // A deterministic spread of directions and angles.
        let t = k as f64;
        let (u, v) = ((t * 0.618_034).fract(), (t * 0.414_214).fract());
        let z = 2.0 * u - 1.0;
        let r = (1.0 - z * z).sqrt();
        let phi = 2.0 * std::f64::consts::PI * v;
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    #[test]
    fn every_overlapping_cone_is_a_candidate() {
        let cones: Vec<(DVec3, f64)> = (0..2000)
            .map(|k| {
                (
                    direction(k),
                    0.001 + 0.2 * ((k as f64 * 0.37).fract().powi(4)),
                )
            })
            .collect();
        let tree = ConeTree::new(&cones);
        let mut pruned = 0;
        for q in 0..300u32 {
            let (axis, angle) = (direction(5000 + q), 0.05 * (q % 7) as f64);
            let mut found = vec![false; cones.len()];
            tree.candidates(axis, angle, |i| found[i as usize] = true);
            for (i, &(c, a)) in cones.iter().enumerate() {
                let overlaps = axis.dot(c).clamp(-1.0, 1.0).acos() <= angle + a;
                assert!(
                    !overlaps || found[i],
                    "cone {i} overlaps query {q} but was pruned"
                );
                pruned += usize::from(!found[i]);
            }
        }
        // The tree must also spare work: most of the 600,000 pairs are pruned.
        assert!(pruned > 500_000, "only {pruned} pairs pruned");
    }
}
