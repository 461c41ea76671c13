//! `lumiere gallery`: the course as a static site. Per topic, one scene through
//! every method side by side (each timed and measured against the topic's
//! reference, with the buffers that explain it), the plots, and every catalogue
//! entry of the topic with its paper, summary and settings.
//!
//! The site is written into a staging directory beside the output and put in its
//! place only when complete. Pictures are kept by a key of the program and the
//! entry's contents (`cards::CardSpec::key`): a re-run renders only what changed.

mod cards;
mod html;
mod plots;
mod svg;
mod topics;

use anyhow::{Context, Result, bail};
use cards::{Card, CardSpec, Fnv};
use indicatif::{ProgressBar, ProgressStyle};
use lumiere::StagedDirectory;
use lumiere::catalogue::{self, Entry, Topic};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::Instant;
use topics::{Page, Plot};

/// Write the course gallery: a static site (index.html and a page per topic) with
/// every method side by side, agreement figures, plots and intermediate buffers.
///
/// Open DIR/index.html in a browser; the site needs nothing but its own files. A
/// re-run into the same directory renders only what changed.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Catalogue ids to show, with their topics' comparisons and plots (default:
    /// the whole catalogue).
    ids: Vec<String>,
    /// The site's directory (made, or replaced if it holds an earlier gallery).
    #[arg(short, long)]
    output: PathBuf,
    /// Width of every picture; the height follows the entry's aspect ratio.
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(16..=2048))]
    width: u32,
    /// Render every picture at its entry's golden-image test size instead.
    #[arg(long, conflicts_with = "width")]
    test_size: bool,
    /// The static viewer (page and WebAssembly) that `tools/build-web.sh` builds,
    /// put on every topic page.
    #[arg(long, value_name = "DIR", default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/target/web/viewer"))]
    viewer: PathBuf,
    /// Leave the live viewer out (pictures and plots only).
    #[arg(long, conflicts_with = "viewer")]
    no_viewer: bool,
    /// The course's notebooks executed and exported as HTML pages
    /// (`tools/build-notebooks.sh` makes them), linked from their topics; left out
    /// with a note when the default folder has none.
    #[arg(long, value_name = "DIR")]
    notebooks: Option<PathBuf>,
}

/// Where `tools/build-notebooks.sh` puts the executed notebooks.
const NOTEBOOKS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/target/web/notebooks");

/// The static viewer's folder, refused in one line when it was not built.
fn live_viewer(folder: &Path) -> Result<PathBuf> {
    if !folder.join("index.html").is_file() || !folder.join("pkg").is_dir() {
        bail!(
            "--viewer {}: no static viewer there (tools/build-web.sh builds it; --no-viewer leaves it out)",
            folder.display()
        );
    }
    Ok(folder.to_path_buf())
}

/// The executed notebooks' pages by topic (the topic's name in the file's name):
/// from `given`, or from the default folder when it has any.
fn notebook_pages(given: Option<&Path>) -> Result<Vec<(Topic, PathBuf)>> {
    let folder = given.unwrap_or(Path::new(NOTEBOOKS));
    let listing = match std::fs::read_dir(folder) {
        Ok(listing) => listing,
        Err(e) if given.is_some() => {
            return Err(e).with_context(|| format!("--notebooks {}", folder.display()));
        }
        Err(_) => {
            eprintln!(
                "gallery: no executed notebooks in {} (tools/build-notebooks.sh makes them): the topics link none",
                folder.display()
            );
            return Ok(Vec::new());
        }
    };
    let mut pages = Vec::new();
    for file in listing {
        let path = file?.path();
        let name = file_name(&path);
        if !name.ends_with(".html") {
            continue;
        }
        if let Some(topic) = Topic::ALL.into_iter().find(|t| name.contains(t.name())) {
            pages.push((topic, path));
        }
    }
    pages.sort();
    if given.is_some() && pages.is_empty() {
        bail!(
            "--notebooks {}: no notebook page (NN-topic.html) there",
            folder.display()
        );
    }
    Ok(pages)
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Copies the folder `from` into `to`, whole.
fn copy_folder(from: &Path, to: &Path) -> Result<()> {
    std::fs::create_dir_all(to).with_context(|| format!("cannot write {}", to.display()))?;
    for entry in
        std::fs::read_dir(from).with_context(|| format!("cannot read {}", from.display()))?
    {
        let entry = entry?;
        let target = to.join(entry.file_name());
        if entry.file_type()?.is_dir() {
            copy_folder(&entry.path(), &target)?;
        } else {
            std::fs::copy(entry.path(), &target)
                .with_context(|| format!("cannot copy {}", entry.path().display()))?;
        }
    }
    Ok(())
}

/// What the site's root records, to recognise an earlier gallery.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Manifest {
    program: String,
    version: String,
    ids: Vec<String>,
    /// Every file the gallery wrote (paths inside it, `/`-separated): any other
    /// file found there is a user's, and the gallery is not replaced over it.
    #[serde(default)]
    files: Vec<String>,
}

