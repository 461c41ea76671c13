//! Weiler–Atherton clipping: K. Weiler, P. Atherton, "Hidden surface removal using
//! polygon area sorting", Computer Graphics (SIGGRAPH '77) 11(2):214–222, 1977.
//!
//! Both operands are regions: lists of contours, outer contours counter-clockwise
//! (positive shoelace area), holes clockwise; concave contours and holes are allowed.
//! Every intersection of a subject edge with a clip edge is inserted, in order along
//! its edge, into both vertex lists, the two copies linked. Walking the subject, an
//! intersection where the subject crosses to the left of the clip edge (the clip
//! region's inside) is an entry, otherwise an exit. The inside result (A ∩ B) is
//! traced from each unused entry: along the subject to the next intersection, there
//! onto the clip contour, forward to the next intersection, back onto the subject…
//! until the start. The outside result (A − B) is traced from the exits the same way,
//! following clip contours backwards. Contours meeting nothing are kept or dropped
//! by whether they lie inside the other region (a clip contour inside the subject
//! becomes, reversed, a hole of A − B).
//!
//! Degenerate cases (shared or collinear edges, a vertex on an edge, coincident
//! polygons), which the paper leaves to the implementer, are removed by perturbation:
//! the clip region is translated by 1e-9 of the operands' size in a fixed direction
//! of irrational slope before clipping, so every intersection is a proper crossing.
//! Results are exact for the perturbed clip region; A ∩ B and A − B always add up to
//! A, since both use the same one.

use glam::DVec2;

/// A region: outer contours counter-clockwise, holes clockwise.
pub type Region = Vec<Vec<DVec2>>;

/// Signed area of a contour (positive counter-clockwise).
pub fn contour_area(c: &[DVec2]) -> f64 {
    let mut twice = 0.0;
    for (i, a) in c.iter().enumerate() {
        let b = c[(i + 1) % c.len()];
        twice += a.perp_dot(b);
    }
    0.5 * twice
}

/// Area of a region: its outer contours less its holes.
pub fn area(region: &Region) -> f64 {
    region.iter().map(|c| contour_area(c)).sum()
}

/// Whether `p` lies inside the region (non-zero winding number).
pub fn contains(region: &Region, p: DVec2) -> bool {
    let mut winding = 0;
    for c in region {
        for (i, a) in c.iter().enumerate() {
            let b = c[(i + 1) % c.len()];
            let side = (b - *a).perp_dot(p - *a);
            if a.y <= p.y && b.y > p.y && side > 0.0 {
                winding += 1;
            } else if a.y > p.y && b.y <= p.y && side < 0.0 {
                winding -= 1;
            }
        }
    }
    winding != 0
}

/// A ∩ B and A − B.
pub fn clip(subject: &Region, clip: &Region) -> (Region, Region) {
    let size = subject
        .iter()
        .chain(clip)
        .flatten()
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()))
        .max(1e-300);
    let nudge = DVec2::new(0.618_033_988_749_895, 0.381_966_011_250_105) * (1e-9 * size);
    let clip: Region = clip
        .iter()
        .map(|c| c.iter().map(|&p| p + nudge).collect())
        .collect();
    Clipper::new(subject, &clip).run()
}

/// One vertex of a contour list: an original vertex, or an intersection linked to
/// its copy in the other operand's lists.
#[derive(Clone, Copy, Debug)]
struct Node {
    point: DVec2,
    /// For an intersection: index of its twin in the other operand's node array.
    twin: Option<usize>,
    /// For a subject intersection: the subject enters the clip region here.
    entering: bool,
    /// Next and previous node along the contour.
    next: usize,
    prev: usize,
    contour: usize,
}

struct Clipper<'a> {
    subject: &'a Region,
    clip: &'a Region,
    a: Vec<Node>,
    b: Vec<Node>,
}

