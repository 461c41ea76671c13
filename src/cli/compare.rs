//! `lumiere compare`: how far apart two images are, and whether that is within the
//! thresholds a regression test allows.

use super::compare_checks::{Figures, Thresholds, exceeded, print};
use anyhow::{Context, Result, bail};
use lumiere::{
    Candidate, FlipRange, Image, Moments, apply_mask, compare_images, comparison_strip,
    default_pixels_per_degree, edge_mask, flip, fuzzy_match, statistical_test, tolerance_check,
    write_image,
};
use std::path::{Path, PathBuf};

/// Compare two images (PNG, PFM or EXR), A the reference and B the candidate: RMSE,
/// PSNR, largest channel difference and the share of pixels differing by more than
/// 2/255, on their 8-bit sRGB values; and on request FLIP, a tolerance image and a
/// statistical test for sampled output.
///
/// With thresholds (--max-rmse, --max-difference, --max-differing) the figures are
/// printed as usual, then, if any is exceeded, one line `error: …` naming it.
///
/// Fuzzy matching, as Skia Gold's (--max-differing-pixels, with --pixel-delta and
/// --ignore-border): the images match if, outside the border, at most N pixels differ
/// at all and none of them by more than D in the sum of its channels' differences
/// (1/255 steps), so an edge moved by a pixel passes and a moved shadow does not.
/// --ignore-edges T leaves out, from every check but FLIP and the statistical test,
/// the pixels on strong edges of either image (a Sobel gradient above T, where a
/// black-to-white step is 1), as Skia Gold's Sobel matching does.
///
/// FLIP (--flip, --max-flip): NVIDIA's perceptual difference (Andersson et al. 2020;
/// HDR-FLIP 2021), LDR on the displayed values or HDR on the linear ones, at
/// --ppd pixels per degree; the mean and percentiles are printed.
///
/// A tolerance image (--tolerance FILE): per pixel and channel the largest
/// difference of the linear values allowed there.
///
/// The statistical test (--reference-variance with --reference-renders): A is the
/// mean of N renders and VAR their per-pixel variance; B one render (a Z-test, as
/// Mitsuba 3's render tests) or, with --candidate-variance and --candidate-renders,
/// the mean of its own renders (Welch's t-test, as Jung et al. 2020). Each pixel is
/// rejected at the false-positive rate --alpha; B passes when at least
/// --min-accepted of the pixels are accepted.
///
/// --diff writes the expected | difference | actual strip.
///
/// Exit status: 0 within the thresholds (or none given), 1 beyond them, 2 for bad
/// input (an unreadable image, images of different sizes, a bad option).
#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    a: PathBuf,
    b: PathBuf,
    /// Write A | the difference, magnified | B, side by side, as an image.
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
    /// Leave out pixels on strong edges of either image: a Sobel gradient of the
    /// displayed luminance above T (in [0, 1]; a black-to-white step is 1).
    #[arg(long, value_name = "T", value_parser = share)]
    ignore_edges: Option<f64>,
    /// Compute FLIP (printed with its percentiles).
    #[arg(long)]
    flip: bool,
    /// Fail (exit 1) if the mean FLIP is above X. Implies --flip.
    #[arg(long, value_name = "X", value_parser = share)]
    max_flip: Option<f64>,
    /// FLIP's dynamic range: `ldr` (the displayed values) or `hdr` (the linear
    /// values over a range of exposures, tone-mapped by ACES).
    #[arg(long, value_enum, default_value = "ldr")]
    flip_range: FlipRangeArg,
    /// FLIP's pixels per degree (default: a 0.7 m, 3840-pixel monitor seen from
    /// 0.7 m, 67.02).
    #[arg(long, value_name = "P", value_parser = positive)]
    ppd: Option<f32>,
    /// HDR-FLIP's first exposure, in stops (default: found from A).
    #[arg(long, value_name = "STOPS", allow_hyphen_values = true)]
    flip_start: Option<f32>,
    /// HDR-FLIP's last exposure, in stops (default: found from A).
    #[arg(long, value_name = "STOPS", allow_hyphen_values = true)]
    flip_stop: Option<f32>,
    /// HDR-FLIP's number of exposures (default: one a stop, at least 2).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(2..=64))]
    flip_exposures: Option<u32>,
    /// Fail (exit 1) where a channel differs by more than this image allows there
    /// (PNG, PFM or EXR of A's size, linear values).
    #[arg(long, value_name = "FILE")]
    tolerance: Option<PathBuf>,
    /// The statistical test: the per-pixel variance of one of the N renders A is the
    /// mean of. Needs --reference-renders.
    #[arg(long, value_name = "VAR", requires = "reference_renders")]
    reference_variance: Option<PathBuf>,
    /// The number of renders A is the mean of.
    #[arg(long, value_name = "N", requires = "reference_variance", value_parser = clap::value_parser!(u32).range(2..))]
    reference_renders: Option<u32>,
    /// Welch's t-test: the per-pixel variance of one of the M renders B is the mean of.
    #[arg(long, value_name = "VAR", requires_all = ["candidate_renders", "reference_variance"])]
    candidate_variance: Option<PathBuf>,
    /// The number of renders B is the mean of.
    #[arg(long, value_name = "M", requires = "candidate_variance", value_parser = clap::value_parser!(u32).range(2..))]
    candidate_renders: Option<u32>,
    /// The statistical test's false-positive rate per pixel.
    #[arg(long, default_value_t = 0.001, value_parser = open_share)]
    alpha: f64,
    /// The share of pixels the statistical test must accept (Mitsuba's 99.75%).
    #[arg(long, default_value_t = 0.9975, value_parser = share)]
    min_accepted: f64,
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
const DIFF_BYTES_PER_PIXEL: u64 = 3 * (12 + 3);
/// FLIP's working images: both in YCxCz (12 each), their filtered rows (16 + 12
/// each) and the colour, feature and error maps (4 each).
const FLIP_BYTES_PER_PIXEL: u64 = 2 * (12 + 16 + 12) + 3 * 4;

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum FlipRangeArg {
    Ldr,
    Hdr,
}

