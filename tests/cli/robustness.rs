//! Bad input a user can give by accident: files that are not files, options that
//! would be ignored, work without a bound, outputs a failure could leave half made.

use super::support::*;
use std::path::Path;
use std::process::Command;

#[test]
fn inputs_that_are_not_regular_files_are_refused_without_being_read() {
    let material_with = |texture: &str| {
        format!(
            "\n[textures.t]\nimage = \"{texture}\"\n\n[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\ndiffuse_texture = \"t\"\n"
        )
    };
    let obj = |file: &str| format!("\n[[objects]]\nshape = \"obj\"\nfile = \"{file}\"\n");
    let dir = workspace(&[
        (
            "model.obj",
            "mtllib endless.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        ),
        ("textured.mtl", "newmtl m\nKd 1 1 1\nmap_Kd endless.png\n"),
        (
            "textured.obj",
            "mtllib textured.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n",
        ),
    ]);
    let d = dir.path();
    for name in [
        "endless.toml",
        "endless.obj",
        "endless.mtl",
        "endless.png",
        "endless.pfm",
    ] {
        std::os::unix::fs::symlink("/dev/zero", d.join(name)).unwrap();
    }
    for name in ["waiting.toml", "waiting.png", "waiting.pfm"] {
        let made = Command::new("mkfifo").arg(d.join(name)).status().unwrap();
        assert!(made.success());
    }
    let camera = CAMERA;
    let scenes = [
        ("obj.toml", scene(camera, &obj("endless.obj"))),
        ("mtl.toml", scene(camera, &obj("model.obj"))),
        ("map_kd.toml", scene(camera, &obj("textured.obj"))),
        (
            "texture.toml",
            scene(camera, "").replace("[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n", "")
                + &material_with("waiting.png"),
        ),
        (
            "environment.toml",
            scene(
                camera,
                "\n[environments.e]\nimage = \"endless.pfm\"\nlayout = \"lat-long\"\n",
            ),
        ),
    ];
    for (name, text) in &scenes {
        std::fs::write(d.join(name), text).unwrap();
    }
    let out = d.join("out.png");
    let out_arg = out.to_str().unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["render", "endless.toml", "-o", out_arg],
            "endless.toml",
        ),
        (
            vec!["render", "waiting.toml", "-o", out_arg],
            "waiting.toml",
        ),
        (vec!["render", "obj.toml", "-o", out_arg], "endless.obj"),
        (vec!["render", "mtl.toml", "-o", out_arg], "endless.mtl"),
        (vec!["render", "map_kd.toml", "-o", out_arg], "endless.png"),
        (vec!["render", "texture.toml", "-o", out_arg], "waiting.png"),
        (
            vec!["render", "environment.toml", "-o", out_arg],
            "endless.pfm",
        ),
        (vec!["compare", "endless.pfm", "waiting.pfm"], "endless.pfm"),
        (vec!["compare", "waiting.png", "endless.png"], "waiting.png"),
        (
            vec![
                "envmap",
                "--from",
                "endless.pfm",
                "--layout",
                "lat-long",
                "--cube",
                "-o",
                out_arg,
            ],
            "endless.pfm",
        ),
    ];
    for (args, file) in cases {
        let run = lumiere_within_30_s(&args, d);
        assert_clear_error(&run, "not a regular file", &out);
        assert!(
            run.stderr.contains(file),
            "{args:?} names {file}: {}",
            run.stderr
        );
    }
}

