//! The scene loader: a scene file's text, then `--set` assignments, one per line
//! after the first NUL byte. Every input ends in a scene or an error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lumiere::internals::scene::{scene_from_table, tables};
use lumiere_fuzz::{MTL, OBJ, files};

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let (scene, sets) = text.split_once('\0').unwrap_or((&text, ""));
    let Ok(mut table) = tables::parse(scene, "fuzz.toml") else {
        return;
    };
    for assignment in sets.lines() {
        if tables::set(&mut table, assignment).is_err() {
            return;
        }
    }
    let _ = scene_from_table(table, &files(OBJ.as_bytes(), MTL.as_bytes()));
});