/// Reads both images' headers and refuses, before decoding either, a comparison
/// over the budget; then decodes them.
fn read_within_budget(args: &Args) -> Result<Vec<Image>> {
    use lumiere::FileOp;
    use lumiere::{decode_image, image_dimensions, read_file};
    let read = |path: &Path| -> Result<(Vec<u8>, lumiere::ImageFormat, u64)> {
        let bytes = read_file(path, FileOp::Read)?;
        let format = lumiere::ImageFormat::of(path)?;
        let (w, h) =
            image_dimensions(&bytes, format).with_context(|| path.display().to_string())?;
        Ok((bytes, format, w as u64 * h as u64))
    };
    let paths: Vec<&Path> = [Some(&args.a), Some(&args.b)]
        .into_iter()
        .chain(
            [
                &args.tolerance,
                &args.reference_variance,
                &args.candidate_variance,
            ]
            .map(Option::as_ref),
        )
        .flatten()
        .map(PathBuf::as_path)
        .collect();
    let read: Vec<_> = paths.iter().map(|p| read(p)).collect::<Result<_>>()?;
    let (a_pixels, b_pixels) = (read[0].2, read[1].2);
    let extra_pixels: u64 = read[2..].iter().map(|r| r.2).sum();
    let files = read.iter().map(|r| r.0.len() as u64).sum::<u64>();
    let flip = if args.flip || args.max_flip.is_some() {
        a_pixels.max(b_pixels).saturating_mul(FLIP_BYTES_PER_PIXEL)
    } else {
        0
    };
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
        .saturating_add(extra_pixels.saturating_mul(BYTES_PER_PIXEL))
        .saturating_add(files)
        .saturating_add(flip)
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
    read.into_iter()
        .zip(paths)
        .map(|((bytes, format, _), path)| {
            decode_image(&bytes, format).with_context(|| path.display().to_string())
        })
        .collect()
}

/// The images differ by more than the thresholds allow: exit status 1, where bad
/// input is 2.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct BeyondThresholds(String);

/// A share: a number in [0, 1].
fn share(text: &str) -> std::result::Result<f64, String> {
    match text.parse::<f64>() {
        Ok(x) if (0.0..=1.0).contains(&x) => Ok(x),
        Ok(_) => Err("must be a number between 0 and 1".into()),
        Err(e) => Err(e.to_string()),
    }
}

