//! Wavefront OBJ + MTL + a JSON sidecar: `scene.obj` (the polygons, as polygons,
//! one group per material), `scene.mtl` (Kd, Ks, Ns, Ke) and `scene.json` (what
//! OBJ cannot say: camera, lights, the whole materials and the units), so that any
//! renderer can rebuild the scene.
//!
//! The sidecar's fields:
//!
//! - `format`: `"lumiere-scene"`, `version`: 1; `obj`, `mtl`: the files beside it.
//! - `units`: `length` (the OBJ's coordinates are lumiere's scene units, which have
//!   no physical unit of their own: the Cornell box's are millimetres), and the unit
//!   of each light quantity below, `per unit²` meaning per square scene unit.
//! - `coordinates`: right-handed, y up; polygons counter-clockwise seen from their
//!   front.
//! - `camera`: `eye`, `look_at`, `up`, `fov_y_degrees` (vertical field of view),
//!   `width`, `height` (pixels), `near` (the near clipping distance).
//! - `render`: `exposure`, `background` (linear RGB radiance where nothing is seen).
//! - `lights`: each with `kind` and `name`, then by kind: `point` (`position`,
//!   `intensity` in W/sr: irradiance I/d² at distance d); `spot` (`position`,
//!   `axis`, `cone_angle_degrees`, `intensity` on the axis, `distribution`:
//!   `{"cosine_power": p}` for cosᵖ θ or `{"table_degrees": [[θ, f], …]}`
//!   interpolated linearly); `distant` (`direction` the light travels,
//!   `irradiance` on a surface facing it); `polygon` (`vertices`, `normal`,
//!   `radiance`, one-sided along the normal, also a face of the OBJ); `sphere`
//!   (`centre`, `radius`, `radiance`; not in the OBJ: lumiere's sphere lights are
//!   not seen by the camera and cast no shadow).
//! - `materials`: `name` (lumiere's), `mtl_name` (the MTL's, spaces replaced),
//!   `diffuse` ρ (radiance ρ/π × irradiance), `specular` and `exponent` (lumiere's
//!   energy-normalised Phong lobe), `emission` (radiance), `mirror`, `ior` (or
//!   null), `transmittance`, `translucence`, `textured` (a texture or bump map is
//!   on it, not written).
//!
//! Every colour is linear RGB.

use super::Mesh;
use crate::error::Result;
use crate::image_io::write_atomically;
use crate::scene::{Light, Scene, SpotDistribution};
use glam::{DVec3, Vec3};
use serde_json::{Value, json};
use std::fmt::Write as _;
use std::path::Path;

/// Writes `output` (`.obj`), and its `.mtl` and `.json` beside it, each whole or
/// not at all; the OBJ, which names the others, last.
pub(super) fn write(scene: &Scene, meshes: &[Mesh], output: &Path) -> Result<()> {
    let mtl_path = output.with_extension("mtl");
    let json_path = output.with_extension("json");
    let file_name = |p: &Path| {
        p.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    };
    let mut mtl =
        String::from("# Written by lumiere export: linear RGB; see the .json beside it.\n");
    let mut obj = format!(
        "# Written by lumiere export: scene units, right-handed, y up.\nmtllib {}\n",
        file_name(&mtl_path)
    );
    let mut next = 1;
    for mesh in meshes {
        let m = &scene.materials[mesh.material];
        let _ = writeln!(
            mtl,
            "newmtl {}\nKd {}\nKs {}\nNs {}\nKe {}\n",
            mtl_name(&m.name),
            rgb(m.diffuse),
            rgb(m.specular),
            m.exponent,
            rgb(m.emission)
        );
        let _ = writeln!(obj, "g {}\nusemtl {}", mtl_name(&m.name), mtl_name(&m.name));
        for polygon in &mesh.polygons {
            for (p, n) in polygon {
                let _ = writeln!(obj, "v {} {} {}\nvn {} {} {}", p.x, p.y, p.z, n.x, n.y, n.z);
            }
            obj.push('f');
            for k in next..next + polygon.len() {
                let _ = write!(obj, " {k}//{k}");
            }
            obj.push('\n');
            next += polygon.len();
        }
    }
    let sidecar = sidecar(scene, &file_name(output), &file_name(&mtl_path));
    let mut json = serde_json::to_string_pretty(&sidecar).unwrap_or_default();
    json.push('\n');
    write_atomically(&mtl_path, mtl.as_bytes())?;
    write_atomically(&json_path, json.as_bytes())?;
    write_atomically(output, obj.as_bytes())
}

