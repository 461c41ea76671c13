//! Radiosity through mirrors and panes: the virtual-environment method of J. R.
//! Wallace, M. F. Cohen, D. P. Greenberg, "A two-pass solution to the rendering
//! equation: a synthesis of ray tracing and radiosity methods", SIGGRAPH '87, and
//! its extension to specular transmission by H. E. Rushmeier, K. E. Torrance,
//! "Extending the radiosity method to include specularly reflecting and translucent
//! materials", ACM TOG 9(1), 1990.
//!
//! A planar mirror shows the environment reflected about its plane. While a
//! hemi-cube is drawn, the mirror is a window: in the cells where the item buffer
//! shows the mirror, the environment is drawn again as seen from the eye mirrored
//! about the mirror's plane (the virtual environment), keeping only what lies
//! beyond the mirror, and each such cell adds ρ_s ΔF to the factor of the real
//! receiver it shows. A thin pane is a window too: in its cells the environment is
//! drawn again without it, keeping only what lies beyond it, weighted by τ_s (no
//! refractive offset, as Rushmeier & Torrance take panes to be thin). A window seen
//! through a window recurses, the weights multiplying, to a depth limit.
//!
//! The factors are kept apart by the first window a path meets, as the course's
//! chain of equations names them: from the front hemisphere of i, F_ij direct,
//! ρ_s,j F_f,ijk by mirror j and τ_s,j T_f,ijk through pane j; from the back
//! hemisphere (a translucent i), T_ij, ρ_s,j F_b,ijk and τ_s,j T_b,ijk.
//!
//! Choices left open: a window is one object whose polygons share a plane; a
//! mirror reflects on its front side only (its back is its backing), a pane
//! transmits both ways; the weights are per band.

use super::hemicube::Hemicube;
use super::mesh::Mesh;
use super::receivers::Receivers;
use crate::error::{Error, Result};
use crate::geometry::sutherland_hodgman::clip;
use crate::raster::{NO_POLYGON, ScreenPolygon, View, rasterize_ids};
use crate::scene::Scene;
use glam::DVec3;

/// Item-buffer flag of a receiver seen from behind (its id in the low bits).
const BEHIND: u32 = 1 << 31;

/// A planar specular object of the scene.
#[derive(Clone, Debug)]
pub struct Window {
    pub object: usize,
    pub point: DVec3,
    /// Unit normal of its front side.
    pub normal: DVec3,
    /// ρ_s: what its reflection is weighted by (0: not a mirror).
    pub reflectance: DVec3,
    /// τ_s: what is seen through it is weighted by (0: opaque).
    pub transmittance: DVec3,
}

/// Which windows pass 1 follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Follow {
    pub mirrors: bool,
    pub panes: bool,
}

/// The scene's windows, and which receivers belong to each.
#[derive(Clone, Debug)]
pub struct Windows {
    pub list: Vec<Window>,
    of_receiver: Vec<Option<u32>>,
    depth: u32,
}

/// A hemi-cube's factors from one point to every receiver, kept apart by the
/// first window each path met (weights applied, per band).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PointFactors {
    /// F_ij (or T_ij from a back hemi-cube): the plain hemi-cube's factors.
    pub direct: Vec<f64>,
    /// Σ_j ρ_s,j F_f,ijk: paths whose first window is a mirror, per receiver k.
    pub mirrored: Vec<(u32, DVec3)>,
    /// Σ_j τ_s,j T_f,ijk: paths whose first window is a pane.
    pub transmitted: Vec<(u32, DVec3)>,
}

/// The two kinds of window, as a path's first one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum First {
    Mirror,
    Pane,
}