/// A probability strictly between 0 and 1.
fn open_share(text: &str) -> std::result::Result<f64, String> {
    match text.parse::<f64>() {
        Ok(x) if x > 0.0 && x < 1.0 => Ok(x),
        Ok(_) => Err("must lie strictly between 0 and 1".into()),
        Err(e) => Err(e.to_string()),
    }
}

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
    let mut images = read_within_budget(&args)?.into_iter();
    let (a, b) = (images.next().unwrap(), images.next().unwrap());
    // Images of different sizes are refused as the comparison refuses them.
    compare_images(&a, &b, args.exposure)?;
    let same_size = |path: &Path, image: &Image| -> Result<()> {
        if (image.width, image.height) != (a.width, a.height) {
            bail!(
                "{}: is {}x{}, the images compared are {}x{}",
                path.display(),
                image.width,
                image.height,
                a.width,
                a.height
            );
        }
        Ok(())
    };
    let tolerance = args.tolerance.as_ref().map(|p| (p, images.next().unwrap()));
    let reference_variance = args
        .reference_variance
        .as_ref()
        .map(|p| (p, images.next().unwrap()));
    let candidate_variance = args
        .candidate_variance
        .as_ref()
        .map(|p| (p, images.next().unwrap()));

    // Masked pixels of B take A's values: every check below but FLIP and the
    // statistical test sees them equal.
    let edges = args
        .ignore_edges
        .map(|t| (t, edge_mask(&a, &b, args.exposure, t as f32)));
    let masked = edges.as_ref().map(|(_, m)| apply_mask(&a, &b, m));
    let checked = masked.as_ref().unwrap_or(&b);
    let mut figures = Figures {
        comparison: compare_images(&a, checked, args.exposure)?,
        fuzzy: None,
        edges: edges
            .as_ref()
            .map(|(t, m)| (*t, m.iter().filter(|&&e| e).count() as u64)),
        flip: None,
        tolerance: None,
        statistical: None,
    };
    if args.max_differing_pixels.is_some() {
        figures.fuzzy = Some(fuzzy_match(&a, checked, args.exposure, args.ignore_border)?);
    }
    if args.flip || args.max_flip.is_some() {
        let range = match args.flip_range {
            FlipRangeArg::Ldr => FlipRange::Ldr,
            FlipRangeArg::Hdr => FlipRange::Hdr {
                start: args.flip_start,
                stop: args.flip_stop,
                exposures: args.flip_exposures,
            },
        };
        let ppd = args.ppd.unwrap_or_else(default_pixels_per_degree);
        let exposed = |i: &Image| Image {
            pixels: i.pixels.iter().map(|p| *p * args.exposure).collect(),
            ..i.clone()
        };
        figures.flip = Some((flip(&exposed(&a), &exposed(&b), range, ppd)?, ppd));
    }
    if let Some((path, image)) = &tolerance {
        same_size(path, image)?;
        figures.tolerance = Some(tolerance_check(&a, checked, image, args.exposure)?);
    }
    if let (Some((path, variance)), Some(renders)) = (reference_variance, args.reference_renders) {
        same_size(path, &variance)?;
        let reference = Moments {
            mean: a.clone(),
            variance,
            renders,
        };
        let candidate = match (candidate_variance, args.candidate_renders) {
            (Some((path, variance)), Some(renders)) => {
                same_size(path, &variance)?;
                Some(Moments {
                    mean: b.clone(),
                    variance,
                    renders,
                })
            }
            _ => None,
        };
        let candidate = match &candidate {
            Some(m) => Candidate::Moments(m),
            None => Candidate::Render(&b),
        };
        figures.statistical = Some(statistical_test(
            &reference,
            candidate,
            args.alpha,
            args.min_accepted,
        )?);
    }
    if let Some(path) = &args.diff {
        write_image(
            &comparison_strip(&a, &b, args.exposure, args.gain),
            path,
            args.exposure,
        )?;
    }
    let printed = print(&figures, args.json);
    // The verdict stands even when the reader of the figures has gone (`| head -1`).
    let exceeded = exceeded(&args.thresholds(), &figures);
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

impl Args {
    fn thresholds(&self) -> Thresholds {
        Thresholds {
            max_rmse: self.max_rmse,
            max_difference: self.max_difference,
            max_differing: self.max_differing,
            max_differing_pixels: self.max_differing_pixels,
            pixel_delta: self.pixel_delta,
            max_flip: self.max_flip,
        }
    }
}

/// The exit status of a failed comparison: 1 beyond the thresholds, 2 for bad input
/// (as `cmp` and `diff` do).
pub fn failure_status(error: &anyhow::Error) -> u8 {
    if error.is::<BeyondThresholds>() { 1 } else { 2 }
}
