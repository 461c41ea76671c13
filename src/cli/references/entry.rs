//! One entry of a reference suite: its reference image (the mean and variance over
//! seeds when it is sampled), every buffer its methods make, its scene as lumiere
//! reads it and as other renderers do, and the checks a candidate must pass.
//! Staged in a hidden directory and moved in whole, with `entry.json` (its record
//! and the settings it was made with) inside, so an interrupted suite resumes.

use super::ground_truth::{self, Plan};
use super::manifest::{
    Against, Check, EntryRecord, Export, Files, GroundTruth, PhysicallyBased, Settings, Transport,
};
use anyhow::{Context, Result};
use clap::ValueEnum;
use lumiere::StagedDirectory;
use lumiere::export::{self, Format, Options};
use lumiere::{BufferData, Image, ImageFormat, MomentsSum, Renderer, catalogue, load_scene};
use std::collections::BTreeMap;
use std::path::Path;

/// Mean FLIP (LDR) a renderer's image of an exported scene must stay under.
/// Measured at 128 x 128 on the hard-shadow boxes: Mitsuba's render of the export
/// 0.015 (64 spp), the same box without shadows 0.089.
pub const FLIP_BOUND: f64 = 0.02;
/// Samples per pixel of the exported Mitsuba scenes: their noise stays well under
/// the FLIP bound (FLIP 0.015 at 64 on the hard-shadow boxes at 128 x 128).
const EXPORT_SPP: u32 = 256;
/// The statistical test's per-pixel false-positive rate and accepted share.
pub const ALPHA: f64 = 0.001;
pub const MIN_ACCEPTED: f64 = 0.9975;

/// What `entry.json` holds: the record and the settings it was made with.
#[derive(serde::Serialize, serde::Deserialize)]
pub struct Made {
    pub settings: Settings,
    pub record: EntryRecord,
}

/// The record of `id` if `suite/id` was made with `settings` and is whole.
pub fn already_made(suite: &Path, id: &str, settings: &Settings) -> Option<EntryRecord> {
    let text = std::fs::read(suite.join(id).join("entry.json")).ok()?;
    let made: Made = serde_json::from_slice(&text).ok()?;
    (made.settings == *settings && made.record.id == id).then_some(made.record)
}

