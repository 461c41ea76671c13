//! The exporters, tested against the real peers: a catalogue scene written as
//! Mitsuba 3 XML and as POV-Ray SDL, rendered by Mitsuba and by POV-Ray, matches
//! lumiere's own render of it (FLIP, NVIDIA's perceptual difference). The peers
//! are installed by the project's script when missing (`.ci/run` runs it too).

use crate::support::{self, lumiere_ok};

use lumiere::image_io;
use std::path::Path;
use std::process::Command;

/// Mitsuba's render of `xml` into `exr`.
fn mitsuba(xml: &str, exr: &str, dir: &Path) {
    let script = format!(
        "import mitsuba as mi\nmi.set_variant('scalar_rgb')\nmi.util.write_bitmap('{exr}', mi.render(mi.load_file('{xml}')))\n"
    );
    let out = Command::new("python3")
        .args(["-c", &script])
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "mitsuba: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// POV-Ray's render of `pov` into `exr` (half floats, linear), 4 × 4 samples per
/// pixel on a regular grid.
fn povray(pov: &str, exr: &str, size: u32, dir: &Path) {
    let out = Command::new("povray")
        .arg(format!("+I{pov}"))
        .arg(format!("+O{exr}"))
        .args([format!("+W{size}"), format!("+H{size}")])
        .args(["+FE", "File_Gamma=1.0", "+A0.0", "+AM1", "+R4", "-D", "-GA"])
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "povray: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn flip(dir: &Path, reference: &str, test: &str) -> f64 {
    let load = |name: &str| image_io::load(&dir.join(name)).unwrap();
    support::flip::mean(&load(reference), &load(test))
}

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs POV-Ray and Mitsuba 3 (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn the_exported_cornell_box_renders_in_mitsuba_and_pov_ray_as_in_lumiere() {
    support::peers::ready();
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let size = ["--width", "128", "--height", "128"];
    // 8 × 8 samples per pixel against Mitsuba's 256 stratified ones, so that edges
    // are antialiased alike.
    let mut args = vec!["render", "cornell-box-point", "--shadows", "ray-cast"];
    args.extend(["--supersample", "8", "-o", "lumiere.exr"]);
    args.extend(size);
    lumiere_ok(&args, d);

    let mut args = vec![
        "export",
        "cornell-box-point",
        "--format",
        "mitsuba",
        "-o",
        "box.xml",
    ];
    args.extend(size);
    lumiere_ok(&args, d);
    mitsuba("box.xml", "mitsuba.exr", d);
    let against_mitsuba = flip(d, "mitsuba.exr", "lumiere.exr");
    assert!(against_mitsuba <= 0.01, "FLIP {against_mitsuba}");

    let mut args = vec![
        "export",
        "cornell-box-point",
        "--format",
        "pov",
        "-o",
        "box.pov",
    ];
    args.extend(size);
    lumiere_ok(&args, d);
    povray("box.pov", "pov.exr", 128, d);
    let against_pov = flip(d, "pov.exr", "lumiere.exr");
    eprintln!("FLIP against Mitsuba {against_mitsuba:.4}, against POV-Ray {against_pov:.4}");
    assert!(against_pov <= 0.01, "FLIP {against_pov}");
}

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs POV-Ray and Mitsuba 3 (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn every_kind_of_light_exports_to_scenes_both_peers_light_where_lumiere_does() {
    support::peers::ready();
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A quad light, a sphere light, a spot (its fog cleared, its cone uniform), a
    // distant light (set
    // on the curved scene).
    let cases: [(&str, &[&str]); 4] = [
        ("cornell-box", &[]),
        ("jittered-soft-shadows", &[]),
        (
            "light-volumes-spot",
            &[
                "--set",
                "medium.extinction=0.0",
                "--set",
                "lights.0.cosine_power=0.0",
            ],
        ),
        (
            "ray-cast-shadows-curved",
            &[
                "--set",
                "lights.0={ type = \"distant\", direction = [0.3, -1.0, -0.2], irradiance = [2.0, 2.0, 2.0] }",
            ],
        ),
    ];
    let lit = |file: &str| {
        let image = image_io::load(&d.join(file)).unwrap();
        let lit = image
            .pixels
            .iter()
            .filter(|p| p.max_element() > 0.01)
            .count();
        lit as f64 / image.pixels.len() as f64
    };
    for (id, sets) in cases {
        // A black background: the peers' pictures have none (an environment
        // emitter would light the scene).
        let size = [
            "--width",
            "48",
            "--height",
            "36",
            "--set",
            "render.background=[0.0, 0.0, 0.0]",
        ];
        for (format, file) in [("mitsuba", "s.xml"), ("pov", "s.pov")] {
            let mut args = vec!["export", id, "--format", format, "-o", file, "--spp", "16"];
            args.extend(size);
            args.extend(sets);
            lumiere_ok(&args, d);
        }
        // Antialiased, as the peers' pictures are.
        let mut args = vec!["render", id, "--supersample", "4", "-o", "l.exr"];
        args.extend(size);
        args.extend(sets);
        lumiere_ok(&args, d);
        mitsuba("s.xml", "m.exr", d);
        povray("s.pov", "p.exr", 48, d);
        // The peers light the same share of the picture as lumiere (the spot made
        // a uniform cone, which is what the peers' spots are).
        let ours = lit("l.exr");
        assert!(ours > 0.05, "{id}: lumiere's picture is dark");
        for file in ["m.exr", "p.exr"] {
            let theirs = lit(file);
            assert!(
                (theirs / ours - 1.0).abs() < 0.25,
                "{id}: {file} lights {theirs:.3} of the picture, lumiere {ours:.3}"
            );
        }
    }
}

#[test]
fn what_cannot_be_carried_over_is_named_and_a_wrong_extension_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let warnings = lumiere_ok(
        &[
            "export",
            "mip-mapping",
            "--format",
            "mitsuba",
            "-o",
            "m.xml",
        ],
        d,
    )
    .stderr;
    assert!(
        warnings.contains("textures and bump maps are left out"),
        "{warnings}"
    );
    let warnings = lumiere_ok(
        &[
            "export",
            "light-volumes-spot",
            "--format",
            "pov",
            "-o",
            "s.pov",
        ],
        d,
    )
    .stderr;
    assert!(
        warnings.contains("participating medium is left out"),
        "{warnings}"
    );
    let unshadowed = lumiere_ok(
        &[
            "export",
            "cornell-box-point",
            "--format",
            "pov",
            "-o",
            "u.pov",
        ],
        d,
    )
    .stderr;
    assert!(unshadowed.contains("casts no shadows"), "{unshadowed}");
    // Glass goes to Mitsuba whole, as its dielectric: Fresnel's split at the
    // index, the reflection white and the transmission the material's.
    let glass = lumiere_ok(
        &[
            "export",
            "photon-map-caustic",
            "--format",
            "mitsuba",
            "-o",
            "g.xml",
        ],
        d,
    )
    .stderr;
    assert_eq!(glass, "");
    let xml = std::fs::read_to_string(d.join("g.xml")).unwrap();
    let dielectric = &xml[xml
        .find("<bsdf type=\"dielectric\">")
        .expect("a dielectric")..];
    let dielectric = &dielectric[..dielectric.find("</bsdf>").unwrap()];
    for line in [
        r#"<float name="int_ior" value="1.5"/>"#,
        r#"<float name="ext_ior" value="1"/>"#,
        r#"<rgb name="specular_reflectance" value="1, 1, 1"/>"#,
        r#"<rgb name="specular_transmittance" value="1, 1, 1"/>"#,
    ] {
        assert!(dielectric.contains(line), "{dielectric}");
    }
    // The same box with its shadows: nothing is left out.
    let quiet = lumiere_ok(
        &["export", "shadow-volumes", "--format", "pov", "-o", "c.pov"],
        d,
    )
    .stderr;
    assert_eq!(quiet, "");
    // POV-Ray's point light: intensity / (2π d²) with d a thousandth of the
    // scene's diagonal, fading as 2d²/r².
    let pov = std::fs::read_to_string(d.join("c.pov")).unwrap();
    let light = pov.lines().find(|l| l.starts_with("light_source")).unwrap();
    let number = |after: &str| -> f64 {
        let rest = &light[light.find(after).unwrap() + after.len()..];
        rest.trim_start()
            .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-'))
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    let fade = number("fade_distance");
    let red = number("color rgb <");
    assert!((red * 2.0 * std::f64::consts::PI * fade * fade / 228437.5 - 1.0).abs() < 1e-9);
    assert!(
        light.contains("<278, 548.6, -279.5>"),
        "z is negated: {light}"
    );

    let out = Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .args(["export", "cornell-box", "--format", "pov", "-o", "box.xml"])
        .current_dir(d)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.lines().count(), 1);
    assert!(stderr.contains("written as .pov"), "{stderr}");
}

/// A Mitsuba export replaces the XML and its meshes together: exporting a scene
/// of fewer materials over an earlier export leaves no stale mesh beside the new
/// ones, and every mesh the XML names is there.
#[test]
fn a_mitsuba_export_replaces_its_meshes_whole() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let meshes = |d: &Path| -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(d.join("scene-meshes"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    };
    lumiere_ok(
        &[
            "export",
            "cornell-box-point",
            "--format",
            "mitsuba",
            "-o",
            "scene.xml",
        ],
        d,
    );
    let many = meshes(d);
    let one = support::camera([0.0, 1.0, 3.0], [0.0, 0.0, 0.0], 40.0, 16, 12)
        + "[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\
               [[lights]]\ntype = \"point\"\nposition = [0.0, 2.0, 2.0]\nintensity = [5.0, 5.0, 5.0]\n\
               [[objects]]\nshape = \"quad\"\nmaterial = \"grey\"\n";
    std::fs::write(d.join("one.toml"), one).unwrap();
    lumiere_ok(
        &[
            "export",
            "one.toml",
            "--format",
            "mitsuba",
            "-o",
            "scene.xml",
        ],
        d,
    );
    let after = meshes(d);
    assert!(many.len() > 1, "{many:?}");
    assert_eq!(after, ["000.obj"]);
    let xml = std::fs::read_to_string(d.join("scene.xml")).unwrap();
    assert_eq!(xml.matches("scene-meshes/").count(), 1, "{xml}");
    let leftovers: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}
