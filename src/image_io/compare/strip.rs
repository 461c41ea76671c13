//! The expected | difference | actual strip resvg's and Skia's triage pages show: the
//! three side by side, so a reader sees what moved and where.

use super::super::Image;
use super::difference_image;
use glam::Vec3;

/// Pixels of grey between the panels.
const GAP: u32 = 2;

/// `expected`, their magnified displayed difference, and `actual`, left to right,
/// as linear values to save with `exposure` (the difference panel is pre-divided
/// by it, so it shows as computed).
pub fn strip(expected: &Image, actual: &Image, exposure: f32, gain: f32) -> Image {
    let (w, h) = (expected.width, expected.height);
    let difference = difference_image(expected, actual, exposure, gain);
    let width = 3 * w + 2 * GAP;
    let grey = Vec3::splat(0.2 / exposure);
    let mut pixels = vec![grey; (width * h) as usize];
    for (panel, image, scale) in [
        (0, expected, 1.0),
        (1, &difference, 1.0 / exposure),
        (2, actual, 1.0),
    ] {
        let left = panel * (w + GAP);
        for y in 0..h {
            for x in 0..w {
                pixels[(y * width + left + x) as usize] =
                    image.pixels[(y * w + x) as usize] * scale;
            }
        }
    }
    Image {
        width,
        height: h,
        pixels,
    }
}
