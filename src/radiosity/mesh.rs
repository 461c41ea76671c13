//! Meshing for radiosity: every scene polygon is cut into patches, and every patch
//! into elements (Cohen, Greenberg, Immel & Brock 1986). Patches exchange energy;
//! elements receive it and carry the shading detail.
//!
//! A quadrilateral is cut on a bilinear grid (a planar quad's grid points stay in its
//! plane, so every cell is a planar quad); a triangle on its barycentric grid of n²
//! triangles; any other polygon is first fanned into triangles. The cuts are made on
//! one fine grid per polygon (patches × elements per patch along each side) whose
//! points are numbered once, so elements of one polygon share their corners and
//! vertex radiosities can be averaged over them. Polygons do not share vertices with
//! each other: a crease (wall against floor) is a discontinuity of radiosity, which
//! averaging across it would smear.

use crate::error::{Error, Result};
use crate::geometry::polygon::{area, newell_normal};
use crate::scene::Scene;
use glam::{DVec3, Vec3};
use std::collections::HashMap;
use std::ops::Range;

pub use crate::settings::Division;

impl Division {
    /// Pieces along a side of length `length` (saturating: a count too large to
    /// cut is refused by `Mesh::count`'s estimate before anything is allocated).
    fn pieces(self, length: f64) -> u64 {
        match self {
            Division::Whole => 1,
            Division::Size(size) => ((length / size).ceil() as u64).max(1),
            Division::Count(n) => n.max(1) as u64,
        }
    }

    /// The scene key and value this division comes from, for messages.
    fn describe(self, key: &str) -> (String, String) {
        match self {
            Division::Whole => (format!("radiosity.{key}"), "absent".into()),
            Division::Size(size) => (format!("radiosity.{key}"), size.to_string()),
            Division::Count(n) => (format!("{key}s per side"), n.to_string()),
        }
    }
}

/// Patches, elements and vertices a mesh would have, counted before it is cut
/// (saturating at `u64::MAX`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MeshCounts {
    pub patches: u64,
    pub elements: u64,
    pub vertices: u64,
}

impl MeshCounts {
    /// Memory the mesh and a solve over it hold, estimated: per patch, the patch,
    /// its corners, its receiver polygon and its unshot radiosity; per element, the
    /// element and its corners, its receiver polygon (with centre, area, patch and
    /// box in the hierarchy), its radiosities (solved and displayed), its entry in
    /// the vertex-to-element lists and its projected polygon on each hemi-cube face
    /// (an upper bound; measured peaks are about two thirds of it); per
    /// vertex, its position, its grid index entry and its element list.
    pub fn bytes(&self) -> u64 {
        use crate::raster::ScreenPolygon;
        use crate::scene::{Polygon, Vertex};
        use std::mem::size_of;
        let receiver = size_of::<Polygon>() + 4 * size_of::<Vertex>() + size_of::<DVec3>() + 80;
        let patch = size_of::<Patch>() + 4 * size_of::<DVec3>() + receiver + size_of::<Vec3>();
        let element = size_of::<Element>()
            + 4 * size_of::<u32>()
            + receiver
            + 2 * size_of::<Vec3>()
            + 4 * size_of::<u32>()
            + 5 * (size_of::<ScreenPolygon>() + 4 * 80);
        let vertex = size_of::<DVec3>() + 32 + size_of::<Vec<u32>>();
        self.patches
            .saturating_mul(patch as u64)
            .saturating_add(self.elements.saturating_mul(element as u64))
            .saturating_add(self.vertices.saturating_mul(vertex as u64))
    }

    fn add(&mut self, patches: u64, elements: u64, vertices: u64) {
        self.patches = self.patches.saturating_add(patches);
        self.elements = self.elements.saturating_add(elements);
        self.vertices = self.vertices.saturating_add(vertices);
    }
}

