//! `lumiere compare`'s fuzzy matching (Skia Gold's): an edge moved by one pixel
//! passes where strict comparison fails, a moved shadow still fails, the delta bound
//! and the ignored border do what they say.

use crate::support::*;
use std::path::Path;

/// A 32 x 24 grey image with a black block over columns `block` and a white column
/// band `edge..` on the right (its last column black if `dark_last`).
fn write(dir: &Path, name: &str, block: std::ops::Range<u32>, edge: u32) {
    write_with(dir, name, block, edge, false)
}

fn write_with(dir: &Path, name: &str, block: std::ops::Range<u32>, edge: u32, dark_last: bool) {
    let image = image::RgbImage::from_fn(32, 24, |x, y| {
        if dark_last && x == 31 {
            image::Rgb([0, 0, 0])
        } else if x >= edge {
            image::Rgb([255, 255, 255])
        } else if block.contains(&x) && (6..18).contains(&y) {
            image::Rgb([0, 0, 0])
        } else {
            image::Rgb([128, 128, 128])
        }
    });
    image.save(dir.join(name)).unwrap();
}

#[test]
fn fuzzy_matching_passes_a_moved_edge_and_fails_a_moved_shadow() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(d, "a.png", 4..9, 24);
    write(d, "edge.png", 4..9, 25); // the edge moved by a pixel: 24 pixels differ
    write(d, "shadow.png", 12..17, 24); // the block moved: 2 x 5 x 12 pixels differ
    write_with(d, "border.png", 4..9, 24, true); // differs in the last column only

    let strict = lumiere(&["compare", "a.png", "edge.png", "--max-differing", "0"], d);
    assert_eq!(strict.code, 1, "{}", strict.stderr);

    let fuzzy = lumiere(
        &[
            "compare",
            "a.png",
            "edge.png",
            "--max-differing-pixels",
            "24",
        ],
        d,
    );
    assert_eq!(fuzzy.code, 0, "{}", fuzzy.stderr);
    assert!(
        fuzzy
            .stdout
            .contains("24 pixels differ, largest delta 381/255"),
        "{}",
        fuzzy.stdout
    );

    let shadow = lumiere(
        &[
            "compare",
            "a.png",
            "shadow.png",
            "--max-differing-pixels",
            "24",
        ],
        d,
    );
    assert_eq!(shadow.code, 1);
    assert_eq!(
        shadow.stderr.trim(),
        "error: a.png and shadow.png differ beyond the threshold: 120 pixels differ > --max-differing-pixels 24"
    );

    let delta = lumiere(
        &[
            "compare",
            "a.png",
            "edge.png",
            "--max-differing-pixels",
            "24",
            "--pixel-delta",
            "100",
        ],
        d,
    );
    assert_eq!(delta.code, 1);
    assert!(
        delta
            .stderr
            .contains("a pixel's delta 381/255 > --pixel-delta 100"),
        "{}",
        delta.stderr
    );

    for (border, code) in [("0", 1), ("1", 0)] {
        let run = lumiere(
            &[
                "compare",
                "a.png",
                "border.png",
                "--max-differing-pixels",
                "0",
                "--ignore-border",
                border,
            ],
            d,
        );
        assert_eq!(run.code, code, "border {border}: {}", run.stderr);
    }

    let json = lumiere(
        &[
            "compare",
            "a.png",
            "edge.png",
            "--max-differing-pixels",
            "24",
            "--json",
        ],
        d,
    );
    let value: serde_json::Value = serde_json::from_str(&json.stdout).unwrap();
    assert_eq!(value["fuzzy"]["differing_pixels"], 24);
}

#[test]
fn fuzzy_options_alone_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "a.png", 4..9, 24);
    for extra in [["--pixel-delta", "3"], ["--ignore-border", "2"]] {
        let mut args = vec!["compare", "a.png", "a.png"];
        args.extend(extra);
        let run = lumiere(&args, dir.path());
        assert_eq!(run.code, 2, "{}", run.stderr);
        assert!(
            run.stderr.contains("--max-differing-pixels"),
            "{}",
            run.stderr
        );
    }
}
