//! The sweep that keeps repeated Weiler–Atherton clipping robust. Clipping with a
//! perturbed operand leaves debris at the perturbation's scale: points a hair
//! apart, contours of no width, spikes, and bridges (a contour running out along
//! one of its own edges and back, so that it touches itself). A later clip whose
//! edge crosses a bridge meets two of its edges at once, at crossings closer than
//! any perturbation can part, and labels them wrongly. The sweep removes all of it
//! at a tolerance well above the perturbation and well below any feature a scene
//! has: close points are merged, a contour is split into simple loops where it
//! touches itself (the winding number of every point farther than the tolerance
//! from the outline is unchanged, so the region is the same), spikes are cut off
//! and loops thinner than the tolerance dropped.

use super::region::{Region, contour_area};
use glam::DVec2;

/// The region swept of debris smaller than `tolerance`.
pub(crate) fn sweep(region: Region, tolerance: f64) -> Region {
    region
        .into_iter()
        .flat_map(|contour| split_at_pinches(merge_close(contour, tolerance), tolerance))
        .filter_map(|mut contour| {
            remove_spikes(&mut contour, tolerance);
            let perimeter: f64 = (0..contour.len())
                .map(|i| contour[i].distance(contour[(i + 1) % contour.len()]))
                .sum();
            let thick =
                contour.len() >= 3 && 2.0 * contour_area(&contour).abs() >= tolerance * perimeter;
            thick.then_some(contour)
        })
        .collect()
}

/// The contour with each run of points closer than `tolerance` (around the end
/// too) reduced to its first.
fn merge_close(contour: Vec<DVec2>, tolerance: f64) -> Vec<DVec2> {
    let mut kept: Vec<DVec2> = Vec::with_capacity(contour.len());
    for p in contour {
        if kept.last().is_none_or(|q| q.distance(p) >= tolerance) {
            kept.push(p);
        }
    }
    while kept.len() > 1 && kept[0].distance(kept[kept.len() - 1]) < tolerance {
        kept.pop();
    }
    kept
}

/// The closed loops a contour is made of where it touches itself: a vertex within
/// `tolerance` of another of its edges is first inserted into that edge, then the
/// walk is cut into loops at every point it comes back to. A bridge (an edge walked
/// both ways) becomes a loop of two points, which has no area and is left out.
fn split_at_pinches(contour: Vec<DVec2>, tolerance: f64) -> Vec<Vec<DVec2>> {
    let n = contour.len();
    if n < 4 {
        return vec![contour];
    }
    // Vertices lying on the inside of an edge that is not theirs, by edge, with
    // their place along it.
    let mut on_edge: Vec<Vec<(f64, DVec2)>> = vec![Vec::new(); n];
    for (i, on) in on_edge.iter_mut().enumerate() {
        let (a, b) = (contour[i], contour[(i + 1) % n]);
        let (lo, hi) = (
            a.min(b) - DVec2::splat(tolerance),
            a.max(b) + DVec2::splat(tolerance),
        );
        for (j, &p) in contour.iter().enumerate() {
            let away = j != i && j != (i + 1) % n;
            if away
                && p.cmpge(lo).all()
                && p.cmple(hi).all()
                && p.distance(a) >= tolerance
                && p.distance(b) >= tolerance
                && distance_to_segment(p, a, b) < tolerance
            {
                on.push(((p - a).dot(b - a), p));
            }
        }
        on.sort_by(|x, y| x.0.total_cmp(&y.0));
    }
    let walk = contour
        .iter()
        .zip(on_edge)
        .flat_map(|(&p, on)| std::iter::once(p).chain(on.into_iter().map(|(_, q)| q)));
    // Cut the walk into loops: coming back near a point already on the path
    // closes the loop from there.
    let mut loops = Vec::new();
    let mut path: Vec<DVec2> = Vec::with_capacity(n);
    for p in walk {
        if let Some(k) = path.iter().position(|q| q.distance(p) < tolerance) {
            let mut closed = vec![path[k]];
            closed.extend(path.split_off(k + 1));
            loops.push(closed);
        } else {
            path.push(p);
        }
    }
    loops.push(path);
    loops.retain(|l| l.len() >= 3);
    loops
}

