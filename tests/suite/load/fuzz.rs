//! Fuzzing the entry points that read user input, with arbitrary and mutated
//! bytes: the scene loader (TOML and `--set`), the OBJ/MTL path, the PFM reader and
//! the image decoders. Each must answer with a result, never a panic.
//!
//! The suite runs a few hundred cases per target; a long run sets `FUZZ_CASES`:
//! `FUZZ_CASES=1000000 cargo test --release --test suite load::fuzz` (see docs/verification.md for what it
//! found). Coverage-guided fuzzing (cargo-fuzz) needs a nightly toolchain; these
//! harnesses drive the same entry points with proptest's generators instead.

use crate::support;

use lumiere::image_io::{self, Format};
use lumiere::scene::{scene_from_table, tables};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

use std::collections::HashMap;
use support::{Files, error_line};

/// The suite's cases are the same on every run (a fixed seed); a long run may set
/// `FUZZ_SEED` to explore elsewhere.
fn config() -> ProptestConfig {
    let number = |name: &str| std::env::var(name).ok().and_then(|v| v.parse::<u64>().ok());
    ProptestConfig {
        cases: number("FUZZ_CASES").unwrap_or(300) as u32,
        rng_seed: RngSeed::Fixed(number("FUZZ_SEED").unwrap_or(1)),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// The same bytes as ever (a leading newline), as the mutations are placed by offset.
fn scene_text() -> String {
    "\n".to_string()
        + &support::camera([0.0, 1.0, 4.0], [0.0, 0.0, 0.0], 40.0, 16, 12)
        + r#"[render]
shading = "gouraud"
supersample = 2

[shadows]
method = "ray-cast"
light_samples = 2

[textures.checks]
procedural = "checkerboard"
cells = 4

[materials.grey]
diffuse = [0.5, 0.5, 0.5]
diffuse_texture = "checks"

[[lights]]
type = "spot"
position = [0.0, 2.0, 0.0]
axis = [0.0, -1.0, 0.0]
cone_angle = 30.0
intensity = [5.0, 5.0, 5.0]

[[lights]]
type = "polygon"
vertices = [[-0.5, 3.0, -0.5], [0.5, 3.0, -0.5], [0.5, 3.0, 0.5], [-0.5, 3.0, 0.5]]
radiance = [1.0, 1.0, 1.0]

[[objects]]
shape = "sphere"
material = "grey"
resolution = 8

[[objects]]
shape = "obj"
name = "model"
file = "m.obj"
"#
}

const OBJ: &str = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\nusemtl red\nf 1/1/1 2/2/1 3/3/1 4/1/1\n";
const MTL: &str = "newmtl red\nKd 0.6 0.1 0.1\nKe 0 0 0\n";

/// The text with `length` bytes at `at` replaced by `insert` (cut at char
/// boundaries): a mutation of valid input, which reaches deeper than noise.
fn mutate(text: &str, at: usize, length: usize, insert: &str) -> String {
    let mut at = at % (text.len() + 1);
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    let mut end = (at + length).min(text.len());
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    format!("{}{}{}", &text[..at], insert, &text[end..])
}

fn files(obj: &str, mtl: &str) -> Files {
    Files(HashMap::from([
        ("m.obj".to_string(), obj.as_bytes().to_vec()),
        ("m.mtl".to_string(), mtl.as_bytes().to_vec()),
    ]))
}

/// Tokens that make mutations meaningful to the scene format.
fn token() -> impl Strategy<Value = String> {
    prop_oneof![
        Just(String::new()),
        Just("-1".to_string()),
        Just("0".to_string()),
        Just("1e308".to_string()),
        Just("nan".to_string()),
        Just("[".to_string()),
        Just("]".to_string()),
        Just("\"".to_string()),
        Just("[[objects]]\nshape = \"box\"\n".to_string()),
        Just("{ }".to_string()),
        "[ -~]{0,12}",
    ]
}

fn load(text: &str, files: &Files, sets: &[String]) {
    let Ok(mut table) = tables::parse(text, "fuzz.toml") else {
        return;
    };
    for assignment in sets {
        if tables::set(&mut table, assignment).is_err() {
            return;
        }
    }
    let _ = scene_from_table(table, files);
}

proptest! {
    #![proptest_config(config())]

    /// Scene files: arbitrary text, and mutations of a valid scene.
    #[test]
    fn scene_files(
        noise in "\\PC{0,200}",
        at in 0usize..2000,
        length in 0usize..20,
        insert in token(),
    ) {
        let files = files(OBJ, MTL);
        load(&noise, &files, &[]);
        load(&mutate(&scene_text(), at, length, &insert), &files, &[]);
    }

    /// `--set` assignments on a valid scene.
    #[test]
    fn overrides(
        key in prop_oneof![
            Just("camera.width".to_string()),
            Just("objects.0.resolution".to_string()),
            Just("lights.1.vertices".to_string()),
            Just("materials.grey.diffuse".to_string()),
            Just("shadows.light_samples".to_string()),
            "[a-z_.0-9]{0,24}",
        ],
        value in token(),
    ) {
        load(&scene_text(), &files(OBJ, MTL), &[format!("{key}={value}")]);
        load(&scene_text(), &files(OBJ, MTL), &[format!("{key}{value}")]);
    }

    /// OBJ and MTL files: mutations of a valid pair, and arbitrary text.
    #[test]
    fn obj_and_mtl(
        at in 0usize..200,
        length in 0usize..10,
        insert in prop_oneof![token(), Just("f 1 2 9\n".to_string()), Just("v nan 0 0\n".to_string()), Just("f -1 -2 -3\n".to_string())],
        noise in "\\PC{0,120}",
    ) {
        load(&scene_text(), &files(&mutate(OBJ, at, length, &insert), MTL), &[]);
        load(&scene_text(), &files(OBJ, &mutate(MTL, at, length, &insert)), &[]);
        load(&scene_text(), &files(&noise, &noise), &[]);
    }

    /// PFM: headers with arbitrary sizes and scales, and arbitrary bytes after them.
    #[test]
    fn pfm(
        width in prop_oneof![0u64..5, Just(u32::MAX as u64), Just(u64::MAX), any::<u64>()],
        height in prop_oneof![0u64..5, Just(u32::MAX as u64), any::<u64>()],
        scale in prop_oneof![Just("-1.0".to_string()), Just("1.0".to_string()), Just("nan".to_string()), "[ -~]{0,6}"],
        body in prop::collection::vec(any::<u8>(), 0..200),
        raw in prop::collection::vec(any::<u8>(), 0..64),
    ) {
        let mut bytes = format!("PF\n{width} {height}\n{scale}\n").into_bytes();
        bytes.extend(&body);
        let _ = image_io::decode(&bytes, Format::Pfm);
        let _ = image_io::decode(&raw, Format::Pfm);
    }

    /// PNG and EXR decoders: a valid file with bytes flipped, and arbitrary bytes.
    #[test]
    fn images(
        flips in prop::collection::vec((0usize..4096, any::<u8>()), 0..6),
        raw in prop::collection::vec(any::<u8>(), 0..128),
    ) {
        let image = image_io::Image { width: 3, height: 2, pixels: vec![glam::Vec3::new(0.2, 0.5, 1.5); 6] };
        for format in [Format::Png, Format::Exr] {
            let mut bytes = image_io::encode(&image, format, 1.0).unwrap();
            for &(at, value) in &flips {
                let n = bytes.len();
                bytes[at % n] ^= value;
            }
            let _ = image_io::decode(&bytes, format);
            let _ = image_io::decode(&raw, format);
        }
    }
}

/// Found by `obj_and_mtl`: tobj's MTL parser panicked on a colour with fewer than
/// three numbers; the line is refused with its number instead.
#[test]
fn a_short_mtl_colour_is_refused_by_line() {
    let mtl = "newmtl red\nKd 0.6 0.1\n";
    let table = tables::parse(&scene_text(), "fuzz.toml").unwrap();
    let error = scene_from_table(table, &files(OBJ, mtl)).err().unwrap();
    let chain = error_line(&error);
    assert!(
        chain.contains("line 2: `Kd` needs three numbers (r g b), got 2"),
        "{chain}"
    );
}

/// A vertex that is not a number drops its face with a warning that says so (not
/// "zero area"); a missing texture image names the texture.
#[test]
fn messages_name_the_real_cause() {
    let obj = "mtllib m.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n";
    let table = tables::parse(&scene_text(), "fuzz.toml").unwrap();
    let scene = scene_from_table(table, &files(obj, MTL)).unwrap();
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w.contains("a vertex that is not a finite number")),
        "{:?}",
        scene.warnings
    );
    assert!(!scene.warnings.iter().any(|w| w.contains("zero area")));
    let text = scene_text().replace(
        "procedural = \"checkerboard\"\ncells = 4",
        "image = \"nowhere.png\"",
    );
    let error = scene_from_table(tables::parse(&text, "fuzz.toml").unwrap(), &files(OBJ, MTL))
        .err()
        .unwrap();
    let chain = error_line(&error);
    assert!(chain.contains("textures.checks.image"), "{chain}");
}

