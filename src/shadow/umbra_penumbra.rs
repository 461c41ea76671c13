//! Umbra and penumbra from an area light, exactly: T. Nishita, E. Nakamae,
//! "Half-tone representation of 3-D objects illuminated by area sources or
//! polyhedron sources", Proc. IEEE COMPSAC '83, pp. 237–242, 1983 (and SIGGRAPH '85
//! 19(3):23–30 for the same direct-light machinery).
//!
//! The light is a convex Lambertian polygon (a concave emitter is split into
//! triangles, each a light of its own for the construction). For each convex
//! occluder O and each vertex s_k of the light, the point-light shadow volume
//! SV(O, s_k) is cut by a receiver's plane: the shadow of O from s_k on that plane
//! (O clipped to the slab between s_k and the plane, projected from s_k). The
//! umbra polygon is the intersection of these shadows; the penumbra polygon is their
//! convex hull less the umbra. Both are cut onto the receiver in a pre-pass. During
//! the frame, the receiver's umbra and penumbra polygons are swept with the
//! scan-line (`spans_inside`), which splits its visible spans at their boundaries:
//! a sample covered by an umbra polygon sees none of the light; one covered only by
//! penumbra polygons sees the light polygon less each tagged occluder projected from
//! the sample onto the light's plane (a convex hole cut to the light by
//! Sutherland–Hodgman; when several overlap, the light is cut along each hole's
//! edges in turn into disjoint convex pieces, `convex::subtract`), and shading takes
//! Lambert's contour integral over what
//! remains (`LightVisibility::Emitter`); elsewhere the light is whole. No sampling.
//!
//! Choices the paper leaves to the implementer:
//! - Occluders are convex pieces. An object is one piece when its faces are convex
//!   and it is convex (every vertex on or behind every face's plane) and either
//!   closed or open along one plane only (the Cornell blocks stand open on the
//!   floor: a segment crosses that plane at most once, so it meets a face whenever it
//!   meets the solid). Any other object (the teapot) is taken face by face, concave
//!   faces as triangles; faces of a closed object that turn their back on every light
//!   vertex are left out (the face a segment last crosses towards the light faces it).
//!   A receiver is never its own occluder's face: a convex piece cannot shade itself.
//! - The hull of the vertex shadows bounds the penumbra when the occluder lies
//!   nearer the receiver's plane than every light vertex (then the shadow of a point
//!   of the light is a projective image of the vertices' shadows). Where an occluder
//!   reaches past the light's nearest vertex, the whole receiver is taken as its
//!   penumbra, with no umbra: still exact, only slower.
//! - The light is cut to each side of a receiver's plane (light within 1e-9 of the
//!   scene's size of the plane grazes it and is left out of the construction only,
//!   not of the irradiance), so a receiver whose plane cuts the light gets both
//!   sides' polygons, and a sample uses those of the side the eye sees.
//! - Point and spot lights are the one-vertex case: the umbra polygon is the hard
//!   shadow and there is no penumbra (the self-shadow rule of the hard-shadow methods
//!   applies to them).
//! - Specular highlights: shading applies the visible part's share of Lambert's
//!   integral to the whole reflected light, the highlight of the light's
//!   representative point (its centroid) included, so a half-hidden light keeps half
//!   its highlight.
//!
//! Scene key: `[shadows] method = "umbra-penumbra"`; buffer `umbra-L`: 0 lit,
//! 1 penumbra, 2 umbra.

use super::receivers::{ReceiverScreens, seen_in};
use super::{BandShadows, FrameShadows, LightShadows, faces_away};
use crate::geometry::bvh::Aabb;
use crate::geometry::central_projection::{SHORT_OF_CENTRE, onto_plane};
use crate::geometry::convex::{hull, intersect, is_convex_ccw, subtract};
use crate::geometry::plane::{PlaneFrame, bounds};
use crate::geometry::polygon::triangulate;
use crate::geometry::sutherland_hodgman::clip;
use crate::geometry::weiler_atherton::contour_area;
use crate::raster::{LightVisibility, ScreenPolygon, View, VisiblePart, VisibleSurface};
use crate::scene::LightKind;
use crate::scene::{Light, Scene};
use crate::settings::ShadowMethod;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::Arc;
use std::sync::OnceLock;

