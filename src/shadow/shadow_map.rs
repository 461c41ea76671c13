//! Shadow depth maps: L. Williams, "Casting curved shadows on curved surfaces",
//! Computer Graphics (SIGGRAPH '78) 12(3):270–274, 1978.
//!
//! First pass: the scene is rendered from the light into a depth image by the
//! project's own scan-line rasterizer. A point light sees all around, so it gets six
//! 90° frusta, the faces of a cube (±x, ±y, ±z). Second pass: each visible point is
//! transformed into the light's frame (the cube face its direction falls in), its
//! depth along that face's axis is compared with the depth stored in the texel it
//! lands in, and it is in shadow when it lies farther than the stored depth plus a
//! bias.
//!
//! How the tests are filtered (`map_filter`): `none` is Williams's single test;
//! `box` tests each texel of a fixed k × k neighbourhood of the point's texel
//! (`pcf = k`) and returns the fraction that passes, a box kernel indexed by the
//! texel, so its result is the same all over a texel and coarse shadows stay blocky;
//! `percentage-closer` is Reeves, Salesin & Cook's filter over the sample's
//! footprint (`percentage_closer.rs`).
//!
//! Choices (Williams leaves the bias open): the bias is measured in texels and
//! slope-scaled, `map_bias` × (1 + tan θ) × the size of one texel at the point's
//! distance (2z/resolution for a 90° face), θ the angle between the surface normal
//! and the light: a surface the light grazes changes depth by tan θ texels from one
//! texel to the next, which a constant bias cannot absorb. tan θ is capped at 50, so
//! surfaces seen almost edge-on from the light keep some acne: the method's limit.
//! Box neighbourhoods stop at the face's border (clamped). Williams's
//! original applied the shadow to the finished image (`post_pass`, see `render`);
//! the default looks the map up inside the light model. Scene keys:
//! `[shadows] method = "shadow-map"`, `map_resolution`, `map_bias`,
//! `map_filter = "none" | "box" | "percentage-closer"`, `pcf`, `post_pass`.

use super::cube_faces::{FACES, face_of, face_view};
pub use super::depth_image::{DepthImage, MapPoint};
use super::percentage_closer::{footprint, percentage_closer};
use super::{BandShadows, FrameShadows, LightShadows, per_sample};
use crate::error::OverBudget;
use crate::geometry::sampling::Stream;
use crate::image_io::{Buffer, BufferData};
use crate::raster::{View, VisibleSurface, rasterize_depth, screen_polygons};
use crate::scene::LightKind;
use crate::scene::Scene;
use crate::settings::ShadowMethod;
use crate::settings::{MapFilter, PercentageCloser, ShadowSettings};
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::sync::Arc;

/// The registry's entry: lights at a point, six faces of depths each, kept by the
/// renderer under `shadows.max_memory_mb`.
pub(crate) static METHOD: super::Method = super::Method {
    method: ShadowMethod::ShadowMap,
    name: "shadow-map",
    entry: Some("shadow-map"),
    handles: "a hard-shadow method for point and spot lights",
    lights: &[LightKind::Point, LightKind::Spot],
    counts: None,
    budget,
    warnings: super::no_warnings,
    prepare: |scene, index, settings, _| {
        let at = scene.lights[index].position().expect("checked");
        Some(Arc::new(CubeShadowMap::build(
            scene,
            at,
            settings.map_resolution,
            Lookup::of(settings, index),
        )))
    },
};

/// Six faces of f32 depths per light, all kept by the renderer.
fn budget(scene: &Scene) -> Result<(), Box<OverBudget>> {
    let shadows = &scene.shadows;
    let lights = scene.lights.len() as u64;
    let needed = (24 * (shadows.map_resolution as u64).pow(2)).saturating_mul(lights);
    let budget = shadows.max_memory_mb.saturating_mul(1 << 20);
    if lights == 0 || needed <= budget {
        return Ok(());
    }
    Err(Box::new(OverBudget {
        key: "shadows.map_resolution".into(),
        value: shadows.map_resolution.to_string(),
        what: format!("the six shadow-map faces of each of the scene's {lights} lights"),
        needed,
        budget,
        budget_key: "shadows.max_memory_mb".into(),
        suggestion: "use a lower map_resolution, or raise shadows.max_memory_mb".into(),
    }))
}

/// One face of the cube: its view from the light and its depth image.
pub struct Face {
    pub view: View,
    pub depth: Vec<f32>,
}

/// How the second pass reads the map.
#[derive(Clone, Debug, PartialEq)]
pub struct Lookup {
    pub filter: MapFilter,
    /// Williams's and the box's bias, in slope-scaled texels.
    pub bias: f64,
    /// The box's side.
    pub kernel: u32,
    pub percentage_closer: PercentageCloser,
    /// The percentage-closer points' generator: the scene's seed and the light.
    pub seed: u64,
}

impl Lookup {
    /// The lookup `settings` ask for, for light `index`.
    pub fn of(settings: &ShadowSettings, index: usize) -> Lookup {
        Lookup {
            filter: settings.map_filter,
            bias: settings.map_bias,
            kernel: settings.pcf,
            percentage_closer: settings.percentage_closer,
            seed: settings.seed ^ (index as u64).rotate_left(32),
        }
    }
}

