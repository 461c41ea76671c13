//! `lumiere check --report`: one HTML page to triage a check, worst first: each
//! entry's verdict and figures, its candidate's thumbnail and the reference |
//! difference | candidate strip. Plain HTML and PNG files, no script, nothing
//! fetched from elsewhere, readable on a phone; written whole or not at all.

use super::Verdict;
use anyhow::Result;
use lumiere::StagedDirectory;
use lumiere::{comparison_strip, read_image, write_image};
use std::fmt::Write as _;
use std::path::Path;

/// Magnification of the difference panel.
const GAIN: f32 = 8.0;

pub fn write(dir: &Path, suite: &Path, verdicts: &[Verdict]) -> Result<()> {
    let staged = StagedDirectory::for_replacing(dir)?;
    std::fs::create_dir_all(staged.root().join("images"))?;
    // Worst first: missing and unreadable, then failed by FLIP, then passed by FLIP.
    let mut order: Vec<usize> = (0..verdicts.len()).collect();
    let rank = |v: &Verdict| (v.candidate.is_some() && v.error.is_none(), v.passed());
    order.sort_by(|&a, &b| {
        let (va, vb) = (&verdicts[a], &verdicts[b]);
        rank(va)
            .cmp(&rank(vb))
            .then(vb.flip.unwrap_or(0.0).total_cmp(&va.flip.unwrap_or(0.0)))
            .then(va.id.cmp(&vb.id))
    });
    let passed = verdicts.iter().filter(|v| v.passed()).count();
    let mut html = String::new();
    writeln!(
        html,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <link rel=\"icon\" href=\"data:,\">\n<title>lumiere check: {passed} of {} passed</title>\n<style>{STYLE}</style>\n</head>\n<body>\n\
         <h1>{passed} of {} passed</h1>\n<p>Worst first. Each strip shows the reference, the difference \
         magnified {GAIN}&times; and the candidate.</p>",
        verdicts.len(),
        verdicts.len()
    )?;
    for i in order {
        let v = &verdicts[i];
        let id = escape(&v.id);
        let class = if v.passed() { "pass" } else { "fail" };
        writeln!(
            html,
            "<section id=\"{id}\" class=\"{class}\">\n<h2><span class=\"verdict\">{}</span> {id}</h2>\n<p>{}</p>",
            v.word(),
            escape(&v.title)
        )?;
        // Read again rather than kept from the check: a suite's images would all be
        // held at once.
        let reference = read_image(&suite.join(&v.against))?;
        match (&v.candidate, &v.error) {
            (Some(path), None) => {
                let candidate = read_image(path)?;
                let strip = format!("images/{}-strip.png", v.id);
                write_image(
                    &comparison_strip(&reference, &candidate, 1.0, GAIN),
                    &staged.root().join(&strip),
                    1.0,
                )?;
                let thumb = format!("images/{}-candidate.png", v.id);
                write_image(&candidate, &staged.root().join(&thumb), 1.0)?;
                let mut figures: Vec<String> = v.checks.iter().map(|c| escape(&c.1)).collect();
                if let Some((rmse, max)) = v.strict {
                    figures.push(format!("rmse {rmse:.5}, largest difference {max}/255"));
                }
                writeln!(
                    html,
                    "<img class=\"thumb\" src=\"{thumb}\" alt=\"{id}: the candidate\">\n<ul>{}</ul>\n\
                     <img class=\"strip\" src=\"{strip}\" alt=\"{id}: reference, difference, candidate\">",
                    figures
                        .iter()
                        .map(|f| format!("<li>{f}</li>"))
                        .collect::<String>()
                )?;
            }
            _ if v.skipped.is_some() => {
                let why = v.skipped.as_deref().unwrap_or_default();
                writeln!(
                    html,
                    "<p class=\"why\">no physically based answer: {}</p>",
                    escape(why)
                )?;
            }
            (candidate, error) => {
                let image = format!("images/{}-reference.png", v.id);
                write_image(&reference, &staged.root().join(&image), 1.0)?;
                let why = match (candidate, error) {
                    (_, Some(e)) => escape(e),
                    _ => "no candidate image".into(),
                };
                writeln!(
                    html,
                    "<p class=\"why\">{why}</p>\n<img class=\"thumb\" src=\"{image}\" alt=\"{id}: the reference\">"
                )?;
            }
        }
        writeln!(html, "</section>")?;
    }
    writeln!(html, "</body>\n</html>")?;
    std::fs::write(staged.root().join("index.html"), html)?;
    Ok(staged.replace()?)
}

const STYLE: &str = "body{font-family:sans-serif;margin:1rem auto;max-width:60rem;padding:0 1rem;\
color:#222}section{border-left:.4rem solid #4a4;padding:.2rem 1rem;margin:1rem 0;display:flow-root}\
section.fail{border-color:#c33}.verdict{font-family:monospace}img{max-width:100%;height:auto;\
image-rendering:pixelated}img.thumb{width:8rem;float:right;margin-left:1rem}img.strip{display:block;\
width:100%;clear:both}ul{padding-left:1.2rem}p.why{color:#c33;overflow-wrap:anywhere}";

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
