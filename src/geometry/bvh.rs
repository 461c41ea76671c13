//! A bounding volume hierarchy over the scene's polygons, built by the surface area
//! heuristic (MacDonald & Booth 1990) with binned splits (Wald 2007). Two queries:
//! does anything block the segment between two points (`any_on_segment`, stopping at
//! the first hit), and which item does a ray meet first (`closest_on_ray`, children
//! visited near-first, boxes beyond the nearest hit so far pruned).

use glam::DVec3;

/// Axis-aligned box.
#[derive(Clone, Copy, Debug)]
pub struct Aabb {
    pub min: DVec3,
    pub max: DVec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: DVec3::splat(f64::INFINITY),
        max: DVec3::splat(f64::NEG_INFINITY),
    };

    pub fn of(points: impl IntoIterator<Item = DVec3>) -> Aabb {
        points.into_iter().fold(Aabb::EMPTY, |b, p| Aabb {
            min: b.min.min(p),
            max: b.max.max(p),
        })
    }

    /// Whether the two boxes share a point (touching counts).
    pub fn overlaps(&self, other: &Aabb) -> bool {
        self.min.cmple(other.max).all() && other.min.cmple(self.max).all()
    }

    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    fn surface_area(&self) -> f64 {
        let d = (self.max - self.min).max(DVec3::ZERO);
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    fn centre(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }

    /// Whether the segment origin + t·direction, t in [0, 1], meets the box
    /// (slab test; `inverse` is 1/direction per axis).
    fn meets_segment(&self, origin: DVec3, inverse: DVec3) -> bool {
        let t0 = (self.min - origin) * inverse;
        let t1 = (self.max - origin) * inverse;
        let near = t0.min(t1).max_element().max(0.0);
        let far = t0.max(t1).min_element().min(1.0);
        near <= far
    }

    /// Where the ray origin + t·direction, t in [t_min, t_max], enters the box, or
    /// `None` if it misses it (`inverse` is 1/direction per axis).
    fn ray_entry(&self, origin: DVec3, inverse: DVec3, t_min: f64, t_max: f64) -> Option<f64> {
        let t0 = (self.min - origin) * inverse;
        let t1 = (self.max - origin) * inverse;
        let near = t0.min(t1).max_element().max(t_min);
        let far = t0.max(t1).min_element().min(t_max);
        (near <= far).then_some(near)
    }
}

enum Node {
    Leaf {
        bounds: Aabb,
        first: u32,
        count: u32,
    },
    Inner {
        bounds: Aabb,
        left: u32,
        right: u32,
    },
}

/// A hierarchy over items given by their boxes; queries return item indices.
pub struct Bvh {
    nodes: Vec<Node>,
    /// Item indices, leaves referring to runs of them.
    items: Vec<u32>,
}

const BINS: usize = 16;
const MAX_LEAF: usize = 4;

