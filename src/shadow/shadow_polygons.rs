//! Shadow polygons by two visibility passes: P. Atherton, K. Weiler, D. Greenberg,
//! "Polygon shadow generation", Computer Graphics (SIGGRAPH '78) 12(3):275–281, 1978.
//!
//! What a point light sees is what it lights. The polygons are transformed into the
//! light's viewing frame and an object-precision hidden-surface pass is run there:
//! Weiler–Atherton polygon area sorting. Its output, the visible fragments, carried
//! back into object coordinates, are the lit parts of their polygons: coplanar
//! *surface detail polygons*. The ordinary pass from the eye then shades what a lit
//! detail polygon covers with the light and the rest without. The result is a 3D
//! polygon database, exact, and measurable: `lumiere shadow-polygons` lists the lit
//! and shadowed polygons of every receiver with their areas.
//!
//! Hidden-surface removal (Weiler & Atherton 1977): the polygons are sorted once,
//! roughly, nearest first. The first of the list is the clip polygon: every polygon
//! of the list is clipped against it into an inside list and an outside list, both
//! keeping the list's order. Inside pieces wholly behind the clip polygon are hidden.
//! An inside piece in front of it somewhere shows the sort was wrong there: the
//! process recurses with that piece as the clip polygon over the inside list, a
//! window within the window, and a stack of clip polygons guards the recursion
//! against cyclic overlap. What is left of the clip polygon is visible; the outside
//! list, still in order, is the next work list.
//!
//! Choices: a point light inside the scene sees all around, which a single viewing
//! frustum cannot hold (the paper's examples are outside the environment), so the
//! light's view is split into the six 90° frusta of a cube and each is processed on
//! its own. Fragment vertices are carried back by intersecting the line from the
//! light through them with the source polygon's plane. A region with holes enters the
//! eye's scan-line pass as one polygon whose contours are joined by doubled bridge
//! edges, which the even-odd sweep ignores. Fragments smaller than 1e-9 of a face's
//! area (debris of the clipper's perturbation) are dropped. A face crowded with more
//! than 256 polygons is first cut into four windows of the screen, recursively, each
//! polygon crossing a window's edge clipped to it, and each window's polygons go
//! through the removal above on their own: the removal compares the pieces of a list
//! pairwise, so one list of n costs n², while windows of bounded size cost n in all
//! (a screen subdivision in the manner of Warnock's, done before the removal; it
//! changes the cost, not which parts are visible). Scene key:
//! `[shadows] method = "shadow-polygons"`.

use super::cube_faces::{FACES, face_view};
use super::receivers::{ReceiverScreens, seen_in};
use super::{BandShadows, FrameShadows, LightShadows, per_sample};
use crate::geometry::plane::bounds;
use crate::geometry::sutherland_hodgman;
use crate::geometry::weiler_atherton::{self, Region, area};
use crate::raster::{DepthPlane, RasterVertex, ScreenPolygon, View, VisibleSurface};
use crate::scene::LightKind;
use crate::scene::Scene;
use crate::settings::ShadowMethod;
use glam::{DVec2, DVec3, Vec3};
use rayon::prelude::*;
use std::sync::Arc;

/// The registry's entry: lights at a point.
pub(crate) static METHOD: super::Method = super::Method {
    method: ShadowMethod::ShadowPolygons,
    name: "shadow-polygons",
    entry: Some("shadow-polygons"),
    handles: "a hard-shadow method for point and spot lights",
    lights: &[LightKind::Point, LightKind::Spot],
    counts: None,
    budget: super::no_budget,
    warnings: super::no_warnings,
    prepare: |scene, index, _, _| {
        let at = scene.lights[index].position().expect("checked");
        Some(Arc::new(ShadowPolygons::new(scene, at)))
    },
};

/// Coordinates of each light face span [0, FACE_SIZE]².
const FACE_SIZE: u32 = 1024;

/// A lit detail polygon: contours in object space on its polygon's plane, each with
/// its sign (+1 outer, −1 hole).
#[derive(Clone, Debug)]
pub struct DetailPolygon {
    pub contours: Vec<(Vec<DVec3>, f64)>,
}

impl DetailPolygon {
    pub fn area(&self) -> f64 {
        self.contours
            .iter()
            .map(|(c, sign)| sign * crate::geometry::polygon::area(c))
            .sum()
    }
}

/// One piece in the hidden-surface pass.
#[derive(Clone, Debug)]
struct Piece {
    source: u32,
    region: Region,
    plane: DepthPlane,
    /// The largest ζ = 1/depth over the region's vertices: its sort key.
    nearest: f64,
    /// The region's bounding box.
    bounds: (DVec2, DVec2),
}

