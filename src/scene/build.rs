//! From a parsed scene table to a `Scene`: shapes generated, OBJ files loaded,
//! transforms applied, materials resolved, emitters turned into polygon lights.

use super::file::{LightFile, MAX_MEMORY_BUDGET_MB, ObjectFile, SceneFile, ShapeKind, TextureFile};
use super::light_settings;
use super::radiosity_settings;
use super::resources::Resources;
use super::shapes::{self, Faces};
use super::tables::named;
use super::{
    Light, Material, Object, ObjectFrame, Polygon, PolygonLight, RenderSettings, Scene,
    environments, materials, obj, textures, transform, validate,
};
use crate::error::ensure_valid;
use crate::error::{Error, Result};
use crate::geometry::polygon::{area, centroid, newell_normal, non_planarity};
use crate::texture::Texture;
use crate::texture::mapping::Mapping;
use glam::{DMat4, DVec3};
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// Default segment count of spheres and cylinders.
const DEFAULT_RESOLUTION: u32 = 32;
/// The most segments a sphere or cylinder may have (a sphere of 1024 has half a
/// million faces).
const MAX_RESOLUTION: u32 = 1024;

pub fn scene_from_table(table: toml::Table, resources: &dyn Resources) -> Result<Scene> {
    let file: SceneFile =
        serde_path_to_error::deserialize(toml::Value::Table(table)).map_err(|e| {
            let key = e.path().to_string();
            let message = plain_serde_message(&e.inner().to_string());
            if key == "." {
                let table = message
                    .strip_prefix("missing field `")
                    .and_then(|rest| rest.strip_suffix('`'))
                    .map(|name| format!("missing the `[{name}]` table"));
                Error::invalid(
                    "the scene",
                    format!("the scene: {}", table.unwrap_or(message)),
                )
            } else {
                Error::invalid(&key, format!("{key}: {message}"))
            }
        })?;
    let camera = validate::camera(&file.camera)?;
    let render = RenderSettings {
        shading: file.render.shading,
        exposure: file.render.exposure as f32,
        supersample: file.render.supersample,
        sample_pattern: file.render.sample_pattern,
        background: validate::colour("render.background", file.render.background)?,
        band_rows: file.render.band_rows,
        backdrop: None,
        environments: file.render.environments,
    };
    ensure_valid!(
        file.render.exposure.is_finite() && file.render.exposure > 0.0,
        "render.exposure",
        "render.exposure must be a positive number"
    );
    validate::image_size(camera.width, camera.height, render.supersample)?;
    let shadows = super::shadow_settings::from_file(&file.shadows)?;

    let radiosity = file
        .radiosity
        .as_ref()
        .map(radiosity_settings::from_file)
        .transpose()?;

    let global = file
        .global
        .as_ref()
        .map(super::global_settings::from_file)
        .transpose()?;
    if let Some(g) = &global {
        ensure_valid!(
            !g.method.antialiases_itself() || render.supersample == 1,
            "render.supersample",
            "render.supersample: ray tracing antialiases by Whitted's adaptive subdivision (global.subdivisions); leave supersample at 1, got {}",
            render.supersample
        );
    }
    ensure_valid!(
        (1..=MAX_MEMORY_BUDGET_MB).contains(&file.render.max_memory_mb),
        "render.max_memory_mb",
        "render.max_memory_mb must be from 1 to {MAX_MEMORY_BUDGET_MB} (1 TiB), got {}",
        file.render.max_memory_mb
    );
    let mut builder = Builder {
        eye: camera.eye,
        geometry_budget: file.render.max_memory_mb << 20,
        texture_budget: textures::TextureBudget {
            limit: file.render.max_memory_mb << 20,
            ..Default::default()
        },
        ..Default::default()
    };
    let mut prepared = Vec::new();
    for (name, t) in &file.textures {
        prepared.push(textures::prepare(
            name,
            t,
            resources,
            &mut builder.texture_budget,
        )?);
    }
    for (texture, name) in prepared.into_iter().zip(file.textures.keys()) {
        builder
            .texture_index
            .insert(name.clone(), builder.textures.len());
        builder.textures.push(Arc::new(texture.load()?));
    }
    let mut environments = Vec::new();
    let mut hidden = Vec::new();
    let mut environment_index = HashMap::new();
    for (name, e) in &file.environments {
        let (environment, hide) = environments::load(name, e, resources)?;
        environment_index.insert(name.clone(), environments.len());
        environments.push(environment);
        hidden.push(hide);
    }
    let backdrop = file
        .render
        .backdrop
        .as_ref()
        .map(|name| named(&environment_index, name, "render.backdrop", "environment"))
        .transpose()?;
    let render = RenderSettings { backdrop, ..render };
    for (name, m) in &file.materials {
        let material = materials::from_file(
            name,
            m,
            &builder.texture_index,
            &environment_index,
            global.is_some(),
        )?;
        ensure_valid!(
            material.gloss.is_none() || global.as_ref().is_some_and(|g| g.method.reads_gloss()),
            format!("materials.{name}.gloss"),
            "materials.{name}.gloss: a glossy mirror is gathered through the two-pass methods' reflection frustum; set [global] method = \"two-pass\" (ray tracing and environment maps follow ideal mirrors and would ignore it)"
        );
        builder.add_material(material);
    }
    for (index, object) in file.objects.iter().enumerate() {
        builder
            .add_object(index, object, resources)
            .map_err(|e| e.within(format!("objects[{index}]")))?;
    }
    for ((environment, hide), name) in environments
        .iter_mut()
        .zip(&hidden)
        .zip(file.environments.keys())
    {
        if let super::EnvironmentSource::Capture(capture) = &mut environment.source {
            for object in hide {
                let named = super::objects_named(&builder.objects, object);
                if named.is_empty() {
                    let mut known: Vec<&str> =
                        builder.objects.iter().map(|o| o.name.as_str()).collect();
                    known.sort();
                    known.dedup();
                    let key = format!("environments.{name}.hide");
                    return Err(Error::invalid(
                        &key,
                        format!(
                            "{key}: no object is named `{object}` (named: {})",
                            known.join(", ")
                        ),
                    ));
                }
                capture.hide.extend(named);
            }
        }
    }
    let mut lights = Vec::new();
    for (index, light) in file.lights.iter().enumerate() {
        if let Some(light) = builder.add_light(index, light).map_err(|e| {
            e.within(match light.name() {
                Some(name) => format!("lights[{index}] (`{name}`)"),
                None => format!("lights[{index}]"),
            })
        })? {
            // A light that gives nothing makes a black image without saying why.
            let (key, amount) = match &light {
                Light::Point(l) => ("intensity", l.intensity),
                Light::Distant(l) => ("irradiance", l.irradiance),
                Light::Sphere(l) => ("radiance", l.radiance),
                Light::Spot(l) => ("intensity", l.intensity),
                Light::Polygon(l) => ("radiance", l.radiance),
            };
            if amount == glam::Vec3::ZERO {
                builder.warnings.push(format!(
                    "lights[{index}]: {key} is zero: the light adds nothing to the image"
                ));
            }
            lights.push(light);
        }
    }
    lights.extend(builder.polygon_lights());
    builder.warn_untextured_modes(render.shading);
    // A black image with no word of why helps nobody.
    if builder.polygons.is_empty() {
        builder
            .warnings
            .push("the scene has no objects: the image shows the background only".into());
    } else if lights.is_empty() && radiosity.is_none() && environments.is_empty() {
        builder
            .warnings
            .push("the scene has no lights and nothing emits: the image is black".into());
    }

    let medium = file
        .medium
        .as_ref()
        .map(super::medium_settings::from_file)
        .transpose()?;
    Ok(Scene {
        camera,
        render,
        shadows,
        radiosity,
        medium,
        global,
        materials: builder.materials,
        objects: builder.objects,
        polygons: builder.polygons,
        lights,
        textures: builder.textures,
        environments,
        warnings: builder.warnings,
    })
}

