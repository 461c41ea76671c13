//! Golden images: every catalogue entry rendered at its test size must match its
//! references under golden/: <id>.png, the displayed image (a pixel fails when a
//! channel differs by more than 1/255), and <id>.exr, the linear radiance in 32-bit
//! floats, which keeps the dark end where shadows and radiosity live: every channel
//! must equal the reference bit for bit, so that work on speed proves it changed no
//! output (the goldens are written uncompressed, and every operation behind them is
//! IEEE-754 arithmetic or the platform's libm). The test asserts no failing pixel in
//! either. On failure, golden-failures/<id>.png shows expected | difference (×8) |
//! actual.
//!
//! Regenerate: `LUMIERE_UPDATE_GOLDEN=1 cargo test --release --test golden`. It
//! rewrites both references and still fails, so that someone looks at each before
//! committing it.

use libtest_mimic::{Arguments, Failed, Trial};
use lumiere::image_io::{self, Image};
use lumiere::{catalogue, load_scene};
use std::path::{Path, PathBuf};

/// Largest per-channel difference (in 1/255 steps) that still counts as equal.
const CHANNEL_TOLERANCE: u8 = 1;

fn main() {
    let args = Arguments::from_args();
    let mut trials: Vec<Trial> = catalogue::ids()
        .into_iter()
        .map(|id| Trial::test(format!("golden::{id}"), move || check(&id)))
        .collect();
    trials.push(Trial::test("golden::every_golden_has_an_entry", orphans));
    trials.push(Trial::test(
        "golden::same_bytes_with_one_two_and_eight_threads",
        deterministic,
    ));
    libtest_mimic::run(&args, trials).exit();
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn render_entry(id: &str) -> Result<(Image, f32), Failed> {
    render_entry_shrunk(id, 1)
}

/// The entry at its test size divided by `shrink` (at least 8 pixels a side).
fn render_entry_shrunk(id: &str, shrink: u32) -> Result<(Image, f32), Failed> {
    let a = catalogue::entry(id).map_err(|e| e.line())?.algorithm;
    let sets = [
        format!("camera.width={}", (a.test_width / shrink).max(8)),
        format!("camera.height={}", (a.test_height / shrink).max(8)),
    ];
    let scene = load_scene(id, &sets).map_err(|e| e.line())?;
    let image = lumiere::render(&scene).map_err(|e| e.line())?;
    Ok((image, scene.render.exposure))
}

fn check(id: &str) -> Result<(), Failed> {
    let (image, exposure) = render_entry(id)?;
    let actual =
        image_io::encode(&image, image_io::Format::Png, exposure).map_err(|e| e.to_string())?;
    let golden = root().join("golden").join(format!("{id}.png"));
    let linear = root().join("golden").join(format!("{id}.exr"));
    let regenerate = format!("LUMIERE_UPDATE_GOLDEN=1 cargo test --release --test golden -- {id}");
    if std::env::var_os("LUMIERE_UPDATE_GOLDEN").is_some() {
        let exr =
            image_io::encode(&image, image_io::Format::Exr, 1.0).map_err(|e| e.to_string())?;
        image_io::write_atomically(&golden, &actual).map_err(|e| e.to_string())?;
        image_io::write_atomically(&linear, &exr).map_err(|e| e.to_string())?;
        return Err(format!(
            "{id}: golden rewritten at {}; look at it, then run the tests again",
            golden.display()
        )
        .into());
    }
    if !golden.exists() {
        return Err(format!(
            "{id}: no golden image at {}; create it with `{regenerate}`",
            golden.display()
        )
        .into());
    }
    let expected = image_io::load(&golden).map_err(|e| e.line())?;
    let actual = image_io::load_png_bytes(&actual).map_err(|e| e.line())?;
    if (expected.width, expected.height) != (actual.width, actual.height) {
        return Err(format!(
            "{id}: golden is {}x{}, render is {}x{}; regenerate with `{regenerate}`",
            expected.width, expected.height, actual.width, actual.height
        )
        .into());
    }
    let failing = failing_pixels(&expected, &actual);
    if failing == 0 {
        return check_linear(id, &image, &linear, &regenerate);
    }
    let comparison = image_io::compare(&expected, &actual, 1.0).map_err(|e| e.to_string())?;
    let report = write_failure(id, &expected, &actual);
    Err(format!(
        "{id}: {failing} pixels differ by more than {CHANNEL_TOLERANCE}/255 (max {}/255, rmse {:.5}); see {}; if the change is intended, regenerate with `{regenerate}`",
        comparison.max_difference,
        comparison.rmse,
        report.display()
    )
    .into())
}

/// The render against the linear reference, channel by channel, in radiance.
fn check_linear(id: &str, image: &Image, path: &Path, regenerate: &str) -> Result<(), Failed> {
    if !path.exists() {
        return Err(format!(
            "{id}: no linear reference at {}; create it with `{regenerate}`",
            path.display()
        )
        .into());
    }
    let expected = image_io::load(path).map_err(|e| e.line())?;
    if (expected.width, expected.height) != (image.width, image.height) {
        return Err(format!(
            "{id}: linear reference is {}x{}; regenerate with `{regenerate}`",
            expected.width, expected.height
        )
        .into());
    }
    let mut failing = 0;
    let mut worst = (0.0f32, 0usize);
    for (k, (e, a)) in expected.pixels.iter().zip(&image.pixels).enumerate() {
        let (e, a) = (e.to_array(), a.to_array());
        if (0..3).all(|c| e[c].to_bits() == a[c].to_bits()) {
            continue;
        }
        failing += 1;
        let off = (0..3)
            .map(|c| (e[c] - a[c]).abs() / e[c].abs().max(f32::MIN_POSITIVE))
            .fold(
                0.0f32,
                |m, v| if v.is_nan() { f32::INFINITY } else { m.max(v) },
            );
        if off >= worst.0 {
            worst = (off, k);
        }
    }
    if failing == 0 {
        return Ok(());
    }
    let (x, y) = (worst.1 as u32 % image.width, worst.1 as u32 / image.width);
    Err(format!(
        "{id}: {failing} pixels differ from the linear reference in their bits (worst at ({x}, {y}), relative {:.2e}: {:?} against {:?}); if the change is intended, regenerate with `{regenerate}`",
        worst.0, image.pixels[worst.1], expected.pixels[worst.1]
    )
    .into())
}

fn failing_pixels(a: &Image, b: &Image) -> usize {
    a.pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(p, q)| {
            let (p, q) = (image_io::to_srgb8(**p, 1.0), image_io::to_srgb8(**q, 1.0));
            (0..3).any(|c| p[c].abs_diff(q[c]) > CHANNEL_TOLERANCE)
        })
        .count()
}

