//! The README's contact sheet is what `lumiere contact-sheet` makes of today's
//! catalogue: made again here, it must equal docs/contact-sheet.png byte for byte.

use std::path::Path;
use std::process::Command;

#[test]
fn the_readmes_contact_sheet_is_current() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = tempfile::tempdir().unwrap();
    let made = dir.path().join("sheet.png");
    let out = Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .args(["contact-sheet", "-o"])
        .arg(&made)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let entries = lumiere::catalogue::ids().len();
    assert!(
        String::from_utf8_lossy(&out.stderr).contains(&format!("{entries} entries")),
        "every entry is on the sheet"
    );
    let committed = std::fs::read(root.join("docs/contact-sheet.png")).unwrap();
    assert!(
        std::fs::read(&made).unwrap() == committed,
        "docs/contact-sheet.png is out of date: run `lumiere contact-sheet -o docs/contact-sheet.png` and look at it"
    );
}
