//! The gallery, tested for real: a small gallery opened in headless Chromium (every
//! page loads without console errors, every image loads and has alt text, every
//! internal link resolves, nothing overflows a phone's width, a screenshot of every
//! page), the cache, and bad input.

mod report;

use crate::support::browser::{Browser, StaticServer, static_viewer};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

/// Ids from three topics whose comparisons are quick at test size.
const IDS: [&str; 3] = ["shadow-volumes", "shading-modes", "planar-mapping"];

struct Run {
    code: i32,
    stderr: String,
}

/// `lumiere gallery ARGS` in `dir`; without the live viewer unless ARGS name one.
fn gallery(args: &[&str], dir: &Path) -> Run {
    let mut args = args.to_vec();
    if !args.contains(&"--viewer") {
        args.push("--no-viewer");
    }
    let out = Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .arg("gallery")
        .args(&args)
        .current_dir(dir)
        .output()
        .expect("the binary runs");
    Run {
        code: out.status.code().unwrap_or(-1),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// The small gallery, built once for the tests that read it.
fn small_gallery() -> &'static Path {
    static SITE: OnceLock<tempfile::TempDir> = OnceLock::new();
    SITE.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let viewer = static_viewer().to_string_lossy().into_owned();
        let mut args = IDS.to_vec();
        args.extend(["--test-size", "-o", "site", "--viewer", &viewer]);
        let run = gallery(&args, dir.path());
        assert_eq!(run.code, 0, "{}", run.stderr);
        dir
    })
    .path()
}

fn pages(site: &Path) -> Vec<PathBuf> {
    let mut pages: Vec<PathBuf> = std::fs::read_dir(site)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "html"))
        .collect();
    pages.sort();
    pages
}

/// The small gallery's pages, or with `LUMIERE_GALLERY=DIR` those of a gallery
/// made by hand (`lumiere gallery -o DIR`, the whole catalogue).
#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs Chromium (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn every_page_loads_whole_in_a_real_browser() {
    let site = match std::env::var_os("LUMIERE_GALLERY") {
        Some(dir) => PathBuf::from(dir),
        None => {
            let site = small_gallery().join("site");
            let names: Vec<String> = pages(&site)
                .iter()
                .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
                .collect();
            assert_eq!(
                names,
                [
                    "hard-shadows.html",
                    "index.html",
                    "texture.html",
                    "visible-surfaces.html"
                ]
            );
            site
        }
    };
    let pages = pages(&site);
    let shots = Path::new(env!("CARGO_TARGET_TMPDIR")).join("gallery-screenshots");
    check_pages(&site, &pages, &shots);
}

