//! `lumiere references` and `lumiere check`: a suite is deterministic, resumable,
//! and made in shards that merge into the same bytes; `check` gives one verdict a
//! candidate, fails what differs, reports missing images and bad input in one
//! line, and `--bless` takes candidates as references yet still exits 1.

use crate::support::*;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

const IDS: [&str; 3] = [
    "jittered-soft-shadows",
    "scanline-visible-surface",
    "shadow-volumes",
];

fn make(dir: &Path, out: &str, extra: &[&str]) -> Run {
    let mut args = vec![
        "references",
        "-o",
        out,
        "--width",
        "40",
        "--samples",
        "4",
        "--ground-truth-paths",
        "2",
    ];
    args.extend(IDS);
    args.extend(extra);
    let run = lumiere(&args, dir);
    assert_eq!(run.code, 0, "{}", run.stderr);
    run
}

/// Every file under `root`, by its path relative to it, with its bytes.
fn tree(root: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut files = BTreeMap::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for child in std::fs::read_dir(&dir).unwrap() {
            let path = child.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let bytes = std::fs::read(&path).unwrap();
                files.insert(path.strip_prefix(root).unwrap().to_path_buf(), bytes);
            }
        }
    }
    files
}

fn manifest(dir: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(dir.join("manifest.json")).unwrap()).unwrap()
}

#[test]
fn a_suite_is_the_same_bytes_made_whole_again_or_in_merged_shards() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    make(d, "whole", &[]);
    make(d, "again", &[]);
    make(d, "part1", &["--shard", "1/2"]);
    make(d, "part2", &["--shard", "2/2"]);
    let whole = tree(&d.join("whole"));
    assert_eq!(
        whole,
        tree(&d.join("again")),
        "made twice, the suites differ"
    );
    // The parts split the entries: 1 and 3 in the first, 2 in the second.
    assert_eq!(
        manifest(&d.join("part1"))["entries"]
            .as_array()
            .unwrap()
            .len(),
        2
    );
    assert_eq!(manifest(&d.join("part2"))["shard"]["index"], 2);
    let merge = lumiere(
        &["references", "--merge", "part2", "part1", "-o", "merged"],
        d,
    );
    assert_eq!(merge.code, 0, "{}", merge.stderr);
    let merged = tree(&d.join("merged"));
    assert_eq!(
        merged.keys().collect::<Vec<_>>(),
        whole.keys().collect::<Vec<_>>()
    );
    for (path, bytes) in &whole {
        assert!(
            merged[path] == *bytes,
            "{} differs once merged",
            path.display()
        );
    }

    let m = manifest(&d.join("whole"));
    let entries = m["entries"].as_array().unwrap();
    let ids: Vec<&str> = entries.iter().map(|e| e["id"].as_str().unwrap()).collect();
    assert_eq!(ids, IDS);
    let jittered = &entries[0];
    assert_eq!(jittered["sampled"], true);
    assert_eq!(jittered["renders"], 4);
    assert_eq!(
        jittered["files"]["variance"],
        "jittered-soft-shadows/variance.exr"
    );
    assert_eq!(jittered["checks"][1]["metric"], "statistical");
    let volumes = &entries[2];
    assert_eq!(volumes["sampled"], false);
    assert!(volumes["files"].get("variance").is_none());
    assert_eq!(volumes["width"], 40);
    assert_eq!(volumes["checks"][0]["metric"], "flip");
    for key in ["mitsuba", "pov"] {
        let file = volumes["exports"][key]["file"].as_str().unwrap();
        assert!(d.join("whole").join(file).is_file(), "{file}");
    }
    // Every file the manifest names is in the suite; each buffer too.
    let buffers = volumes["files"]["buffers"].as_object().unwrap();
    assert!(
        buffers.contains_key("shadow-volume-counts-0"),
        "{buffers:?}"
    );
    for file in buffers
        .values()
        .chain([&volumes["files"]["reference"], &volumes["files"]["scene"]])
    {
        assert!(
            d.join("whole").join(file.as_str().unwrap()).is_file(),
            "{file}"
        );
    }
    // The variance is of renders that differ: above zero in the penumbra.
    let variance =
        lumiere::read_image(&d.join("whole/jittered-soft-shadows/variance.exr")).unwrap();
    assert!(variance.pixels.iter().any(|p| p.x > 0.0));

    // What a physically based renderer is held to: the path tracer's direct light
    // where the light is sampled, the reference where the method is exact, nothing
    // where the lights cast no shadows.
    assert_eq!(m["settings"]["ground_truth_paths"], 2);
    assert_eq!(
        jittered["ground_truth"],
        serde_json::json!({
            "transport": "direct", "renders": 4, "paths": 4,
            "biased_by": "shadows.method = \"jittered-soft-shadows\""
        })
    );
    assert_eq!(jittered["physically_based"]["against"], "ground-truth");
    assert_eq!(jittered["physically_based"]["checks"][0]["test"], "welch");
    for key in ["ground_truth", "ground_truth_variance"] {
        let file = jittered["files"][key].as_str().unwrap();
        let image = lumiere::read_image(&d.join("whole").join(file)).unwrap();
        assert_eq!((image.width, image.height), (40, 30), "{file}");
    }
    // Direct light, as the entry's: the ground truth's mean is the reference's
    // within a few percent (the jittered cells sample the same light).
    let mean = |file: &str| {
        let image = lumiere::read_image(&d.join("whole").join(file)).unwrap();
        image.pixels.iter().map(|p| p.x as f64).sum::<f64>() / image.pixels.len() as f64
    };
    let (truth, reference) = (
        mean("jittered-soft-shadows/ground-truth.exr"),
        mean("jittered-soft-shadows/reference.exr"),
    );
    assert!(
        (truth / reference - 1.0).abs() < 0.03,
        "ground truth {truth}, reference {reference}"
    );
    let visible = &entries[1];
    assert!(visible.get("ground_truth").is_none());
    assert!(
        visible["physically_based"]["none"]
            .as_str()
            .unwrap()
            .contains("cast no shadows"),
        "{visible}"
    );
    assert_eq!(volumes["physically_based"]["against"], "reference");
    assert_eq!(volumes["physically_based"]["checks"], volumes["checks"]);
}

