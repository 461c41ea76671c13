//! PFM (portable float map): a text header `PF\n<w> <h>\n<scale>\n` then
//! little-endian f32 RGB triples (negative scale), rows from the bottom up.

use super::Image;
use crate::error::{Error, Result};
use glam::Vec3;

pub fn encode(image: &Image) -> Vec<u8> {
    let mut out = Vec::new();
    write(image, &mut out).expect("writing to memory");
    out
}

/// Writes row by row into `out` (no copy of the whole image).
pub fn write(image: &Image, mut out: impl std::io::Write) -> std::io::Result<()> {
    write!(out, "PF\n{} {}\n-1.0\n", image.width, image.height)?;
    let mut bytes = Vec::with_capacity(12 * image.width as usize);
    for row in image.pixels.chunks(image.width.max(1) as usize).rev() {
        bytes.clear();
        for p in row {
            for c in p.to_array() {
                bytes.extend_from_slice(&c.to_le_bytes());
            }
        }
        out.write_all(&bytes)?;
    }
    Ok(())
}

/// A PFM header: width, height, the scale (its sign the byte order) and where the
/// data starts.
pub struct Header {
    pub width: u32,
    pub height: u32,
    pub scale: f32,
    data: usize,
}

/// Reads the header alone: nothing is allocated for the pixels it declares.
pub fn header(bytes: &[u8]) -> Result<Header> {
    let mut fields = Vec::new();
    let mut at = 0;
    // Three whitespace-separated header tokens after "PF": width, height, scale.
    while fields.len() < 4 {
        while at < bytes.len() && bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        let start = at;
        while at < bytes.len() && !bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        if at == start {
            return Err(Error::image("not a PFM file (short header)"));
        }
        let field =
            std::str::from_utf8(&bytes[start..at]).map_err(|e| Error::image(e.to_string()))?;
        fields.push(field.to_string());
    }
    at += 1; // the single whitespace byte that ends the header
    if fields[0] != "PF" {
        return Err(Error::image(format!(
            "not a colour PFM file (header {})",
            fields[0]
        )));
    }
    let bad = |what: &str, e: &dyn std::fmt::Display| Error::image(format!("bad PFM {what}: {e}"));
    let width: u32 = fields[1].parse().map_err(|e| bad("width", &e))?;
    let height: u32 = fields[2].parse().map_err(|e| bad("height", &e))?;
    let scale: f32 = fields[3].parse().map_err(|e| bad("scale", &e))?;
    // Its sign gives the byte order, its size nothing more: 0 or NaN has no sign.
    if scale == 0.0 || !scale.is_finite() {
        return Err(Error::image(format!(
            "bad PFM scale: {} (a non-zero number: negative for little-endian data, positive for big-endian)",
            fields[3]
        )));
    }
    if width == 0 || height == 0 {
        return Err(Error::image("the image is empty"));
    }
    Ok(Header {
        width,
        height,
        scale,
        data: at,
    })
}

pub fn decode(bytes: &[u8]) -> Result<Image> {
    let Header {
        width,
        height,
        scale,
        data: at,
    } = header(bytes)?;
    // The header's size must match the data there is before anything is allocated
    // for it: a crafted header (4294967295 x 4294967295) would overflow or exhaust
    // memory.
    let needed = (width as u64)
        .checked_mul(height as u64)
        .and_then(|count| count.checked_mul(12));
    let available = bytes.len().saturating_sub(at) as u64;
    if needed.is_none_or(|n| n > available) {
        return Err(Error::image(format!(
            "a {width} x {height} PFM image needs {} bytes of data, only {available} follow its header",
            needed.map_or("more than 2^64".to_string(), |n| n.to_string())
        )));
    }
    let count = width as usize * height as usize;
    let data = &bytes[at..];
    let read = |k: usize| {
        let b = [
            data[4 * k],
            data[4 * k + 1],
            data[4 * k + 2],
            data[4 * k + 3],
        ];
        if scale < 0.0 {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        }
    };
    let mut pixels = vec![Vec3::ZERO; count];
    for y in 0..height as usize {
        let source = (height as usize - 1 - y) * width as usize;
        for x in 0..width as usize {
            let k = 3 * (source + x);
            pixels[y * width as usize + x] = Vec3::new(read(k), read(k + 1), read(k + 2));
        }
    }
    Ok(Image {
        width,
        height,
        pixels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_is_exact() {
        let image = Image {
            width: 3,
            height: 2,
            pixels: (0..6)
                .map(|k| Vec3::new(k as f32, 0.5, -1e-3 * k as f32))
                .collect(),
        };
        assert_eq!(decode(&encode(&image)).unwrap(), image);
    }

    /// A header whose size overflows, or does not match the data after it, is an
    /// error before anything is allocated for it.
    #[test]
    fn a_header_that_does_not_match_its_data_is_refused() {
        for bytes in [
            &b"PF\n4294967295 4294967295\n-1.0\n0123456789ab"[..],
            &b"PF\n2 1\n-1.0\n0123456789ab"[..],
            &b"PF\n4294967295 1\n-1.0\n0123456789ab"[..],
        ] {
            let e = decode(bytes).err().unwrap();
            assert!(e.to_string().contains("PFM image needs"), "{e}");
        }
    }
}