impl Piece {
    fn new(source: u32, region: Region, plane: DepthPlane) -> Piece {
        let nearest = region
            .iter()
            .flatten()
            .map(|p| plane.zeta(p.x, p.y))
            .fold(f64::NEG_INFINITY, f64::max);
        let bounds = bounds(region.iter().flatten());
        Piece {
            source,
            region,
            plane,
            nearest,
            bounds,
        }
    }

    /// The same polygon's piece over another region.
    fn with_region(&self, region: Region) -> Piece {
        Piece::new(self.source, region, self.plane)
    }
}

/// The lit detail polygons of every scene polygon, for a point light at `light`.
pub fn lit_polygons(scene: &Scene, light: DVec3) -> Vec<Vec<DetailPolygon>> {
    let per_face: Vec<Vec<(u32, DetailPolygon)>> = FACES
        .par_iter()
        .map(|&face| {
            let view = face_view(scene, light, face, FACE_SIZE);
            let pieces: Vec<Piece> = scene
                .polygons
                .iter()
                .enumerate()
                .filter_map(|(id, p)| {
                    let vertices = p
                        .vertices
                        .iter()
                        .map(|v| RasterVertex::new(&view, v, Vec3::ZERO))
                        .collect();
                    let screen = ScreenPolygon::new(&view, id as u32, vertices)?;
                    let mut contour: Vec<DVec2> = screen
                        .vertices
                        .iter()
                        .map(|v| DVec2::new(v.x, v.y))
                        .collect();
                    if weiler_atherton::contour_area(&contour) < 0.0 {
                        contour.reverse();
                    }
                    Some(Piece::new(id as u32, vec![contour], screen.plane))
                })
                .collect();
            visible_by_windows(pieces)
                .into_iter()
                .map(|piece| {
                    let polygon = &scene.polygons[piece.source as usize];
                    let origin = polygon.vertices[0].position;
                    let back = |q: &DVec2| {
                        let d = view.ray(q.x, q.y);
                        light + d * ((origin - light).dot(polygon.normal) / d.dot(polygon.normal))
                    };
                    let contours = piece
                        .region
                        .iter()
                        .map(|c| {
                            (
                                c.iter().map(back).collect(),
                                weiler_atherton::contour_area(c).signum(),
                            )
                        })
                        .collect();
                    (piece.source, DetailPolygon { contours })
                })
                .collect()
        })
        .collect();
    let mut lit = vec![Vec::new(); scene.polygons.len()];
    for (source, detail) in per_face.into_iter().flatten() {
        lit[source as usize].push(detail);
    }
    lit
}

/// Most pieces one window's removal takes before its window is cut into quarters.
const WINDOW_PIECES: usize = 256;

/// How many times a window may be quartered: 1024 / 2^8 = 4 units across at most.
const DEEPEST: u32 = 8;

/// The visible part of every piece, by screen-area subdivision: a window holding
/// more than `WINDOW_PIECES` pieces is cut into four quarters, each piece reaching a
/// quarter clipped to it; each window's pieces then go through Weiler & Atherton's
/// removal on their own, literally. Without it the removal compares every piece with
/// every window's clip polygon, which grows as n² (a million polygons would take
/// hours); with it, as n. A face with fewer pieces is one window, as before.
fn visible_by_windows(pieces: Vec<Piece>) -> Vec<Piece> {
    let (lo, hi) = pieces.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p.bounds.0), hi.max(p.bounds.1)),
    );
    let sliver = 1e-9 * (FACE_SIZE as f64).powi(2);
    window_of(pieces, lo, hi, 0, sliver)
}

fn window_of(pieces: Vec<Piece>, lo: DVec2, hi: DVec2, depth: u32, sliver: f64) -> Vec<Piece> {
    if pieces.len() <= WINDOW_PIECES || depth == DEEPEST {
        return hidden_surface(pieces);
    }
    let middle = 0.5 * (lo + hi);
    let quarters = [
        (lo, middle),
        (DVec2::new(middle.x, lo.y), DVec2::new(hi.x, middle.y)),
        (middle, hi),
        (DVec2::new(lo.x, middle.y), DVec2::new(middle.x, hi.y)),
    ];
    quarters
        .into_par_iter()
        .flat_map_iter(|(qlo, qhi)| {
            let within: Vec<Piece> = pieces
                .iter()
                .filter_map(|piece| clipped_to(piece, qlo, qhi, sliver))
                .collect();
            window_of(within, qlo, qhi, depth + 1, sliver)
        })
        .collect()
}

