//! A frame's intermediate buffers as pictures, for the gallery and the viewer.

use lumiere::internals::image_io::{self, Buffer, BufferData, Image};

/// A buffer as a picture: ids and counts colour-mapped; visibility and texture
/// coordinates as they are; normals from [-1, 1]; radiance at the scene's
/// exposure; other values (depths, positions, levels) stretched over their range.
pub fn displayed(buffer: &Buffer, exposure: f32) -> Image {
    let mut image = buffer.to_image(image_io::Format::Png);
    if !matches!(buffer.data, BufferData::Values { .. }) {
        return image;
    }
    let name = buffer.name.as_str();
    if name.starts_with("visibility") || name == "uv" {
        return image;
    }
    if name == "normal" {
        for p in &mut image.pixels {
            *p = (*p + 1.0) * 0.5;
        }
        return image;
    }
    if name == "radiosity" || name == "inscattered" {
        let scale = if name == "radiosity" {
            exposure / std::f32::consts::PI
        } else {
            exposure
        };
        for p in &mut image.pixels {
            *p *= scale;
        }
        return image;
    }
    for channel in 0..3 {
        let finite = image
            .pixels
            .iter()
            .map(|p| p[channel])
            .filter(|v| v.is_finite());
        let (low, high) = finite.fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
        let span = (high - low).max(f32::MIN_POSITIVE);
        for p in &mut image.pixels {
            let v = p[channel];
            // What nothing covers (an infinite depth) shows white.
            p[channel] = if v.is_finite() { (v - low) / span } else { 1.0 };
        }
    }
    // Stretched values are shown as grey levels, not as linear radiance.
    for p in &mut image.pixels {
        *p = p.map(image_io::srgb_decode);
    }
    image
}