impl<'a> Clipper<'a> {
    fn new(subject: &'a Region, clip: &'a Region) -> Clipper<'a> {
        Clipper {
            subject,
            clip,
            a: Vec::new(),
            b: Vec::new(),
        }
    }

    fn run(mut self) -> (Region, Region) {
        // All proper crossings: (subject contour, edge, t, clip contour, edge, u, point).
        let mut crossings = Vec::new();
        for (ca, contour_a) in self.subject.iter().enumerate() {
            for (ea, &p0) in contour_a.iter().enumerate() {
                let p1 = contour_a[(ea + 1) % contour_a.len()];
                for (cb, contour_b) in self.clip.iter().enumerate() {
                    for (eb, &q0) in contour_b.iter().enumerate() {
                        let q1 = contour_b[(eb + 1) % contour_b.len()];
                        if let Some((t, u)) = crossing(p0, p1, q0, q1) {
                            let entering = (q1 - q0).perp_dot(p1 - p0) > 0.0;
                            crossings.push((ca, ea, t, cb, eb, u, p0 + (p1 - p0) * t, entering));
                        }
                    }
                }
            }
        }
        let a_ids = build(&mut self.a, self.subject, crossings.iter().map(|c| (c.0, c.1, c.2, c.6)));
        let b_ids = build(&mut self.b, self.clip, crossings.iter().map(|c| (c.3, c.4, c.5, c.6)));
        for (k, c) in crossings.iter().enumerate() {
            let (ia, ib) = (a_ids[k], b_ids[k]);
            self.a[ia].twin = Some(ib);
            self.a[ia].entering = c.7;
            self.b[ib].twin = Some(ia);
        }
        let inside = self.trace(true);
        let outside = self.trace(false);
        let (mut inside, mut outside) = match (inside, outside) {
            (Some(i), Some(o)) => (i, o),
            // A tangle the traversal cannot close (only from numerical trouble):
            // keep the identity by treating the operands as not crossing.
            _ => (Vec::new(), Vec::new()),
        };
        let crossed_a: Vec<bool> = (0..self.subject.len())
            .map(|c| crossings.iter().any(|x| x.0 == c))
            .collect();
        let crossed_b: Vec<bool> = (0..self.clip.len())
            .map(|c| crossings.iter().any(|x| x.3 == c))
            .collect();
        let untouched = inside.is_empty() && outside.is_empty() && !crossings.is_empty();
        for (c, contour) in self.subject.iter().enumerate() {
            if crossed_a[c] && !untouched {
                continue;
            }
            if contains(self.clip, representative(contour)) {
                inside.push(contour.clone());
            } else {
                outside.push(contour.clone());
            }
        }
        for (c, contour) in self.clip.iter().enumerate() {
            if crossed_b[c] && !untouched {
                continue;
            }
            if contains(self.subject, representative(contour)) {
                inside.push(contour.clone());
                outside.push(contour.iter().rev().copied().collect());
            }
        }
        (inside, outside)
    }

    /// Traces the inside (from entries) or outside (from exits) contours; `None` if a
    /// walk does not close.
    fn trace(&self, inside: bool) -> Option<Region> {
        let mut used = vec![false; self.a.len()];
        let mut out = Vec::new();
        let limit = 2 * (self.a.len() + self.b.len()) + 4;
        for start in 0..self.a.len() {
            let n = &self.a[start];
            if n.twin.is_none() || used[start] || n.entering != inside {
                continue;
            }
            let mut contour = Vec::new();
            let (mut on_a, mut at) = (true, start);
            for step in 0.. {
                if step > limit {
                    return None;
                }
                if on_a {
                    used[at] = true;
                    contour.push(self.a[at].point);
                    at = self.a[at].next;
                    // Walk the subject to its next intersection.
                    while self.a[at].twin.is_none() {
                        contour.push(self.a[at].point);
                        at = self.a[at].next;
                    }
                    if at == start {
                        break;
                    }
                    used[at] = true;
                    on_a = false;
                    at = self.a[at].twin.expect("an intersection");
                } else {
                    // Walk the clip contour (forwards inside, backwards outside).
                    contour.push(self.b[at].point);
                    at = if inside { self.b[at].next } else { self.b[at].prev };
                    while self.b[at].twin.is_none() {
                        contour.push(self.b[at].point);
                        at = if inside { self.b[at].next } else { self.b[at].prev };
                    }
                    at = self.b[at].twin.expect("an intersection");
                    on_a = true;
                    if at == start {
                        break;
                    }
                }
            }
            if contour.len() >= 3 {
                out.push(contour);
            }
        }
        Some(out)
    }
}