/// The browser checks every page of a site must pass: it loads whole (every image,
/// folded ones too, with a size and a description; no error in the console), its
/// links stay in the site and find their anchors, nothing is fetched from elsewhere
/// and no script runs, and on a phone nothing is wider than the screen.
/// Screenshots go to `shots`.
pub fn check_pages(site: &Path, pages: &[PathBuf], shots: &Path) {
    std::fs::create_dir_all(shots).unwrap();
    // Served as a static host serves it (a module worker does not start from
    // file://).
    let server = StaticServer::start(site);
    let url = |page: &Path| server.url(&page.strip_prefix(site).unwrap().to_string_lossy());
    let mut browser = Browser::start();
    for page in pages {
        let name = page.file_stem().unwrap().to_string_lossy().into_owned();
        browser.open(&url(page));
        // A topic's live viewer draws its first frame, pixels on its canvas.
        let live = browser.evaluate(
            "(async () => {
                const frame = document.querySelector('iframe.live');
                if (!frame) return null;
                const deadline = Date.now() + 60000;
                while (!(frame.contentWindow.lumiere && frame.contentWindow.lumiere.frameCount > 0)) {
                    if (Date.now() > deadline) return 'no frame in 60 s';
                    await new Promise(r => setTimeout(r, 50));
                }
                const c = frame.contentDocument.getElementById('canvas');
                const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
                let lit = 0;
                for (let i = 0; i < d.length; i += 4) lit += (d[i] + d[i + 1] + d[i + 2]) > 30;
                return { lit: lit / (d.length / 4), errors: frame.contentWindow.lumiere.errors };
            })()",
        );
        if name != "index" && site.join("viewer").is_dir() {
            assert!(
                live["lit"].as_f64().is_some_and(|l| l > 0.2),
                "{name}: the live viewer: {live}"
            );
            assert_eq!(live["errors"], serde_json::json!([]), "{name}");
        }
        let shot = browser.screenshot();
        let decoded = image_size(&shot);
        assert_eq!(decoded.0, 1280, "{name}: screenshot {decoded:?}");
        assert!(decoded.1 >= 600, "{name}: screenshot {decoded:?}");
        std::fs::write(shots.join(format!("{name}.png")), &shot).unwrap();

        // Every image, folded ones too, loaded with a size and described.
        let images = browser.evaluate(
            "(async () => {
                document.querySelectorAll('details').forEach(d => d.open = true);
                const images = [...document.images];
                await Promise.all(images.map(i => i.complete ? null : new Promise(r => { i.onload = i.onerror = r; })));
                return {
                    count: images.length,
                    broken: images.filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.getAttribute('src')),
                    undescribed: images.filter(i => !i.alt.trim()).map(i => i.getAttribute('src')),
                };
            })()",
        );
        assert!(images["count"].as_u64().unwrap() >= 3, "{name}: {images}");
        assert_eq!(images["broken"], serde_json::json!([]), "{name}");
        assert_eq!(images["undescribed"], serde_json::json!([]), "{name}");
        assert_eq!(browser.errors(), Vec::<String>::new(), "{name}");

        // Every link stays in the site and finds its page (and its anchor).
        let links = browser
            .evaluate("[...document.querySelectorAll('a[href]')].map(a => a.getAttribute('href'))");
        for link in links.as_array().unwrap() {
            let link = link.as_str().unwrap();
            assert!(!link.contains("://"), "{name}: {link} leaves the site");
            let (file, anchor) = link.split_once('#').unwrap_or((link, ""));
            let file = file.split('?').next().unwrap();
            let target = if file.is_empty() {
                page.clone()
            } else {
                site.join(file)
            };
            assert!(target.is_file(), "{name}: {link} is missing");
            if !anchor.is_empty() {
                let text = std::fs::read_to_string(&target).unwrap();
                assert!(
                    text.contains(&format!("id=\"{anchor}\"")),
                    "{name}: {link} has no anchor"
                );
            }
        }
        // Nothing is fetched from elsewhere: no scripts at all, styles and images local.
        let external = browser.evaluate(
            "[...document.querySelectorAll('script, link[href], img')].map(e => e.getAttribute('src') || e.getAttribute('href') || 'inline script')",
        );
        for source in external.as_array().unwrap() {
            let source = source.as_str().unwrap();
            assert!(
                !source.contains("://") && source != "inline script",
                "{name}: {source}"
            );
        }
    }

    // A phone: images scale and text wraps, so nothing is wider than the screen.
    browser.set_viewport(390, 844, true);
    for page in pages {
        let name = page.file_stem().unwrap().to_string_lossy().into_owned();
        browser.open(&url(page));
        let overflow = browser.evaluate(
            "(() => { document.querySelectorAll('details').forEach(d => d.open = true);
                      return document.documentElement.scrollWidth - window.innerWidth; })()",
        );
        assert!(
            overflow.as_i64().unwrap() <= 0,
            "{name}: {overflow} px too wide on a phone"
        );
        std::fs::write(
            shots.join(format!("{name}-phone.png")),
            browser.screenshot(),
        )
        .unwrap();
    }
}

/// Width and height from a PNG's header.
fn image_size(png: &[u8]) -> (u32, u32) {
    assert_eq!(&png[1..4], b"PNG");
    let word = |at: usize| u32::from_be_bytes(png[at..at + 4].try_into().unwrap());
    (word(16), word(20))
}

#[test]
fn the_exact_hard_shadow_methods_show_as_identical_to_ray_casting() {
    let page = std::fs::read_to_string(small_gallery().join("site/hard-shadows.html")).unwrap();
    let cards: Vec<&str> = page.split("<figure class=\"card\">").skip(1).collect();
    assert_eq!(cards.len(), 7);
    for method in [
        "scan-line shadows",
        "shadow polygons",
        "shadow volumes",
        "stencil shadow volumes",
    ] {
        let card = cards
            .iter()
            .find(|c| c.contains(&format!("<h3>{method}</h3>")))
            .unwrap_or_else(|| panic!("no card for {method}"));
        assert!(
            card.contains("identical to ray casting as displayed"),
            "{method}: {card}"
        );
    }
    let unshadowed = cards
        .iter()
        .find(|c| c.contains("<h3>no shadows</h3>"))
        .unwrap();
    assert!(unshadowed.contains("of pixels differ by more than 2/255"));
    assert!(unshadowed.contains("class=\"difference\""));
    // The shadow-polygon card has its plan; the entry its settings and command.
    assert!(page.contains("Plan of the lit and shadowed polygons of shadow polygons"));
    assert!(page.contains("settings (algorithms/shadow-volumes.toml)"));
    assert!(page.contains("lumiere render shadow-volumes --width 128 --height 128 -o out.png"));
}