/// Found by the coverage-guided `images` target (`tools/fuzz.sh`): an EXR header of
/// 1.6 kB whose ZIP block declared 42 GB of pixels, which the decoder allocated
/// before reading them. Refused from its header now, by `compare` and as a texture.
#[test]
fn an_exr_declaring_a_huge_block_is_refused_from_its_header() {
    let bytes = include_bytes!("../../references/fuzz/exr-huge-block.exr");
    let error = image_io::decode(bytes, Format::Exr)
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("larger than 16384 on a side") || error.contains("a block of this image"),
        "{error}"
    );
    assert!(lumiere::texture::Texels::decode(bytes).is_err());
}

/// An MTL file's `map_Kd` is loaded (relative to the OBJ file) and scales its
/// material's diffuse colour, as users of OBJ files expect.
#[test]
fn mtl_diffuse_maps_are_loaded() {
    let image = image_io::Image {
        width: 2,
        height: 2,
        pixels: vec![glam::Vec3::new(0.25, 0.5, 1.0); 4],
    };
    let png = image_io::encode(&image, Format::Png, 1.0).unwrap();
    let mut files = files(OBJ, "newmtl red\nKd 0.6 0.1 0.1\nmap_Kd maps/wood.png\n");
    files.0.insert("maps/wood.png".to_string(), png);
    let scene =
        scene_from_table(tables::parse(&scene_text(), "fuzz.toml").unwrap(), &files).unwrap();
    let red = scene.materials.iter().find(|m| m.name == "red").unwrap();
    let texture = &scene.textures[red.diffuse_texture.expect("map_Kd loaded")];
    assert_eq!((texture.texels.width, texture.texels.height), (2, 2));
    let missing = files_without(&files, "maps/wood.png");
    let error = scene_from_table(tables::parse(&scene_text(), "fuzz.toml").unwrap(), &missing)
        .err()
        .unwrap();
    let chain = error_line(&error);
    assert!(
        chain.contains("map_Kd") && chain.contains("maps/wood.png"),
        "{chain}"
    );
}

fn files_without(files: &Files, name: &str) -> Files {
    let mut kept = files.0.clone();
    kept.remove(name);
    Files(kept)
}
