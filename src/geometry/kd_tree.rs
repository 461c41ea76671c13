//! A balanced kd-tree of points (J. L. Bentley, "Multidimensional binary search
//! trees used for associative searching", CACM 18(9), 1975), as Jensen's photon
//! map keeps its photons: built once, each node splitting its points at their
//! median along the axis of their largest extent, so the tree is balanced whatever
//! the points' order; searched for the k nearest points of a position with a
//! max-heap of the best found, whose worst distance narrows the search.
//!
//! Layout: the points reordered in place, every subtree a contiguous slice with its
//! median node in the middle (an implicit tree: no pointers). Jensen stored the
//! same balanced tree in heap order; the slice layout needs no left-balancing.

use glam::DVec3;
use std::collections::BinaryHeap;

/// Points with their payloads, in a balanced kd-tree.
pub struct KdTree<T> {
    items: Vec<(DVec3, T)>,
    /// The axis each node splits at (0, 1, 2), by the node's index.
    axes: Vec<u8>,
}

/// A neighbour found: its squared distance and its index in `KdTree::items`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Neighbour {
    pub distance2: f64,
    pub index: usize,
}

impl<T> KdTree<T> {
    /// The tree of `items`, balanced by median splits.
    pub fn build(mut items: Vec<(DVec3, T)>) -> KdTree<T> {
        let mut axes = vec![0u8; items.len()];
        balance(&mut items, &mut axes);
        KdTree { items, axes }
    }

    /// The points and payloads, in the tree's order.
    pub fn items(&self) -> &[(DVec3, T)] {
        &self.items
    }

    pub fn len(&self) -> usize {
        self.items.len()
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// The `k` points nearest `x` (fewer if the tree holds fewer), into `found`
    /// (cleared first), in no particular order.
    pub fn nearest(&self, x: DVec3, k: usize, found: &mut Vec<Neighbour>) {
        found.clear();
        if k == 0 {
            return;
        }
        let mut heap = BinaryHeap::with_capacity(k + 1);
        let mut worst = f64::INFINITY;
        self.walk(
            0,
            self.items.len(),
            x,
            &mut worst,
            &mut |index, distance2, worst| {
                // Non-negative floats order as their bits do.
                let entry = Farthest(distance2.to_bits(), index);
                if heap.len() < k {
                    heap.push(entry);
                    if heap.len() == k {
                        *worst = f64::from_bits(heap.peek().map_or(0, |f| f.0));
                    }
                } else if distance2 < *worst {
                    // The farthest kept gives way: one sift instead of a push and a pop.
                    if let Some(mut top) = heap.peek_mut() {
                        *top = entry;
                    }
                    *worst = f64::from_bits(heap.peek().map_or(0, |f| f.0));
                }
            },
        );
        found.extend(heap.into_iter().map(|Farthest(bits, index)| Neighbour {
            distance2: f64::from_bits(bits),
            index,
        }));
    }

    /// The point nearest `x` among those whose payload `accept`s, if any: one
    /// best-so-far distance instead of a heap, the subtrees beyond it skipped.
    pub fn nearest_where(&self, x: DVec3, accept: impl Fn(&T) -> bool) -> Option<Neighbour> {
        let mut best = None;
        let mut worst = f64::INFINITY;
        self.walk(
            0,
            self.items.len(),
            x,
            &mut worst,
            &mut |index, distance2, worst| {
                if distance2 < *worst && accept(&self.items[index].1) {
                    *worst = distance2;
                    best = Some(Neighbour { distance2, index });
                }
            },
        );
        best
    }

    /// Visits the nodes of the subtree `low..high` near `x`, the nearer side of
    /// each split first, with each node's index and squared distance; a far side
    /// is skipped when its splitting plane lies beyond `worst` (which `visit`
    /// narrows).
    fn walk(
        &self,
        low: usize,
        high: usize,
        x: DVec3,
        worst: &mut f64,
        visit: &mut impl FnMut(usize, f64, &mut f64),
    ) {
        if low >= high {
            return;
        }
        let middle = low + (high - low) / 2;
        let (point, _) = &self.items[middle];
        let axis = self.axes[middle] as usize;
        let delta = x[axis] - point[axis];
        let (near, far) = if delta < 0.0 {
            ((low, middle), (middle + 1, high))
        } else {
            ((middle + 1, high), (low, middle))
        };
        self.walk(near.0, near.1, x, worst, visit);
        visit(middle, x.distance_squared(*point), worst);
        if delta * delta < *worst {
            self.walk(far.0, far.1, x, worst, visit);
        }
    }
}

/// A heap entry ordered by distance, the farthest on top.
#[derive(PartialEq, Eq, PartialOrd, Ord)]
struct Farthest(u64, usize);

/// Puts the median along the widest axis in the middle of `items`, the smaller
/// before it and the larger after, and does the same in each half.
fn balance<T>(items: &mut [(DVec3, T)], axes: &mut [u8]) {
    if items.len() <= 1 {
        return;
    }
    let (low, high) = items.iter().fold(
        (DVec3::INFINITY, DVec3::NEG_INFINITY),
        |(low, high), (p, _)| (low.min(*p), high.max(*p)),
    );
    let extent = high - low;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let middle = items.len() / 2;
    items.select_nth_unstable_by(middle, |a, b| a.0[axis].total_cmp(&b.0[axis]));
    axes[middle] = axis as u8;
    let (left, rest) = items.split_at_mut(middle);
    let (left_axes, rest_axes) = axes.split_at_mut(middle);
    balance(left, left_axes);
    balance(&mut rest[1..], &mut rest_axes[1..]);
}
