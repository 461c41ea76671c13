//! Shadow volumes: F. C. Crow, "Shadow algorithms for computer graphics", Computer
//! Graphics (SIGGRAPH '77) 11(2):242–248, 1977.
//!
//! For each object, the edges of its silhouette as seen from the light are found:
//! edges between a polygon facing the light and one facing away (or no polygon at
//! all, on an open boundary). An object of a single polygon is two-sided: whichever
//! side the light is on faces it. Through each silhouette edge a shadow polygon is built,
//! the quad from the edge to its projection away from the light, "taken far enough"
//! (Crow's V_i) and then clipped to the view volume like any polygon. The shadow
//! polygons are invisible surfaces of the scan-line pass itself: they enter its edge
//! table beside the scene's polygons and cut its spans, but take no part in
//! visibility (`raster::scan_out`). Along each piece of a span, a shadow polygon in
//! front of the visible surface counts +1 if it faces the eye (entering a volume)
//! and −1 if it faces away (leaving it); where its depth crosses the visible
//! surface's the piece is split. A point is in shadow when the count, started at
//! the number of volumes that contain the eye, is positive. Heidmann's count buffer
//! (`stencil_shadow_volumes`) finds the same counts after the pass.
//!
//! The method is only as valid as the objects: a volume is closed only if its object
//! is a closed 2-manifold. On an open mesh, polygons facing away from the light still
//! block it, but no silhouette edge bounds their shadow, so light leaks (entry
//! `shadow-volumes-open-mesh`); `open_objects` names such objects for a warning. A
//! light inside a closed object sees only its back faces: no silhouette, no volume,
//! and the object shadows nothing (Crow assumes lights outside the objects).
//!
//! Choices: the eye's starting count is the number of light-facing polygons crossed
//! by the segment from the eye to the light; a shadow polygon counts at a pixel when
//! it is nearer than the visible surface by a relative 1e-9 (the quads start on the
//! occluders' own edges). Scene key: `[shadows] method = "shadow-volumes"`.

use super::{BandShadows, FrameShadows, LightShadows, faces_away, per_sample};
use crate::geometry::bvh::Aabb;
use crate::geometry::polygon::{centroid, newell_normal};
use crate::raster::{
    DepthPlane, EdgeTable, LightVisibility, ScreenPolygon, View, VisibleSurface, scan_out,
    screen_polygons,
};
use crate::scene::Scene;
use crate::scene::ray_queries::segment_meets_polygon;
use crate::scene::{Light, LightKind, Reach};
use crate::settings::ShadowMethod;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::Arc;

/// The registry's entry: lights at a point and distant lights; a warning for the
/// objects whose volumes may leak.
pub(crate) static METHOD: super::Method = super::Method {
    method: ShadowMethod::ShadowVolumes,
    name: "shadow-volumes",
    entry: Some("shadow-volumes"),
    handles: "a hard-shadow method for point, spot and distant lights",
    lights: &[LightKind::Point, LightKind::Spot, LightKind::Distant],
    counts: Some(COUNTS),
    budget: super::no_budget,
    warnings: leak_warnings,
    prepare: |scene, index, _, _| {
        let source = Source::of(&scene.lights[index]);
        Some(Arc::new(ShadowVolumes::from_source(
            scene,
            source,
            Counting::ScanOut,
        )))
    },
};

/// Crow's count per sample, the buffer both ways of counting make.
pub(crate) const COUNTS: super::CountBuffer = super::CountBuffer {
    prefix: "shadow-volume-counts",
    description: "shadow volumes of light {l} containing each visible point (Crow's count; colour-mapped)",
};