/// The memory budget of `Mesh::build`: the default of `radiosity.max_memory_mb`.
pub const DEFAULT_MEMORY_BUDGET: u64 = 4096 << 20;

/// A patch: a piece of one scene polygon that shoots or gathers as a whole.
#[derive(Clone, Debug)]
pub struct Patch {
    pub polygon: usize,
    pub corners: Vec<DVec3>,
    pub normal: DVec3,
    pub centre: DVec3,
    pub area: f64,
    /// Lambertian reflectance per band, and emitted radiosity (π × the material's
    /// emitted radiance: power per unit area).
    pub reflectance: Vec3,
    pub emission: Vec3,
    pub elements: Range<usize>,
}

/// An element: a piece of a patch with its own radiosity, displayed by the
/// scan-line pass. Its corners index `Mesh::vertices`.
#[derive(Clone, Debug)]
pub struct Element {
    pub patch: usize,
    pub corners: Vec<u32>,
    pub centre: DVec3,
    pub area: f64,
    /// The radiosity ρ_e H_e the element receives straight from the scene's point,
    /// spot, distant and sphere lights (`light_sources::shine`; zero until then).
    pub received: Vec3,
}

#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub vertices: Vec<DVec3>,
    pub patches: Vec<Patch>,
    pub elements: Vec<Element>,
    /// Edges cut by adaptive subdivision (`refine`), by their end vertices (the
    /// smaller index first): the vertex at their midpoint.
    pub midpoints: HashMap<(u32, u32), u32>,
    /// Polygons left out, and why (zero area).
    pub warnings: Vec<String>,
}

impl Mesh {
    /// Cuts every polygon of `scene` into patches and elements, within the default
    /// memory budget.
    pub fn build(scene: &Scene, patches: Division, elements: Division) -> Result<Mesh> {
        Mesh::build_within(scene, patches, elements, DEFAULT_MEMORY_BUDGET, 0)
    }

    /// The counts `build` would make, without cutting anything.
    pub fn count(scene: &Scene, patches: Division, elements: Division) -> MeshCounts {
        let mut counts = MeshCounts::default();
        for polygon in &scene.polygons {
            let corners: Vec<DVec3> = polygon.positions().collect();
            let measure = area(&corners);
            if measure <= 0.0 || !measure.is_finite() {
                continue;
            }
            if corners.len() == 4 {
                let (pu, pv, eu, ev) = quad_pieces(&corners, patches, elements);
                let (nu, nv) = (pu.saturating_mul(eu), pv.saturating_mul(ev));
                counts.add(
                    pu.saturating_mul(pv),
                    nu.saturating_mul(nv),
                    nu.saturating_add(1).saturating_mul(nv.saturating_add(1)),
                );
            } else {
                for k in 1..corners.len() - 1 {
                    let triangle = [corners[0], corners[k], corners[k + 1]];
                    let (np, ne) = triangle_pieces(&triangle, patches, elements);
                    let n = np.saturating_mul(ne);
                    counts.add(
                        np.saturating_mul(np),
                        n.saturating_mul(n),
                        n.saturating_add(1).saturating_mul(n.saturating_add(2)) / 2,
                    );
                }
            }
        }
        counts
    }