const MANIFEST: &str = "gallery.json";

pub fn run(args: Args) -> Result<()> {
    let started = Instant::now();
    let entries = chosen_entries(&args.ids)?;
    let topics: Vec<Topic> = Topic::ALL
        .into_iter()
        .filter(|t| entries.iter().any(|e| e.algorithm.topic == *t))
        .collect();
    let earlier = earlier_gallery(&args.output)?;
    let program = program_fingerprint()?;
    let staged = StagedDirectory::for_replacing(&args.output)
        .with_context(|| format!("cannot write the gallery {}", args.output.display()))?;
    let mut site = Site {
        root: staged.root().to_path_buf(),
        earlier,
        program,
        cards: HashMap::new(),
        rendered: 0,
        reused: 0,
    };
    let size = |id: &str| -> Result<(u32, u32)> {
        let a = catalogue::entry(id)?.algorithm;
        Ok(if args.test_size {
            (a.test_width, a.test_height)
        } else {
            let height = (args.width as f64 * a.test_height as f64 / a.test_width as f64).round();
            (args.width, (height as u32).max(1))
        })
    };

    let viewer = (!args.no_viewer)
        .then(|| live_viewer(&args.viewer))
        .transpose()?;
    let notebooks = notebook_pages(args.notebooks.as_deref())?;
    if let Some(folder) = &viewer {
        copy_folder(folder, &site.root.join("viewer"))?;
    }
    for (_, page) in &notebooks {
        let name = format!("notebooks/{}", file_name(page));
        std::fs::create_dir_all(site.root.join("notebooks"))?;
        std::fs::copy(page, site.root.join(&name))
            .with_context(|| format!("cannot copy {}", page.display()))?;
    }

    let pages: Vec<&Page> = topics.iter().map(|&t| topics::page(t)).collect();
    let jobs: u64 = pages
        .iter()
        .map(|p| (p.variants.len() + p.plots.len()) as u64)
        .sum::<u64>()
        + entries.len() as u64;
    let bar = ProgressBar::new(jobs).with_style(
        ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:40} {pos}/{len} {msg}")
            .expect("a valid template"),
    );
    bar.enable_steady_tick(std::time::Duration::from_millis(100));

    for page in &pages {
        let mut body = format!(
            "<h1>{}</h1><p>{}</p>",
            html::escape(page.topic.title()),
            html::escape(page.intro)
        );
        if viewer.is_some() {
            let (width, height) = size(page.live.scene)?;
            body += &html::live_viewer(&page.live, width, height, page.topic.title());
        }
        if let Some((_, notebook)) = notebooks.iter().find(|(t, _)| *t == page.topic) {
            body += &format!(
                r#"<p class="notebook">The course's notebook for this topic, executed: <a href="notebooks/{0}">{0}</a>.</p>"#,
                html::escape(&file_name(notebook))
            );
        }
        // One scene, every method: the first variant is the reference.
        body.push_str("<h2>One scene, every method</h2><div class=\"grid\">");
        let mut reference: Option<(String, &str)> = None;
        for variant in page.variants {
            bar.set_message(format!("{}: {}", page.topic.name(), variant.label));
            let (width, height) = size(variant.scene)?;
            let spec = CardSpec {
                scene: variant.scene.into(),
                sets: variant.sets.iter().map(|s| s.to_string()).collect(),
                width,
                height,
                reference: reference.as_ref().map(|r| r.0.clone()),
                topic: page.topic,
            };
            let (key, card) = site.card(&spec, page)?;
            let method = catalogue::entry(variant.cites)?.algorithm;
            body += &html::comparison_card(
                &spec,
                &card,
                variant.label,
                &method,
                entries.iter().any(|e| e.algorithm.id == method.id),
                reference.as_ref().map_or("", |r| r.1),
            );
            if reference.is_none() {
                reference = Some((key, variant.label));
            }
            bar.inc(1);
        }
        body.push_str("</div>");
        if !page.plots.is_empty() {
            body.push_str("<h2>Plots</h2>");
        }
        for &plot in page.plots {
            bar.set_message(format!("{}: plot {}", page.topic.name(), plot.name()));
            let (file, drawn) = site.plot(plot)?;
            body += &format!(
                r#"<figure class="plot"><img src="{}" alt="{}"><figcaption>{}</figcaption></figure>"#,
                html::escape(&file),
                html::escape(&drawn.alt),
                html::escape(&drawn.caption)
            );
            bar.inc(1);
        }
        body.push_str("<h2>The catalogue entries</h2>");
        for e in entries.iter().filter(|e| e.algorithm.topic == page.topic) {
            let a = &e.algorithm;
            bar.set_message(format!("{}: {}", page.topic.name(), a.id));
            let (width, height) = size(&a.id)?;
            let spec = CardSpec {
                scene: a.id.clone(),
                sets: Vec::new(),
                width,
                height,
                reference: None,
                topic: page.topic,
            };
            let (_, card) = site.card(&spec, page)?;
            body += &html::entry(&spec, &card, a, catalogue::source(&a.id)?);
            bar.inc(1);
        }
        site.write(
            &format!("{}.html", page.topic.name()),
            &html::page(page.topic.title(), &topics, Some(page.topic), &body),
        )?;
    }
    bar.finish_and_clear();
    site.write(
        "index.html",
        &index(&site, &topics, &pages, &entries, size)?,
    )?;
    site.write("style.css", html::STYLESHEET)?;
    let mut files = files_under(&site.root)?;
    files.push(MANIFEST.into());
    let manifest = Manifest {
        program: format!("{:016x}", site.program),
        version: env!("CARGO_PKG_VERSION").into(),
        ids: entries.iter().map(|e| e.algorithm.id.clone()).collect(),
        files,
    };
    site.write(MANIFEST, &serde_json::to_string_pretty(&manifest)?)?;
    let (rendered, reused) = (site.rendered, site.reused);
    staged
        .replace()
        .with_context(|| format!("cannot write the gallery {}", args.output.display()))?;
    eprintln!(
        "gallery: {} pages, {} pictures ({rendered} made, {reused} from the earlier gallery) in {:.1} s: {}",
        topics.len() + 1,
        rendered + reused,
        started.elapsed().as_secs_f64(),
        args.output.join("index.html").display()
    );
    Ok(())
}

