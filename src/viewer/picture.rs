//! What the viewer puts on screen: an image as 8-bit sRGB after the exposure (as
//! PNG output encodes it), and a frame's intermediate buffer as a picture, with a
//! line saying how its values map to colours.

use crate::image_io::{self, Buffer, BufferData, Image};

/// `image` as RGBA bytes, sRGB after `exposure`, alpha opaque.
pub fn rgba(image: &Image, exposure: f32) -> Vec<u8> {
    let mut bytes = Vec::with_capacity(image.pixels.len() * 4);
    for &p in &image.pixels {
        let [r, g, b] = image_io::to_srgb8(p, exposure);
        bytes.extend_from_slice(&[r, g, b, 255]);
    }
    bytes
}

/// A buffer as a picture, and its legend: ids and counts colour-mapped;
/// visibility and texture coordinates as they are; normals from [-1, 1];
/// radiance at the scene's exposure; other values (depths, positions, levels)
/// stretched over their range, as grey levels.
pub fn buffer_picture(buffer: &Buffer, exposure: f32) -> (Image, String) {
    let mut image = buffer.to_image(image_io::Format::Png);
    let name = buffer.name.as_str();
    match &buffer.data {
        BufferData::Ids(ids) => {
            let distinct = distinct_ids(ids);
            return (
                image,
                format!("{distinct} ids, one colour each; black: nothing"),
            );
        }
        BufferData::Counts(counts) => {
            let (low, high) = counts
                .iter()
                .fold((i32::MAX, i32::MIN), |(l, h), &c| (l.min(c), h.max(c)));
            return (
                image,
                format!("counts {low} to {high}, one colour each; black: 0"),
            );
        }
        BufferData::Values { .. } => {}
    }
    if name.starts_with("visibility") || name == "uv" {
        let legend = if name == "uv" {
            "red u, green v, from 0 to 1".to_string()
        } else {
            "black: the light hidden, white: all of it seen".to_string()
        };
        return (image, legend);
    }
    if name == "normal" {
        for p in &mut image.pixels {
            *p = (*p + 1.0) * 0.5;
        }
        return (image, "x, y, z from -1 to 1 as red, green, blue".into());
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
        return (image, format!("radiance at exposure {exposure}"));
    }
    let mut ranges = Vec::new();
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
        ranges.push((low, high));
    }
    // Stretched values are shown as grey levels, not as linear radiance.
    for p in &mut image.pixels {
        *p = p.map(image_io::srgb_decode);
    }
    let legend = if ranges.iter().all(|r| *r == ranges[0]) || buffer_channels(buffer) == 1 {
        format!(
            "black {} to white {}",
            number(ranges[0].0),
            number(ranges[0].1)
        )
    } else {
        let names = ["red", "green", "blue"];
        let parts: Vec<String> = ranges
            .iter()
            .zip(names)
            .map(|((l, h), n)| format!("{n} {} to {}", number(*l), number(*h)))
            .collect();
        parts.join(", ")
    };
    (image, legend)
}

fn buffer_channels(buffer: &Buffer) -> usize {
    match buffer.data {
        BufferData::Values { channels, .. } => channels,
        BufferData::Ids(_) | BufferData::Counts(_) => 1,
    }
}

fn distinct_ids(ids: &[u32]) -> usize {
    let mut seen: Vec<u32> = ids
        .iter()
        .copied()
        .filter(|&i| i != image_io::NO_ID)
        .collect();
    seen.sort_unstable();
    seen.dedup();
    seen.len()
}

/// A value for a legend: four significant digits; "none" when nothing was finite.
fn number(v: f32) -> String {
    if v.is_finite() {
        format!("{}", (v as f64 * 1e4).round() / 1e4)
    } else {
        "none".into()
    }
}

/// The values of `buffer` unrounded, `channels` floats a pixel: ids (-1 where
/// none) and counts as numbers.
pub fn buffer_values(buffer: &Buffer) -> (usize, Vec<f32>) {
    match &buffer.data {
        BufferData::Ids(ids) => (
            1,
            ids.iter()
                .map(|&i| if i == image_io::NO_ID { -1.0 } else { i as f32 })
                .collect(),
        ),
        BufferData::Counts(counts) => (1, counts.iter().map(|&c| c as f32).collect()),
        BufferData::Values { channels, data } => (*channels, data.clone()),
    }
}
