//! Every `lumiere …` example in the README's shell blocks runs as written, in order,
//! in a fresh directory (beside a `golden/` like the checkout's, and a `my-scene.toml`
//! standing for the user's own scene), and succeeds.

use std::path::Path;
use std::process::Command;

/// The `lumiere` command lines of the README's ```sh blocks, comments removed.
fn examples(readme: &str) -> Vec<String> {
    let mut inside = false;
    let mut lines = Vec::new();
    for line in readme.lines() {
        if line.starts_with("```") {
            inside = line == "```sh";
            continue;
        }
        if inside && line.starts_with("lumiere ") {
            let command = match line.find("  #") {
                Some(comment) => &line[..comment],
                None => line,
            };
            lines.push(command.trim().to_string());
        }
    }
    lines
}

const MY_SCENE: &str = r#"
[camera]
eye = [0.0, 1.0, 3.0]
look_at = [0.0, 0.0, 0.0]
fov_y = 40.0
width = 64
height = 48

[materials.grey]
diffuse = [0.5, 0.5, 0.5]

[[lights]]
type = "point"
position = [0.0, 2.0, 2.0]
intensity = [5.0, 5.0, 5.0]

[[objects]]
shape = "sphere"
material = "grey"
"#;

#[test]
fn every_readme_example_runs_as_written() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let examples = examples(&readme);
    assert!(examples.len() >= 20, "found {} examples", examples.len());
    let dir = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink(root.join("golden"), dir.path().join("golden")).unwrap();
    std::fs::write(dir.path().join("my-scene.toml"), MY_SCENE).unwrap();
    let binary = Path::new(env!("CARGO_BIN_EXE_lumiere"));
    let path = format!(
        "{}:{}",
        binary.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    for example in &examples {
        let out = Command::new("sh")
            .arg("-c")
            .arg(example)
            .current_dir(dir.path())
            .env("PATH", &path)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "`{example}` failed ({}): {}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
    }
}