/// The entries named (each once, in catalogue order), or the whole catalogue.
fn chosen_entries(ids: &[String]) -> Result<Vec<Entry>> {
    if ids.is_empty() {
        return Ok(catalogue::entries()?);
    }
    let mut entries = Vec::new();
    for id in catalogue::ids() {
        if ids.contains(&id) {
            entries.push(catalogue::entry(&id)?);
        }
    }
    for id in ids {
        // Unknown ids fail here, with the nearest known one.
        catalogue::entry(id)?;
    }
    Ok(entries)
}

/// The earlier gallery at `output`, whose pictures may be kept. A file, or a
/// directory holding something other than a gallery, is refused: the site
/// replaces the directory whole.
fn earlier_gallery(output: &Path) -> Result<Option<PathBuf>> {
    let Ok(meta) = std::fs::metadata(output) else {
        return Ok(None);
    };
    if !meta.is_dir() {
        bail!(
            "{} is a file: the gallery is written as a directory",
            output.display()
        );
    }
    // A gallery is recognised by its manifest, read whole: a stray file of that
    // name does not make a user's directory one to replace.
    let manifest = std::fs::read_to_string(output.join(MANIFEST)).ok();
    if let Some(m) = manifest
        .and_then(|text| serde_json::from_str::<Manifest>(&text).ok())
        .filter(|m| !m.program.is_empty() && !m.version.is_empty())
    {
        let foreign: Vec<String> = files_under(output)?
            .into_iter()
            .filter(|f| !m.files.is_empty() && !m.files.contains(f))
            .collect();
        if !foreign.is_empty() {
            let mut named: Vec<&str> = foreign.iter().take(5).map(String::as_str).collect();
            let more = format!("and {} more", foreign.len().saturating_sub(5));
            if foreign.len() > 5 {
                named.push(&more);
            }
            bail!(
                "{} holds files the gallery did not write ({}): the gallery replaces its directory whole, so move them or name another directory",
                output.display(),
                named.join(", ")
            );
        }
        return Ok(Some(output.to_path_buf()));
    }
    let empty = std::fs::read_dir(output)
        .with_context(|| format!("cannot read {}", output.display()))?
        .next()
        .is_none();
    if !empty {
        bail!(
            "{} is not empty and holds no gallery ({MANIFEST}): the gallery replaces its directory whole, so name a new or empty one",
            output.display()
        );
    }
    Ok(None)
}

