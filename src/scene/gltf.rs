//! glTF 2.0 scenes (`.gltf` with its buffers, or `.glb`), read through the `gltf`
//! crate into a scene table, the same table a TOML scene file gives: lumiere's
//! render settings (shading, shadow method, image size) are then its defaults,
//! changed by the usual `key=value` overrides (`--set shadows.method=...`).
//!
//! What is read:
//!
//! - triangles (lists, strips and fans) of the default scene's nodes, each node's
//!   transform applied (normals by the inverse transpose, the winding reversed
//!   under a mirroring transform); a primitive whose vertex normals are its face
//!   normals is shaded flat, else smooth. Each primitive goes to the builder as an
//!   in-memory OBJ model, so it meets the same checks as an OBJ file's faces (the
//!   memory budget, faces of zero area dropped with a warning);
//! - the base colour factor as the diffuse reflectance, and the base colour
//!   texture (texture coordinates 0) as the diffuse texture multiplying it;
//! - `KHR_lights_punctual` point, spot and directional lights, at 683 lm/W back to
//!   radiometric units (see `LUMENS_PER_WATT`); a spot's smooth edge between its
//!   inner and outer cone becomes a table of its fall-off;
//! - the first perspective camera (depth first through the scene's nodes): its
//!   vertical field of view, `znear` as the near plane, and an image whose longer
//!   side is 512 pixels at its aspect ratio (square without one). Without a
//!   camera the scene is framed from +z and a warning says so.
//!
//! Everything else is named in a warning, one line each: metallic and roughness
//! (lumiere reads the base colour as a Lambertian reflectance), normal, occlusion
//! and emissive textures and emission, transparency, vertex colours, other texture
//! coordinate sets, animations, skins, morph targets, lights' ranges, extra or
//! orthographic cameras, points and lines, other scenes, unknown extensions.
//! Single-sided materials are shaded on both sides, as every lumiere surface is.

use super::resources::{Directory, Resources};
use crate::error::{Error, FileOp, Result};
use crate::image_io::read_file;
use base64::Engine as _;
use glam::{DMat3, DMat4, DVec2, DVec3};
use gltf::khr_lights_punctual::Kind;
use gltf::mesh::Mode;
use gltf::texture::WrappingMode;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use toml::{Table, Value};

/// Lumens per watt between radiometric and photometric units: 683 lm/W, the
/// luminous efficacy of 540 THz light that defines the candela. glTF's point and
/// spot lights are in candela (lm/sr), directional lights in lux (lm/m²): lumiere's
/// I W/sr is 683 I cd, its E W/m² is 683 E lx (a scene unit taken as a metre).
pub const LUMENS_PER_WATT: f64 = 683.0;

/// A spot light's inner cone over its outer cone at and above which the edge is
/// read as sharp (a uniform cone): glTF asks for an inner angle below the outer,
/// so lumiere's uniform cone is written with this ratio.
pub const SHARP_CONE_EDGE: f64 = 0.999;

/// The longer side of the image of a glTF camera, in pixels.
const IMAGE_SIDE: f64 = 512.0;

/// Angles at which a spot light's smooth edge is tabulated.
const EDGE_STEPS: usize = 16;

/// A glTF scene as a scene table, the files the table names (OBJ models and
/// texture images, in memory) and what could not be carried over.
pub struct Imported {
    /// The scene table (camera, lights, materials, textures, objects).
    pub table: Table,
    /// The files its objects and textures name, by path.
    pub files: HashMap<String, Vec<u8>>,
    /// What the scene leaves out, a line each, each starting `gltf: `.
    pub warnings: Vec<String>,
}

/// Reads the glTF or GLB file at `path` (its external buffers and images beside it).
pub fn read(path: &Path) -> Result<Imported> {
    let bytes = read_file(path, FileOp::ReadScene)?;
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    from_bytes(&bytes, path, &Directory(base))
}

