//! Results a user would otherwise get in silence: a black image from a scene with
//! nothing to see or nothing to light it, an output file that was read-only.

use crate::support;

use lumiere::image_io::{self, Image};
use lumiere::scene::{scene_from_table, tables};

use support::Files;

fn camera() -> String {
    support::camera([0.0, 0.0, 3.0], [0.0, 0.0, 0.0], 40.0, 8, 8)
}

fn warnings(text: &str) -> Vec<String> {
    let table = tables::parse(text, "s.toml").unwrap();
    scene_from_table(table, &Files(Default::default()))
        .unwrap()
        .warnings
}

#[test]
fn a_scene_that_renders_black_says_why() {
    let quad = "[materials.m]\ndiffuse = [0.5, 0.5, 0.5]\n[[objects]]\nshape = \"quad\"\nmaterial = \"m\"\n";
    let light =
        "[[lights]]\ntype = \"point\"\nposition = [0.0, 1.0, 1.0]\nintensity = [1.0, 1.0, 1.0]\n";
    assert!(
        warnings(&format!("{}{light}", camera()))
            .iter()
            .any(|w| w.contains("no objects"))
    );
    assert!(
        warnings(&format!("{}{quad}", camera()))
            .iter()
            .any(|w| w.contains("no lights"))
    );
    assert!(warnings(&format!("{}{quad}{light}", camera())).is_empty());
}

#[cfg(unix)]
#[test]
fn a_read_only_output_is_left_alone() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("kept.pfm");
    std::fs::write(&path, b"keep me").unwrap();
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o444)).unwrap();
    let image = Image {
        width: 1,
        height: 1,
        pixels: vec![glam::Vec3::ONE],
    };
    let error = image_io::save(&image, &path, 1.0).expect_err("refused");
    let line = support::error_line(&error);
    assert!(
        line.contains("read-only") && line.contains("kept.pfm"),
        "{line}"
    );
    assert_eq!(std::fs::read(&path).unwrap(), b"keep me");
}