    /// `build`, refusing (before cutting anything) a mesh whose estimated memory
    /// (`MeshCounts::bytes`), with the `reserved` bytes the solve holds besides, is
    /// over `budget` bytes, or whose vertices could not be numbered in 32 bits.
    pub fn build_within(
        scene: &Scene,
        patches: Division,
        elements: Division,
        budget: u64,
        reserved: u64,
    ) -> Result<Mesh> {
        let counts = Mesh::count(scene, patches, elements);
        let needed = counts.bytes().saturating_add(reserved);
        if needed > budget || counts.vertices > u32::MAX as u64 {
            // The finer of the two divisions is the one that made the count.
            let (key, value) = match (patches, elements) {
                (_, Division::Whole) => patches.describe("patch_size"),
                (Division::Size(p), Division::Size(e)) if p < e => patches.describe("patch_size"),
                _ => elements.describe("element_size"),
            };
            let shown = crate::error::count;
            return Err(Error::OverBudget(Box::new(crate::error::OverBudget {
                key,
                value,
                what: format!(
                    "{} patches, {} elements and {} vertices",
                    shown(counts.patches),
                    shown(counts.elements),
                    shown(counts.vertices)
                ),
                needed,
                budget,
                budget_key: "radiosity.max_memory_mb".into(),
                suggestion:
                    "use a larger element_size or patch_size, or raise radiosity.max_memory_mb"
                        .into(),
            })));
        }
        let mut mesh = Mesh::default();
        for (id, polygon) in scene.polygons.iter().enumerate() {
            let corners: Vec<DVec3> = polygon.positions().collect();
            let measure = area(&corners);
            if measure <= 0.0 || !measure.is_finite() {
                mesh.warnings.push(format!(
                    "polygon {id} of object `{}` has no area: left out of the radiosity mesh",
                    scene.objects[polygon.object].name
                ));
                continue;
            }
            let material = &scene.materials[polygon.material];
            if material.diffuse.max_element() >= 1.0 {
                return Err(Error::Radiosity(format!(
                    "material `{}`: a diffuse reflectance of {} would create energy; radiosity needs every band below 1",
                    material.name,
                    material.diffuse.max_element()
                )));
            }
            let surface = Surface {
                polygon: id,
                normal: polygon.normal,
                reflectance: material.diffuse,
                emission: material.emission * std::f32::consts::PI,
            };
            if corners.len() == 4 {
                mesh.cut_quad(&surface, &corners, patches, elements);
            } else {
                for k in 1..corners.len() - 1 {
                    let triangle = [corners[0], corners[k], corners[k + 1]];
                    mesh.cut_triangle(&surface, &triangle, patches, elements);
                }
            }
        }
        if mesh.patches.is_empty() {
            return Err(Error::Radiosity(
                "the scene has no polygon with an area to mesh for radiosity".into(),
            ));
        }
        Ok(mesh)
    }

    /// Total emitted power per band, Σ E_i A_i.
    pub fn emitted_power(&self) -> Vec3 {
        self.patches
            .iter()
            .map(|p| p.emission * p.area as f32)
            .sum()
    }

    /// Per patch, the radiosity it has before any interreflection: its emission
    /// and the area-weighted mean of what its elements received from the lights.
    pub fn patch_sources(&self) -> Vec<Vec3> {
        self.patches
            .iter()
            .map(|p| {
                let received: Vec3 = self.elements[p.elements.clone()]
                    .iter()
                    .map(|e| e.received * (e.area / p.area) as f32)
                    .sum();
                p.emission + received
            })
            .collect()
    }

    /// The power a solve starts with per band: Σ E_i A_i over the patches, and
    /// Σ ρ_e H_e A_e over the elements the lights reach.
    pub fn source_power(&self) -> Vec3 {
        let received: Vec3 = self
            .elements
            .iter()
            .map(|e| e.received * e.area as f32)
            .sum();
        self.emitted_power() + received
    }

    /// Per vertex, the elements whose outline passes through it (`outline`).
    pub fn vertex_elements(&self) -> Vec<Vec<u32>> {
        let mut users = vec![Vec::new(); self.vertices.len()];
        for e in 0..self.elements.len() {
            for v in self.outline(e) {
                users[v as usize].push(e as u32);
            }
        }
        users
    }

    /// Element `e`'s outline for display: its corners with, along each side, the
    /// midpoints a subdivided neighbour put there (T-vertices). Drawn through them,
    /// the element takes the neighbours' values at those points, so Gouraud shading
    /// does not crack along the side.
    pub fn outline(&self, e: usize) -> Vec<u32> {
        let corners = &self.elements[e].corners;
        let mut outline = Vec::with_capacity(corners.len());
        for (k, &a) in corners.iter().enumerate() {
            outline.push(a);
            self.push_midpoints(a, corners[(k + 1) % corners.len()], &mut outline);
        }
        outline
    }

