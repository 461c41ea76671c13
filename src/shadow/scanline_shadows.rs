//! Shadows found during scan-out: W. J. Bouknight, K. C. Kelley, "An algorithm for
//! producing half-tone computer graphics presentations with shadows and movable light
//! sources", AFIPS SJCC 1970, pp. 1–10 (after Appel 1968); steps as in Foley, van
//! Dam, Feiner & Hughes, *Computer Graphics: Principles and Practice*, §16.4.1.
//!
//! Pre-pass, in object space, once per light: every polygon is projected centrally
//! onto a sphere around the light; two polygons whose projections do not overlap
//! cannot shadow each other, which prunes the pairs. For each remaining pair, the
//! caster C can shadow the receiver R only where C lies between the light and R's
//! plane: C is clipped to that slab and projected from the light onto R's plane
//! (`geometry::central_projection`). The projections are R's shadow polygons; they take no part in visibility.
//!
//! Scan-out: the scan-line visible-surface sweep (`raster::scan_out`) hands over, row
//! by row as it resolves them, the span segments where each polygon R is visible.
//! R's shadow polygons, entered in an edge table of their own and swept like any
//! polygons, give the row's shadowed intervals. Each segment is compared with them
//! there and then: no overlap, lit; covered, shadowed; partly covered, split at the
//! interval ends and each piece classified again.
//!
//! Choices: a polygon's extent on the sphere is bounded by a cone (axis the mean of
//! its vertex directions, half-angle the widest of them), which has no azimuth wrap
//! to handle; a cone wider than a hemisphere is taken as the whole sphere. The slab
//! stops a relative 1e-6 short of the light's own distance to R's plane (points level
//! with the light project to infinity). A bounding hierarchy over the cones
//! (`cone_tree`) hands each receiver the casters whose cones may overlap its own, so
//! the pairwise test is not run n² times. Pruning changes only the cost: `prune =
//! false` gives the same image. Shadow polygons are projected only onto receivers
//! the eye sees somewhere: the others are never scanned out. Scene key: `[shadows] method = "scanline"`.

use super::cone_tree::ConeTree;
use super::receivers::ReceiverScreens;
use super::{BandShadows, FrameShadows, LightShadows, per_sample};
use crate::geometry::central_projection::onto_plane;
use crate::raster::{
    EdgeTable, LightVisibility, ScreenPolygon, View, VisibleSurface, scan_out, screen_polygons,
};
use crate::scene::LightKind;
use crate::scene::{Polygon, Scene};
use crate::settings::ShadowMethod;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;
use std::f64::consts::PI;
use std::ops::Range;
use std::sync::Arc;
use std::sync::OnceLock;

/// The registry's entry: lights at a point.
pub(crate) static METHOD: super::Method = super::Method {
    method: ShadowMethod::Scanline,
    name: "scanline",
    entry: Some("scanline-shadows"),
    handles: "a hard-shadow method for point and spot lights",
    lights: &[LightKind::Point, LightKind::Spot],
    counts: None,
    budget: super::no_budget,
    warnings: super::no_warnings,
    prepare: |scene, index, _, _| {
        let at = scene.lights[index].position().expect("checked");
        Some(Arc::new(ScanlineShadows::new(scene, at, true)))
    },
};

/// A polygon's extent as seen from the light: a cone around `axis`.
#[derive(Clone, Copy, Debug)]
struct Cone {
    axis: DVec3,
    half_angle: f64,
    /// cos and sin of the half-angle.
    cos: f64,
    sin: f64,
}

impl Cone {
    fn of(polygon: &Polygon, light: DVec3) -> Cone {
        let directions: Vec<DVec3> = polygon
            .positions()
            .map(|v| (v - light).normalize_or_zero())
            .collect();
        let axis = directions
            .iter()
            .copied()
            .sum::<DVec3>()
            .normalize_or_zero();
        let half_angle = directions
            .iter()
            .map(|d| d.dot(axis).clamp(-1.0, 1.0).acos())
            .fold(0.0, f64::max);
        if axis == DVec3::ZERO || half_angle >= 0.5 * PI {
            Cone::new(DVec3::Z, PI)
        } else {
            Cone::new(axis, half_angle)
        }
    }

    fn new(axis: DVec3, half_angle: f64) -> Cone {
        let (sin, cos) = half_angle.sin_cos();
        Cone {
            axis,
            half_angle,
            cos,
            sin,
        }
    }