/// The scene of glTF or GLB `bytes` named `path`, external files (buffers, images)
/// read from `files` by their paths relative to it.
pub fn from_bytes(bytes: &[u8], path: &Path, files: &dyn Resources) -> Result<Imported> {
    let model = |message: String| Error::Model {
        path: path.to_path_buf(),
        message,
    };
    let gltf = gltf::Gltf::from_slice(bytes)
        .map_err(|e| model(format!("not a readable glTF 2.0 file: {e}")))?;
    let buffers = buffers(&gltf, files).map_err(model)?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene.gltf".into());
    let mut import = Import {
        doc: &gltf.document,
        buffers: &buffers,
        external: files,
        name,
        table: Table::new(),
        files: HashMap::new(),
        warnings: Vec::new(),
        objects: Vec::new(),
        lights: Vec::new(),
        camera: None,
        low: DVec3::splat(f64::INFINITY),
        high: DVec3::splat(f64::NEG_INFINITY),
        materials: HashMap::new(),
    };
    import.whole_document();
    let scene = gltf.default_scene().or_else(|| gltf.scenes().next());
    match scene {
        Some(scene) => {
            if gltf.scenes().len() > 1 {
                import.warn(format!(
                    "only scene {} of its {} scenes is read",
                    scene.index(),
                    gltf.scenes().len()
                ));
            }
            for node in scene.nodes() {
                import.node(&node, DMat4::IDENTITY).map_err(model)?;
            }
        }
        None => {
            // No scene: the nodes no other node holds are the roots.
            let children: Vec<usize> = gltf
                .nodes()
                .flat_map(|n| n.children().map(|c| c.index()).collect::<Vec<_>>())
                .collect();
            for node in gltf.nodes().filter(|n| !children.contains(&n.index())) {
                import.node(&node, DMat4::IDENTITY).map_err(model)?;
            }
        }
    }
    import.finish();
    Ok(Imported {
        table: import.table,
        files: import.files,
        warnings: import.warnings,
    })
}

/// Each buffer's bytes: the GLB's binary chunk, a data URI, or a file beside the
/// glTF; each at least as long as it says, and each view within its buffer.
fn buffers(gltf: &gltf::Gltf, files: &dyn Resources) -> std::result::Result<Vec<Vec<u8>>, String> {
    let mut out = Vec::new();
    for buffer in gltf.buffers() {
        let index = buffer.index();
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => gltf
                .blob
                .clone()
                .ok_or_else(|| format!("buffer {index}: the GLB has no binary chunk"))?,
            gltf::buffer::Source::Uri(uri) => {
                uri_bytes(uri, files).map_err(|e| format!("buffer {index}: {e}"))?
            }
        };
        if data.len() < buffer.length() {
            return Err(format!(
                "buffer {index} holds {} bytes, fewer than its byteLength {}",
                data.len(),
                buffer.length()
            ));
        }
        out.push(data);
    }
    for view in gltf.views() {
        let end = view.offset().saturating_add(view.length());
        let held = out[view.buffer().index()].len();
        if end > held {
            return Err(format!(
                "bufferView {} reaches byte {end}, beyond the {held} bytes of buffer {}",
                view.index(),
                view.buffer().index()
            ));
        }
    }
    Ok(out)
}

/// The bytes a URI names: a base64 data URI, or a file relative to the glTF.
fn uri_bytes(uri: &str, files: &dyn Resources) -> std::result::Result<Vec<u8>, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, data) = rest
            .split_once(";base64,")
            .ok_or("a data URI that is not base64")?;
        return base64::engine::general_purpose::STANDARD
            .decode(data)
            .map_err(|e| format!("its data URI is not base64: {e}"));
    }
    if uri.contains("://") {
        return Err(format!(
            "{uri}: only files beside the glTF and data URIs are read"
        ));
    }
    let file = PathBuf::from(percent_decoded(uri));
    files
        .read(&file)
        .map_err(|e| match std::error::Error::source(&e) {
            Some(cause) => format!("{e}: {cause}"),
            None => e.to_string(),
        })
}

