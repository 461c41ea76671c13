//! `lumiere export`: a lumiere scene as another renderer's scene, so that any
//! catalogue entry can be rendered by POV-Ray or Mitsuba 3 and compared with
//! lumiere: the same camera, geometry, materials, lights and units.
//!
//! What the other renderer cannot say the same way (textures, bump maps,
//! environment maps, media, lumiere's normalised Phong lobe) is left out, and each
//! thing left out is named in a warning: an exported scene is a peer for direct
//! and diffuse light, not a copy of every effect.

mod mitsuba;
mod pov;

use anyhow::{Result, bail};
use glam::{DVec3, Vec3};
use lumiere::load_scene;
use lumiere::scene::Scene;
use std::path::{Path, PathBuf};

/// Write a scene (a catalogue id or a .toml file) as POV-Ray SDL or Mitsuba 3 XML.
///
/// Mitsuba's meshes go into OUT-meshes/ beside the XML, one OBJ per material.
#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// A catalogue id or the path of a .toml scene file.
    scene: String,
    #[arg(long, value_enum)]
    format: Format,
    /// The scene file written (.pov or .xml).
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    size: super::ImageSize,
    /// Mitsuba: samples per pixel of its stratified sampler.
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..=1 << 20))]
    spp: u32,
    /// Mitsuba: the integrator (default: `direct` for a scene lit by its lights,
    /// `path` for one lit by radiosity or a global method).
    #[arg(long, value_enum)]
    integrator: Option<Integrator>,
    /// POV-Ray: lightlets along each side of an area light.
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(2..=64))]
    area_samples: u32,
    /// Override any scene key (as for `render`). Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// POV-Ray 3.7 scene description language.
    Pov,
    /// Mitsuba 3 XML.
    Mitsuba,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Integrator {
    /// Direct light only (emitter sampling).
    Direct,
    /// Every bounce (unbounded path tracing).
    Path,
}

pub fn run(args: Args) -> Result<()> {
    let extension = match args.format {
        Format::Pov => "pov",
        Format::Mitsuba => "xml",
    };
    if args.output.extension().is_none_or(|e| e != extension) {
        bail!(
            "{}: a {} scene is written as .{extension}",
            args.output.display(),
            match args.format {
                Format::Pov => "POV-Ray",
                Format::Mitsuba => "Mitsuba",
            }
        );
    }
    let mut sets = args.sets.clone();
    sets.extend(args.size.sets());
    let scene = load_scene(&args.scene, &sets)?;
    for warning in left_out(&scene, args.format) {
        eprintln!("warning: export: {warning}");
    }
    let meshes = meshes(&scene);
    match args.format {
        Format::Pov => {
            let text = pov::scene(&scene, &meshes, args.area_samples);
            lumiere::image_io::write_atomically(&args.output, text.as_bytes())?;
        }
        Format::Mitsuba => {
            let integrator =
                args.integrator
                    .unwrap_or(if scene.radiosity.is_some() || scene.global.is_some() {
                        Integrator::Path
                    } else {
                        Integrator::Direct
                    });
            mitsuba::write(&scene, &meshes, &args.output, args.spp, integrator)?;
        }
    }
    Ok(())
}

/// The polygons of one material: what both formats write as one mesh.
pub struct Mesh {
    pub material: usize,
    /// Each polygon's vertices: position and shading normal.
    pub polygons: Vec<Vec<(DVec3, DVec3)>>,
    /// Whether every polygon is shaded with its face normal (no interpolation).
    pub faceted: bool,
}

/// The scene's polygons by material, in the order materials first appear.
pub fn meshes(scene: &Scene) -> Vec<Mesh> {
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

/// What the export cannot carry over, said once each.
fn left_out(scene: &Scene, format: Format) -> Vec<String> {
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
        if m.specular != Vec3::ZERO {
            say(format!(
                "material `{}`: the Phong highlight is left out (diffuse only)",
                m.name
            ));
        }
        if m.environment.is_some()
            || m.ior.is_some()
            || m.transmittance != Vec3::ZERO
            || m.translucence != Vec3::ZERO
        {
            say(format!(
                "material `{}`: environment maps, refraction and transmission are left out",
                m.name
            ));
        }
        if m.mirror != Vec3::ZERO {
            say(match format {
                Format::Pov => format!(
                    "material `{}`: the mirror is left out of POV-Ray's direct light",
                    m.name
                ),
                Format::Mitsuba => format!(
                    "material `{}`: a one-sided conductor, without its diffuse part (black under the direct integrator)",
                    m.name
                ),
            });
        }
    }
    if format == Format::Mitsuba && scene.render.background != Vec3::ZERO {
        say(
            "the background colour is left out (Mitsuba's would be an emitter lighting the scene)"
                .into(),
        );
    }
    for (index, light) in scene.lights.iter().enumerate() {
        match light {
            lumiere::scene::Light::Sphere(_) if format == Format::Mitsuba => say(format!(
                "{}: an emitting sphere, seen by the camera and casting shadows, which lumiere's is not",
                light.label(index)
            )),
            lumiere::scene::Light::Polygon(l)
                if format == Format::Pov && !parallelogram(&l.vertices) =>
            {
                say(format!(
                    "{}: not a parallelogram: POV-Ray's area light spans the parallelogram of its first edges",
                    light.label(index)
                ))
            }
            _ => {}
        }
    }
    if scene.medium.is_some() {
        say("the participating medium is left out".into());
    }
    if format == Format::Pov && (scene.radiosity.is_some() || scene.global.is_some()) {
        say("POV-Ray's scene is lit directly only (no radiosity, no global method)".into());
    }
    for (index, light) in scene.lights.iter().enumerate() {
        if let lumiere::scene::Light::Spot(s) = light
            && !matches!(s.distribution, lumiere::scene::SpotDistribution::CosinePower(p) if p == 0.0)
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
pub fn sibling(output: &Path, suffix: &str) -> PathBuf {
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