/// The registry's entry: polygon lights exactly, and lights at a point.
pub(crate) static METHOD: super::Method = super::Method {
    method: ShadowMethod::UmbraPenumbra,
    name: "umbra-penumbra",
    entry: Some("umbra-penumbra"),
    handles: "a soft-shadow method for polygon lights (and point and spot lights)",
    lights: &[LightKind::Point, LightKind::Spot, LightKind::Polygon],
    counts: Some(super::CountBuffer {
        prefix: "umbra",
        description: "light {l}'s umbra map: 0 lit, 1 penumbra, 2 umbra (Nishita & Nakamae; colour-mapped)",
    }),
    budget: super::no_budget,
    warnings: super::no_warnings,
    prepare: |scene, index, _, _| {
        let exact = UmbraPenumbra::new(scene, &scene.lights[index]).expect("checked");
        Some(Arc::new(exact))
    },
};

/// The umbra map's levels.
pub const LIT: i32 = 0;
pub const PENUMBRA: i32 = 1;
pub const UMBRA: i32 = 2;

/// The light as the construction sees it.
struct Emitter {
    /// Convex pieces (counter-clockwise seen from the emitting side); a point light
    /// is one piece of one point.
    pieces: Vec<Vec<DVec3>>,
    /// The light's plane, emitting side as normal (none for a point light).
    plane: Option<PlaneFrame>,
    /// The pieces in the plane's frame, and their bounding box there.
    pieces_2d: Vec<Vec<DVec2>>,
    bounds_2d: (DVec2, DVec2),
    /// The scene polygon that emits (it occludes nothing).
    polygon: Option<usize>,
}

/// A convex occluder: its faces, and the scene polygons they are.
struct Occluder {
    faces: Vec<Vec<DVec3>>,
    /// The faces' corners, each once, and its edges, each once (as corner indices).
    corners: Vec<DVec3>,
    edges: Vec<(u32, u32)>,
    polygons: Vec<usize>,
    bounds: Aabb,
    sphere: Sphere,
}

/// A bounding sphere, for a quick test of whether an occluder can come between a
/// point and the light at all.
#[derive(Clone, Copy, Debug)]
struct Sphere {
    centre: DVec3,
    radius: f64,
}

impl Sphere {
    fn around<'a>(points: impl IntoIterator<Item = &'a DVec3> + Clone) -> Sphere {
        let b = Aabb::of(points.clone().into_iter().copied());
        let centre = 0.5 * (b.min + b.max);
        let radius = points
            .into_iter()
            .map(|p| (*p - centre).length())
            .fold(0.0, f64::max);
        Sphere { centre, radius }
    }

    /// Whether, seen from `x`, the cones around the two spheres are apart (neither
    /// sphere holds x): then nothing of one is in front of the other.
    fn apart_from(&self, other: &Sphere, x: DVec3) -> bool {
        let (a, b) = (self.centre - x, other.centre - x);
        let (da, db) = (a.length(), b.length());
        if da <= self.radius || db <= other.radius {
            return false;
        }
        let (sa, sb) = (self.radius / da, other.radius / db);
        let (ca, cb) = ((1.0 - sa * sa).sqrt(), (1.0 - sb * sb).sqrt());
        // The angle between the axes exceeds the sum of the half-angles when its
        // cosine is below cos(α + β) (with a margin for rounding).
        a.dot(b) / (da * db) < ca * cb - sa * sb - 1e-9
    }
}

/// An umbra or penumbra polygon on a receiver's plane.
#[derive(Clone, Debug)]
struct Cut {
    /// Which side of the receiver's plane it is for (+1 along its normal).
    side: i8,
    piece: u16,
    occluder: u32,
    umbra: bool,
    corners: Vec<DVec3>,
}

/// The pre-pass for one light: the occluders, and per receiver its umbra and
/// penumbra polygons, cut the first time a frame shows the receiver.
pub struct UmbraPenumbra {
    emitter: Emitter,
    occluders: Vec<Occluder>,
    /// Distances below this (the scene's size × 1e-9) count as on a plane.
    grazing: f64,
    cuts: Vec<OnceLock<Vec<Cut>>>,
    /// The light's position for a point-like light (the self-shadow rule).
    point: Option<DVec3>,
    light_sphere: Sphere,
}