    /// Whether the angle between the axes is at most the sum of the half-angles,
    /// compared by cosines (cos is decreasing on [0, π]; cos(a + b) from each cone's
    /// own cosine and sine) to spare n² trigonometric calls.
    fn overlaps(&self, other: &Cone) -> bool {
        self.half_angle + other.half_angle >= PI
            || self.axis.dot(other.axis) >= self.cos * other.cos - self.sin * other.sin - 1e-12
    }
}

/// The pre-pass for a point light at `light`: every polygon's cone, and per
/// receiver its shadow polygons, projected the first time a frame shows the
/// receiver (only receivers the eye sees are ever scanned out) and kept for later
/// frames.
pub struct ScanlineShadows {
    light: DVec3,
    prune: bool,
    cones: Vec<Cone>,
    /// The cones' bounding hierarchy, which finds each receiver's candidate casters.
    tree: ConeTree,
    lists: Vec<OnceLock<Vec<Vec<DVec3>>>>,
}

impl ScanlineShadows {
    pub fn new(scene: &Scene, light: DVec3, prune: bool) -> ScanlineShadows {
        let cones: Vec<Cone> = scene
            .polygons
            .par_iter()
            .map(|p| Cone::of(p, light))
            .collect();
        let bounds: Vec<(DVec3, f64)> = cones.iter().map(|c| (c.axis, c.half_angle)).collect();
        ScanlineShadows {
            light,
            prune,
            tree: ConeTree::new(if prune { &bounds } else { &[] }),
            cones,
            lists: scene.polygons.iter().map(|_| OnceLock::new()).collect(),
        }
    }

    /// Receiver `r`'s shadow polygons (world space, on its plane).
    pub fn shadow_polygons(&self, scene: &Scene, r: usize) -> &[Vec<DVec3>] {
        self.lists[r].get_or_init(|| project_onto(scene, self.light, self.casters(r), r))
    }

    /// The casters that may shadow receiver `r`, in the scene's order: with pruning,
    /// those whose cone overlaps r's (the tree finds the candidates, the pairwise
    /// test decides), else every polygon but r.
    fn casters(&self, r: usize) -> Vec<u32> {
        if !self.prune {
            return (0..self.cones.len() as u32)
                .filter(|&c| c as usize != r)
                .collect();
        }
        let cone = &self.cones[r];
        let mut casters = Vec::new();
        self.tree.candidates(cone.axis, cone.half_angle, |c| {
            if c as usize != r && cone.overlaps(&self.cones[c as usize]) {
                casters.push(c);
            }
        });
        // The scene's order, as the shadow polygons were always listed.
        casters.sort_unstable();
        casters
    }
}

/// The shadow polygons every caster throws on receiver `r`'s plane: each caster
/// clipped to the slab between the light and R's plane and projected from the light.
fn project_onto(scene: &Scene, light: DVec3, casters: Vec<u32>, r: usize) -> Vec<Vec<DVec3>> {
    let receiver = &scene.polygons[r];
    let origin = receiver.vertices[0].position;
    casters
        .into_iter()
        .filter_map(|c| {
            let corners: Vec<DVec3> = scene.polygons[c as usize].positions().collect();
            onto_plane(&corners, light, origin, receiver.normal)
        })
        .collect()
}

/// Per receiver, its shadow polygons (world space, on its plane), for the receivers
/// for which `wanted` holds (the others get none).
pub fn shadow_polygons(
    scene: &Scene,
    light: DVec3,
    prune: bool,
    wanted: impl Fn(usize) -> bool + Sync,
) -> Vec<Vec<Vec<DVec3>>> {
    let shadows = ScanlineShadows::new(scene, light, prune);
    (0..scene.polygons.len())
        .into_par_iter()
        .map(|r| {
            if wanted(r) {
                shadows.shadow_polygons(scene, r).to_vec()
            } else {
                Vec::new()
            }
        })
        .collect()
}

impl LightShadows for ScanlineShadows {
    fn frame<'a>(&'a self, scene: &'a Scene, view: &'a View) -> Box<dyn FrameShadows + 'a> {
        let project = move |r: usize| {
            self.shadow_polygons(scene, r)
                .iter()
                .filter_map(|corners| ScreenPolygon::from_points(view, r as u32, corners))
                .collect()
        };
        let polygons = screen_polygons(scene, view);
        Box::new(ScanlineFrame {
            shadows: self,
            scene,
            view,
            table: EdgeTable::build(&polygons, view.height),
            polygons,
            screens: ReceiverScreens::new(scene.polygons.len(), view.height, project),
        })
    }
}

