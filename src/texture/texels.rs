//! A texture image: linear RGB texels, decoded from PNG or JPEG (sRGB to linear) or
//! generated, with the two basic lookups (nearest texel, bilinear) and the wrap modes.
//!
//! Conventions: (u, v) = (0, 0) is the image's bottom-left corner and (1, 1) its
//! top-right; texel (i, j) has row j = 0 at the top of the image and its centre at
//! u = (i + 0.5) / width, v = 1 − (j + 0.5) / height.

use crate::error::{Error, Result};
use crate::image_io::srgb_decode;
use glam::{DVec2, Vec3};

/// What a lookup outside [0, 1] does.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Wrap {
    /// The texture tiles the plane.
    #[default]
    Repeat,
    /// Coordinates are clamped to the edge texels.
    Clamp,
}

impl Wrap {
    /// The texel index `i` of a row or column of `n` texels.
    pub fn index(self, i: i64, n: u32) -> usize {
        let n = n as i64;
        match self {
            Wrap::Repeat => i.rem_euclid(n) as usize,
            Wrap::Clamp => i.clamp(0, n - 1) as usize,
        }
    }
}

/// Largest side of a texture image accepted.
pub const MAX_TEXTURE_SIDE: u32 = 16_384;

/// The PNG or JPEG header's width and height, without decoding the image (so that a
/// size can be refused before its memory is taken).
pub fn image_size(bytes: &[u8]) -> Result<(u32, u32)> {
    let format = texture_format(bytes)?;
    // A PNG's first chunk is IHDR, width and height big-endian at bytes 16 and 20
    // (the PNG decoder's own reader looks on for the first data chunk).
    if format == image::ImageFormat::Png && bytes.len() >= 24 && &bytes[12..16] == b"IHDR" {
        let word = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
        return Ok((word(16), word(20)));
    }
    image::ImageReader::with_format(std::io::Cursor::new(bytes), format)
        .into_dimensions()
        .map_err(|e| Error::image(format!("not a readable PNG or JPEG image: {e}")))
}

/// Only the formats a texture is documented to be: the other decoders the image crate
/// carries (EXR's among them) trust sizes their headers declare.
fn texture_format(bytes: &[u8]) -> Result<image::ImageFormat> {
    image::guess_format(bytes)
        .ok()
        .filter(|f| matches!(f, image::ImageFormat::Png | image::ImageFormat::Jpeg))
        .ok_or_else(|| Error::image("not a PNG or JPEG image"))
}

#[derive(Clone, Debug, PartialEq)]
pub struct Texels {
    pub width: u32,
    pub height: u32,
    /// Row-major, row 0 at the top.
    pub texels: Vec<Vec3>,
}

impl Texels {
    /// Decodes a PNG or JPEG file's bytes; 8-bit channels are sRGB-encoded, so they are
    /// decoded to linear radiometric values.
    pub fn decode(bytes: &[u8]) -> Result<Texels> {
        let format = texture_format(bytes)?;
        let image = image::load_from_memory_with_format(bytes, format)
            .map_err(|e| Error::image(format!("not a readable PNG or JPEG image: {e}")))?;
        let (width, height) = (image.width(), image.height());
        if width == 0 || height == 0 {
            return Err(Error::image(format!(
                "the image is empty ({width}x{height})"
            )));
        }
        if width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE {
            return Err(Error::image(format!(
                "the image is {width}x{height}, larger than {MAX_TEXTURE_SIDE} on a side"
            )));
        }
        let rgb = image.to_rgb8();
        let table: Vec<f32> = (0..=255u8).map(|c| srgb_decode(c as f32 / 255.0)).collect();
        let texels = rgb
            .pixels()
            .map(|p| {
                Vec3::new(
                    table[p[0] as usize],
                    table[p[1] as usize],
                    table[p[2] as usize],
                )
            })
            .collect();
        Ok(Texels {
            width,
            height,
            texels,
        })
    }

