//! A tolerance image: per pixel and channel, the largest difference allowed there
//! (a reference suite writes one where a method is known to be loose, on
//! silhouettes, in noisy penumbrae), on the linear values after the exposure.

use super::super::Image;
use super::same_size;
use crate::error::Result;

/// How far `b` strays beyond the tolerance image.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ToleranceCheck {
    /// Pixels with a channel differing by more than its tolerance (or not a number
    /// in one image only).
    pub pixels_beyond: u64,
    /// The largest excess of a difference over its tolerance (0 when none).
    pub largest_excess: f32,
}

/// Checks `|a − b| ≤ tolerance` per channel of every pixel, on the linear values
/// after `exposure`; all three images of one size.
pub fn tolerance_check(
    a: &Image,
    b: &Image,
    tolerance: &Image,
    exposure: f32,
) -> Result<ToleranceCheck> {
    same_size(a, b)?;
    same_size(a, tolerance)?;
    let mut check = ToleranceCheck {
        pixels_beyond: 0,
        largest_excess: 0.0,
    };
    for ((p, q), t) in a.pixels.iter().zip(&b.pixels).zip(&tolerance.pixels) {
        let mut beyond = false;
        for c in 0..3 {
            if p[c].is_nan() != q[c].is_nan() {
                beyond = true;
                check.largest_excess = f32::INFINITY;
                continue;
            }
            let excess = (exposure * (p[c] - q[c])).abs() - t[c];
            if excess > 0.0 {
                beyond = true;
                check.largest_excess = check.largest_excess.max(excess);
            }
        }
        check.pixels_beyond += u64::from(beyond);
    }
    Ok(check)
}