/// A relative URI's path with its `%XX` escapes decoded (`my%20model.bin`).
fn percent_decoded(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut k = 0;
    while k < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        match (
            bytes[k],
            bytes.get(k + 1).and_then(|&b| hex(b)),
            bytes.get(k + 2).and_then(|&b| hex(b)),
        ) {
            (b'%', Some(h), Some(l)) => {
                out.push((h * 16 + l) as u8);
                k += 3;
            }
            (b, _, _) => {
                out.push(b);
                k += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

struct Import<'a> {
    doc: &'a gltf::Document,
    buffers: &'a [Vec<u8>],
    external: &'a dyn Resources,
    /// The glTF file's name, for the in-memory files' paths.
    name: String,
    table: Table,
    files: HashMap<String, Vec<u8>>,
    warnings: Vec<String>,
    objects: Vec<Value>,
    lights: Vec<Value>,
    camera: Option<Table>,
    /// The bounds of the vertices read, for a camera when the file has none.
    low: DVec3,
    high: DVec3,
    /// The scene table's material name of each glTF material (None: the default).
    materials: HashMap<Option<usize>, String>,
}

impl Import<'_> {
    fn warn(&mut self, what: String) {
        let line = format!("gltf: {what}");
        if !self.warnings.contains(&line) {
            self.warnings.push(line);
        }
    }

    /// What the document holds beyond any node: animations, skins, extensions.
    fn whole_document(&mut self) {
        let animations = self.doc.animations().count();
        if animations > 0 {
            self.warn(format!(
                "{animations} animations are left out (the scene is read at rest)"
            ));
        }
        for extension in self.doc.extensions_used() {
            if !["KHR_lights_punctual", "KHR_materials_emissive_strength"].contains(&extension) {
                self.warn(format!("extension {extension} is not read"));
            }
        }
    }

    fn node(&mut self, node: &gltf::Node, parent: DMat4) -> std::result::Result<(), String> {
        let local = DMat4::from_cols_array_2d(&node.transform().matrix().map(|c| c.map(f64::from)));
        let world = parent * local;
        // The object's name, and the node as warnings name it.
        let object = node
            .name()
            .map_or_else(|| format!("node {}", node.index()), str::to_string);
        let label = match node.name() {
            Some(name) => format!("node {} (`{name}`)", node.index()),
            None => format!("node {}", node.index()),
        };
        if node.skin().is_some() {
            self.warn(format!(
                "{label}: its skin is left out (the mesh is read unposed)"
            ));
        }
        if let Some(mesh) = node.mesh() {
            if mesh.weights().is_some() || node.weights().is_some() {
                self.warn(format!("{label}: morph target weights are left out"));
            }
            for primitive in mesh.primitives() {
                self.primitive(&label, &object, &primitive, &world)?;
            }
        }
        if let Some(camera) = node.camera() {
            self.camera(&label, &camera, &world);
        }
        if let Some(light) = node.light() {
            self.light(&light, &world);
        }
        for child in node.children() {
            self.node(&child, world)?;
        }
        Ok(())
    }

    fn camera(&mut self, label: &str, camera: &gltf::Camera, world: &DMat4) {
        let name = camera.name().map_or(String::new(), |n| format!(" `{n}`"));
        let gltf::camera::Projection::Perspective(p) = camera.projection() else {
            self.warn(format!(
                "{label}: orthographic camera{name} left out (lumiere's cameras are perspective)"
            ));
            return;
        };
        if self.camera.is_some() {
            self.warn(format!(
                "{label}: camera{name} left out (lumiere renders through the first perspective camera)"
            ));
            return;
        }
        let eye = world.transform_point3(DVec3::ZERO);
        let forward = world.transform_vector3(DVec3::NEG_Z).normalize_or_zero();
        let up = world.transform_vector3(DVec3::Y).normalize_or_zero();
        let aspect = p.aspect_ratio().map_or(1.0, f64::from);
        let (width, height) = image_size(aspect);
        let mut table = Table::new();
        table.insert("eye".into(), vector(eye));
        table.insert("look_at".into(), vector(eye + forward));
        table.insert("up".into(), vector(up));
        table.insert(
            "fov_y".into(),
            Value::Float(f64::from(p.yfov()).to_degrees()),
        );
        table.insert("width".into(), Value::Integer(width));
        table.insert("height".into(), Value::Integer(height));
        table.insert("near".into(), Value::Float(f64::from(p.znear())));
        self.camera = Some(table);
    }

    fn light(&mut self, light: &gltf::khr_lights_punctual::Light, world: &DMat4) {
        let name = light
            .name()
            .map_or_else(|| format!("light {}", light.index()), str::to_string);
        if light.range().is_some() {
            self.warn(format!(
                "light `{name}`: its range is left out (lumiere's lights fall off by the inverse square, without a cut-off)"
            ));
        }
        // Back from lumens to watts: cd → W/sr, lx → W/m².
        let amount = DVec3::from(light.color().map(f64::from))
            * (f64::from(light.intensity()) / LUMENS_PER_WATT);
        let position = world.transform_point3(DVec3::ZERO);
        let direction = world.transform_vector3(DVec3::NEG_Z).normalize_or_zero();
        let mut table = Table::new();
        table.insert("name".into(), Value::String(name));
        match light.kind() {
            Kind::Point => {
                table.insert("type".into(), "point".into());
                table.insert("position".into(), vector(position));
                table.insert("intensity".into(), vector(amount));
            }
            Kind::Directional => {
                table.insert("type".into(), "distant".into());
                table.insert("direction".into(), vector(direction));
                table.insert("irradiance".into(), vector(amount));
            }
            Kind::Spot {
                inner_cone_angle,
                outer_cone_angle,
            } => {
                let (inner, outer) = (f64::from(inner_cone_angle), f64::from(outer_cone_angle));
                // lumiere's cone is at most a half space; glTF's is too, but f32 may
                // put π/2 a hair above it.
                let outer_degrees = outer.to_degrees().min(90.0);
                table.insert("type".into(), "spot".into());
                table.insert("position".into(), vector(position));
                table.insert("axis".into(), vector(direction));
                table.insert("cone_angle".into(), Value::Float(outer_degrees));
                table.insert("intensity".into(), vector(amount));
                // f32 holds 0.999 to 6e-8.
                if inner < outer * SHARP_CONE_EDGE * (1.0 - 1e-6) {
                    table.insert("distribution".into(), spot_edge(inner, outer));
                }
            }
        }
        self.lights.push(Value::Table(table));
    }

    fn primitive(
        &mut self,
        label: &str,
        object_name: &str,
        primitive: &gltf::Primitive,
        world: &DMat4,
    ) -> std::result::Result<(), String> {
        let what = format!("{label}, primitive {}", primitive.index());
        let triangles_of = |mode: Mode, n: usize| -> Option<Vec<[usize; 3]>> {
            Some(match mode {
                Mode::Triangles => (0..n / 3).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
                // Every other triangle of a strip is turned to keep the winding.
                Mode::TriangleStrip => (0..n.saturating_sub(2))
                    .map(|t| {
                        if t % 2 == 0 {
                            [t, t + 1, t + 2]
                        } else {
                            [t + 1, t, t + 2]
                        }
                    })
                    .collect(),
                Mode::TriangleFan => (1..n.saturating_sub(1)).map(|t| [0, t, t + 1]).collect(),
                Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => return None,
            })
        };
        if primitive.morph_targets().len() > 0 {
            self.warn(format!("{what}: its morph targets are left out"));
        }
        if primitive.get(&gltf::Semantic::Positions).is_none() {
            self.warn(format!("{what}: no positions, left out"));
            return Ok(());
        }
        let reader = primitive.reader(|b| self.buffers.get(b.index()).map(Vec::as_slice));
        let outside =
            |attribute: &str| format!("{what}: its {attribute} lie outside their bufferView");
        let positions: Vec<DVec3> = reader
            .read_positions()
            .ok_or_else(|| outside("positions"))?
            .map(|p| DVec3::from(p.map(f64::from)))
            .collect();
        let normals: Option<Vec<DVec3>> = match primitive.get(&gltf::Semantic::Normals) {
            Some(_) => Some(
                reader
                    .read_normals()
                    .ok_or_else(|| outside("normals"))?
                    .map(|n| DVec3::from(n.map(f64::from)))
                    .collect(),
            ),
            None => None,
        };
        let material = primitive.material();
        let textured = material.pbr_metallic_roughness().base_color_texture();
        let uvs: Option<Vec<DVec2>> =
            match (&textured, primitive.get(&gltf::Semantic::TexCoords(0))) {
                (Some(_), Some(_)) => Some(
                    reader
                        .read_tex_coords(0)
                        .ok_or_else(|| outside("texture coordinates"))?
                        .into_f32()
                        .map(|[u, v]| DVec2::new(f64::from(u), f64::from(v)))
                        .collect(),
                ),
                (Some(_), None) => {
                    self.warn(format!(
                        "{what}: textured without TEXCOORD_0: its texture shows one texel"
                    ));
                    None
                }
                (None, _) => None,
            };
        if primitive.get(&gltf::Semantic::Colors(0)).is_some() {
            self.warn(format!("{what}: its vertex colours are left out"));
        }
        let corners: Vec<usize> = match primitive.indices() {
            Some(_) => reader
                .read_indices()
                .ok_or_else(|| outside("indices"))?
                .into_u32()
                .map(|i| i as usize)
                .collect(),
            None => (0..positions.len()).collect(),
        };
        if let Some(&bad) = corners.iter().find(|&&i| i >= positions.len()) {
            return Err(format!(
                "{what}: index {bad} beyond its {} vertices",
                positions.len()
            ));
        }
        let Some(triangles) = triangles_of(primitive.mode(), corners.len()) else {
            self.warn(format!(
                "{what}: {:?} are not triangles, left out",
                primitive.mode()
            ));
            return Ok(());
        };
        if triangles.is_empty() {
            return Ok(());
        }
        // A mirroring transform turns front faces into back faces: reverse them.
        let mirrored = DMat3::from_mat4(*world).determinant() < 0.0;
        let normal_matrix = DMat3::from_mat4(*world).inverse().transpose();
        let placed: Vec<DVec3> = positions
            .iter()
            .map(|&p| world.transform_point3(p))
            .collect();
        for p in &placed {
            self.low = self.low.min(*p);
            self.high = self.high.max(*p);
        }
        let placed_normals: Option<Vec<DVec3>> = normals.as_ref().map(|n| {
            n.iter()
                .map(|&n| (normal_matrix * n).normalize_or_zero())
                .collect()
        });
        let faces: Vec<[usize; 3]> = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|k| corners[k]);
                if mirrored { [a, c, b] } else { [a, b, c] }
            })
            .collect();
        // Flat when every corner's normal is its face's: the builder's own face
        // normals are then exact.
        let smooth = placed_normals.as_ref().is_some_and(|n| {
            faces.iter().any(|f| {
                let face = (placed[f[1]] - placed[f[0]])
                    .cross(placed[f[2]] - placed[f[0]])
                    .normalize_or_zero();
                f.iter().any(|&k| n[k].dot(face) < 1.0 - 1e-6)
            })
        });
        let mut obj = format!("o primitive {}\n", primitive.index());
        for p in &placed {
            let _ = writeln!(obj, "v {} {} {}", p.x, p.y, p.z);
        }
        if let (true, Some(n)) = (smooth, &placed_normals) {
            for n in n {
                let _ = writeln!(obj, "vn {} {} {}", n.x, n.y, n.z);
            }
        }
        if let Some(uv) = &uvs {
            // glTF's (0, 0) is the image's top-left corner, lumiere's its bottom-left.
            for t in uv {
                let _ = writeln!(obj, "vt {} {}", t.x, 1.0 - t.y);
            }
        }
        for face in &faces {
            obj.push('f');
            for &k in face {
                let k = k + 1;
                let _ = match (uvs.is_some(), smooth) {
                    (true, true) => write!(obj, " {k}/{k}/{k}"),
                    (true, false) => write!(obj, " {k}/{k}"),
                    (false, true) => write!(obj, " {k}//{k}"),
                    (false, false) => write!(obj, " {k}"),
                };
            }
            obj.push('\n');
        }
        let material = self.material(&material, uvs.is_some())?;
        let file = format!(
            "{}#{object_name}/primitive {}",
            self.name,
            primitive.index()
        );
        self.files.insert(file.clone(), obj.into_bytes());
        let mut object = Table::new();
        object.insert("shape".into(), "obj".into());
        object.insert("name".into(), Value::String(object_name.to_string()));
        object.insert("file".into(), Value::String(file));
        object.insert("material".into(), Value::String(material));
        object.insert("smooth".into(), Value::Boolean(smooth));
        self.objects.push(Value::Table(object));
        Ok(())
    }

    /// The scene table's name of a glTF material, added at its first use; `uv`:
    /// the primitive has texture coordinates for its base colour texture.
    fn material(
        &mut self,
        material: &gltf::Material,
        uv: bool,
    ) -> std::result::Result<String, String> {
        if let Some(name) = self.materials.get(&material.index()) {
            return Ok(name.clone());
        }
        let name = match (material.index(), material.name()) {
            (None, _) => "default".to_string(),
            (Some(_), Some(name)) if !self.materials.values().any(|n| n == name) => {
                name.to_string()
            }
            (Some(k), _) => format!("material {k}"),
        };
        let said = format!("material `{name}`");
        let pbr = material.pbr_metallic_roughness();
        let [r, g, b, alpha] = pbr.base_color_factor();
        let mut table = Table::new();
        table.insert(
            "diffuse".into(),
            vector(DVec3::new(f64::from(r), f64::from(g), f64::from(b))),
        );
        if material.index().is_some()
            && (pbr.metallic_factor() != 0.0 || pbr.roughness_factor() != 1.0)
        {
            self.warn(format!(
                "{said}: metallic {} and roughness {} are left out (the base colour is read as a Lambertian reflectance)",
                pbr.metallic_factor(),
                pbr.roughness_factor()
            ));
        }
        if pbr.metallic_roughness_texture().is_some() {
            self.warn(format!(
                "{said}: its metallic-roughness texture is left out"
            ));
        }
        if material.normal_texture().is_some() {
            self.warn(format!(
                "{said}: its normal texture is left out (lumiere's bump maps are height fields, a normal map is not one)"
            ));
        }
        if material.occlusion_texture().is_some() {
            self.warn(format!("{said}: its occlusion texture is left out"));
        }
        if material.emissive_factor() != [0.0; 3] || material.emissive_texture().is_some() {
            self.warn(format!(
                "{said}: its emission is left out (lumiere's emitters are its lights)"
            ));
        }
        if alpha < 1.0 || material.alpha_mode() != gltf::material::AlphaMode::Opaque {
            self.warn(format!(
                "{said}: transparency is left out (the surface is opaque)"
            ));
        }
        if let Some(info) = pbr.base_color_texture() {
            if info.tex_coord() != 0 {
                self.warn(format!(
                    "{said}: its base colour texture reads TEXCOORD_{}: left out",
                    info.tex_coord()
                ));
            } else if uv {
                let texture = self.texture(&said, &info.texture())?;
                table.insert("diffuse_texture".into(), Value::String(texture));
            }
        }
        self.tables("materials")
            .insert(name.clone(), Value::Table(table));
        self.materials.insert(material.index(), name.clone());
        Ok(name)
    }

    /// The scene table's name of a texture's image, added at its first use.
    fn texture(
        &mut self,
        said: &str,
        texture: &gltf::Texture,
    ) -> std::result::Result<String, String> {
        let name = format!("gltf-texture-{}", texture.index());
        if self.tables("textures").contains_key(&name) {
            return Ok(name);
        }
        let image = texture.source();
        let bytes = match image.source() {
            gltf::image::Source::View { view, .. } => {
                let data = &self.buffers[view.buffer().index()];
                data[view.offset()..view.offset() + view.length()].to_vec()
            }
            gltf::image::Source::Uri { uri, .. } => uri_bytes(uri, self.external)
                .map_err(|e| format!("{said}: image {}: {e}", image.index()))?,
        };
        let file = format!("{}#image {}", self.name, image.index());
        self.files.insert(file.clone(), bytes);
        let sampler = texture.sampler();
        let (s, t) = (sampler.wrap_s(), sampler.wrap_t());
        let clamp = s == WrappingMode::ClampToEdge && t == WrappingMode::ClampToEdge;
        if !clamp && (s != WrappingMode::Repeat || t != WrappingMode::Repeat) {
            self.warn(format!(
                "{said}: its texture wraps {s:?} × {t:?}: read as repeating"
            ));
        }
        let mut table = Table::new();
        table.insert("image".into(), Value::String(file));
        table.insert("wrap".into(), if clamp { "clamp" } else { "repeat" }.into());
        self.tables("textures")
            .insert(name.clone(), Value::Table(table));
        Ok(name)
    }

    /// The scene table's sub-table `key`, made if absent.
    fn tables(&mut self, key: &str) -> &mut Table {
        self.table
            .entry(key)
            .or_insert_with(|| Value::Table(Table::new()))
            .as_table_mut()
            .expect("made as a table")
    }

    /// The camera (or one framing the scene), the lights and the objects, into
    /// the table.
    fn finish(&mut self) {
        let camera = match self.camera.take() {
            Some(camera) => camera,
            None => {
                self.warn(
                    "no perspective camera: the scene is framed from +z (set camera.eye, camera.look_at to move it)"
                        .into(),
                );
                framing(self.low, self.high)
            }
        };
        self.table.insert("camera".into(), Value::Table(camera));
        self.table.insert(
            "lights".into(),
            Value::Array(std::mem::take(&mut self.lights)),
        );
        self.table.insert(
            "objects".into(),
            Value::Array(std::mem::take(&mut self.objects)),
        );
    }
}

