//! What the integrators that read a radiosity solution share: the solution kept
//! (solved the first time a frame needs it, or handed over) and the scan-line
//! lighting through its elements, Gouraud-shaded as B/π, with textures modulating
//! the reflected part and the lights the solution does not hold (point, spot,
//! distant, sphere) added directly with their shadows; with the two-pass methods'
//! second pass (rays off specular surfaces reading the solution) and final gather
//! when they have one.

use super::ScanLine;
use crate::error::{Error, Result};
use crate::global::irradiance_cache::{IrradianceCache, ViewGather};
use crate::global::two_pass::SecondPass;
use crate::image_io::{Buffer, BufferData, NO_ID};
use crate::radiosity::hemicube::{BACK, Hemicube};
use crate::radiosity::receivers::Receivers;
use crate::radiosity::{self, Solution, display};
use crate::raster::{
    NO_POLYGON, ScreenPolygon, ToPrepare, View, Visibility, VisibleSurface, prepare,
};
use crate::scene::{Light, Scene};
use crate::shading::{FrameShading, radiance_at};
use glam::{DVec3, Vec3};
use rayon::prelude::*;
use std::f32::consts::PI;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// The name of the irradiance cache's buffer.
pub const CACHE_RECORDS: &str = "irradiance-cache";

/// Per light, whether shading adds it directly under a radiosity solution: every
/// light but the polygon lights, which are emitters of the solution already (all
/// of them when the second pass computes the direct light exactly).
pub fn lights_beside_the_solution(scene: &Scene) -> Vec<bool> {
    let exact = exact_direct(scene);
    scene
        .lights
        .iter()
        .map(|light| exact || !matches!(light, Light::Polygon(_)))
        .collect()
}

/// Whether the second pass computes the direct light of every light itself (and
/// the solution is drawn with its indirect part only).
pub fn exact_direct(scene: &Scene) -> bool {
    scene
        .global
        .as_ref()
        .is_some_and(|g| g.method.reads_radiosity() && g.exact_direct)
}

/// A radiosity solution kept between frames, as frames draw it.
pub struct KeptSolution {
    drawn: Mutex<Option<Arc<Solution>>>,
    solved: AtomicUsize,
}

impl KeptSolution {
    pub fn new() -> KeptSolution {
        KeptSolution {
            drawn: Mutex::new(None),
            solved: AtomicUsize::new(0),
        }
    }

    /// The solution as frames draw it, solved the first time; `whole` is shown the
    /// whole solution before its drawn part is taken (the final gather reads it
    /// whole).
    pub fn get(&self, scene: &Scene, whole: &dyn Fn(&Solution)) -> Result<Arc<Solution>> {
        let mut slot = self.drawn.lock().expect("no poisoned lock");
        if let Some(solution) = slot.as_ref() {
            return Ok(solution.clone());
        }
        let Some(settings) = &scene.radiosity else {
            return Err(Error::Radiosity(
                "the scene has no [radiosity] table to solve".into(),
            ));
        };
        let solution = radiosity::solve(scene, settings, &mut |_, _| {})?;
        self.solved.fetch_add(1, Ordering::Relaxed);
        whole(&solution);
        let solution = Arc::new(drawn(scene, solution)?);
        *slot = Some(solution.clone());
        Ok(solution)
    }

    /// Keeps `solution` (solved elsewhere), `whole` shown it first.
    pub fn hand_over(&self, scene: &Scene, solution: Arc<Solution>, whole: &dyn Fn(&Solution)) {
        whole(&solution);
        let solution = drawn_part(scene, &solution).map_or(solution, Arc::new);
        *self.drawn.lock().expect("no poisoned lock") = Some(solution);
    }

    /// Drops the solution: the next frame solves again.
    pub fn forget(&self) {
        *self.drawn.lock().expect("no poisoned lock") = None;
    }

    pub fn is_kept(&self) -> bool {
        self.drawn.lock().expect("no poisoned lock").is_some()
    }

    pub fn solved(&self) -> usize {
        self.solved.load(Ordering::Relaxed)
    }
}