#[derive(Default)]
struct Builder {
    /// The camera's eye (the reflected-ray texture projector depends on it).
    eye: DVec3,
    textures: Vec<Arc<Texture>>,
    texture_index: HashMap<String, usize>,
    materials: Vec<Material>,
    material_index: HashMap<String, usize>,
    objects: Vec<Object>,
    polygons: Vec<Polygon>,
    /// The vertices of `polygons`, counted.
    vertices: u64,
    /// Bytes the geometry may take (`render.max_memory_mb`, less the textures').
    geometry_budget: u64,
    /// What the textures take of the same budget.
    texture_budget: textures::TextureBudget,
    warnings: Vec<String>,
}

/// Memory a polygon costs over a render, estimated: the scene's polygon and its
/// vertices, its share of the bounding volume hierarchy, its projected copy in each
/// band and a shadow method's working set. Measured: a sphere of resolution 1024
/// (524,288 quadrilaterals) peaks at 550 MB unshadowed and 770 MB with ray-cast
/// shadows, about 1.5 kB a quadrilateral.
const BYTES_PER_POLYGON: u64 = 1024;
const BYTES_PER_VERTEX: u64 = 128;

impl Builder {
    fn add_material(&mut self, m: Material) -> usize {
        let index = self.materials.len();
        self.material_index.insert(m.name.clone(), index);
        self.materials.push(m);
        index
    }

