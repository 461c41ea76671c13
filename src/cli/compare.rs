//! `lumiere compare`: how far apart two images are, and whether that is within the
//! thresholds a regression test allows.

use anyhow::{Context, Result, bail};
use lumiere::{Comparison, FuzzyMatch, compare_images, difference_image, fuzzy_match, write_image};
use std::path::PathBuf;

/// Compare two images (PNG, PFM or EXR): RMSE, PSNR, largest channel difference and the
/// share of pixels differing by more than 2/255, on their 8-bit sRGB values.
///
/// With thresholds (--max-rmse, --max-difference, --max-differing) the figures are
/// printed as usual, then, if any is exceeded, one line `error: …` naming it.
///
/// Fuzzy matching, as Skia Gold's (--max-differing-pixels, with --pixel-delta and
/// --ignore-border): the images match if, outside the border, at most N pixels differ
/// at all and none of them by more than D in the sum of its channels' differences
/// (1/255 steps), so an edge moved by a pixel passes and a moved shadow does not.
/// Exit status: 0 within the thresholds (or none given), 1 beyond them, 2 for bad
/// input (an unreadable image, images of different sizes, a bad option).
#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    a: PathBuf,
    b: PathBuf,
    /// Write the difference, magnified, as an image.
    #[arg(long, value_name = "OUT.png")]
    diff: Option<PathBuf>,
    /// Magnification of the difference image (a positive number).
    #[arg(long, default_value_t = 8.0, value_parser = positive)]
    gain: f32,
    /// Exposure applied to both before comparing (matters for PFM and EXR; a positive
    /// number).
    #[arg(long, default_value_t = 1.0, value_parser = positive)]
    exposure: f32,
    /// Print the figures as JSON.
    #[arg(long)]
    json: bool,
    /// Fail (exit 1) if the RMSE, in [0, 1], is above X.
    #[arg(long, value_name = "X")]
    max_rmse: Option<f64>,
    /// Fail (exit 1) if a channel differs by more than N/255.
    #[arg(long, value_name = "N")]
    max_difference: Option<u8>,
    /// Fail (exit 1) if more than FRACTION (in [0, 1]) of the pixels differ by more
    /// than 2/255.
    #[arg(long, value_name = "FRACTION")]
    max_differing: Option<f64>,
    /// Fuzzy matching (Skia Gold's): fail (exit 1) if more than N pixels differ at all
    /// (outside the --ignore-border).
    #[arg(long, value_name = "N")]
    max_differing_pixels: Option<u64>,
    /// Fuzzy matching: fail (exit 1) if a pixel's channel differences, in 1/255
    /// steps, sum to more than D (0 to 765). Needs --max-differing-pixels.
    #[arg(long, value_name = "D", requires = "max_differing_pixels", value_parser = clap::value_parser!(u32).range(0..=765))]
    pixel_delta: Option<u32>,
    /// Fuzzy matching: leave out the K pixels along each edge. Needs
    /// --max-differing-pixels.
    #[arg(
        long,
        value_name = "K",
        default_value_t = 0,
        requires = "max_differing_pixels"
    )]
    ignore_border: u32,
    /// The memory the comparison may take, counted from the images' headers before
    /// either is decoded (as render.max_memory_mb is for a render).
    #[arg(long, value_name = "MB", default_value_t = 4096, value_parser = clap::value_parser!(u64).range(1..=1 << 20))]
    max_memory_mb: u64,
}

/// Bytes a comparison holds per pixel of each image: its linear pixels (12) and
/// the 8-bit sRGB values compared (3); the decoder's own buffer (up to 16 a pixel,
/// RGBA 32-bit) is held for one image at a time; the difference image, if
/// written, takes 12 more a pixel and its encoding 3. The files' bytes are held
/// too. Measured on two 2048² images with --diff: 155 MB peak for PNG (estimated
/// 256 MiB), 192 MB for uncompressed EXR (estimated 316 MiB).
const BYTES_PER_PIXEL: u64 = 12 + 3;
const DECODER_BYTES_PER_PIXEL: u64 = 16;
const DIFF_BYTES_PER_PIXEL: u64 = 12 + 3;

/// Reads both images' headers and refuses, before decoding either, a comparison
/// over the budget; then decodes them.
fn read_within_budget(args: &Args) -> Result<(lumiere::Image, lumiere::Image)> {
    use lumiere::FileOp;
    use lumiere::internals::image_io::{decode, dimensions, read_file};
    let read = |path: &std::path::Path| -> Result<(Vec<u8>, lumiere::ImageFormat, u64)> {
        let bytes = read_file(path, FileOp::Read)?;
        let format = lumiere::ImageFormat::of(path)?;
        let (w, h) = dimensions(&bytes, format).with_context(|| path.display().to_string())?;
        Ok((bytes, format, w as u64 * h as u64))
    };
    let (a, a_format, a_pixels) = read(&args.a)?;
    let (b, b_format, b_pixels) = read(&args.b)?;
    let files = (a.len() + b.len()) as u64;
    let diff = if args.diff.is_some() {
        a_pixels.max(b_pixels).saturating_mul(DIFF_BYTES_PER_PIXEL)
    } else {
        0
    };
    let needed = a_pixels
        .saturating_add(b_pixels)
        .saturating_mul(BYTES_PER_PIXEL)
        .saturating_add(
            a_pixels
                .max(b_pixels)
                .saturating_mul(DECODER_BYTES_PER_PIXEL),
        )
        .saturating_add(files)
        .saturating_add(diff);
    let budget = args.max_memory_mb << 20;
    if needed > budget {
        bail!(
            "comparing {} ({a_pixels} pixels) with {} ({b_pixels} pixels) needs about {} MiB, more than --max-memory-mb {} allows",
            args.a.display(),
            args.b.display(),
            needed.div_ceil(1 << 20),
            args.max_memory_mb
        );
    }
    let decoded = |bytes: Vec<u8>, format, path: &std::path::Path| {
        decode(&bytes, format).with_context(|| path.display().to_string())
    };
    Ok((
        decoded(a, a_format, &args.a)?,
        decoded(b, b_format, &args.b)?,
    ))
}

