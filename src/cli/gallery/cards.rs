//! One picture of the gallery (a card): a catalogue scene with some keys changed,
//! rendered and timed, with the buffers that explain it, its agreement with the
//! reference of its comparison, the progressive frames of a shooting solve and the
//! shadow-polygon plan.

use super::topics::Page;
use anyhow::{Context, Result};
use lumiere::Renderer;
use lumiere::radiosity_solution;
use lumiere::settings::ShadowMethod;
use lumiere::settings::Solver;
use lumiere::{catalogue, load_scene};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

/// At most this many buffers per card.
const MAX_BUFFERS: usize = 8;
/// Differences are shown magnified this many times.
const DIFFERENCE_GAIN: f32 = 4.0;

/// What to render.
#[derive(Clone, Debug)]
pub struct CardSpec {
    /// The catalogue entry whose scene is rendered.
    pub scene: String,
    /// Keys changed, as `--set` takes them.
    pub sets: Vec<String>,
    pub width: u32,
    pub height: u32,
    /// The key of the card this one is measured against.
    pub reference: Option<String>,
    /// The page it is shown on, which chooses the buffers shown.
    pub topic: lumiere::catalogue::Topic,
}

impl CardSpec {
    /// The cache key: the program, the entry's contents and everything changed.
    pub fn key(&self, program: u64) -> Result<String> {
        let entry = toml::to_string(&catalogue::entry(&self.scene)?.scene)?;
        let mut hash = Fnv::new();
        hash.add(&program.to_le_bytes());
        for part in [self.scene.as_str(), entry.as_str()]
            .into_iter()
            .chain(self.sets.iter().map(String::as_str))
        {
            hash.add(part.as_bytes());
            hash.add(&[0]);
        }
        hash.add(&self.width.to_le_bytes());
        hash.add(&self.height.to_le_bytes());
        hash.add(self.reference.as_deref().unwrap_or("").as_bytes());
        hash.add(self.topic.name().as_bytes());
        Ok(format!("{:016x}", hash.0))
    }

    /// The command that renders the same image.
    pub fn command(&self) -> String {
        let mut words = vec!["lumiere".to_string(), "render".into(), self.scene.clone()];
        for set in &self.sets {
            words.push("--set".into());
            words.push(shell_quote(set));
        }
        words.extend([
            "--width".into(),
            self.width.to_string(),
            "--height".into(),
            self.height.to_string(),
            "-o".into(),
            "out.png".into(),
        ]);
        words.join(" ")
    }
}

/// A rendered card, as the page shows it (paths relative to the site's root).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Card {
    pub image: String,
    pub seconds: f64,
    pub buffers: Vec<Shown>,
    pub agreement: Option<Agreement>,
    /// The shooting solve's intermediate states, as an animation.
    pub animation: Option<String>,
    /// Shadow polygons: the plan of the lit and shadowed polygons.
    pub plan: Option<String>,
    /// What a radiosity solve did.
    pub note: String,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Shown {
    pub name: String,
    pub description: String,
    pub file: String,
}

/// The card's image against its reference's, as both display (8-bit sRGB).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Agreement {
    pub rmse: f64,
    pub differing_share: f64,
    pub max_difference: u8,
    pub difference: String,
}

