//! `lumiere export`: a scene as POV-Ray SDL, Mitsuba 3 XML, glTF 2.0 or OBJ + MTL +
//! JSON (the library's `export`), with what it leaves out printed as warnings.

use anyhow::Result;
use lumiere::export::{self, Format, MitsubaIntegrator, Options};
use lumiere::load_scene;
use std::path::PathBuf;

/// Write a scene (a catalogue id, a .toml or a glTF file) as POV-Ray SDL, Mitsuba 3
/// XML, glTF 2.0 or OBJ.
///
/// Mitsuba's meshes go into OUT-meshes/ beside the XML, one OBJ per material. glTF
/// is one .gltf file, its buffer embedded, lights through KHR_lights_punctual at
/// 683 lm/W. OBJ writes OUT.obj, OUT.mtl and OUT.json (camera, lights, materials
/// and units) side by side.
#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// A catalogue id or the path of a .toml, .gltf or .glb scene file.
    scene: String,
    #[arg(long, value_enum)]
    format: Format,
    /// The scene file written (.pov, .xml, .gltf or .obj).
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
    integrator: Option<MitsubaIntegrator>,
    /// POV-Ray: lightlets along each side of an area light.
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(2..=64))]
    area_samples: u32,
    /// Override any scene key (as for `render`). Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
}

pub fn run(args: Args) -> Result<()> {
    let options = Options {
        format: args.format,
        spp: args.spp,
        integrator: args.integrator,
        area_samples: args.area_samples,
    };
    // A wrong extension is refused before the scene is loaded.
    export::check_output(options.format, &args.output)?;
    let mut sets = args.sets.clone();
    sets.extend(args.size.sets());
    let scene = load_scene(&args.scene, &sets)?;
    for warning in export::export(&scene, &options, &args.output)? {
        eprintln!("warning: export: {warning}");
    }
    Ok(())
}
