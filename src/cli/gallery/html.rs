//! The gallery's pages as HTML: one stylesheet, no scripts, no fonts, nothing
//! fetched from elsewhere; images scale with the window and text wraps.

use super::super::url::percent_encoded;
use super::cards::{Card, CardSpec};
use lumiere::catalogue::{Algorithm, Topic};
use std::fmt::Write as _;

pub const STYLESHEET: &str = r#"
:root { color-scheme: light; --ink: #1d1d1f; --muted: #5a5a60; --line: #d8d8de; --accent: #1f5fa8; }
* { box-sizing: border-box; }
body { margin: 0; font: 18px/1.5 system-ui, sans-serif; color: var(--ink); background: #fafafa; }
header, main, footer { max-width: 1400px; margin: 0 auto; padding: 0 16px; }
nav { display: flex; flex-wrap: wrap; gap: 4px 14px; padding: 12px 0; border-bottom: 1px solid var(--line); }
nav a { color: var(--accent); text-decoration: none; }
nav a[aria-current] { font-weight: bold; color: var(--ink); }
h1 { font-size: 2em; margin: 16px 0 8px; }
h2 { margin-top: 40px; border-bottom: 2px solid var(--line); }
h3 { margin: 8px 0 4px; font-size: 1.1em; }
p, li { max-width: 75ch; overflow-wrap: anywhere; }
img { max-width: 100%; height: auto; image-rendering: pixelated; background: #000; display: block; }
.live { width: 100%; height: min(90vh, 720px); border: 1px solid #ccc; border-radius: 6px; }
.grid { display: grid; gap: 20px; grid-template-columns: repeat(auto-fill, minmax(min(100%, 300px), 1fr)); }
.card, .entry, .topic { background: #fff; border: 1px solid var(--line); border-radius: 6px; padding: 12px; margin: 0; }
.card img.main, .entry img.main, .topic img { width: 100%; }
.topic { color: inherit; text-decoration: none; display: block; }
.topic:hover { border-color: var(--accent); }
.topic h2 { margin: 12px 0 4px; border: 0; }
.badge { font-size: 0.75em; background: var(--accent); color: #fff; border-radius: 4px; padding: 1px 6px; vertical-align: middle; }
.cite, .measure, figcaption.small { color: var(--muted); font-size: 0.9em; }
.difference { max-width: 60%; margin-top: 6px; }
.buffers { display: grid; gap: 10px; grid-template-columns: repeat(auto-fill, minmax(min(100%, 160px), 1fr)); }
.buffers figure { margin: 0; }
.entry { display: grid; gap: 16px; grid-template-columns: minmax(0, 1fr) minmax(0, 1.4fr); margin-bottom: 20px; }
@media (max-width: 760px) { .entry { grid-template-columns: minmax(0, 1fr); } body { font-size: 17px; } }
.pictures { display: grid; gap: 8px; }
.plot { background: #fff; border: 1px solid var(--line); border-radius: 6px; padding: 12px; margin: 0 0 20px; }
.plot img { background: #fff; image-rendering: auto; width: 100%; max-width: 720px; }
pre { background: #f1f1f4; padding: 8px; white-space: pre-wrap; overflow-wrap: anywhere; font-size: 0.8em; }
details { margin-top: 6px; }
summary { cursor: pointer; color: var(--accent); }
footer { color: var(--muted); font-size: 0.85em; padding: 32px 16px; }
"#;

pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A whole page around `body`, with the topics in its navigation.
pub fn page(title: &str, topics: &[Topic], current: Option<Topic>, body: &str) -> String {
    let mut nav = String::from(r#"<a href="index.html">Gallery</a>"#);
    for &t in topics {
        let here = if Some(t) == current {
            r#" aria-current="page""#
        } else {
            ""
        };
        let _ = write!(
            nav,
            r#"<a href="{}.html"{here}>{}</a>"#,
            t.name(),
            t.title()
        );
    }
    format!(
        r#"<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{title}</title>
<link rel="icon" href="data:,">
<link rel="stylesheet" href="style.css">
</head>
<body>
<header><nav>{nav}</nav></header>
<main>
{body}
</main>
<footer>Made by lumiere {version}, a software scan-line renderer that reproduces the classic rendering algorithms as their papers did them. Every image is linear radiance shown as sRGB; times are wall-clock on the machine that built the gallery.</footer>
</body>
</html>
"#,
        title = escape(title),
        version = env!("CARGO_PKG_VERSION"),
    )
}

/// Seconds as the page shows them.
pub fn duration(seconds: f64) -> String {
    if seconds < 1.0 {
        format!("{:.0} ms", seconds * 1000.0)
    } else {
        format!("{seconds:.2} s")
    }
}

/// The intermediate buffers of a card, folded.
fn buffers(out: &mut String, card: &Card, label: &str) {
    if card.buffers.is_empty() {
        return;
    }
    let _ = write!(
        out,
        r#"<details><summary>intermediate buffers ({})</summary><div class="buffers">"#,
        card.buffers.len()
    );
    for b in &card.buffers {
        let _ = write!(
            out,
            r#"<figure><img src="{}" alt="The {} buffer of {}: {}"><figcaption class="small"><b>{}</b>: {}</figcaption></figure>"#,
            escape(&b.file),
            escape(&b.name),
            escape(label),
            escape(&b.description),
            escape(&b.name),
            escape(&b.description)
        );
    }
    out.push_str("</div></details>");
}

/// The pictures a card has besides its image: the plan, the progressive frames.
fn extras(out: &mut String, card: &Card, label: &str) {
    if let Some(plan) = &card.plan {
        let _ = write!(
            out,
            r#"<figure><img src="{}" alt="Plan of the lit and shadowed polygons of {} seen from above"><figcaption class="small">The plan: what the light sees (lit detail polygons) and what it does not.</figcaption></figure>"#,
            escape(plan),
            escape(label)
        );
    }
    if let Some(animation) = &card.animation {
        let _ = write!(
            out,
            r#"<figure><img src="{}" alt="Animation of the progressive radiosity solution of {}, step after step"><figcaption class="small">The intermediate states of shooting, at steps 1, 2, 4, 8… and the end.</figcaption></figure>"#,
            escape(animation),
            escape(label)
        );
    }
}

/// The topic's live viewer: the static site's WebAssembly viewer in a frame,
/// opened on the topic's scene and methods.
pub fn live_viewer(live: &super::topics::Live, width: u32, height: u32, topic: &str) -> String {
    let mut sets = vec![
        format!("camera.width={width}"),
        format!("camera.height={height}"),
    ];
    sets.extend(live.sets.iter().map(|s| s.to_string()));
    let sets: Vec<String> = sets.iter().map(|s| percent_encoded(s)).collect();
    let mut query = format!(
        "embed=1&scene={}&sets={}",
        percent_encoded(live.scene),
        sets.join(",")
    );
    if !live.methods.is_empty() {
        query += &format!("&methods={}", live.methods.join(","));
    }
    format!(
        r#"<h2>Try it</h2><p>The methods live, computed in your browser (the library compiled to WebAssembly): drag to turn the view, switch the method, move the light, split the view between two methods. <a href="viewer/index.html?{query_full}">Open the viewer on its own page</a>.</p><iframe class="live" src="viewer/index.html?{query}" title="the live viewer: {topic}"></iframe>"#,
        query = escape(&query),
        query_full = escape(&query.replacen("embed=1&", "", 1)),
        topic = escape(topic),
    )
}

/// One image of the side-by-side comparison.
pub fn comparison_card(
    spec: &CardSpec,
    card: &Card,
    label: &str,
    method: &Algorithm,
    linked: bool,
    reference_label: &str,
) -> String {
    let mut out = String::from(r#"<figure class="card">"#);
    let _ = write!(
        out,
        r#"<img class="main" src="{}" alt="{}, rendered with {}" width="{}" height="{}">"#,
        escape(&card.image),
        escape(&spec.scene),
        escape(label),
        spec.width,
        spec.height
    );
    out.push_str("<figcaption>");
    let badge = if card.agreement.is_none() {
        r#" <span class="badge">reference</span>"#
    } else {
        ""
    };
    // The method's entry, linked where the gallery shows it.
    let entry = if linked {
        format!(
            r#"<a href="{}.html#{id}">{id}</a>"#,
            method.topic.name(),
            id = escape(&method.id)
        )
    } else {
        format!("<code>{}</code>", escape(&method.id))
    };
    let _ = write!(
        out,
        r#"<h3>{}{badge}</h3><p class="cite">{}: {entry}</p><p class="measure">{}"#,
        escape(label),
        escape(&method.authors),
        duration(card.seconds)
    );
    match &card.agreement {
        None => out.push_str("</p>"),
        Some(a) if a.max_difference == 0 => {
            let _ = write!(
                out,
                r#"; identical to {} as displayed</p>"#,
                escape(reference_label)
            );
        }
        Some(a) => {
            let _ = write!(
                out,
                r#"; against {}: RMSE {:.4}, {:.2}% of pixels differ by more than 2/255 (largest {}/255)</p><img class="difference" src="{}" alt="Difference between {} and {}, magnified 4 times">"#,
                escape(reference_label),
                a.rmse,
                100.0 * a.differing_share,
                a.max_difference,
                escape(&a.difference),
                escape(label),
                escape(reference_label)
            );
        }
    }
    if !card.note.is_empty() {
        let _ = write!(out, r#"<p class="measure">{}</p>"#, escape(&card.note));
    }
    extras(&mut out, card, label);
    buffers(&mut out, card, label);
    let _ = writeln!(
        out,
        "<details><summary>command</summary><pre>{}</pre></details></figcaption></figure>",
        escape(&spec.command())
    );
    out
}

/// A catalogue entry: its picture, paper, summary, settings and buffers.
pub fn entry(spec: &CardSpec, card: &Card, a: &Algorithm, source: &str) -> String {
    let mut out = format!(
        r#"<article class="entry" id="{}"><div class="pictures">"#,
        escape(&a.id)
    );
    let _ = write!(
        out,
        r#"<img class="main" src="{}" alt="{}: {}" width="{}" height="{}">"#,
        escape(&card.image),
        escape(&a.id),
        escape(&a.title),
        spec.width,
        spec.height
    );
    extras(&mut out, card, &a.id);
    let _ = write!(
        out,
        r#"</div><div><h3>{}</h3><p class="cite"><code>{}</code> · {}</p><p>{}</p><p class="cite">{}</p><p class="measure">{} × {}, {}{}</p>"#,
        escape(&a.title),
        escape(&a.id),
        escape(&a.authors),
        escape(&a.summary),
        escape(&a.citation),
        spec.width,
        spec.height,
        duration(card.seconds),
        if card.note.is_empty() {
            String::new()
        } else {
            format!("; {}", escape(&card.note))
        }
    );
    buffers(&mut out, card, &a.id);
    let _ = writeln!(
        out,
        "<details><summary>settings (algorithms/{}.toml)</summary><pre>{}</pre></details><details><summary>command</summary><pre>{}</pre></details></div></article>",
        escape(&a.id),
        escape(source),
        escape(&spec.command())
    );
    out
}