    fn material(&self, name: &str) -> Result<usize> {
        self.material_index.get(name).copied().ok_or_else(|| {
            let mut known: Vec<&str> = self.material_index.keys().map(String::as_str).collect();
            known.sort();
            Error::invalid(
                "material",
                format!("unknown material `{name}` (known: {})", known.join(", ")),
            )
        })
    }

    fn add_object(&mut self, index: usize, o: &ObjectFile, res: &dyn Resources) -> Result<()> {
        check_keys(o)?;
        let name = o.name.clone().unwrap_or_else(|| format!("object {index}"));
        let m = transform::matrix(&o.transform)?;
        let resolution = o.resolution.unwrap_or(DEFAULT_RESOLUTION);
        let smooth = o.smooth.unwrap_or(true);
        let faces: Faces = match o.shape {
            ShapeKind::Obj => return self.add_obj(&name, o, &m, res),
            ShapeKind::Polygon => {
                let vertices = o.vertices.as_deref().unwrap_or_default();
                let corners = vertices
                    .iter()
                    .map(|&v| validate::position("vertices", v))
                    .collect::<Result<Vec<_>>>()?;
                check_polygon(&corners)?;
                shapes::polygon(&corners)
            }
            ShapeKind::Quad => shapes::quad(),
            ShapeKind::Box => shapes::cube(),
            ShapeKind::Sphere => {
                ensure_valid!(
                    (4..=MAX_RESOLUTION).contains(&resolution),
                    "resolution",
                    "resolution must be from 4 to {MAX_RESOLUTION} for a sphere, got {resolution}"
                );
                shapes::sphere(resolution, smooth)
            }
            ShapeKind::Cylinder => {
                ensure_valid!(
                    (3..=MAX_RESOLUTION).contains(&resolution),
                    "resolution",
                    "resolution must be from 3 to {MAX_RESOLUTION} for a cylinder, got {resolution}"
                );
                shapes::cylinder(resolution, o.caps.unwrap_or(true), smooth)
            }
        };
        let (key, value) = match o.shape {
            ShapeKind::Sphere | ShapeKind::Cylinder => ("resolution", resolution.to_string()),
            ShapeKind::Obj | ShapeKind::Polygon | ShapeKind::Quad | ShapeKind::Box => {
                ("shape", format!("{:?}", o.shape).to_lowercase())
            }
        };
        self.check_geometry(&faces, key, &value)?;
        check_extent(&m, &faces)?;
        let material_name = o.material.as_deref().ok_or_else(|| {
            Error::invalid(
                "material",
                format!("{name}: a {:?} needs a `material`", o.shape),
            )
        })?;
        let material = self.material(material_name)?;
        let own_mapping = match o.shape {
            ShapeKind::Sphere => Some(shapes::sphere_mapping()),
            ShapeKind::Cylinder => Some(shapes::cylinder_mapping()),
            ShapeKind::Obj | ShapeKind::Polygon | ShapeKind::Quad | ShapeKind::Box => None,
        };
        let frame = object_frame(&m, &faces, own_mapping);
        let object = self.push_object(name, o, frame);
        for face in faces {
            self.place_face(face, material, object);
        }
        Ok(())
    }

