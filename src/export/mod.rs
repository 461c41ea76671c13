//! A lumiere scene as another renderer's scene, so that any catalogue entry can be
//! rendered by POV-Ray or Mitsuba 3 and compared with lumiere: the same camera,
//! geometry, materials, lights and units. glTF 2.0 and OBJ + MTL + a JSON sidecar
//! carry the same scene to any other renderer or viewer.
//!
//! What the other renderer cannot say the same way (textures, bump maps,
//! environment maps, media, lumiere's normalised Phong lobe) is left out, and each
//! thing left out is named in a warning: an exported scene is a peer for direct
//! and diffuse light, not a copy of every effect.

mod gltf;
mod mitsuba;
mod obj;
mod pov;

use crate::error::{Error, Result};
use crate::image_io::write_atomically;
use crate::scene::{Light, Scene, SpotDistribution};
use glam::{DVec3, Vec3};
use std::path::{Path, PathBuf};

/// The renderer a scene is written for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Format {
    /// POV-Ray 3.7 scene description language (`.pov`).
    Pov,
    /// Mitsuba 3 XML (`.xml`), its meshes as OBJ files in a folder beside it.
    Mitsuba,
    /// glTF 2.0 (`.gltf`, its buffer embedded), lights through KHR_lights_punctual.
    Gltf,
    /// Wavefront OBJ (`.obj`) with its `.mtl` and a `.json` sidecar (camera, lights,
    /// materials, units) beside it.
    Obj,
}

impl Format {
    /// The extension of the scene file written.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Pov => "pov",
            Format::Mitsuba => "xml",
            Format::Gltf => "gltf",
            Format::Obj => "obj",
        }
    }

    /// The renderer's name.
    pub fn renderer(self) -> &'static str {
        match self {
            Format::Pov => "POV-Ray",
            Format::Mitsuba => "Mitsuba",
            Format::Gltf => "glTF",
            Format::Obj => "Wavefront OBJ",
        }
    }
}

/// Mitsuba's integrator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum MitsubaIntegrator {
    /// Direct light only (emitter sampling).
    Direct,
    /// Every bounce (unbounded path tracing).
    Path,
}

/// How a scene is exported.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// The renderer written for.
    pub format: Format,
    /// Mitsuba: samples per pixel of its stratified sampler.
    pub spp: u32,
    /// Mitsuba: the integrator (`None`: `direct` for a scene lit by its lights,
    /// `path` for one lit by radiosity or a global method).
    pub integrator: Option<MitsubaIntegrator>,
    /// POV-Ray: lightlets along each side of an area light.
    pub area_samples: u32,
}

impl Options {
    /// The command line's defaults for `format`: 64 samples per pixel for Mitsuba,
    /// 8 × 8 lightlets per area light for POV-Ray.
    pub fn new(format: Format) -> Options {
        Options {
            format,
            spp: 64,
            integrator: None,
            area_samples: 8,
        }
    }
}

/// Refuses an `output` whose extension is not `format`'s (`.pov`, `.xml`, `.gltf`,
/// `.obj`): a caller
/// may ask before the scene is loaded.
pub fn check_output(format: Format, output: &Path) -> Result<()> {
    let extension = format.extension();
    if output.extension().is_none_or(|e| e != extension) {
        return Err(Error::Invalid {
            key: "output".into(),
            message: format!(
                "{}: a {} scene is written as .{extension}",
                output.display(),
                format.renderer()
            ),
        });
    }
    Ok(())
}

/// Writes `scene` at `output` (a `.pov`, `.xml`, `.gltf` or `.obj` file; Mitsuba's
/// meshes go into the folder `OUT-meshes/` beside it, OBJ's `.mtl` and `.json`
/// beside it), each file written whole or not at all. Returns what the export left
/// out, a line each (see `left_out`).
pub fn export(scene: &Scene, options: &Options, output: &Path) -> Result<Vec<String>> {
    check_output(options.format, output)?;
    let meshes = meshes(scene);
    match options.format {
        Format::Pov => {
            let text = pov::scene(scene, &meshes, options.area_samples);
            write_atomically(output, text.as_bytes())?;
        }
        Format::Mitsuba => {
            let integrator = options.integrator.unwrap_or(
                if scene.radiosity.is_some() || scene.global.is_some() {
                    MitsubaIntegrator::Path
                } else {
                    MitsubaIntegrator::Direct
                },
            );
            mitsuba::write(scene, &meshes, output, options.spp, integrator)?;
        }
        Format::Gltf => write_atomically(output, gltf::document(scene, &meshes).as_bytes())?,
        Format::Obj => obj::write(scene, &meshes, output)?,
    }
    Ok(left_out(scene, options.format))
}

/// The polygons of one material: what every format writes as one mesh.
struct Mesh {
    material: usize,
    /// Each polygon's vertices: position and shading normal.
    polygons: Vec<Vec<(DVec3, DVec3)>>,
    /// Whether every polygon is shaded with its face normal (no interpolation).
    faceted: bool,
}

/// The scene's polygons by material, in the order materials first appear.
fn meshes(scene: &Scene) -> Vec<Mesh> {
    let mut meshes: Vec<Mesh> = Vec::new();
    for p in &scene.polygons {
        let polygon: Vec<(DVec3, DVec3)> =
            p.vertices.iter().map(|v| (v.position, v.normal)).collect();
        let faceted = p
            .vertices
            .iter()
            .all(|v| (v.normal - p.normal).length() < 1e-9);
        match meshes.iter_mut().find(|m| m.material == p.material) {
            Some(m) => {
                m.polygons.push(polygon);
                m.faceted &= faceted;
            }
            None => meshes.push(Mesh {
                material: p.material,
                polygons: vec![polygon],
                faceted,
            }),
        }
    }
    meshes
}

