//! Bad input a user can give by accident: files that are not files, options that
//! would be ignored, work without a bound, outputs a failure could leave half made.

use crate::support::*;
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
        // Settings of one method given to another that ignores them.
        (
            vec![
                "render",
                "ray-tracing",
                "--shadows",
                "shadow-map",
                "-o",
                "x.png",
            ],
            "shadows.method = \"shadow-map\": ray tracing (global.method = \"ray-tracing\") casts its own shadow rays",
        ),
        (
            vec![
                "render",
                "ray-tracing",
                "--set",
                "global.window_depth=3",
                "-o",
                "x.png",
            ],
            "global.window_depth is read by two-pass, rushmeier-torrance; ray-tracing (global.method = \"ray-tracing\") would ignore it",
        ),
        (
            vec![
                "render",
                "ray-tracing",
                "--set",
                "global.mechanisms=[\"diffuse-diffuse\"]",
                "-o",
                "x.png",
            ],
            "global.mechanisms is read by two-pass, rushmeier-torrance; ray-tracing",
        ),
        (
            vec![
                "render",
                "shadow-map-box",
                "--set",
                "shadows.map_filter=\"none\"",
                "-o",
                "x.png",
            ],
            "shadows.pcf = 5 is the box filter's kernel, which map_filter = \"none\" does not use",
        ),
        (
            vec![
                "render",
                "shadow-map-pcf",
                "--set",
                "shadows.pcf=3",
                "-o",
                "x.png",
            ],
            "shadows.pcf = 3 is the box filter's kernel, which map_filter = \"percentage-closer\" does not use",
        ),
        (
            vec![
                "envmap",
                "--from",
                "a.png",
                "--layout",
                "cube",
                "--sphere",
                "--set",
                "camera.width=8",
                "-o",
                "x.png",
            ],
            "'--from <MAP>' cannot be used with '--set <KEY=VALUE>'",
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
    let scene = camera([2.0, 1.6, 5.0], [2.0, 1.6, 0.0], 60.0, 32, 24)
        + "[materials.white]\ndiffuse = [0.7, 0.7, 0.7]\n\n\
                 [[lights]]\ntype = \"point\"\nposition = [2, 1.6, 4]\nintensity = [10, 10, 10]\n\n\
                 [[objects]]\nshape = \"obj\"\nfile = \"many.obj\"\nmaterial = \"white\"\n";
    let dir = workspace(&[("many.obj", &obj), ("many.toml", &scene)]);
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

/// Messages say what was given in the scene's words: a whole number past what a
/// scene holds, a number where a name goes; a megabyte name or a key of 100,000
/// characters is cut to its ends; a refusal that can be made before a solve is.
#[test]
fn messages_name_the_value_in_the_scene_words() {
    let s = [("s.toml", scene(CAMERA, ""))];
    let s: Vec<(&str, &str)> = s.iter().map(|(n, t)| (*n, t.as_str())).collect();
    render_error(
        &s,
        &["s.toml", "--set", "shadows.seed=18446744073709551615"],
        "18446744073709551615 is beyond the whole numbers a scene holds",
    );
    render_error(
        &s,
        &["s.toml", "--set", "render.shading=3"],
        "render.shading: expected one of its names, in quotes",
    );
    let dir = workspace(&s);
    let d = dir.path();
    let out = d.join("never.png");
    let key = format!("render.{}=1", "k".repeat(100_000));
    let run = lumiere(&["render", "s.toml", "--set", &key, "-o", "never.png"], d);
    assert_clear_error(&run, "characters]", &out);
    assert!(run.stderr.len() < 1000, "{} bytes", run.stderr.len());
    let name = "m".repeat(1 << 20);
    let text = scene(CAMERA, "").replace("material = \"grey\"", &format!("material = \"{name}\""));
    std::fs::write(d.join("long.toml"), text).unwrap();
    let run = lumiere(&["render", "long.toml", "-o", "never.png"], d);
    assert_clear_error(&run, "characters]", &out);
    assert!(run.stderr.len() < 1000, "{} bytes", run.stderr.len());
    // Refused before the solve, and naming the key that made the count.
    let run = lumiere_within_30_s(
        &[
            "render",
            "radiosity-gathering",
            "--aov",
            "hemicube-top",
            "--hemicube-element",
            "99999999",
            "-o",
            "never.png",
        ],
        d,
    );
    assert_clear_error(&run, "--hemicube-element 99999999: the mesh has", &out);
    let run = lumiere(
        &[
            "render",
            "radiosity-gathering",
            "--patch-size",
            "1e-9",
            "-o",
            "never.png",
        ],
        d,
    );
    assert_clear_error(&run, "radiosity.patch_size", &out);
    assert!(
        run.stderr.contains("more than 1.8e19 patches"),
        "{}",
        run.stderr
    );
    // A byte that is not text, with its line.
    std::fs::write(
        d.join("bad.obj"),
        b"v 0 0 0\nv 1 0 0\nv 0 \xff 1\nf 1 2 3\n",
    )
    .unwrap();
    std::fs::write(
        d.join("obj.toml"),
        scene(
            CAMERA,
            "\n[[objects]]\nshape = \"obj\"\nfile = \"bad.obj\"\nmaterial = \"grey\"\n",
        ),
    )
    .unwrap();
    let run = lumiere(&["render", "obj.toml", "-o", "never.png"], d);
    assert_clear_error(&run, "line 3: byte 0xff is not UTF-8 text", &out);
    // Standard output that cannot be written is named.
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let listed = Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .arg("list")
        .stdout(full)
        .output()
        .unwrap();
    assert_ne!(listed.status.code(), Some(0));
    let stderr = String::from_utf8_lossy(&listed.stderr);
    assert!(
        stderr.starts_with("error: writing standard output: No space left on device"),
        "{stderr}"
    );
}

/// A warning said for every polygon of one misplaced object is said once, with
/// its count.
#[test]
fn a_warning_said_many_times_is_said_once_with_its_count() {
    let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n");
    obj += &"f 1 2 4\n".repeat(40);
    obj += "f 1 2 3\n";
    let text = scene(
        CAMERA,
        "\n[[objects]]\nshape = \"obj\"\nfile = \"flat.obj\"\nmaterial = \"grey\"\n",
    );
    let dir = workspace(&[("flat.obj", &obj), ("s.toml", &text)]);
    let run = lumiere(&["render", "s.toml", "-o", "s.png"], dir.path());
    assert_eq!(run.code, 0, "{}", run.stderr);
    let warnings: Vec<&str> = run
        .stderr
        .lines()
        .filter(|l| l.contains("zero area"))
        .collect();
    assert_eq!(warnings.len(), 1, "{}", run.stderr);
    assert!(
        warnings[0].ends_with("a face of zero area was dropped (40 times)"),
        "{}",
        warnings[0]
    );
}

/// Inputs that rendered black, or were misreported: a light or an object placed
/// beyond what floating point measures, a step of a transform that is not a
/// number, an environment image that is not radiance, a PFM of scale 0, OBJ
/// files with nothing to draw or naming materials their MTL does not define.
#[test]
fn misplaced_and_empty_inputs_are_named() {
    let with = |extra: &str| scene(CAMERA, extra);
    let object = |extra: &str| {
        with(&format!(
            "\n[[objects]]\nshape = \"quad\"\nmaterial = \"grey\"\n{extra}\n"
        ))
    };
    let obj = |file: &str| {
        with(&format!(
            "\n[[objects]]\nshape = \"obj\"\nfile = \"{file}\"\nmaterial = \"grey\"\n"
        ))
    };
    let pfm = |scale: &str, value: f32| {
        let mut bytes = format!("PF\n2 1\n{scale}\n").into_bytes();
        for _ in 0..6 {
            bytes.extend(value.to_le_bytes());
        }
        bytes
    };
    let dir = workspace(&[
        ("empty.obj", ""),
        ("text.obj", "this is a note, not a model\n"),
        ("note.mtl", "a note, not materials\n"),
        (
            "named.obj",
            "mtllib note.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n",
        ),
        (
            "lines.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\nf 3\nf 1 2 3\n",
        ),
    ]);
    let d = dir.path();
    std::fs::write(d.join("nan.pfm"), pfm("-1.0", f32::NAN)).unwrap();
    std::fs::write(d.join("negative.pfm"), pfm("-1.0", -1.0)).unwrap();
    std::fs::write(d.join("zero-scale.pfm"), pfm("0", 1.0)).unwrap();
    let environment = |file: &str| {
        with(&format!(
            "\n[environments.e]\nimage = \"{file}\"\nlayout = \"lat-long\"\n\n[render]\nbackdrop = \"e\"\n"
        ))
    };
    let far_light =
        scene(CAMERA, "").replace("position = [0.0, 2.0, 2.0]", "position = [1e308, 2.0, 2.0]");
    let cases = [
        (far_light, "lies beyond ±1e12"),
        (
            object("transform = [{ scale = 1e308 }]"),
            "transform: the object reaches",
        ),
        (
            object("transform = [{ translate = [nan, 0.0, 0.0] }]"),
            "transform[0].translate must be finite numbers",
        ),
        (
            object("transform = [{ rotate = { axis = [0.0, nan, 1.0], degrees = 30.0 } }]"),
            "transform[0].rotate.axis must be finite numbers",
        ),
        (
            object("transform = [{ scale = [1.0, 0.0, 1.0] }]"),
            "transform[0].scale: a scale must be finite and not zero",
        ),
        (
            environment("nan.pfm"),
            "texels are not radiance (finite, at least 0): the first, at x = 0, y = 0, is (NaN, NaN, NaN)",
        ),
        (
            environment("negative.pfm"),
            "2 of its texels are not radiance",
        ),
        (environment("zero-scale.pfm"), "bad PFM scale: 0"),
        (obj("empty.obj"), "no face to draw"),
        (obj("text.obj"), "no face to draw"),
        (
            obj("named.obj"),
            "usemtl red: no such material in its MTL file (defined: none)",
        ),
    ];
    let out = d.join("never.png");
    for (text, fragment) in &cases {
        std::fs::write(d.join("case.toml"), text).unwrap();
        let run = lumiere(&["render", "case.toml", "-o", "never.png"], d);
        assert_clear_error(&run, fragment, &out);
    }
    // Faces of one or two vertices are left out with a word.
    std::fs::write(d.join("lines.toml"), obj("lines.obj")).unwrap();
    let run = lumiere(&["render", "lines.toml", "-o", "lines.png"], d);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stderr.contains("lines.obj: 2 faces of fewer than 3 vertices (points or lines, not polygons) were left out"),
        "{}",
        run.stderr
    );
    // envmap reads its --from map as radiance too.
    let run = lumiere(
        &[
            "envmap",
            "--from",
            "nan.pfm",
            "--layout",
            "lat-long",
            "--cube",
            "-o",
            "never.png",
        ],
        d,
    );
    assert_clear_error(&run, "nan.pfm: 2 of its texels are not radiance", &out);
}