    /// The midpoints strictly between `a` and `b`, in order from `a`.
    fn push_midpoints(&self, a: u32, b: u32, out: &mut Vec<u32>) {
        if let Some(&m) = self.midpoints.get(&(a.min(b), a.max(b))) {
            self.push_midpoints(a, m, out);
            out.push(m);
            self.push_midpoints(m, b, out);
        }
    }

    /// The vertex halfway along the edge `a`–`b`, made on first use.
    fn midpoint(&mut self, a: u32, b: u32) -> u32 {
        let key = (a.min(b), a.max(b));
        if let Some(&m) = self.midpoints.get(&key) {
            return m;
        }
        let m = self.vertices.len() as u32;
        self.vertices
            .push(0.5 * (self.vertices[a as usize] + self.vertices[b as usize]));
        self.midpoints.insert(key, m);
        m
    }

    /// Adaptive subdivision (Cohen et al. 1986): a mesh in which every `marked`
    /// element is cut into four, quads at their side midpoints and centre, triangles
    /// at their side midpoints. Patches are unchanged; each keeps its elements
    /// together. Returns the mesh and, per new element, the element of `self` it
    /// is (`Ok`) or was cut from (`Err`).
    pub fn refine(&self, marked: &[bool]) -> (Mesh, Vec<std::result::Result<usize, usize>>) {
        let mut mesh = Mesh {
            vertices: self.vertices.clone(),
            patches: self.patches.clone(),
            elements: Vec::with_capacity(self.elements.len()),
            midpoints: self.midpoints.clone(),
            warnings: self.warnings.clone(),
        };
        let mut origin = Vec::with_capacity(self.elements.len());
        for (p, patch) in self.patches.iter().enumerate() {
            let first = mesh.elements.len();
            for e in patch.elements.clone() {
                if !marked[e] {
                    mesh.elements.push(self.elements[e].clone());
                    origin.push(Ok(e));
                    continue;
                }
                let c = self.elements[e].corners.clone();
                let m: Vec<u32> = (0..c.len())
                    .map(|k| mesh.midpoint(c[k], c[(k + 1) % c.len()]))
                    .collect();
                let children = if c.len() == 4 {
                    let centre = mesh.vertices.len() as u32;
                    let mean = c.iter().map(|&v| mesh.vertices[v as usize]).sum::<DVec3>() / 4.0;
                    mesh.vertices.push(mean);
                    vec![
                        vec![c[0], m[0], centre, m[3]],
                        vec![m[0], c[1], m[1], centre],
                        vec![centre, m[1], c[2], m[2]],
                        vec![m[3], centre, m[2], c[3]],
                    ]
                } else {
                    vec![
                        vec![c[0], m[0], m[2]],
                        vec![m[0], c[1], m[1]],
                        vec![m[2], m[1], c[2]],
                        vec![m[0], m[1], m[2]],
                    ]
                };
                for corners in children {
                    let positions: Vec<DVec3> =
                        corners.iter().map(|&v| mesh.vertices[v as usize]).collect();
                    mesh.elements.push(Element {
                        patch: p,
                        centre: area_centroid(&positions),
                        area: area(&positions),
                        corners,
                        received: Vec3::ZERO,
                    });
                    origin.push(Err(e));
                }
            }
            mesh.patches[p].elements = first..mesh.elements.len();
        }
        (mesh, origin)
    }

    /// World corners of element `e`.
    pub fn element_corners(&self, e: usize) -> Vec<DVec3> {
        self.elements[e]
            .corners
            .iter()
            .map(|&v| self.vertices[v as usize])
            .collect()
    }