/// Makes `suite/id` (replacing what was there) and returns its record.
pub fn make(suite: &Path, id: &str, settings: &Settings) -> Result<EntryRecord> {
    let entry = catalogue::entry(id)?;
    let (width, height) = size(id, &entry.algorithm, settings.width)?;
    // The tracers antialias by themselves (Whitted's adaptive subdivision, the
    // path tracer's paths over the pixel) and refuse supersampling: their entries
    // keep one sample a pixel.
    let traced = load_scene(id, &[])?
        .global
        .is_some_and(|g| g.method.antialiases_itself());
    let supersample = if traced { 1 } else { settings.supersample };
    let sets = vec![
        format!("camera.width={width}"),
        format!("camera.height={height}"),
        format!("render.supersample={supersample}"),
    ];
    let seeded = |seed: u32| {
        let mut s = sets.clone();
        s.push(format!("shadows.seed={seed}"));
        load_scene(id, &s).map(Renderer::new)
    };
    let staged = StagedDirectory::for_replacing(&suite.join(id))?;
    let root = staged.root();
    let write = |name: &str, image: &Image, exposure: f32| -> Result<()> {
        let path = root.join(name);
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).with_context(|| dir.display().to_string())?;
        }
        Ok(lumiere::write_image(image, &path, exposure)?)
    };

    // Seed 0 with every buffer; an entry is sampled when seed 1 differs.
    let first = seeded(0)?;
    let names: Vec<String> = first
        .available_buffers()?
        .into_iter()
        .map(|b| b.name)
        .collect();
    let frame = first.render_with_buffers(&names)?;
    let second = seeded(1)?.render()?;
    let sampled = second.pixels != frame.image.pixels;
    let mut files = Files {
        reference: format!("{id}/reference.exr"),
        variance: None,
        buffers: BTreeMap::new(),
        scene: format!("{id}/scene.toml"),
        ground_truth: None,
        ground_truth_variance: None,
    };
    let renders = if sampled {
        let mut sum = MomentsSum::new(frame.image.width, frame.image.height);
        sum.add(&frame.image)?;
        sum.add(&second)?;
        for seed in 2..settings.samples {
            sum.add(&seeded(seed)?.render()?)?;
        }
        let moments = sum.finish()?;
        write("reference.exr", &moments.mean, 1.0)?;
        write("variance.exr", &moments.variance, 1.0)?;
        files.variance = Some(format!("{id}/variance.exr"));
        settings.samples
    } else {
        write("reference.exr", &frame.image, 1.0)?;
        1
    };
    for buffer in &frame.buffers {
        let format = match buffer.data {
            BufferData::Values { .. } => ImageFormat::Exr,
            BufferData::Ids(_) | BufferData::Counts(_) => ImageFormat::Png,
        };
        let name = format!("buffers/{}.{}", buffer.name, format.extension());
        write(&name, &buffer.to_image(format), 1.0)?;
        files
            .buffers
            .insert(buffer.name.clone(), format!("{id}/{name}"));
    }

    let mut table = entry.scene.clone();
    let camera = table
        .entry("camera")
        .or_insert_with(|| toml::Value::Table(Default::default()));
    if let Some(camera) = camera.as_table_mut() {
        camera.insert("width".into(), (width as i64).into());
        camera.insert("height".into(), (height as i64).into());
    }
    let scene_text = toml::to_string(&table).context("writing the scene as TOML")?;
    std::fs::write(root.join("scene.toml"), scene_text).context("scene.toml")?;

    let scene = load_scene(id, &sets)?;
    let plan = ground_truth::plan(&scene);
    let mut made_truth = None;
    if let Plan::Trace {
        transport,
        biased_by,
    } = &plan
    {
        let paths = settings.ground_truth_paths;
        let traced = ground_truth::scene_table(&table, *transport, paths);
        let context = || format!("{id}: its ground truth");
        files.ground_truth = Some(format!("{id}/ground-truth.exr"));
        made_truth = Some(if *transport == Transport::Whitted {
            let image = ground_truth::render_once(&traced).with_context(context)?;
            write("ground-truth.exr", &image, 1.0)?;
            GroundTruth {
                transport: *transport,
                renders: 1,
                paths: None,
                biased_by: biased_by.clone(),
            }
        } else {
            let moments = ground_truth::render(&traced, settings.samples).with_context(context)?;
            write("ground-truth.exr", &moments.mean, 1.0)?;
            write("ground-truth-variance.exr", &moments.variance, 1.0)?;
            files.ground_truth_variance = Some(format!("{id}/ground-truth-variance.exr"));
            GroundTruth {
                transport: *transport,
                renders: settings.samples,
                paths: Some(paths * paths),
                biased_by: biased_by.clone(),
            }
        });
    }
    std::fs::create_dir_all(root.join("export")).context("export")?;
    let mut exports = BTreeMap::new();
    for format in Format::value_variants() {
        let name = format!("export/scene.{}", format.extension());
        let key = format
            .to_possible_value()
            .map(|v| v.get_name().to_string())
            .unwrap_or_default();
        let options = Options {
            spp: EXPORT_SPP,
            ..Options::new(*format)
        };
        let written = export::export(&scene, &options, &root.join(&name));
        exports.insert(
            key,
            match written {
                Ok(left_out) => Export::Written {
                    file: format!("{id}/{name}"),
                    left_out,
                },
                Err(e) => Export::Failed {
                    error: e.to_string(),
                },
            },
        );
    }

    let mut checks = vec![Check::Flip {
        range: "ldr".into(),
        max_mean: FLIP_BOUND,
    }];
    if sampled {
        checks.push(Check::Statistical {
            test: "z".into(),
            alpha: ALPHA,
            min_accepted: MIN_ACCEPTED,
            same_sampler_only: true,
        });
    }
    // Another renderer's mean over its own renders, against a path tracer's.
    let welch = vec![Check::Statistical {
        test: "welch".into(),
        alpha: ALPHA,
        min_accepted: MIN_ACCEPTED,
        same_sampler_only: false,
    }];
    let physically_based = match plan {
        Plan::Trace {
            transport: Transport::Whitted,
            ..
        } => PhysicallyBased::Checked {
            against: Against::GroundTruth,
            checks: checks[..1].to_vec(),
        },
        Plan::Trace { .. } => PhysicallyBased::Checked {
            against: Against::GroundTruth,
            checks: welch,
        },
        Plan::Itself if sampled => PhysicallyBased::Checked {
            against: Against::Reference,
            checks: welch,
        },
        Plan::Itself | Plan::Exact => PhysicallyBased::Checked {
            against: Against::Reference,
            checks: checks[..1].to_vec(),
        },
        Plan::Unavailable(why) => PhysicallyBased::Unchecked { none: why },
    };
    let record = EntryRecord {
        id: id.to_string(),
        title: entry.algorithm.title.clone(),
        authors: entry.algorithm.authors.clone(),
        year: entry.algorithm.year,
        topic: serde_json::to_value(entry.algorithm.topic)?
            .as_str()
            .unwrap_or_default()
            .to_string(),
        citation: entry.algorithm.citation.clone(),
        width,
        height,
        supersample,
        sampled,
        renders,
        files,
        exports,
        checks,
        ground_truth: made_truth,
        physically_based,
    };
    let made = Made {
        settings: *settings,
        record: record.clone(),
    };
    std::fs::write(root.join("entry.json"), serde_json::to_vec_pretty(&made)?)
        .context("entry.json")?;
    staged.replace()?;
    Ok(record)
}

/// The reference's size: `width` wide at the entry's aspect ratio, or its test size.
fn size(id: &str, algorithm: &catalogue::Algorithm, width: Option<u32>) -> Result<(u32, u32)> {
    let Some(w) = width else {
        return Ok((algorithm.test_width, algorithm.test_height));
    };
    let camera = load_scene(id, &[])?.camera;
    let h = ((w as f64 * camera.height as f64 / camera.width as f64).round() as u32).max(1);
    Ok((w, h))
}
