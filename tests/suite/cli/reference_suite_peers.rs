//! A renderer team's use of the reference suite, with a real peer: Mitsuba 3
//! renders the exported hard-shadow scenes of a suite, and `lumiere check` passes
//! them at the tolerance the manifest states; the same scenes rendered without
//! shadows fail it. (docs/testing-your-renderer.md walks through the same steps.)

use crate::support::{self, Run, lumiere};

use std::process::Command;

/// Exact hard-shadow entries whose export leaves nothing out.
const IDS: [&str; 4] = [
    "ray-cast-shadows",
    "scanline-shadows",
    "shadow-polygons",
    "shadow-volumes",
];

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Mitsuba 3 (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn mitsubas_renders_of_the_exported_hard_shadow_scenes_pass_check_and_unshadowed_ones_fail() {
    support::peers::ready();
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let ids: Vec<&str> = IDS
        .iter()
        .copied()
        .filter(|id| !id.contains("none"))
        .collect();
    let mut args = vec!["references", "-o", "suite", "--width", "96"];
    args.extend(&ids);
    let Run { code, stderr, .. } = lumiere(&args, d);
    assert_eq!(code, 0, "{stderr}");
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("suite/manifest.json")).unwrap()).unwrap();
    std::fs::create_dir_all(d.join("mitsuba")).unwrap();
    std::fs::create_dir_all(d.join("unshadowed")).unwrap();
    for entry in manifest["entries"].as_array().unwrap() {
        let id = entry["id"].as_str().unwrap();
        let export = &entry["exports"]["mitsuba"];
        assert_eq!(export["left_out"], serde_json::json!([]), "{id}");
        // As a team's CI would: load the exported XML, render, write an EXR.
        let script = format!(
            "import mitsuba as mi\nmi.set_variant('scalar_rgb')\n\
             mi.util.write_bitmap('mitsuba/{id}.exr', mi.render(mi.load_file('suite/{}')))\n",
            export["file"].as_str().unwrap()
        );
        let out = Command::new("python3")
            .args(["-c", &script])
            .current_dir(d)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let height = entry["height"].to_string();
        let Run { code, stderr, .. } = lumiere(
            &[
                "render",
                id,
                "--width",
                "96",
                "--height",
                &height,
                "--supersample",
                "4",
                "--set",
                "shadows.method=\"none\"",
                "-o",
                &format!("unshadowed/{id}.exr"),
            ],
            d,
        );
        assert_eq!(code, 0, "{stderr}");
    }
    let Run {
        code,
        stdout,
        stderr,
        ..
    } = lumiere(&["check", "suite/manifest.json", "mitsuba"], d);
    eprintln!("{stdout}");
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(stdout.contains(&format!(
        "{0} passed, 0 failed, 0 missing of {0}",
        ids.len()
    )));
    let Run { code, stdout, .. } = lumiere(&["check", "suite/manifest.json", "unshadowed"], d);
    eprintln!("{stdout}");
    assert_eq!(code, 1);
    assert!(
        stdout.contains(&format!(
            "0 passed, {0} failed, 0 missing of {0}",
            ids.len()
        )),
        "{stdout}"
    );
}