    fn cut_quad(&mut self, s: &Surface, q: &[DVec3], patches: Division, elements: Division) {
        // `build_within` has bounded the counts: they fit in memory, so in usize.
        let (pu, pv, eu, ev) = quad_pieces(q, patches, elements);
        let (pu, pv, eu, ev) = (pu as usize, pv as usize, eu as usize, ev as usize);
        let (nu, nv) = (pu * eu, pv * ev);
        let point = |a: usize, b: usize| {
            let (s, t) = (a as f64 / nu as f64, b as f64 / nv as f64);
            let bottom = q[0].lerp(q[1], s);
            let top = q[3].lerp(q[2], s);
            bottom.lerp(top, t)
        };
        let mut grid = Grid::default();
        for (i, j) in (0..pv).flat_map(|j| (0..pu).map(move |i| (i, j))) {
            let cells = (0..ev).flat_map(|b| (0..eu).map(move |a| (i * eu + a, j * ev + b)));
            let cells: Vec<Vec<(usize, usize)>> = cells
                .map(|(a, b)| vec![(a, b), (a + 1, b), (a + 1, b + 1), (a, b + 1)])
                .collect();
            let outline = [
                (i * eu, j * ev),
                ((i + 1) * eu, j * ev),
                ((i + 1) * eu, (j + 1) * ev),
                (i * eu, (j + 1) * ev),
            ];
            self.push_patch(s, &mut grid, &cells, &outline, point);
        }
    }

    fn cut_triangle(&mut self, s: &Surface, t: &[DVec3; 3], patches: Division, elements: Division) {
        let (np, ne) = triangle_pieces(t, patches, elements);
        let (np, ne) = (np as usize, ne as usize);
        let n = np * ne;
        // Grid point (a, b) is t0 + a/n (t1 − t0) + b/n (t2 − t0), a + b ≤ n.
        let point = |a: usize, b: usize| {
            t[0] + (t[1] - t[0]) * (a as f64 / n as f64) + (t[2] - t[0]) * (b as f64 / n as f64)
        };
        let mut grid = Grid::default();
        for (i, j, up) in triangle_cells(np) {
            // The patch's own fine cells: its triangle cut into ne² triangles, in
            // fine-grid coordinates.
            let map = |a: usize, b: usize| -> (usize, usize) {
                if up {
                    (i * ne + a, j * ne + b)
                } else {
                    // The downward cell (i+1, j), (i, j+1), (i+1, j+1) is the upward
                    // one mirrored: local (a, b) ↦ corner − (a, b).
                    ((i + 1) * ne - a, (j + 1) * ne - b)
                }
            };
            let cells: Vec<Vec<(usize, usize)>> = triangle_cells(ne)
                .map(|(a, b, up)| {
                    if up {
                        vec![map(a, b), map(a + 1, b), map(a, b + 1)]
                    } else {
                        vec![map(a + 1, b), map(a + 1, b + 1), map(a, b + 1)]
                    }
                })
                .collect();
            let outline = [map(0, 0), map(ne, 0), map(0, ne)];
            self.push_patch(s, &mut grid, &cells, &outline, point);
        }
    }

