//! Every `lumiere …` example in the shell blocks of the README and the pages beside it
//! (BENCHMARKS.md, docs/*.md, docs/topics/*.md) runs as written, in order, and
//! succeeds. Each page's examples run in a fresh directory of their own (beside a
//! `golden/` like the checkout's, and the example scene the README renders,
//! `examples/my-scene.toml`), so an example may read only what an earlier example of its page wrote.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The `lumiere` command lines of a page's ```sh blocks, comments removed.
fn examples(page: &str) -> Vec<String> {
    let mut inside = false;
    let mut lines = Vec::new();
    for line in page.lines() {
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

/// The pages whose examples run: README.md first, then BENCHMARKS.md, docs/*.md and
/// docs/topics/*.md, sorted by path.
fn documented_pages(root: &Path) -> Vec<PathBuf> {
    let mut pages = vec![root.join("BENCHMARKS.md")];
    for dir in ["docs", "docs/topics"] {
        for entry in std::fs::read_dir(root.join(dir)).unwrap() {
            let path = entry.unwrap().path();
            if path.extension() == Some(OsStr::new("md")) {
                pages.push(path);
            }
        }
    }
    pages.sort();
    pages.insert(0, root.join("README.md"));
    pages
}

/// How many examples the pages hold (the README held them all before its topics had
/// pages of their own): fewer found means some were lost on the way.
const EXAMPLES: usize = 29;

#[test]
fn every_documented_example_runs_as_written() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let pages: Vec<(PathBuf, Vec<String>)> = documented_pages(root)
        .into_iter()
        .map(|page| {
            let examples = examples(&std::fs::read_to_string(&page).unwrap());
            (page, examples)
        })
        .collect();
    let count: usize = pages.iter().map(|(_, examples)| examples.len()).sum();
    assert!(count >= EXAMPLES, "found {count} examples");
    let binary = Path::new(env!("CARGO_BIN_EXE_lumiere"));
    let path = format!(
        "{}:{}",
        binary.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    for (page, examples) in &pages {
        if examples.is_empty() {
            continue;
        }
        let page = page.strip_prefix(root).unwrap().display();
        let dir = tempfile::tempdir().unwrap();
        std::os::unix::fs::symlink(root.join("golden"), dir.path().join("golden")).unwrap();
        std::fs::create_dir(dir.path().join("examples")).unwrap();
        std::fs::copy(
            root.join("examples/my-scene.toml"),
            dir.path().join("examples/my-scene.toml"),
        )
        .unwrap();
        for example in examples {
            let out = Command::new("sh")
                .arg("-c")
                .arg(example)
                .current_dir(dir.path())
                .env("PATH", &path)
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "`{example}` ({page}) failed ({}): {}",
                out.status,
                String::from_utf8_lossy(&out.stderr)
            );
        }
    }
}

/// The scene the README renders is the complete example of docs/scene-format.md.
#[test]
fn the_shipped_example_scene_is_the_documented_one() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let page = std::fs::read_to_string(root.join("docs/scene-format.md")).unwrap();
    let at = page.find("## A complete example").unwrap();
    let start = at + page[at..].find("```toml\n").unwrap() + "```toml\n".len();
    let end = start + page[start..].find("```").unwrap();
    let shipped = std::fs::read_to_string(root.join("examples/my-scene.toml")).unwrap();
    assert_eq!(shipped, page[start..end]);
}
