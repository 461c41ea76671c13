//! What every command-line test uses: the binary run in a directory, scenes, and
//! the one-line error check.

use std::path::{Path, PathBuf};
use std::process::Command;

pub struct Run {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

pub fn lumiere(args: &[&str], dir: &Path) -> Run {
    let out = Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs");
    Run {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// `lumiere ARGS` in `dir`, which must succeed.
pub fn lumiere_ok(args: &[&str], dir: &Path) -> Run {
    let run = lumiere(args, dir);
    assert_eq!(run.code, 0, "lumiere {args:?}: {}", run.stderr);
    run
}

/// A fresh directory holding `files` (name, contents).
pub fn workspace(files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    dir
}

/// A valid scene with `extra` appended, its camera given by `camera`.
pub fn scene(camera: &str, extra: &str) -> String {
    format!(
        "[camera]\n{camera}\nwidth = 16\nheight = 12\n\n[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\n\
         [[lights]]\ntype = \"point\"\nposition = [0.0, 2.0, 2.0]\nintensity = [5.0, 5.0, 5.0]\n\n\
         [[objects]]\nshape = \"quad\"\nmaterial = \"grey\"\n{extra}"
    )
}

pub const CAMERA: &str = "eye = [0.0, 1.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_y = 40.0";

/// The command failed with exactly one line, `error: …` containing `fragment`, and
/// wrote no output file.
pub fn assert_clear_error(run: &Run, fragment: &str, output: &Path) {
    assert_ne!(run.code, 0, "should fail: {}", run.stderr);
    assert!(!run.stderr.contains("panicked"), "panic: {}", run.stderr);
    let lines: Vec<&str> = run.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "one line expected, got: {}", run.stderr);
    assert!(lines[0].starts_with("error: "), "{}", lines[0]);
    assert!(
        lines[0].contains(fragment),
        "`{fragment}` not in: {}",
        lines[0]
    );
    assert!(!output.exists(), "{} was written", output.display());
}

pub fn render_error(files: &[(&str, &str)], args: &[&str], fragment: &str) {
    let dir = workspace(files);
    let output: PathBuf = dir.path().join("out.png");
    let mut all = vec!["render"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", "out.png"]);
    let run = lumiere(&all, dir.path());
    assert_clear_error(&run, fragment, &output);
}

pub fn spawned(args: &[&str], dir: &Path) -> std::process::Child {
    Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .args(args)
        .current_dir(dir)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the binary runs")
}

/// `args` run in `dir`, stopped (and the test failed) if it takes longer than 30 s: a
/// read that never ends must not hang the suite.
pub fn lumiere_within_30_s(args: &[&str], dir: &Path) -> Run {
    let mut child = spawned(args, dir);
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > std::time::Duration::from_secs(30) {
            let _ = child.kill();
            panic!("`lumiere {}` still running after 30 s", args.join(" "));
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    Run {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// A PNG whose header claims `width × height` (with a valid checksum) and no pixels.
pub fn png_header_only(width: u32, height: u32) -> Vec<u8> {
    fn crc32(bytes: &[u8]) -> u32 {
        let mut crc = !0u32;
        for &b in bytes {
            crc ^= b as u32;
            for _ in 0..8 {
                crc = if crc & 1 == 1 {
                    (crc >> 1) ^ 0xEDB8_8320
                } else {
                    crc >> 1
                };
            }
        }
        !crc
    }
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend(width.to_be_bytes());
    ihdr.extend(height.to_be_bytes());
    ihdr.extend([8, 2, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    png.extend(13u32.to_be_bytes());
    png.extend(&ihdr);
    png.extend(crc32(&ihdr).to_be_bytes());
    png
}
