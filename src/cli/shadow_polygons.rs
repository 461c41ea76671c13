//! `lumiere shadow-polygons`: the lit and shadowed polygons of a scene, measured.

use anyhow::{Context, Result, bail};
use lumiere::shadow_polygons::{ReceiverShadows, receiver_shadows};
use lumiere::{ImageFormat, Light, Scene, load_scene, write_atomically};
use std::path::PathBuf;
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Transform};

/// List, per polygon, the parts the first point light reaches and the parts in its
/// shadow (Atherton, Weiler & Greenberg 1978), with their areas in scene units.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A catalogue id or the path of a .toml scene file.
    scene: String,
    /// Print every receiver's lit and shadowed polygons as JSON.
    #[arg(long)]
    json: bool,
    /// Draw the plan (top view) of the lit and shadowed polygons to a PNG.
    #[arg(long, value_name = "OUT.png")]
    png: Option<PathBuf>,
    /// Override any scene key (as for `render`).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
}

pub fn run(args: Args) -> Result<()> {
    if let Some(path) = &args.png
        && ImageFormat::of(path)? != ImageFormat::Png
    {
        bail!("{}: the plan is drawn as a .png", path.display());
    }
    let scene = load_scene(&args.scene, &args.sets)?;
    let light = first_point_light(&scene)?;
    let receivers = receiver_shadows(&scene, light);
    if let Some(path) = &args.png {
        write_atomically(path, &plan(&receivers)?)?;
    }
    if args.json {
        let report = serde_json::json!({ "light": light.to_array(), "receivers": receivers });
        outln!("{}", serde_json::to_string_pretty(&report)?)?;
    } else if args.png.is_none() {
        outln!(
            "{:>7}  {:<28} {:>14} {:>14} {:>14}",
            "polygon",
            "object",
            "area",
            "lit",
            "shadowed"
        )?;
        for r in &receivers {
            outln!(
                "{:>7}  {:<28} {:>14.4} {:>14.4} {:>14.4}",
                r.polygon,
                r.object,
                r.area,
                r.lit_area,
                r.shadowed_area
            )?;
        }
    }
    Ok(())
}

/// The plan of `scene`'s lit and shadowed polygons under its first point light, as
/// PNG bytes.
pub fn plan_of(scene: &Scene) -> Result<Vec<u8>> {
    plan(&receiver_shadows(scene, first_point_light(scene)?))
}

fn first_point_light(scene: &Scene) -> Result<glam::DVec3> {
    scene
        .lights
        .iter()
        .find_map(Light::position)
        .context("the scene has no point light to cast shadow polygons from")
}

/// The plan: the polygons facing up, seen from above (x to the right, z downwards),
/// lower ones first, lit parts light and shadowed parts dark.
fn plan(receivers: &[ReceiverShadows]) -> Result<Vec<u8>> {
    const SIZE: f32 = 800.0;
    let receivers: Vec<&ReceiverShadows> =
        receivers.iter().filter(|r| r.normal[1] > 0.05).collect();
    if receivers.is_empty() {
        bail!("no polygon faces up: the plan would be empty");
    }
    let points = receivers
        .iter()
        .flat_map(|r| r.lit.iter().chain(&r.shadowed))
        .flatten();
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    for p in points {
        lo = [lo[0].min(p[0]), lo[1].min(p[2])];
        hi = [hi[0].max(p[0]), hi[1].max(p[2])];
    }
    let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-12);
    let scale = 0.9 * SIZE as f64 / extent;
    let at = |p: &[f64; 3]| {
        (
            (0.05 * SIZE as f64 + (p[0] - lo[0]) * scale) as f32,
            (0.05 * SIZE as f64 + (p[2] - lo[1]) * scale) as f32,
        )
    };
    let mut pixmap = Pixmap::new(SIZE as u32, SIZE as u32).context("plan image")?;
    pixmap.fill(Color::from_rgba8(250, 250, 246, 255));
    let mut order = receivers;
    let height = |r: &ReceiverShadows| {
        r.lit
            .iter()
            .chain(&r.shadowed)
            .flatten()
            .map(|p| p[1])
            .fold(f64::MIN, f64::max)
    };
    order.sort_by(|a, b| height(a).total_cmp(&height(b)));
    for r in order {
        for (region, colour) in [(&r.shadowed, (70, 70, 90)), (&r.lit, (245, 215, 120))] {
            let mut builder = PathBuilder::new();
            for contour in region {
                let (x, y) = at(&contour[0]);
                builder.move_to(x, y);
                for p in &contour[1..] {
                    let (x, y) = at(p);
                    builder.line_to(x, y);
                }
                builder.close();
            }
            if let Some(path) = builder.finish() {
                let mut paint = Paint::default();
                paint.set_color_rgba8(colour.0, colour.1, colour.2, 255);
                pixmap.fill_path(
                    &path,
                    &paint,
                    FillRule::EvenOdd,
                    Transform::identity(),
                    None,
                );
            }
        }
    }
    pixmap.encode_png().context("encoding the plan")
}
