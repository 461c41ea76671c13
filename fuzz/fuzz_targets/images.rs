//! The image loaders: PNG and EXR as `lumiere compare` reads them, and texture
//! images (PNG, JPEG, GIF, whatever the bytes say) as a scene's textures are read.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lumiere::internals::image_io::{self, Format};
use lumiere::internals::texture::Texels;

fuzz_target!(|data: &[u8]| {
    let _ = image_io::decode(data, Format::Png);
    let _ = image_io::decode(data, Format::Exr);
    let _ = Texels::decode(data);
});
