//! The Python package as a user meets it, inside `cargo test`: the wheel built by
//! `maturin build --release`, installed into a clean virtual environment with the
//! test tools, and its tests run there: python/tests/test_package.py (the arrays
//! against this command line's PFM output, overrides, errors, pre-passes, the GIL,
//! Ctrl-C) and python/tests/test_notebooks.py (every notebook of notebooks/
//! executed through a real Jupyter kernel, its interactive callback invoked).
//! Then the README's install command, `pip install ./python`, into another clean
//! environment.

use std::path::{Path, PathBuf};
use std::process::Command;

fn run(command: &mut Command, what: &str) {
    let out = command.output().unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(
        out.status.success(),
        "{what}:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A fresh virtual environment at `dir`, and its Python.
fn venv(dir: &Path) -> PathBuf {
    let _ = std::fs::remove_dir_all(dir);
    run(
        Command::new("python3").args(["-m", "venv"]).arg(dir),
        "python3 -m venv",
    );
    let python = dir.join("bin/python");
    run(
        Command::new(&python).args(["-m", "pip", "install", "--quiet", "--upgrade", "pip"]),
        "pip upgrade",
    );
    python
}

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Python 3 and PyPI (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn the_wheel_installs_into_a_clean_environment_and_its_tests_and_notebooks_pass() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let work = Path::new(env!("CARGO_TARGET_TMPDIR")).join("python-package");
    std::fs::create_dir_all(&work).unwrap();

    // The wheel, built as a packager builds it.
    let builder = venv(&work.join("build-env"));
    run(
        Command::new(&builder).args(["-m", "pip", "install", "--quiet", "maturin>=1.5,<2"]),
        "pip install maturin",
    );
    let wheels = work.join("wheels");
    let _ = std::fs::remove_dir_all(&wheels);
    run(
        Command::new(&builder)
            .args(["-m", "maturin", "build", "--release", "--manifest-path"])
            .arg(root.join("python/Cargo.toml"))
            .arg("--out")
            .arg(&wheels),
        "maturin build --release",
    );
    let wheel = std::fs::read_dir(&wheels)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "whl"))
        .expect("maturin wrote a wheel");

    // A clean environment with the wheel and the test tools.
    let python = venv(&work.join("env"));
    run(
        Command::new(&python)
            .args(["-m", "pip", "install", "--quiet"])
            .arg(&wheel)
            .args([
                "pytest",
                "nbclient",
                "nbformat",
                // As tools/build-notebooks.sh pins it (ipython/ipykernel#1554).
                "ipykernel>=6.29,<7",
                "matplotlib",
                "ipywidgets",
            ]),
        "pip install the wheel and the test tools",
    );
    // Run from elsewhere than python/, whose lumiere/ folder would shadow the install.
    run(
        Command::new(&python)
            .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
            .arg(root.join("python/tests"))
            .env("LUMIERE_BIN", env!("CARGO_BIN_EXE_lumiere"))
            .current_dir(&work),
        "pytest python/tests",
    );

    // The README's install command.
    let user = venv(&work.join("user-env"));
    run(
        Command::new(&user)
            .args(["-m", "pip", "install", "--quiet"])
            .arg(root.join("python")),
        "pip install ./python",
    );
    run(
        Command::new(&user)
            .args([
                "-c",
                "import lumiere; f = lumiere.Renderer(lumiere.load('cornell-box-point', camera={'width': 8, 'height': 8})).render(); assert f.image.shape == (8, 8, 3)",
            ])
            .current_dir(&work),
        "import lumiere after pip install ./python",
    );
}