/// `--threads N` runs the passes on N threads, to the same image; `list --ids`
/// prints the ids alone.
#[test]
fn threads_and_ids_for_scripts() {
    let dir = workspace(&[]);
    let d = dir.path();
    for threads in ["1", "2"] {
        let out = format!("t{threads}.pfm");
        let run = lumiere(
            &[
                "--threads",
                threads,
                "render",
                "cornell-box-point",
                "--width",
                "40",
                "--height",
                "30",
                "-o",
                &out,
            ],
            d,
        );
        assert_eq!(run.code, 0, "{}", run.stderr);
    }
    assert_eq!(
        std::fs::read(d.join("t1.pfm")).unwrap(),
        std::fs::read(d.join("t2.pfm")).unwrap()
    );
    let run = lumiere(
        &[
            "render",
            "cornell-box-point",
            "--threads",
            "0",
            "-o",
            "x.png",
        ],
        d,
    );
    assert_clear_error(
        &run,
        "'--threads <N>': must be at least 1",
        &d.join("x.png"),
    );
    let run = lumiere(&["list", "--ids"], d);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let ids: Vec<&str> = run.stdout.lines().collect();
    assert!(ids.len() > 50, "{}", run.stdout);
    assert!(
        ids.contains(&"cornell-box") && ids.iter().all(|id| !id.contains(' ')),
        "{}",
        run.stdout
    );
}

