//! The PFM reader (`lumiere compare`, environment maps): any bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lumiere::internals::image_io::{self, Format};

fuzz_target!(|data: &[u8]| {
    let _ = image_io::decode(data, Format::Pfm);
});
