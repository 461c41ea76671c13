//! PNG: 8-bit sRGB.

use super::{Image, srgb_decode, to_srgb8};
use crate::{Error, Result};
use glam::Vec3;

pub fn encode(image: &Image, exposure: f32) -> Result<Vec<u8>> {
    let data: Vec<u8> = image
        .pixels
        .iter()
        .flat_map(|&p| to_srgb8(p, exposure))
        .collect();
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out).write_image(
        &data,
        image.width,
        image.height,
        image::ExtendedColorType::Rgb8,
    )?;
    Ok(out)
}

use image::ImageEncoder;

pub fn decode(bytes: &[u8]) -> Result<Image> {
    let decoded = image::load_from_memory_with_format(bytes, image::ImageFormat::Png)?.to_rgb8();
    if decoded.width() == 0 || decoded.height() == 0 {
        return Err(Error::image("the image is empty"));
    }
    let pixels = decoded
        .pixels()
        .map(|p| Vec3::from_array(p.0.map(|c| srgb_decode(c as f32 / 255.0))))
        .collect();
    Ok(Image {
        width: decoded.width(),
        height: decoded.height(),
        pixels,
    })
}