/// `compare` counts its memory from the two headers before decoding either (an
/// image that claims 30,000 x 30,000 pixels is refused at once); `-o -` writes
/// the PNG to standard output; `--summary` says the render's size, time and rate.
#[test]
fn compare_under_a_budget_and_an_image_to_standard_output() {
    let dir = workspace(&[]);
    let d = dir.path();
    let never = d.join("never.png");
    std::fs::write(d.join("huge.png"), png_header_only(30_000, 30_000)).unwrap();
    let run = lumiere(&["compare", "huge.png", "huge.png"], d);
    assert_clear_error(
        &run,
        "comparing huge.png (900000000 pixels) with huge.png (900000000 pixels) needs about",
        &never,
    );
    assert!(
        run.stderr.contains("more than --max-memory-mb 4096 allows"),
        "{}",
        run.stderr
    );
    assert_eq!(run.code, 2);
    let out = Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .args([
            "render",
            "cornell-box-point",
            "--width",
            "256",
            "--height",
            "192",
            "-o",
            "-",
            "--summary",
        ])
        .current_dir(d)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.stdout.starts_with(b"\x89PNG\r\n\x1a\n"));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("rendered cornell-box-point at 256 x 192 in")
            && stderr.contains("49152 samples"),
        "{stderr}"
    );
    std::fs::write(d.join("a.png"), &out.stdout).unwrap();
    let run = lumiere(&["compare", "a.png", "a.png", "--max-memory-mb", "1"], d);
    assert_clear_error(&run, "more than --max-memory-mb 1 allows", &never);
    let run = lumiere(&["compare", "a.png", "a.png"], d);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("rmse"), "{}", run.stdout);
}