#[test]
fn options_that_would_be_ignored_are_refused_or_do_what_they_say() {
    let dir = workspace(&[]);
    let d = dir.path();
    let out = d.join("never.png");
    let png = d.join("a.png");
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("golden/cornell-box.png"),
        &png,
    )
    .unwrap();
    let before = std::fs::read(&png).unwrap();
    // A difference image written over an input: refused, the input kept.
    let run = lumiere(&["compare", "a.png", "a.png", "--diff", "./a.png"], d);
    assert_clear_error(&run, "--diff ./a.png: is the input a.png", &out);
    assert_eq!(run.code, 2);
    assert_eq!(std::fs::read(&png).unwrap(), before);
    // Numbers that would be used as they are, to no sense.
    for (args, fragment) in [
        (
            vec!["compare", "a.png", "a.png", "--gain", "-1"],
            "'--gain <GAIN>': must be a positive number",
        ),
        (
            vec!["compare", "a.png", "a.png", "--exposure", "nan"],
            "'--exposure <EXPOSURE>': must be a positive number",
        ),
        (
            vec!["bench", "--runs", "0"],
            "'--runs <RUNS>': must be at least 1",
        ),
        (
            vec!["view", "cornell-box", "--benchmark", "0"],
            "--benchmark <N>",
        ),
        (
            vec![
                "render",
                "cornell-box",
                "-o",
                "x.png",
                "--frames",
                "f",
                "--frame-every",
                "0",
            ],
            "'--frame-every <FRAME_EVERY>': must be at least 1",
        ),
        (
            vec!["render", "cornell-box-point", "--aov", "all", "-o", "-"],
            "--aov all writes a directory of images: give -o DIR, not -",
        ),
    ] {
        let run = lumiere(&args, d);
        assert_clear_error(&run, fragment, &out);
    }
    assert!(!d.join("-").exists(), "no directory named -");
    // --test-size is an entry's: a scene file is not called a missing entry.
    std::fs::write(d.join("s.toml"), scene(CAMERA, "")).unwrap();
    let run = lumiere(&["render", "s.toml", "--test-size", "-o", "never.png"], d);
    assert_clear_error(&run, "--test-size: s.toml is a scene file", &out);
    // `--aov list -o FILE` writes the list into FILE.
    let run = lumiere(
        &[
            "render",
            "cornell-box-point",
            "--aov",
            "list",
            "-o",
            "buffers.txt",
        ],
        d,
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.is_empty());
    let list = std::fs::read_to_string(d.join("buffers.txt")).unwrap();
    assert!(list.lines().any(|l| l.starts_with("depth ")), "{list}");
}

/// Work that grows with the scene grows linearly: an OBJ of 200,000 objects of one
/// triangle each loads and renders in about a second (a check of every object
/// against every polygon took minutes; the watchdog stops a run past 30 s).
#[test]
fn a_scene_of_200000_objects_loads_in_linear_time() {
    let mut obj = String::new();
    for i in 0..200_000 {
        let (x, y) = ((i % 500) as f64 * 0.008, (i / 500) as f64 * 0.008);
        obj += &format!(
            "o t{i}\nv {x} {y} 0\nv {} {y} 0\nv {x} {} 0\nf -3 -2 -1\n",
            x + 0.004,
            y + 0.004
        );
    }
    let scene = "[camera]\neye = [2, 1.6, 5]\nlook_at = [2, 1.6, 0]\nfov_y = 60\nwidth = 32\nheight = 24\n\n\
                 [materials.white]\ndiffuse = [0.7, 0.7, 0.7]\n\n\
                 [[lights]]\ntype = \"point\"\nposition = [2, 1.6, 4]\nintensity = [10, 10, 10]\n\n\
                 [[objects]]\nshape = \"obj\"\nfile = \"many.obj\"\nmaterial = \"white\"\n";
    let dir = workspace(&[("many.obj", &obj), ("many.toml", scene)]);
    let run = lumiere_within_30_s(&["render", "many.toml", "-o", "many.png"], dir.path());
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(dir.path().join("many.png").exists());
}

