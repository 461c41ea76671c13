//! `lumiere envmap`: environment maps captured from a scene by lumiere's own renderer
//! (the course's acquisition from photographs, with renders as the photographs), or
//! converted between layouts.

use anyhow::{Context, Result, bail};
use lumiere::Scene;
use lumiere::environment_maps::{self, Layout};
use lumiere::{ImageFormat, load_scene, read_image, write_image};
use std::path::PathBuf;
use std::time::Instant;

/// Make an environment map: the six cube faces of a scene rendered from a point
/// (`lumiere envmap cornell-box --at 0,1,0 --cube -o room.png`), or an existing map
/// converted to another layout (`lumiere envmap --from room.png --layout cube
/// --sphere -o ball.png`).
///
/// Layouts: `cube` is written as a horizontal cross (4:3; middle row −x, −z, +x, +z,
/// +y above −z, −y below); `sphere` as a mirror ball seen from +z; `lat-long` as the
/// course's latitude-longitude map (2:1, zenith at the top, −z at the centre). PNG is
/// sRGB; PFM and EXR are linear.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A catalogue id or a .toml scene file to capture (not with --from).
    scene: Option<String>,
    /// The world centre the faces are rendered from, X,Y,Z.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    at: Option<String>,
    /// An object (by name) left out of the capture: the reflector. Repeatable.
    #[arg(long, value_name = "NAME")]
    hide: Vec<String>,
    /// An environment map image to convert instead of capturing.
    #[arg(long, value_name = "MAP", conflicts_with_all = ["scene", "at", "hide", "sets"])]
    from: Option<PathBuf>,
    /// How the --from image is laid out.
    #[arg(long, value_enum, requires = "from")]
    layout: Option<Layout>,
    /// Write a cube map (as a horizontal cross).
    #[arg(long, group = "to")]
    cube: bool,
    /// Write a sphere map.
    #[arg(long, group = "to")]
    sphere: bool,
    /// Write a latitude-longitude map.
    #[arg(long, group = "to")]
    lat_long: bool,
    /// Texels per cube face side, sphere-map side or latitude-longitude height
    /// (default 256; a conversion keeps the input's size).
    #[arg(long)]
    size: Option<u32>,
    /// Output image: .png (sRGB), .pfm or .exr (linear radiance).
    #[arg(short, long)]
    output: PathBuf,
    /// Override any scene key (see `lumiere render --help`). Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
}

/// The largest side accepted for a written map.
const MAX_SIZE: u32 = 4096;

pub fn run(args: Args) -> Result<()> {
    ImageFormat::of(&args.output)?;
    let to = match (args.cube, args.sphere, args.lat_long) {
        (true, _, _) => Layout::Cube,
        (_, true, _) => Layout::Sphere,
        (_, _, true) => Layout::LatLong,
        _ => bail!("say which layout to write: --cube, --sphere or --lat-long"),
    };
    if let Some(size) = args.size
        && !(1..=MAX_SIZE).contains(&size)
    {
        bail!("--size must be between 1 and {MAX_SIZE}, got {size}");
    }
    let started = Instant::now();
    let (image, exposure) = match (&args.from, &args.scene) {
        (Some(from), _) => {
            let Some(layout) = args.layout else {
                bail!("--from needs --layout: how {} is laid out", from.display());
            };
            let image = read_image(from)?;
            lumiere::refuse_non_radiance(&image).with_context(|| from.display().to_string())?;
            let map = environment_maps::convert(image, layout, to, args.size)
                .with_context(|| from.display().to_string())?;
            (map, 1.0)
        }
        (None, Some(scene)) => {
            let Some(at) = &args.at else {
                bail!("a capture needs --at X,Y,Z: the point the faces are rendered from");
            };
            let at = parse_point(at)?;
            let scene = load_scene(scene, &args.sets)?;
            let hidden = hidden_objects(&scene, &args.hide)?;
            let size = args.size.unwrap_or(256);
            let map = environment_maps::capture(&scene, at, size, &hidden, to)
                .context("rendering the cube faces")?;
            (map, scene.render.exposure)
        }
        (None, None) => bail!("give a scene to capture, or --from MAP to convert"),
    };
    write_image(&image, &args.output, exposure)?;
    outln!(
        "wrote {} ({} map, {}x{}) in {:.2} s",
        args.output.display(),
        to.name(),
        image.width,
        image.height,
        started.elapsed().as_secs_f64()
    )?;
    Ok(())
}

fn parse_point(text: &str) -> Result<glam::DVec3> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let numbers: Vec<f64> = parts.iter().filter_map(|p| p.parse().ok()).collect();
    if parts.len() != 3 || numbers.len() != 3 || numbers.iter().any(|x| !x.is_finite()) {
        bail!("--at {text}: expected three finite numbers X,Y,Z, e.g. --at 0,1.2,-0.5");
    }
    Ok(glam::DVec3::new(numbers[0], numbers[1], numbers[2]))
}

/// The indices of the named objects (every object of a name).
fn hidden_objects(scene: &Scene, names: &[String]) -> Result<Vec<usize>> {
    let mut hidden = Vec::new();
    for name in names {
        let found = scene.objects_named(name);
        if found.is_empty() {
            let mut known: Vec<&str> = scene.objects.iter().map(|o| o.name.as_str()).collect();
            known.sort();
            known.dedup();
            bail!(
                "--hide {name}: the scene has no object of that name (named: {})",
                known.join(", ")
            );
        }
        hidden.extend(found);
    }
    Ok(hidden)
}
