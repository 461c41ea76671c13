//! Interrupted runs leave nothing half-written: Ctrl-C (SIGINT) while an image is
//! being written, or while a progressive solve writes its frames, ends the process
//! with status 130 and leaves neither a partial output nor a hidden temporary file
//! or staging directory; an earlier run's frames are left as they were.
#![cfg(unix)]

use std::path::Path;
use std::process::{Child, Command};
use std::time::{Duration, Instant};

fn start(args: &[&str], dir: &Path) -> Child {
    Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .args(args)
        .current_dir(dir)
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("the binary runs")
}

/// The names in `dir` starting with a dot.
fn hidden(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect()
}

/// Waits until a hidden file or directory appears in `dir` (the run has started
/// writing), then sends SIGINT; returns the exit status.
fn interrupt_while_writing(mut child: Child, dir: &Path) -> i32 {
    let start = Instant::now();
    while hidden(dir).is_empty() {
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run ended before it was seen writing"
        );
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "nothing written"
        );
        std::thread::sleep(Duration::from_millis(2));
    }
    let kill = Command::new("sh")
        .args(["-c", &format!("kill -INT {}", child.id())])
        .status()
        .unwrap();
    assert!(kill.success());
    child.wait().unwrap().code().unwrap_or(-1)
}

#[test]
fn an_image_interrupted_while_written_leaves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    // About 450 MB of PFM: long enough to be caught writing.
    let child = start(
        &[
            "render",
            "cornell-box-point",
            "--width",
            "6144",
            "--height",
            "6144",
            "-o",
            "big.pfm",
        ],
        dir.path(),
    );
    assert_eq!(interrupt_while_writing(child, dir.path()), 130);
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "{left:?}");
}

#[test]
fn frames_interrupted_leave_the_earlier_run() {
    let dir = tempfile::tempdir().unwrap();
    let frames = |every: &str| {
        start(
            &[
                "render",
                "radiosity-shooting",
                "--element-size",
                "100",
                "--width",
                "48",
                "--height",
                "48",
                "--frames",
                "steps",
                "--frame-every",
                every,
                "-o",
                "out.png",
            ],
            dir.path(),
        )
    };
    assert!(frames("40").wait().unwrap().success());
    let listing = |dir: &Path| {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    };
    let steps = dir.path().join("steps");
    let before = listing(&steps);
    let gif = std::fs::read(steps.join("convergence.gif")).unwrap();
    assert_eq!(interrupt_while_writing(frames("1"), dir.path()), 130);
    assert_eq!(listing(&steps), before);
    assert_eq!(std::fs::read(steps.join("convergence.gif")).unwrap(), gif);
    assert!(hidden(dir.path()).is_empty(), "{:?}", hidden(dir.path()));
}