/// Renders `spec` into `dir` (the site's `rel` folder); `reference` is the
/// reference card's image file.
pub fn render(
    spec: &CardSpec,
    page: &Page,
    dir: &Path,
    rel: &str,
    reference: Option<&Path>,
) -> Result<Card> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let mut sets = spec.sets.clone();
    sets.push(format!("camera.width={}", spec.width));
    sets.push(format!("camera.height={}", spec.height));
    let scene = load_scene(&spec.scene, &sets)?;
    let exposure = scene.render.exposure;
    let mut renderer = Renderer::new(scene);
    renderer.check()?;
    let start = Instant::now();
    let mut snapshots = Vec::new();
    let mut note = String::new();
    if let Some(settings) = renderer.scene().radiosity.clone() {
        let scene = renderer.scene().clone();
        let animate = settings.solver == Solver::Shooting;
        let mut next = 1;
        let solution = radiosity_solution::solve(&scene, &settings, &mut |step| {
            // Steps 1, 2, 4, 8…: the early states change most.
            if animate && step.steps() >= next {
                next = step.steps() * 2;
                snapshots.push(step.snapshot(format!("step {}", step.steps())));
            }
        })?;
        note = solution.summary.clone();
        renderer.set_radiosity_solution(Arc::new(solution));
    }
    let image = renderer.render()?;
    let seconds = start.elapsed().as_secs_f64();
    lumiere::write_image(&image, &dir.join("image.png"), exposure)?;
    let file = |name: &str| format!("{rel}/{name}");

    // The buffers this page shows, with what each holds.
    let shown: Vec<_> = renderer
        .available_buffers()?
        .into_iter()
        .filter(|b| page.shows_buffer(&b.name))
        .take(MAX_BUFFERS)
        .collect();
    let names: Vec<String> = shown.iter().map(|b| b.name.clone()).collect();
    let mut buffers = Vec::new();
    if !names.is_empty() {
        for buffer in renderer.render_with_buffers(&names)?.buffers {
            let name = format!("buffer-{}.png", buffer.name);
            lumiere::write_image(
                &lumiere::viewer::buffer_picture(&buffer, exposure).0,
                &dir.join(&name),
                1.0,
            )?;
            let description = shown
                .iter()
                .find(|b| b.name == buffer.name)
                .map(|b| b.description.clone())
                .unwrap_or_default();
            buffers.push(Shown {
                name: buffer.name,
                description,
                file: file(&name),
            });
        }
    }

    let animation = if snapshots.is_empty() {
        None
    } else {
        let path = dir.join("progress.gif");
        let out = std::fs::File::create(&path)
            .with_context(|| format!("cannot write {}", path.display()))?;
        let mut gif = lumiere::GifAnimation::new(std::io::BufWriter::new(out), exposure, 600);
        for snapshot in snapshots {
            let mut frame = Renderer::new(renderer.scene().clone());
            frame.set_radiosity_solution(Arc::new(snapshot));
            gif.add(&frame.render()?)?;
        }
        gif.add(&image)?;
        gif.finish()?;
        Some(file("progress.gif"))
    };

    let plan = if renderer.scene().shadows.method == ShadowMethod::ShadowPolygons {
        super::super::shadow_polygons::plan_of(renderer.scene())
            .ok()
            .map(|bytes| -> Result<String> {
                lumiere::write_atomically(&dir.join("plan.png"), &bytes)?;
                Ok(file("plan.png"))
            })
            .transpose()?
    } else {
        None
    };

    let agreement = match reference {
        None => None,
        Some(reference) => {
            let theirs = lumiere::read_image(reference)?;
            let png = lumiere::encode_image(&image, lumiere::ImageFormat::Png, exposure)?;
            let ours = lumiere::decode_image(&png, lumiere::ImageFormat::Png)?;
            let c = lumiere::compare_images(&theirs, &ours, 1.0)?;
            let difference = lumiere::difference_image(&theirs, &ours, 1.0, DIFFERENCE_GAIN);
            lumiere::write_image(&difference, &dir.join("difference.png"), 1.0)?;
            Some(Agreement {
                rmse: c.rmse,
                differing_share: c.differing_share,
                max_difference: c.max_difference,
                difference: file("difference.png"),
            })
        }
    };
    Ok(Card {
        image: file("image.png"),
        seconds,
        buffers,
        agreement,
        animation,
        plan,
        note,
    })
}

/// FNV-1a, 64 bits: a stable hash (the standard library's may change between
/// releases, and cache keys outlive a build).
pub struct Fnv(pub u64);

impl Fnv {
    pub fn new() -> Fnv {
        Fnv(0xcbf2_9ce4_8422_2325)
    }

    pub fn add(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ b as u64).wrapping_mul(0x0100_0000_01b3);
        }
    }
}

/// `word` quoted for a POSIX shell when it needs it.
fn shell_quote(word: &str) -> String {
    if word
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || "-_.=/,:+".contains(c))
    {
        word.to_string()
    } else {
        format!("'{}'", word.replace('\'', "'\\''"))
    }
}