struct ScanlineFrame<'a, F> {
    shadows: &'a ScanlineShadows,
    scene: &'a Scene,
    view: &'a View,
    /// The scene on this view's screen, swept again at scan-out.
    polygons: Vec<ScreenPolygon>,
    table: EdgeTable,
    screens: ReceiverScreens<F>,
}

/// What one group of rows of the scan-out keeps: per receiver met, its shadow
/// polygons' intervals on each of the group's rows (sorted, disjoint).
struct GroupIntervals {
    rows: Range<u32>,
    per_receiver: HashMap<u32, Vec<Vec<(u32, u32)>>>,
}

impl GroupIntervals {
    /// Receiver `r`'s shadowed intervals on `row`, its shadow polygons swept over the
    /// group's rows the first time the group meets it.
    fn on<F: Fn(usize) -> Vec<ScreenPolygon> + Sync>(
        &mut self,
        screens: &ReceiverScreens<F>,
        width: u32,
        r: u32,
        row: u32,
    ) -> &[(u32, u32)] {
        let rows = self.rows.clone();
        let per_row = self.per_receiver.entry(r).or_insert_with(|| {
            let mut per_row: Vec<Vec<(u32, u32)>> = vec![Vec::new(); rows.len()];
            screens.spans_on(r as usize, width, rows.clone(), |y, a, b, _| {
                let intervals = &mut per_row[(y - rows.start) as usize];
                match intervals.last_mut() {
                    Some(last) if last.1 + 1 >= a => last.1 = last.1.max(b),
                    _ => intervals.push((a, b)),
                }
            });
            per_row
        });
        &per_row[(row - rows.start) as usize]
    }
}

impl<F: Fn(usize) -> Vec<ScreenPolygon> + Sync + Send> FrameShadows for ScanlineFrame<'_, F> {
    fn band(&self, band: &VisibleSurface) -> BandShadows {
        let width = band.width;
        // During scan-out: each visible segment (a run of one polygon on the row) is
        // classified against its polygon's shadow intervals on that row.
        let dark = scan_out(
            &self.polygons,
            self.polygons.len(),
            &self.table,
            width,
            band.rows(),
            false,
            |rows| GroupIntervals {
                rows,
                per_receiver: HashMap::new(),
            },
            |group, row, out| {
                let mut pieces = row.pieces.iter().peekable();
                while let Some(piece) = pieces.next() {
                    let (x0, mut x1) = (piece.first, piece.last);
                    while let Some(next) =
                        pieces.next_if(|p| p.visible == piece.visible && p.first == x1 + 1)
                    {
                        x1 = next.last;
                    }
                    let receiver = self.polygons[piece.visible as usize].id;
                    let intervals = group.on(&self.screens, width, receiver, row.row);
                    classify(x0, x1, intervals, &mut |a, b| {
                        out[a as usize..=b as usize].fill(true)
                    });
                }
            },
        );
        BandShadows::fraction(per_sample(
            self.scene,
            self.view,
            band,
            self.shadows.light,
            |k, _, _| !dark[k],
        ))
    }
}

/// The visibility of the point light at `light` for every sample of `surface`, with
/// the sphere pruning on or off.
pub fn visibility_with(
    scene: &Scene,
    view: &View,
    surface: &VisibleSurface,
    light: DVec3,
    prune: bool,
) -> Vec<f32> {
    let shadows = ScanlineShadows::new(scene, light, prune);
    match shadows.frame(scene, view).band(surface).visibility {
        LightVisibility::Fraction(f) => f,
        LightVisibility::Emitter(_) => unreachable!("a point light has no emitter"),
    }
}

/// Classifies the segment [x0, x1] against the row's shadowed intervals (sorted,
/// disjoint): no overlap, lit; covered, shadowed; partly covered, split at the
/// interval ends and each piece classified again. Calls `dark(a, b)` for every
/// shadowed piece.
fn classify(x0: u32, x1: u32, intervals: &[(u32, u32)], dark: &mut impl FnMut(u32, u32)) {
    let overlapping: Vec<(u32, u32)> = intervals
        .iter()
        .copied()
        .filter(|&(a, b)| a <= x1 && b >= x0)
        .collect();
    match overlapping.as_slice() {
        [] => {}
        [(a, b)] if *a <= x0 && *b >= x1 => dark(x0, x1),
        [(a, b), ..] => {
            // Split at the first interval end inside the segment; classify both parts.
            let cut = if *a > x0 { a - 1 } else { *b };
            classify(x0, cut, intervals, dark);
            if cut < x1 {
                classify(cut + 1, x1, intervals, dark);
            }
        }
    }
}
