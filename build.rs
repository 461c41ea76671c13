// The catalogue under algorithms/ is embedded in the binary: rebuild when it changes.
//
// LUMIERE_SKIP_SYSTEM_TESTS=1 compiles the tests that need Debian packages (the
// viewer's X server, the exporters' POV-Ray and Mitsuba, the gallery's Chromium) as
// ignored, for a machine where they cannot be installed: the test summary counts them.
fn main() {
    println!("cargo::rerun-if-changed=algorithms");
    println!("cargo::rerun-if-env-changed=LUMIERE_SKIP_SYSTEM_TESTS");
    println!("cargo::rustc-check-cfg=cfg(skip_system_tests)");
    if std::env::var("LUMIERE_SKIP_SYSTEM_TESTS").is_ok_and(|v| !v.is_empty() && v != "0") {
        println!("cargo::rustc-cfg=skip_system_tests");
    }
}
