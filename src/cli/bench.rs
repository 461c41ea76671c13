//! `lumiere bench`: how fast the renderer is, on this machine.

use super::timing::median;
use anyhow::Result;
use lumiere::settings::{Filter, ShadowMethod};
use lumiere::visible_surface_pass::VisibleSurfacePass;
use lumiere::{load_scene, render};

/// Time whole renders (median of several runs) per scene, variant (shadow method or
/// texture filter) and size, in milliseconds and million samples per second, and
/// the scan-line visible-surface pass's own rate.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Catalogue ids or scene files to time.
    #[arg(long, value_delimiter = ',', default_values_t = ["cornell-box".to_string()])]
    scenes: Vec<String>,
    /// Shadow methods to time (each overrides the scene's own).
    #[arg(long, value_enum, value_delimiter = ',')]
    shadows: Vec<ShadowMethod>,
    /// Texture filters to time (each overrides the filter of every texture of the
    /// scene).
    #[arg(long, value_enum, value_delimiter = ',')]
    filters: Vec<Filter>,
    /// Image sizes (square) to time.
    #[arg(long, value_delimiter = ',', default_values_t = [512u32, 1024])]
    sizes: Vec<u32>,
    /// Time radiosity solves of the first scene (a radiosity scene) at about these
    /// element counts instead of renders.
    #[arg(long, value_delimiter = ',')]
    radiosity_elements: Vec<usize>,
    /// Samples per pixel along each axis to time (N x N, box filtered).
    #[arg(long, value_delimiter = ',', default_values_t = [1u32])]
    supersample: Vec<u32>,
    /// Scene overrides applied to every render timed (KEY=VALUE, as `render --set`),
    /// e.g. `shadows.light_points=16`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
    /// Also time each scene with environment lookups off (`render.environments =
    /// false`): what reflection and refraction mapping add to the plain render.
    #[arg(long)]
    environments: bool,
    /// Runs per measurement; the median is reported.
    #[arg(long, default_value_t = 15, value_parser = super::at_least_one)]
    runs: usize,
}

pub fn run(args: Args) -> Result<()> {
    outln!("threads: {}", rayon::current_num_threads())?;
    if !args.radiosity_elements.is_empty() {
        let runs = args.runs.min(3);
        return super::bench_radiosity::run(&args.scenes[0], &args.radiosity_elements, runs);
    }
    outln!(
        "{:<26} {:<22} {:>10} {:>8} {:>12} {:>16} {:>16}",
        "scene",
        "variant",
        "size",
        "samples",
        "render (ms)",
        "render (Ms/s)",
        "sweep (Ms/s)"
    )?;
    for scene_name in &args.scenes {
        for (label, variant) in variants(&args, scene_name)? {
            for (&size, &samples) in args
                .sizes
                .iter()
                .flat_map(|s| args.supersample.iter().map(move |n| (s, n)))
            {
                let mut sets = vec![
                    format!("camera.width={size}"),
                    format!("camera.height={size}"),
                    format!("render.supersample={samples}"),
                ];
                sets.extend(variant.iter().cloned());
                sets.extend(args.sets.iter().cloned());
                let scene = load_scene(scene_name, &sets)?;
                // A method that refuses one of the scene's lights has nothing to time.
                if let Err(lumiere::Error::Unsupported(refusal)) = render(&scene) {
                    outln!("{scene_name:<26} {label:<22} refused: {refusal}")?;
                    break;
                }
                render(&scene)?;
                let full = median(args.runs, || {
                    let _ = std::hint::black_box(render(&scene));
                });
                let grid = (size as f64 * samples as f64).powi(2);
                let sweep = sweep_rate(&scene, args.runs);
                outln!(
                    "{:<26} {:<22} {:>10} {:>8} {:>12.2} {:>16.1} {:>16.1}",
                    scene_name,
                    label,
                    format!("{size}x{size}"),
                    format!("{samples}x{samples}"),
                    full.as_secs_f64() * 1e3,
                    grid / full.as_secs_f64() / 1e6,
                    sweep
                )?;
            }
        }
    }
    Ok(())
}

/// The variants to time, each a label and its `--set` overrides: the scene as it
/// is, or each shadow method, or each texture filter on all its textures.
fn variants(args: &Args, scene_name: &str) -> Result<Vec<(String, Vec<String>)>> {
    let name = |v: &dyn Fn() -> Option<clap::builder::PossibleValue>| {
        v().expect("no skipped variants").get_name().to_string()
    };
    let mut variants = Vec::new();
    for m in &args.shadows {
        let method = name(&|| clap::ValueEnum::to_possible_value(m));
        variants.push((method.clone(), vec![format!("shadows.method=\"{method}\"")]));
    }
    if !args.filters.is_empty() {
        let textures: Vec<String> = load_scene(scene_name, &[])?
            .textures
            .iter()
            .map(|t| t.name.clone())
            .collect();
        for f in &args.filters {
            let filter = name(&|| clap::ValueEnum::to_possible_value(f));
            let sets = textures
                .iter()
                .map(|t| format!("textures.{t}.filter=\"{filter}\""))
                .collect();
            variants.push((filter, sets));
        }
    }
    if variants.is_empty() {
        variants.push(("(scene's)".to_string(), Vec::new()));
    }
    if args.environments {
        variants.push((
            "no environment lookups".to_string(),
            vec!["render.environments=false".to_string()],
        ));
    }
    Ok(variants)
}

/// Million samples per second of the visible-surface pass alone, swept in the
/// frame's bands into one reused buffer as a frame does (polygons prepared once).
fn sweep_rate(scene: &lumiere::Scene, runs: usize) -> f64 {
    let mut pass = VisibleSurfacePass::prepare(scene);
    let sweep = median(runs, || pass.sweep());
    pass.samples() as f64 / sweep.as_secs_f64() / 1e6
}