/// expected | difference | actual, side by side.
fn write_failure(id: &str, expected: &Image, actual: &Image) -> PathBuf {
    let diff = image_io::difference_image(expected, actual, 1.0, 8.0);
    let (w, h) = (expected.width, expected.height);
    let mut pixels = Vec::with_capacity((3 * w * h) as usize);
    for y in 0..h as usize {
        for part in [expected, &diff, actual] {
            pixels.extend_from_slice(&part.pixels[y * w as usize..(y + 1) * w as usize]);
        }
    }
    let sheet = Image {
        width: 3 * w,
        height: h,
        pixels,
    };
    let dir = root().join("golden-failures");
    let path = dir.join(format!("{id}.png"));
    let _ = std::fs::create_dir_all(&dir)
        .and_then(|_| image_io::save(&sheet, &path, 1.0).map_err(std::io::Error::other));
    path
}

fn orphans() -> Result<(), Failed> {
    let ids = catalogue::ids();
    let dir = root().join("golden");
    let mut orphans = Vec::new();
    for entry in std::fs::read_dir(&dir).map_err(|e| e.to_string())? {
        let path = entry.map_err(|e| e.to_string())?.path();
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or_default();
        let reference = ["png", "exr"]
            .iter()
            .any(|e| path.extension() == Some(e.as_ref()));
        if reference && !ids.iter().any(|id| id == stem) {
            orphans.push(Path::new(&path).display().to_string());
        }
    }
    if orphans.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "golden images without a catalogue entry: {}",
            orphans.join(", ")
        )
        .into())
    }
}

/// The same bytes whatever the thread count: every entry's PFM (exact f32
/// radiance) with pools of 1, 2 and 8 threads, at half its test size (how the
/// threads split the work is what is checked; three renders of the catalogue at
/// full test size cost minutes).
fn deterministic() -> Result<(), Failed> {
    let render_all = |threads: usize| -> Result<Vec<Vec<u8>>, Failed> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| e.to_string())?;
        pool.install(|| {
            catalogue::ids()
                .iter()
                .map(|id| {
                    let (image, _) = render_entry_shrunk(id, 2)?;
                    image_io::encode(&image, image_io::Format::Pfm, 1.0)
                        .map_err(|e| Failed::from(e.to_string()))
                })
                .collect()
        })
    };
    let one = render_all(1)?;
    for threads in [2, 8] {
        let many = render_all(threads)?;
        for (id, (a, b)) in catalogue::ids().iter().zip(one.iter().zip(&many)) {
            if a != b {
                return Err(
                    format!("{id}: the image differs between 1 and {threads} threads").into(),
                );
            }
        }
    }
    Ok(())
}
