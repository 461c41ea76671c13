//! The install scripts the tests call when a program is missing are safe to start
//! from several threads and several test binaries at once: one lock around every
//! install, the check for what is missing made again inside it. Checked against a
//! stub package manager (dpkg-query, apt-get and sudo on a PATH of the test's own)
//! whose apt-get fails as Debian's does when another holds its lock.

use std::path::Path;
use std::process::Command;

/// A package manager that knows `installed/NAME` as installed, and whose `install`
/// takes a while, refuses to run beside another, and logs each run to `installs`.
fn stub_package_manager(dir: &Path) {
    let bin = dir.join("bin");
    std::fs::create_dir_all(bin.join("../installed")).unwrap();
    let scripts = [
        (
            "dpkg-query",
            r#"#!/bin/sh
# dpkg-query -W -f='${Status}' NAME
for last; do :; done
[ -e "$STUB/installed/$last" ] && printf 'install ok installed'
"#,
        ),
        (
            "apt-get",
            r#"#!/bin/sh
case " $* " in
  *" install "*) ;;
  *) exit 0 ;;
esac
mkdir "$STUB/apt-lock" 2>/dev/null || { echo "E: Could not get lock $STUB/apt-lock" >&2; exit 100; }
sleep 0.3
for p; do case "$p" in -*|install) ;; *) touch "$STUB/installed/$p" ;; esac; done
echo "$*" >> "$STUB/installs"
rmdir "$STUB/apt-lock"
"#,
        ),
        ("sudo", "#!/bin/sh\nexec \"$@\"\n"),
    ];
    for (name, text) in scripts {
        let path = bin.join(name);
        std::fs::write(&path, text).unwrap();
        Command::new("chmod").arg("+x").arg(&path).status().unwrap();
    }
}

#[test]
fn installers_started_together_install_once_and_all_see_it() {
    let dir = tempfile::tempdir().unwrap();
    stub_package_manager(dir.path());
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/apt-install.sh");
    let path = format!(
        "{}:{}",
        dir.path().join("bin").display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let statuses: Vec<(bool, String)> = std::thread::scope(|scope| {
        let runs: Vec<_> = (0..6)
            .map(|_| {
                scope.spawn(|| {
                    let out = Command::new(&script)
                        .args(["stub-tool", "stub-library"])
                        .env("PATH", &path)
                        .env("STUB", dir.path())
                        .env("TMPDIR", dir.path())
                        .env_remove("LUMIERE_INSTALL_LOCKED")
                        .output()
                        .unwrap();
                    (
                        out.status.success(),
                        String::from_utf8_lossy(&out.stderr).into_owned(),
                    )
                })
            })
            .collect();
        runs.into_iter().map(|r| r.join().unwrap()).collect()
    });
    for (ok, stderr) in &statuses {
        assert!(ok, "an installer failed: {stderr}");
    }
    let installs = std::fs::read_to_string(dir.path().join("installs")).unwrap();
    assert_eq!(
        installs.lines().count(),
        1,
        "one install, the others found it done: {installs}"
    );
    for package in ["stub-tool", "stub-library"] {
        assert!(dir.path().join("installed").join(package).exists());
    }
    // Asked again, nothing is installed.
    let again = Command::new(&script)
        .args(["stub-tool"])
        .env("PATH", &path)
        .env("STUB", dir.path())
        .env("TMPDIR", dir.path())
        .status()
        .unwrap();
    assert!(again.success());
    let installs = std::fs::read_to_string(dir.path().join("installs")).unwrap();
    assert_eq!(installs.lines().count(), 1);
}