/// The six depth images around a point light, and how the second pass reads them.
pub struct CubeShadowMap {
    pub light: DVec3,
    pub resolution: u32,
    pub faces: Vec<Face>,
    pub lookup: Lookup,
}

/// The faces' names in buffer names, in `FACES` order.
pub const FACE_NAMES: [&str; 6] = ["px", "nx", "py", "ny", "pz", "nz"];

/// Largest tan θ the slope-scaled bias follows.
const MAX_SLOPE: f64 = 50.0;

impl CubeShadowMap {
    /// The first pass: depth images of the scene from `light`. The six faces are
    /// built in parallel: each face's projection and edge table are serial, and
    /// overlapping them halves the pass on two cores.
    pub fn build(scene: &Scene, light: DVec3, resolution: u32, lookup: Lookup) -> CubeShadowMap {
        let faces = FACES
            .par_iter()
            .map(|&face| {
                let view = face_view(scene, light, face, resolution);
                let depth = rasterize_depth(&screen_polygons(scene, &view), resolution, resolution);
                Face { view, depth }
            })
            .collect();
        CubeShadowMap {
            light,
            resolution,
            faces,
            lookup,
        }
    }

    /// Face `face`'s depth image.
    pub fn image(&self, face: usize) -> DepthImage<'_> {
        DepthImage {
            size: self.resolution,
            depth: &self.faces[face].depth,
        }
    }

    /// Where point `p` with unit normal `n` falls in the map.
    pub fn locate(&self, p: DVec3, n: DVec3) -> MapPoint {
        let face = face_of(p - self.light);
        let view = &self.faces[face].view;
        let eye = view.to_eye(p);
        let (x, y) = view.project(eye);
        let cos = n.dot((self.light - p).normalize()).abs().max(1e-12);
        let tan = ((1.0 - cos * cos).sqrt() / cos).min(MAX_SLOPE);
        MapPoint {
            face,
            at: DVec2::new(x, y),
            depth: eye.z,
            slope: 1.0 + tan,
            texel: 2.0 * eye.z / self.resolution as f64,
        }
    }

    /// The box filter at `p` (kernel 1: Williams's test), with the map's bias.
    pub fn box_filter(&self, p: DVec3, n: DVec3, kernel: u32) -> f32 {
        let at = self.locate(p, n);
        let image = self.image(at.face);
        image.box_filter(image.texel(at.at), kernel, at.less(self.lookup.bias))
    }
}

impl LightShadows for CubeShadowMap {
    fn frame<'a>(&'a self, scene: &'a Scene, view: &'a View) -> Box<dyn FrameShadows + 'a> {
        Box::new(MapFrame {
            map: self,
            scene,
            view,
        })
    }

    fn buffers(&self, prefix: &str) -> Vec<Buffer> {
        self.faces
            .iter()
            .zip(FACE_NAMES)
            .map(|(face, name)| Buffer {
                name: format!("{prefix}-{name}"),
                width: self.resolution,
                height: self.resolution,
                data: BufferData::Values {
                    channels: 1,
                    data: face.depth.clone(),
                },
            })
            .collect()
    }
}

struct MapFrame<'a> {
    map: &'a CubeShadowMap,
    scene: &'a Scene,
    view: &'a View,
}

impl MapFrame<'_> {
    /// Reeves's filter at sample `k` of `band`, over its cell's footprint.
    fn percentage_closer(&self, band: &VisibleSurface, k: usize, p: DVec3, n: DVec3) -> f32 {
        let (map, lookup) = (self.map, &self.map.lookup);
        let at = map.locate(p, n);
        let cell = band.position_of(k);
        let light_view = &map.faces[at.face].view;
        let filter = &lookup.percentage_closer;
        let region = footprint(self.view, cell, p, n, light_view, at.at)
            .enlarged(filter.scale, filter.min_size);
        // The sample's own stream, by its place on the whole grid: the same numbers
        // whatever the bands and threads.
        let index = cell.1 as u64 * band.width as u64 + cell.0 as u64;
        let mut stream = Stream::new(lookup.seed, index);
        percentage_closer(&map.image(at.face), &at, region, filter, &mut stream)
    }
}

impl FrameShadows for MapFrame<'_> {
    fn band(&self, band: &VisibleSurface) -> BandShadows {
        let map = self.map;
        let lookup = &map.lookup;
        let lit = per_sample(self.scene, self.view, band, map.light, |_, _, _| true);
        BandShadows::fraction(
            band.samples
                .par_iter()
                .zip(lit)
                .enumerate()
                .map(|(k, (sample, self_lit))| {
                    if self_lit == 0.0 {
                        return 0.0;
                    }
                    let (p, n) = (
                        sample.position,
                        self.scene.polygons[sample.polygon as usize].normal,
                    );
                    match lookup.filter {
                        MapFilter::None => map.box_filter(p, n, 1),
                        MapFilter::Box => map.box_filter(p, n, lookup.kernel),
                        MapFilter::PercentageCloser => self.percentage_closer(band, k, p, n),
                    }
                })
                .collect(),
        )
    }
}
