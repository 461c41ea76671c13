//! OpenEXR: linear RGB as 32-bit floats, written through the `exr` crate
//! uncompressed, in scan lines; any exposure is the viewer's business, as with PFM.
//! Files in any of OpenEXR's compressions are read.
//!
//! Why uncompressed: a render's radiance is noise in its low bits, which lossless
//! codecs barely shrink. On the point-lit box at 512 × 512 × 16 (3.15 MB of pixels),
//! measured whole process against PFM's 0.07 s: ZIP over 16 lines 2.55 MB in 0.12 s,
//! PIZ 2.10 MB in 0.10 s, RLE 2.70 MB in 0.09 s, uncompressed 0.07-0.08 s. An EXR
//! costs about what a PFM does, and keeps its half floats, layers and readers.

use super::Image;
use crate::error::{Error, Result};
use ::exr::prelude::{Encoding, SpecificChannels, Vec2, WritableImage};
use glam::Vec3;
use std::io::{Cursor, Seek, Write};

/// The bytes of `image` as an OpenEXR file.
pub fn encode(image: &Image) -> Result<Vec<u8>> {
    let mut out = Cursor::new(Vec::new());
    write(image, &mut out)?;
    Ok(out.into_inner())
}

/// Streams `image` as an OpenEXR file into `out`, block by block: a second copy of
/// the pixels, as bytes, would double the memory of a large render (8192 x 8192:
/// 805 MB of pixels).
pub fn write(image: &Image, out: impl Write + Seek) -> Result<()> {
    let width = image.width as usize;
    let channels = SpecificChannels::rgb(|at: Vec2<usize>| {
        let p = image.pixels[at.y() * width + at.x()];
        (p.x, p.y, p.z)
    });
    let exr = ::exr::prelude::Image::from_encoded_channels(
        (width, image.height as usize),
        Encoding::UNCOMPRESSED,
        channels,
    );
    exr.write()
        .to_buffered(out)
        .map_err(|e| Error::image(format!("cannot encode OpenEXR: {e}")))
}

/// Largest side of an EXR file read: the largest image lumiere makes.
const MAX_SIDE: usize = 16_384;

/// Largest block (a tile, or the scan lines compressed together) whose pixels an EXR
/// file may declare: the decoder allocates a block's declared size before it has
/// read a byte of it (a fuzzed header of 1.6 kB asked for 42 GB).
const MAX_BLOCK_BYTES: usize = 1 << 28;

/// Refuses an EXR file whose header declares layers, or blocks, larger than lumiere
/// reads, before any pixel is decoded.
/// The size of the file's first layer, from its header.
pub fn dimensions(bytes: &[u8]) -> Result<(u32, u32)> {
    let meta = ::exr::meta::MetaData::read_from_buffered(bytes, false)
        .map_err(|e| Error::image(format!("not a readable OpenEXR file: {e}")))?;
    let header = meta
        .headers
        .first()
        .ok_or_else(|| Error::image("an OpenEXR file without a layer"))?;
    let side = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
    Ok((
        side(header.layer_size.width()),
        side(header.layer_size.height()),
    ))
}

fn check_sizes(bytes: &[u8]) -> Result<()> {
    use ::exr::meta::{BlockDescription, MetaData};
    let meta = MetaData::read_from_buffered(bytes, false)
        .map_err(|e| Error::image(format!("not a readable OpenEXR file: {e}")))?;
    for header in &meta.headers {
        let (width, height) = (header.layer_size.width(), header.layer_size.height());
        if width > MAX_SIDE || height > MAX_SIDE {
            return Err(Error::image(format!(
                "the image is {width}x{height}, larger than {MAX_SIDE} on a side"
            )));
        }
        let pixels = match header.blocks {
            BlockDescription::Tiles(tiles) => tiles
                .tile_size
                .width()
                .checked_mul(tiles.tile_size.height()),
            BlockDescription::ScanLines => {
                header.compression.scan_lines_per_block().checked_mul(width)
            }
        };
        let block = pixels.and_then(|p| p.checked_mul(header.channels.bytes_per_pixel));
        if block.is_none_or(|b| b > MAX_BLOCK_BYTES) {
            return Err(Error::image(format!(
                "a block of this image would hold more than {} MiB of pixels",
                MAX_BLOCK_BYTES >> 20
            )));
        }
    }
    Ok(())
}

/// Reads the R, G and B channels (as f32, whatever their stored type); alpha, if
/// any, is dropped.
pub fn decode(bytes: &[u8]) -> Result<Image> {
    check_sizes(bytes)?;
    let decoded =
        image::load_from_memory_with_format(bytes, image::ImageFormat::OpenExr)?.into_rgb32f();
    if decoded.width() == 0 || decoded.height() == 0 {
        return Err(Error::image("the image is empty"));
    }
    Ok(Image {
        width: decoded.width(),
        height: decoded.height(),
        pixels: decoded.pixels().map(|p| Vec3::from_array(p.0)).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Zero, subnormal, tiny, huge, negative and non-integer values come back bit for
    /// bit.
    #[test]
    fn round_trip_is_exact() {
        let values = [
            0.0,
            f32::MIN_POSITIVE / 8.0,
            1e-30,
            1e-7,
            0.1,
            1.0 / 3.0,
            0.5,
            1.0,
            std::f32::consts::PI,
            17.25,
            6.02e23,
            3.0e38,
            -2.5,
        ];
        let (width, height) = (5, 3);
        let image = Image {
            width,
            height,
            pixels: (0..width * height)
                .map(|k| {
                    let at = |j: u32| values[(k as usize * 3 + j as usize) % values.len()];
                    Vec3::new(at(0), at(1), at(2))
                })
                .collect(),
        };
        let back = decode(&encode(&image).unwrap()).unwrap();
        assert_eq!((back.width, back.height), (width, height));
        for (a, b) in image.pixels.iter().zip(&back.pixels) {
            assert_eq!(
                a.to_array().map(f32::to_bits),
                b.to_array().map(f32::to_bits)
            );
        }
    }
}

#[cfg(test)]
mod parallel_tests {
    use super::*;

    /// The blocks compressed in parallel are the bytes one thread writes.
    #[test]
    fn parallel_blocks_write_the_same_bytes_as_one_thread() {
        let pixels = (0..300 * 200)
            .map(|i| {
                Vec3::new(
                    (i % 300) as f32 / 300.0,
                    (i / 300) as f32 * 0.01,
                    (i % 7) as f32,
                )
            })
            .collect();
        let image = Image {
            width: 300,
            height: 200,
            pixels,
        };
        let parallel = encode(&image).unwrap();
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let serial = one.install(|| encode(&image).unwrap());
        assert!(parallel == serial, "the bytes depend on the threads");
        assert_eq!(
            super::super::decode(&parallel, super::super::Format::Exr).unwrap(),
            image
        );
    }

    /// A file saved as OpenEXR, streamed block by block, holds the bytes `encode`
    /// makes in memory.
    #[test]
    fn a_saved_file_holds_the_encoded_bytes() {
        let image = Image {
            width: 70,
            height: 41,
            pixels: (0..70 * 41)
                .map(|i| Vec3::new(i as f32 * 0.37, (i % 13) as f32, -(i as f32).sqrt()))
                .collect(),
        };
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("streamed.exr");
        super::super::save(&image, &path, 1.0).unwrap();
        assert!(std::fs::read(&path).unwrap() == encode(&image).unwrap());
    }
}