/// The images differ by more than the thresholds allow: exit status 1, where bad
/// input is 2.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct BeyondThresholds(String);

/// A finite number above zero: a negative gain or exposure, zero or NaN would be
/// accepted and give a meaningless picture or figures.
fn positive(text: &str) -> std::result::Result<f32, String> {
    match text.parse::<f32>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        Ok(_) => Err("must be a positive number".into()),
        Err(e) => Err(e.to_string()),
    }
}

/// Whether `output` names the same file as `input` (an existing file reached by
/// another path, a link, counts).
fn same_file(output: &std::path::Path, input: &std::path::Path) -> bool {
    output == input
        || matches!(
            (output.canonicalize(), input.canonicalize()),
            (Ok(a), Ok(b)) if a == b
        )
}

pub fn run(args: Args) -> Result<()> {
    if let Some(diff) = &args.diff
        && let Some(input) = [&args.a, &args.b].into_iter().find(|i| same_file(diff, i))
    {
        bail!(
            "--diff {}: is the input {}; write the difference to another file",
            diff.display(),
            input.display()
        );
    }
    if let Some(x) = args.max_rmse
        && !(0.0..=1.0).contains(&x)
    {
        bail!("--max-rmse {x}: must be between 0 and 1");
    }
    if let Some(f) = args.max_differing
        && !(0.0..=1.0).contains(&f)
    {
        bail!("--max-differing {f}: must be a fraction between 0 and 1");
    }
    let (a, b) = read_within_budget(&args)?;
    let c = compare_images(&a, &b, args.exposure)?;
    let fuzzy = match args.max_differing_pixels {
        Some(_) => Some(fuzzy_match(&a, &b, args.exposure, args.ignore_border)?),
        None => None,
    };
    if let Some(path) = &args.diff {
        write_image(
            &difference_image(&a, &b, args.exposure, args.gain),
            path,
            1.0,
        )?;
    }
    let printed = print(&c, fuzzy.as_ref(), args.json);
    // The verdict stands even when the reader of the figures has gone (`| head -1`).
    let exceeded = exceeded(&args, &c, fuzzy.as_ref());
    if !exceeded.is_empty() {
        return Err(BeyondThresholds(format!(
            "{} and {} differ beyond the threshold{}: {}",
            args.a.display(),
            args.b.display(),
            if exceeded.len() == 1 { "" } else { "s" },
            exceeded.join(", ")
        ))
        .into());
    }
    printed
}

/// The figures, as text or JSON, on standard output.
fn print(c: &Comparison, fuzzy: Option<&FuzzyMatch>, json: bool) -> Result<()> {
    if json {
        let mut value = serde_json::to_value(c)?;
        if let Some(f) = fuzzy {
            value["fuzzy"] = serde_json::to_value(f)?;
        }
        outln!("{}", serde_json::to_string_pretty(&value)?)?;
    } else {
        outln!("rmse            {:.6}", c.rmse)?;
        outln!("psnr            {:.2} dB", c.psnr)?;
        outln!("max difference  {}/255", c.max_difference)?;
        outln!(
            "differing       {:.4}% of pixels (> 2/255)",
            100.0 * c.differing_share
        )?;
        if let Some(f) = fuzzy {
            outln!(
                "fuzzy           {} pixels differ, largest delta {}/255 (border {})",
                f.differing_pixels,
                f.largest_pixel_delta,
                f.border
            )?;
        }
    }
    Ok(())
}

/// The exit status of a failed comparison: 1 beyond the thresholds, 2 for bad input
/// (as `cmp` and `diff` do).
pub fn failure_status(error: &anyhow::Error) -> u8 {
    if error.is::<BeyondThresholds>() { 1 } else { 2 }
}

/// Each threshold exceeded, with the measured value.
fn exceeded(args: &Args, c: &Comparison, fuzzy: Option<&FuzzyMatch>) -> Vec<String> {
    let mut beyond = Vec::new();
    if let Some(x) = args.max_rmse
        && c.rmse > x
    {
        beyond.push(format!("rmse {:.6} > --max-rmse {x}", c.rmse));
    }
    if let Some(n) = args.max_difference
        && c.max_difference > n
    {
        beyond.push(format!(
            "max difference {}/255 > --max-difference {n}",
            c.max_difference
        ));
    }
    if let Some(f) = args.max_differing
        && c.differing_share > f
    {
        beyond.push(format!(
            "differing {:.6} of pixels > --max-differing {f}",
            c.differing_share
        ));
    }
    if let (Some(n), Some(f)) = (args.max_differing_pixels, fuzzy)
        && f.differing_pixels > n
    {
        beyond.push(format!(
            "{} pixels differ > --max-differing-pixels {n}",
            f.differing_pixels
        ));
    }
    if let (Some(d), Some(f)) = (args.pixel_delta, fuzzy)
        && f.largest_pixel_delta > d
    {
        beyond.push(format!(
            "a pixel's delta {}/255 > --pixel-delta {d}",
            f.largest_pixel_delta
        ));
    }
    beyond
}
