//! The binary as a user meets it: subcommands, and one clear error line (never a
//! panic, never a half-written file) for every kind of bad input.

mod compare_metrics;
mod contact_sheet;
mod fuzzy_compare;
mod gallery;
mod ground_truth_peers;
mod interrupt;
mod reference_suite;
mod reference_suite_peers;
mod robustness;

use crate::support::*;
use std::path::Path;

#[test]
fn renders_a_catalogue_entry_from_any_directory() {
    let dir = workspace(&[]);
    for name in ["c.png", "c.pfm"] {
        let run = lumiere(
            &[
                "render",
                "cornell-box",
                "--width",
                "24",
                "--height",
                "20",
                "-o",
                name,
            ],
            dir.path(),
        );
        assert_eq!(run.code, 0, "{}", run.stderr);
        let image = lumiere::read_image(&dir.path().join(name)).unwrap();
        assert_eq!((image.width, image.height), (24, 20));
    }
    let compare = lumiere(
        &["compare", "c.png", "c.pfm", "--json", "--diff", "d.png"],
        dir.path(),
    );
    assert_eq!(compare.code, 0, "{}", compare.stderr);
    let figures: serde_json::Value = serde_json::from_str(&compare.stdout).unwrap();
    assert_eq!(figures["max_difference"], 0);
    assert!(dir.path().join("d.png").exists());
}

/// EXR and PFM both hold the linear radiance as f32: the same render written to
/// each reads back bit for bit the same, and `compare` finds no difference; a file
/// that is not an EXR is one error line naming it.
#[test]
fn exr_and_pfm_hold_the_same_linear_image() {
    let dir = workspace(&[("broken.exr", "not an image")]);
    for name in ["c.exr", "c.pfm"] {
        let run = lumiere(
            &["render", "cornell-box", "--test-size", "-o", name],
            dir.path(),
        );
        assert_eq!(run.code, 0, "{}", run.stderr);
    }
    let exr = lumiere::read_image(&dir.path().join("c.exr")).unwrap();
    let pfm = lumiere::read_image(&dir.path().join("c.pfm")).unwrap();
    assert_eq!((exr.width, exr.height), (128, 128));
    assert_eq!(exr, pfm);
    let compare = lumiere(&["compare", "c.exr", "c.pfm", "--json"], dir.path());
    assert_eq!(compare.code, 0, "{}", compare.stderr);
    let figures: serde_json::Value = serde_json::from_str(&compare.stdout).unwrap();
    assert_eq!(figures["rmse"], 0.0);
    assert_eq!(figures["max_difference"], 0);
    assert_eq!(figures["differing_share"], 0.0);
    let run = lumiere(&["compare", "broken.exr", "c.pfm"], dir.path());
    assert_clear_error(&run, "broken.exr", &dir.path().join("nothing"));
}