/// One line naming the objects whose volumes may leak light, if any: Crow's count
/// assumes closed objects, and an open one's volume has sides missing where its
/// boundary edges are. Whether a leak reaches the image depends on where the eye's
/// rays cross those sides, so the line says how to check.
pub(crate) fn leak_warnings(scene: &Scene) -> Vec<String> {
    let open = open_objects(scene);
    if open.is_empty() {
        return Vec::new();
    }
    const NAMED: usize = 5;
    let mut names: Vec<String> = open.iter().take(NAMED).map(|n| format!("`{n}`")).collect();
    if open.len() > NAMED {
        names.push(format!("and {} more", open.len() - NAMED));
    }
    let (count, are) = match open.len() {
        1 => (
            "1 object is not a closed 2-manifold".to_string(),
            "its shadow volume",
        ),
        n => (
            format!("{n} objects are not closed 2-manifolds"),
            "their shadow volumes",
        ),
    };
    vec![format!(
        "{count} ({}): {are} may leak light where a view ray crosses a missing side; compare with --shadows ray-cast to see whether this image is touched",
        names.join(", ")
    )]
}

/// A shadow polygon: the quad through a silhouette edge, with its normal pointing out
/// of the shadow volume.
#[derive(Clone, Debug)]
pub struct ShadowQuad {
    pub corners: [DVec3; 4],
    pub outward: DVec3,
}

/// An edge by the exact bits of its end points (shared vertices are equal points).
type EdgeKey = ([u64; 3], [u64; 3]);

fn key(p: DVec3) -> [u64; 3] {
    [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]
}

/// Where a volume's light comes from: a point, or a direction (a distant light,
/// whose volumes are prisms: their quads are extruded along its travel).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Source {
    Point(DVec3),
    /// The unit direction the light travels.
    Distant(DVec3),
}

impl Source {
    /// Where `light`'s volumes start: its direction if distant, else its position.
    pub fn of(light: &Light) -> Source {
        match light.reach() {
            Reach::Direction { direction, .. } => Source::Distant(direction),
            Reach::Point { at, .. } => Source::Point(at),
            Reach::Extended { .. } => Source::Point(light.position().expect("checked")),
        }
    }

    fn faces(self, normal: DVec3, on_plane: DVec3) -> bool {
        match self {
            Source::Point(light) => normal.dot(light - on_plane) > 0.0,
            Source::Distant(travel) => normal.dot(-travel) > 0.0,
        }
    }

    /// `p` moved `far` away from the light.
    fn away(self, p: DVec3, far: f64) -> DVec3 {
        match self {
            Source::Point(light) => p + (p - light).normalize() * far,
            Source::Distant(travel) => p + travel * far,
        }
    }
}

/// The shadow polygons of every object for a point light at `light`.
pub fn shadow_quads(scene: &Scene, light: DVec3) -> Vec<ShadowQuad> {
    quads_from(scene, Source::Point(light))
}

/// How far the quads reach beyond the scene (and a point light): 4 times the
/// diagonal of their bounds.
pub fn reach(scene: &Scene, source: Source) -> f64 {
    let light = match source {
        Source::Point(p) => Some(p),
        Source::Distant(_) => None,
    };
    let bounds = Aabb::of(
        scene
            .polygons
            .iter()
            .flat_map(|p| p.positions())
            .chain(light),
    );
    4.0 * (bounds.max - bounds.min).length()
}

/// The shadow polygons of every object for a light from `source`.
pub fn quads_from(scene: &Scene, source: Source) -> Vec<ShadowQuad> {
    quads_except(scene, source, None)
}

