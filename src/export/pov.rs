//! POV-Ray 3.7 scene description language. POV-Ray's conventions differ from
//! lumiere's, and each difference is undone here:
//!
//! - it is left-handed: every z (geometry, camera, lights) is negated, and the
//!   mirror image of the scene seen by a left-handed camera is the right-handed
//!   image of the scene;
//! - its diffuse term has no 1/π and its lights do not fall off: each light gets
//!   `fade_power 2` with a `fade_distance` d far smaller than the scene (a
//!   thousandth of its diagonal), whose attenuation 2 / (1 + (r/d)²) is 2d²/r² to
//!   one part in a million at a thousand times d, and a colour scaled by 1/(2πd²)
//!   to compensate (a point light of intensity I: I / (2πd²));
//! - an area light's lightlets sit on the corners of its grid: the axes are made
//!   (n − 1)/n of the emitter's edges, so that they sit on the centres of n × n cells
//!   tiling it, and jitter moves each over its own cell; `area_illumination` shades
//!   from every lightlet, and a spotlight along the emitter's normal (tightness 1,
//!   radius and falloff 90°) gives each the emitter's cos θ';
//! - colours are linear (`assumed_gamma 1.0`); render with `File_Gamma=1.0` to a
//!   16-bit PNG, or to EXR, which POV-Ray writes as half floats.

use super::Mesh;
use crate::scene::{Light, Scene};
use glam::{DVec3, Vec3};
use std::f64::consts::PI;
use std::fmt::Write as _;

/// A vector in POV-Ray's left-handed frame.
fn v(p: DVec3) -> String {
    format!("<{}, {}, {}>", p.x, p.y, -p.z)
}

fn colour(c: Vec3, scale: f64) -> String {
    let s = |x: f32| x as f64 * scale;
    format!("rgb <{}, {}, {}>", s(c.x), s(c.y), s(c.z))
}

/// The scene's diagonal, for the fade distance and for placing distant lights.
fn diagonal(scene: &Scene) -> f64 {
    let mut low = DVec3::splat(f64::INFINITY);
    let mut high = DVec3::splat(f64::NEG_INFINITY);
    for p in scene.polygons.iter().flat_map(|p| p.positions()) {
        low = low.min(p);
        high = high.max(p);
    }
    if low.x > high.x {
        1.0
    } else {
        (high - low).length().max(1e-9)
    }
}