impl Bvh {
    pub fn build(boxes: &[Aabb]) -> Bvh {
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * boxes.len()),
            items: (0..boxes.len() as u32).collect(),
        };
        if !boxes.is_empty() {
            bvh.split(boxes, 0, boxes.len());
        }
        bvh
    }

    /// Builds the node over items[first..first + count]; returns its index.
    fn split(&mut self, boxes: &[Aabb], first: usize, count: usize) -> u32 {
        let range = first..first + count;
        let bounds = self.items[range.clone()]
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.union(&boxes[i as usize]));
        let index = self.nodes.len() as u32;
        self.nodes.push(Node::Leaf {
            bounds,
            first: first as u32,
            count: count as u32,
        });
        if count <= MAX_LEAF {
            return index;
        }
        let Some(mid) = self.partition(boxes, first, count) else {
            return index;
        };
        let left = self.split(boxes, first, mid - first);
        let right = self.split(boxes, mid, first + count - mid);
        self.nodes[index as usize] = Node::Inner {
            bounds,
            left,
            right,
        };
        index
    }

    /// The cheapest binned SAH split of items[first..first + count], applied; the
    /// index where the right half starts, or `None` when no split beats a leaf.
    fn partition(&mut self, boxes: &[Aabb], first: usize, count: usize) -> Option<usize> {
        let items = &mut self.items[first..first + count];
        let centres = Aabb::of(items.iter().map(|&i| boxes[i as usize].centre()));
        let extent = centres.max - centres.min;
        let axis = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        if extent[axis] <= 0.0 {
            return None;
        }
        let bin_of = |i: u32| {
            let c = boxes[i as usize].centre()[axis];
            (((c - centres.min[axis]) / extent[axis] * BINS as f64) as usize).min(BINS - 1)
        };
        let mut bins = [(Aabb::EMPTY, 0usize); BINS];
        for &i in items.iter() {
            let b = &mut bins[bin_of(i)];
            *b = (b.0.union(&boxes[i as usize]), b.1 + 1);
        }
        // Cost of splitting after bin k: area-weighted counts of both sides.
        let mut best = (f64::INFINITY, 0);
        for k in 0..BINS - 1 {
            let side = |r: &[(Aabb, usize)]| {
                r.iter()
                    .fold((Aabb::EMPTY, 0), |(b, n), (bb, nn)| (b.union(bb), n + nn))
            };
            let ((lb, ln), (rb, rn)) = (side(&bins[..=k]), side(&bins[k + 1..]));
            if ln == 0 || rn == 0 {
                continue;
            }
            let cost = lb.surface_area() * ln as f64 + rb.surface_area() * rn as f64;
            if cost < best.0 {
                best = (cost, k);
            }
        }
        let whole = Aabb::of(
            items
                .iter()
                .flat_map(|&i| [boxes[i as usize].min, boxes[i as usize].max]),
        );
        if best.0 >= whole.surface_area() * count as f64 {
            return None;
        }
        let mut left = 0;
        for j in 0..items.len() {
            if bin_of(items[j]) <= best.1 {
                items.swap(j, left);
                left += 1;
            }
        }
        Some(first + left)
    }

    /// Whether `hit(item)` holds for an item whose box meets the segment from `a`
    /// to `b`; stops at the first.
    pub fn any_on_segment(&self, a: DVec3, b: DVec3, mut hit: impl FnMut(u32) -> bool) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let inverse = DVec3::ONE / (b - a);
        let mut stack = vec![0u32];
        while let Some(n) = stack.pop() {
            match &self.nodes[n as usize] {
                Node::Leaf {
                    bounds,
                    first,
                    count,
                } => {
                    if bounds.meets_segment(a, inverse)
                        && self.items[*first as usize..(*first + *count) as usize]
                            .iter()
                            .any(|&i| hit(i))
                    {
                        return true;
                    }
                }
                Node::Inner {
                    bounds,
                    left,
                    right,
                } => {
                    if bounds.meets_segment(a, inverse) {
                        stack.push(*left);
                        stack.push(*right);
                    }
                }
            }
        }
        false
    }

    /// The nearest item the ray origin + t·direction meets for t in [t_min, t_max],
    /// with its parameter. `hit(item)` gives the parameter where the ray meets the
    /// item itself, if it does; parameters outside [t_min, t_max] are ignored. Of
    /// equal parameters the smaller item index wins, so the answer does not depend on
    /// the order of the traversal.
    pub fn closest_on_ray(
        &self,
        origin: DVec3,
        direction: DVec3,
        t_min: f64,
        t_max: f64,
        mut hit: impl FnMut(u32) -> Option<f64>,
    ) -> Option<(u32, f64)> {
        if self.nodes.is_empty() || t_min > t_max {
            return None;
        }
        let inverse = DVec3::ONE / direction;
        let mut best: Option<(u32, f64)> = None;
        let limit = |best: &Option<(u32, f64)>| best.map_or(t_max, |b| b.1);
        let mut stack = Vec::with_capacity(64);
        if let Some(entry) = self.nodes[0]
            .bounds()
            .ray_entry(origin, inverse, t_min, t_max)
        {
            stack.push((0u32, entry));
        }
        while let Some((n, entry)) = stack.pop() {
            // A box entered beyond the nearest hit so far cannot hold a nearer one.
            if entry > limit(&best) {
                continue;
            }
            match &self.nodes[n as usize] {
                Node::Leaf { first, count, .. } => {
                    for &i in &self.items[*first as usize..(*first + *count) as usize] {
                        let Some(t) = hit(i) else { continue };
                        if !(t_min..=t_max).contains(&t) {
                            continue;
                        }
                        let nearer = match best {
                            None => true,
                            Some((j, b)) => t < b || (t == b && i < j),
                        };
                        if nearer {
                            best = Some((i, t));
                        }
                    }
                }
                Node::Inner { left, right, .. } => {
                    let t_far = limit(&best);
                    let enter = |c: u32| {
                        self.nodes[c as usize]
                            .bounds()
                            .ray_entry(origin, inverse, t_min, t_far)
                            .map(|e| (c, e))
                    };
                    let (l, r) = (enter(*left), enter(*right));
                    // Pushed far child first, so the near one is visited first.
                    match (l, r) {
                        (Some(a), Some(b)) => {
                            let (near, far) = if a.1 <= b.1 { (a, b) } else { (b, a) };
                            stack.push(far);
                            stack.push(near);
                        }
                        (Some(a), None) | (None, Some(a)) => stack.push(a),
                        (None, None) => {}
                    }
                }
            }
        }
        best
    }
}

impl Node {
    fn bounds(&self) -> &Aabb {
        match self {
            Node::Leaf { bounds, .. } | Node::Inner { bounds, .. } => bounds,
        }
    }
}
