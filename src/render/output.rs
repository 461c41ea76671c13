//! What a frame gives: its image and buffers, and the list of buffers it can give.
//! Below every other part of the renderer, so that the integrators, the frame and
//! the buffers all name it without reaching each other.

use crate::image_io::{Buffer, Image};

/// A frame: its linear radiance image and the buffers asked for.
pub struct Frame {
    /// Linear radiance, pixel by pixel.
    pub image: Image,
    /// The buffers asked for, in the order asked.
    pub buffers: Vec<Buffer>,
}

impl Frame {
    /// The buffer named `name`, if the frame made it.
    pub fn buffer(&self, name: &str) -> Option<&Buffer> {
        self.buffers.iter().find(|b| b.name == name)
    }
}

/// A buffer a scene's frame can give, and what it holds.
#[derive(Clone, Debug, PartialEq)]
pub struct BufferInfo {
    /// The name a frame is asked for it by.
    pub name: String,
    /// What it holds, in a line.
    pub description: String,
}