pub(super) fn scene(scene: &Scene, meshes: &[Mesh], area_samples: u32) -> String {
    let diagonal = diagonal(scene);
    let fade = diagonal * 1e-3;
    // Light colour per unit of intensity (W/sr), with the fade above.
    let per_intensity = 1.0 / (2.0 * PI * fade * fade);
    let mut out = String::from(
        "// Written by lumiere export: see its documentation for the conventions.\n#version 3.7;\n",
    );
    let b = scene.render.background;
    let _ = writeln!(
        out,
        "global_settings {{ assumed_gamma 1.0 max_trace_level 5 ambient_light rgb 0 }}\nbackground {{ {} }}",
        colour(b, 1.0)
    );
    let c = &scene.camera;
    let aspect = c.width as f64 / c.height as f64;
    let horizontal = 2.0 * ((c.fov_y.to_radians() / 2.0).tan() * aspect).atan();
    let _ = writeln!(
        out,
        "camera {{\n  perspective\n  location {}\n  sky {}\n  right x*{aspect}\n  up y\n  angle {}\n  look_at {}\n}}",
        v(c.eye),
        v(c.up),
        horizontal.to_degrees(),
        v(c.look_at)
    );
    for (k, mesh) in meshes.iter().enumerate() {
        let m = &scene.materials[mesh.material];
        let texture = if m.is_emitter() {
            format!(
                "texture {{ pigment {{ {} }} finish {{ ambient 0 emission 1 diffuse 0 }} }}",
                colour(m.emission, 1.0)
            )
        } else {
            format!(
                "texture {{ pigment {{ {} }} finish {{ ambient 0 emission 0 diffuse 1 specular 0 }} }}",
                colour(m.diffuse, 1.0)
            )
        };
        let _ = writeln!(out, "// material {}\nmesh2 {{", m.name.replace('\n', " "));
        let count: usize = mesh.polygons.iter().map(Vec::len).sum();
        let _ = write!(out, "  vertex_vectors {{ {count}");
        for (p, _) in mesh.polygons.iter().flatten() {
            let _ = write!(out, ",\n    {}", v(*p));
        }
        out.push_str("\n  }\n");
        if !mesh.faceted {
            let _ = write!(out, "  normal_vectors {{ {count}");
            for (_, n) in mesh.polygons.iter().flatten() {
                let _ = write!(out, ",\n    {}", v(*n));
            }
            out.push_str("\n  }\n");
        }
        let mut faces = Vec::new();
        let mut next = 0;
        for polygon in &mesh.polygons {
            let positions: Vec<DVec3> = polygon.iter().map(|p| p.0).collect();
            for [a, b, c] in crate::geometry::polygon::triangulate(&positions) {
                faces.push(format!("<{}, {}, {}>", next + a, next + b, next + c));
            }
            next += polygon.len();
        }
        let _ = writeln!(
            out,
            "  face_indices {{ {},\n    {}\n  }}",
            faces.len(),
            faces.join(",\n    ")
        );
        let _ = writeln!(
            out,
            "  {texture}\n  {}\n}} // mesh {k}",
            if m.is_emitter() { "no_shadow" } else { "" }
        );
    }
    let n = area_samples;
    let shrink = (n - 1) as f64 / n as f64;
    for light in &scene.lights {
        match light {
            Light::Point(l) => {
                let _ = writeln!(
                    out,
                    "light_source {{ {} color {} fade_distance {fade} fade_power 2 }}",
                    v(l.position),
                    colour(l.intensity, per_intensity)
                );
            }
            Light::Spot(l) => {
                let angle = l.cone_angle.to_degrees();
                let _ = writeln!(
                    out,
                    "light_source {{ {} color {} spotlight point_at {} radius {angle} falloff {angle} tightness 0 fade_distance {fade} fade_power 2 }}",
                    v(l.position),
                    colour(l.intensity, per_intensity),
                    v(l.position + l.axis)
                );
            }
            Light::Distant(l) => {
                // Far away along the light's travel, with no fade: colour E / π.
                let at = -l.direction * diagonal * 100.0;
                let _ = writeln!(
                    out,
                    "light_source {{ {} color {} parallel point_at {} }}",
                    v(at),
                    colour(l.irradiance, 1.0 / PI),
                    v(DVec3::ZERO)
                );
            }
            Light::Polygon(l) => {
                // The intensity of a Lambertian emitter along its normal is L A; the
                // spotlight's tightness 1 gives the cos θ' of other directions.
                let (e1, e2) = (
                    l.vertices[1] - l.vertices[0],
                    l.vertices[l.vertices.len() - 1] - l.vertices[0],
                );
                let _ = writeln!(
                    out,
                    "light_source {{ {} color {} spotlight point_at {} radius 90 falloff 90 tightness 1\n  area_light {}, {}, {n}, {n} jitter area_illumination on\n  fade_distance {fade} fade_power 2 }}",
                    v(l.centre),
                    colour(l.radiance, l.area * per_intensity),
                    v(l.centre + l.normal),
                    v(e1 * shrink),
                    v(e2 * shrink)
                );
            }
            Light::Sphere(l) => {
                // A sphere of radiance L has intensity L π r² in every direction;
                // its lightlets fill the disc it shows to each point.
                let d = 2.0 * l.radius * shrink;
                let _ = writeln!(
                    out,
                    "light_source {{ {} color {}\n  area_light <{d}, 0, 0>, <0, 0, {d}>, {n}, {n} circular orient jitter area_illumination on\n  fade_distance {fade} fade_power 2 }}",
                    v(l.centre),
                    colour(l.radiance, PI * l.radius * l.radius * per_intensity)
                );
            }
        }
    }
    out
}