    /// A patch made of `cells` (each a list of fine-grid points) and bounded by
    /// `outline` (fine-grid points), with its elements.
    fn push_patch(
        &mut self,
        s: &Surface,
        grid: &mut Grid,
        cells: &[Vec<(usize, usize)>],
        outline: &[(usize, usize)],
        point: impl Fn(usize, usize) -> DVec3,
    ) {
        let patch = self.patches.len();
        let first = self.elements.len();
        for cell in cells {
            let mut corners: Vec<u32> = cell
                .iter()
                .map(|&(a, b)| grid.vertex(&mut self.vertices, (a, b), || point(a, b)))
                .collect();
            let mut positions: Vec<DVec3> =
                corners.iter().map(|&v| self.vertices[v as usize]).collect();
            // Keep the polygon's orientation: the mirrored cells of a triangle
            // come out the other way round.
            if newell_normal(&positions).dot(s.normal) < 0.0 {
                corners.reverse();
                positions.reverse();
            }
            self.elements.push(Element {
                patch,
                centre: area_centroid(&positions),
                area: area(&positions),
                corners,
                received: Vec3::ZERO,
            });
        }
        let elements = first..self.elements.len();
        let area_sum: f64 = self.elements[elements.clone()].iter().map(|e| e.area).sum();
        let centre = self.elements[elements.clone()]
            .iter()
            .map(|e| e.centre * e.area)
            .sum::<DVec3>()
            / area_sum;
        let mut corners: Vec<DVec3> = outline.iter().map(|&(a, b)| point(a, b)).collect();
        if newell_normal(&corners).dot(s.normal) < 0.0 {
            corners.reverse();
        }
        self.patches.push(Patch {
            polygon: s.polygon,
            corners,
            normal: s.normal,
            centre,
            area: area_sum,
            reflectance: s.reflectance,
            emission: s.emission,
            elements,
        });
    }
}

/// A quad's patches along its two directions, and elements per patch along each.
fn quad_pieces(q: &[DVec3], patches: Division, elements: Division) -> (u64, u64, u64, u64) {
    let side = |a: usize, b: usize| (q[b] - q[a]).length();
    let (u, v) = (side(0, 1).max(side(3, 2)), side(1, 2).max(side(0, 3)));
    let (pu, pv) = (patches.pieces(u), patches.pieces(v));
    (
        pu,
        pv,
        elements.pieces(u / pu as f64),
        elements.pieces(v / pv as f64),
    )
}

/// A triangle's patches along each side, and elements per patch along each.
fn triangle_pieces(t: &[DVec3; 3], patches: Division, elements: Division) -> (u64, u64) {
    let longest = (0..3)
        .map(|k| (t[(k + 1) % 3] - t[k]).length())
        .fold(0.0, f64::max);
    let np = patches.pieces(longest);
    (np, elements.pieces(longest / np as f64))
}

/// What a polygon's patches inherit from it.
struct Surface {
    polygon: usize,
    normal: DVec3,
    reflectance: Vec3,
    emission: Vec3,
}

/// Fine-grid points of one polygon, numbered on first use.
#[derive(Default)]
struct Grid {
    index: HashMap<(usize, usize), u32>,
}

impl Grid {
    fn vertex(
        &mut self,
        vertices: &mut Vec<DVec3>,
        key: (usize, usize),
        point: impl FnOnce() -> DVec3,
    ) -> u32 {
        *self.index.entry(key).or_insert_with(|| {
            vertices.push(point());
            (vertices.len() - 1) as u32
        })
    }
}

/// The n² cells of a triangle's barycentric grid: (a, b, upward). Upward cell (a, b)
/// has corners (a, b), (a+1, b), (a, b+1); downward cell (a, b) has corners (a+1, b),
/// (a+1, b+1), (a, b+1).
fn triangle_cells(n: usize) -> impl Iterator<Item = (usize, usize, bool)> {
    (0..n).flat_map(move |b| {
        (0..n - b).flat_map(move |a| {
            let down = (a + b + 1 < n).then_some((a, b, false));
            std::iter::once((a, b, true)).chain(down)
        })
    })
}

/// The area centroid of a planar polygon (its vertex mean is not, for a quad).
pub fn area_centroid(vertices: &[DVec3]) -> DVec3 {
    let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
    for k in 1..vertices.len() - 1 {
        let t = [vertices[0], vertices[k], vertices[k + 1]];
        let a = area(&t);
        sum += (t[0] + t[1] + t[2]) / 3.0 * a;
        weight += a;
    }
    if weight > 0.0 {
        sum / weight
    } else {
        vertices.iter().copied().sum::<DVec3>() / vertices.len() as f64
    }
}
