//! NVIDIA's FLIP (Andersson et al. 2020) on lumiere's images, through `nv-flip`
//! (bindings to the C++ FLIP): the perceptual difference the Mitsuba comparisons
//! report (tools/mitsuba_reference.py, flip-evaluator's LDR mode).

use lumiere::image_io::{Image, srgb_encode};

/// flip-evaluator's default viewing: 0.7 m from a 0.7 m wide, 3840-pixel monitor
/// (67.0206; nv-flip's own default is a rounded 67.0).
pub fn pixels_per_degree() -> f32 {
    nv_flip::pixels_per_degree(0.7, 3840.0, 0.7)
}

/// Linear radiance as 8-bit sRGB: clamped to [0, 1], then the sRGB curve, as the
/// Mitsuba script does before FLIP. nv-flip takes 8-bit images only; rounding moves
/// the mean by about 1e-4 against FLIP of the float sRGB values.
pub fn srgb8(image: &Image) -> Vec<u8> {
    image
        .pixels
        .iter()
        .flat_map(|p| p.to_array())
        .map(|c| (srgb_encode(c.clamp(0.0, 1.0)) * 255.0).round() as u8)
        .collect()
}

/// LDR-FLIP's per-pixel error map (0 equal … 1 most different), row-major.
pub fn error_map(reference: &Image, test: &Image) -> nv_flip::FlipImageFloat {
    assert_eq!(
        (reference.width, reference.height),
        (test.width, test.height),
        "FLIP compares images of one size"
    );
    let image = |i: &Image| nv_flip::FlipImageRgb8::with_data(i.width, i.height, &srgb8(i));
    nv_flip::flip(image(reference), image(test), pixels_per_degree())
}

/// The mean of LDR-FLIP's error map: the single figure FLIP's authors recommend.
pub fn mean(reference: &Image, test: &Image) -> f64 {
    let map = error_map(reference, test).to_vec();
    map.iter().map(|&e| e as f64).sum::<f64>() / map.len() as f64
}

/// The error map through FLIP's magma colour map, as an sRGB image to save beside
/// a failure.
pub fn magma(reference: &Image, test: &Image) -> Image {
    let map = error_map(reference, test).apply_color_lut(&nv_flip::magma_lut());
    Image {
        width: map.width(),
        height: map.height(),
        pixels: map
            .to_vec()
            .chunks_exact(3)
            .map(|c| {
                let linear = |v: u8| lumiere::image_io::srgb_decode(v as f32 / 255.0);
                glam::Vec3::new(linear(c[0]), linear(c[1]), linear(c[2]))
            })
            .collect(),
    }
}