    /// A face in modelling coordinates: texture coordinates from its material's
    /// mapping if it has one, then into the world.
    fn place_face(&mut self, mut face: Vec<super::Vertex>, material: usize, object: usize) {
        let frame = &self.objects[object].frame;
        if let Some(mapping) = &self.materials[material].mapping {
            let eye = frame.to_object.transform_point3(self.eye);
            textures::map_vertices(mapping, &mut face, frame, eye);
        }
        transform::apply(&frame.to_world, &mut face);
        self.push_polygon(face, material, object);
    }

    /// An MTL file's `map_Kd` image (relative to the OBJ file, as the MTL is),
    /// loaded once per file with the default wrap and filter.
    fn add_mtl_texture(&mut self, obj: &str, map: &str, res: &dyn Resources) -> Result<usize> {
        let file = Path::new(obj).parent().unwrap_or(Path::new("")).join(map);
        let name = file.to_string_lossy().into_owned();
        if let Some(&index) = self.texture_index.get(&name) {
            return Ok(index);
        }
        let t = TextureFile {
            image: Some(name.clone()),
            procedural: None,
            cells: None,
            colors: None,
            line: None,
            seed: None,
            resolution: None,
            wrap: Default::default(),
            filter: Default::default(),
        };
        self.texture_budget.geometry = self.geometry_bytes(0, 0);
        let texture = textures::prepare(&name, &t, res, &mut self.texture_budget)
            .and_then(textures::Prepared::load)
            .map_err(|e| e.within(format!("{obj}: its MTL file's map_Kd")))?;
        self.texture_index.insert(name, self.textures.len());
        self.textures.push(Arc::new(texture));
        Ok(self.textures.len() - 1)
    }

    fn add_obj(
        &mut self,
        name: &str,
        o: &ObjectFile,
        m: &glam::DMat4,
        res: &dyn Resources,
    ) -> Result<()> {
        let path = o.file.as_deref().unwrap_or_default();
        let model = obj::load(res, Path::new(path), o.smooth.unwrap_or(true))?;
        self.check_geometry(&model.faces, "file", path)?;
        check_extent(m, &model.faces)?;
        self.warnings.extend(model.warnings);
        let forced = o
            .material
            .as_deref()
            .map(|n| self.material(n))
            .transpose()?;
        for mtl in &model.materials {
            if !self.material_index.contains_key(&mtl.name) {
                let mut material = materials::from_mtl(mtl)?;
                if let Some(map) = &mtl.diffuse_texture {
                    material.diffuse_texture = Some(self.add_mtl_texture(path, map, res)?);
                }
                self.add_material(material);
            }
        }
        let frame = object_frame(m, &model.faces, None);
        let mut objects: HashMap<String, usize> = HashMap::new();
        for ((face, material), part) in model
            .faces
            .into_iter()
            .zip(model.face_materials)
            .zip(model.face_objects)
        {
            let material = match (forced, material) {
                (Some(m), _) => m,
                (None, Some(n)) => self.material(&n)?,
                (None, None) => {
                    return Err(Error::Model {
                        path: path.into(),
                        message: format!(
                            "object {part} has no material (usemtl) and the scene gives none"
                        ),
                    });
                }
            };
            let object = match objects.get(&part) {
                Some(&k) => k,
                None => {
                    let k = self.push_object(format!("{name}/{part}"), o, frame.clone());
                    objects.insert(part, k);
                    k
                }
            };
            self.place_face(face, material, object);
        }
        Ok(())
    }

    /// Refuses an object whose `faces`, with the polygons already in the scene,
    /// would take more than the geometry budget (`key = value` names the setting
    /// that made them).
    fn check_geometry(&self, faces: &Faces, key: &str, value: &str) -> Result<()> {
        let polygons = (self.polygons.len() + faces.len()) as u64;
        let vertices = faces.iter().map(|f| f.len() as u64).sum::<u64>();
        let needed = self
            .geometry_bytes(faces.len() as u64, vertices)
            .saturating_add(self.texture_budget.used);
        if needed <= self.geometry_budget {
            return Ok(());
        }
        Err(Error::OverBudget(Box::new(crate::error::OverBudget {
            key: key.into(),
            value: value.into(),
            what: format!(
                "the scene's {polygons} polygons with this object's {}",
                faces.len()
            ),
            needed,
            budget: self.geometry_budget,
            budget_key: "render.max_memory_mb".into(),
            suggestion: "use lower resolutions or fewer objects, or raise render.max_memory_mb"
                .into(),
        })))
    }

