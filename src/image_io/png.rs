//! PNG: 8-bit sRGB.

use super::{Image, srgb_decode, to_srgb8};
use crate::error::{Error, Result};
use glam::Vec3;

pub fn encode(image: &Image, exposure: f32) -> Result<Vec<u8>> {
    let mut out = Vec::new();
    write(image, exposure, &mut out)?;
    Ok(out)
}

/// Encodes row by row into `out`: no 8-bit copy of the whole image is made (at
/// 8192 × 8192 it would be 200 MB).
pub fn write(image: &Image, exposure: f32, out: impl std::io::Write) -> Result<()> {
    let failed = |e: ::png::EncodingError| Error::image(e.to_string());
    let mut encoder = ::png::Encoder::new(out, image.width, image.height);
    encoder.set_color(::png::ColorType::Rgb);
    encoder.set_depth(::png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(failed)?;
    let mut stream = writer.stream_writer().map_err(failed)?;
    let mut row = Vec::with_capacity(3 * image.width as usize);
    for pixels in image.pixels.chunks(image.width.max(1) as usize) {
        row.clear();
        row.extend(pixels.iter().flat_map(|&p| to_srgb8(p, exposure)));
        std::io::Write::write_all(&mut stream, &row).map_err(|e| Error::image(e.to_string()))?;
    }
    stream.finish().map_err(failed)
}

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