/// As `quads_from`, polygon `emitter` (the light's own, whose points are the
/// sources) casting nothing: a source in its plane sees it edge-on, and the quads
/// its edges would sweep lie in that plane, where a concave emitter's overlap.
pub fn quads_except(scene: &Scene, source: Source, emitter: Option<usize>) -> Vec<ShadowQuad> {
    let far = reach(scene, source);
    let mut quads = Vec::new();
    for object in 0..scene.objects.len() {
        // Directed edges of the light-facing polygons; an edge walked both ways lies
        // between two of them and bounds nothing.
        let mut edges: HashMap<EdgeKey, (DVec3, DVec3, DVec3, i32)> = HashMap::new();
        let polygons: Vec<_> = scene
            .polygons
            .iter()
            .enumerate()
            .filter(|&(i, p)| p.object == object && Some(i) != emitter)
            .map(|(_, p)| p)
            .collect();
        // A lone polygon is two-sided: whichever side the light is on faces it.
        let lone = polygons.len() == 1;
        for p in polygons {
            let corners: Vec<DVec3> = p.positions().collect();
            let facing =
                source.faces(p.normal, corners[0]) || (lone && source.faces(-p.normal, corners[0]));
            if !facing {
                continue;
            }
            let inside = centroid(&corners);
            for i in 0..corners.len() {
                let (a, b) = (corners[i], corners[(i + 1) % corners.len()]);
                let (ka, kb) = (key(a), key(b));
                if let Some(e) = edges.get_mut(&(kb, ka)) {
                    e.3 -= 1;
                } else {
                    edges.entry((ka, kb)).or_insert((a, b, inside, 0)).3 += 1;
                }
            }
        }
        let mut silhouette: Vec<(DVec3, DVec3, DVec3, i32)> =
            edges.into_values().filter(|e| e.3 != 0).collect();
        // HashMap order is arbitrary; the counts do not depend on it, but keep the
        // quads in a reproducible order anyway.
        silhouette.sort_by_key(|e| (key(e.0), key(e.1)));
        for (a, b, inside, _) in silhouette {
            let corners = [a, b, source.away(b, far), source.away(a, far)];
            let n = newell_normal(&corners).normalize_or_zero();
            if n == DVec3::ZERO {
                continue; // the edge points at the light: its quad has no area
            }
            let outward = if n.dot(inside - a) > 0.0 { -n } else { n };
            quads.push(ShadowQuad { corners, outward });
        }
    }
    quads
}

/// The quads on a view's screen, each with its step along a line of sight: +1 for
/// one facing the eye (entering a volume), −1 for one facing away (leaving it).
pub fn on_screen(quads: &[ShadowQuad], view: &View) -> (Vec<ScreenPolygon>, Vec<i32>) {
    let mut screens = Vec::new();
    let mut steps = Vec::new();
    for quad in quads {
        let facing = quad.outward.dot(view.eye - quad.corners[0]);
        if let Some(screen) = ScreenPolygon::from_points(view, 0, &quad.corners) {
            screens.push(screen);
            steps.push(if facing > 0.0 { 1 } else { -1 });
        }
    }
    (screens, steps)
}

/// How the volumes are counted along a line of sight.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Counting {
    /// Crow's: the quads are invisible surfaces of the scan-line pass.
    ScanOut,
    /// Heidmann's: each quad drawn on its own into a count buffer
    /// (`stencil_shadow_volumes`).
    Stencil,
}

/// The pre-pass for one light: the quads of every object's silhouette.
pub struct ShadowVolumes {
    pub(super) source: Source,
    pub(super) quads: Vec<ShadowQuad>,
    /// How far the quads reach (a distant light's self-shadow test looks that far).
    reach: f64,
    counting: Counting,
    /// The polygon the source lies on, which casts nothing (a point of an area
    /// light, for soft shadow volumes).
    pub(super) emitter: Option<usize>,
}

impl ShadowVolumes {
    /// Crow's volumes for a point light at `light`.
    pub fn new(scene: &Scene, light: DVec3) -> ShadowVolumes {
        ShadowVolumes::from_source(scene, Source::Point(light), Counting::ScanOut)
    }

    /// The volumes of a light from `source`, a point or a distant light's prisms,
    /// counted by `counting`.
    pub fn from_source(scene: &Scene, source: Source, counting: Counting) -> ShadowVolumes {
        ShadowVolumes {
            source,
            quads: quads_from(scene, source),
            reach: reach(scene, source),
            counting,
            emitter: None,
        }
    }

    /// Crow's volumes for a point `light` on polygon `emitter`, which casts none.
    pub fn on_emitter(scene: &Scene, light: DVec3, emitter: usize) -> ShadowVolumes {
        let source = Source::Point(light);
        ShadowVolumes {
            source,
            quads: quads_except(scene, source, Some(emitter)),
            reach: reach(scene, source),
            counting: Counting::ScanOut,
            emitter: Some(emitter),
        }
    }

