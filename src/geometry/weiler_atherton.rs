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
//! the clip region is translated by 1 to 2 × 1e-10 of the operands' size before
//! clipping, so every intersection is a proper crossing. The translation is drawn
//! from the clip region's own vertices (a hash of their bits): deterministic, and
//! different for different clip regions, since a fixed one would recreate the
//! coincidence when a piece cut by one polygon is cut again by its neighbour across
//! the shared edge.
//! The debris this leaves at that scale is swept from the results (see
//! `contour_sweep`): points closer than 1e-9 of the size are merged, contours that
//! touch themselves split into loops, contours thinner than that (mean width
//! 2·area/perimeter) dropped, and spikes (a vertex where a contour runs out and
//! back along itself within that distance) cut off, so that repeated clipping, as
//! in hidden-surface removal, never meets features as small as its own
//! perturbation. A ∩ B and A − B
//! add up to A within that sweep (a relative 1e-8 at most; 1e-6 after the rare
//! retries below, whose perturbations are larger). Should a perturbation
//! still meet a near-degeneracy, which shows as parts that do not add up, an inside
//! larger than an operand, or an A ∩ B unlike the B ∩ A of the same clipping with the
//! roles swapped, or points well inside the operands' contours landing in the wrong
//! result, another one is drawn, growing from 1e-10 to 1e-6 of the size over eight
//! tries (debris of earlier clips can be larger than the first perturbation).

use super::contour_sweep::sweep;
use super::plane::bounds;
use glam::DVec2;

pub use super::region::{Region, area, contour_area};

/// Whether `p` lies inside the region (non-zero winding number).
pub fn contains(region: &Region, p: DVec2) -> bool {
    region.iter().map(|c| winding(c, p)).sum::<i32>() != 0
}

/// The winding number of a contour around `p`.
fn winding(c: &[DVec2], p: DVec2) -> i32 {
    let mut winding = 0;
    for (i, a) in c.iter().enumerate() {
        let b = c[(i + 1) % c.len()];
        let side = (b - *a).perp_dot(p - *a);
        if a.y <= p.y && b.y > p.y && side > 0.0 {
            winding += 1;
        } else if a.y > p.y && b.y <= p.y && side < 0.0 {
            winding -= 1;
        }
    }
    winding
}

/// A region with the bounding box of each contour, for many containment tests: a
/// contour does not wind around a point outside its box.
struct Located<'a> {
    region: &'a Region,
    boxes: Vec<(DVec2, DVec2)>,
}

