//! The PFM reader (`lumiere compare`, environment maps): any bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lumiere::output::{self, Format};

fuzz_target!(|data: &[u8]| {
    let _ = output::decode(data, Format::Pfm);
});
