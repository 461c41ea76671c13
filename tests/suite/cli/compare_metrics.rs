//! `lumiere compare`'s metrics beyond the strict figures: the Sobel edge mask,
//! FLIP, a tolerance image, the statistical test and the expected | difference |
//! actual strip, each failing with one line that says by how much.

use crate::support::*;
use std::path::Path;

/// A 32 x 24 grey image with a black block over columns `block` (rows 6..18) and a
/// white band from column `edge` on.
fn write(dir: &Path, name: &str, block: std::ops::Range<u32>, edge: u32) {
    image::RgbImage::from_fn(32, 24, |x, y| {
        if x >= edge {
            image::Rgb([255, 255, 255])
        } else if block.contains(&x) && (6..18).contains(&y) {
            image::Rgb([0, 0, 0])
        } else {
            image::Rgb([128, 128, 128])
        }
    })
    .save(dir.join(name))
    .unwrap();
}

/// A linear PFM of `w` x `h` pixels, each `f(x, y)`.
fn pfm(dir: &Path, name: &str, w: u32, h: u32, f: impl Fn(u32, u32) -> [f32; 3]) {
    let image = lumiere::Image {
        width: w,
        height: h,
        pixels: (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| f(x, y).into())
            .collect(),
    };
    lumiere::write_image(&image, &dir.join(name), 1.0).unwrap();
}

#[test]
fn the_edge_mask_passes_a_moved_edge_and_fails_a_moved_shadow() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "a.png", 4..9, 24);
    write(d, "edge.png", 4..9, 25);
    write(d, "shadow.png", 12..17, 24);
    let strict = lumiere(&["compare", "a.png", "edge.png", "--max-differing", "0"], d);
    assert_eq!(strict.code, 1, "{}", strict.stderr);
    let masked = ["--ignore-edges", "0.25", "--max-differing", "0"];
    let edge = lumiere(
        &[&["compare", "a.png", "edge.png"][..], &masked].concat(),
        d,
    );
    assert_eq!(edge.code, 0, "{}", edge.stderr);
    assert!(edge.stdout.contains("edges ignored"), "{}", edge.stdout);
    let shadow = lumiere(
        &[&["compare", "a.png", "shadow.png"][..], &masked].concat(),
        d,
    );
    assert_eq!(shadow.code, 1, "{}", shadow.stdout);
    assert!(
        shadow.stderr.contains("differing") && shadow.stderr.contains("> --max-differing 0"),
        "{}",
        shadow.stderr
    );
}

#[test]
fn flip_is_reported_with_percentiles_and_bounds_the_verdict() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "a.png", 4..9, 24);
    write(d, "shadow.png", 12..17, 24);
    let same = lumiere(&["compare", "a.png", "a.png", "--flip", "--json"], d);
    let value: serde_json::Value = serde_json::from_str(&same.stdout).unwrap();
    assert_eq!(value["flip"]["mean"], 0.0);
    let run = lumiere(&["compare", "a.png", "shadow.png", "--flip", "--json"], d);
    let value: serde_json::Value = serde_json::from_str(&run.stdout).unwrap();
    let flip = &value["flip"];
    let mean = flip["mean"].as_f64().unwrap();
    assert!(mean > 0.01 && mean < 1.0, "{flip}");
    let (p50, p99, max) = (
        flip["p50"].as_f64().unwrap(),
        flip["p99"].as_f64().unwrap(),
        flip["p100"].as_f64().unwrap(),
    );
    assert!(p50 <= p99 && p99 <= max && max <= 1.0, "{flip}");
    assert_eq!(flip["range"], "ldr");
    let bound = format!("{}", mean * 0.9);
    let fail = lumiere(&["compare", "a.png", "shadow.png", "--max-flip", &bound], d);
    assert_eq!(fail.code, 1);
    assert!(
        fail.stderr
            .contains(&format!("flip {mean:.6} > --max-flip {bound}")),
        "{}",
        fail.stderr
    );
    let pass = format!("{}", mean * 1.1);
    assert_eq!(
        lumiere(&["compare", "a.png", "shadow.png", "--max-flip", &pass], d).code,
        0
    );
    let hdr = lumiere(
        &[
            "compare",
            "a.png",
            "shadow.png",
            "--flip",
            "--flip-range",
            "hdr",
            "--json",
        ],
        d,
    );
    let value: serde_json::Value = serde_json::from_str(&hdr.stdout).unwrap();
    assert_eq!(value["flip"]["range"], "hdr", "{}", hdr.stderr);
    assert!(value["flip"]["exposures"]["count"].as_u64().unwrap() >= 2);
}

