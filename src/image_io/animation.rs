//! Animated GIF of a sequence of images (the convergence of a progressive solve),
//! encoded frame by frame as the images come: only the frame being encoded is held,
//! however many there are.

use super::{Image, to_srgb8};
use crate::error::{Error, Result};
use std::io::Write;

/// A looping GIF being written to `W`; each frame shown `delay_ms`, sRGB after
/// `exposure`, with a 256-colour palette chosen per frame.
pub struct Animation<W: Write> {
    out: Option<W>,
    encoder: Option<gif::Encoder<W>>,
    /// The first frame's size, which every frame has.
    size: (u16, u16),
    exposure: f32,
    delay_ms: u32,
}

impl<W: Write> Animation<W> {
    pub fn new(out: W, exposure: f32, delay_ms: u32) -> Animation<W> {
        Animation {
            out: Some(out),
            encoder: None,
            size: (0, 0),
            exposure,
            delay_ms,
        }
    }

    /// Encodes the next frame; every frame has the first one's size.
    pub fn add(&mut self, image: &Image) -> Result<()> {
        let side = |n: u32| u16::try_from(n).map_err(|_| gif_error("an image side over 65535"));
        let (width, height) = (side(image.width)?, side(image.height)?);
        if self.encoder.is_none() {
            let out = self.out.take().expect("the output before the first frame");
            let mut encoder = gif::Encoder::new(out, width, height, &[]).map_err(gif_error)?;
            encoder
                .set_repeat(gif::Repeat::Infinite)
                .map_err(gif_error)?;
            self.encoder = Some(encoder);
            self.size = (width, height);
        }
        if self.size != (width, height) {
            return Err(gif_error("frames of different sizes"));
        }
        let encoder = self.encoder.as_mut().expect("made above");
        let mut rgba: Vec<u8> = image
            .pixels
            .iter()
            .flat_map(|&p| {
                let [r, g, b] = to_srgb8(p, self.exposure);
                [r, g, b, 255]
            })
            .collect();
        let mut frame = gif::Frame::from_rgba_speed(width, height, &mut rgba, 10);
        frame.delay = u16::try_from(self.delay_ms / 10).unwrap_or(u16::MAX);
        encoder.write_frame(&frame).map_err(gif_error)
    }

    /// Ends the file (its trailer) and hands back the output.
    pub fn finish(self) -> Result<W> {
        let encoder = self
            .encoder
            .ok_or_else(|| Error::image("no frames to animate"))?;
        encoder.into_inner().map_err(gif_error)
    }
}

fn gif_error(e: impl std::fmt::Display) -> Error {
    Error::image(format!("cannot encode the animation: {e}"))
}
