//! Comparing two images: RMSE, PSNR, largest channel difference and the share of
//! pixels that differ visibly, on the 8-bit sRGB values both images display as (so
//! a PNG and a PFM or EXR of the same render compare equal).

mod edges;
mod flip;
mod statistics;
mod strip;
mod tolerance;

pub use edges::{apply_mask, edge_mask};
pub use flip::{Flip, FlipRange, default_pixels_per_degree, flip, pixels_per_degree};
pub use statistics::{Candidate, Moments, MomentsSum, StatisticalTest, statistical_test};
pub use strip::strip;
pub use tolerance::{ToleranceCheck, tolerance_check};

use super::{Image, srgb_decode, to_srgb8};
use crate::error::{Error, Result};
use glam::Vec3;

#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
/// How far two images are apart, on their 8-bit sRGB values.
pub struct Comparison {
    /// Root mean square difference of the channels, in [0, 1].
    pub rmse: f64,
    /// Peak signal-to-noise ratio in dB (infinite for identical images).
    pub psnr: f64,
    /// Largest difference of one channel, in 1/255 steps.
    pub max_difference: u8,
    /// Share of pixels with a channel differing by more than 2/255.
    pub differing_share: f64,
}

/// Compares two images of the same size, each encoded to 8-bit sRGB after `exposure`.
pub fn compare(a: &Image, b: &Image, exposure: f32) -> Result<Comparison> {
    same_size(a, b)?;
    let mut squares = 0.0;
    let mut max_difference = 0u8;
    let mut differing = 0usize;
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        let d = displayed_difference(*p, *q, exposure);
        let worst = d.into_iter().max().unwrap_or(0);
        max_difference = max_difference.max(worst);
        differing += usize::from(worst > 2);
        squares += d.iter().map(|&c| (c as f64 / 255.0).powi(2)).sum::<f64>();
    }
    let rmse = (squares / (3 * a.pixels.len()) as f64).sqrt();
    Ok(Comparison {
        rmse,
        psnr: if rmse == 0.0 {
            f64::INFINITY
        } else {
            -20.0 * rmse.log10()
        },
        max_difference,
        differing_share: differing as f64 / a.pixels.len() as f64,
    })
}

/// Skia Gold's fuzzy matching figures (Skia's image comparison for its regression
/// tests: `max_different_pixels`, `pixel_delta_threshold`,
/// `ignored_border_thickness`): outside a border `border` pixels wide, how many pixels
/// differ at all on the 8-bit values, and the largest sum of one pixel's channel
/// differences, in 1/255 steps.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct FuzzyMatch {
    pub differing_pixels: u64,
    pub largest_pixel_delta: u32,
    pub border: u32,
}

/// The fuzzy matching figures of two images of the same size (see `FuzzyMatch`).
pub fn fuzzy_match(a: &Image, b: &Image, exposure: f32, border: u32) -> Result<FuzzyMatch> {
    same_size(a, b)?;
    let inside = |i: u32, n: u32| i >= border && i + border < n;
    let mut m = FuzzyMatch {
        differing_pixels: 0,
        largest_pixel_delta: 0,
        border,
    };
    for (k, (p, q)) in a.pixels.iter().zip(&b.pixels).enumerate() {
        let (x, y) = (k as u32 % a.width, k as u32 / a.width);
        if !(inside(x, a.width) && inside(y, a.height)) {
            continue;
        }
        let delta: u32 = displayed_difference(*p, *q, exposure)
            .iter()
            .map(|&c| c as u32)
            .sum();
        if delta > 0 {
            m.differing_pixels += 1;
            m.largest_pixel_delta = m.largest_pixel_delta.max(delta);
        }
    }
    Ok(m)
}

/// |a − b| per channel of the displayed values, magnified `gain` times (linear
/// values, ready to save as PNG with exposure 1).
pub fn difference_image(a: &Image, b: &Image, exposure: f32, gain: f32) -> Image {
    let pixels = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .map(|(p, q)| {
            let difference = displayed_difference(*p, *q, exposure);
            // Linear values whose sRGB encoding is the magnified difference.
            let d = |c: usize| srgb_decode((difference[c] as f32 / 255.0 * gain).min(1.0));
            Vec3::new(d(0), d(1), d(2))
        })
        .collect();
    Image {
        width: a.width,
        height: a.height,
        pixels,
    }
}

/// The difference of each channel as displayed, in 1/255 steps. A channel that is
/// not a number in one image only (a defect the 8-bit encoding would show as black)
/// differs by the whole range.
fn displayed_difference(p: Vec3, q: Vec3, exposure: f32) -> [u8; 3] {
    let (a, b) = (to_srgb8(p, exposure), to_srgb8(q, exposure));
    std::array::from_fn(|c| {
        if p[c].is_nan() != q[c].is_nan() {
            255
        } else {
            a[c].abs_diff(b[c])
        }
    })
}

/// Refuses two images of different sizes.
pub(super) fn same_size(a: &Image, b: &Image) -> Result<()> {
    if (a.width, a.height) != (b.width, b.height) {
        return Err(Error::SizeMismatch {
            first: (a.width, a.height),
            second: (b.width, b.height),
        });
    }
    Ok(())
}