#[test]
fn a_second_run_renders_nothing_and_writes_the_same_site() {
    let dir = tempfile::tempdir().unwrap();
    let args = ["shading-modes", "--test-size", "-o", "site"];
    let first = gallery(&args, dir.path());
    assert_eq!(first.code, 0, "{}", first.stderr);
    assert!(
        first
            .stderr
            .contains("(4 made, 0 from the earlier gallery)"),
        "{}",
        first.stderr
    );
    let before = snapshot(&dir.path().join("site"));
    let second = gallery(&args, dir.path());
    assert_eq!(second.code, 0, "{}", second.stderr);
    assert!(
        second
            .stderr
            .contains("(0 made, 4 from the earlier gallery)"),
        "{}",
        second.stderr
    );
    let after = snapshot(&dir.path().join("site"));
    // The pages and pictures are the same; only the recorded times could differ,
    // and those are kept from the first run too.
    assert_eq!(before, after);
    // A changed setting renders again: another size is another picture.
    let third = gallery(
        &["shading-modes", "--width", "64", "-o", "site"],
        dir.path(),
    );
    assert_eq!(third.code, 0, "{}", third.stderr);
    assert!(third.stderr.contains("(4 made, 0 from"), "{}", third.stderr);
    assert_eq!(leftovers(dir.path()), Vec::<String>::new());
    // A file of the user's put in the gallery is not deleted by the next run: the
    // run is refused, naming it, and the gallery is left as it was.
    let site = dir.path().join("site");
    std::fs::write(site.join("notes.txt"), "mine").unwrap();
    let before = snapshot(&site);
    let fourth = gallery(&args, dir.path());
    assert_ne!(fourth.code, 0);
    assert_eq!(fourth.stderr.lines().count(), 1, "{}", fourth.stderr);
    assert!(
        fourth
            .stderr
            .contains("holds files the gallery did not write (notes.txt)"),
        "{}",
        fourth.stderr
    );
    assert_eq!(snapshot(&site), before);
    assert_eq!(leftovers(dir.path()), Vec::<String>::new());
}

/// Every file under `dir`, with its bytes.
fn snapshot(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut files = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let path = e.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let bytes = std::fs::read(&path).unwrap();
                files.push((path.strip_prefix(dir).unwrap().to_path_buf(), bytes));
            }
        }
    }
    files.sort();
    files
}

/// Hidden staging or replaced directories left in `dir`.
fn leftovers(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".lumiere"))
        .collect()
}

#[test]
fn bad_input_is_one_line_and_leaves_nothing_behind() {
    let dir = tempfile::tempdir().unwrap();
    let one_line = |run: &Run, fragment: &str| {
        assert_ne!(run.code, 0);
        assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
        assert!(run.stderr.starts_with("error: "), "{}", run.stderr);
        assert!(run.stderr.contains(fragment), "{}", run.stderr);
    };
    let run = gallery(&["shadow-volume", "-o", "site"], dir.path());
    one_line(&run, "shadow-volumes");
    assert!(!dir.path().join("site").exists());

    std::fs::write(dir.path().join("file"), "mine").unwrap();
    let run = gallery(&["shading-modes", "-o", "file"], dir.path());
    one_line(&run, "file is a file");
    assert_eq!(
        std::fs::read_to_string(dir.path().join("file")).unwrap(),
        "mine"
    );

    let run = gallery(&["shading-modes", "-o", "file/site"], dir.path());
    one_line(&run, "file");

    std::fs::create_dir(dir.path().join("mine")).unwrap();
    std::fs::write(dir.path().join("mine/notes.txt"), "keep").unwrap();
    let run = gallery(&["shading-modes", "-o", "mine"], dir.path());
    one_line(&run, "holds no gallery");
    assert_eq!(
        std::fs::read_to_string(dir.path().join("mine/notes.txt")).unwrap(),
        "keep"
    );
    // A stray file named like the manifest does not make a directory a gallery.
    std::fs::write(dir.path().join("mine/gallery.json"), "{\"notes\": 1}").unwrap();
    let run = gallery(&["shading-modes", "-o", "mine"], dir.path());
    one_line(&run, "holds no gallery");
    assert!(dir.path().join("mine/notes.txt").exists());
    assert_eq!(leftovers(dir.path()), Vec::<String>::new());
}

#[test]
fn notebook_pages_are_copied_and_linked_and_a_missing_viewer_is_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let notebooks = dir.path().join("executed");
    std::fs::create_dir(&notebooks).unwrap();
    let page = "<!doctype html><title>hard shadows</title><p>executed</p>";
    std::fs::write(notebooks.join("02-hard-shadows.html"), page).unwrap();
    std::fs::write(notebooks.join("05-texture.html"), page).unwrap();
    let folder = notebooks.to_string_lossy().into_owned();
    let run = gallery(
        &[
            "shadow-volumes",
            "--test-size",
            "-o",
            "site",
            "--notebooks",
            &folder,
        ],
        dir.path(),
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let site = dir.path().join("site");
    assert_eq!(
        std::fs::read_to_string(site.join("notebooks/02-hard-shadows.html")).unwrap(),
        page
    );
    let topic = std::fs::read_to_string(site.join("hard-shadows.html")).unwrap();
    assert!(
        topic.contains(r#"<a href="notebooks/02-hard-shadows.html">"#),
        "the topic links its notebook"
    );
    // A notebook folder without pages, and a viewer folder without a build.
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    let empty = empty.to_string_lossy().into_owned();
    let run = gallery(
        &["shadow-volumes", "-o", "other", "--notebooks", &empty],
        dir.path(),
    );
    assert_eq!(run.code, 1);
    assert!(run.stderr.contains("no notebook page"), "{}", run.stderr);
    let run = gallery(
        &["shadow-volumes", "-o", "other", "--viewer", &empty],
        dir.path(),
    );
    assert_eq!(run.code, 1);
    assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    assert!(run.stderr.contains("tools/build-web.sh"), "{}", run.stderr);
    assert!(!dir.path().join("other").exists());
}