impl<'a> Located<'a> {
    fn new(region: &'a Region) -> Located<'a> {
        let boxes = region.iter().map(bounds).collect();
        Located { region, boxes }
    }

    fn contains(&self, p: DVec2) -> bool {
        self.region
            .iter()
            .zip(&self.boxes)
            .filter(|(_, (lo, hi))| p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y)
            .map(|(c, _)| winding(c, p))
            .sum::<i32>()
            != 0
    }
}

/// Whether the interiors of two regions are certainly apart: some line through an
/// edge of either has every vertex of one region on or beyond it and every vertex
/// of the other on or before it. Then A ∩ B is empty and A − B is A, exactly, with
/// no clipping (polygons of a mesh that share an edge meet this way all the time).
/// The test costs the product of the vertex counts: regions of more than
/// `APART_MOST` vertices in all are not tested (false: left to clipping).
pub fn apart(a: &Region, b: &Region) -> bool {
    let count = |r: &Region| r.iter().map(Vec::len).sum::<usize>();
    if count(a) + count(b) > APART_MOST {
        return false;
    }
    let separates = |edges: &Region, near: &Region, far: &Region| {
        edges.iter().any(|contour| {
            (0..contour.len()).any(|i| {
                let (p, q) = (contour[i], contour[(i + 1) % contour.len()]);
                let side = |v: &DVec2| (q - p).perp_dot(*v - p);
                far.iter().flatten().all(|v| side(v) <= 0.0)
                    && near.iter().flatten().all(|v| side(v) >= 0.0)
            })
        })
    };
    separates(b, b, a) || separates(a, a, b)
}

const APART_MOST: usize = 64;

/// A ∩ B and A − B.
///
/// Only the subject's contours whose boxes meet the clip region's box take part: a
/// contour away from it winds around no point of B, so it adds nothing to A ∩ B and
/// passes to A − B as it is (the holes that earlier clips punched into a large
/// polygon are thus not clipped again by every later one).
pub fn clip(subject: &Region, clip: &Region) -> (Region, Region) {
    let size = subject
        .iter()
        .chain(clip)
        .flatten()
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()))
        .max(1e-300);
    // Contours with no area to speak of (a polygon folded onto a line, a point)
    // bound nothing, and would confuse the entry and exit labels: swept first.
    let clip = &sweep(clip.clone(), 1e-9 * size);
    if clip.is_empty() {
        return (Vec::new(), sweep(subject.clone(), 1e-9 * size));
    }
    // The box grown by more than the largest perturbation below.
    let (lo, hi) = bounds(clip.iter().flatten());
    let margin = DVec2::splat(4e-6 * size);
    let (lo, hi) = (lo - margin, hi + margin);
    let (near, far): (Region, Region) = subject.iter().cloned().partition(|c| {
        let (clo, chi) = bounds(c);
        clo.x <= hi.x && clo.y <= hi.y && chi.x >= lo.x && chi.y >= lo.y
    });
    let near = sweep(near, 1e-9 * size);
    if near.is_empty() {
        return (Vec::new(), far);
    }
    let (inside, mut outside) = clip_near(&near, clip, size);
    outside.extend(far);
    (inside, outside)
}

/// A ∩ B and A − B for operands of the given size, by perturbed clipping.
fn clip_near(subject: &Region, clip: &Region, size: f64) -> (Region, Region) {
    let (whole, limit) = (area(subject), area(subject).min(area(clip)));
    let mut result = (Vec::new(), Vec::new());
    for salt in 0..PERTURBATION_TRIES {
        // Two tries at each scale, then larger ones: a near-degeneracy left by
        // earlier clips at one scale is stepped over at the next.
        let scale = [1e-10, 1e-10, 1e-9, 1e-9, 1e-8, 1e-8, 1e-7, 1e-6][salt as usize];
        let nudge = nudge_for(clip, salt) * (scale * size);
        let moved: Region = clip
            .iter()
            .map(|c| c.iter().map(|&p| p + nudge).collect())
            .collect();
        let (inside, outside) = Clipper::new(subject, &moved).run();
        result = (sweep(inside, 1e-9 * size), sweep(outside, 1e-9 * size));
        // A consistent result: parts that add up, an inside no larger than either
        // operand and as large as the clip region's inside of the subject (the same
        // clipping with the roles swapped). Otherwise the perturbation met a
        // near-degeneracy: draw another.
        let (i, o) = (area(&result.0), area(&result.1));
        let slack = 1e-7 * whole.abs().max(size * size * 1e-12);
        let consistent =
            (i + o - whole).abs() <= slack && i <= limit + slack && i >= -slack && o >= -slack;
        if consistent
            && (area(&Clipper::new(&moved, subject).run().0) - i).abs() <= slack
            && probes_agree(subject, &moved, &result)
        {
            break;
        }
    }
    result
}

/// Whether points well inside the operands' contours land where the operands say:
/// in A ∩ B when in both, in A − B when in A only. Catches a result whose areas add
/// up but whose pieces are misplaced (crossings missed near pinched contours).
fn probes_agree(subject: &Region, clip: &Region, (inside, outside): &(Region, Region)) -> bool {
    let (a, b) = (Located::new(subject), Located::new(clip));
    let (i, o) = (Located::new(inside), Located::new(outside));
    subject
        .iter()
        .chain(clip)
        .filter_map(|c| probe(c))
        .all(|p| {
            let (in_a, in_b) = (a.contains(p), b.contains(p));
            i.contains(p) == (in_a && in_b) && o.contains(p) == (in_a && !in_b)
        })
}