impl Windows {
    /// The windows among `receivers` (pieces of `mesh`'s patches): each object
    /// whose material has a mirror reflectance (when `follow.mirrors`) or a
    /// specular transmittance (when `follow.panes`). Refuses an object that is not
    /// planar.
    pub fn find(
        scene: &Scene,
        mesh: &Mesh,
        receivers: &Receivers,
        follow: Follow,
        depth: u32,
    ) -> Result<Windows> {
        let mut list: Vec<Window> = Vec::new();
        let mut of_object: std::collections::HashMap<usize, u32> = Default::default();
        for polygon in &scene.polygons {
            let material = &scene.materials[polygon.material];
            let reflectance = if follow.mirrors {
                material.mirror.as_dvec3()
            } else {
                DVec3::ZERO
            };
            let transmittance = if follow.panes {
                material.transmittance.as_dvec3()
            } else {
                DVec3::ZERO
            };
            if reflectance.max_element() <= 0.0 && transmittance.max_element() <= 0.0 {
                continue;
            }
            let object = polygon.object;
            let point = polygon.vertices[0].position;
            match of_object.get(&object) {
                Some(&w) => {
                    let window = &list[w as usize];
                    let size = polygon
                        .positions()
                        .map(|p| (p - point).length())
                        .fold(1.0f64, f64::max);
                    let coplanar = window.normal.dot(polygon.normal) > 1.0 - 1e-9
                        && polygon
                            .positions()
                            .all(|p| (p - window.point).dot(window.normal).abs() <= 1e-9 * size);
                    if !coplanar {
                        return Err(Error::Radiosity(format!(
                            "object `{}` is specular (material `{}`) but not planar: radiosity's first pass reflects and transmits through planar mirrors and panes only (Wallace et al. 1987); make it flat, or trace it with [global] method = \"ray-tracing\"",
                            scene.objects[object].name, material.name
                        )));
                    }
                }
                None => {
                    of_object.insert(object, list.len() as u32);
                    list.push(Window {
                        object,
                        point,
                        normal: polygon.normal,
                        reflectance,
                        transmittance,
                    });
                }
            }
        }
        let of_receiver = receivers
            .patch
            .iter()
            .map(|&p| {
                let polygon = &scene.polygons[mesh.patches[p].polygon];
                of_object.get(&polygon.object).copied()
            })
            .collect();
        Ok(Windows {
            list,
            of_receiver,
            depth,
        })
    }

    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// The factors from `centre` (hemi-cube along `normal`) to every receiver,
    /// through the windows; receivers for which `skip` holds are not drawn in the
    /// real environment (the patch's own pieces), but may be seen in a mirror.
    pub fn factors(
        &self,
        hemicube: &Hemicube,
        centre: DVec3,
        normal: DVec3,
        receivers: &Receivers,
        skip: &(dyn Fn(usize) -> bool + Sync),
    ) -> PointFactors {
        let n = receivers.len();
        let mut direct = vec![0.0; n];
        let mut found = Found {
            mirrored: vec![DVec3::ZERO; n],
            transmitted: vec![DVec3::ZERO; n],
        };
        for (face, view) in hemicube.views(centre, normal).iter().enumerate() {
            let deltas = hemicube.deltas(face);
            let ids = self.item_buffer(view, receivers, skip, None);
            for (&id, &delta) in ids.iter().zip(deltas) {
                if id != NO_POLYGON && id & BEHIND == 0 {
                    direct[id as usize] += delta;
                }
            }
            let cells: Vec<u32> = (0..ids.len() as u32).collect();
            let look = Look {
                view,
                ids: &ids,
                cells: &cells,
                weight: DVec3::ONE,
                first: None,
                level: 1,
            };
            self.through(look, receivers, deltas, &mut found);
        }
        let sparse = |v: Vec<DVec3>| -> Vec<(u32, DVec3)> {
            v.into_iter()
                .enumerate()
                .filter(|(_, f)| f.max_element() > 0.0)
                .map(|(k, f)| (k as u32, f))
                .collect()
        };
        PointFactors {
            direct,
            mirrored: sparse(found.mirrored),
            transmitted: sparse(found.transmitted),
        }
    }