/// The files under `root`, as `/`-separated paths inside it, sorted.
fn files_under(root: &Path) -> Result<Vec<String>> {
    let mut files = Vec::new();
    let mut folders = vec![PathBuf::new()];
    while let Some(folder) = folders.pop() {
        let dir = root.join(&folder);
        for entry in
            std::fs::read_dir(&dir).with_context(|| format!("cannot read {}", dir.display()))?
        {
            let entry = entry.with_context(|| format!("cannot read {}", dir.display()))?;
            let inside = folder.join(entry.file_name());
            if entry.file_type().is_ok_and(|t| t.is_dir()) {
                folders.push(inside);
            } else {
                let parts: Vec<String> = inside
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect();
                files.push(parts.join("/"));
            }
        }
    }
    files.sort();
    Ok(files)
}

/// A hash of the running program: pictures made by another build are made again.
fn program_fingerprint() -> Result<u64> {
    let exe = std::env::current_exe().context("cannot find the running program")?;
    let bytes = std::fs::read(&exe).with_context(|| format!("cannot read {}", exe.display()))?;
    let mut hash = Fnv::new();
    hash.add(env!("CARGO_PKG_VERSION").as_bytes());
    hash.add(&bytes);
    Ok(hash.0)
}

/// The site being written, and the earlier one whose pictures it may keep.
struct Site {
    root: PathBuf,
    earlier: Option<PathBuf>,
    program: u64,
    cards: HashMap<String, Card>,
    rendered: usize,
    reused: usize,
}

