//! glTF 2.0 (`.gltf`): one mesh per material, PBR metallic-roughness materials
//! holding the diffuse reflectance (metallic 0, roughness 1), the camera, and the
//! point, spot and distant lights through `KHR_lights_punctual`.
//!
//! The buffer is embedded in the JSON as a base64 data URI, not written as a `.bin`
//! beside it: one self-contained file, written whole or not at all by one atomic
//! rename, that a reference suite can hand around alone. The price (a third more
//! bytes) is small for the catalogue's scenes.
//!
//! Units: a scene unit is written as glTF's metre, unchanged (lumiere's lengths have
//! no unit of their own; the Cornell box's are millimetres), so distances and the
//! inverse-square fall-off stay what they were. Light is converted from radiometric
//! to photometric units at 683 lm/W (the luminous efficacy that defines the
//! candela): a point or spot light of I W/sr becomes 683 I cd, a distant light of
//! E W/m² becomes 683 E lx, an emitter of radiance L becomes 683 L nits. glTF gives
//! a light one intensity and a colour: the intensity is that of the brightest
//! channel, the colour the channels divided by it. Importing divides by 683 again.
//!
//! Polygon and sphere lights become emissive meshes (`KHR_materials_emissive_strength`,
//! emissive factor × strength = 683 L): glTF has no area light, and a viewer may
//! not light the scene with them (`left_out` says so).

use super::Mesh;
use crate::geometry::polygon::triangulate;
use crate::scene::gltf::{LUMENS_PER_WATT, SHARP_CONE_EDGE};
use crate::scene::{Light, Scene};
use base64::Engine as _;
use glam::{DMat3, DQuat, DVec3, Vec3};
use serde_json::{Value, json};

/// Segments around a sphere light's emissive mesh.
const SPHERE_SEGMENTS: u32 = 32;