    /// The light's position (for a distant light, a point beyond the scene against
    /// its travel from the origin).
    pub fn light(&self) -> DVec3 {
        match self.source {
            Source::Point(p) => p,
            Source::Distant(travel) => -travel * self.reach,
        }
    }

    /// The light's visibility on `band` from each sample's count: lit where no
    /// volume contains the visible point and the surface faces the light.
    pub(super) fn shadows_from(
        &self,
        scene: &Scene,
        view: &View,
        band: &VisibleSurface,
        counts: Vec<i32>,
    ) -> BandShadows {
        let visibility = match self.source {
            Source::Point(light) => per_sample(scene, view, band, light, |k, _, _| counts[k] <= 0),
            // The self-shadow rule towards a point beyond the scene against the travel.
            Source::Distant(travel) => band
                .samples
                .par_iter()
                .zip(&counts)
                .map(|(s, &count)| {
                    let towards = s.position - travel * self.reach;
                    let lit = !s.is_empty()
                        && count <= 0
                        && !faces_away(scene, view, s.polygon, s.position, towards);
                    if lit { 1.0 } else { 0.0 }
                })
                .collect(),
        };
        BandShadows {
            visibility: LightVisibility::Fraction(visibility),
            counts: Some(counts),
        }
    }
}

impl LightShadows for ShadowVolumes {
    fn frame<'a>(&'a self, scene: &'a Scene, view: &'a View) -> Box<dyn FrameShadows + 'a> {
        match self.counting {
            Counting::ScanOut => Box::new(CrowFrame::new(self, scene, view)),
            Counting::Stencil => Box::new(self.count_buffer(scene, view)),
        }
    }
}

/// Crow's frame: the scene's polygons and, after them, the shadow quads on this
/// view's screen, in one edge table.
struct CrowFrame<'a> {
    volumes: &'a ShadowVolumes,
    scene: &'a Scene,
    view: &'a View,
    polygons: Vec<ScreenPolygon>,
    /// How many of `polygons` are the scene's (the rest are quads).
    visible: usize,
    table: EdgeTable,
    /// Per screen quad, +1 entering a volume, −1 leaving it.
    steps: Vec<i32>,
    /// The number of volumes containing the eye.
    start: i32,
}

impl<'a> CrowFrame<'a> {
    fn new(volumes: &'a ShadowVolumes, scene: &'a Scene, view: &'a View) -> CrowFrame<'a> {
        let mut polygons = screen_polygons(scene, view);
        let visible = polygons.len();
        let (quads, steps) = on_screen(&volumes.quads, view);
        polygons.extend(quads);
        CrowFrame {
            volumes,
            scene,
            view,
            table: EdgeTable::build(&polygons, view.height),
            polygons,
            visible,
            steps,
            start: eye_count_except(scene, view.eye, volumes.source, volumes.emitter),
        }
    }
}

impl FrameShadows for CrowFrame<'_> {
    /// Along each piece of a span (one visible polygon, the quads covering it), a
    /// quad counts where it lies in front of the visible surface: both are planes,
    /// so the piece is split where their depths cross and each part decided by its
    /// ends, as the sweep decides visibility.
    fn band(&self, band: &VisibleSurface) -> BandShadows {
        let counts = scan_out(
            &self.polygons,
            self.visible,
            &self.table,
            band.width,
            band.rows(),
            self.start,
            |_| (),
            |_, row, out| {
                let y = row.row as f64 + 0.5;
                for piece in row.pieces {
                    let surface = self.polygons[piece.visible as usize].plane;
                    for &q in row.invisible(piece) {
                        let quad = self.polygons[q as usize].plane;
                        let step = self.steps[q as usize - self.visible];
                        in_front(piece.first, piece.last, y, quad, surface, |a, b| {
                            out[a as usize..=b as usize]
                                .iter_mut()
                                .for_each(|c| *c += step)
                        });
                    }
                }
            },
        );
        self.volumes
            .shadows_from(self.scene, self.view, band, counts)
    }
}