#[test]
fn check_holds_physically_based_candidates_to_each_entrys_answer() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    make(d, "suite", &[]);
    std::fs::create_dir_all(d.join("c")).unwrap();
    // The suite's own images as candidates: the ground truth with its variance,
    // the exact reference, and the reference of the entry that has no answer.
    let copy = |from: &str, to: &str| {
        std::fs::copy(d.join("suite").join(from), d.join("c").join(to)).unwrap();
    };
    copy(
        "jittered-soft-shadows/ground-truth.exr",
        "jittered-soft-shadows.exr",
    );
    copy(
        "jittered-soft-shadows/ground-truth-variance.exr",
        "jittered-soft-shadows.variance.exr",
    );
    copy("shadow-volumes/reference.exr", "shadow-volumes.exr");
    copy(
        "scanline-visible-surface/reference.exr",
        "scanline-visible-surface.exr",
    );
    let check = |extra: &[&str]| {
        let mut args = vec!["check", "suite/manifest.json", "c", "--physically-based"];
        args.extend(extra);
        lumiere(&args, d)
    };
    let run = check(&["--candidate-renders", "4"]);
    assert_eq!(run.code, 0, "{}{}", run.stdout, run.stderr);
    assert!(
        run.stdout
            .contains("2 passed, 0 failed, 0 missing of 2 (1 skipped: no physically based answer)"),
        "{}",
        run.stdout
    );
    assert!(
        run.stdout.contains("welch-test 100.000% accepted"),
        "{}",
        run.stdout
    );
    assert!(run.stdout.contains("SKIP"), "{}", run.stdout);
    // Welch's test needs the candidate's renders; same-sampler and physically
    // based checks are one or the other.
    let run = check(&[]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert!(run.stderr.contains("--candidate-renders"), "{}", run.stderr);
    let run = check(&["--candidate-renders", "4", "--same-sampler"]);
    assert_eq!(run.code, 2, "{}", run.stderr);
}