/// The glTF document of `scene`, its buffer embedded.
pub(super) fn document(scene: &Scene, meshes: &[Mesh]) -> String {
    let mut buffer = Buffer::default();
    let mut gltf_meshes = Vec::new();
    let mut materials = Vec::new();
    let mut nodes = Vec::new();
    for mesh in meshes {
        let mut triangles = Vec::new();
        for polygon in &mesh.polygons {
            let positions: Vec<DVec3> = polygon.iter().map(|v| v.0).collect();
            for t in triangulate(&positions) {
                triangles.push(t.map(|k| polygon[k]));
            }
        }
        let m = &scene.materials[mesh.material];
        materials.push(material(&m.name, m.diffuse, m.emission));
        gltf_meshes.push(buffer.mesh(&m.name, &triangles, materials.len() - 1));
    }
    for (index, light) in scene.lights.iter().enumerate() {
        if let Light::Sphere(l) = light {
            let triangles: Vec<[(DVec3, DVec3); 3]> =
                crate::scene::shapes::sphere(SPHERE_SEGMENTS, true)
                    .iter()
                    .flat_map(|face| {
                        let corners: Vec<(DVec3, DVec3)> = face
                            .iter()
                            .map(|v| (l.centre + v.position * l.radius, v.normal))
                            .collect();
                        (1..corners.len() - 1)
                            .map(move |k| [corners[0], corners[k], corners[k + 1]])
                    })
                    .collect();
            let name = light.label(index);
            materials.push(material(&name, Vec3::ZERO, l.radiance));
            gltf_meshes.push(buffer.mesh(&name, &triangles, materials.len() - 1));
        }
    }
    for (k, mesh) in gltf_meshes.iter().enumerate() {
        nodes.push(json!({"name": mesh["name"], "mesh": k}));
    }

    let c = &scene.camera;
    let forward = (c.look_at - c.eye).normalize();
    let z = -forward;
    let x = c.up.cross(z).normalize();
    let camera_rotation = DQuat::from_mat3(&DMat3::from_cols(x, z.cross(x), z));
    nodes.push(json!({
        "name": "camera",
        "camera": 0,
        "translation": c.eye.to_array(),
        "rotation": camera_rotation.normalize().to_array(),
    }));
    let cameras = json!([{
        "type": "perspective",
        "perspective": {
            "yfov": c.fov_y.to_radians(),
            "aspectRatio": c.width as f64 / c.height as f64,
            "znear": c.near,
        },
    }]);

    let mut lights = Vec::new();
    for (index, light) in scene.lights.iter().enumerate() {
        let name = light.label(index);
        let (description, position, direction) = match light {
            Light::Point(l) => (
                punctual("point", &name, l.intensity),
                Some(l.position),
                None,
            ),
            Light::Spot(l) => {
                let mut spot = punctual("spot", &name, l.intensity);
                spot["spot"] = json!({
                    "innerConeAngle": l.cone_angle * SHARP_CONE_EDGE,
                    "outerConeAngle": l.cone_angle,
                });
                (spot, Some(l.position), Some(l.axis))
            }
            Light::Distant(l) => (
                punctual("directional", &name, l.irradiance),
                None,
                Some(l.direction),
            ),
            Light::Polygon(_) | Light::Sphere(_) => continue,
        };
        let mut node = json!({
            "name": name,
            "extensions": {"KHR_lights_punctual": {"light": lights.len()}},
        });
        if let Some(p) = position {
            node["translation"] = json!(p.to_array());
        }
        if let Some(d) = direction {
            node["rotation"] = json!(pointing(d).to_array());
        }
        nodes.push(node);
        lights.push(description);
    }

    let emissive = materials.iter().any(|m| m.get("extensions").is_some());
    let mut used = Vec::new();
    if !lights.is_empty() {
        used.push("KHR_lights_punctual");
    }
    if emissive {
        used.push("KHR_materials_emissive_strength");
    }
    let mut document = json!({
        "asset": {"version": "2.0", "generator": "lumiere export"},
        "scene": 0,
        "scenes": [{"name": "lumiere", "nodes": (0..nodes.len()).collect::<Vec<_>>()}],
        "nodes": nodes,
        "meshes": gltf_meshes,
        "materials": materials,
        "cameras": cameras,
        "accessors": buffer.accessors,
        "bufferViews": buffer.views,
        "buffers": [{
            "byteLength": buffer.bytes.len(),
            "uri": format!(
                "data:application/octet-stream;base64,{}",
                base64::engine::general_purpose::STANDARD.encode(&buffer.bytes)
            ),
        }],
    });
    // The Khronos validator refuses an empty list of lights or of extensions.
    if !used.is_empty() {
        document["extensionsUsed"] = json!(used);
    }
    if !lights.is_empty() {
        document["extensions"] = json!({"KHR_lights_punctual": {"lights": lights}});
    }
    let mut text = serde_json::to_string_pretty(&document).unwrap_or_default();
    text.push('\n');
    text
}

/// A PBR material of diffuse reflectance `diffuse`, emitting radiance `emission`.
/// Two-sided unless it emits: lumiere shades both sides of a surface, and emits
/// from the front only.
fn material(name: &str, diffuse: Vec3, emission: Vec3) -> Value {
    let mut m = json!({
        "name": name,
        "pbrMetallicRoughness": {
            "baseColorFactor": [diffuse.x, diffuse.y, diffuse.z, 1.0],
            "metallicFactor": 0.0,
            "roughnessFactor": 1.0,
        },
        "doubleSided": emission.max_element() <= 0.0,
    });
    if emission.max_element() > 0.0 {
        let (colour, strength) = colour_and_scale(emission);
        m["emissiveFactor"] = json!(colour);
        m["extensions"] = json!({"KHR_materials_emissive_strength": {
            "emissiveStrength": strength * LUMENS_PER_WATT,
        }});
    }
    m
}