    /// The bytes the polygons so far take with `polygons` more (of `vertices`).
    fn geometry_bytes(&self, polygons: u64, vertices: u64) -> u64 {
        (self.polygons.len() as u64 + polygons)
            .saturating_mul(BYTES_PER_POLYGON)
            .saturating_add((self.vertices + vertices).saturating_mul(BYTES_PER_VERTEX))
    }

    fn push_object(&mut self, name: String, o: &ObjectFile, frame: ObjectFrame) -> usize {
        self.objects.push(Object {
            name,
            shading: o.shading,
            sphere: o.shape == ShapeKind::Sphere,
            frame,
        });
        self.objects.len() - 1
    }

    fn push_polygon(&mut self, vertices: Vec<super::Vertex>, material: usize, object: usize) {
        let positions: Vec<DVec3> = vertices.iter().map(|v| v.position).collect();
        let normal = newell_normal(&positions).normalize_or_zero();
        if normal == DVec3::ZERO {
            self.warnings.push(format!(
                "{}: a polygon of zero area was dropped",
                self.objects[object].name
            ));
            return;
        }
        self.vertices += vertices.len() as u64;
        self.polygons.push(Polygon {
            vertices,
            normal,
            material,
            object,
        });
    }

    /// A point, distant, sphere or spot light is returned; a polygon light becomes
    /// an emissive polygon (and so a light, through `polygon_lights`).
    /// The light a `[[lights]]` entry makes; a polygon light is a polygon of the
    /// scene, added here, and becomes a light with the others (`polygon_lights`).
    fn add_light(&mut self, index: usize, light: &LightFile) -> Result<Option<Light>> {
        match light {
            LightFile::Polygon {
                name,
                vertices,
                radiance,
            } => {
                self.add_polygon_light(index, name, vertices, *radiance)?;
                Ok(None)
            }
            other @ (LightFile::Point { .. }
            | LightFile::Distant { .. }
            | LightFile::Sphere { .. }
            | LightFile::Spot { .. }) => light_settings::light(other, self.eye).map(Some),
        }
    }

    fn add_polygon_light(
        &mut self,
        index: usize,
        name: &Option<String>,
        vertices: &[[f64; 3]],
        radiance: [f64; 3],
    ) -> Result<()> {
        let corners = vertices
            .iter()
            .map(|&v| validate::vec3("vertices", v))
            .collect::<Result<Vec<_>>>()?;
        check_polygon(&corners)?;
        let name = name.clone().unwrap_or_else(|| format!("lights[{index}]"));
        let material = self.add_material(Material {
            name: format!("polygon light {index}"),
            exponent: 1.0,
            emission: validate::colour("radiance", radiance)?,
            ..Default::default()
        });
        self.objects.push(Object {
            name,
            shading: None,
            frame: ObjectFrame::identity(),
            sphere: false,
        });
        let object = self.objects.len() - 1;
        for face in shapes::polygon(&corners) {
            self.push_polygon(face, material, object);
        }
        Ok(())
    }

    /// Textures and bump maps are applied per sample, in Phong shading only.
    /// One pass over the polygons marks the textured objects (a search per object
    /// made this quadratic: 28 s for an OBJ of 100,000 triangles).
    fn warn_untextured_modes(&mut self, default: super::ShadingMode) {
        let mut textured = vec![false; self.objects.len()];
        for p in &self.polygons {
            if self.materials[p.material].is_textured() {
                textured[p.object] = true;
            }
        }
        for (object, textured) in self.objects.iter().zip(textured) {
            let mode = object.shading.unwrap_or(default);
            if textured && mode != super::ShadingMode::Phong {
                self.warnings.push(format!(
                    "{}: textures and bump maps apply in phong shading only; {mode:?} shading shows the untextured material",
                    object.name
                ));
            }
        }
    }