/// The solution as frames draw it (`drawn_part`); with exact direct light, an
/// error when the solution kept no direct part to take out.
fn drawn(scene: &Scene, solution: Solution) -> Result<Solution> {
    match drawn_part(scene, &solution) {
        Some(drawn) => Ok(drawn),
        None if exact_direct(scene) => Err(Error::Radiosity(
            "global.exact_direct needs the solution's direct part, which adaptive subdivision does not keep: leave `subdivide` out".into(),
        )),
        None => Ok(solution),
    }
}

/// What frames draw of `solution`, where it is not the solution itself: its
/// indirect part when the second pass computes the direct light exactly; else the
/// solution without the direct light of the point, spot, distant and sphere
/// lights, which every sample adds itself. `None`: nothing to take out (or, with
/// exact direct light, no direct part kept).
fn drawn_part(scene: &Scene, solution: &Solution) -> Option<Solution> {
    if exact_direct(scene) {
        solution.indirect()
    } else {
        solution.without_light_sources()
    }
}

/// A solution's elements lit for the scan-line pass.
pub struct SolutionLighting {
    pub solution: Arc<Solution>,
    /// The two-pass methods' second pass (rays off specular surfaces).
    pub second: Option<Arc<SecondPass>>,
    /// The final gather with this view's irradiance cache.
    pub gather: Option<Arc<ViewGather>>,
}

impl SolutionLighting {
    /// The solution's elements as the scan-line pass draws them.
    fn elements(&self, scene: &Scene) -> Vec<display::ElementPolygon> {
        let s = &self.solution;
        display::element_polygons(scene, &s.mesh, &s.elements, s.display)
    }
}

impl ScanLine for SolutionLighting {
    fn draw_list(&self, scene: &Scene, view: &View, _: &[bool]) -> Vec<ScreenPolygon> {
        let pieces = self.elements(scene);
        prepare(
            view,
            pieces.iter().enumerate().map(|(e, piece)| ToPrepare {
                id: piece.polygon as u32,
                element: e as u32,
                vertices: &piece.vertices,
                colors: &piece.colors,
                affine_uv: false,
            }),
        )
    }

    /// Light by light whenever a light is added directly: the samples'
    /// interpolated colour is the solution's, not the lights'.
    fn gouraud_per_light(&self, scene: &Scene, direct: &[bool], _: bool) -> bool {
        super::gouraud_shaded(scene) && direct.contains(&true)
    }

    fn light_draw_list(&self, scene: &Scene, view: &View, l: usize) -> Vec<ScreenPolygon> {
        let pieces = self.elements(scene);
        let colors: Vec<Vec<Vec3>> = pieces
            .par_iter()
            .map(|piece| {
                let polygon = &scene.polygons[piece.polygon];
                piece
                    .vertices
                    .iter()
                    .map(|v| radiance_at(scene, polygon, v.position, v.normal, view.eye, l))
                    .collect()
            })
            .collect();
        prepare(
            view,
            pieces
                .iter()
                .zip(&colors)
                .enumerate()
                .map(|(e, (piece, c))| ToPrepare {
                    id: piece.polygon as u32,
                    element: e as u32,
                    vertices: &piece.vertices,
                    colors: c,
                    affine_uv: false,
                }),
        )
    }

    fn shade_band(
        &self,
        shading: &FrameShading,
        scene: &Scene,
        band: &VisibleSurface,
        visibility: &Visibility,
        gouraud: &[Vec<Vec3>],
    ) -> Vec<Vec3> {
        (0..band.samples.len())
            .into_par_iter()
            .map(|k| {
                let s = &band.samples[k];
                if s.is_empty() {
                    return shading.background(band, k);
                }
                // Radiosity leaves the front only; a surface seen from behind is
                // black.
                if !shading.front(band, k) {
                    return Vec3::ZERO;
                }
                let material = scene.material_of(s.polygon as usize);
                let emitted = material.emission;
                let scale = shading.diffuse_texture_scale(band, k);
                let solved = match (&self.gather, scale) {
                    (Some(gather), _) => {
                        let diffuse = material.diffuse * scale.unwrap_or(Vec3::ONE);
                        // A surface that reflects nothing diffusely (a lamp) needs
                        // no gather.
                        if diffuse.max_element() > 0.0 {
                            emitted + diffuse * gathered_at(shading, gather, band, k) / PI
                        } else {
                            emitted
                        }
                    }
                    (None, Some(scale)) => emitted + (s.color - emitted) * scale,
                    (None, None) => s.color,
                };
                let mut radiance = solved
                    + shading.lit(band, k, visibility, gouraud)
                    + shading.environment(band, k);
                if let Some(second) = &self.second
                    && material.is_specular()
                {
                    radiance += second_pass_at(shading, second, band, k);
                }
                radiance
            })
            .collect()
    }

