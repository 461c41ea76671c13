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
//! Hidden-surface removal (Weiler & Atherton 1977): the polygons, sorted nearest
//! first, are taken in turn; the front one clips every other into the part inside
//! its outline and the part outside. Inside parts behind it are hidden. An inside
//! part in front of it (a sort error, or interpenetration: it is split where the two
//! depths cross) hides that much of it and carries on. The front polygon's remaining
//! area is emitted, and the process repeats on the rest.
//!
//! Choices: a point light inside the scene sees all around, which a single viewing
//! frustum cannot hold (the paper's examples are outside the environment), so the
//! light's view is split into the six 90° frusta of a cube and each is processed on
//! its own. Fragment vertices are carried back by intersecting the line from the
//! light through them with the source polygon's plane. A region with holes enters the
//! eye's scan-line pass as one polygon whose contours are joined by doubled bridge
//! edges, which the even-odd sweep ignores. Fragments smaller than 1e-9 of a face's
//! area (debris of the clipper's perturbation) are dropped. Scene key:
//! `[shadows] method = "shadow-polygons"`.

use super::cube_faces::{FACES, face_view};
use super::receivers::{ReceiverScreens, seen_in};
use super::{BandShadows, FrameShadows, LightShadows, per_sample};
use crate::geometry::sutherland_hodgman;
use crate::geometry::weiler_atherton::{self, Region, area};
use crate::raster::{DepthPlane, RasterVertex, ScreenPolygon, View, VisibleSurface};
use crate::scene::Scene;
use glam::{DVec2, DVec3, Vec3};
use rayon::prelude::*;

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
        let bounds = weiler_atherton::bounds(region.iter().flatten());
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
            hidden_surface(pieces)
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

/// Weiler–Atherton hidden-surface removal: the visible part of every piece.
fn hidden_surface(mut pieces: Vec<Piece>) -> Vec<Piece> {
    let sliver = 1e-9 * (FACE_SIZE as f64).powi(2);
    let mut visible = Vec::new();
    sort_nearest_first(&mut pieces);
    while !pieces.is_empty() {
        let front = pieces.remove(0);
        let (lo, hi) = front.bounds;
        let mut shown = front.region.clone();
        let mut rest = Vec::with_capacity(pieces.len());
        for piece in pieces.drain(..) {
            let (plo, phi) = piece.bounds;
            if plo.x > hi.x || plo.y > hi.y || phi.x < lo.x || phi.y < lo.y {
                rest.push(piece);
                continue;
            }
            let (inside, outside) = weiler_atherton::clip(&piece.region, &front.region);
            if area(&outside) > sliver {
                rest.push(piece.with_region(outside));
            }
            if area(&inside) <= sliver {
                continue;
            }
            // The part of the inside piece nearer than the front polygon.
            let (p, f) = (piece.plane, front.plane);
            let ahead: Region = inside
                .iter()
                .map(|c| {
                    sutherland_hodgman::clip(c, |q| {
                        p.zeta(q.x, q.y) - f.zeta(q.x, q.y) * (1.0 + 1e-9)
                    })
                })
                .filter(|c| c.len() >= 3)
                .collect();
            if area(&ahead) > sliver {
                shown = weiler_atherton::clip(&shown, &ahead).1;
                rest.push(piece.with_region(ahead));
            }
        }
        if area(&shown) > sliver {
            visible.push(front.with_region(shown));
        }
        pieces = rest;
        sort_nearest_first(&mut pieces);
    }
    visible
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