    /// `width × height` texels, each the value of `f` at its centre's (u, v).
    pub fn generate(width: u32, height: u32, f: impl Fn(DVec2) -> Vec3) -> Texels {
        let mut texels = Vec::with_capacity(width as usize * height as usize);
        for j in 0..height {
            for i in 0..width {
                let uv = DVec2::new(
                    (i as f64 + 0.5) / width as f64,
                    1.0 - (j as f64 + 0.5) / height as f64,
                );
                texels.push(f(uv));
            }
        }
        Texels {
            width,
            height,
            texels,
        }
    }

    /// Texel (i, j), wrapped.
    pub fn at(&self, i: i64, j: i64, wrap: Wrap) -> Vec3 {
        self.at_wrapped(i, j, [wrap, wrap])
    }

    /// Texel (i, j), wrapped along the columns by `wrap[0]`, along the rows by
    /// `wrap[1]` (a latitude-longitude map repeats in longitude, clamps at the poles).
    pub fn at_wrapped(&self, i: i64, j: i64, wrap: [Wrap; 2]) -> Vec3 {
        let (i, j) = (wrap[0].index(i, self.width), wrap[1].index(j, self.height));
        self.texels[j * self.width as usize + i]
    }

    /// `uv` in continuous texel coordinates, where texel (i, j)'s centre is at
    /// (i + 0.5, j + 0.5).
    pub fn texel_space(&self, uv: DVec2) -> DVec2 {
        DVec2::new(uv.x * self.width as f64, (1.0 - uv.y) * self.height as f64)
    }

    /// The texel that contains `uv` (point sampling).
    pub fn nearest(&self, uv: DVec2, wrap: Wrap) -> Vec3 {
        let t = self.texel_space(uv);
        self.at(t.x.floor() as i64, t.y.floor() as i64, wrap)
    }

    /// Bilinear interpolation between the four texel centres around `uv`.
    pub fn bilinear(&self, uv: DVec2, wrap: Wrap) -> Vec3 {
        self.bilinear_wrapped(uv, [wrap, wrap])
    }

    /// `bilinear` with a wrap mode per axis (columns, rows).
    pub fn bilinear_wrapped(&self, uv: DVec2, wrap: [Wrap; 2]) -> Vec3 {
        let t = self.texel_space(uv) - 0.5;
        let (i, j) = (t.x.floor(), t.y.floor());
        let (fx, fy) = ((t.x - i) as f32, (t.y - j) as f32);
        let (i, j) = (i as i64, j as i64);
        let top = self
            .at_wrapped(i, j, wrap)
            .lerp(self.at_wrapped(i + 1, j, wrap), fx);
        let bottom = self
            .at_wrapped(i, j + 1, wrap)
            .lerp(self.at_wrapped(i + 1, j + 1, wrap), fx);
        top.lerp(bottom, fy)
    }

    pub fn mean(&self) -> Vec3 {
        let sum: glam::DVec3 = self.texels.iter().map(|t| t.as_dvec3()).sum();
        (sum / self.texels.len() as f64).as_vec3()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texel_centres_round_trip() {
        let t = Texels::generate(4, 2, |uv| Vec3::new(uv.x as f32, uv.y as f32, 0.0));
        // Bilinear at a texel centre returns that texel.
        let c = t.texels[5]; // i = 1, j = 1
        assert_eq!(
            t.bilinear(DVec2::new(c.x as f64, c.y as f64), Wrap::Clamp),
            c
        );
        assert_eq!(t.nearest(DVec2::new(0.3, 0.2), Wrap::Repeat), c);
    }

    #[test]
    fn wrap_modes() {
        assert_eq!(Wrap::Repeat.index(-1, 4), 3);
        assert_eq!(Wrap::Repeat.index(9, 4), 1);
        assert_eq!(Wrap::Clamp.index(-3, 4), 0);
        assert_eq!(Wrap::Clamp.index(9, 4), 3);
    }
}