/// A ray march is estimated before it starts and refused over its budget, with the
/// smallest step that fits; its keys are refused where they would be ignored.
#[test]
fn a_ray_march_over_its_budget_is_refused_before_it_starts() {
    let marched = |extra: &str| {
        scene(
            CAMERA,
            &format!("\n[medium]\nextinction = 0.1\nmethod = \"ray-marching\"\n{extra}"),
        )
    };
    let endless = marched("march_step = 1e-9\n");
    let dir = workspace(&[("s.toml", &endless)]);
    let run = lumiere_within_30_s(&["render", "s.toml", "-o", "out.png"], dir.path());
    assert_clear_error(
        &run,
        "medium.march_step = 1e-9 would take about",
        &dir.path().join("out.png"),
    );
    assert!(
        run.stderr.contains("use a step of at least"),
        "{}",
        run.stderr
    );
    // The same march within a raised budget is not refused by the estimate.
    let run = lumiere(
        &[
            "render",
            "s.toml",
            "--set",
            "medium.max_march_steps=1e30",
            "--aov",
            "list",
            "-o",
            "-",
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    render_error(
        &[("s.toml", &marched("max_march_steps = nan\n"))],
        &["s.toml"],
        "medium.max_march_steps must be a count of at least 1, got NaN",
    );
    let volumes = scene(CAMERA, "\n[medium]\nextinction = 0.1\nmarch_step = 0.5\n");
    render_error(
        &[("s.toml", &volumes)],
        &["s.toml"],
        "medium.march_step is ray marching's step; light volumes integrate each lit interval without one",
    );
}

/// Textures are counted against render.max_memory_mb from their headers and
/// resolutions before any is decoded or generated: an 8193² image under the
/// trilinear filter (its pyramid resampled to 16384²) and three 8192² procedural
/// textures (5.5 GB resident before) are refused at once.
#[test]
fn textures_are_refused_over_the_memory_budget_before_they_are_made() {
    let textured = |textures: &str| {
        format!(
            "{}\n{textures}\n[materials.m]\ndiffuse = [0.5, 0.5, 0.5]\ndiffuse_texture = \"t\"\n",
            scene(CAMERA, "").replace("material = \"grey\"", "material = \"m\"")
        )
    };
    let dir = workspace(&[("s.toml", &textured("[textures.t]\nimage = \"big.png\"\n"))]);
    std::fs::write(dir.path().join("big.png"), png_header_only(8193, 8193)).unwrap();
    let run = lumiere_within_30_s(&["render", "s.toml", "-o", "out.png"], dir.path());
    assert_clear_error(
        &run,
        "textures.t.image = big.png would need about 5.4 GiB for its 8193x8193 texels under the trilinear filter",
        &dir.path().join("out.png"),
    );
    let three: String = ["t", "u", "v"]
        .iter()
        .map(|n| format!("[textures.{n}]\nprocedural = \"checkerboard\"\nresolution = 8192\n"))
        .collect();
    let dir = workspace(&[("s.toml", &textured(&three))]);
    let run = lumiere_within_30_s(&["render", "s.toml", "-o", "out.png"], dir.path());
    assert_clear_error(
        &run,
        "textures.v.resolution = 8192 would need about 5.2 GiB",
        &dir.path().join("out.png"),
    );
    // Within a budget raised for them the header is read on and found to hold no
    // pixels: the budget, not the decoder, refused the image above.
    let dir = workspace(&[("s.toml", &textured("[textures.t]\nimage = \"big.png\"\n"))]);
    std::fs::write(dir.path().join("big.png"), png_header_only(8193, 8193)).unwrap();
    let run = lumiere(
        &[
            "render",
            "s.toml",
            "--set",
            "render.max_memory_mb=8192",
            "-o",
            "out.png",
        ],
        dir.path(),
    );
    assert_clear_error(&run, "big.png", &dir.path().join("out.png"));
    assert!(!run.stderr.contains("would need"), "{}", run.stderr);
}

/// A light of every kind that gives nothing is named in a warning (its image is
/// black, or lacks its share, without a word otherwise).
#[test]
fn a_light_that_gives_nothing_is_warned_about() {
    let lights = [
        (
            "point",
            "position = [0.0, 2.0, 2.0]\nintensity = [0.0, 0.0, 0.0]",
            "intensity",
        ),
        (
            "distant",
            "direction = [0.0, -1.0, 0.0]\nirradiance = [0.0, 0.0, 0.0]",
            "irradiance",
        ),
        (
            "sphere",
            "centre = [0.0, 2.0, 0.0]\nradius = 0.25\nradiance = [0.0, 0.0, 0.0]",
            "radiance",
        ),
        (
            "spot",
            "position = [0.0, 2.0, 0.0]\naxis = [0.0, -1.0, 0.0]\ncone_angle = 30.0\nintensity = [0.0, 0.0, 0.0]",
            "intensity",
        ),
    ];
    for (kind, keys, key) in lights {
        let s = scene(CAMERA, "").replace(
            "type = \"point\"\nposition = [0.0, 2.0, 2.0]\nintensity = [5.0, 5.0, 5.0]",
            &format!("type = \"{kind}\"\n{keys}"),
        );
        let dir = workspace(&[("s.toml", &s)]);
        let run = lumiere(&["render", "s.toml", "-o", "out.png"], dir.path());
        assert_eq!(run.code, 0, "{kind}: {}", run.stderr);
        assert!(
            run.stderr.contains(&format!(
                "warning: lights[0]: {key} is zero: the light adds nothing to the image"
            )),
            "{kind}: {}",
            run.stderr
        );
    }
    // A light that gives something is not warned about.
    let dir = workspace(&[("s.toml", &scene(CAMERA, ""))]);
    let run = lumiere(&["render", "s.toml", "-o", "out.png"], dir.path());
    assert!(!run.stderr.contains("is zero"), "{}", run.stderr);
}
