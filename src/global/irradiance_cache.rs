//! The irradiance cache of G. J. Ward, F. M. Rubinstein, R. D. Clear, "A ray
//! tracing solution for diffuse interreflection", SIGGRAPH '88, with the gradients
//! of G. J. Ward, P. S. Heckbert, "Irradiance gradients", 1992.
//!
//! Indirect irradiance changes slowly over a surface, except near other surfaces:
//! so it is gathered at sparse points (records) and interpolated between them.
//! Record i, gathered at P_i with normal N_i, serves a point P with normal N while
//! Ward's error estimate
//!
//!   ε_i(P, N) = |P − P_i| / R_i + √(1 − N·N_i)
//!
//! stays under the accuracy a, R_i the harmonic mean distance of the surfaces its
//! rays met (a record near a wall serves a small neighbourhood, one in the open a
//! large one). The irradiance at P is the mean of the records that serve it, each
//! weighted by w_i = 1/ε_i and extrapolated by its gradients:
//!
//!   E(P) = Σ w_i [E_i + (N_i × N)·∇_r E_i + (P − P_i)·∇_t E_i] / Σ w_i.
//!
//! A record lying in front of P (d_i = (P − P_i)·(N + N_i)/2 < 0, Ward's test) is
//! not used. Records are found through an octree of their neighbourhoods, each
//! record in the nodes about as large as its neighbourhood (radius a R_i) that it
//! overlaps, so a lookup reads the nodes on the path of P from the root.
//!
//! Choices left open: Ward made records on demand as pixels were traced, one after
//! another; here they are made by a sweep over the camera's pixel centres from a
//! coarse grid to every pixel, each level's pixels judged against the records of
//! the levels before it and gathered in parallel (so the cache does not depend on
//! the order of threads), then the image's samples only read the cache, and a
//! sample no record serves gathers for itself. R_i is kept between two fractions of
//! the scene's size (Ward bounded it too), and no less than two pixels' width at
//! the record over a, so that a record serves its own pixel's samples and its
//! neighbours' (the
//! screen-space bound of Tabellion & Lamorlette 2004: near a crease R_i falls to
//! nothing, and every sample there would gather for itself); each extrapolated
//! term is kept ≥ 0.

use super::final_gather::{FinalGather, Gathered};
use super::traced_scene::{Leaving, TracedScene};
use crate::geometry::bvh::Aabb;
use crate::raster::View;
use crate::scene::Scene;
use crate::settings::FinalGatherSettings;
use glam::{DVec3, Vec3};
use rayon::prelude::*;

/// A final gather the cache can sweep: what it casts rays in, its settings, the
/// scene's bounds, and the gather itself (at `position` on polygon `polygon`, unit
/// `normal` on the side seen, its rays from stream `stream`).
pub trait Gatherer: Sync {
    fn traced(&self) -> &TracedScene;
    fn settings(&self) -> FinalGatherSettings;
    fn bounds(&self) -> Aabb;
    fn gather(
        &self,
        scene: &Scene,
        polygon: u32,
        position: DVec3,
        normal: DVec3,
        stream: u64,
    ) -> Gathered;
}

impl Gatherer for FinalGather {
    fn traced(&self) -> &TracedScene {
        FinalGather::traced(self)
    }

    fn settings(&self) -> FinalGatherSettings {
        self.settings
    }

    fn bounds(&self) -> Aabb {
        self.bounds
    }

    fn gather(
        &self,
        scene: &Scene,
        polygon: u32,
        position: DVec3,
        normal: DVec3,
        stream: u64,
    ) -> Gathered {
        FinalGather::gather(self, scene, polygon, position, normal, stream)
    }
}

/// A gather kept for interpolation.
#[derive(Clone, Debug)]
pub struct Record {
    pub position: DVec3,
    pub normal: DVec3,
    pub gathered: Gathered,
    /// R_i, clamped.
    pub radius: f64,
    /// The pixel whose centre it was gathered at.
    pub pixel: (u32, u32),
}

/// The records of one view, and the octree that finds them.
pub struct IrradianceCache {
    pub records: Vec<Record>,
    octree: Octree,
    /// Ward's a.
    accuracy: f64,
    gradients: bool,
}

impl IrradianceCache {
    /// An empty cache of accuracy `accuracy` over `bounds`.
    pub fn new(bounds: Aabb, accuracy: f64, gradients: bool) -> IrradianceCache {
        IrradianceCache {
            records: Vec::new(),
            octree: Octree::new(bounds),
            accuracy,
            gradients,
        }
    }

