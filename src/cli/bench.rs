//! `lumiere bench`: how fast the renderer is, on this machine.

use anyhow::Result;
use lumiere::shadow::ShadowMethod;
use lumiere::{load_scene, raster, render};
use std::time::{Duration, Instant};

/// Time whole renders (median of several runs) per scene, shadow method and size,
/// and the scan-line pass's fill rate.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Catalogue ids or scene files to time.
    #[arg(long, value_delimiter = ',', default_values_t = ["cornell-box".to_string()])]
    scenes: Vec<String>,
    /// Shadow methods to time (each overrides the scene's own).
    #[arg(long, value_enum, value_delimiter = ',')]
    shadows: Vec<ShadowMethod>,
    /// Image sizes (square) to time.
    #[arg(long, value_delimiter = ',', default_values_t = [512u32, 1024])]
    sizes: Vec<u32>,
    /// Runs per measurement; the median is reported.
    #[arg(long, default_value_t = 15)]
    runs: usize,
}

pub fn run(args: Args) -> Result<()> {
    println!("threads: {}", rayon::current_num_threads());
    println!(
        "{:<26} {:<15} {:>10} {:>12} {:>14}",
        "scene", "shadows", "size", "render (ms)", "fill (Mpix/s)"
    );
    let methods: Vec<Option<ShadowMethod>> = if args.shadows.is_empty() {
        vec![None]
    } else {
        args.shadows.iter().copied().map(Some).collect()
    };
    for scene_name in &args.scenes {
        for method in &methods {
            for &size in &args.sizes {
                let mut sets = vec![
                    format!("camera.width={size}"),
                    format!("camera.height={size}"),
                ];
                if let Some(m) = method {
                    let name = clap::ValueEnum::to_possible_value(m).expect("no skipped variants");
                    sets.push(format!("shadows.method=\"{}\"", name.get_name()));
                }
                let scene = load_scene(scene_name, &sets)?;
                let full = median(args.runs, || {
                    std::hint::black_box(render::render(&scene));
                });
                let fill = fill_rate(&scene, args.runs);
                let label = method.map_or("(scene's)".to_string(), |m| format!("{m:?}"));
                println!(
                    "{:<26} {:<15} {:>10} {:>12.2} {:>14.1}",
                    scene_name,
                    label,
                    format!("{size}x{size}"),
                    full.as_secs_f64() * 1e3,
                    fill
                );
            }
        }
    }
    Ok(())
}

/// Mpixels per second of the visible-surface pass alone (polygons prepared once).
fn fill_rate(scene: &lumiere::Scene, runs: usize) -> f64 {
    let view = render::sample_view(scene);
    let polygons = render::screen_polygons(scene, &view);
    let sweep = median(runs, || {
        std::hint::black_box(raster::rasterize(&polygons, view.width, view.height));
    });
    (view.width * view.height) as f64 / sweep.as_secs_f64() / 1e6
}

fn median(runs: usize, mut f: impl FnMut()) -> Duration {
    f(); // warm-up
    let mut times: Vec<Duration> = (0..runs.max(1))
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed()
        })
        .collect();
    times.sort();
    times[times.len() / 2]
}
