//! Named intermediate buffers: what a method computed on its way to the image (the
//! visible polygon per sample, depths, a light's visibility, shadow-map faces,
//! shadow-volume counts, hemi-cube item buffers…), written out for teaching and
//! debugging. Ids and counts are written as colour-mapped PNG (or their numbers in a
//! float image); values as linear PFM or EXR (or clamped grey/RGB in a PNG).

use super::{Format, Image, srgb_decode};
use glam::Vec3;

/// Id meaning "nothing here" in an id buffer.
pub const NO_ID: u32 = u32::MAX;

#[derive(Clone, Debug, PartialEq)]
/// What a buffer holds, one value (or one or three floats) per sample.
pub enum BufferData {
    /// One id per sample (polygon, element), `NO_ID` where none.
    Ids(Vec<u32>),
    /// One signed count per sample (shadow volumes containing it).
    Counts(Vec<i32>),
    /// One or three floats per sample, row-major and interleaved.
    /// Floats, `channels` of them per sample, row-major and interleaved.
    Values {
        /// Floats per sample: 1 or 3.
        channels: usize,
        /// The floats.
        data: Vec<f32>,
    },
}

#[derive(Clone, Debug, PartialEq)]
/// A named intermediate buffer of a frame (`--aov`): ids, counts or values per pixel.
pub struct Buffer {
    /// Its name (`visibility-0`, `shadow-volume-counts-0`, `polygon-ids`).
    pub name: String,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Its values, row-major, row 0 at the top.
    pub data: BufferData,
}

impl Buffer {
    /// The format a buffer is best written as when the user names no file.
    pub fn natural_format(&self) -> Format {
        match self.data {
            BufferData::Ids(_) | BufferData::Counts(_) => Format::Png,
            BufferData::Values { .. } => Format::Pfm,
        }
    }

    /// What the pixels of an image file of this buffer hold, and the exposure to
    /// write it with.
    pub fn to_image(&self, format: Format) -> Image {
        let numeric = format != Format::Png;
        let pixels: Vec<Vec3> = match &self.data {
            BufferData::Ids(ids) if numeric => ids
                .iter()
                .map(|&i| Vec3::splat(if i == NO_ID { -1.0 } else { i as f32 }))
                .collect(),
            BufferData::Ids(ids) => ids.iter().map(|&i| id_colour(i)).collect(),
            BufferData::Counts(counts) if numeric => {
                counts.iter().map(|&c| Vec3::splat(c as f32)).collect()
            }
            BufferData::Counts(counts) => counts.iter().map(|&c| count_colour(c)).collect(),
            BufferData::Values { channels: 1, data } => {
                data.iter().map(|&v| Vec3::splat(v)).collect()
            }
            BufferData::Values { data, .. } => data
                .chunks_exact(3)
                .map(|c| Vec3::new(c[0], c[1], c[2]))
                .collect(),
        };
        Image {
            width: self.width,
            height: self.height,
            pixels,
        }
    }
}

/// A distinct, bright colour per id (a hash of it), black for `NO_ID`; as linear
/// values that encode to those sRGB colours.
fn id_colour(id: u32) -> Vec3 {
    if id == NO_ID {
        return Vec3::ZERO;
    }
    let mut h = (id as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    h ^= h >> 29;
    let channel = |shift: u32| 64 + ((h >> shift) & 0xBF) as u32;
    srgb8(channel(0), channel(16), channel(32))
}

/// Counts: 0 black, positive counts red getting brighter (inside 1, 2, 3… volumes),
/// negative ones blue (a count below zero means a leaking volume).
fn count_colour(count: i32) -> Vec3 {
    let level = |n: i32| 80 + 40 * (n.unsigned_abs().min(4) - 1);
    match count {
        0 => Vec3::ZERO,
        n if n > 0 => srgb8(level(n), level(n) / 4, 0),
        n => srgb8(0, level(n) / 2, level(n)),
    }
}

fn srgb8(r: u32, g: u32, b: u32) -> Vec3 {
    let c = |v: u32| srgb_decode(v as f32 / 255.0);
    Vec3::new(c(r), c(g), c(b))
}
