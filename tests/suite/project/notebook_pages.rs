//! The course's notebooks as the site publishes them: tools/build-notebooks.sh (which
//! makes its own Python environment and installs the lumiere wheel when missing)
//! executes the eight notebooks and exports each as one HTML page. Every notebook has
//! its page, named as the notebook; no page loads anything from another host (a
//! static site, readable offline); the plots are embedded; each notebook's widget is
//! frozen into a note and the picture it drew.

use std::path::Path;
use std::process::{Command, Stdio};

/// The tags of `page` that load something: `<script src>`, `<link href>`, `<img src>`,
/// `<iframe src>`, `<source src>`, `<embed src>`, `<object data>`.
fn loading_tags(page: &str) -> Vec<&str> {
    let mut tags = Vec::new();
    let mut rest = page;
    while let Some(start) = rest.find('<') {
        rest = &rest[start + 1..];
        let end = rest.find('>').unwrap_or(rest.len());
        let tag = &rest[..end];
        let name = tag
            .split_whitespace()
            .next()
            .unwrap_or("")
            .to_ascii_lowercase();
        if [
            "script", "link", "img", "iframe", "source", "embed", "object",
        ]
        .contains(&name.as_str())
        {
            tags.push(tag);
        }
        rest = &rest[end..];
    }
    tags
}

/// Whether a tag takes anything from another host (an absolute or protocol-relative
/// address in one of its loading attributes).
fn loads_from_elsewhere(tag: &str) -> bool {
    let lower = tag.to_ascii_lowercase();
    ["src=", "href=", "data="].iter().any(|attribute| {
        lower.match_indices(attribute).any(|(at, _)| {
            let value = lower[at + attribute.len()..].trim_start_matches(['"', '\'']);
            value.starts_with("http:") || value.starts_with("https:") || value.starts_with("//")
        })
    })
}

#[test]
fn the_offline_check_sees_what_nbconvert_would_load() {
    let page = r#"<html><head><script src="https://cdnjs.cloudflare.com/require.js"></script>
<link rel="stylesheet" href="//fonts.example/x.css"><style>a{}</style></head>
<body><img src="data:image/png;base64,AAAA"><a href="https://example.org">a link</a>
<script type="text/javascript">var a = 1 > 0;</script></body></html>"#;
    let elsewhere: Vec<_> = loading_tags(page)
        .into_iter()
        .filter(|t| loads_from_elsewhere(t))
        .collect();
    assert_eq!(elsewhere.len(), 2, "{elsewhere:?}");
    assert!(elsewhere[0].starts_with("script"));
    assert!(elsewhere[1].starts_with("link"));
}

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Python 3 and PyPI (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn every_notebook_is_one_offline_page_with_its_outputs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("notebook-pages");
    let _ = std::fs::remove_dir_all(&out);
    let script = root.join("tools/build-notebooks.sh");
    let run = Command::new(&script)
        .env("LUMIERE_NOTEBOOKS_OUT", &out)
        .stderr(Stdio::inherit())
        .output()
        .expect("the build script runs");
    assert!(run.status.success(), "{} failed", script.display());
    let stdout = String::from_utf8(run.stdout).unwrap();
    assert_eq!(
        Path::new(stdout.trim().lines().last().unwrap()),
        out.canonicalize().unwrap(),
        "the last line names the output folder"
    );

    let mut notebooks: Vec<String> = std::fs::read_dir(root.join("notebooks"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter_map(|n| n.strip_suffix(".ipynb").map(str::to_owned))
        .collect();
    notebooks.sort();
    assert_eq!(notebooks.len(), 8, "{notebooks:?}");
    let mut pages: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    pages.sort();
    let expected: Vec<String> = notebooks.iter().map(|n| format!("{n}.html")).collect();
    assert_eq!(pages, expected, "one page a notebook, named as it");

    for name in &expected {
        let page = std::fs::read_to_string(out.join(name)).unwrap();
        let elsewhere: Vec<_> = loading_tags(&page)
            .into_iter()
            .filter(|t| loads_from_elsewhere(t))
            .collect();
        assert!(
            elsewhere.is_empty(),
            "{name} loads from another host: {elsewhere:?}"
        );
        let plots = page.matches("src=\"data:image/png;base64,").count();
        assert!(plots >= 3, "{name}: {plots} embedded images");
        assert!(
            !page.contains("application/vnd.jupyter.widget"),
            "{name} keeps a live widget a static page cannot run"
        );
        let note = page
            .find("lumiere-widget-note\">")
            .unwrap_or_else(|| panic!("{name} has no note for its widget"));
        assert!(
            page[note..].contains("src=\"data:image/png;base64,"),
            "{name}: the widget's picture is missing"
        );
        assert!(!page.contains("Traceback"), "{name} shows an error");
    }
}