impl UmbraPenumbra {
    /// `None` for a light the method cannot shadow (distant, sphere).
    pub fn new(scene: &Scene, light: &Light) -> Option<UmbraPenumbra> {
        let emitter = match light {
            Light::Point(_) | Light::Spot(_) => Emitter {
                pieces: vec![vec![light.position().expect("point-like")]],
                plane: None,
                pieces_2d: Vec::new(),
                bounds_2d: (DVec2::ZERO, DVec2::ZERO),
                polygon: None,
            },
            Light::Polygon(l) => {
                let plane = PlaneFrame::new(l.centre, l.normal);
                // Counter-clockwise about the emitting side, whatever the file's order.
                let counter_clockwise = |mut p: Vec<DVec3>| {
                    let flat: Vec<DVec2> = p.iter().map(|&q| plane.coords(q)).collect();
                    if contour_area(&flat) < 0.0 {
                        p.reverse();
                    }
                    p
                };
                let outline = counter_clockwise(l.vertices.clone());
                let whole: Vec<DVec2> = outline.iter().map(|&p| plane.coords(p)).collect();
                let pieces: Vec<Vec<DVec3>> = if is_convex_ccw(&whole) {
                    vec![outline]
                } else {
                    l.triangles
                        .iter()
                        .map(|t| counter_clockwise(t.to_vec()))
                        .collect()
                };
                let pieces_2d: Vec<Vec<DVec2>> = pieces
                    .iter()
                    .map(|p| p.iter().map(|&q| plane.coords(q)).collect())
                    .collect();
                Emitter {
                    pieces,
                    plane: Some(plane),
                    bounds_2d: bounds(pieces_2d.iter().flatten()),
                    pieces_2d,
                    polygon: Some(l.polygon),
                }
            }
            Light::Distant(_) | Light::Sphere(_) => return None,
        };
        let bounds = Aabb::of(scene.polygons.iter().flat_map(|p| p.positions()));
        let light_points: Vec<DVec3> = emitter.pieces.iter().flatten().copied().collect();
        let occluders = occluders(scene, emitter.polygon, &light_points);
        Some(UmbraPenumbra {
            emitter,
            occluders,
            grazing: 1e-9 * (bounds.max - bounds.min).length().max(1e-300),
            cuts: scene.polygons.iter().map(|_| OnceLock::new()).collect(),
            point: light.position(),
            light_sphere: Sphere::around(light_points.iter()),
        })
    }

    /// Receiver `r`'s umbra and penumbra polygons.
    fn cuts(&self, scene: &Scene, r: usize) -> &[Cut] {
        self.cuts[r].get_or_init(|| self.cut_onto(scene, r))
    }

