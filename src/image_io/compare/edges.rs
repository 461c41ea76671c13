//! An edge mask, as Skia Gold's Sobel matching uses one: the pixels on strong edges
//! of either image, where a one-pixel shift of an edge (a rasterisation rounding
//! another way) would otherwise count as a difference. A shadow moved by more
//! than the mask's width still differs on the pixels between its edges.

use super::super::{Image, to_srgb8};

/// Pixels where the Sobel gradient of either image's displayed luminance (8-bit
/// sRGB after `exposure`, scaled to [0, 1]) exceeds `threshold`; the gradient is
/// normalised so a black-to-white step measures 1. Row-major, one flag a pixel.
pub fn edge_mask(a: &Image, b: &Image, exposure: f32, threshold: f32) -> Vec<bool> {
    let (ga, gb) = (gradient(a, exposure), gradient(b, exposure));
    ga.iter()
        .zip(&gb)
        .map(|(&p, &q)| p > threshold || q > threshold)
        .collect()
}

/// `b` with the pixels under `mask` replaced by `a`'s: masked pixels compare equal.
pub fn apply_mask(a: &Image, b: &Image, mask: &[bool]) -> Image {
    Image {
        width: b.width,
        height: b.height,
        pixels: b
            .pixels
            .iter()
            .zip(&a.pixels)
            .zip(mask)
            .map(|((&q, &p), &masked)| if masked { p } else { q })
            .collect(),
    }
}

/// The Sobel gradient magnitude of the displayed luminance, borders repeated.
fn gradient(image: &Image, exposure: f32) -> Vec<f32> {
    let (w, h) = (image.width as i64, image.height as i64);
    let luminance: Vec<f32> = image
        .pixels
        .iter()
        .map(|p| {
            let [r, g, b] = to_srgb8(*p, exposure);
            (0.2126 * r as f32 + 0.7152 * g as f32 + 0.0722 * b as f32) / 255.0
        })
        .collect();
    let at = |x: i64, y: i64| luminance[(y.clamp(0, h - 1) * w + x.clamp(0, w - 1)) as usize];
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let gx = at(x + 1, y - 1) + 2.0 * at(x + 1, y) + at(x + 1, y + 1)
                - at(x - 1, y - 1)
                - 2.0 * at(x - 1, y)
                - at(x - 1, y + 1);
            let gy = at(x - 1, y + 1) + 2.0 * at(x, y + 1) + at(x + 1, y + 1)
                - at(x - 1, y - 1)
                - 2.0 * at(x, y - 1)
                - at(x + 1, y - 1);
            (gx * gx + gy * gy).sqrt() / 4.0
        })
        .collect()
}