    /// Follows the windows seen in `look`'s cells: each one's virtual environment
    /// (mirror) or what lies beyond it (pane), drawn in those cells, credited, and
    /// followed in turn.
    fn through(&self, look: Look, receivers: &Receivers, deltas: &[f64], found: &mut Found) {
        if look.level > self.depth {
            return;
        }
        // The cells of each window, and whether it is seen from its front there.
        let mut cells_of: Vec<Vec<(u32, bool)>> = vec![Vec::new(); self.list.len()];
        for &c in look.cells {
            let id = look.ids[c as usize];
            if id == NO_POLYGON {
                continue;
            }
            if let Some(w) = self.of_receiver[(id & !BEHIND) as usize] {
                cells_of[w as usize].push((c, id & BEHIND == 0));
            }
        }
        for (w, cells) in cells_of.iter().enumerate() {
            if cells.is_empty() {
                continue;
            }
            let window = &self.list[w];
            let own = |r: usize| self.of_receiver[r] == Some(w as u32);
            let eye_side = (look.view.eye - window.point).dot(window.normal).signum();
            if window.reflectance.max_element() > 0.0 && eye_side > 0.0 {
                let front: Vec<u32> = cells.iter().filter(|c| c.1).map(|c| c.0).collect();
                let view = reflected_view(look.view, window);
                // Real geometry on the mirror's front side is what lies beyond the
                // mirror seen from the virtual eye.
                let keep = (window.point, window.normal);
                let ids = self.item_buffer(&view, receivers, &own, Some(keep));
                let next = Look {
                    view: &view,
                    ids: &ids,
                    cells: &front,
                    weight: look.weight * window.reflectance,
                    first: look.first.or(Some(First::Mirror)),
                    level: look.level + 1,
                };
                credit(&next, deltas, found);
                self.through(next, receivers, deltas, found);
            }
            if window.transmittance.max_element() > 0.0 && eye_side != 0.0 {
                let all: Vec<u32> = cells.iter().map(|c| c.0).collect();
                let keep = (window.point, -window.normal * eye_side);
                let ids = self.item_buffer(look.view, receivers, &own, Some(keep));
                let next = Look {
                    view: look.view,
                    ids: &ids,
                    cells: &all,
                    weight: look.weight * window.transmittance,
                    first: look.first.or(Some(First::Pane)),
                    level: look.level + 1,
                };
                credit(&next, deltas, found);
                self.through(next, receivers, deltas, found);
            }
        }
    }

    /// The nearest receiver at every cell of a face, `BEHIND`-flagged where seen
    /// from behind; with `keep` = (point, normal), only the parts of receivers on
    /// the normal's side of that plane.
    fn item_buffer(
        &self,
        view: &View,
        receivers: &Receivers,
        skip: &dyn Fn(usize) -> bool,
        keep: Option<(DVec3, DVec3)>,
    ) -> Vec<u32> {
        let frustum = view.frustum();
        let polygons: Vec<ScreenPolygon> = (0..receivers.len())
            .filter(|&r| !skip(r))
            .filter_map(|r| {
                let polygon = &receivers.polygons[r];
                let mut points: Vec<DVec3> = polygon.positions().collect();
                let eye: Vec<DVec3> = points.iter().map(|&p| view.to_eye(p)).collect();
                if View::rejects(&frustum, &eye) {
                    return None;
                }
                if let Some((q, m)) = keep {
                    points = clip(&points, |p| (*p - q).dot(m));
                    if points.len() < 3 {
                        return None;
                    }
                }
                let id = if receivers.faces(r, view.eye) {
                    r as u32
                } else {
                    r as u32 | BEHIND
                };
                ScreenPolygon::from_points(view, id, &points)
            })
            .collect();
        rasterize_ids(&polygons, view.width, view.height)
    }
}

/// One look through windows: a face's view (perhaps mirrored), its item buffer,
/// the cells that matter, the weight of the path so far.
struct Look<'a> {
    view: &'a View,
    ids: &'a [u32],
    cells: &'a [u32],
    weight: DVec3,
    first: Option<First>,
    level: u32,
}

struct Found {
    mirrored: Vec<DVec3>,
    transmitted: Vec<DVec3>,
}

/// Adds weight × ΔF of each cell to the receiver it shows (from its front).
fn credit(look: &Look, deltas: &[f64], found: &mut Found) {
    let out = match look.first {
        Some(First::Mirror) => &mut found.mirrored,
        Some(First::Pane) => &mut found.transmitted,
        None => return,
    };
    for &c in look.cells {
        let id = look.ids[c as usize];
        if id != NO_POLYGON && id & BEHIND == 0 {
            out[id as usize] += look.weight * deltas[c as usize];
        }
    }
}

/// The view mirrored about the window's plane: drawing the real environment from
/// it draws the virtual environment from `view`.
fn reflected_view(view: &View, window: &Window) -> View {
    let n = window.normal;
    let point = |p: DVec3| p - 2.0 * (p - window.point).dot(n) * n;
    let vector = |d: DVec3| d - 2.0 * d.dot(n) * n;
    View {
        eye: point(view.eye),
        right: vector(view.right),
        up: vector(view.up),
        forward: vector(view.forward),
        ..view.clone()
    }
}