/// A punctual light of `kind` whose radiometric amount per channel is `amount`.
fn punctual(kind: &str, name: &str, amount: Vec3) -> Value {
    let (colour, scale) = colour_and_scale(amount);
    json!({
        "name": name,
        "type": kind,
        "color": colour,
        "intensity": scale * LUMENS_PER_WATT,
    })
}

/// An RGB amount as glTF's colour in [0, 1] (the channels over the brightest) and
/// that brightest channel.
fn colour_and_scale(amount: Vec3) -> ([f64; 3], f64) {
    let a = amount.as_dvec3();
    let scale = a.max_element();
    if scale > 0.0 {
        ((a / scale).to_array(), scale)
    } else {
        ([1.0; 3], 0.0)
    }
}

/// The rotation taking glTF's -Z (where lights point) to `direction`.
fn pointing(direction: DVec3) -> DQuat {
    let z = -direction.normalize();
    let x = z.any_orthonormal_vector();
    DQuat::from_mat3(&DMat3::from_cols(x, z.cross(x), z)).normalize()
}

/// The binary buffer, its views and accessors, filled mesh by mesh.
#[derive(Default)]
struct Buffer {
    bytes: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Buffer {
    /// A mesh of one primitive: the triangles' corners (position, normal), not
    /// shared between triangles, and their indices.
    fn mesh(&mut self, name: &str, triangles: &[[(DVec3, DVec3); 3]], material: usize) -> Value {
        let corners: Vec<(DVec3, DVec3)> = triangles.iter().flatten().copied().collect();
        let positions: Vec<[f32; 3]> = corners.iter().map(|c| c.0.as_vec3().to_array()).collect();
        let normals: Vec<[f32; 3]> = corners
            .iter()
            .map(|c| c.1.normalize_or_zero().as_vec3().to_array())
            .collect();
        let mut low = [f32::INFINITY; 3];
        let mut high = [f32::NEG_INFINITY; 3];
        for p in &positions {
            for k in 0..3 {
                low[k] = low[k].min(p[k]);
                high[k] = high[k].max(p[k]);
            }
        }
        let position = self.accessor(&positions, "VEC3", 5126, 34962);
        self.accessors[position]["min"] = json!(low);
        self.accessors[position]["max"] = json!(high);
        let normal = self.accessor(&normals, "VEC3", 5126, 34962);
        let indices: Vec<[u32; 1]> = (0..corners.len() as u32).map(|k| [k]).collect();
        let indices = self.accessor(&indices, "SCALAR", 5125, 34963);
        json!({
            "name": name,
            "primitives": [{
                "attributes": {"POSITION": position, "NORMAL": normal},
                "indices": indices,
                "material": material,
                "mode": 4,
            }],
        })
    }

    /// An accessor over a new view of `items` (4-byte components: f32 or u32).
    fn accessor<T: Copy + ToBytes, const N: usize>(
        &mut self,
        items: &[[T; N]],
        kind: &str,
        component: u32,
        target: u32,
    ) -> usize {
        let offset = self.bytes.len();
        for item in items {
            for c in item {
                self.bytes.extend_from_slice(&c.le_bytes());
            }
        }
        self.views.push(json!({
            "buffer": 0,
            "byteOffset": offset,
            "byteLength": self.bytes.len() - offset,
            "target": target,
        }));
        self.accessors.push(json!({
            "bufferView": self.views.len() - 1,
            "componentType": component,
            "count": items.len(),
            "type": kind,
        }));
        self.accessors.len() - 1
    }
}

/// A 4-byte component, little-endian as glTF stores it.
trait ToBytes {
    fn le_bytes(self) -> [u8; 4];
}

impl ToBytes for f32 {
    fn le_bytes(self) -> [u8; 4] {
        self.to_le_bytes()
    }
}

impl ToBytes for u32 {
    fn le_bytes(self) -> [u8; 4] {
        self.to_le_bytes()
    }
}