/// What an export of `scene` for `format` cannot carry over, said once each.
pub fn left_out(scene: &Scene, format: Format) -> Vec<String> {
    let mut out = Vec::new();
    let mut say = |what: String| {
        if !out.contains(&what) {
            out.push(what);
        }
    };
    for m in &scene.materials {
        let used = scene
            .polygons
            .iter()
            .any(|p| scene.materials[p.material].name == m.name);
        if !used {
            continue;
        }
        if m.diffuse_texture.is_some() || m.specular_texture.is_some() || m.bump.is_some() {
            say(format!(
                "material `{}`: textures and bump maps are left out (its plain reflectance is kept)",
                m.name
            ));
        }
        if m.specular != Vec3::ZERO && format != Format::Obj {
            say(format!(
                "material `{}`: the Phong highlight is left out (diffuse only)",
                m.name
            ));
        }
        if format == Format::Obj {
            // The sidecar holds every coefficient; only the map is missing.
            if m.environment.is_some() {
                say(format!(
                    "material `{}`: its environment map is left out (the sidecar keeps mirror, ior and transmittance)",
                    m.name
                ));
            }
        } else if format == Format::Mitsuba && m.ior.is_some() {
            // A dielectric: Fresnel's split, as lumiere's glass.
            if m.environment.is_some() || m.translucence != Vec3::ZERO {
                say(format!(
                    "material `{}`: environment maps and translucence are left out (the glass is kept)",
                    m.name
                ));
            }
            if m.diffuse != Vec3::ZERO {
                say(format!(
                    "material `{}`: glass with a diffuse part: the diffuse part is left out",
                    m.name
                ));
            }
        } else if m.environment.is_some()
            || m.ior.is_some()
            || m.transmittance != Vec3::ZERO
            || m.translucence != Vec3::ZERO
        {
            say(format!(
                "material `{}`: environment maps, refraction and transmission are left out",
                m.name
            ));
        }
        if m.mirror != Vec3::ZERO && !(format == Format::Mitsuba && m.ior.is_some()) {
            match format {
                Format::Pov => say(format!(
                    "material `{}`: the mirror is left out of POV-Ray's direct light",
                    m.name
                )),
                Format::Mitsuba => say(format!(
                    "material `{}`: a one-sided conductor, without its diffuse part (black under the direct integrator)",
                    m.name
                )),
                Format::Gltf => say(format!(
                    "material `{}`: the mirror is left out (glTF's metallic-roughness holds no mirror beside a diffuse part)",
                    m.name
                )),
                Format::Obj => {}
            }
        }
    }
    if scene.render.background != Vec3::ZERO {
        match format {
            Format::Mitsuba => say(
                "the background colour is left out (Mitsuba's would be an emitter lighting the scene)"
                    .into(),
            ),
            Format::Gltf => say("the background colour is left out (glTF has none)".into()),
            Format::Pov | Format::Obj => {}
        }
    }
    for (index, light) in scene.lights.iter().enumerate() {
        match light {
            Light::Sphere(_) if format == Format::Mitsuba => say(format!(
                "{}: an emitting sphere, seen by the camera and casting shadows, which lumiere's is not",
                light.label(index)
            )),
            Light::Polygon(l) if format == Format::Pov && !parallelogram(&l.vertices) => {
                say(format!(
                    "{}: not a parallelogram: POV-Ray's area light spans the parallelogram of its first edges",
                    light.label(index)
                ))
            }
            Light::Polygon(_) | Light::Sphere(_) if format == Format::Gltf => say(format!(
                "{}: an emissive mesh (KHR_materials_emissive_strength), not a punctual light: a glTF viewer may not light the scene with it",
                light.label(index)
            )),
            Light::Point(_)
            | Light::Distant(_)
            | Light::Polygon(_)
            | Light::Sphere(_)
            | Light::Spot(_) => {}
        }
    }
    if scene.medium.is_some() {
        say("the participating medium is left out".into());
    }
    if scene.shadows.method == crate::settings::ShadowMethod::None
        && !scene.lights.is_empty()
        && scene.radiosity.is_none()
        && scene.global.is_none()
    {
        say("lumiere's scene casts no shadows (shadows.method = \"none\"); the exported lights cast them".into());
    }
    if scene.radiosity.is_some() || scene.global.is_some() {
        match format {
            Format::Pov => say(
                "POV-Ray's scene is lit directly only (no radiosity, no global method)".into(),
            ),
            Format::Gltf | Format::Obj => say(
                "the radiosity or global-illumination settings are left out (the files hold the scene, not how lumiere lights it)"
                    .into(),
            ),
            Format::Mitsuba => {}
        }
    }
    for (index, light) in scene.lights.iter().enumerate() {
        if let Light::Spot(s) = light
            && format != Format::Obj
            && !matches!(s.distribution, SpotDistribution::CosinePower(p) if p == 0.0)
        {
            say(format!(
                "{}: its intensity distribution becomes a uniform cone",
                light.label(index)
            ));
        }
    }
    out
}

/// A path beside `output` named after it: `out.xml` → `out-meshes`.
fn sibling(output: &Path, suffix: &str) -> PathBuf {
    let stem = output
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    output.with_file_name(format!("{stem}{suffix}"))
}

/// Whether a polygon is a parallelogram (four corners, opposite edges equal).
fn parallelogram(vertices: &[DVec3]) -> bool {
    vertices.len() == 4 && {
        let e = vertices[1] - vertices[0];
        let f = vertices[2] - vertices[3];
        (e - f).length() <= 1e-6 * e.length().max(f.length())
    }
}