    /// Every emissive polygon is a one-sided Lambertian polygon light, named after
    /// its object.
    fn polygon_lights(&self) -> Vec<Light> {
        self.polygons
            .iter()
            .enumerate()
            .filter(|(_, p)| self.materials[p.material].is_emitter())
            .map(|(index, p)| {
                Light::Polygon(PolygonLight::new(
                    p.positions().collect(),
                    p.normal,
                    self.materials[p.material].emission,
                    index,
                    Some(self.objects[p.object].name.clone()),
                ))
            })
            .collect()
    }
}

/// The frame of an object whose faces (in modelling coordinates) `m` takes into the
/// world.
fn object_frame(m: &DMat4, faces: &Faces, own_mapping: Option<Mapping>) -> ObjectFrame {
    let points: Vec<DVec3> = faces.iter().flatten().map(|v| v.position).collect();
    ObjectFrame {
        to_world: *m,
        to_object: m.inverse(),
        centroid: if points.is_empty() {
            DVec3::ZERO
        } else {
            centroid(&points)
        },
        own_mapping,
    }
}

fn check_polygon(corners: &[DVec3]) -> Result<()> {
    ensure_valid!(
        corners.len() >= 3,
        "vertices",
        "a polygon needs at least 3 vertices"
    );
    ensure_valid!(area(corners) > 0.0, "vertices", "the polygon has zero area");
    ensure_valid!(
        non_planarity(corners) < 1e-6,
        "vertices",
        "the polygon is not planar (a vertex lies {:.2e} of its size off its plane)",
        non_planarity(corners)
    );
    Ok(())
}

/// The object placed by `m` stays within the coordinates a scene holds: a scale
/// of 1e308 would make every polygon's area infinite, reported as empty.
fn check_extent(m: &glam::DMat4, faces: &Faces) -> Result<()> {
    let reach = faces
        .iter()
        .flatten()
        .map(|v| m.transform_point3(v.position).abs().max_element())
        .fold(
            0.0f64,
            |a, b| if b.is_nan() { f64::INFINITY } else { a.max(b) },
        );
    ensure_valid!(
        reach <= validate::MAX_COORDINATE,
        "transform",
        "transform: the object reaches {reach:e}, beyond ±{:e}, the largest coordinate a scene holds (a scale or translation too large)",
        validate::MAX_COORDINATE
    );
    Ok(())
}

/// Keys that do not apply to the object's shape are errors, like unknown keys.
fn check_keys(o: &ObjectFile) -> Result<()> {
    use ShapeKind::*;
    let given = [
        ("file", o.file.is_some(), &[Obj][..]),
        ("vertices", o.vertices.is_some(), &[Polygon][..]),
        (
            "resolution",
            o.resolution.is_some(),
            &[Sphere, Cylinder][..],
        ),
        ("caps", o.caps.is_some(), &[Cylinder][..]),
        ("smooth", o.smooth.is_some(), &[Obj, Sphere, Cylinder][..]),
    ];
    for (key, present, shapes) in given {
        if present && !shapes.contains(&o.shape) {
            return Err(Error::invalid(
                key,
                format!("key `{key}` does not apply to shape {:?}", o.shape),
            ));
        }
        if !present && key == "file" && o.shape == Obj {
            return Err(Error::invalid(key, "shape obj needs a `file`"));
        }
        if !present && key == "vertices" && o.shape == Polygon {
            return Err(Error::invalid(key, "shape polygon needs `vertices`"));
        }
    }
    Ok(())
}

/// A deserialiser's message in the scene file's words: its first line (the key is
/// named already), Rust's type names spelled out.
fn plain_serde_message(message: &str) -> String {
    let first = message.lines().next().unwrap_or_default().trim();
    [
        (
            "expected u32",
            "expected a whole number from 0 to 4294967295",
        ),
        ("expected u64", "expected a whole number of at least 0"),
        ("expected usize", "expected a whole number of at least 0"),
        ("expected f64", "expected a number"),
        ("expected a boolean", "expected true or false"),
        // What an enumeration's deserialiser says of a number or a boolean.
        (
            "invalid type: unit variant, expected string only",
            "expected one of its names, in quotes",
        ),
    ]
    .iter()
    .fold(first.to_string(), |m, (from, to)| m.replace(from, to))
}