#[test]
fn an_interrupted_suite_resumes_and_keeps_what_was_made() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    make(d, "suite", &[]);
    let before = tree(&d.join("suite"));
    std::fs::remove_file(d.join("suite/manifest.json")).unwrap();
    std::fs::remove_dir_all(d.join("suite/scanline-visible-surface")).unwrap();
    let run = make(d, "suite", &[]);
    assert!(
        run.stderr.contains("jittered-soft-shadows: kept"),
        "{}",
        run.stderr
    );
    assert!(
        !run.stderr.contains("scanline-visible-surface: kept"),
        "{}",
        run.stderr
    );
    assert_eq!(tree(&d.join("suite")), before);
    // Other settings remake the entries.
    let run = lumiere(
        &[
            "references",
            "-o",
            "suite",
            "shadow-volumes",
            "--width",
            "32",
        ],
        d,
    );
    assert!(!run.stderr.contains("kept"), "{}", run.stderr);
}

#[test]
fn merging_refuses_a_missing_a_repeated_or_a_whole_part() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    make(d, "part1", &["--shard", "1/2"]);
    make(d, "whole", &[]);
    let missing = lumiere(&["references", "--merge", "part1", "-o", "out"], d);
    assert_clear_error(&missing, "part 2/2 is missing", &d.join("out"));
    let twice = lumiere(&["references", "--merge", "part1", "part1", "-o", "out"], d);
    assert_clear_error(&twice, "both are part 1/2", &d.join("out"));
    let whole = lumiere(&["references", "--merge", "whole", "-o", "out"], d);
    assert_clear_error(&whole, "a whole suite, not a part", &d.join("out"));
    let bad = lumiere(&["references", "-o", "x", "--shard", "3/2"], d);
    assert_eq!(bad.code, 2);
    assert!(bad.stderr.contains("1 <= K <= N"), "{}", bad.stderr);
}

/// Renders `id` as the suite did (40 wide, 4 x 4 samples) with `sets`, into `out`.
fn candidate(d: &Path, id: &str, sets: &[&str], out: &str) {
    let height = manifest(&d.join("suite"))["entries"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["id"] == id)
        .unwrap()["height"]
        .to_string();
    let mut args = vec![
        "render",
        id,
        "--width",
        "40",
        "--height",
        &height,
        "--supersample",
        "4",
        "-o",
        out,
    ];
    for s in sets {
        args.extend(["--set", s]);
    }
    let run = lumiere(&args, d);
    assert_eq!(run.code, 0, "{}", run.stderr);
}

#[test]
fn check_gives_a_verdict_per_entry_and_bless_takes_the_candidates() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    make(d, "suite", &[]);
    std::fs::create_dir(d.join("good")).unwrap();
    candidate(d, "shadow-volumes", &[], "good/shadow-volumes.exr");
    candidate(
        d,
        "scanline-visible-surface",
        &[],
        "good/scanline-visible-surface.png",
    );
    candidate(
        d,
        "jittered-soft-shadows",
        &["shadows.seed=99"],
        "good/jittered-soft-shadows.exr",
    );
    let run = lumiere(
        &["check", "suite/manifest.json", "good", "--same-sampler"],
        d,
    );
    assert_eq!(run.code, 0, "{}\n{}", run.stdout, run.stderr);
    assert!(
        run.stdout.contains("3 passed, 0 failed, 0 missing of 3"),
        "{}",
        run.stdout
    );
    assert!(run.stdout.contains("z-test"), "{}", run.stdout);

    // Shadows off, a missing image, a wrong size.
    std::fs::create_dir(d.join("bad")).unwrap();
    candidate(
        d,
        "shadow-volumes",
        &["shadows.method=\"none\""],
        "bad/shadow-volumes.exr",
    );
    image::RgbImage::new(8, 8)
        .save(d.join("bad/scanline-visible-surface.png"))
        .unwrap();
    let run = lumiere(&["check", "suite/manifest.json", "bad"], d);
    assert_eq!(run.code, 1, "{}", run.stderr);
    let line = |id: &str| {
        run.stdout
            .lines()
            .find(|l| l.contains(id))
            .unwrap()
            .to_string()
    };
    assert!(
        line("shadow-volumes").starts_with("FAIL") && line("shadow-volumes").contains("> 0.02"),
        "{}",
        run.stdout
    );
    assert!(
        line("jittered-soft-shadows").starts_with("MISSING"),
        "{}",
        run.stdout
    );
    assert!(
        line("scanline-visible-surface").contains("is 8x8, the reference is 40x"),
        "{}",
        run.stdout
    );
    assert_eq!(
        run.stderr.trim(),
        "error: 2 failed and 1 missing of 3 entries"
    );

    // Blessing takes the unshadowed box as the reference, then exits 1 all the same.
    let bless = lumiere(&["check", "suite/manifest.json", "bad", "--bless"], d);
    assert_eq!(bless.code, 1);
    assert!(
        bless.stderr.contains("blessed 1 reference: look at them"),
        "{}",
        bless.stderr
    );
    let after = lumiere(&["check", "suite/manifest.json", "bad"], d);
    assert!(
        after
            .stdout
            .lines()
            .any(|l| l.starts_with("PASS") && l.contains("shadow-volumes")),
        "{}",
        after.stdout
    );
}