    /// The umbra and penumbra polygons of every occluder on receiver `r`.
    fn cut_onto(&self, scene: &Scene, r: usize) -> Vec<Cut> {
        if Some(r) == self.emitter.polygon {
            return Vec::new();
        }
        let receiver = &scene.polygons[r];
        let origin = receiver.vertices[0].position;
        let frame = PlaneFrame::new(origin, receiver.normal);
        let outline: Vec<DVec3> = receiver.positions().collect();
        let outline_2d = hull(&outline.iter().map(|&p| frame.coords(p)).collect::<Vec<_>>());
        if outline_2d.len() < 3 {
            return Vec::new();
        }
        let mut cuts = Vec::new();
        for side in [1i8, -1] {
            let normal = receiver.normal * side as f64;
            let distance = |p: DVec3| (p - origin).dot(normal);
            // Each light piece's part on this side of the plane.
            let parts: Vec<Vec<DVec3>> = self
                .emitter
                .pieces
                .iter()
                .map(|piece| {
                    if piece.len() == 1 {
                        piece
                            .iter()
                            .copied()
                            .filter(|&p| distance(p) > self.grazing)
                            .collect()
                    } else {
                        clip(piece, |p| distance(*p) - self.grazing)
                    }
                })
                .collect();
            let lit: Vec<&DVec3> = parts.iter().flatten().collect();
            if lit.is_empty() {
                continue;
            }
            let reach = Aabb::of(outline.iter().copied().chain(lit.iter().map(|p| **p)));
            let light_near = lit
                .iter()
                .map(|&&p| distance(p))
                .fold(f64::INFINITY, f64::min);
            let light_far = lit.iter().map(|&&p| distance(p)).fold(0.0, f64::max);
            for (o, occluder) in self.occluders.iter().enumerate() {
                if occluder.polygons.contains(&r) || !occluder.bounds.overlaps(&reach) {
                    continue;
                }
                let (near, far) = occluder
                    .faces
                    .iter()
                    .flatten()
                    .map(|&p| distance(p))
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), d| {
                        (a.min(d), b.max(d))
                    });
                if far <= 0.0 || near >= light_far {
                    continue; // behind the receiver, or beyond the light
                }
                let mut push = |piece: usize, umbra: bool, region: &[DVec2]| {
                    let clipped = if umbra {
                        intersect(region, &outline_2d)
                    } else {
                        region.to_vec() // cut to the outline already
                    };
                    if !clipped.is_empty() {
                        cuts.push(Cut {
                            side,
                            piece: piece as u16,
                            occluder: o as u32,
                            umbra,
                            corners: clipped.iter().map(|&q| frame.point(q)).collect(),
                        });
                    }
                };
                // The umbra is the vertex shadows' intersection when the occluder is
                // nearer the plane than every light vertex.
                let bounded = far < light_near * (1.0 - 1e-6);
                for (piece, part) in parts.iter().enumerate() {
                    if part.is_empty() {
                        continue;
                    }
                    let shadows: Vec<Vec<DVec2>> = part
                        .iter()
                        .map(|&s| {
                            let points: Vec<DVec2> = occluder
                                .faces
                                .iter()
                                .filter_map(|f| onto_plane(f, s, origin, normal))
                                .flatten()
                                .map(|p| frame.coords(p))
                                .collect();
                            hull(&points)
                        })
                        .collect();
                    if part.len() == 1 {
                        // A point light: the shadow is the umbra, exactly.
                        if shadows[0].len() >= 3 {
                            push(piece, true, &shadows[0]);
                        }
                        continue;
                    }
                    let Some(penumbra) =
                        penumbra_section(occluder, part, &frame, normal, &outline_2d, self.grazing)
                    else {
                        continue;
                    };
                    if bounded && shadows.iter().all(|s| s.len() >= 3) {
                        let mut umbra = shadows[0].clone();
                        for s in &shadows[1..] {
                            umbra = intersect(&umbra, s);
                            if umbra.is_empty() {
                                break;
                            }
                        }
                        if !umbra.is_empty() {
                            push(piece, true, &umbra);
                        }
                    }
                    push(piece, false, &penumbra);
                }
            }
        }
        cuts
    }

    /// The part of the light seen from `x` on the emitting side, given for each
    /// light piece whether an umbra polygon covers `x` and which occluders' penumbra
    /// polygons do.
    fn visible_part(&self, x: DVec3, per_piece: &[(bool, Vec<u32>)]) -> Option<VisiblePart> {
        let plane = self.emitter.plane.expect("an area light");
        let mut contours = Vec::new();
        let mut hidden = false;
        for (j, (umbra, tagged)) in per_piece.iter().enumerate() {
            if *umbra {
                hidden = true;
                continue;
            }
            let piece = &self.emitter.pieces_2d[j];
            let holes: Vec<Vec<DVec2>> = tagged
                .iter()
                .filter_map(|&o| {
                    let projected = self.seen_from(x, &self.occluders[o as usize], &plane)?;
                    let hole = intersect(&projected, piece);
                    (!hole.is_empty()).then_some(hole)
                })
                .collect();
            hidden |= !holes.is_empty();
            match holes.as_slice() {
                [] => contours.push((self.emitter.pieces[j].clone(), 1.0)),
                [hole] => {
                    contours.push((self.emitter.pieces[j].clone(), 1.0));
                    contours.push((hole.iter().map(|&q| plane.point(q)).collect(), -1.0));
                }
                _ => {
                    for c in subtract(piece, &holes) {
                        contours.push((c.iter().map(|&q| plane.point(q)).collect(), 1.0));
                    }
                }
            }
        }
        hidden.then_some(VisiblePart { contours })
    }

    /// Occluder `o` seen from `x`: its part between x and the light's plane,
    /// projected from x onto that plane (convex: the hull of its faces' projections).
    fn seen_from(&self, x: DVec3, o: &Occluder, plane: &PlaneFrame) -> Option<Vec<DVec2>> {
        if o.sphere.apart_from(&self.light_sphere, x) {
            return None;
        }
        // Distances to the light's plane, on x's side.
        let height = (x - plane.origin).dot(plane.normal);
        let side = height.signum();
        let h = height.abs();
        let limit = h * SHORT_OF_CENTRE;
        let distance = |p: DVec3| (p - plane.origin).dot(plane.normal) * side;
        let project = |p: DVec3, d: f64| plane.coords(x + (p - x) * (h / (h - d)));
        // The convex occluder cut to the slab between x and the plane: its corners
        // inside, and where its edges cross the slab's two faces.
        let mut points = Vec::with_capacity(o.corners.len() + 2 * o.edges.len());
        let mut cut = false;
        for &p in &o.corners {
            let d = distance(p);
            if (0.0..=limit).contains(&d) {
                points.push(project(p, d));
            } else {
                cut = true;
            }
        }
        if cut {
            for &(i, j) in &o.edges {
                let (a, b) = (o.corners[i as usize], o.corners[j as usize]);
                let (da, db) = (distance(a), distance(b));
                for level in [0.0, limit] {
                    if (da - level) * (db - level) < 0.0 {
                        points.push(project(a + (b - a) * ((level - da) / (db - da)), level));
                    }
                }
            }
        }
        // Nothing of it over the light: no need for its outline.
        let (lo, hi) = bounds(&points);
        let (light_lo, light_hi) = self.emitter.bounds_2d;
        if lo.x > light_hi.x || lo.y > light_hi.y || hi.x < light_lo.x || hi.y < light_lo.y {
            return None;
        }
        let outline = hull(&points);
        (outline.len() >= 3).then_some(outline)
    }
}