/// A glTF that cannot be read is one error line naming the file: not JSON, cut
/// short, a GLB cut short, a buffer file that is missing, a buffer shorter than it
/// says.
#[test]
fn broken_gltf_files_are_one_error_line() {
    let buffer = |uri: &str, length: usize| {
        format!(
            r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": {length}, "uri": "{uri}"}}]}}"#
        )
    };
    let valid = buffer("data:application/octet-stream;base64,AAAAAA==", 4);
    let cut = &valid[..valid.len() / 2];
    let dir = workspace(&[
        ("garbage.gltf", "this is not json"),
        ("cut.gltf", cut),
        ("cut.glb", "glTF\u{2}\0\0\0"),
        ("no-buffer.gltf", &buffer("missing.bin", 12)),
        ("short.bin", "abc"),
        ("short.gltf", &buffer("short.bin", 12)),
    ]);
    let out = dir.path().join("out.png");
    for (file, fragment) in [
        ("garbage.gltf", "garbage.gltf: not a readable glTF 2.0 file"),
        ("cut.gltf", "cut.gltf: not a readable glTF 2.0 file"),
        ("cut.glb", "cut.glb: not a readable glTF 2.0 file"),
        ("no-buffer.gltf", "no-buffer.gltf: buffer 0: cannot read"),
        (
            "short.gltf",
            "short.gltf: buffer 0 holds 3 bytes, fewer than its byteLength 12",
        ),
    ] {
        let run = lumiere(&["render", file, "-o", "out.png"], dir.path());
        assert_clear_error(&run, fragment, &out);
    }
    let run = lumiere(&["render", "no-buffer.gltf", "-o", "out.png"], dir.path());
    assert!(run.stderr.contains("missing.bin"), "{}", run.stderr);
}