#[test]
fn check_refuses_bad_manifests_and_candidate_directories_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("garbage.json"), "{ not json").unwrap();
    std::fs::write(d.join("other.json"), "{\"schema\": \"something-else/9\"}").unwrap();
    std::fs::create_dir(d.join("c")).unwrap();
    for (manifest, candidates, fragment) in [
        (
            "garbage.json",
            "c",
            "garbage.json: not a reference suite's manifest",
        ),
        (
            "other.json",
            "c",
            "other.json: not a reference suite's manifest",
        ),
        ("none.json", "c", "none.json: No such file"),
    ] {
        let run = lumiere(&["check", manifest, candidates], d);
        assert_eq!(run.code, 2, "{}", run.stderr);
        assert_clear_error(&run, fragment, &d.join("nothing"));
    }
    make(d, "suite", &[]);
    let run = lumiere(&["check", "suite/manifest.json", "nowhere"], d);
    assert_eq!(run.code, 2);
    assert_clear_error(
        &run,
        "nowhere: no such directory of candidates",
        &d.join("nothing"),
    );
}

#[test]
fn ray_traced_entries_keep_their_own_antialiasing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let run = lumiere(
        &[
            "references",
            "-o",
            "s",
            "ray-tracing",
            "shadow-volumes",
            "--width",
            "32",
        ],
        d,
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let m = manifest(&d.join("s"));
    let supersample: Vec<u64> = m["entries"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["supersample"].as_u64().unwrap())
        .collect();
    assert_eq!(supersample, [1, 4], "Whitted's subdivision, then 4 x 4");
}

/// Environment mapping's ground truth is Whitted's tracer where the map's
/// surroundings are the scene's: one deterministic render without a variance,
/// held by FLIP; the teapot that does not reflect itself in its map does in it.
#[test]
fn a_captured_environment_maps_ground_truth_is_whitteds() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let run = lumiere(
        &[
            "references",
            "-o",
            "suite",
            "--width",
            "48",
            "--samples",
            "2",
            "reflection-mapping-self",
        ],
        d,
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let m = manifest(&d.join("suite"));
    let entry = &m["entries"][0];
    assert_eq!(
        entry["ground_truth"],
        serde_json::json!({
            "transport": "whitted", "renders": 1, "biased_by": "environment mapping"
        })
    );
    assert!(entry["files"].get("ground_truth_variance").is_none());
    assert_eq!(entry["physically_based"]["against"], "ground-truth");
    assert_eq!(entry["physically_based"]["checks"][0]["metric"], "flip");
    let image = |file: &str| lumiere::read_image(&d.join("suite").join(file)).unwrap();
    let truth = image("reflection-mapping-self/ground-truth.exr");
    let reference = image("reflection-mapping-self/reference.exr");
    assert_eq!((truth.width, truth.height), (48, 36));
    let differing = truth
        .pixels
        .iter()
        .zip(&reference.pixels)
        .filter(|(a, b)| (**a - **b).abs().max_element() > 0.05)
        .count();
    assert!(
        differing > 0,
        "the traced mirror and the map's lookup should differ somewhere"
    );
}