    /// Keeps `record`.
    pub fn insert(&mut self, record: Record) {
        let index = self.records.len() as u32;
        let reach = self.accuracy * record.radius;
        self.octree.insert(index, record.position, reach);
        self.records.push(record);
    }

    /// Ward's ε of record `r` at (P, N), or `None` where it does not serve.
    fn error(&self, r: &Record, position: DVec3, normal: DVec3) -> Option<f64> {
        let d = position - r.position;
        if d.dot(normal + r.normal) * 0.5 < -1e-3 * r.radius {
            return None;
        }
        let turn = (1.0 - normal.dot(r.normal)).max(0.0).sqrt();
        let error = d.length() / r.radius + turn;
        (error < self.accuracy).then_some(error)
    }

    /// Whether some record serves (P, N).
    pub fn serves(&self, position: DVec3, normal: DVec3) -> bool {
        let mut found = false;
        self.octree.visit(position, |i| {
            found = found
                || self
                    .error(&self.records[i as usize], position, normal)
                    .is_some();
        });
        found
    }

    /// The interpolated irradiance at (P, N), or `None` where no record serves.
    pub fn irradiance(&self, position: DVec3, normal: DVec3) -> Option<Vec3> {
        let mut sum = Vec3::ZERO;
        let mut weights = 0.0f64;
        self.octree.visit(position, |i| {
            let r = &self.records[i as usize];
            let Some(error) = self.error(r, position, normal) else {
                return;
            };
            // A sample at the record itself: its own value, with all the weight.
            let weight = 1.0 / error.max(1e-9);
            let g = &r.gathered;
            let value = if self.gradients {
                g.irradiance
                    + g.rotational.along(r.normal.cross(normal))
                    + g.translational.along(position - r.position)
            } else {
                g.irradiance
            };
            sum += value.max(Vec3::ZERO) * weight as f32;
            weights += weight;
        });
        (weights > 0.0).then(|| sum / weights as f32)
    }

    /// The cache of `gather` for `scene` seen by `view` (one sample per pixel):
    /// records made by a coarse-to-fine sweep of the pixel centres.
    pub fn sweep(scene: &Scene, gather: &dyn Gatherer, view: &View) -> IrradianceCache {
        let traced = gather.traced();
        let settings = gather.settings();
        let bounds = gather.bounds();
        let mut cache = IrradianceCache::new(bounds, settings.error, settings.gradients);
        if settings.error <= 0.0 {
            return cache;
        }
        let size = (bounds.max - bounds.min).length();
        let (lowest, highest) = (settings.min_spacing * size, settings.max_spacing * size);
        let (width, height) = (view.width, view.height);
        let mut step = COARSEST.min(width.max(height).next_power_of_two());
        loop {
            let pixels: Vec<(u32, u32)> = (0..height)
                .step_by(step as usize)
                .flat_map(|y| (0..width).step_by(step as usize).map(move |x| (x, y)))
                .filter(|&(x, y)| step == COARSEST || x % (2 * step) != 0 || y % (2 * step) != 0)
                .collect();
            let made: Vec<Record> = pixels
                .par_iter()
                .filter_map(|&(x, y)| {
                    let (origin, direction) = view.ray_through(x as f64 + 0.5, y as f64 + 0.5);
                    let hit = traced.closest(
                        origin,
                        direction.normalize(),
                        f64::INFINITY,
                        Leaving::Eye,
                    )?;
                    let polygon = hit.polygon?;
                    if scene.materials[hit.material].diffuse.max_element() <= 0.0 {
                        return None;
                    }
                    let normal = if hit.normal.dot(direction) > 0.0 {
                        -hit.normal
                    } else {
                        hit.normal
                    };
                    if cache.serves(hit.position, normal) {
                        return None;
                    }
                    let stream = RECORD_STREAMS + y as u64 * width as u64 + x as u64;
                    let gathered = gather.gather(scene, polygon, hit.position, normal, stream);
                    // A record reaches at least the pixels beside its own: its R
                    // no less than two pixels' width there over a.
                    let pixel = hit.t / view.ray(x as f64 + 0.5, y as f64 + 0.5).length();
                    let least = lowest.max(2.0 * pixel / settings.error).min(highest);
                    Some(Record {
                        position: hit.position,
                        normal,
                        gathered,
                        radius: gathered.harmonic_distance.clamp(least, highest),
                        pixel: (x, y),
                    })
                })
                .collect();
            for record in made {
                cache.insert(record);
            }
            if step == 1 {
                return cache;
            }
            step /= 2;
        }
    }
}