    fn element_radiosity(&self, element: u32) -> Option<Vec3> {
        self.solution.elements.get(element as usize).copied()
    }

    fn buffers(&self, scene: &Scene, hemicube_element: usize) -> Vec<Buffer> {
        let mut buffers = Vec::new();
        if let Some(gather) = &self.gather {
            buffers.push(cache_records(scene, &gather.cache));
        }
        buffers.extend(hemicube_buffers(
            scene,
            hemicube_element,
            &self.solution.mesh,
        ));
        buffers
    }
}

/// The indirect irradiance the final gather finds at sample `k`.
fn gathered_at(
    shading: &FrameShading,
    gather: &ViewGather,
    band: &VisibleSurface,
    k: usize,
) -> Vec3 {
    let (normal, _) = eye_side_normal(shading, band, k);
    let s = &band.samples[k];
    gather.irradiance(
        shading.scene(),
        s.polygon,
        s.position,
        normal,
        sample_stream(band, k),
    )
}

/// Sample `k`'s unit shading normal turned to the eye's side, and the unit
/// direction from the eye to it.
fn eye_side_normal(shading: &FrameShading, band: &VisibleSurface, k: usize) -> (DVec3, DVec3) {
    let scene = shading.scene();
    let s = &band.samples[k];
    let incident = (s.position - shading.eye()).normalize();
    let mut normal = s
        .normal
        .as_dvec3()
        .normalize_or(scene.polygons[s.polygon as usize].normal);
    if normal.dot(incident) > 0.0 {
        normal = -normal;
    }
    (normal, incident)
}

/// Sample `k`'s index in the frame's sample grid: the stream its rays draw from.
fn sample_stream(band: &VisibleSurface, k: usize) -> u64 {
    let (x, y) = band.position_of(k);
    y as u64 * band.width as u64 + x as u64
}

/// The second pass at a visible sample of a specular surface.
fn second_pass_at(
    shading: &FrameShading,
    second: &SecondPass,
    band: &VisibleSurface,
    k: usize,
) -> Vec3 {
    let s = &band.samples[k];
    let (normal, incident) = eye_side_normal(shading, band, k);
    let stream = sample_stream(band, k);
    second.specular(
        shading.scene(),
        s.polygon,
        s.position,
        normal,
        incident,
        stream,
    )
}

/// The item buffers of the hemi-cube at the centre of the chosen `element`,
/// looking at the patches (ids are patch indices): what gathering sees from there.
fn hemicube_buffers(scene: &Scene, element: usize, mesh: &radiosity::Mesh) -> Vec<Buffer> {
    let Some(settings) = &scene.radiosity else {
        return Vec::new();
    };
    let Some(element) = mesh.elements.get(element) else {
        return Vec::new();
    };
    let patch = &mesh.patches[element.patch];
    let receivers = Receivers::patches(mesh);
    let own = element.patch;
    Hemicube::new(settings.resolution)
        .faces(element.centre, patch.normal, &receivers, &|r| r == own)
        .into_iter()
        .map(|(face, width, height, ids)| Buffer {
            name: format!("hemicube-{face}"),
            width,
            height,
            data: BufferData::Ids(
                ids.into_iter()
                    .map(|i| {
                        if i == NO_POLYGON || i == BACK {
                            NO_ID
                        } else {
                            i
                        }
                    })
                    .collect(),
            ),
        })
        .collect()
}

/// Where the irradiance cache's records were gathered: per pixel of the image, the
/// number of records made at its centre (Ward's sparse gathers, denser near
/// surfaces that meet).
fn cache_records(scene: &Scene, cache: &IrradianceCache) -> Buffer {
    let (width, height) = (scene.camera.width, scene.camera.height);
    let mut counts = vec![0; width as usize * height as usize];
    for r in &cache.records {
        let (x, y) = r.pixel;
        if x < width && y < height {
            counts[y as usize * width as usize + x as usize] += 1;
        }
    }
    Buffer {
        name: CACHE_RECORDS.into(),
        width,
        height,
        data: BufferData::Counts(counts),
    }
}