/// Width and height of an image whose longer side is `IMAGE_SIDE`.
fn image_size(aspect: f64) -> (i64, i64) {
    let aspect = if aspect.is_finite() && aspect > 0.0 {
        aspect
    } else {
        1.0
    };
    let side = |x: f64| (x.round() as i64).max(1);
    if aspect >= 1.0 {
        (IMAGE_SIDE as i64, side(IMAGE_SIDE / aspect))
    } else {
        (side(IMAGE_SIDE * aspect), IMAGE_SIDE as i64)
    }
}

/// A camera looking down -z at the box `low`..`high` from far enough to see it
/// whole under a 45° field of view.
pub(super) fn framing(low: DVec3, high: DVec3) -> Table {
    let (centre, radius) = if low.x <= high.x {
        ((low + high) / 2.0, ((high - low).length() / 2.0).max(1e-3))
    } else {
        (DVec3::ZERO, 1.0)
    };
    let fov: f64 = 45.0;
    let distance = radius / (fov.to_radians() / 2.0).sin();
    let mut table = Table::new();
    table.insert("eye".into(), vector(centre + DVec3::Z * distance));
    table.insert("look_at".into(), vector(centre));
    table.insert("fov_y".into(), Value::Float(fov));
    table.insert("width".into(), Value::Integer(IMAGE_SIDE as i64));
    table.insert("height".into(), Value::Integer(IMAGE_SIDE as i64));
    table
}

/// glTF's spot fall-off between the inner and the outer cone (its specification's
/// ((cos θ − cos outer) / (cos inner − cos outer))², clamped), as lumiere's table of
/// (degrees, factor).
fn spot_edge(inner: f64, outer: f64) -> Value {
    let scale = 1.0 / (inner.cos() - outer.cos()).max(1e-3);
    let factor = |theta: f64| {
        ((theta.cos() - outer.cos()) * scale)
            .clamp(0.0, 1.0)
            .powi(2)
    };
    let mut table = Vec::new();
    if inner > 0.0 {
        table.push(Value::Array(vec![Value::Float(0.0), Value::Float(1.0)]));
    }
    for k in 0..=EDGE_STEPS {
        let theta = inner + (outer - inner) * k as f64 / EDGE_STEPS as f64;
        table.push(Value::Array(vec![
            Value::Float(theta.to_degrees().min(90.0)),
            Value::Float(factor(theta)),
        ]));
    }
    Value::Array(table)
}

fn vector(v: DVec3) -> Value {
    Value::Array(v.to_array().map(Value::Float).to_vec())
}