impl Site {
    fn write(&self, name: &str, text: &str) -> Result<()> {
        let path = self.root.join(name);
        std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))
    }

    /// The card of `spec`: made already in this run, kept from the earlier
    /// gallery, or rendered.
    fn card(&mut self, spec: &CardSpec, page: &Page) -> Result<(String, Card)> {
        let key = spec.key(self.program)?;
        if let Some(card) = self.cards.get(&key) {
            return Ok((key, card.clone()));
        }
        let rel = format!("img/{key}");
        let dir = self.root.join(&rel);
        let card = match self.keep(&rel) {
            Some(card) => {
                self.reused += 1;
                card
            }
            None => {
                let reference = spec
                    .reference
                    .as_ref()
                    .map(|r| self.root.join(format!("img/{r}/image.png")));
                let card = cards::render(spec, page, &dir, &rel, reference.as_deref())
                    .with_context(|| format!("{}: {}", spec.scene, spec.sets.join(" ")))?;
                std::fs::write(dir.join("card.json"), serde_json::to_string_pretty(&card)?)
                    .with_context(|| format!("cannot write in {}", dir.display()))?;
                self.rendered += 1;
                card
            }
        };
        self.cards.insert(key.clone(), card.clone());
        Ok((key, card))
    }

    /// The earlier gallery's folder `rel` copied into this one, with its card.
    fn keep(&self, rel: &str) -> Option<Card> {
        let from = self.earlier.as_ref()?.join(rel);
        let text = std::fs::read_to_string(from.join("card.json")).ok()?;
        let card: Card = serde_json::from_str(&text).ok()?;
        let to = self.root.join(rel);
        std::fs::create_dir_all(&to).ok()?;
        for file in std::fs::read_dir(&from).ok()? {
            let file = file.ok()?;
            std::fs::copy(file.path(), to.join(file.file_name())).ok()?;
        }
        Some(card)
    }

    /// The plot drawn (or kept from the earlier gallery), and its file.
    fn plot(&mut self, plot: Plot) -> Result<(String, plots::Drawn)> {
        let mut hash = Fnv::new();
        hash.add(&self.program.to_le_bytes());
        hash.add(plot.name().as_bytes());
        let rel = format!("plots/{}-{:016x}", plot.name(), hash.0);
        let file = format!("{rel}.svg");
        let kept = self.earlier.as_ref().and_then(|earlier| {
            let svg = std::fs::read_to_string(earlier.join(&file)).ok()?;
            let text = std::fs::read_to_string(earlier.join(format!("{rel}.json"))).ok()?;
            let (caption, alt): (String, String) = serde_json::from_str(&text).ok()?;
            Some(plots::Drawn { svg, caption, alt })
        });
        let drawn = match kept {
            Some(drawn) => {
                self.reused += 1;
                drawn
            }
            None => {
                self.rendered += 1;
                plot.draw()
                    .with_context(|| format!("the plot {}", plot.name()))?
            }
        };
        std::fs::create_dir_all(self.root.join("plots"))?;
        self.write(&file, &drawn.svg)?;
        self.write(
            &format!("{rel}.json"),
            &serde_json::to_string(&(&drawn.caption, &drawn.alt))?,
        )?;
        Ok((file, drawn))
    }
}

/// The index: what the gallery is, and a tile per topic.
fn index(
    site: &Site,
    topics: &[Topic],
    pages: &[&Page],
    entries: &[Entry],
    size: impl Fn(&str) -> Result<(u32, u32)>,
) -> Result<String> {
    let mut body = String::from(
        "<h1>lumiere: the course gallery</h1><p>Each page takes one part of the course and shows \
         one scene through every method of it, side by side: the time each took, how far each is \
         from the topic's reference method (with the difference magnified), and the intermediate \
         buffers that explain it; then the plots, and every catalogue entry of the topic with its \
         paper, what it shows and its settings. Every picture can be made again with the command \
         under it.</p><div class=\"grid\">",
    );
    for (topic, page) in topics.iter().zip(pages) {
        let first = &page.variants[0];
        let (width, height) = size(first.scene)?;
        let spec = CardSpec {
            scene: first.scene.into(),
            sets: first.sets.iter().map(|s| s.to_string()).collect(),
            width,
            height,
            reference: None,
            topic: *topic,
        };
        let image = &site.cards[&spec.key(site.program)?].image;
        let count = entries
            .iter()
            .filter(|e| e.algorithm.topic == *topic)
            .count();
        body += &format!(
            r#"<a class="topic" href="{}.html"><img src="{}" alt="{}: {}" width="{width}" height="{height}"><h2>{}</h2><p>{} methods side by side; {} catalogue {}.</p></a>"#,
            topic.name(),
            html::escape(image),
            html::escape(topic.title()),
            html::escape(first.label),
            html::escape(topic.title()),
            page.variants.len(),
            count,
            if count == 1 { "entry" } else { "entries" }
        );
    }
    body.push_str("</div>");
    Ok(html::page(
        "lumiere: the course gallery",
        topics,
        None,
        &body,
    ))
}