/// Removes the contour's spikes: vertices where it runs out and comes back along
/// itself, so that the next vertex lies within `tolerance` of the edge just
/// walked. A spike encloses no area, but its two edges, moved together by the
/// perturbation, would be crossed twice at once by any edge that meets them.
fn remove_spikes(contour: &mut Vec<DVec2>, tolerance: f64) {
    let mut i = 0;
    let mut unchanged = 0;
    while contour.len() >= 3 && unchanged < contour.len() {
        let n = contour.len();
        let (prev, vertex, next) = (
            contour[(i + n - 1) % n],
            contour[i % n],
            contour[(i + 1) % n],
        );
        let folds_back = distance_to_segment(next, prev, vertex) < tolerance
            || distance_to_segment(prev, vertex, next) < tolerance;
        if folds_back && vertex.distance(prev) >= tolerance && vertex.distance(next) >= tolerance {
            contour.remove(i % n);
            // Merge the two ends the spike leaves side by side.
            let n = contour.len();
            let at = (i + n - 1) % n;
            if n >= 2 && contour[at].distance(contour[(at + 1) % n]) < tolerance {
                contour.remove((at + 1) % n);
            }
            unchanged = 0;
            i = i.saturating_sub(1);
        } else {
            unchanged += 1;
            i += 1;
        }
    }
}

/// Distance from `p` to the segment from `a` to `b`.
fn distance_to_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + t * ab)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::region::area;

    /// A spike (out to a point and back along the same line, within the tolerance)
    /// is cut off; a sharp corner, however sharp, that encloses more than the
    /// tolerance is kept.
    #[test]
    fn spikes_are_removed_and_sharp_corners_kept() {
        let p = DVec2::new;
        let mut spiked = vec![
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0, 0.5),
            p(3.0, 0.5),
            p(1.0, 0.5 + 1e-8),
            p(1.0, 1.0),
            p(0.0, 1.0),
        ];
        remove_spikes(&mut spiked, 1e-6);
        assert_eq!(spiked.len(), 5, "{spiked:?}");
        assert!((contour_area(&spiked) - 1.0).abs() < 1e-7);
        let mut sharp = vec![
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0, 0.5),
            p(3.0, 0.5),
            p(1.0, 0.5 + 1e-4),
            p(1.0, 1.0),
            p(0.0, 1.0),
        ];
        remove_spikes(&mut sharp, 1e-6);
        assert_eq!(sharp.len(), 7);
    }

    /// A contour that runs out along one of its own edges and back (two lobes
    /// joined by a bridge of width 5e-9, as a clip left it) is split into the two
    /// lobes, with the same area; a square whose hole is joined to its outline by a
    /// bridge becomes the square and the hole, which keeps its clockwise turn.
    #[test]
    fn bridges_are_cut_and_lobes_kept() {
        let p = DVec2::new;
        // The lobes: the triangle (0,0) (4,0) (2,2), and the triangle (2,-3) (3,-1)
        // (1,-1) hung below the base's midpoint by a bridge down the line x = 2.
        let bridged = vec![
            p(0.0, 0.0),
            p(2.0, 0.0),
            p(2.0 + 5e-9, -1.0),
            p(1.0, -1.0),
            p(2.0, -3.0),
            p(3.0, -1.0),
            p(2.0 - 5e-9, -1.0),
            p(2.0, 0.0),
            p(4.0, 0.0),
            p(2.0, 2.0),
        ];
        let swept = sweep(vec![bridged.clone()], 1e-6);
        assert_eq!(swept.len(), 2, "{swept:?}");
        assert!((area(&swept) - (4.0 + 2.0)).abs() < 1e-6, "{swept:?}");
        assert!(swept.iter().all(|c| contour_area(c) > 0.0));
        // Two lobes whose bridge lies along an edge of the contour, its ends on
        // that edge's inside (as Sutherland–Hodgman leaves a concave polygon cut
        // by a line): the triangles (0,0) (1,-1) (2,0) and (3,0) (3.5,-1) (4,0).
        let along = vec![
            p(4.0, 0.0),
            p(0.0, 0.0),
            p(1.0, -1.0),
            p(2.0, 1e-9),
            p(3.0, -1e-9),
            p(3.5, -1.0),
        ];
        let swept = sweep(vec![along], 1e-6);
        assert_eq!(swept.len(), 2, "{swept:?}");
        assert!((area(&swept) - 1.5).abs() < 1e-6, "{swept:?}");
        assert!(swept.iter().all(|c| contour_area(c) > 0.0));
        let keyhole = vec![
            p(0.0, 0.0),
            p(4.0, 0.0),
            p(4.0, 4.0),
            p(2.0 + 4e-9, 4.0),
            p(2.0 + 4e-9, 3.0),
            p(3.0, 3.0),
            p(3.0, 1.0),
            p(1.0, 1.0),
            p(1.0, 3.0),
            p(2.0, 3.0),
            p(2.0, 4.0),
            p(0.0, 4.0),
        ];
        let swept = sweep(vec![keyhole], 1e-6);
        assert_eq!(swept.len(), 2, "{swept:?}");
        assert!((area(&swept) - 12.0).abs() < 1e-6);
        assert!(swept.iter().any(|c| (contour_area(c) + 4.0).abs() < 1e-6));
    }
}
