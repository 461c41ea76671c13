//! The ways a frame is lit, siblings over one visible-surface pass and one shading
//! pass (as pbrt's integrators are over one film):
//!
//! - `Direct`: the scan-line renderer's own lighting: every light, weighted per
//!   sample by its visibility (shadows);
//! - `Radiosity`: a view-independent diffuse solution (`radiosity`) drawn through
//!   its elements, Gouraud-shaded as B/π, with textures modulating the reflected part
//!   and the lights the solution does not hold (point, spot, distant, sphere) added
//!   directly with their shadows; with the two-pass methods' second pass (rays off
//!   specular surfaces reading the solution) when `[global]` asks for one;
//! - `Whitted`: recursive ray tracing (`global::whitted`), which makes its frame
//!   with rays through the pixels instead of the scan-line pass.
//!
//! A scan-line integrator says which polygons the scan-line pass draws (with which
//! vertex colours), which lights shading adds directly, and how a band's samples
//! become radiance. The renderer alone chooses the integrator (`Renderer::plan`).

use crate::global::TracedScene;
use crate::global::irradiance_cache::ViewGather;
use crate::global::two_pass::SecondPass;
use crate::radiosity::{Solution, display};
use crate::raster::{ScreenPolygon, ToPrepare, View, Visibility, VisibleSurface, prepare};
use crate::scene::{Light, Scene, ShadingMode};
use crate::settings::GlobalSettings;
use crate::shading::{FrameShading, radiance_at, vertex_colors};
use glam::{DVec3, Vec3};
use rayon::prelude::*;
use std::f32::consts::PI;
use std::sync::Arc;

#[derive(Clone)]
pub enum Integrator {
    Direct,
    /// With the second pass of the two-pass method (rays off specular surfaces),
    /// and the final gather with this view's irradiance cache.
    Radiosity(
        Arc<Solution>,
        Option<Arc<SecondPass>>,
        Option<Arc<ViewGather>>,
    ),
    /// Whitted's ray tracer over the scene as rays see it, with its settings.
    Whitted(Arc<TracedScene>, GlobalSettings),
}

/// A scan-line method asked of the ray-traced integrator, which has no scan-line
/// pass (the frame dispatches it before).
const NO_SCAN_LINE: &str = "a ray-traced frame has no scan-line pass";

