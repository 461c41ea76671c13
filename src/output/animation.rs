//! Animated GIF of a sequence of images (the convergence of a progressive solve).

use super::{Image, to_srgb8};
use crate::{Error, Result};
use image::codecs::gif::{GifEncoder, Repeat};
use image::{Delay, Frame, RgbaImage};

/// The frames, each shown `delay_ms`, looping; sRGB after `exposure` (GIF's
/// 256-colour palette is chosen per frame by the encoder).
pub fn encode_gif(frames: &[Image], exposure: f32, delay_ms: u32) -> Result<Vec<u8>> {
    if frames.is_empty() {
        return Err(Error::image("no frames to animate"));
    }
    let mut bytes = Vec::new();
    {
        let mut encoder = GifEncoder::new_with_speed(&mut bytes, 10);
        encoder.set_repeat(Repeat::Infinite)?;
        for image in frames {
            let rgba = RgbaImage::from_fn(image.width, image.height, |x, y| {
                let [r, g, b] = to_srgb8(image.pixels[(y * image.width + x) as usize], exposure);
                image::Rgba([r, g, b, 255])
            });
            encoder.encode_frame(Frame::from_parts(
                rgba,
                0,
                0,
                Delay::from_numer_denom_ms(delay_ms, 1),
            ))?;
        }
    }
    Ok(bytes)
}