/// The section by a receiver's plane (`frame`, normal towards the light part) of
/// the convex hull of the shadow volumes of `occluder` from the light points
/// `part`, within the receiver's outline `outline`: a bound of every point some
/// point of the light's part is hidden from by the occluder (Nishita & Nakamae's
/// penumbra with its umbra).
///
/// The hull is that of the occluder's corners (cut to the light's side of the
/// plane) and of the rays from each corner o away from each light point s, along
/// o − s. Rays running towards the plane meet it at points P; rays running away
/// from it or along it give, paired so that their combination runs along the plane,
/// the section's unbounded directions W. With no such direction, the section is the
/// hull of P (the hull of the vertex shadows). With some, it is hull(P) + cone(W):
/// for a pointed cone of half-angle θ it is truncated at P + M·(its two edges), M
/// the span of P and the outline over cos θ, which loses nothing within the outline;
/// a cone of half a plane or more is the whole outline.
///
/// `normal` is the receiver's normal on the light part's side (the frame's, or its
/// opposite when the part lies behind the receiver's plane).
fn penumbra_section(
    occluder: &Occluder,
    part: &[DVec3],
    frame: &PlaneFrame,
    normal: DVec3,
    outline: &[DVec2],
    grazing: f64,
) -> Option<Vec<DVec2>> {
    let distance = |p: DVec3| (p - frame.origin).dot(normal);
    // The occluder's corners on the light's side of the plane.
    let mut corners: Vec<DVec3> = occluder
        .corners
        .iter()
        .copied()
        .filter(|&p| distance(p) >= 0.0)
        .collect();
    for &(i, j) in &occluder.edges {
        let (a, b) = (occluder.corners[i as usize], occluder.corners[j as usize]);
        let (da, db) = (distance(a), distance(b));
        if da * db < 0.0 {
            corners.push(a + (b - a) * (da / (da - db)));
        }
    }
    let mut points = Vec::new();
    let (mut toward, mut along) = (Vec::new(), Vec::new());
    for &o in &corners {
        let d_o = distance(o);
        if d_o <= grazing {
            points.push(frame.coords(o));
        }
        for &s in part {
            let direction = o - s;
            let rate = direction.dot(normal);
            if rate < -grazing * 1e-3 {
                points.push(frame.coords(o + direction * (d_o / -rate)));
                toward.push((direction, rate));
            } else {
                along.push((direction, rate));
            }
        }
    }
    if points.is_empty() {
        return None;
    }
    // Directions along the plane: those already along it, and away + toward pairs.
    let in_plane = |v: DVec3| frame.coords(frame.origin + v);
    let mut unbounded: Vec<DVec2> = Vec::new();
    for &(a, rate_a) in &along {
        if rate_a <= grazing * 1e-3 {
            unbounded.push(in_plane(a));
        } else {
            for &(t, rate_t) in &toward {
                unbounded.push(in_plane(a * -rate_t + t * rate_a));
            }
        }
    }
    unbounded.retain(|w| w.length() > 0.0);
    if unbounded.is_empty() {
        let h = hull(&points);
        return (h.len() >= 3)
            .then(|| intersect(&h, outline))
            .filter(|c| !c.is_empty());
    }
    let mut angles: Vec<f64> = unbounded.iter().map(|w| w.y.atan2(w.x)).collect();
    angles.sort_by(f64::total_cmp);
    // The widest gap between neighbouring directions: the cone is what it leaves.
    let (mut gap, mut after) = (
        angles[0] + 2.0 * std::f64::consts::PI - angles[angles.len() - 1],
        0,
    );
    for i in 1..angles.len() {
        if angles[i] - angles[i - 1] > gap {
            gap = angles[i] - angles[i - 1];
            after = i;
        }
    }
    let half = 0.5 * (2.0 * std::f64::consts::PI - gap);
    if half.cos() < 1e-3 {
        return Some(outline.to_vec());
    }
    let first = angles[after];
    let last = angles[(after + angles.len() - 1) % angles.len()];
    let (lo, hi) = bounds(points.iter().chain(outline));
    let reach = (hi - lo).length() / half.cos();
    let edges = [first, last].map(|a| DVec2::new(a.cos(), a.sin()) * reach);
    let far: Vec<DVec2> = points
        .iter()
        .flat_map(|&p| [p, p + edges[0], p + edges[1]])
        .collect();
    let h = hull(&far);
    (h.len() >= 3)
        .then(|| intersect(&h, outline))
        .filter(|c| !c.is_empty())
}