impl Integrator {
    /// Its name in messages and buffer lists.
    pub fn name(&self) -> &'static str {
        match self {
            Integrator::Direct => "direct",
            Integrator::Radiosity(..) => "radiosity",
            Integrator::Whitted(..) => "ray tracing",
        }
    }

    /// Per light, whether shading adds it directly (and so whether it is shadowed;
    /// Whitted's tracer adds every light itself, with its own shadow rays).
    pub fn direct_lights(&self, scene: &Scene) -> Vec<bool> {
        match self {
            Integrator::Whitted(..) => vec![false; scene.lights.len()],
            Integrator::Direct | Integrator::Radiosity(..) => lit_directly(
                scene,
                matches!(self, Integrator::Radiosity(..)) && !exact_direct(scene),
            ),
        }
    }

    /// Whether Gouraud shading must interpolate each direct light on its own: when
    /// lights are weighted differently, or when the samples' interpolated colour is
    /// not the lights' (under radiosity it is the solution's).
    pub fn gouraud_per_light(&self, scene: &Scene, shadowed: bool) -> bool {
        let gouraud =
            (0..scene.polygons.len()).any(|p| scene.shading_of(p) == ShadingMode::Gouraud);
        let direct = self.direct_lights(scene);
        gouraud
            && match self {
                Integrator::Direct => shadowed && scene.lights.len() > 1,
                Integrator::Radiosity(..) => direct.iter().any(|&d| d),
                Integrator::Whitted(..) => unreachable!("{NO_SCAN_LINE}"),
            }
    }

    /// The drawn polygons again, coloured by light `l`'s unshadowed vertex radiance
    /// alone (for Gouraud shading light by light).
    pub fn light_draw_list(&self, scene: &Scene, view: &View, l: usize) -> Vec<ScreenPolygon> {
        let only: Vec<bool> = (0..scene.lights.len()).map(|m| m == l).collect();
        match self {
            Integrator::Direct => self.draw_list(scene, view, &only),
            Integrator::Radiosity(solution, ..) => {
                let pieces = elements(scene, solution);
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
            Integrator::Whitted(..) => unreachable!("{NO_SCAN_LINE}"),
        }
    }

    /// The polygons the scan-line pass draws, on `view`'s screen.
    pub fn draw_list(&self, scene: &Scene, view: &View, direct: &[bool]) -> Vec<ScreenPolygon> {
        match self {
            Integrator::Direct => {
                let colors = vertex_colors(scene, view, direct);
                prepare(
                    view,
                    scene
                        .polygons
                        .iter()
                        .zip(&colors)
                        .enumerate()
                        .map(|(id, (p, c))| ToPrepare {
                            id: id as u32,
                            element: id as u32,
                            vertices: &p.vertices,
                            colors: c,
                            affine_uv: scene.materials[p.material].interpolation
                                == crate::texture::Interpolation::Affine,
                        }),
                )
            }
            Integrator::Radiosity(solution, ..) => {
                let pieces = elements(scene, solution);
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
            Integrator::Whitted(..) => unreachable!("{NO_SCAN_LINE}"),
        }
    }

    /// The radiance of every sample of `band`.
    pub fn shade_band(
        &self,
        shading: &FrameShading,
        scene: &Scene,
        band: &VisibleSurface,
        visibility: &Visibility,
        gouraud: &[Vec<Vec3>],
    ) -> Vec<Vec3> {
        match self {
            Integrator::Direct => shading.shade_band(band, visibility, gouraud),
            Integrator::Radiosity(_, second, gather) => (0..band.samples.len())
                .into_par_iter()
                .map(|k| {
                    let s = &band.samples[k];
                    if s.is_empty() {
                        return shading.background(band, k);
                    }
                    // Radiosity leaves the front only; a surface seen from behind
                    // is black.
                    if !shading.front(band, k) {
                        return Vec3::ZERO;
                    }
                    let material = scene.material_of(s.polygon as usize);
                    let emitted = material.emission;
                    let scale = shading.diffuse_texture_scale(band, k);
                    let solved = match (gather, scale) {
                        (Some(gather), _) => {
                            let diffuse = material.diffuse * scale.unwrap_or(Vec3::ONE);
                            // A surface that reflects nothing diffusely (a lamp)
                            // needs no gather.
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
                    if let Some(second) = second
                        && scene.material_of(s.polygon as usize).is_specular()
                    {
                        radiance += second_pass_at(shading, second, band, k);
                    }
                    radiance
                })
                .collect(),
            Integrator::Whitted(..) => unreachable!("{NO_SCAN_LINE}"),
        }
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

/// Per light, whether shading adds it directly: every light, but under radiosity
/// the polygon lights, which are emitters of the solution already.
pub fn lit_directly(scene: &Scene, radiosity: bool) -> Vec<bool> {
    scene
        .lights
        .iter()
        .map(|light| !(radiosity && matches!(light, Light::Polygon(_))))
        .collect()
}

/// Whether the second pass computes the direct light of every light itself (and
/// the solution is drawn with its indirect part only).
pub fn exact_direct(scene: &Scene) -> bool {
    scene.radiosity.is_some() && second_pass(scene).is_some_and(|g| g.exact_direct)
}

/// The `[global]` settings of a second pass over a radiosity solution (the two-pass
/// methods; not ray tracing, which reads no solution).
pub fn second_pass(scene: &Scene) -> Option<&GlobalSettings> {
    scene.global.as_ref().filter(|g| g.method.reads_radiosity())
}

/// A solution's elements as the scan-line pass draws them.
fn elements(scene: &Scene, solution: &Solution) -> Vec<display::ElementPolygon> {
    display::element_polygons(scene, &solution.mesh, &solution.elements, solution.display)
}
