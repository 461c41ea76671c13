//! The OBJ/MTL path: an OBJ file, then its MTL file after the first NUL byte,
//! loaded by a scene that names the OBJ file.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lumiere::internals::scene::{scene_from_table, tables};
use lumiere_fuzz::{OBJ_SCENE, files};

fuzz_target!(|data: &[u8]| {
    let split = data.iter().position(|&b| b == 0).unwrap_or(data.len());
    let (obj, mtl) = (&data[..split], data.get(split + 1..).unwrap_or(&[]));
    let table = tables::parse(OBJ_SCENE, "fuzz.toml").expect("the fixed scene parses");
    let _ = scene_from_table(table, &files(obj, mtl));
});
