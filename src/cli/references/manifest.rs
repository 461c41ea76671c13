//! The reference suite's manifest (`manifest.json`), schema `lumiere-reference-suite/2`:
//!
//! ```text
//! {
//!   "schema": "lumiere-reference-suite/2",
//!   "lumiere": "0.1.0",                     the version that made it
//!   "settings": { "width": 256 | null,      null: each entry's test size
//!                 "samples": 16,            seeds of a sampled entry
//!                 "supersample": 4,         samples per pixel side
//!                 "ground_truth_paths": 16 }, a ground truth's paths per pixel side
//!   "ids": [...],                           the entries asked for, catalogue order
//!   "shard": { "index": 1, "count": 4 },    only in one part of a sharded suite
//!   "entries": [ {                          one per id (of this shard)
//!     "id", "title", "authors", "year", "topic", "citation",
//!     "width", "height", "supersample",     its size and samples per pixel side
//!     "sampled": bool,                      two seeds give different images
//!     "renders": N,                         renders the reference is the mean of
//!     "files": { "reference": "ID/reference.exr",      linear, 32-bit float
//!                "variance": "ID/variance.exr",        sampled entries only
//!                "buffers": { NAME: "ID/buffers/NAME.exr" | ".png" },
//!                "scene": "ID/scene.toml",             lumiere's own scene
//!                "ground_truth": "ID/ground-truth.exr",         biased entries:
//!                "ground_truth_variance": "ID/ground-truth-variance.exr" }, path traced
//!     "ground_truth": { "transport": "full" | "direct" | "whitted",
//!                       "renders": N, "paths": P,       seeds, paths per pixel each
//!                       "biased_by": "radiosity" },     what the entry's method misses
//!     "exports": { FORMAT: { "file": "ID/export/scene.EXT",
//!                            "left_out": [ "..." ] } | { "error": "..." } },
//!     "checks": [ { "metric": "flip", "range": "ldr", "max_mean": X },
//!                 { "metric": "statistical", "test": "z", "alpha": A,
//!                   "min_accepted": L, "same_sampler_only": true } ],
//!     "physically_based": { "against": "reference" | "ground-truth",
//!                           "checks": [ ... ] }     what a physically based renderer
//!                       | { "none": "why" }         of the scene is held to
//!   } ]
//! }
//! ```
//!
//! Paths are relative to the manifest's directory. Written with sorted keys and a
//! fixed layout, so the same suite is the same bytes wherever it is made.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

pub const SCHEMA: &str = "lumiere-reference-suite/2";

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    pub schema: String,
    pub lumiere: String,
    pub settings: Settings,
    pub ids: Vec<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shard: Option<Shard>,
    pub entries: Vec<EntryRecord>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Settings {
    pub width: Option<u32>,
    pub samples: u32,
    pub supersample: u32,
    /// Paths per pixel side of each of a ground truth's renders.
    pub ground_truth_paths: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shard {
    pub index: u32,
    pub count: u32,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EntryRecord {
    pub id: String,
    pub title: String,
    pub authors: String,
    pub year: u32,
    pub topic: String,
    pub citation: String,
    pub width: u32,
    pub height: u32,
    /// Samples per pixel side the reference was rendered with.
    pub supersample: u32,
    pub sampled: bool,
    pub renders: u32,
    pub files: Files,
    pub exports: BTreeMap<String, Export>,
    pub checks: Vec<Check>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground_truth: Option<GroundTruth>,
    pub physically_based: PhysicallyBased,
}

/// How a biased entry's ground truth was made.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroundTruth {
    pub transport: Transport,
    /// Renders (seeds) its mean and variance are taken over (1: Whitted's, with
    /// no variance).
    pub renders: u32,
    /// Paths per pixel of each render (none for Whitted's adaptive rays).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub paths: Option<u32>,
    /// What the entry's own method leaves out or approximates.
    pub biased_by: String,
}

/// The light a ground truth carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Transport {
    /// Every path from the lights to the eye.
    Full,
    /// Direct light only: paths of one surface.
    Direct,
    /// Whitted's: direct light, and the ideal mirror's and refraction's rays.
    Whitted,
}

/// What a physically based renderer's image of the scene is held to.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged, deny_unknown_fields)]
pub enum PhysicallyBased {
    Checked {
        against: Against,
        checks: Vec<Check>,
    },
    /// No answer a physically based renderer should reach, and why.
    Unchecked { none: String },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Against {
    /// The entry's reference: an exact method, or a path tracer's own.
    Reference,
    /// `files.ground_truth`, with `files.ground_truth_variance`.
    GroundTruth,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Files {
    pub reference: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub variance: Option<String>,
    pub buffers: BTreeMap<String, String>,
    pub scene: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground_truth: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground_truth_variance: Option<String>,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged, deny_unknown_fields)]
pub enum Export {
    Written { file: String, left_out: Vec<String> },
    Failed { error: String },
}

/// A comparison a candidate must pass.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "metric", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Check {
    /// Mean FLIP at most `max_mean` (any renderer's image of the scene).
    Flip { range: String, max_mean: f64 },
    /// The per-pixel test against the reference's mean and variance. `z`: one
    /// render of a candidate that samples as lumiere does (lumiere itself after a
    /// change), which `lumiere check --same-sampler` runs. `welch`: any
    /// renderer's mean and variance over its own renders, which `lumiere check
    /// --physically-based` runs.
    Statistical {
        test: String,
        alpha: f64,
        min_accepted: f64,
        same_sampler_only: bool,
    },
}

impl Manifest {
    /// The manifest as written: pretty JSON and a final newline.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut text = serde_json::to_string_pretty(self).expect("a manifest serialises");
        text.push('\n');
        text.into_bytes()
    }
}
