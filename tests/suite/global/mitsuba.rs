//! lumiere against a physically based renderer, inside the suite: the quad-lit
//! Cornell box, direct light with exact soft shadows, against Mitsuba 3's direct
//! illumination held in tests/references/cornell-box-direct-mitsuba.pfm (made by
//! `tools/mitsuba_reference.py --quad`: scalar_rgb, box filter, 4096 spp; its own
//! noise is FLIP 0.0006 between two seeds); and the two-pass method's mirrored box
//! against Mitsuba's path tracer (tests/references/two-pass-mitsuba.pfm). Compared
//! with NVIDIA's FLIP on the sRGB images, the figure the by-hand Mitsuba comparisons
//! report.

use crate::support;

use lumiere::image_io::{self, Image};
use std::path::{Path, PathBuf};
use std::process::Command;
use support::flip;

const REFERENCE: &str = "tests/references/cornell-box-direct-mitsuba.pfm";

/// Mean FLIP the exact soft shadows must stay under.
const MAX_FLIP: f64 = 0.01;

fn reference() -> Image {
    image_io::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join(REFERENCE))
        .unwrap_or_else(|e| panic!("{}", support::error_line(&e)))
}

/// `lumiere render cornell-box` at the reference's size and sampling, with `shading`
/// (the shadow method and its settings), read back from linear PFM.
fn render(name: &str, shading: &[&str]) -> (Image, PathBuf) {
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("flip-reference-{name}.pfm"));
    let run = Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .args(["render", "cornell-box", "--supersample", "4"])
        .args(["--width", "256", "--height", "256"])
        .args(shading)
        .arg("-o")
        .arg(&out)
        .output()
        .expect("running lumiere");
    assert!(
        run.status.success(),
        "lumiere render cornell-box {}: {}",
        shading.join(" "),
        String::from_utf8_lossy(&run.stderr)
    );
    let image = image_io::load(&out).unwrap_or_else(|e| panic!("{}", support::error_line(&e)));
    (image, out)
}

/// FLIP of `shading`'s render against the reference, within `bound`; beyond it the
/// render and FLIP's error map are left in the target directory to look at.
fn check(name: &str, shading: &[&str], bound: f64) -> f64 {
    let reference = reference();
    let (image, path) = render(name, shading);
    let mean = flip::mean(&reference, &image);
    eprintln!("{name}: FLIP {mean:.5} against Mitsuba (bound {bound})");
    if mean >= bound {
        let map = path.with_extension("flip.png");
        image_io::save(&flip::magma(&reference, &image), &map, 1.0).unwrap();
        panic!(
            "{name}: FLIP {mean:.5} against Mitsuba's direct light, bound {bound}; render {}, error map {}",
            path.display(),
            map.display()
        );
    }
    mean
}

/// Nishita & Nakamae's exact umbra and penumbra: the visible part of the quad at
/// every sample, so the image converges to the physically based one.
#[test]
fn exact_soft_shadows_match_mitsuba() {
    check("umbra-penumbra", &["--shadows", "umbra-penumbra"], MAX_FLIP);
}

/// The test can fail: without shadows the box is far from the reference.
#[test]
fn an_unshadowed_box_does_not_match() {
    let reference = reference();
    let (image, _) = render("none", &["--shadows", "none"]);
    let mean = flip::mean(&reference, &image);
    assert!(mean > 3.0 * MAX_FLIP, "FLIP without shadows {mean:.5}");
}

/// The held reference is what the script writes: 256 x 256 linear radiance, finite,
/// non-negative, the right way up (PFM rows run bottom to top).
#[test]
fn the_reference_is_sane() {
    let reference = reference();
    assert_eq!((reference.width, reference.height), (256, 256));
    assert!(
        reference
            .pixels
            .iter()
            .all(|p| p.is_finite() && p.min_element() >= 0.0)
    );
    // The light quad, seen from below, covers rows 31 to 40 near the top: its
    // pixels hold its radiance exactly.
    let light = reference.pixels[36 * 256 + 128];
    assert!(
        (light - glam::Vec3::new(17.0, 12.0, 4.0))
            .abs()
            .max_element()
            < 1e-3
    );
}

/// Stratified samples over the quad (Cook, Porter & Carpenter 1984), 16 x 16 per
/// shading sample: the sampled soft shadows, for comparison. About a minute on two
/// cores, so run by hand: `cargo test --release --test suite -- --ignored global::mitsuba`.
#[test]
#[ignore = "about a minute on two cores"]
fn sampled_soft_shadows_against_mitsuba() {
    check(
        "ray-cast-16",
        &["--shadows", "ray-cast", "--set", "shadows.light_samples=16"],
        MAX_FLIP,
    );
}