/// A view's irradiance cache and the gather it was made with: what the shading
/// pass reads the indirect irradiance of its samples from.
pub struct ViewGather {
    pub gather: std::sync::Arc<FinalGather>,
    pub cache: IrradianceCache,
}

impl ViewGather {
    /// The indirect irradiance at a sample of polygon `polygon` (unit `normal` on
    /// the eye's side): interpolated from the cache, or gathered on the spot from
    /// stream `stream` where no record serves.
    pub fn irradiance(
        &self,
        scene: &Scene,
        polygon: u32,
        position: DVec3,
        normal: DVec3,
        stream: u64,
    ) -> Vec3 {
        self.cache.irradiance(position, normal).unwrap_or_else(|| {
            self.gather
                .gather(scene, polygon, position, normal, stream)
                .irradiance
        })
    }
}

/// The sweep's first grid: a pixel in 32 × 32.
const COARSEST: u32 = 32;

/// Records' streams start past every sample's (a frame has fewer than 2⁴⁸ samples).
const RECORD_STREAMS: u64 = 1 << 48;

/// An octree over the records' neighbourhoods.
struct Octree {
    low: DVec3,
    size: f64,
    nodes: Vec<Node>,
}

#[derive(Default)]
struct Node {
    children: [u32; 8],
    records: Vec<u32>,
}

/// Deepest level: a node 2⁻²⁰ of the scene.
const MAX_DEPTH: u32 = 20;

impl Octree {
    fn new(bounds: Aabb) -> Octree {
        let size = (bounds.max - bounds.min).max_element().max(1e-9) * 1.01;
        let centre = 0.5 * (bounds.max + bounds.min);
        Octree {
            low: centre - DVec3::splat(0.5 * size),
            size,
            nodes: vec![Node::default()],
        }
    }

    /// Files record `index` at `position`, reaching `reach` around it, in the
    /// nodes at least 2 × reach wide that its reach overlaps (at most eight).
    fn insert(&mut self, index: u32, position: DVec3, reach: f64) {
        let mut depth = 0;
        while depth < MAX_DEPTH && self.size / f64::from(1u32 << (depth + 1)) >= 2.0 * reach {
            depth += 1;
        }
        let cells = f64::from(1u32 << depth);
        let size = self.size;
        let cell = |x: f64| {
            let at = (x / size * cells).floor();
            at.clamp(0.0, cells - 1.0) as u32
        };
        let (lo, hi) = (
            position - DVec3::splat(reach) - self.low,
            position + DVec3::splat(reach) - self.low,
        );
        for z in cell(lo.z)..=cell(hi.z) {
            for y in cell(lo.y)..=cell(hi.y) {
                for x in cell(lo.x)..=cell(hi.x) {
                    let node = self.node_at(depth, [x, y, z]);
                    self.nodes[node].records.push(index);
                }
            }
        }
    }

    /// The node at `depth` holding cell `at`, made with its ancestors if missing.
    fn node_at(&mut self, depth: u32, at: [u32; 3]) -> usize {
        let mut node = 0;
        for level in (0..depth).rev() {
            let octant = ((at[0] >> level) & 1)
                | (((at[1] >> level) & 1) << 1)
                | (((at[2] >> level) & 1) << 2);
            let child = self.nodes[node].children[octant as usize];
            node = if child == 0 {
                self.nodes.push(Node::default());
                let made = self.nodes.len() - 1;
                self.nodes[node].children[octant as usize] = made as u32;
                made
            } else {
                child as usize
            };
        }
        node
    }

    /// Calls `each` with the records of every node on `position`'s path.
    fn visit(&self, position: DVec3, mut each: impl FnMut(u32)) {
        let p = (position - self.low) / self.size;
        if p.min_element() < 0.0 || p.max_element() >= 1.0 {
            // Outside the scene: only the root's records can reach.
            self.nodes[0].records.iter().for_each(|&i| each(i));
            return;
        }
        let cells = f64::from(1u32 << MAX_DEPTH);
        let at = [
            (p.x * cells) as u32,
            (p.y * cells) as u32,
            (p.z * cells) as u32,
        ];
        let mut node = 0;
        for level in (0..=MAX_DEPTH).rev() {
            self.nodes[node].records.iter().for_each(|&i| each(i));
            if level == 0 {
                return;
            }
            let shift = level - 1;
            let octant = ((at[0] >> shift) & 1)
                | (((at[1] >> shift) & 1) << 1)
                | (((at[2] >> shift) & 1) << 2);
            match self.nodes[node].children[octant as usize] {
                0 => return,
                child => node = child as usize,
            }
        }
    }
}
