//! POV-Ray, Mitsuba 3 and NVIDIA's flip-evaluator, installed by the project's
//! script when missing (`.ci/run` runs it too).

use std::path::Path;
use std::process::Command;

/// Installs the peers when one is missing (once a test binary: its tests ask from
/// several threads; the script itself is safe to start from parallel binaries).
pub fn ready() {
    static READY: std::sync::OnceLock<()> = std::sync::OnceLock::new();
    READY.get_or_init(install_when_missing);
}

fn install_when_missing() {
    let ready = Command::new("python3")
        .args(["-c", "import mitsuba, flip_evaluator, numpy"])
        .status()
        .is_ok_and(|s| s.success())
        && Command::new("sh")
            // Mitsuba's llvm variants load Debian's libLLVM-19.
            .args(["-c", "command -v povray && dpkg -s libllvm19"])
            .stdout(std::process::Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
    if !ready {
        let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/install-peers.sh");
        let status = Command::new(&script)
            .status()
            .expect("the install script runs");
        assert!(status.success(), "{} failed", script.display());
    }
}