/// The two-pass entry's mirrored box (three mirrors of reflectance 0.9) against
/// Mitsuba's path tracer with perfect-mirror conductors, held in
/// tests/references/two-pass-mitsuba.pfm (`tools/mitsuba_reference.py --mirrors
/// --size 128 --spp 4096`; its own noise is FLIP 0.018 between two seeds). Plain
/// radiosity on the same 35 mm mesh is FLIP 0.070 from Mitsuba's box without
/// mirrors; the mirrors keep it there (measured 0.070): the bound is 0.08.
const TWO_PASS_REFERENCE: &str = "tests/references/two-pass-mitsuba.pfm";
const TWO_PASS_MAX_FLIP: f64 = 0.08;

/// FLIP of `lumiere render ENTRY --supersample 4` at the held reference's size
/// against it (`reference`, a path under the crate).
fn entry_flip(entry: &str, reference: &str, size: u32) -> f64 {
    entry_flip_with(entry, &[], reference, size)
}

/// `entry_flip` with more arguments for `lumiere render`.
fn entry_flip_with(entry: &str, args: &[&str], reference: &str, size: u32) -> f64 {
    let mut all = vec!["--supersample", "4"];
    all.extend(args);
    flip_of(entry, &all, reference, size)
}

/// FLIP of `lumiere render ENTRY ARGS` at `size` against `reference`.
fn flip_of(entry: &str, args: &[&str], reference: &str, size: u32) -> f64 {
    let reference = image_io::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join(reference))
        .unwrap_or_else(|e| panic!("{}", support::error_line(&e)));
    assert_eq!((reference.width, reference.height), (size, size));
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("flip-{entry}.pfm"));
    let size = size.to_string();
    let run = Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .args(["render", entry, "--width", &size, "--height", &size])
        .args(args)
        .arg("-o")
        .arg(&out)
        .output()
        .expect("running lumiere");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let image = image_io::load(&out).unwrap_or_else(|e| panic!("{}", support::error_line(&e)));
    let mean = flip::mean(&reference, &image);
    eprintln!("{entry}: FLIP {mean:.5} against Mitsuba's path tracer");
    mean
}

fn two_pass_flip(entry: &str) -> f64 {
    entry_flip(entry, TWO_PASS_REFERENCE, 128)
}

#[test]
fn the_two_pass_mirror_box_matches_a_path_tracer() {
    let with_mirrors = two_pass_flip("two-pass");
    assert!(with_mirrors < TWO_PASS_MAX_FLIP, "FLIP {with_mirrors:.5}");
    // The test can fail: without the mirrors' transport (diffuse-diffuse alone, the
    // mirrors black) the same mesh is far from the reference (measured 0.17).
    let plain = two_pass_flip("two-pass-diffuse-diffuse");
    assert!(
        plain > 1.5 * TWO_PASS_MAX_FLIP,
        "FLIP without the mirrors {plain:.5}"
    );
}

/// The same mirrored box with the direct light exact and the rest gathered from the
/// same solution through the irradiance cache, gather rays going on through the
/// mirrors (`two-pass-final-gather`): measured 0.0388 (0.0399 before the direct
/// light at the gathers' hits was weighted as irradiance), within the 0.04 asked
/// (the 35 mm mesh displayed as it is: 0.070; 10 mm elements: 0.035 in 108 s).
#[test]
fn the_final_gather_brings_the_mirrored_box_within_0_04_of_a_path_tracer() {
    let gathered = two_pass_flip("two-pass-final-gather");
    assert!(gathered < 0.04, "two-pass-final-gather: FLIP {gathered:.5}");
}

/// The diffuse Cornell box, every bounce, against Mitsuba's path tracer, held in
/// tests/references/cornell-box-global-mitsuba.pfm (`tools/mitsuba_reference.py
/// --global --size 256 --spp 4096 --seed 7`; a 1024-spp render is FLIP 0.0094 from
/// it). The two-pass way with exact direct light (`cornell-box-global`) measures
/// 0.050; the issue asked 0.03, which the 35 mm mesh of the indirect light does not
/// give (see docs/topics/global-illumination.md). Radiosity alone on the same mesh measures 0.070.
const GLOBAL_REFERENCE: &str = "tests/references/cornell-box-global-mitsuba.pfm";

fn global_flip(entry: &str) -> f64 {
    entry_flip(entry, GLOBAL_REFERENCE, 256)
}

#[test]
fn exact_direct_light_brings_the_global_cornell_box_closer_to_a_path_tracer() {
    let exact = global_flip("cornell-box-global");
    assert!(exact < 0.055, "cornell-box-global: FLIP {exact:.5}");
    let meshed = global_flip("radiosity-shooting");
    assert!(
        meshed > exact + 0.015,
        "radiosity-shooting {meshed:.5} against {exact:.5}"
    );
}