/// A material's name as an MTL name: one word.
fn mtl_name(name: &str) -> String {
    name.split_whitespace().collect::<Vec<_>>().join("_")
}

fn rgb(c: Vec3) -> String {
    format!("{} {} {}", c.x, c.y, c.z)
}

fn v(p: DVec3) -> Value {
    json!(p.to_array())
}

fn c(colour: Vec3) -> Value {
    json!(colour.to_array())
}

fn sidecar(scene: &Scene, obj: &str, mtl: &str) -> Value {
    let camera = &scene.camera;
    let lights: Vec<Value> = scene
        .lights
        .iter()
        .enumerate()
        .map(|(index, light)| {
            let mut l = match light {
                Light::Point(l) => json!({
                    "kind": "point",
                    "position": v(l.position),
                    "intensity": c(l.intensity),
                }),
                Light::Spot(l) => json!({
                    "kind": "spot",
                    "position": v(l.position),
                    "axis": v(l.axis),
                    "cone_angle_degrees": l.cone_angle.to_degrees(),
                    "intensity": c(l.intensity),
                    "distribution": match &l.distribution {
                        SpotDistribution::CosinePower(p) => json!({"cosine_power": p}),
                        SpotDistribution::Table(t) => json!({"table_degrees": t
                            .iter()
                            .map(|(theta, f)| [theta.to_degrees(), *f])
                            .collect::<Vec<_>>()}),
                    },
                }),
                Light::Distant(l) => json!({
                    "kind": "distant",
                    "direction": v(l.direction),
                    "irradiance": c(l.irradiance),
                }),
                Light::Polygon(l) => json!({
                    "kind": "polygon",
                    "vertices": l.vertices.iter().map(|p| p.to_array()).collect::<Vec<_>>(),
                    "normal": v(l.normal),
                    "radiance": c(l.radiance),
                }),
                Light::Sphere(l) => json!({
                    "kind": "sphere",
                    "centre": v(l.centre),
                    "radius": l.radius,
                    "radiance": c(l.radiance),
                }),
            };
            l["name"] = json!(light.label(index));
            l
        })
        .collect();
    let materials: Vec<Value> = scene
        .materials
        .iter()
        .map(|m| {
            json!({
                "name": m.name,
                "mtl_name": mtl_name(&m.name),
                "diffuse": c(m.diffuse),
                "specular": c(m.specular),
                "exponent": m.exponent,
                "emission": c(m.emission),
                "mirror": c(m.mirror),
                "ior": m.ior,
                "transmittance": c(m.transmittance),
                "translucence": c(m.translucence),
                "textured": m.is_textured(),
            })
        })
        .collect();
    json!({
        "format": "lumiere-scene",
        "version": 1,
        "obj": obj,
        "mtl": mtl,
        "units": {
            "length": "scene units, as the OBJ's coordinates (lumiere's lengths have no physical unit of their own; the Cornell box's are millimetres)",
            "intensity": "W/sr",
            "irradiance": "W/unit²",
            "radiance": "W/(sr·unit²)",
            "angles": "degrees",
        },
        "coordinates": "right-handed, y up; polygons counter-clockwise seen from their front",
        "camera": {
            "eye": v(camera.eye),
            "look_at": v(camera.look_at),
            "up": v(camera.up),
            "fov_y_degrees": camera.fov_y,
            "width": camera.width,
            "height": camera.height,
            "near": camera.near,
        },
        "render": {
            "exposure": scene.render.exposure,
            "background": c(scene.render.background),
        },
        "lights": lights,
        "materials": materials,
    })
}