/// A point inside a contour, away from its edges: the centroid of the first of its
/// fan triangles that lies inside it with its centroid, if any.
fn probe(contour: &[DVec2]) -> Option<DVec2> {
    let alone = vec![contour.to_vec()];
    (1..contour.len().saturating_sub(1))
        .map(|i| (contour[0] + contour[i] + contour[i + 1]) / 3.0)
        .find(|&p| contains(&alone, p))
}

/// How many perturbations are tried before a result is accepted as it is.
const PERTURBATION_TRIES: u64 = 8;

/// A direction of length 1 to 2 drawn from the bits of all the region's vertices
/// (and the attempt number).
fn nudge_for(region: &Region, salt: u64) -> DVec2 {
    let mut h: u64 = 0x9E37_79B9_7F4A_7C15 ^ salt.wrapping_mul(0xD6E8_FEB8_6659_FD93);
    for p in region.iter().flatten() {
        for bits in [p.x.to_bits(), p.y.to_bits()] {
            h = (h ^ bits).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            h ^= h >> 29;
        }
    }
    let angle = (h >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::TAU;
    let length = 1.0 + (h & 0x3FF) as f64 / 1024.0;
    DVec2::new(angle.cos(), angle.sin()) * length
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
        let a_ids = build(
            &mut self.a,
            self.subject,
            crossings.iter().map(|c| (c.0, c.1, c.2, c.6)),
        );
        let b_ids = build(
            &mut self.b,
            self.clip,
            crossings.iter().map(|c| (c.3, c.4, c.5, c.6)),
        );
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
            if lies_inside(contour, self.clip) {
                inside.push(contour.clone());
            } else {
                outside.push(contour.clone());
            }
        }
        for (c, contour) in self.clip.iter().enumerate() {
            if crossed_b[c] && !untouched {
                continue;
            }
            if lies_inside(contour, self.subject) {
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
                    // The walk stopped at an intersection; a missing twin would be
                    // a broken list (numerical trouble): the caller falls back.
                    at = self.a[at].twin?;
                } else {
                    // Walk the clip contour (forwards inside, backwards outside).
                    contour.push(self.b[at].point);
                    at = if inside {
                        self.b[at].next
                    } else {
                        self.b[at].prev
                    };
                    while self.b[at].twin.is_none() {
                        contour.push(self.b[at].point);
                        at = if inside {
                            self.b[at].next
                        } else {
                            self.b[at].prev
                        };
                    }
                    at = self.b[at].twin?;
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
        for (i, node) in nodes.iter_mut().enumerate().skip(first) {
            node.next = if i + 1 == last { first } else { i + 1 };
            node.prev = if i == first { last - 1 } else { i - 1 };
        }
    }
    debug_assert!(nodes.iter().all(|n| n.contour < region.len()));
    ids
}

/// Parameters (t along p, u along q) where segments p0p1 and q0q1 cross.
///
/// Whether they cross is decided by orientation signs alone (each end of one segment
/// against the line of the other), zero counting as positive: the side of a vertex
/// is then the same number for both edges that meet at it, so a crossing at or near
/// a vertex is counted for exactly one of them and two closed contours always cross
/// an even number of times. t and u only place the crossing.
fn crossing(p0: DVec2, p1: DVec2, q0: DVec2, q1: DVec2) -> Option<(f64, f64)> {
    let side = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    let (s0, s1) = (side(q0, q1, p0), side(q0, q1, p1));
    let (r0, r1) = (side(p0, p1, q0), side(p0, p1, q1));
    if (s0 >= 0.0) == (s1 >= 0.0) || (r0 >= 0.0) == (r1 >= 0.0) {
        return None;
    }
    Some((
        (s0 / (s0 - s1)).clamp(0.0, 1.0),
        (r0 / (r0 - r1)).clamp(0.0, 1.0),
    ))
}

/// Whether a contour that crosses nothing lies inside `region`: the vote of its
/// vertices and edge midpoints. One point could sit on a boundary the contour only
/// touches (an edge shared with a neighbour, a common vertex); most cannot.
fn lies_inside(contour: &[DVec2], region: &Region) -> bool {
    let n = contour.len();
    let votes = (0..n)
        .flat_map(|i| [contour[i], 0.5 * (contour[i] + contour[(i + 1) % n])])
        .filter(|&p| contains(region, p))
        .count();
    2 * votes > 2 * n
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

    /// Regions are apart when a line through an edge parts them: neighbours of a
    /// mesh sharing an edge or a corner, a triangle beside another's diagonal; not
    /// when they overlap by a hair, nor when a concave region's notch holds the other
    /// (no edge line of either parts them, though their interiors do not meet).
    #[test]
    fn apart_when_an_edge_line_parts_them() {
        let p = DVec2::new;
        let region = |c: Vec<DVec2>| vec![c];
        let unit = region(square(0.0, 0.0, 1.0));
        assert!(apart(&unit, &region(square(1.0, 0.0, 1.0))));
        assert!(apart(&region(square(1.0, 1.0, 1.0)), &unit));
        assert!(apart(
            &region(vec![p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)]),
            &region(vec![p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)])
        ));
        assert!(!apart(&unit, &region(square(1.0 - 1e-12, 0.0, 1.0))));
        assert!(!apart(&unit, &region(square(0.25, 0.25, 0.5))));
        let notched = region(vec![
            p(0.0, 0.0),
            p(3.0, 0.0),
            p(3.0, 3.0),
            p(2.0, 3.0),
            p(2.0, 1.0),
            p(1.0, 1.0),
            p(1.0, 3.0),
            p(0.0, 3.0),
        ]);
        let in_notch = region(vec![p(1.5, 1.5), p(1.6, 2.5), p(1.4, 2.5)]);
        assert!(!apart(&notched, &in_notch) && !apart(&in_notch, &notched));
        // A concave region reaching past the line of one of its own edges, and a
        // triangle beyond that line overlapping the part that reaches past it.
        let reaching = region(vec![
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.2, -0.03),
            p(1.2, 1.0),
            p(0.0, 1.0),
        ]);
        let below = region(vec![p(0.9, -0.5), p(1.5, -0.5), p(1.15, -0.01)]);
        assert!(!apart(&reaching, &below) && !apart(&below, &reaching));
    }

    /// Whenever two random triangles are called apart, clipping one by the other
    /// finds no area in common; and most overlapping pairs are not called apart.
    #[test]
    fn apart_regions_share_no_area() {
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut triangle = || {
            let mut c: Vec<DVec2> = (0..3).map(|_| DVec2::new(next(), next())).collect();
            if contour_area(&c) < 0.0 {
                c.reverse();
            }
            vec![c]
        };
        let (mut called_apart, mut overlapping) = (0, 0);
        for _ in 0..3000 {
            let (a, b) = (triangle(), triangle());
            let common = area(&clip(&a, &b).0);
            if apart(&a, &b) {
                called_apart += 1;
                assert!(common <= 1e-9, "apart, yet {common} in common: {a:?} {b:?}");
            } else {
                overlapping += usize::from(common > 1e-9);
            }
        }
        assert!(
            called_apart > 300 && overlapping > 300,
            "{called_apart} {overlapping}"
        );
    }

    /// Degenerate operands (repeated and collinear vertices, slivers, coordinates
    /// near 1e-9 and 1e9) are clipped without a panic.
    #[test]
    fn degenerate_operands_do_not_panic() {
        let p = DVec2::new;
        let shapes: Vec<Vec<DVec2>> = vec![
            vec![p(0.0, 0.0), p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)],
            vec![p(0.0, 0.0), p(0.5, 0.0), p(1.0, 0.0), p(2.0, 0.0)],
            vec![p(0.0, 0.0), p(1e-9, 0.0), p(1e-9, 1e-9), p(0.0, 1e-9)],
            vec![p(-1e9, -1e9), p(1e9, -1e9), p(1e9, 1e9), p(-1e9, 1e9)],
            vec![p(0.0, 0.0), p(1e9, 1e-9), p(1e9, 2e-9)],
            vec![p(0.5, 0.5), p(0.5, 0.5), p(0.5, 0.5)],
            vec![p(0.0, 0.0), p(1.0, 1.0), p(1.0, 0.0), p(0.0, 1.0)],
            square(0.0, 0.0, 1.0),
            vec![p(1.0, 0.0), p(2.0, 0.0), p(2.0, 1.0), p(1.0, 1.0)],
        ];
        for a in &shapes {
            for b in &shapes {
                let (i, o) = clip(&vec![a.clone()], &vec![b.clone()]);
                assert!(area(&i).is_finite() && area(&o).is_finite());
                let (i, o) = Clipper::new(&vec![a.clone()], &vec![b.clone()]).run();
                assert!(area(&i).is_finite() && area(&o).is_finite());
            }
        }
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
        let bar = vec![
            DVec2::new(-1.0, 1.25),
            DVec2::new(4.0, 1.25),
            DVec2::new(4.0, 1.75),
            DVec2::new(-1.0, 1.75),
        ];
        let (i, o) = clip(&a, &vec![bar]);
        assert!((area(&i) - 1.0).abs() < 1e-6, "inside {} {i:?}", area(&i));
        assert!((area(&o) - 7.0).abs() < 1e-6, "outside {} {o:?}", area(&o));
    }

    /// A subject touching itself at a vertex, a clip corner on that pinch (met in
    /// hidden-surface removal of the Cornell box).
    #[test]
    fn clip_corner_on_a_pinched_subject() {
        let a: Region = vec![vec![
            DVec2::new(524.1327014638737, 496.6008020524939),
            DVec2::new(542.448307458561, 473.3540713927409),
            DVec2::new(474.34020348097226, 250.96026248632876),
            DVec2::new(771.4531534815895, 250.96026248632876),
            DVec2::new(771.4531534815895, 772.8530805687204),
            DVec2::new(255.53335763762306, 772.8530805687204),
            DVec2::new(256.69862435236166, 569.2227221681453),
            DVec2::new(376.6737149584467, 542.3317535840227),
            DVec2::new(330.9427634455046, 393.93948234814957),
            DVec2::new(257.9739514982521, 346.35930342378134),
            DVec2::new(258.51986875683554, 250.96026248632876),
            DVec2::new(458.75676746105165, 250.96026248632876),
            DVec2::new(478.40174995662386, 347.2752461104536),
            DVec2::new(519.2195690346058, 480.5579206508029),
            DVec2::new(371.7323779605571, 526.297619148451),
            DVec2::new(376.6737149853047, 542.3317535756934),
        ]];
        let b: Region = vec![vec![
            DVec2::new(376.6737149349322, 542.3317535377118),
            DVec2::new(172.3842638538942, 588.1207684180442),
            DVec2::new(371.7323779127921, 526.2976191189306),
        ]];
        let (i, o) = clip(&a, &b);
        let (mut wrong, mut n) = (0, 0);
        for gx in 0..300 {
            for gy in 0..300 {
                let p = DVec2::new(
                    150.0 + 650.0 * (gx as f64 + 0.5) / 300.0,
                    240.0 + 560.0 * (gy as f64 + 0.5) / 300.0,
                );
                let (ia, ib) = (contains(&a, p), contains(&b, p));
                n += 1;
                wrong +=
                    ((contains(&i, p) != (ia && ib)) || (contains(&o, p) != (ia && !ib))) as usize;
            }
        }
        assert!(
            wrong < 20,
            "{wrong} of {n} samples misplaced; areas {} {} of {}",
            area(&i),
            area(&o),
            area(&a)
        );
    }
}