/// The part of `piece` inside the rectangle [lo, hi], if more than a sliver.
fn clipped_to(piece: &Piece, lo: DVec2, hi: DVec2, sliver: f64) -> Option<Piece> {
    let (plo, phi) = piece.bounds;
    if plo.x >= hi.x || plo.y >= hi.y || phi.x <= lo.x || phi.y <= lo.y {
        return None;
    }
    if plo.cmpge(lo).all() && phi.cmple(hi).all() {
        return Some(piece.clone());
    }
    let rectangle = vec![lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
    let (within, _) = weiler_atherton::clip(&piece.region, &vec![rectangle]);
    (area(&within) > sliver).then(|| piece.with_region(within))
}

/// Weiler & Atherton's hidden-surface removal: the visible part of every piece.
///
/// The preliminary depth sort is done once; from then on every list is cut into
/// inside and outside lists that keep their order, so the work list stays sorted
/// without sorting it again. The first piece of the list is the clip polygon of a
/// window; what lies outside it is the next work list.
fn hidden_surface(mut pieces: Vec<Piece>) -> Vec<Piece> {
    sort_nearest_first(&mut pieces);
    let mut removal = Removal {
        sliver: 1e-9 * (FACE_SIZE as f64).powi(2),
        stack: Vec::new(),
        visible: Vec::new(),
    };
    while !pieces.is_empty() {
        pieces = removal.window(pieces, 0);
    }
    removal.visible
}

/// The state of one hidden-surface removal: the stack of clip polygons (their
/// source polygons) of the windows being worked on, and the pieces found visible.
struct Removal {
    sliver: f64,
    stack: Vec<u32>,
    visible: Vec<Piece>,
}

impl Removal {
    /// One window, whose clip polygon is `list[clip]`: every other piece of the list
    /// is clipped against a copy of it into an inside and an outside list. Inside
    /// pieces wholly behind the clip polygon are hidden and removed. An inside piece
    /// in front of it somewhere means the preliminary sort was wrong there: that
    /// piece becomes the clip polygon of a window within this one, over the inside
    /// list, which hands back the inside list less that piece's area; this repeats
    /// until nothing inside lies in front. What remains of the clip polygon is then
    /// visible. Returns the outside list, in the order of `list`.
    ///
    /// The paper guards its recursion against cyclic overlap with the stack of clip
    /// polygons; it leaves open what is done when the polygon in front is already on
    /// the stack (which, for planar polygons, means their depths cross in this
    /// window: interpenetration, or a cycle of several). Our choice: that piece is
    /// cut along the line where its depth crosses the clip polygon's, the part behind
    /// is hidden, and the part in front, wholly in front, becomes the next window's
    /// clip polygon. The recursion ends: a window within a window either takes a
    /// polygon not yet on the stack, or one wholly in front of its clip polygon over
    /// its area, and no chain of windows each wholly in front of the last can come
    /// back to a polygon in it; each round of the loop removes a piece's area.
    fn window(&mut self, list: Vec<Piece>, clip: usize) -> Vec<Piece> {
        let clipper = list[clip].clone();
        let (lo, hi) = clipper.bounds;
        self.stack.push(clipper.source);
        let mut inside = Vec::new();
        let mut outside = Vec::with_capacity(list.len());
        for (i, piece) in list.into_iter().enumerate() {
            if i == clip {
                inside.push(piece);
                continue;
            }
            let (plo, phi) = piece.bounds;
            let boxes_apart = plo.x > hi.x || plo.y > hi.y || phi.x < lo.x || phi.y < lo.y;
            if boxes_apart || weiler_atherton::apart(&piece.region, &clipper.region) {
                outside.push(piece);
                continue;
            }
            let (within, beyond) = weiler_atherton::clip(&piece.region, &clipper.region);
            if area(&within) > self.sliver {
                inside.push(piece.with_region(within));
            }
            if area(&beyond) > self.sliver {
                outside.push(piece.with_region(beyond));
            }
        }
        loop {
            // Remove what lies wholly behind; the first piece in front is next.
            let mut in_front = None;
            let mut kept = Vec::with_capacity(inside.len());
            for piece in inside {
                if piece.source != clipper.source {
                    let Some(ahead) = self.ahead(&piece, &clipper) else {
                        continue;
                    };
                    in_front.get_or_insert((kept.len(), ahead));
                }
                kept.push(piece);
            }
            inside = kept;
            let Some((at, ahead)) = in_front else {
                break;
            };
            if self.stack.contains(&inside[at].source) {
                inside[at] = inside[at].with_region(ahead);
            }
            inside = self.window(inside, at);
        }
        self.visible.extend(inside);
        self.stack.pop();
        outside
    }

    /// The part of `piece` nearer the light than `clipper`'s plane, if it is more
    /// than a sliver. Both are planar, so a piece none of whose vertices is nearer
    /// lies wholly behind.
    ///
    /// The cut is a Weiler–Atherton clip against the half-plane where the piece is
    /// nearer (the piece's box, grown, cut by the line where the depths cross):
    /// cutting a concave contour with Sutherland–Hodgman instead would join its
    /// parts by edges running both ways along the line, an outline that touches
    /// itself, on which the next window's clipping finds every crossing twice.
    fn ahead(&self, piece: &Piece, clipper: &Piece) -> Option<Region> {
        let (p, f) = (piece.plane, clipper.plane);
        let nearer = |q: &DVec2| p.zeta(q.x, q.y) - f.zeta(q.x, q.y) * (1.0 + 1e-9);
        if !piece.region.iter().flatten().any(|q| nearer(q) > 0.0) {
            return None;
        }
        if piece.region.iter().flatten().all(|q| nearer(q) > 0.0) {
            return Some(piece.region.clone());
        }
        let (lo, hi) = piece.bounds;
        let margin = (hi - lo).max_element() + 1.0;
        let (lo, hi) = (lo - DVec2::splat(margin), hi + DVec2::splat(margin));
        let frame = [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
        let half_plane = sutherland_hodgman::clip(&frame, nearer);
        if half_plane.len() < 3 {
            return None;
        }
        let (ahead, _) = weiler_atherton::clip(&piece.region, &vec![half_plane]);
        (area(&ahead) > self.sliver).then_some(ahead)
    }
}

fn sort_nearest_first(pieces: &mut [Piece]) {
    pieces.sort_by(|a, b| {
        b.nearest
            .total_cmp(&a.nearest)
            .then(a.source.cmp(&b.source))
    });
}

/// One polygon of the eye's view for a detail polygon: its contours joined by
/// doubled bridge edges from the first vertex (ignored by the even-odd sweep).
fn keyholed(view: &View, id: u32, detail: &DetailPolygon) -> Option<ScreenPolygon> {
    let anchor = detail.contours.first()?.0.first().copied()?;
    let mut loop_points = Vec::new();
    for (contour, _) in &detail.contours {
        loop_points.extend(contour.iter().copied());
        loop_points.push(contour[0]);
        loop_points.push(anchor);
    }
    ScreenPolygon::from_points(view, id, &loop_points)
}

/// The pre-pass for a point light: every polygon's lit detail polygons.
pub struct ShadowPolygons {
    light: DVec3,
    lit: Vec<Vec<DetailPolygon>>,
}

impl ShadowPolygons {
    pub fn new(scene: &Scene, light: DVec3) -> ShadowPolygons {
        ShadowPolygons {
            light,
            lit: lit_polygons(scene, light),
        }
    }
}

impl LightShadows for ShadowPolygons {
    fn frame<'a>(&'a self, scene: &'a Scene, view: &'a View) -> Box<dyn FrameShadows + 'a> {
        let project = move |r: usize| {
            self.lit[r]
                .iter()
                .filter_map(|d| keyholed(view, r as u32, d))
                .collect()
        };
        Box::new(DetailFrame {
            shadows: self,
            scene,
            view,
            screens: ReceiverScreens::new(scene.polygons.len(), view.height, project),
        })
    }
}