/// The final gather through Ward's irradiance cache (`irradiance-caching`) against
/// the same reference: measured 0.0228 at 256 x 256, 4 x 4 (0.0249 before the
/// direct light at the gathers' hits was weighted as irradiance; the two-pass way
/// on the mesh, 0.050). The target is 0.02: what remains comes from the solution the
/// gather reads (about 1% dark over the walls, and its light bounced twice near
/// creases, read from 35 mm elements); see docs/topics/global-illumination.md.
#[test]
fn the_final_gather_brings_the_global_cornell_box_within_0_027_of_a_path_tracer() {
    let cached = global_flip("irradiance-caching");
    assert!(cached < 0.027, "irradiance-caching: FLIP {cached:.5}");
    let meshed = global_flip("cornell-box-global");
    assert!(
        cached < meshed - 0.02,
        "irradiance-caching {cached:.5} against cornell-box-global {meshed:.5}"
    );
}

/// The point-lit box, every bounce, against Mitsuba's path tracer, held in
/// tests/references/cornell-box-point-global-mitsuba.pfm (`tools/mitsuba_reference.py
/// --point-global --variant llvm_ad_rgb --size 128 --spp 4096`; its own noise, FLIP
/// between two seeds, is 0.0077). `radiosity-point-light` shoots the point light into
/// the solution and adds its direct light exactly per sample: measured 0.070, the
/// 35 mm mesh's figure on the quad-lit box too. The direct light alone is far.
const POINT_GLOBAL_REFERENCE: &str = "tests/references/cornell-box-point-global-mitsuba.pfm";

#[test]
fn a_point_light_shot_into_the_solution_matches_a_path_tracer() {
    let global = entry_flip("radiosity-point-light", POINT_GLOBAL_REFERENCE, 128);
    assert!(global < 0.08, "radiosity-point-light: FLIP {global:.5}");
    // The test can fail: the same box without the light's interreflection
    // (measured 0.47).
    let direct = entry_flip_with(
        "cornell-box-point",
        &["--shadows", "ray-cast"],
        POINT_GLOBAL_REFERENCE,
        128,
    );
    assert!(direct > 0.3, "direct light alone: FLIP {direct:.5}");
}

/// Jensen's photon map on the diffuse box (`photon-map`: 200,000 photons, the 100
/// nearest an estimate, 1,024 gather rays through the irradiance cache, 3 x 3 eye
/// rays a pixel, its own antialiasing) against the same 4,096-spp reference:
/// measured 0.0177 (2 x 2 eye rays: 0.0201), within the 0.02 asked with a margin
/// of 0.0023; the final gather over the meshed radiosity solution
/// (`irradiance-caching`) measures 0.0228.
#[test]
fn the_photon_map_brings_the_global_cornell_box_within_0_02_of_a_path_tracer() {
    let photons = flip_of("photon-map", &[], GLOBAL_REFERENCE, 256);
    assert!(photons <= 0.02, "photon-map: FLIP {photons:.5}");
}

/// Christensen's precomputed irradiance (`photon-map-precomputed`: the same map,
/// the gather reading the estimate made at every fourth photon) against the same
/// reference: measured 0.0180, within the 0.02 with a margin of 0.0020, in a
/// tenth of the time (4.3 s against 44 s at 256 x 256 on 2 cores).
#[test]
fn precomputed_irradiance_keeps_the_photon_map_within_0_02_of_a_path_tracer() {
    let photons = flip_of("photon-map-precomputed", &[], GLOBAL_REFERENCE, 256);
    assert!(photons <= 0.02, "photon-map-precomputed: FLIP {photons:.5}");
}

/// The glass ball on the box's floor (`photon-map-caustic`) against Mitsuba 3's
/// path tracer on the exported scene (the ball a dielectric of index 1.5), held in
/// tests/references/photon-map-caustic-mitsuba.pfm: `lumiere export
/// photon-map-caustic --format mitsuba --width 256 --height 256`, then
/// `tools/mitsuba_moments.py --xml` with 2 renders of 4,096 spp (llvm_ad_rgb), the
/// mean. The issue asks 0.03. Jensen's gather measured 0.0251 (BENCHMARKS.md, 100 s
/// at this size); the test renders with Christensen's precomputed irradiance, whose
/// caustic map and its cone-filtered estimate are the same and whose gather is
/// 0.004 from Jensen's: measured 0.0259, a margin of 0.0041. Without the caustic
/// map (no caustic photons) the bright patch under the ball is gone and the bound
/// fails (measured 0.0307).
const CAUSTIC_REFERENCE: &str = "tests/references/photon-map-caustic-mitsuba.pfm";

#[test]
fn the_glass_balls_caustic_is_within_0_03_of_a_path_tracer() {
    let precomputed = ["--set", "global.precomputed_irradiance=true"];
    let caustic = flip_of("photon-map-caustic", &precomputed, CAUSTIC_REFERENCE, 256);
    assert!(caustic <= 0.03, "photon-map-caustic: FLIP {caustic:.5}");
    let mut without = precomputed.to_vec();
    without.extend(["--set", "global.caustic_photons=0"]);
    let none = flip_of("photon-map-caustic", &without, CAUSTIC_REFERENCE, 256);
    assert!(none > 0.03, "without caustics {none:.5}, with {caustic:.5}");
}