#[test]
fn a_tolerance_image_allows_its_differences_and_no_more() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    pfm(d, "a.pfm", 8, 4, |_, _| [0.5; 3]);
    // B is brighter by 0.1 on the left half.
    pfm(d, "b.pfm", 8, 4, |x, _| [if x < 4 { 0.6 } else { 0.5 }; 3]);
    pfm(d, "loose.pfm", 8, 4, |x, _| {
        [if x < 4 { 0.15 } else { 0.0 }; 3]
    });
    pfm(d, "tight.pfm", 8, 4, |x, _| {
        [if x < 2 { 0.15 } else { 0.05 }; 3]
    });
    let loose = lumiere(
        &["compare", "a.pfm", "b.pfm", "--tolerance", "loose.pfm"],
        d,
    );
    assert_eq!(loose.code, 0, "{}", loose.stderr);
    let tight = lumiere(
        &["compare", "a.pfm", "b.pfm", "--tolerance", "tight.pfm"],
        d,
    );
    assert_eq!(tight.code, 1);
    // Columns 2 and 3 of four rows, each 0.05 beyond.
    assert!(
        tight
            .stderr
            .contains("8 pixels beyond the tolerance image (by up to 0.05"),
        "{}",
        tight.stderr
    );
    pfm(d, "small.pfm", 4, 4, |_, _| [1.0; 3]);
    let run = lumiere(
        &["compare", "a.pfm", "b.pfm", "--tolerance", "small.pfm"],
        d,
    );
    assert_clear_error(
        &run,
        "small.pfm: is 4x4, the images compared are 8x4",
        &d.join("none"),
    );
}

#[test]
fn the_statistical_test_passes_noise_and_fails_bias() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A reference mean of 1 with a variance of 0.01 a render (sd 0.1) over 64 renders.
    pfm(d, "mean.pfm", 16, 16, |_, _| [1.0; 3]);
    pfm(d, "var.pfm", 16, 16, |_, _| [0.01; 3]);
    // A candidate within noise: +-0.1 (1 sd) in a checkerboard; a biased one: +0.5 (5 sd).
    pfm(d, "noise.pfm", 16, 16, |x, y| {
        [if (x + y) % 2 == 0 { 1.1 } else { 0.9 }; 3]
    });
    pfm(d, "bias.pfm", 16, 16, |_, _| [1.5; 3]);
    let test = [
        "--reference-variance",
        "var.pfm",
        "--reference-renders",
        "64",
    ];
    let noise = lumiere(
        &[&["compare", "mean.pfm", "noise.pfm", "--json"][..], &test].concat(),
        d,
    );
    assert_eq!(noise.code, 0, "{}", noise.stderr);
    let value: serde_json::Value = serde_json::from_str(&noise.stdout).unwrap();
    assert_eq!(value["statistical"]["test"], "z");
    assert_eq!(value["statistical"]["rejected"], 0);
    let bias = lumiere(
        &[&["compare", "mean.pfm", "bias.pfm"][..], &test].concat(),
        d,
    );
    assert_eq!(bias.code, 1);
    assert!(
        bias.stderr
            .contains("the z test accepts 0.0000% of pixels < --min-accepted 99.75%"),
        "{}",
        bias.stderr
    );
    // Welch's test: the candidate's own variance over 4 renders.
    let welch = lumiere(
        &[
            &["compare", "mean.pfm", "noise.pfm", "--json"][..],
            &test,
            &[
                "--candidate-variance",
                "var.pfm",
                "--candidate-renders",
                "4",
            ],
        ]
        .concat(),
        d,
    );
    let value: serde_json::Value = serde_json::from_str(&welch.stdout).unwrap();
    assert_eq!(value["statistical"]["test"], "welch", "{}", welch.stderr);
    let alone = lumiere(
        &[
            "compare",
            "mean.pfm",
            "noise.pfm",
            "--reference-variance",
            "var.pfm",
        ],
        d,
    );
    assert_eq!(alone.code, 2);
}

#[test]
fn diff_writes_expected_difference_actual_side_by_side() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "a.png", 4..9, 24);
    write(d, "shadow.png", 12..17, 24);
    let run = lumiere(
        &["compare", "a.png", "shadow.png", "--diff", "strip.png"],
        d,
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let strip = image::open(d.join("strip.png")).unwrap().to_rgb8();
    assert_eq!(strip.dimensions(), (3 * 32 + 4, 24));
    let (a, b) = (
        image::open(d.join("a.png")).unwrap().to_rgb8(),
        image::open(d.join("shadow.png")).unwrap().to_rgb8(),
    );
    for y in 0..24 {
        for x in 0..32 {
            assert_eq!(strip.get_pixel(x, y), a.get_pixel(x, y));
            assert_eq!(strip.get_pixel(2 * 34 + x, y), b.get_pixel(x, y));
            // The middle panel is black where they agree, bright where the block moved.
            let moved = (4..9).contains(&x) != (12..17).contains(&x) && (6..18).contains(&y);
            assert_eq!(strip.get_pixel(34 + x, y).0[0] > 0, moved, "({x}, {y})");
        }
    }
}

/// The gradient is scaled so a black-to-white step measures 1: the grey-to-white
/// step here (128 to 255) measures 127/255 = 0.498, so moved by a pixel it is left
/// out under a threshold of 0.49 and counted under 0.50.
#[test]
fn the_edge_threshold_measures_a_full_step_as_one() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "a.png", 0..0, 16);
    write(d, "b.png", 0..0, 17);
    for (threshold, code) in [("0.49", 0), ("0.50", 1)] {
        let run = lumiere(
            &[
                "compare",
                "a.png",
                "b.png",
                "--ignore-edges",
                threshold,
                "--max-differing",
                "0",
            ],
            d,
        );
        assert_eq!(run.code, code, "threshold {threshold}: {}", run.stdout);
    }
}
