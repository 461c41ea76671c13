//! `lumiere bench`: how fast the renderer is, on this machine.

use anyhow::Result;
use lumiere::{load_scene, raster, render};
use std::time::{Duration, Instant};

/// Time the Cornell box at several sizes (median of several runs) and the scan-line
/// pass's fill rate.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Catalogue id or scene file to time.
    #[arg(long, default_value = "cornell-box")]
    scene: String,
    /// Image sizes (square) to time.
    #[arg(long, value_delimiter = ',', default_values_t = [512u32, 1024])]
    sizes: Vec<u32>,
    /// Runs per size; the median is reported.
    #[arg(long, default_value_t = 15)]
    runs: usize,
}

pub fn run(args: Args) -> Result<()> {
    println!("threads: {}", rayon::current_num_threads());
    println!(
        "{:<22} {:>10} {:>14} {:>16}",
        "scene", "size", "render (ms)", "fill (Mpix/s)"
    );
    for &size in &args.sizes {
        let sets = [
            format!("camera.width={size}"),
            format!("camera.height={size}"),
        ];
        let scene = load_scene(&args.scene, &sets)?;
        let full = median(args.runs, || {
            std::hint::black_box(render::render(&scene));
        });
        // The visible-surface pass alone: polygons prepared once, then swept.
        let view = render::sample_view(&scene);
        let polygons = raster::prepare(
            &view,
            scene
                .polygons
                .iter()
                .enumerate()
                .map(|(id, p)| (id as u32, p.vertices.as_slice(), &[][..])),
        );
        let sweep = median(args.runs, || {
            std::hint::black_box(raster::rasterize(&polygons, view.width, view.height));
        });
        let pixels = (view.width * view.height) as f64;
        println!(
            "{:<22} {:>10} {:>14.2} {:>16.1}",
            args.scene,
            format!("{size}x{size}"),
            ms(full),
            pixels / sweep.as_secs_f64() / 1e6
        );
    }
    Ok(())
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

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}