struct DetailFrame<'a, F> {
    shadows: &'a ShadowPolygons,
    scene: &'a Scene,
    view: &'a View,
    screens: ReceiverScreens<F>,
}

impl<F: Fn(usize) -> Vec<ScreenPolygon> + Sync + Send> FrameShadows for DetailFrame<'_, F> {
    fn band(&self, band: &VisibleSurface) -> BandShadows {
        let width = band.width as usize;
        let marks: Vec<Vec<usize>> = seen_in(band, self.scene.polygons.len())
            .into_par_iter()
            .filter(|&r| !self.shadows.lit[r].is_empty())
            .map(|receiver| {
                let mut covered = Vec::new();
                self.screens.spans(receiver, band, |row, a, b, _| {
                    for x in a..=b {
                        let k = (row - band.first_row) as usize * width + x as usize;
                        if band.samples[k].polygon == receiver as u32 {
                            covered.push(k);
                        }
                    }
                });
                covered
            })
            .collect();
        let mut lit_sample = vec![false; band.samples.len()];
        for k in marks.into_iter().flatten() {
            lit_sample[k] = true;
        }
        BandShadows::fraction(per_sample(
            self.scene,
            self.view,
            band,
            self.shadows.light,
            |k, _, _| lit_sample[k],
        ))
    }
}