/// The scene's convex occluders for a light with points `light_points`, the
/// emitter's own polygon left out.
fn occluders(scene: &Scene, emitter: Option<usize>, light_points: &[DVec3]) -> Vec<Occluder> {
    let mut by_object: Vec<Vec<usize>> = vec![Vec::new(); scene.objects.len()];
    for (id, p) in scene.polygons.iter().enumerate() {
        if Some(id) != emitter {
            by_object[p.object].push(id);
        }
    }
    let mut occluders = Vec::new();
    for (object, ids) in by_object.iter().enumerate() {
        if ids.is_empty() {
            continue;
        }
        let holds_emitter = emitter.is_some_and(|e| scene.polygons[e].object == object);
        let faces: Vec<Vec<DVec3>> = ids
            .iter()
            .map(|&id| scene.polygons[id].positions().collect())
            .collect();
        let (convex, closed) = shape_of(scene, ids);
        if convex && !holds_emitter {
            occluders.push(Occluder {
                bounds: Aabb::of(faces.iter().flatten().copied()),
                sphere: Sphere::around(faces.iter().flatten()),
                corners: distinct(faces.iter().flatten()),
                edges: edges_of(&faces),
                faces,
                polygons: ids.clone(),
            });
            continue;
        }
        for (&id, face) in ids.iter().zip(faces) {
            let p = &scene.polygons[id];
            // On a closed object, a face with every light point behind it is never
            // the last one a segment towards the light crosses.
            if closed
                && light_points
                    .iter()
                    .all(|&s| p.normal.dot(s - face[0]) <= 0.0)
            {
                continue;
            }
            let pieces = if face_is_convex(&face, p.normal) {
                vec![face]
            } else {
                triangulate(&face)
                    .into_iter()
                    .map(|t| t.iter().map(|&k| face[k]).collect())
                    .collect()
            };
            for piece in pieces {
                occluders.push(Occluder {
                    bounds: Aabb::of(piece.iter().copied()),
                    sphere: Sphere::around(piece.iter()),
                    corners: distinct(piece.iter()),
                    edges: edges_of(std::slice::from_ref(&piece)),
                    faces: vec![piece],
                    polygons: vec![id],
                });
            }
        }
    }
    occluders
}

/// The points, each once (by their bits).
fn distinct<'a>(points: impl Iterator<Item = &'a DVec3>) -> Vec<DVec3> {
    let mut out: Vec<DVec3> = Vec::new();
    for p in points {
        if !out.contains(p) {
            out.push(*p);
        }
    }
    out
}

/// The edges of `faces`, each once, as indices into `distinct` of their corners.
fn edges_of(faces: &[Vec<DVec3>]) -> Vec<(u32, u32)> {
    let corners = distinct(faces.iter().flatten());
    let index = |p: &DVec3| corners.iter().position(|q| q == p).expect("a corner") as u32;
    let mut edges = Vec::new();
    for f in faces {
        for i in 0..f.len() {
            let (a, b) = (index(&f[i]), index(&f[(i + 1) % f.len()]));
            let e = (a.min(b), a.max(b));
            if a != b && !edges.contains(&e) {
                edges.push(e);
            }
        }
    }
    edges
}