#[test]
fn renders_a_scene_file_with_overrides() {
    let dir = workspace(&[("s.toml", &scene(CAMERA, ""))]);
    let run = lumiere(
        &[
            "render",
            "s.toml",
            "--set",
            "camera.width=10",
            "--set",
            "render.shading=flat",
            "--supersample",
            "2",
            "-o",
            "s.png",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let image = lumiere::read_image(&dir.path().join("s.png")).unwrap();
    assert_eq!((image.width, image.height), (10, 12));
}

#[test]
fn lists_the_catalogue() {
    let dir = workspace(&[]);
    let run = lumiere(&["list"], dir.path());
    assert_eq!(run.code, 0);
    assert!(
        run.stdout
            .lines()
            .any(|l| l.starts_with("cornell-box ") && l.contains("1984"))
    );
    let json = lumiere(&["list", "--json"], dir.path());
    let entries: serde_json::Value = serde_json::from_str(&json.stdout).unwrap();
    assert!(
        entries
            .as_array()
            .unwrap()
            .iter()
            .any(|e| e["id"] == "scanline-visible-surface")
    );
}

/// `lumiere bench` times what it is asked to, row by row, with rates that agree
/// with its own times (a row's samples over its milliseconds), and names a method
/// that cannot light the scene instead of timing it.
#[test]
fn bench_reports_times_and_rates_per_method() {
    let dir = workspace(&[]);
    let run = lumiere(
        &[
            "bench",
            "--scenes",
            "cornell-box-point,cornell-box",
            "--shadows",
            "none,scanline",
            "--sizes",
            "64",
            "--supersample",
            "1,2",
            "--runs",
            "1",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let rows: Vec<Vec<&str>> = run
        .stdout
        .lines()
        .filter(|l| l.starts_with("cornell-box-point "))
        .map(|l| l.split_whitespace().collect())
        .collect();
    assert_eq!(rows.len(), 4, "{}", run.stdout);
    for row in &rows {
        let n: f64 = row[3].split('x').next().unwrap().parse().unwrap();
        let (ms, rate): (f64, f64) = (row[4].parse().unwrap(), row[5].parse().unwrap());
        let sweep: f64 = row[6].parse().unwrap();
        // Milliseconds are printed to 0.01, rates to 0.1.
        let expected = (64.0 * n).powi(2) / (ms / 1e3) / 1e6;
        let rounding = expected * 0.006 / ms + 0.06;
        assert!((rate - expected).abs() <= rounding, "{row:?}");
        assert!(sweep > 0.0, "{row:?}");
    }
    assert!(
        run.stdout
            .lines()
            .any(|l| l.starts_with("cornell-box ")
                && l.contains("refused: shadow method `scanline`")),
        "{}",
        run.stdout
    );
}

#[test]
fn lists_the_catalogue_by_topic_with_summaries() {
    let dir = workspace(&[]);
    let run = lumiere(&["list"], dir.path());
    assert_eq!(run.code, 0, "{}", run.stderr);
    let headers: Vec<&str> = run.stdout.lines().filter(|l| l.ends_with(']')).collect();
    assert_eq!(headers.len(), 8, "{headers:?}");
    assert_eq!(headers[1], "Hard shadows [hard-shadows]");
    // Each entry's summary follows it, indented.
    let lines: Vec<&str> = run.stdout.lines().collect();
    let at = lines
        .iter()
        .position(|l| l.starts_with("shadow-map-acne "))
        .unwrap();
    assert!(
        lines[at + 1].starts_with("    The bias set to zero"),
        "{}",
        lines[at + 1]
    );

    let run = lumiere(&["list", "--topic", "radiosity", "--brief"], dir.path());
    assert_eq!(run.code, 0, "{}", run.stderr);
    let ids: Vec<&str> = run
        .stdout
        .lines()
        .skip(2)
        .filter(|l| !l.is_empty())
        .map(|l| l.split_whitespace().next().unwrap())
        .collect();
    assert_eq!(ids.len(), 8, "{ids:?}");
    assert!(ids.contains(&"substructuring") && !ids.contains(&"cornell-box"));
}

#[test]
fn show_prints_a_scene_that_renders_as_the_entry_does() {
    let dir = workspace(&[]);
    let run = lumiere(&["show", "shadow-map-acne"], dir.path());
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stdout
            .contains("# L. Williams, \"Casting curved shadows on curved surfaces\"")
    );
    assert!(run.stdout.contains("# The bias set to zero"));
    assert!(run.stdout.contains("map_bias = 0.0"));
    // Its own keys and those of the scene it extends, merged.
    assert!(run.stdout.contains("[camera]") && run.stdout.contains("[[objects]]"));
    let source = lumiere(&["show", "shadow-map-acne", "--source"], dir.path());
    assert!(source.stdout.starts_with("[algorithm]"));
    assert!(
        source
            .stdout
            .contains("extends = \"ray-cast-shadows-curved\"")
    );

    let shown = lumiere(&["show", "cornell-box-point"], dir.path());
    std::fs::write(dir.path().join("shown.toml"), &shown.stdout).unwrap();
    let size = ["--width", "24", "--height", "24"];
    for (scene, out) in [("shown.toml", "a.png"), ("cornell-box-point", "b.png")] {
        let mut args = vec!["render", scene, "-o", out];
        args.extend(size);
        let run = lumiere(&args, dir.path());
        assert_eq!(run.code, 0, "{}", run.stderr);
    }
    let read = |name: &str| std::fs::read(dir.path().join(name)).unwrap();
    assert_eq!(read("a.png"), read("b.png"));
    let run = lumiere(&["show", "cornell-bx"], dir.path());
    assert_eq!(run.code, 1);
    assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    assert!(run.stderr.contains("cornell-box"), "{}", run.stderr);
}

#[test]
fn malformed_toml_names_file_line_and_column() {
    let text = scene(CAMERA, "").replace("fov_y = 40.0", "fov_y = = 40.0");
    render_error(&[("s.toml", &text)], &["s.toml"], "s.toml:4:");
}

#[test]
fn unknown_keys_are_errors() {
    render_error(
        &[("s.toml", &scene(CAMERA, "colour = \"red\"\n"))],
        &["s.toml"],
        "objects[0].colour: unknown field `colour`",
    );
    render_error(
        &[("s.toml", &scene(CAMERA, "resolution = 8\n"))],
        &["s.toml"],
        "`resolution` does not apply",
    );
}

#[test]
fn missing_and_broken_obj_files() {
    let obj = scene(CAMERA, "").replace(
        "shape = \"quad\"",
        "shape = \"obj\"\nfile = \"missing.obj\"",
    );
    render_error(&[("s.toml", &obj)], &["s.toml"], "missing.obj");
    let broken = obj.replace("missing.obj", "broken.obj");
    render_error(
        &[("s.toml", &broken), ("broken.obj", "v 1 2\nf 1 2 3\n")],
        &["s.toml"],
        "broken.obj",
    );
    // Where tobj only says what is wrong, the line is found.
    for (text, fragment) in [
        (
            "v 0 0 0\nv 1 0 0\nv 1 x 0\nf 1 2 3\n",
            "at line 3: `v 1 x 0`",
        ),
        (
            "v 0 0 0\nv 1 0 0\nv 0 1 0\n# ok\nf 1 2 4\n",
            "at line 5: `f 1 2 4`",
        ),
        ("v 0 0 0\nvn 0 0 1\nvn 0 q 1\n", "at line 3: `vn 0 q 1`"),
    ] {
        render_error(
            &[("s.toml", &broken), ("broken.obj", text)],
            &["s.toml"],
            fragment,
        );
    }
    let no_mtl = obj.replace("missing.obj", "m.obj");
    let m_obj = "mtllib nope.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
    render_error(
        &[("s.toml", &no_mtl), ("m.obj", m_obj)],
        &["s.toml"],
        "cannot read nope.mtl",
    );
}

#[test]
fn unknown_ids_suggest_the_nearest() {
    render_error(&[], &["cornel-box"], "did you mean `cornell-box`");
}

#[test]
fn zero_and_absurd_sizes() {
    // The option's range, then the scene key's own check.
    render_error(
        &[],
        &["cornell-box", "--width", "0"],
        "0 is not in 1..=16384",
    );
    render_error(
        &[],
        &["cornell-box", "--width", "100000"],
        "100000 is not in 1..=16384",
    );
    render_error(
        &[],
        &["cornell-box", "--set", "camera.width=0"],
        "width must be between 1",
    );
    render_error(
        &[],
        &["cornell-box", "--set", "camera.width=100000"],
        "width must be between 1",
    );
    render_error(
        &[],
        &["cornell-box", "--width", "16000", "--height", "16000"],
        "samples",
    );
}

#[test]
fn degenerate_cameras() {
    let up = format!("{CAMERA}\nup = [0.0, -1.0, -3.0]");
    render_error(
        &[("s.toml", &scene(&up, ""))],
        &["s.toml"],
        "parallel to the view direction",
    );
    for fov in ["0.0", "180.0"] {
        let camera = CAMERA.replace("40.0", fov);
        render_error(
            &[("s.toml", &scene(&camera, ""))],
            &["s.toml"],
            "fov_y must be strictly between 0 and 180",
        );
    }
    let same = "eye = [1.0, 1.0, 1.0]\nlook_at = [1.0, 1.0, 1.0]\nfov_y = 40.0";
    render_error(
        &[("s.toml", &scene(same, ""))],
        &["s.toml"],
        "the same point",
    );
}

#[test]
fn nan_in_a_vector() {
    let camera = CAMERA.replace("[0.0, 1.0, 3.0]", "[nan, 1.0, 3.0]");
    render_error(
        &[("s.toml", &scene(&camera, ""))],
        &["s.toml"],
        "camera.eye must be finite",
    );
}

#[test]
fn bad_output_and_overrides() {
    render_error(
        &[],
        &["cornell-box", "--set", "camera.width"],
        "expected key=value",
    );
    let dir = workspace(&[]);
    for (output, fragment) in [
        ("out.bmp", "unknown image format"),
        ("no/such/dir/out.png", "cannot write"),
    ] {
        let args = [
            "render",
            "cornell-box",
            "--width",
            "8",
            "--height",
            "8",
            "-o",
            output,
        ];
        let run = lumiere(&args, dir.path());
        assert_clear_error(&run, fragment, &dir.path().join(output));
    }
    let run = lumiere(&["compare", "a.png", "b.png"], dir.path());
    assert_clear_error(&run, "cannot read", &dir.path().join("a.png"));
}

#[test]
fn missing_scene_file() {
    render_error(
        &[],
        &["nothing-here.toml"],
        "cannot read scene nothing-here.toml",
    );
}

#[test]
fn shadow_polygons_lists_and_draws() {
    let dir = workspace(&[("s.toml", &scene(CAMERA, ""))]);
    let run = lumiere(
        &[
            "shadow-polygons",
            "cornell-box-point",
            "--json",
            "--png",
            "plan.png",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let report: serde_json::Value = serde_json::from_str(&run.stdout).unwrap();
    let receivers = report["receivers"].as_array().unwrap();
    assert!(
        receivers
            .iter()
            .any(|r| r["object"] == "cornell/floor" && r["shadowed_area"].as_f64().unwrap() > 1e4)
    );
    assert!(dir.path().join("plan.png").exists());
    let no_point_light = scene(CAMERA, "").replace(
        "type = \"point\"\nposition = [0.0, 2.0, 2.0]\nintensity",
        "type = \"area\"\nvertices = [[0.0, 2.0, 0.0], [0.0, 2.0, 1.0], [1.0, 2.0, 1.0]]\nradiance",
    );
    let run = lumiere(&["shadow-polygons", "s2.toml"], dir.path());
    assert_ne!(run.code, 0);
    std::fs::write(dir.path().join("s2.toml"), no_point_light).unwrap();
    let run = lumiere(
        &["shadow-polygons", "s2.toml", "--png", "p2.png"],
        dir.path(),
    );
    assert_clear_error(&run, "no point light", &dir.path().join("p2.png"));
}

#[test]
fn shadow_methods_and_the_visibility_buffer() {
    let dir = workspace(&[]);
    for method in [
        "ray-cast",
        "scanline",
        "shadow-polygons",
        "shadow-map",
        "shadow-volumes",
    ] {
        let args = [
            "render",
            "cornell-box-point",
            "--width",
            "24",
            "--height",
            "24",
            "--shadows",
            method,
            "--aov",
            "shadow",
            "-o",
            "v.png",
        ];
        let run = lumiere(&args, dir.path());
        assert_eq!(run.code, 0, "{method}: {}", run.stderr);
        let image = lumiere::read_image(&dir.path().join("v.png")).unwrap();
        // White where lit, black in shadow: both occur.
        assert!(
            image.pixels.iter().any(|p| p.x == 1.0) && image.pixels.iter().any(|p| p.x == 0.0),
            "{method}"
        );
    }
    let run = lumiere(
        &[
            "render",
            "cornell-box-point",
            "--shadows",
            "fog",
            "-o",
            "v.png",
        ],
        dir.path(),
    );
    assert_ne!(run.code, 0);
    assert!(run.stderr.contains("invalid value 'fog'"), "{}", run.stderr);
    let run = lumiere(
        &[
            "render",
            "shadow-volumes-open-mesh",
            "--width",
            "16",
            "--height",
            "12",
            "-o",
            "o.png",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0);
    assert!(
        run.stderr
            .contains("warning: 1 object is not a closed 2-manifold (`tube`)"),
        "{}",
        run.stderr
    );
    // The Cornell box's open walls and blocks: one line, naming them all.
    let run = lumiere(
        &[
            "render",
            "cornell-box-point",
            "--shadows",
            "shadow-volumes",
            "--width",
            "16",
            "--height",
            "12",
            "-o",
            "c.png",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let warnings: Vec<&str> = run
        .stderr
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .collect();
    assert_eq!(warnings.len(), 1, "{}", run.stderr);
    assert!(
        warnings[0].starts_with(
            "warning: 3 objects are not closed 2-manifolds (`cornell/left`, `cornell/short_block`, `cornell/tall_block`)"
        ),
        "{}",
        warnings[0]
    );
}

/// The complete example of docs/scene-format.md renders as written.
#[test]
fn the_documented_example_renders() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/scene-format.md"))
        .unwrap();
    let start = doc.find("```toml\n").expect("an example") + "```toml\n".len();
    let example = &doc[start..start + doc[start..].find("```").unwrap()];
    let dir = workspace(&[("example.toml", example)]);
    let run = lumiere(
        &[
            "render",
            "example.toml",
            "--width",
            "32",
            "--height",
            "24",
            "-o",
            "e.png",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
}

/// A user's scene can start from a catalogue entry and change only what differs.
#[test]
fn a_scene_file_extends_a_catalogue_entry() {
    let text = "extends = \"cornell-box\"\n[camera]\nwidth = 20\nheight = 20\n[materials.red]\ndiffuse = [0.1, 0.1, 0.6]\n";
    let dir = workspace(&[("mine.toml", text)]);
    let run = lumiere(&["render", "mine.toml", "-o", "m.png"], dir.path());
    assert_eq!(run.code, 0, "{}", run.stderr);
    let image = lumiere::read_image(&dir.path().join("m.png")).unwrap();
    assert_eq!((image.width, image.height), (20, 20));
    // The wall on the left, red in the entry, is blue here.
    let left = image.pixels[10 * 20 + 1];
    assert!(left.z > left.x, "{left}");
}

/// A scene whose quad wears the texture `texture` (a `[textures.t]` body).
fn textured_scene(texture: &str) -> String {
    scene(CAMERA, "")
        .replace(
            "[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]",
            "[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\ndiffuse_texture = \"t\"",
        )
        .replacen(
            "[camera]",
            &format!("[textures.t]\n{texture}\n\n[camera]"),
            1,
        )
}

#[test]
fn missing_corrupt_and_empty_texture_images() {
    let missing = textured_scene("image = \"missing.png\"");
    render_error(&[("s.toml", &missing)], &["s.toml"], "missing.png");

    let corrupt = textured_scene("image = \"corrupt.png\"");
    render_error(
        &[("s.toml", &corrupt), ("corrupt.png", "not an image at all")],
        &["s.toml"],
        "corrupt.png",
    );

    let empty = textured_scene("image = \"empty.png\"");
    let dir = workspace(&[("s.toml", &empty)]);
    std::fs::write(dir.path().join("empty.png"), png_header_only(0, 0)).unwrap();
    let run = lumiere(&["render", "s.toml", "-o", "out.png"], dir.path());
    assert_clear_error(&run, "empty.png", &dir.path().join("out.png"));
}

#[test]
fn bad_textures_and_mappings() {
    let unknown = textured_scene("procedural = \"checkerboard\"")
        .replace("diffuse_texture = \"t\"", "diffuse_texture = \"wood\"");
    render_error(
        &[("s.toml", &unknown)],
        &["s.toml"],
        "unknown texture `wood`",
    );
    let neither = textured_scene("wrap = \"clamp\"");
    render_error(
        &[("s.toml", &neither)],
        &["s.toml"],
        "needs an `image` file or a `procedural`",
    );
    let filter = textured_scene("procedural = \"grid\"\nfilter = \"cubic\"");
    render_error(&[("s.toml", &filter)], &["s.toml"], "filter");
    let degenerate = textured_scene("procedural = \"grid\"").replace(
        "diffuse_texture = \"t\"",
        "diffuse_texture = \"t\"\nmapping = { surface = \"cylinder\", axis = [0.0, 1.0, 0.0], reference = [0.0, 2.0, 0.0] }",
    );
    render_error(&[("s.toml", &degenerate)], &["s.toml"], "degenerate frame");
    let zero_axis = textured_scene("procedural = \"grid\"").replace(
        "diffuse_texture = \"t\"",
        "diffuse_texture = \"t\"\nmapping = { surface = \"sphere\", axis = [0.0, 0.0, 0.0] }",
    );
    render_error(
        &[("s.toml", &zero_axis)],
        &["s.toml"],
        "axis is a zero vector",
    );
    let zero_size = textured_scene("procedural = \"grid\"").replace(
        "diffuse_texture = \"t\"",
        "diffuse_texture = \"t\"\nmapping = { surface = \"plane\", size = [0.0, 1.0] }",
    );
    render_error(
        &[("s.toml", &zero_size)],
        &["s.toml"],
        "size must be positive",
    );
}

#[test]
fn a_textured_scene_renders() {
    let card = include_bytes!("../../../algorithms/textures/test-card.png");
    let text = textured_scene("image = \"card.png\"\nfilter = \"summed-area\"");
    let dir = workspace(&[("s.toml", &text)]);
    std::fs::write(dir.path().join("card.png"), card).unwrap();
    let run = lumiere(&["render", "s.toml", "-o", "out.png"], dir.path());
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(dir.path().join("out.png").exists());
}

/// A lamp over a floor, lit by radiosity with `extra` radiosity keys.
fn radiosity_scene(floor_rho: &str, lamp_emission: &str, extra: &str) -> String {
    format!(
        "[camera]\n{CAMERA}\nwidth = 16\nheight = 12\n\n\
         [materials.floor]\ndiffuse = [{floor_rho}, 0.5, 0.5]\n\
         [materials.lamp]\ndiffuse = [0.0, 0.0, 0.0]\nemission = {lamp_emission}\n\n\
         [[objects]]\nshape = \"quad\"\nmaterial = \"floor\"\n\
         [[objects]]\nshape = \"quad\"\nmaterial = \"lamp\"\n\
         transform = [{{ rotate = {{ axis = [1.0, 0.0, 0.0], degrees = 180.0 }} }}, {{ translate = [0.0, 1.0, 0.0] }}]\n\n\
         [radiosity]\nresolution = 16\nelement_size = 0.25\n{extra}"
    )
}

#[test]
fn radiosity_renders_with_frames_and_a_convergence_animation() {
    let dir = workspace(&[("lamp.toml", &radiosity_scene("0.5", "[1.0, 1.0, 1.0]", ""))]);
    let run = lumiere(
        &[
            "render",
            "lamp.toml",
            "-o",
            "out.png",
            "--frames",
            "steps",
            "--ambient",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stderr.contains("shooting: 2 patches, 32 elements"),
        "{}",
        run.stderr
    );
    assert!(dir.path().join("out.png").exists());
    assert!(dir.path().join("steps/step-00001.png").exists());
    let gif = std::fs::read(dir.path().join("steps/convergence.gif")).unwrap();
    assert_eq!(&gif[..6], b"GIF89a");
    let run = lumiere(
        &[
            "render",
            "lamp.toml",
            "-o",
            "out.pfm",
            "--radiosity",
            "gathering",
            "--form-factors",
            "nusselt",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stderr.contains("gathering: 2 patches"),
        "{}",
        run.stderr
    );
}

/// A frames directory holds one run: a second run with other steps replaces the
/// first one's frames and animation (leaving other files alone), and the animation
/// has a frame per step image and one for the final solution.
#[test]
fn frames_directories_hold_one_run() {
    let dir = workspace(&[("lamp.toml", &radiosity_scene("0.5", "[1.0, 1.0, 1.0]", ""))]);
    let frames = |every: &str| {
        let run = lumiere(
            &[
                "render",
                "lamp.toml",
                "-o",
                "out.png",
                "--frames",
                "steps",
                "--frame-every",
                every,
            ],
            dir.path(),
        );
        assert_eq!(run.code, 0, "{}", run.stderr);
        let mut names: Vec<String> = std::fs::read_dir(dir.path().join("steps"))
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        names
    };
    let first = frames("1");
    std::fs::write(dir.path().join("steps/notes.txt"), "mine").unwrap();
    let second = frames("2");
    let steps: Vec<&String> = second.iter().filter(|n| n.starts_with("step-")).collect();
    assert!(!steps.is_empty());
    assert!(
        steps.iter().all(|n| {
            let k: u32 = n["step-".len()..n.len() - 4].parse().unwrap();
            k.is_multiple_of(2)
        }),
        "{second:?} after {first:?}"
    );
    assert!(
        second.contains(&"notes.txt".to_string())
            && second.contains(&"convergence.gif".to_string())
    );
    // Nothing staged is left beside it.
    let beside: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(beside.is_empty(), "{beside:?}");
    use image::AnimationDecoder;
    let gif = std::fs::File::open(dir.path().join("steps/convergence.gif")).unwrap();
    let decoder = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(gif)).unwrap();
    let count = decoder.into_frames().collect_frames().unwrap().len();
    assert_eq!(count, steps.len() + 1);
}

/// `--aov all` writes every buffer or none: with one earlier file read-only, the
/// run fails naming it and every earlier file is left as it was.
#[test]
fn every_buffer_or_none() {
    let dir = workspace(&[]);
    let all = |size: &str| {
        lumiere(
            &[
                "render",
                "shadow-map-curved",
                "--aov",
                "all",
                "--width",
                size,
                "--height",
                size,
                "-o",
                "bufs",
            ],
            dir.path(),
        )
    };
    assert_eq!(all("16").code, 0);
    let bufs = dir.path().join("bufs");
    let before: Vec<(String, Vec<u8>)> = {
        let mut files: Vec<_> = std::fs::read_dir(&bufs)
            .unwrap()
            .map(|e| e.unwrap().path())
            .map(|p| {
                (
                    p.file_name().unwrap().to_string_lossy().into_owned(),
                    std::fs::read(&p).unwrap(),
                )
            })
            .collect();
        files.sort();
        files
    };
    let locked = bufs.join("depth.pfm");
    let mut permissions = std::fs::metadata(&locked).unwrap().permissions();
    permissions.set_readonly(true);
    std::fs::set_permissions(&locked, permissions).unwrap();
    let run = all("20");
    assert_clear_error(
        &run,
        "depth.pfm: the file is read-only",
        &dir.path().join("nothing"),
    );
    for (name, bytes) in &before {
        assert_eq!(
            &std::fs::read(bufs.join(name)).unwrap(),
            bytes,
            "{name} changed"
        );
    }
    let staged = std::fs::read_dir(dir.path()).unwrap().filter(|e| {
        e.as_ref()
            .unwrap()
            .file_name()
            .to_string_lossy()
            .starts_with('.')
    });
    assert_eq!(staged.count(), 0);
}

#[test]
fn radiosity_bad_input() {
    let out = |dir: &tempfile::TempDir| dir.path().join("out.png");
    for (text, fragment) in [
        (radiosity_scene("1.0", "[1.0, 1.0, 1.0]", ""), "below 1"),
        (
            radiosity_scene("0.5", "[0.0, 0.0, 0.0]", ""),
            "no emitting surface",
        ),
        (
            radiosity_scene("0.5", "[1.0, 1.0, 1.0]", "patch_size = -1.0"),
            "radiosity.patch_size",
        ),
        (
            radiosity_scene("0.5", "[1.0, 1.0, 1.0]", "tolerance = 2.0"),
            "radiosity.tolerance",
        ),
        (
            radiosity_scene("0.5", "[1.0, 1.0, 1.0]", "solver = \"jacobi\""),
            "solver",
        ),
        (
            radiosity_scene(
                "0.5",
                "[1.0, 1.0, 1.0]",
                "solver = \"gathering\"\nmax_memory_mb = 1\npatch_size = 0.01",
            ),
            "use the shooting solver",
        ),
        (
            radiosity_scene("0.5", "[1.0, 1.0, 1.0]", "subdivide = -0.1"),
            "radiosity.subdivide",
        ),
        (
            radiosity_scene("0.5", "[1.0, 1.0, 1.0]", "subdivide = 0.1"),
            "use the gathering solver",
        ),
    ] {
        let dir = workspace(&[("s.toml", &text)]);
        let run = lumiere(&["render", "s.toml", "-o", "out.png"], dir.path());
        assert_clear_error(&run, fragment, &out(&dir));
    }
}

const SPOT: &str = "\n[[lights]]\ntype = \"spot\"\nposition = [0.0, 2.0, 0.0]\naxis = [0.0, -1.0, 0.0]\ncone_angle = 30.0\nintensity = [4.0, 4.0, 4.0]\n";

/// Every kind of light renders, without shadows and with ray casting (which samples
/// extended lights); a hard-shadow method refuses the lights it cannot shadow, in one
/// line naming both; `area` still names a polygon light.
#[test]
fn five_kinds_of_light_render() {
    let lights = format!(
        "{SPOT}distribution = [[0.0, 1.0], [20.0, 0.7], [30.0, 0.0]]\n\n\
         [[lights]]\ntype = \"distant\"\nname = \"sun\"\ndirection = [0.3, -1.0, 0.2]\nirradiance = [1.0, 1.0, 1.0]\n\n\
         [[lights]]\ntype = \"sphere\"\ncentre = [1.0, 1.5, 0.0]\nradius = 0.25\nradiance = [2.0, 2.0, 2.0]\n\n\
         [[lights]]\ntype = \"area\"\nvertices = [[-0.5, 2.0, 0.5], [0.5, 2.0, 0.5], [0.5, 2.0, -0.5], [-0.5, 2.0, -0.5]]\nradiance = [1.0, 1.0, 1.0]\n"
    );
    let text = scene(CAMERA, &lights);
    let dir = workspace(&[("s.toml", &text)]);
    for (method, refused) in [
        ("shadow-map", "light 2 (distant `sun`)"),
        ("scanline", "light 2 (distant `sun`)"),
        (
            "shadow-volumes",
            "light 3 (sphere): it is a hard-shadow method for point, spot and distant lights",
        ),
        ("shadow-polygons", "light 2 (distant `sun`)"),
    ] {
        let run = lumiere(
            &["render", "s.toml", "--shadows", method, "-o", "o.png"],
            dir.path(),
        );
        assert_clear_error(
            &run,
            &format!("shadow method `{method}` cannot shadow {refused}"),
            &dir.path().join("o.png"),
        );
    }
    for method in ["none", "ray-cast"] {
        let run = lumiere(
            &["render", "s.toml", "--shadows", method, "-o", "o.png"],
            dir.path(),
        );
        assert_eq!(run.code, 0, "{method}: {}", run.stderr);
        let image = lumiere::read_image(&dir.path().join("o.png")).unwrap();
        assert!(image.pixels.iter().any(|p| p.x > 0.0), "{method}: black");
    }
}

#[test]
fn bad_lights() {
    let sphere = "\n[[lights]]\ntype = \"sphere\"\nname = \"bulb\"\ncentre = [0.0, 2.0, 0.0]\nradiance = [1.0, 1.0, 1.0]\n";
    let distant = "\n[[lights]]\ntype = \"distant\"\nirradiance = [1.0, 1.0, 1.0]\n";
    for (extra, fragment) in [
        (
            format!("{sphere}radius = 0.0\n"),
            "lights[1] (`bulb`): radius must be a positive number, got 0",
        ),
        (
            format!("{distant}direction = [0.0, 0.0, 0.0]\n"),
            "lights[1]: direction must not be zero, got [0.0, 0.0, 0.0]",
        ),
        (
            SPOT.replace("[0.0, -1.0, 0.0]", "[0.0, 0.0, 0.0]"),
            "axis must not be zero",
        ),
        (
            SPOT.replace("30.0", "95.0"),
            "cone_angle must be in (0, 90] degrees, got 95",
        ),
        (
            SPOT.replace("30.0", "0.0"),
            "cone_angle must be in (0, 90] degrees, got 0",
        ),
        (
            format!("{SPOT}distribution = [[0.0, 1.0], [20.0, 0.7], [20.0, 0.0]]\n"),
            "distribution angles must increase, got 20 then 20",
        ),
        (
            format!("{SPOT}distribution = [[0.0, 1.0], [20.0, -0.5]]\n"),
            "distribution[1]: factor must be a non-negative number, got -0.5",
        ),
        (
            format!("{SPOT}cosine_power = 2.0\ndistribution = [[0.0, 1.0]]\n"),
            "give `cosine_power` or `distribution`, not both",
        ),
        (
            format!("{SPOT}cosine_power = -1.0\n"),
            "cosine_power must be a non-negative number, got -1",
        ),
        (
            format!("{distant}direction = [0.0, -1.0, 0.0]\nradius = 2.0\n"),
            "unknown field `radius`",
        ),
        (
            "\n[[lights]]\ntype = \"laser\"\n".to_string(),
            "unknown variant `laser`",
        ),
    ] {
        render_error(&[("s.toml", &scene(CAMERA, &extra))], &["s.toml"], fragment);
    }
}

#[test]
fn form_factors_prints_the_matrix_as_json() {
    // Two unit squares facing each other at distance 1: the closed form is 0.1998.
    let text = camera([0.0, 0.5, 3.0], [0.0, 0.5, 0.0], 40.0, 8, 8)
        + "[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\
        [[objects]]\nshape = \"quad\"\nname = \"floor\"\nmaterial = \"grey\"\n\
        [[objects]]\nshape = \"quad\"\nname = \"ceiling\"\nmaterial = \"grey\"\n\
        transform = [{ rotate = { axis = [1.0, 0.0, 0.0], degrees = 180.0 } }, { translate = [0.0, 1.0, 0.0] }]\n";
    let dir = workspace(&[("pair.toml", &text)]);
    let run = lumiere(
        &[
            "form-factors",
            "pair.toml",
            "--method",
            "analytic",
            "--elements",
            "16",
            "--json",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let report: serde_json::Value = serde_json::from_str(&run.stdout).unwrap();
    assert_eq!(report["patches"][0]["name"], "floor");
    assert!((report["patches"][1]["area"].as_f64().unwrap() - 1.0).abs() < 1e-12);
    let f = report["factors"][0][1].as_f64().unwrap();
    assert!((f - 0.1998249).abs() < 2e-4, "{f}");
    assert_eq!(report["factors"][0][0].as_f64().unwrap(), 0.0);
    let run = lumiere(
        &["form-factors", "pair.toml", "--resolution", "1"],
        dir.path(),
    );
    assert_ne!(run.code, 0);
    assert!(!run.stderr.contains("panicked"));
}

#[test]
fn a_bent_obj_face_is_split_with_a_warning() {
    let obj = scene(CAMERA, "").replace(
        "shape = \"quad\"\nmaterial = \"grey\"",
        "shape = \"obj\"\nfile = \"bent.obj\"\nmaterial = \"grey\"",
    );
    // A unit square with one corner raised by half its side.
    let bent = "v 0 0 0\nv 1 0 0\nv 1 0.5 1\nv 0 0 1\nf 1 2 3 4\n";
    let dir = workspace(&[("s.toml", &obj), ("bent.obj", bent)]);
    let run = lumiere(&["render", "s.toml", "-o", "out.png"], dir.path());
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stderr.starts_with("warning: bent.obj"),
        "{}",
        run.stderr
    );
    assert!(run.stderr.contains("is not planar"), "{}", run.stderr);
    // The measured Cornell box's red wall is only 0.2% off: no warning.
    let run = lumiere(
        &[
            "render",
            "cornell-box",
            "--width",
            "8",
            "--height",
            "8",
            "-o",
            "c.png",
        ],
        dir.path(),
    );
    assert_eq!(run.stderr, "");
}

/// `--aov list` names the buffers the scene's frame makes, `--aov all -o DIR` writes
/// each (ids and counts as PNG, values as PFM), `--aov NAME` one, and a name the
/// frame does not make is one error line listing those it does.
#[test]
fn buffers_as_outputs() {
    let dir = workspace(&[]);
    let size = ["--width", "24", "--height", "18"];
    let base = |extra: &[&'static str]| {
        let mut args = vec!["render", "cornell-box-point"];
        args.extend(size);
        args.extend(extra);
        args
    };
    let run = lumiere(
        &base(&["--shadows", "shadow-volumes", "--aov", "list", "-o", "-"]),
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    for name in [
        "polygon",
        "depth",
        "normal",
        "uv",
        "visibility-0",
        "shadow-volume-counts-0",
    ] {
        assert!(
            run.stdout.lines().any(|l| l.starts_with(name)),
            "{name}: {}",
            run.stdout
        );
    }
    let run = lumiere(
        &base(&["--shadows", "shadow-map", "--aov", "all", "-o", "buffers"]),
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let written = |name: &str| dir.path().join("buffers").join(name);
    for file in [
        "polygon.png",
        "depth.pfm",
        "normal.pfm",
        "visibility-0.pfm",
        "shadow-map-0-py.pfm",
    ] {
        assert!(written(file).exists(), "{file}");
    }
    let depth = lumiere::read_image(&written("depth.pfm")).unwrap();
    assert_eq!((depth.width, depth.height), (24, 18));
    let map = lumiere::read_image(&written("shadow-map-0-py.pfm")).unwrap();
    assert_eq!((map.width, map.height), (1024, 1024));
    let run = lumiere(&base(&["--aov", "polygon", "-o", "ids.pfm"]), dir.path());
    assert_eq!(run.code, 0, "{}", run.stderr);
    let ids = lumiere::read_image(&dir.path().join("ids.pfm")).unwrap();
    // The numbers themselves: polygon ids, -1 where nothing is seen.
    assert!(ids.pixels.iter().all(|p| p.x == p.x.round() && p.x >= -1.0));
    let run = lumiere(
        &base(&["--aov", "shadow-map-0-px", "-o", "m.pfm"]),
        dir.path(),
    );
    assert_clear_error(
        &run,
        "no buffer `shadow-map-0-px`; it has: polygon, depth",
        &dir.path().join("m.pfm"),
    );
    let run = lumiere(
        &[
            "render",
            "radiosity-shooting",
            "--width",
            "16",
            "--height",
            "16",
            "--steps",
            "5",
            "--aov",
            "list",
            "-o",
            "-",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    for name in ["element", "radiosity", "hemicube-top", "hemicube-side1"] {
        assert!(
            run.stdout.lines().any(|l| l.starts_with(name)),
            "{name}: {}",
            run.stdout
        );
    }
}

/// The quad-lit Cornell box under a point-light method: one line naming both.
#[test]
fn a_method_refuses_a_light_it_cannot_shadow() {
    let dir = workspace(&[]);
    for method in [
        "scanline",
        "shadow-polygons",
        "shadow-map",
        "shadow-volumes",
    ] {
        let run = lumiere(
            &["render", "cornell-box", "--shadows", method, "-o", "o.png"],
            dir.path(),
        );
        assert_clear_error(
            &run,
            &format!("shadow method `{method}` cannot shadow light 0 (polygon"),
            &dir.path().join("o.png"),
        );
    }
    let run = lumiere(
        &[
            "render",
            "cornell-box",
            "--width",
            "32",
            "--height",
            "32",
            "--shadows",
            "ray-cast",
            "-o",
            "o.png",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
}

/// The binary started in `dir`, its standard output and error piped.
/// Runs the binary with its standard output closed before it writes: a reader that
/// went away (`lumiere list | head -1`).
fn lumiere_into_closed_pipe(args: &[&str], dir: &Path) -> Run {
    let mut child = spawned(args, dir);
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("the binary ends");
    Run {
        code: out.status.code().unwrap_or(-1),
        stdout: String::new(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// A closed pipe on standard output ends a command quietly: status 0, no panic.
#[test]
fn a_closed_pipe_ends_quietly() {
    let dir = workspace(&[]);
    for name in ["a.png", "b.png"] {
        let run = lumiere(
            &[
                "render",
                "cornell-box",
                "--width",
                "16",
                "--height",
                "16",
                "-o",
                name,
            ],
            dir.path(),
        );
        assert_eq!(run.code, 0, "{}", run.stderr);
    }
    for args in [
        &["list"][..],
        &["list", "--json"],
        &["compare", "a.png", "b.png", "--json"],
        &["compare", "a.png", "b.png"],
        &["form-factors", "cornell-box", "--method", "analytic"],
        &["shadow-polygons", "cornell-box-point"],
        &["render", "shadow-map-curved", "--aov", "list", "-o", "-"],
    ] {
        let run = lumiere_into_closed_pipe(args, dir.path());
        assert!(!run.stderr.contains("panicked"), "{args:?}: {}", run.stderr);
        assert_eq!(run.code, 0, "{args:?}: {}", run.stderr);
        assert_eq!(run.stderr, "", "{args:?}");
    }
}

/// A reader that stops after the first line (`compare … | head -1`) does not hide a
/// failed threshold: the verdict is still exit status 1, with its line.
#[test]
fn a_closed_pipe_does_not_hide_a_failed_comparison() {
    let dir = workspace(&[]);
    for (name, exposure) in [("a.png", "1.0"), ("b.png", "2.0")] {
        let set = format!("render.exposure={exposure}");
        let run = lumiere(
            &[
                "render",
                "cornell-box",
                "--width",
                "16",
                "--height",
                "16",
                "--set",
                &set,
                "-o",
                name,
            ],
            dir.path(),
        );
        assert_eq!(run.code, 0, "{}", run.stderr);
    }
    let run = lumiere_into_closed_pipe(
        &["compare", "a.png", "b.png", "--max-rmse", "0.001"],
        dir.path(),
    );
    assert_eq!(run.code, 1, "{}", run.stderr);
    assert!(
        run.stderr.starts_with("error: ") && run.stderr.contains("--max-rmse"),
        "{}",
        run.stderr
    );
}

/// A channel that is not a number in one image only is a difference of the whole
/// range, not a black pixel equal to the other image's black.
#[test]
fn compare_counts_a_nan_as_a_difference() {
    let dir = workspace(&[]);
    let pfm = |name: &str, value: f32| {
        let mut bytes = b"PF\n1 1\n-1.0\n".to_vec();
        for _ in 0..3 {
            bytes.extend(value.to_le_bytes());
        }
        std::fs::write(dir.path().join(name), bytes).unwrap();
    };
    pfm("black.pfm", 0.0);
    pfm("nan.pfm", f32::NAN);
    let run = lumiere(
        &["compare", "black.pfm", "nan.pfm", "--max-difference", "2"],
        dir.path(),
    );
    assert_eq!(run.code, 1, "{}", run.stderr);
    assert!(
        run.stdout.contains("max difference  255/255"),
        "{}",
        run.stdout
    );
    let same = lumiere(
        &["compare", "nan.pfm", "nan.pfm", "--max-difference", "0"],
        dir.path(),
    );
    assert_eq!(same.code, 0, "{}", same.stderr);
}

/// `compare` as a regression test's check: the figures, then one error line naming the
/// threshold exceeded and the measured value; 0 within, 1 beyond, 2 for bad input.
#[test]
fn compare_fails_beyond_its_thresholds() {
    let dir = workspace(&[("broken.png", "not an image")]);
    let sized = |name: &str, extra: &[&str]| {
        let mut args = vec!["render", "cornell-box", "--height", "20"];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["-o", name]);
        let run = lumiere(&args, dir.path());
        assert_eq!(run.code, 0, "{}", run.stderr);
    };
    sized("a.png", &["--width", "24"]);
    sized("b.png", &["--width", "24", "--set", "render.exposure=1.5"]);
    sized("small.png", &["--width", "8"]);
    let within = lumiere(
        &[
            "compare",
            "a.png",
            "a.png",
            "--max-rmse",
            "0",
            "--max-difference",
            "0",
            "--max-differing",
            "0",
        ],
        dir.path(),
    );
    assert_eq!(within.code, 0, "{}", within.stderr);
    assert!(within.stdout.contains("rmse"));
    assert_eq!(within.stderr, "");

    let figures = lumiere(&["compare", "a.png", "b.png", "--json"], dir.path());
    assert_eq!(figures.code, 0, "{}", figures.stderr);
    let figures: serde_json::Value = serde_json::from_str(&figures.stdout).unwrap();
    let largest = figures["max_difference"].as_u64().unwrap();
    assert!(largest > 2, "{figures}");

    let beyond = lumiere(
        &["compare", "a.png", "b.png", "--max-difference", "2"],
        dir.path(),
    );
    assert_eq!(beyond.code, 1, "{}", beyond.stderr);
    assert!(
        beyond.stdout.contains("max difference"),
        "{}",
        beyond.stdout
    );
    assert_clear_error(&beyond, "--max-difference 2", &dir.path().join("nothing"));
    assert!(
        beyond.stderr.contains(&format!("{largest}/255")),
        "{}",
        beyond.stderr
    );
    // A threshold not exceeded is not named.
    let one = lumiere(
        &[
            "compare",
            "a.png",
            "b.png",
            "--json",
            "--max-rmse",
            "0",
            "--max-difference",
            "255",
        ],
        dir.path(),
    );
    assert_eq!(one.code, 1, "{}", one.stderr);
    serde_json::from_str::<serde_json::Value>(&one.stdout).expect("the figures as JSON");
    assert_clear_error(&one, "--max-rmse 0", &dir.path().join("nothing"));
    assert!(!one.stderr.contains("--max-difference"), "{}", one.stderr);
    let share = lumiere(
        &["compare", "a.png", "b.png", "--max-differing", "0.001"],
        dir.path(),
    );
    assert_eq!(share.code, 1, "{}", share.stderr);
    assert_clear_error(&share, "--max-differing 0.001", &dir.path().join("nothing"));

    for (args, fragment) in [
        (&["compare", "broken.png", "a.png"][..], "broken.png"),
        (
            &["compare", "missing.png", "a.png", "--max-rmse", "0.1"],
            "missing.png",
        ),
        (&["compare", "a.png", "small.png", "--max-rmse", "0.1"], "8"),
        (
            &["compare", "a.png", "b.png", "--max-differing", "1.5"],
            "--max-differing",
        ),
        (
            &["compare", "a.png", "b.png", "--max-rmse=-1"],
            "--max-rmse",
        ),
    ] {
        let run = lumiere(args, dir.path());
        assert_eq!(run.code, 2, "{args:?}: {}", run.stderr);
        assert_clear_error(&run, fragment, &dir.path().join("nothing"));
    }
}

/// The README's regression check: a render at the entry's test size against its golden.
#[test]
fn the_readme_compare_example_works() {
    let dir = workspace(&[]);
    let run = lumiere(
        &["render", "cornell-box", "--test-size", "-o", "out.png"],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let golden = concat!(env!("CARGO_MANIFEST_DIR"), "/golden/cornell-box.png");
    let run = lumiere(
        &[
            "compare",
            "out.png",
            golden,
            "--diff",
            "diff.png",
            "--max-difference",
            "2",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(dir.path().join("diff.png").exists());
}

/// `--set` changes what the scene defines: a misspelt material or texture name (an
/// entry nothing uses) is refused with the nearest name, while new settings tables,
/// a material an object is given, and an OBJ model's MTL material are accepted.
#[test]
fn overrides_refuse_entries_nothing_uses() {
    let grey = scene(CAMERA, "");
    let files = [("s.toml", grey.as_str())];
    render_error(
        &files,
        &["s.toml", "--set", "materials.gery.diffuse=[1, 0, 0]"],
        "no material `gery` that anything uses (did you mean `grey`?)",
    );
    render_error(
        &[],
        &[
            "perspective-texture",
            "--set",
            "materials.afine.interpolation=perspective",
        ],
        "did you mean `affine`?",
    );
    render_error(
        &[],
        &[
            "perspective-texture",
            "--set",
            "textures.chekcs.filter=nearest",
        ],
        "did you mean `checks`?",
    );
    render_error(
        &files,
        &["s.toml", "--set", "objects.3.material=grey"],
        "past the end",
    );
    let dir = workspace(&files);
    for args in [
        &[
            "s.toml",
            "--set",
            "materials.red.diffuse=[0.8, 0.1, 0.1]",
            "--set",
            "objects.0.material=red",
        ][..],
        &[
            "s.toml",
            "--set",
            "shadows.light_samples=8",
            "--set",
            "render.band_rows=7",
        ],
        &[
            "cornell-box",
            "--width",
            "16",
            "--height",
            "16",
            "--set",
            "materials.white.diffuse=[0.2, 0.2, 0.9]",
        ],
    ] {
        let mut all = vec!["render"];
        all.extend_from_slice(args);
        all.extend_from_slice(&["-o", "ok.png"]);
        let run = lumiere(&all, dir.path());
        assert_eq!(run.code, 0, "{args:?}: {}", run.stderr);
    }
}

/// `--steps`, `--ambient` and `--frames` are the shooting solver's; with gathering they
/// would do nothing, so they are refused.
#[test]
fn shooting_options_are_refused_with_gathering() {
    for (option, fragment) in [
        (
            &["--steps", "5"][..],
            "--steps belongs to the shooting solver",
        ),
        (&["--ambient"], "--ambient belongs to the shooting solver"),
        (
            &["--frames", "steps"],
            "--frames belongs to the shooting solver",
        ),
    ] {
        let mut args = vec!["radiosity-gathering"];
        args.extend_from_slice(option);
        render_error(&[], &args, fragment);
        let mut args = vec!["cornell-box", "--radiosity", "gathering"];
        args.extend_from_slice(option);
        render_error(&[], &args, fragment);
    }
}

/// Counts that drive allocations are checked before anything is allocated: one
/// line naming the setting, its value and what to do, never an abort.
#[test]
fn counts_that_drive_allocations_are_checked_first() {
    for (args, fragment) in [
        (
            &["--element-size", "0.0001"][..],
            "radiosity.element_size = 0.0001 would need",
        ),
        (
            &["--element-size", "1"][..],
            "radiosity.element_size = 1 would need",
        ),
        (
            &[
                "--hemicube-resolution",
                "4096",
                "--set",
                "radiosity.max_memory_mb=16",
            ][..],
            "radiosity.resolution = 4096 would need",
        ),
    ] {
        let dir = workspace(&[]);
        let mut all = vec!["render", "radiosity-shooting"];
        all.extend_from_slice(args);
        all.extend_from_slice(&["-o", "out.png"]);
        let run = lumiere(&all, dir.path());
        assert_clear_error(&run, fragment, &dir.path().join("out.png"));
        assert!(
            run.stderr.contains("raise radiosity.max_memory_mb"),
            "{}",
            run.stderr
        );
    }
    for shape in ["sphere", "cylinder"] {
        let text = scene(
            CAMERA,
            &format!(
                "[[objects]]\nshape = \"{shape}\"\nmaterial = \"grey\"\nresolution = 100000\n"
            ),
        );
        render_error(&[("s.toml", &text)], &["s.toml"], "objects[1]");
        render_error(
            &[("s.toml", &text)],
            &["s.toml"],
            "objects[1]: resolution must be from",
        );
    }
    // The scene's geometry, object by object: two spheres of 131,072 quadrilaterals
    // fit 450 MiB, a third does not.
    let balls: String = (0..3)
        .map(|i| format!("[[objects]]\nshape = \"sphere\"\nmaterial = \"grey\"\nresolution = 512\ntransform = [{{ translate = [{i}.0, 0.0, 0.0] }}]\n"))
        .collect();
    let text = scene(CAMERA, &format!("\n[render]\nmax_memory_mb = 450\n{balls}"));
    render_error(
        &[("s.toml", &text)],
        &["s.toml"],
        "objects[3]: resolution = 512 would need about",
    );
    render_error(
        &[("s.toml", &text)],
        &["s.toml"],
        "for the scene's 393217 polygons with this object's 131072, more than the 450.0 MiB that render.max_memory_mb allows",
    );
    // Adaptive subdivision: each level is estimated before it is cut (here the
    // first fits the budget, the second, about 36 MiB, does not).
    let dir = workspace(&[]);
    let run = lumiere(
        &[
            "render",
            "cornell-box",
            "--radiosity",
            "gathering",
            "--patch-size",
            "140",
            "--element-size",
            "70",
            "--subdivide",
            "1e-9",
            "--set",
            "radiosity.subdivision_levels=8",
            "--set",
            "radiosity.max_memory_mb=16",
            "--width",
            "16",
            "--height",
            "16",
            "-o",
            "out.png",
        ],
        dir.path(),
    );
    assert_clear_error(
        &run,
        "for level 2 of adaptive subdivision (cutting 2934 of 2948 elements into four), more than the 16.0 MiB",
        &dir.path().join("out.png"),
    );
    assert!(
        run.stderr.contains("fewer subdivision_levels"),
        "{}",
        run.stderr
    );
    // A budget so large that its count of bytes would overflow is refused, not
    // turned into no limit at all.
    for key in ["radiosity", "shadows"] {
        let dir = workspace(&[]);
        let set = format!("{key}.max_memory_mb=17592186044416");
        let run = lumiere(
            &[
                "render",
                "radiosity-shooting",
                "--set",
                &set,
                "-o",
                "out.png",
            ],
            dir.path(),
        );
        assert_clear_error(
            &run,
            &format!("{key}.max_memory_mb must be from 1 to 1048576 (1 TiB), got 17592186044416"),
            &dir.path().join("out.png"),
        );
    }
    let text = scene(
        CAMERA,
        "\n[shadows]\nmethod = \"shadow-map\"\nmap_resolution = 8192\n",
    );
    render_error(
        &[("s.toml", &text)],
        &["s.toml"],
        "shadows.map_resolution = 8192 would need about 1.5 GiB",
    );
    // The maps of all lights together: 2048² is 96 MiB a light, 1.1 GiB for twelve.
    let lights: String = (0..12)
        .map(|i| {
            format!(
                "\n[[lights]]\ntype = \"point\"\nposition = [{i}.0, 2.0, 2.0]\nintensity = [1.0, 1.0, 1.0]\n"
            )
        })
        .collect();
    let text = scene(
        CAMERA,
        &format!("\n[shadows]\nmethod = \"shadow-map\"\nmap_resolution = 2048\n{lights}"),
    );
    render_error(
        &[("s.toml", &text)],
        &["s.toml"],
        "the six shadow-map faces of each of the scene's 13 lights",
    );
    let text = scene(
        CAMERA,
        "\n[shadows]\nmethod = \"shadow-map\"\nmap_resolution = 2048\n",
    );
    let dir = workspace(&[("s.toml", &text)]);
    let run = lumiere(&["render", "s.toml", "-o", "out.png"], dir.path());
    assert_eq!(run.code, 0, "one light's 2048² maps fit: {}", run.stderr);
}

/// A PFM header whose size overflows (or exceeds the data after it) is one error
/// line naming the file, not a panic or an allocation.
#[test]
fn compare_refuses_a_crafted_pfm_header() {
    let dir = workspace(&[]);
    std::fs::write(
        dir.path().join("big.pfm"),
        b"PF\n4294967295 4294967295\n-1.0\n0123456789ab",
    )
    .unwrap();
    std::fs::write(dir.path().join("one.pfm"), b"PF\n1 1\n-1.0\n0123456789ab").unwrap();
    let run = lumiere(&["compare", "big.pfm", "one.pfm"], dir.path());
    assert_clear_error(&run, "big.pfm", &dir.path().join("nothing"));
    // Refused from its header by the memory budget, before anything is decoded.
    assert!(
        run.stderr.contains("big.pfm (18446744065119617025 pixels)"),
        "{}",
        run.stderr
    );
}

/// The soft-shadow methods' settings and lights: one clear line each.
#[test]
fn soft_shadow_bad_input() {
    let sphere = "\n[[lights]]\ntype = \"sphere\"\nname = \"bulb\"\nradiance = [1.0, 1.0, 1.0]\n";
    for (extra, args, fragment) in [
        (
            format!("{sphere}centre = [0.0, 1.0, 3.0]\nradius = 0.5\n"),
            vec![],
            "lights[1] (`bulb`): the sphere light (radius 0.5) encloses the eye",
        ),
        (
            String::new(),
            vec!["--shadows", "soft-shadow-volumes", "--set", "shadows.light_points=0"],
            "shadows.light_points must be between 1 and 1024 (points replacing each light), got 0",
        ),
        (
            String::new(),
            vec!["--shadows", "jittered-soft-shadows", "--set", "shadows.rings=65"],
            "shadows.rings must be at most 64",
        ),
        (
            String::new(),
            vec!["--set", "shadows.sampling=random"],
            "unknown variant `random`",
        ),
        (
            format!("{sphere}centre = [0.0, 3.0, 0.0]\nradius = 0.5\n"),
            vec!["--shadows", "umbra-penumbra"],
            "shadow method `umbra-penumbra` cannot shadow light 1 (sphere `bulb`)",
        ),
        (
            format!("{sphere}centre = [0.0, 3.0, 0.0]\nradius = 0.5\n"),
            vec!["--shadows", "soft-shadow-volumes"],
            "shadow method `soft-shadow-volumes` cannot shadow light 1 (sphere `bulb`)",
        ),
        (
            String::new(),
            vec!["--shadows", "jittered-soft-shadows"],
            "shadow method `jittered-soft-shadows` cannot shadow light 0 (point)",
        ),
        (
            "\n[[lights]]\ntype = \"polygon\"\nvertices = [[0.0, 2.0, 0.0], [1.0, 2.0, 0.0], [1.0, 2.5, 1.0], [0.0, 2.0, 1.0]]\nradiance = [1.0, 1.0, 1.0]\n".to_string(),
            vec!["--shadows", "umbra-penumbra"],
            "the polygon is not planar",
        ),
        (
            "\n[[lights]]\ntype = \"polygon\"\nvertices = [[0.0, 2.0, 0.0], [1.0, 2.0, 0.0], [2.0, 2.0, 0.0]]\nradiance = [1.0, 1.0, 1.0]\n".to_string(),
            vec!["--shadows", "umbra-penumbra"],
            "the polygon has zero area",
        ),
    ] {
        let mut all = vec!["s.toml"];
        all.extend(args);
        render_error(&[("s.toml", &scene(CAMERA, &extra))], &all, fragment);
    }
    // The quad-lit Cornell box under the sphere-light method.
    let dir = workspace(&[]);
    let run = lumiere(
        &[
            "render",
            "cornell-box",
            "--shadows",
            "jittered-soft-shadows",
            "-o",
            "o.png",
        ],
        dir.path(),
    );
    assert_clear_error(
        &run,
        "shadow method `jittered-soft-shadows` cannot shadow light 0 (polygon",
        &dir.path().join("o.png"),
    );
}

/// The soft-shadow methods' buffers: the umbra map's three levels and the blocked
/// count, listed and written.
#[test]
fn soft_shadow_buffers() {
    let dir = workspace(&[]);
    let run = lumiere(
        &["render", "umbra-penumbra", "--aov", "list", "-o", "-"],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("umbra-0"), "{}", run.stdout);
    let run = lumiere(
        &[
            "render",
            "soft-shadow-volumes",
            "--test-size",
            "--aov",
            "blocked-0",
            "-o",
            "b.pfm",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let blocked = lumiere::read_image(&dir.path().join("b.pfm")).unwrap();
    // Counts of 0 to 4 hidden points, every one of them somewhere.
    let mut seen = [false; 5];
    for p in &blocked.pixels {
        let c = p.x;
        assert!(c == c.round() && (0.0..=4.0).contains(&c), "{c}");
        seen[c as usize] = true;
    }
    assert!(seen.iter().all(|&s| s), "{seen:?}");
}

/// A participating medium's bad input: one clear line each.
#[test]
fn medium_bad_input() {
    for (medium, fragment) in [
        (
            "extinction = -0.1",
            "medium.extinction must be a non-negative number",
        ),
        (
            "extinction = inf",
            "medium.extinction must be a non-negative number",
        ),
        (
            "extinction = 0.1\nalbedo = 1.5",
            "medium.albedo must be between 0 and 1",
        ),
        (
            "extinction = 0.1\nalbedo = -0.1",
            "medium.albedo must be between 0 and 1",
        ),
        (
            "extinction = 0.1\nphase = \"henyey-greenstein\"\ng = 1.0",
            "medium.g must be strictly between -1 and 1, got 1",
        ),
        (
            "extinction = 0.1\ng = 0.5",
            "medium.g is Henyey-Greenstein's asymmetry",
        ),
        ("extinction = 0.1\nphase = \"mie\"", "unknown variant `mie`"),
        (
            "extinction = 0.1\nnodes = 0",
            "medium.nodes must be between 1 and 64, got 0",
        ),
        (
            "extinction = 0.1\nmarch_step = -1.0",
            "medium.march_step must be a positive length",
        ),
        (
            "extinction = 0.1\nextent = { min = [0.0, 0.0, 0.0], max = [1.0, -1.0, 1.0] }",
            "medium.extent needs finite corners with min below max",
        ),
        ("albedo = 0.5", "missing field `extinction`"),
    ] {
        let extra = format!("\n[medium]\n{medium}\n");
        render_error(&[("s.toml", &scene(CAMERA, &extra))], &["s.toml"], fragment);
    }
}

/// The medium's buffers: lit intervals per light and the in-scattered light.
#[test]
fn medium_buffers() {
    let dir = workspace(&[]);
    let run = lumiere(
        &["render", "light-volumes-spot", "--aov", "list", "-o", "-"],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("lit-intervals-0") && run.stdout.contains("inscattered"));
    let run = lumiere(
        &[
            "render",
            "light-volumes-spot",
            "--test-size",
            "--aov",
            "lit-intervals-0",
            "-o",
            "l.pfm",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let lit = lumiere::read_image(&dir.path().join("l.pfm")).unwrap();
    // One lit interval for most rays, two for those passing through the ball's shadow.
    let ones = lit.pixels.iter().filter(|p| p.x == 1.0).count();
    let twos = lit.pixels.iter().filter(|p| p.x == 2.0).count();
    assert!(
        ones > 1000 && twos > 100,
        "{ones} rays with one lit interval, {twos} with two"
    );
}

#[test]
fn envmap_captures_a_scene_and_converts_between_layouts() {
    let dir = workspace(&[]);
    let run = lumiere(
        &[
            "envmap",
            "reflection-mapping-parallax",
            "--at",
            "0,1,0",
            "--hide",
            "ball",
            "--cube",
            "--size",
            "16",
            "-o",
            "room.png",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("cube map, 64x48"), "{}", run.stdout);
    let cross = image::open(dir.path().join("room.png")).unwrap();
    assert_eq!((cross.width(), cross.height()), (64, 48));
    for (to, size) in [("--sphere", (16, 16)), ("--lat-long", (32, 16))] {
        let run = lumiere(
            &[
                "envmap", "--from", "room.png", "--layout", "cube", to, "-o", "out.pfm",
            ],
            dir.path(),
        );
        assert_eq!(run.code, 0, "{}", run.stderr);
        let out = lumiere::read_image(&dir.path().join("out.pfm")).unwrap();
        assert_eq!((out.width, out.height), size);
    }
    // A scene naming the written cross renders with it.
    let scene = format!(
        "{}\n[environments.room]\nimage = \"room.png\"\nlayout = \"cube\"\n\
         [materials.chrome]\nmirror = [0.9, 0.9, 0.9]\nenvironment = \"room\"\n",
        scene(CAMERA, "")
    )
    .replace("material = \"grey\"", "material = \"chrome\"");
    std::fs::write(dir.path().join("chrome.toml"), scene).unwrap();
    let run = lumiere(&["render", "chrome.toml", "-o", "chrome.png"], dir.path());
    assert_eq!(run.code, 0, "{}", run.stderr);
}

#[test]
fn envmap_refuses_bad_input_in_one_line() {
    let dir = workspace(&[]);
    let out = dir.path().join("out.png");
    let wide = image::RgbImage::new(30, 20);
    wide.save(dir.path().join("wide.png")).unwrap();
    for (args, fragment) in [
        (
            vec!["envmap", "cornell-box", "--cube", "-o", "out.png"],
            "a capture needs --at X,Y,Z",
        ),
        (
            vec![
                "envmap",
                "cornell-box",
                "--at",
                "1,2",
                "--cube",
                "-o",
                "out.png",
            ],
            "--at 1,2: expected three finite numbers",
        ),
        (
            vec!["envmap", "cornell-box", "--at", "0,0,0", "-o", "out.png"],
            "--cube, --sphere or --lat-long",
        ),
        (
            vec![
                "envmap",
                "cornell-box",
                "--at",
                "0,0,0",
                "--hide",
                "nothing",
                "--cube",
                "-o",
                "out.png",
            ],
            "--hide nothing: the scene has no object of that name",
        ),
        (
            vec![
                "envmap", "--from", "wide.png", "--layout", "sphere", "--cube", "-o", "out.png",
            ],
            "a sphere map must be square, got 30x20",
        ),
        (
            vec![
                "envmap", "--from", "wide.png", "--layout", "cube", "--sphere", "-o", "out.png",
            ],
            "a cross image must be 4:3",
        ),
        (
            vec![
                "envmap", "--from", "wide.png", "--layout", "lat-long", "--cube", "--size", "0",
                "-o", "out.png",
            ],
            "--size must be between 1 and 4096",
        ),
    ] {
        let run = lumiere(&args, dir.path());
        assert_clear_error(&run, fragment, &out);
    }
}

#[test]
fn numbers_are_refused_in_the_scene_files_words() {
    let negative = scene(CAMERA, "").replace("width = 16", "width = -5");
    render_error(
        &[("s.toml", &negative)],
        &["s.toml"],
        "camera.width must be between 1 and 16384, got -5",
    );
    render_error(
        &[("s.toml", "[render]\nexposure = 1.0\n")],
        &["s.toml"],
        "the scene: missing the `[camera]` table",
    );
    let huge = scene(CAMERA, "").replace(
        "intensity = [5.0, 5.0, 5.0]",
        "intensity = [1e39, 1.0, 1.0]",
    );
    render_error(
        &[("s.toml", &huge)],
        &["s.toml"],
        "intensity must be at most 3.4028235e38 (a 32-bit float), got [1e39, 1.0, 1.0]",
    );
    // A negative number on the command line is a value, not an unknown option.
    let dir = workspace(&[]);
    let run = lumiere(
        &["render", "cornell-box", "--width", "-5", "-o", "out.png"],
        dir.path(),
    );
    assert_ne!(run.code, 0);
    assert!(
        run.stderr.contains("invalid value '-5' for '--width"),
        "{}",
        run.stderr
    );
    assert!(!run.stderr.contains("-- -5"), "{}", run.stderr);
    assert!(!dir.path().join("out.png").exists());
}

/// Usage errors are one line too, exit status 2: clap's message, what continues it
/// (the missing arguments, the possible values, the real range of a size), a tip
/// naming a similar argument, and where help is; no usage summary, no tip to put
/// `--` before a value.
#[test]
fn usage_errors_take_one_line() {
    let dir = workspace(&[]);
    for (args, fragments) in [
        (
            &["render", "x", "--bogus"][..],
            &[
                "unexpected argument '--bogus'",
                "see `lumiere render --help`",
            ][..],
        ),
        (
            &["render", "x", "--widht", "5"],
            &["(a similar argument exists: '--width')"],
        ),
        (&["render"], &["not provided: --output <OUTPUT> <SCENE>"]),
        (
            &["render", "x", "--shadows", "bogus"],
            &["[possible values: none, ray-cast"],
        ),
        (
            &["render", "x", "-o", "y.png", "--width", "-5"],
            &["-5 is not in 1..=16384"],
        ),
        (
            &["render", "x", "-o", "y.png", "--height", "20000"],
            &["20000 is not in 1..=16384"],
        ),
        (
            &["compare", "a", "b", "--max-difference", "-1"],
            &["-1 is not in 0..=255"],
        ),
        (
            &["rendr"],
            &[
                "(a similar subcommand exists: 'render')",
                "see `lumiere --help`",
            ],
        ),
    ] {
        let run = lumiere(args, dir.path());
        assert_eq!(run.code, 2, "{args:?}: {}", run.stderr);
        let lines: Vec<&str> = run.stderr.lines().collect();
        assert_eq!(lines.len(), 1, "{args:?}: {}", run.stderr);
        assert!(lines[0].starts_with("error: "), "{}", lines[0]);
        assert!(
            !lines[0].contains("Usage") && !lines[0].contains("-- -"),
            "{}",
            lines[0]
        );
        for fragment in fragments {
            assert!(
                lines[0].contains(fragment),
                "`{fragment}` not in: {}",
                lines[0]
            );
        }
    }
    // Help is still help.
    let help = lumiere(&["render", "--help"], dir.path());
    assert_eq!(help.code, 0);
    assert!(help.stdout.contains("Usage:"));
}

#[test]
fn silent_results_are_warned_about() {
    // Everything behind the camera.
    let behind = scene(
        "eye = [0.0, 1.0, 3.0]\nlook_at = [0.0, 1.0, 6.0]\nfov_y = 40.0",
        "",
    );
    let dir = workspace(&[("s.toml", &behind)]);
    let run = lumiere(&["render", "s.toml", "-o", "out.png"], dir.path());
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stderr
            .contains("warning: no polygon lies in front of the camera"),
        "{}",
        run.stderr
    );
    // Radiance beyond a 32-bit float: a very bright light a hair above the floor.
    let blinding = scene(CAMERA, "")
        .replace("position = [0.0, 2.0, 2.0]", "position = [0.0, 0.05, 0.0]")
        .replace(
            "intensity = [5.0, 5.0, 5.0]",
            "intensity = [3e38, 3e38, 3e38]",
        );
    let dir = workspace(&[("s.toml", &blinding)]);
    let run = lumiere(&["render", "s.toml", "-o", "out.pfm"], dir.path());
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stderr
            .contains("pixels have infinite or undefined radiance"),
        "{}",
        run.stderr
    );
    // A scene in view says nothing.
    let fine = workspace(&[("s.toml", &scene(CAMERA, ""))]);
    let run = lumiere(&["render", "s.toml", "-o", "out.png"], fine.path());
    assert_eq!((run.code, run.stderr.as_str()), (0, ""));
}

/// Writing into a directory that does not exist names that directory and the
/// system's reason, not the temporary file the image is first written to.
#[test]
fn a_missing_output_directory_is_named_without_temporary_names() {
    let dir = workspace(&[("s.toml", &scene(CAMERA, ""))]);
    let out = dir.path().join("nodir/sub/x.png");
    let run = lumiere(&["render", "s.toml", "-o", "nodir/sub/x.png"], dir.path());
    assert_clear_error(&run, "nodir/sub", &out);
    assert!(
        run.stderr.contains("No such file or directory") && !run.stderr.contains(".tmp"),
        "{}",
        run.stderr
    );
}

/// `export --format gltf` and `--format obj` write their files, which render (the
/// glTF) and read (the OBJ's sidecar) back; what glTF leaves out is a warning
/// line, and what is read from a glTF and left out is one too.
#[test]
fn exports_gltf_and_obj_that_read_back() {
    let dir = workspace(&[]);
    let run = lumiere(
        &[
            "export",
            "cornell-box",
            "--format",
            "gltf",
            "-o",
            "box.gltf",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stderr
            .lines()
            .any(|l| l.starts_with("warning: export: light 0 (polygon")
                && l.contains("not a punctual light")),
        "{}",
        run.stderr
    );
    let run = lumiere(
        &[
            "render", "box.gltf", "--width", "16", "--height", "16", "-o", "box.png",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stderr
            .lines()
            .any(|l| l.starts_with("warning: gltf: material")
                && l.contains("its emission is left out")),
        "{}",
        run.stderr
    );
    let image = lumiere::read_image(&dir.path().join("box.png")).unwrap();
    assert_eq!((image.width, image.height), (16, 16));

    let run = lumiere(
        &[
            "export",
            "cornell-box-point",
            "--format",
            "obj",
            "-o",
            "box.obj",
        ],
        dir.path(),
    );
    // The point-lit box is lumiere's unshadowed scene: the only thing said.
    assert_eq!(
        (run.code, run.stderr.as_str()),
        (
            0,
            "warning: export: lumiere's scene casts no shadows (shadows.method = \"none\"); the exported lights cast them\n"
        )
    );
    for file in ["box.obj", "box.mtl", "box.json"] {
        assert!(dir.path().join(file).is_file(), "{file}");
    }
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("box.json")).unwrap()).unwrap();
    assert_eq!(json["lights"][0]["kind"], "point");
    assert_eq!(json["obj"], "box.obj");
    // The wrong extension is refused before anything is written.
    let run = lumiere(
        &["export", "cornell-box", "--format", "gltf", "-o", "box.glb"],
        dir.path(),
    );
    assert_clear_error(
        &run,
        "a glTF scene is written as .gltf",
        &dir.path().join("box.glb"),
    );
}