/// Builds the linked node lists of a region with the intersections inserted in
/// order along their edges; returns, per intersection, its node index.
fn build(
    nodes: &mut Vec<Node>,
    region: &Region,
    crossings: impl Iterator<Item = (usize, usize, f64, DVec2)>,
) -> Vec<usize> {
    let crossings: Vec<(usize, usize, f64, DVec2)> = crossings.collect();
    let mut ids = vec![0; crossings.len()];
    for (c, contour) in region.iter().enumerate() {
        let first = nodes.len();
        for (e, &p) in contour.iter().enumerate() {
            let mut along: Vec<(f64, usize)> = crossings
                .iter()
                .enumerate()
                .filter(|(_, x)| x.0 == c && x.1 == e)
                .map(|(k, x)| (x.2, k))
                .collect();
            along.sort_by(|x, y| x.0.total_cmp(&y.0));
            nodes.push(Node {
                point: p,
                twin: None,
                entering: false,
                next: 0,
                prev: 0,
                contour: c,
            });
            for (_, k) in along {
                ids[k] = nodes.len();
                nodes.push(Node {
                    point: crossings[k].3,
                    twin: None,
                    entering: false,
                    next: 0,
                    prev: 0,
                    contour: c,
                });
            }
        }
        let last = nodes.len();
        for i in first..last {
            nodes[i].next = if i + 1 == last { first } else { i + 1 };
            nodes[i].prev = if i == first { last - 1 } else { i - 1 };
        }
    }
    debug_assert!(nodes.iter().all(|n| n.contour < region.len()));
    ids
}

/// Parameters (t along p, u along q) of a proper crossing of segments p0p1 and q0q1.
fn crossing(p0: DVec2, p1: DVec2, q0: DVec2, q1: DVec2) -> Option<(f64, f64)> {
    let (r, s) = (p1 - p0, q1 - q0);
    let denominator = r.perp_dot(s);
    if denominator == 0.0 {
        return None;
    }
    let t = (q0 - p0).perp_dot(s) / denominator;
    let u = (q0 - p0).perp_dot(r) / denominator;
    ((0.0..1.0).contains(&t) && (0.0..1.0).contains(&u) && t > 0.0 && u > 0.0).then_some((t, u))
}

/// A point of a contour that crosses nothing, to place the whole contour: the
/// midpoint of its first edge (after perturbation it lies on no other boundary).
fn representative(contour: &[DVec2]) -> DVec2 {
    0.5 * (contour[0] + contour[1 % contour.len()])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, side: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(x, y),
            DVec2::new(x + side, y),
            DVec2::new(x + side, y + side),
            DVec2::new(x, y + side),
        ]
    }

    #[test]
    fn overlapping_corner() {
        let (i, o) = clip(&vec![square(0.0, 0.0, 2.0)], &vec![square(1.0, 1.0, 2.0)]);
        assert!((area(&i) - 1.0).abs() < 1e-6, "{i:?}");
        assert!((area(&o) - 3.0).abs() < 1e-6, "{o:?}");
    }

    #[test]
    fn through_a_hole() {
        let mut hole = square(1.0, 1.0, 1.0);
        hole.reverse();
        let a = vec![square(0.0, 0.0, 3.0), hole];
        // A bar across the whole region, through the hole.
        let bar = vec![DVec2::new(-1.0, 1.25), DVec2::new(4.0, 1.25), DVec2::new(4.0, 1.75), DVec2::new(-1.0, 1.75)];
        let (i, o) = clip(&a, &vec![bar]);
        assert!((area(&i) - 1.0).abs() < 1e-6, "inside {} {i:?}", area(&i));
        assert!((area(&o) - 7.0).abs() < 1e-6, "outside {} {o:?}", area(&o));
    }
}
