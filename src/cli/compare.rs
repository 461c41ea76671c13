//! `lumiere compare`: how far apart two images are.

use anyhow::Result;
use lumiere::output;
use std::path::PathBuf;

/// Compare two images (PNG, PFM or EXR): RMSE, PSNR, largest channel difference and the
/// share of pixels differing by more than 2/255, on their 8-bit sRGB values.
#[derive(clap::Args, Debug)]
pub struct Args {
    a: PathBuf,
    b: PathBuf,
    /// Write the difference, magnified, as an image.
    #[arg(long, value_name = "OUT.png")]
    diff: Option<PathBuf>,
    /// Magnification of the difference image.
    #[arg(long, default_value_t = 8.0)]
    gain: f32,
    /// Exposure applied to both before comparing (matters for PFM and EXR).
    #[arg(long, default_value_t = 1.0)]
    exposure: f32,
    /// Print the figures as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> Result<()> {
    let a = output::load(&args.a)?;
    let b = output::load(&args.b)?;
    let c = output::compare(&a, &b, args.exposure)?;
    if let Some(path) = &args.diff {
        output::save(
            &output::difference_image(&a, &b, args.exposure, args.gain),
            path,
            1.0,
        )?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&c)?);
    } else {
        println!("rmse            {:.6}", c.rmse);
        println!("psnr            {:.2} dB", c.psnr);
        println!("max difference  {}/255", c.max_difference);
        println!(
            "differing       {:.4}% of pixels (> 2/255)",
            100.0 * c.differing_share
        );
    }
    Ok(())
}
