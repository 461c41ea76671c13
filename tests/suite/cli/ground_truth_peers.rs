//! The reference suite's ground truth with a real peer: Mitsuba 3's renders of the
//! exported scenes of two biased entries (progressive radiosity, Brotman & Badler's
//! soft shadow volumes) pass `lumiere check --physically-based` against the path
//! tracer's ground truth by Welch's test, where lumiere's own references of the same
//! entries (the meshed radiosity, the light as sixteen points) fail it.
//! (docs/testing-your-renderer.md walks through the same steps.)

use crate::support::{self, Run, lumiere, lumiere_ok};
use std::path::Path;
use std::process::Command;

/// Biased entries whose Mitsuba export leaves nothing out: one with every path
/// (radiosity), one with direct light only (sampled soft shadows).
const IDS: [(&str, &str); 2] = [
    ("radiosity-shooting", "full"),
    ("soft-shadow-volumes", "direct"),
];
/// Renders each side's moments are taken over.
const RENDERS: &str = "8";

fn write_pfm(path: &Path, width: usize, height: usize, value: f32) {
    let mut bytes = format!("PF\n{width} {height}\n-1.0\n").into_bytes();
    for _ in 0..width * height * 3 {
        bytes.extend(value.to_le_bytes());
    }
    std::fs::write(path, bytes).unwrap();
}

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Mitsuba 3 (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn mitsubas_renders_pass_the_ground_truth_and_lumieres_biased_references_fail_it() {
    support::peers::ready();
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut args = vec![
        "references",
        "-o",
        "suite",
        "--width",
        "64",
        "--samples",
        RENDERS,
        "--ground-truth-paths",
        "8",
    ];
    args.extend(IDS.iter().map(|(id, _)| *id));
    lumiere_ok(&args, d);
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("suite/manifest.json")).unwrap()).unwrap();
    assert_eq!(manifest["schema"], "lumiere-reference-suite/2");
    let tool = Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/mitsuba_moments.py");
    for dir in ["mitsuba", "own"] {
        std::fs::create_dir_all(d.join(dir)).unwrap();
    }
    for (entry, (id, transport)) in manifest["entries"].as_array().unwrap().iter().zip(IDS) {
        assert_eq!(entry["id"], id);
        assert_eq!(entry["ground_truth"]["transport"], transport, "{id}");
        assert_eq!(entry["ground_truth"]["paths"], 64, "{id}");
        assert_eq!(entry["physically_based"]["against"], "ground-truth", "{id}");
        assert_eq!(
            entry["physically_based"]["checks"][0]["test"], "welch",
            "{id}"
        );
        let export = &entry["exports"]["mitsuba"];
        assert_eq!(export["left_out"], serde_json::json!([]), "{id}");
        // As a renderer team would: its renderer's mean and variance over its own
        // renders of the exported scene.
        let out = Command::new("python3")
            .arg(&tool)
            .args([
                "--xml",
                &format!("suite/{}", export["file"].as_str().unwrap()),
            ])
            .args(["--renders", RENDERS, "--spp", "64", "--out"])
            .arg(format!("mitsuba/{id}"))
            .current_dir(d)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        // lumiere's own reference as a candidate: a deterministic one has no
        // variance, a sampled one its seeds'.
        std::fs::copy(
            d.join("suite")
                .join(entry["files"]["reference"].as_str().unwrap()),
            d.join(format!("own/{id}.exr")),
        )
        .unwrap();
        match entry["files"]["variance"].as_str() {
            Some(variance) => {
                std::fs::copy(
                    d.join("suite").join(variance),
                    d.join(format!("own/{id}.variance.exr")),
                )
                .unwrap();
            }
            None => write_pfm(
                &d.join(format!("own/{id}.variance.pfm")),
                entry["width"].as_u64().unwrap() as usize,
                entry["height"].as_u64().unwrap() as usize,
                0.0,
            ),
        }
    }
    let check = |candidates: &str| {
        lumiere(
            &[
                "check",
                "suite/manifest.json",
                candidates,
                "--physically-based",
                "--candidate-renders",
                RENDERS,
            ],
            d,
        )
    };
    let Run { code, stdout, .. } = check("mitsuba");
    eprintln!("{stdout}");
    assert_eq!(code, 0, "{stdout}");
    assert!(
        stdout.contains("2 passed, 0 failed, 0 missing of 2"),
        "{stdout}"
    );
    let Run { code, stdout, .. } = check("own");
    eprintln!("{stdout}");
    assert_eq!(code, 1, "{stdout}");
    assert!(
        stdout.contains("0 passed, 2 failed, 0 missing of 2"),
        "{stdout}"
    );
    // The same candidates without their variance cannot be tested, said per entry.
    std::fs::remove_file(d.join("mitsuba/radiosity-shooting.variance.pfm")).unwrap();
    let Run { code, stdout, .. } = check("mitsuba");
    assert_eq!(code, 1, "{stdout}");
    assert!(
        stdout.contains("no radiosity-shooting.variance.exr or .pfm"),
        "{stdout}"
    );
}