/// Calls `f(first, last)` for the runs of samples `a..=b` of the row at centre `y`
/// where plane `quad` is nearer than plane `surface` by a relative 1e-9 (the quads
/// start on the occluders' own edges): decided at the run's ends, split where the
/// depths cross.
fn in_front(
    a: u32,
    b: u32,
    y: f64,
    quad: DepthPlane,
    surface: DepthPlane,
    mut f: impl FnMut(u32, u32),
) {
    let ahead = |x: u32| {
        let x = x as f64 + 0.5;
        quad.zeta(x, y) > surface.zeta(x, y) * (1.0 + 1e-9)
    };
    let mut pending = vec![(a, b)];
    while let Some((a, b)) = pending.pop() {
        let (left, right) = (ahead(a), ahead(b));
        if left == right {
            if left {
                f(a, b);
            }
            continue;
        }
        if a == b {
            continue;
        }
        // ζ_quad − (1 + 1e-9) ζ_surface is linear in x: split at its zero.
        let k = 1.0 + 1e-9;
        let slope = quad.a - k * surface.a;
        let crossing = -((quad.b - k * surface.b) * y + (quad.c - k * surface.c)) / slope;
        let split = if crossing.is_finite() {
            ((crossing - 0.5).floor() as i64).clamp(a as i64, b as i64 - 1) as u32
        } else {
            a + (b - a) / 2
        };
        pending.push((split + 1, b));
        pending.push((a, split));
    }
}

/// Per sample, the count of shadow volumes containing the visible point.
pub fn counts(scene: &Scene, view: &View, surface: &VisibleSurface, light: DVec3) -> Vec<i32> {
    let volumes = ShadowVolumes::new(scene, light);
    let counts = volumes.frame(scene, view).band(surface).counts;
    counts.expect("shadow volumes count")
}

/// The number of volumes from `source` containing the eye (for a distant light, the
/// polygons casting a volume crossed by the segment from the eye back along the
/// light's travel, beyond the scene).
pub fn eye_count_from(scene: &Scene, eye: DVec3, source: Source) -> i32 {
    eye_count_except(scene, eye, source, None)
}

/// As `eye_count_from`, polygon `emitter` casting no volume.
pub fn eye_count_except(scene: &Scene, eye: DVec3, source: Source, emitter: Option<usize>) -> i32 {
    let light = match source {
        Source::Point(p) => p,
        Source::Distant(travel) => eye - travel * reach(scene, source),
    };
    let mut per_object = vec![0usize; scene.objects.len()];
    for p in &scene.polygons {
        per_object[p.object] += 1;
    }
    scene
        .polygons
        .iter()
        .enumerate()
        .filter(|&(i, _)| Some(i) != emitter)
        .map(|(_, p)| p)
        .filter(|p| {
            let on_plane = p.vertices[0].position;
            source.faces(p.normal, on_plane)
                || (per_object[p.object] == 1 && source.faces(-p.normal, on_plane))
        })
        .filter(|p| segment_meets_polygon(eye, light, p))
        .count() as i32
}

/// Objects of more than one polygon that are not closed 2-manifolds (some edge not
/// shared by exactly two polygons walking it in opposite directions), whose shadow
/// volumes may leak. A single polygon's volume is always exact.
pub fn open_objects(scene: &Scene) -> Vec<String> {
    let mut open = Vec::new();
    for (index, object) in scene.objects.iter().enumerate() {
        let polygons: Vec<_> = scene
            .polygons
            .iter()
            .filter(|p| p.object == index)
            .collect();
        if polygons.len() < 2 {
            continue;
        }
        let mut uses: HashMap<EdgeKey, i32> = HashMap::new();
        for p in &polygons {
            let corners: Vec<DVec3> = p.positions().collect();
            for i in 0..corners.len() {
                let (a, b) = (key(corners[i]), key(corners[(i + 1) % corners.len()]));
                *uses.entry((a, b)).or_default() += 1;
            }
        }
        let closed = uses
            .iter()
            .all(|(&(a, b), &n)| n == 1 && uses.get(&(b, a)) == Some(&1));
        if !closed {
            open.push(object.name.clone());
        }
    }
    open
}