/// Whether a planar polygon is convex (no reflex corner about its normal).
fn face_is_convex(face: &[DVec3], normal: DVec3) -> bool {
    let n = face.len();
    (0..n).all(|i| {
        let (a, b, c) = (face[i], face[(i + 1) % n], face[(i + 2) % n]);
        (b - a).cross(c - b).dot(normal) >= -1e-12 * (b - a).length() * (c - b).length()
    })
}

/// Above this many face–vertex tests an object is taken face by face without
/// testing its convexity (a finely tessellated sphere).
const CONVEXITY_TESTS: usize = 10_000_000;

/// Whether the object made of polygons `ids` can be taken as one convex occluder
/// (convex faces; every vertex on or behind every face's plane; closed, or open
/// along one plane only), and whether it is closed.
fn shape_of(scene: &Scene, ids: &[usize]) -> (bool, bool) {
    type Key = [u64; 3];
    let key = |p: DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
    let mut edges: HashMap<(Key, Key), (DVec3, DVec3)> = HashMap::new();
    let mut vertices = Vec::new();
    for &id in ids {
        let corners: Vec<DVec3> = scene.polygons[id].positions().collect();
        for i in 0..corners.len() {
            let (a, b) = (corners[i], corners[(i + 1) % corners.len()]);
            if edges.remove(&(key(b), key(a))).is_none() {
                edges.insert((key(a), key(b)), (a, b));
            }
        }
        vertices.extend(corners);
    }
    let closed = edges.is_empty();
    if ids.len() * vertices.len() > CONVEXITY_TESTS {
        return (false, closed);
    }
    let bounds = Aabb::of(vertices.iter().copied());
    let tolerance = 1e-9 * (bounds.max - bounds.min).length();
    let convex_faces = ids.iter().all(|&id| {
        let p = &scene.polygons[id];
        face_is_convex(&p.positions().collect::<Vec<_>>(), p.normal)
    });
    let convex = convex_faces
        && ids.iter().all(|&id| {
            let p = &scene.polygons[id];
            let at = p.vertices[0].position;
            vertices.iter().all(|&v| p.normal.dot(v - at) <= tolerance)
        });
    if !convex || closed {
        return (convex, closed);
    }
    // Open: the boundary must lie in one plane.
    let boundary: Vec<DVec3> = edges.values().flat_map(|&(a, b)| [a, b]).collect();
    let normal = boundary
        .iter()
        .flat_map(|&a| boundary.iter().map(move |&b| (a, b)))
        .map(|(a, b)| (a - boundary[0]).cross(b - boundary[0]))
        .max_by(|x, y| x.length().total_cmp(&y.length()))
        .unwrap_or(DVec3::ZERO)
        .normalize_or_zero();
    let planar = normal == DVec3::ZERO
        || boundary
            .iter()
            .all(|&p| normal.dot(p - boundary[0]).abs() <= tolerance);
    (planar, closed)
}

impl LightShadows for UmbraPenumbra {
    fn frame<'a>(&'a self, scene: &'a Scene, view: &'a View) -> Box<dyn FrameShadows + 'a> {
        let project = move |r: usize| {
            self.cuts(scene, r)
                .iter()
                .enumerate()
                .filter_map(|(i, cut)| ScreenPolygon::from_points(view, i as u32, &cut.corners))
                .collect()
        };
        Box::new(UmbraFrame {
            method: self,
            scene,
            view,
            screens: ReceiverScreens::new(scene.polygons.len(), view.height, project),
        })
    }
}

struct UmbraFrame<'a, F> {
    method: &'a UmbraPenumbra,
    scene: &'a Scene,
    view: &'a View,
    screens: ReceiverScreens<F>,
}

/// One sample's answer: its umbra-map level and, for an area light, the visible part
/// (`None`: all of the light).
type Answer = (i32, Option<VisiblePart>);

