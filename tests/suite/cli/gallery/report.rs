//! `lumiere check --report`: the triage page passes the gallery's browser checks
//! (whole, described images, local, no script, fits a phone) and lists the worst
//! entries first.

use super::check_pages;
use crate::support::{lumiere, lumiere_ok};
use std::path::Path;

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Chromium (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn the_check_report_passes_the_browser_checks_worst_first() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let ids = [
        "scanline-shadows",
        "scanline-visible-surface",
        "shadow-volumes",
    ];
    lumiere_ok(
        &[&["references", "-o", "suite", "--width", "48"][..], &ids].concat(),
        d,
    );
    std::fs::create_dir(d.join("c")).unwrap();
    // shadow-volumes passes (its own reference), scanline-shadows fails (no
    // shadows), scanline-visible-surface is missing.
    std::fs::copy(
        d.join("suite/shadow-volumes/reference.exr"),
        d.join("c/shadow-volumes.exr"),
    )
    .unwrap();
    lumiere_ok(
        &[
            "render",
            "scanline-shadows",
            "--width",
            "48",
            "--height",
            "48",
            "--supersample",
            "4",
            "--set",
            "shadows.method=\"none\"",
            "-o",
            "c/scanline-shadows.exr",
        ],
        d,
    );
    let check = lumiere(
        &["check", "suite/manifest.json", "c", "--report", "report"],
        d,
    );
    assert_eq!(check.code, 1, "{}", check.stderr);
    let page = d.join("report/index.html");
    let html = std::fs::read_to_string(&page).unwrap();
    let at = |id: &str| html.find(&format!("id=\"{id}\"")).unwrap();
    assert!(at("scanline-visible-surface") < at("scanline-shadows"));
    assert!(at("scanline-shadows") < at("shadow-volumes"));
    assert!(html.contains("1 of 3 passed"));
    let shots = Path::new(env!("CARGO_TARGET_TMPDIR")).join("check-report-screenshots");
    check_pages(&d.join("report"), &[page], &shots);
}