impl<F: Fn(usize) -> Vec<ScreenPolygon> + Sync + Send> FrameShadows for UmbraFrame<'_, F> {
    fn band(&self, band: &VisibleSurface) -> BandShadows {
        let method = self.method;
        let pieces = method.emitter.pieces.len();
        // Per receiver, the answers at the samples where it is visible.
        let found: Vec<Vec<(usize, Answer)>> = seen_in(band, self.scene.polygons.len())
            .into_par_iter()
            .map(|r| {
                let cuts = method.cuts(self.scene, r);
                let receiver = &self.scene.polygons[r];
                // A plane is seen from one side only: the eye's.
                let towards_eye = receiver
                    .normal
                    .dot(self.view.eye - receiver.vertices[0].position);
                let side = if towards_eye >= 0.0 { 1 } else { -1 };
                let mut answers = Vec::new();
                let mut per_piece: Vec<(bool, Vec<u32>)> = vec![(false, Vec::new()); pieces];
                self.screens.spans(r, band, |row, a, b, inside| {
                    per_piece.iter_mut().for_each(|(umbra, tagged)| {
                        *umbra = false;
                        tagged.clear();
                    });
                    let mut touched = false;
                    for &i in inside {
                        let cut = &cuts[i as usize];
                        if cut.side != side {
                            continue;
                        }
                        touched = true;
                        let entry = &mut per_piece[cut.piece as usize];
                        if cut.umbra {
                            entry.0 = true;
                        } else if !entry.1.contains(&cut.occluder) {
                            entry.1.push(cut.occluder);
                        }
                    }
                    if !touched {
                        return;
                    }
                    for x in a..=b {
                        let k = ((row - band.first_row) * band.width + x) as usize;
                        let s = &band.samples[k];
                        if s.polygon as usize == r {
                            answers.push((k, method.answer(s.position, &per_piece)));
                        }
                    }
                });
                answers
            })
            .collect();
        let mut levels = vec![LIT; band.samples.len()];
        let mut parts: Vec<Option<VisiblePart>> = vec![None; band.samples.len()];
        for (k, (level, part)) in found.into_iter().flatten() {
            levels[k] = level;
            parts[k] = part;
        }
        let visibility = match method.point {
            Some(light) => LightVisibility::Fraction(
                band.samples
                    .par_iter()
                    .zip(&levels)
                    .map(|(s, &level)| {
                        let lit = !s.is_empty()
                            && level != UMBRA
                            && !faces_away(self.scene, self.view, s.polygon, s.position, light);
                        if lit { 1.0 } else { 0.0 }
                    })
                    .collect(),
            ),
            None => LightVisibility::Emitter(parts),
        };
        BandShadows {
            visibility,
            counts: Some(levels),
        }
    }
}

impl UmbraPenumbra {
    /// The level and visible part at `x`, from what covers it.
    fn answer(&self, x: DVec3, per_piece: &[(bool, Vec<u32>)]) -> Answer {
        if per_piece.iter().all(|(umbra, _)| *umbra) {
            return (UMBRA, Some(VisiblePart::default()));
        }
        if self.emitter.plane.is_none() {
            return (LIT, None); // a point light outside every umbra
        }
        if per_piece
            .iter()
            .all(|(umbra, tagged)| !umbra && tagged.is_empty())
        {
            return (LIT, None);
        }
        match self.visible_part(x, per_piece) {
            None => (LIT, None),
            Some(part) if part.contours.is_empty() => (UMBRA, Some(part)),
            Some(part) => (PENUMBRA, Some(part)),
        }
    }
}

/// The visible part of `light` (a polygon light) from `x` with every occluder of the
/// scene subtracted, no umbra or penumbra polygon consulted: the brute-force
/// reference the construction must equal (`UmbraPenumbra::everywhere` for many
/// points, its occluders found once).
pub fn visible_part_everywhere(scene: &Scene, light: &Light, x: DVec3) -> Option<VisiblePart> {
    UmbraPenumbra::new(scene, light)?.everywhere(x)
}

impl UmbraPenumbra {
    /// As `visible_part_everywhere`, for this light (`None` for a point light).
    pub fn everywhere(&self, x: DVec3) -> Option<VisiblePart> {
        self.emitter.plane?;
        let all: Vec<u32> = (0..self.occluders.len() as u32).collect();
        let per_piece: Vec<(bool, Vec<u32>)> = self
            .emitter
            .pieces
            .iter()
            .map(|_| (false, all.clone()))
            .collect();
        Some(self.visible_part(x, &per_piece).unwrap_or_else(|| {
            VisiblePart {
                contours: self
                    .emitter
                    .pieces
                    .iter()
                    .map(|p| (p.clone(), 1.0))
                    .collect(),
            }
        }))
    }
}
