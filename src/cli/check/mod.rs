//! `lumiere check`: a directory of candidate images (another renderer's, or
//! lumiere's own after a change) against a reference suite, one verdict per entry
//! and a summary; `--physically-based` holds them to each entry's ground truth
//! instead, `--report` writes an HTML triage page, `--bless` takes the candidates
//! as the new references.

mod report;

use super::references::manifest::{Against, Check, EntryRecord, PhysicallyBased};
use super::references::read_manifest;
use anyhow::{Result, bail};
use lumiere::{
    Candidate, FlipRange, Image, Moments, compare_images, default_pixels_per_degree, flip,
    read_image, statistical_test, write_image,
};
use std::path::{Path, PathBuf};

/// Check candidate images against a reference suite (made by `lumiere references`).
///
/// For each entry of MANIFEST, CANDIDATES/ID.exr (or .pfm, or .png) is held to the
/// checks the manifest names: mean FLIP (LDR) under the entry's bound, and for a
/// sampled entry, with --same-sampler, the per-pixel test against the reference's
/// mean and variance. One line per entry (PASS, FAIL, MISSING), then a summary.
///
/// With --physically-based, each entry's candidate is held to what a physically
/// based renderer of its scene should reach (the manifest's `physically_based`):
/// for a biased entry (radiosity, the two-pass methods, sampled soft shadows) the
/// path tracer's ground truth, by Welch's t-test against the candidate's own mean
/// (ID.exr) and per-render variance (ID.variance.exr, or .pfm) over
/// --candidate-renders renders; for an exact entry the reference, by FLIP. Entries
/// with no such answer (a participating medium, environment maps) are skipped.
///
/// Exit status: 0 when every entry passes, 1 when one fails or is missing, 2 for
/// bad input (an unreadable manifest or candidate directory).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The suite's manifest.json.
    manifest: PathBuf,
    /// The directory of candidate images, one per entry, named by its id.
    candidates: PathBuf,
    /// Write an HTML triage page into this directory: each entry's reference,
    /// candidate and difference strip with its figures, worst first.
    #[arg(long, value_name = "DIR")]
    report: Option<PathBuf>,
    /// Run the statistical checks too: the candidates sample as lumiere does (its
    /// own renders after a change).
    #[arg(long, conflicts_with = "physically_based")]
    same_sampler: bool,
    /// Hold the candidates to what a physically based renderer of each scene
    /// should reach: the ground truth where the entry's method is biased.
    #[arg(long, requires = "candidate_renders")]
    physically_based: bool,
    /// Renders each candidate is the mean of (its ID.variance.exr is one render's
    /// variance), for Welch's test.
    #[arg(long, value_name = "M", value_parser = clap::value_parser!(u32).range(2..))]
    candidate_renders: Option<u32>,
    /// Take the failing candidates as the new references (after a deliberate
    /// change), then still exit 1 so the change is looked at before it is kept.
    #[arg(long, conflicts_with = "physically_based")]
    bless: bool,
}

/// What the candidates are held to.
#[derive(Clone, Copy)]
enum Mode {
    /// The references' checks; the statistical ones with `same_sampler`.
    References { same_sampler: bool },
    /// The physically based checks, the candidates the means of `renders` renders.
    PhysicallyBased { renders: u32 },
}

/// Some entry failed or was missing: exit status 1, where bad input is 2.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct Failed(String);

pub fn failure_status(error: &anyhow::Error) -> u8 {
    if error.is::<Failed>() { 1 } else { 2 }
}

/// One entry's outcome.
pub struct Verdict {
    pub id: String,
    pub title: String,
    /// The candidate file, if found.
    pub candidate: Option<PathBuf>,
    /// Each check said, passed or not.
    pub checks: Vec<(bool, String)>,
    /// The mean FLIP, where measured (the report sorts by it).
    pub flip: Option<f64>,
    /// RMSE and largest difference of the displayed values, where measured.
    pub strict: Option<(f64, u8)>,
    /// Why the entry could not be compared (a size mismatch, an unreadable file).
    pub error: Option<String>,
    /// The image the candidate is held to, relative to the suite.
    pub against: String,
    /// Why the entry has nothing to be held to (no physically based answer).
    pub skipped: Option<String>,
}

impl Verdict {
    pub fn passed(&self) -> bool {
        self.skipped.is_none()
            && self.candidate.is_some()
            && self.error.is_none()
            && self.checks.iter().all(|c| c.0)
    }

    fn word(&self) -> &'static str {
        if self.skipped.is_some() {
            return "SKIP";
        }
        match (&self.candidate, &self.error) {
            (None, _) => "MISSING",
            (_, Some(_)) => "FAIL",
            _ if self.passed() => "PASS",
            _ => "FAIL",
        }
    }
}

pub fn run(args: Args) -> Result<()> {
    let manifest = read_manifest(&args.manifest)?;
    let suite = args
        .manifest
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    if !args.candidates.is_dir() {
        bail!(
            "{}: no such directory of candidates",
            args.candidates.display()
        );
    }
    let mode = match args.candidate_renders {
        Some(renders) if args.physically_based => Mode::PhysicallyBased { renders },
        _ => Mode::References {
            same_sampler: args.same_sampler,
        },
    };
    let mut verdicts = Vec::new();
    for entry in &manifest.entries {
        let verdict = check_entry(&suite, entry, &args.candidates, mode);
        let figures: Vec<&str> = verdict.checks.iter().map(|c| c.1.as_str()).collect();
        let detail = match (&verdict.skipped, &verdict.candidate, &verdict.error) {
            (Some(why), _, _) => format!("no physically based answer: {why}"),
            (_, None, _) => format!(
                "no {}.exr, .pfm or .png in {}",
                entry.id,
                args.candidates.display()
            ),
            (_, _, Some(e)) => e.clone(),
            _ => figures.join("; "),
        };
        outln!("{:<8}{:<32}{detail}", verdict.word(), entry.id)?;
        verdicts.push(verdict);
    }
    let passed = verdicts.iter().filter(|v| v.passed()).count();
    let skipped = verdicts.iter().filter(|v| v.skipped.is_some()).count();
    let missing = verdicts
        .iter()
        .filter(|v| v.skipped.is_none() && v.candidate.is_none())
        .count();
    let failed = verdicts.len() - passed - missing - skipped;
    let tail = if skipped > 0 {
        format!(" ({skipped} skipped: no physically based answer)")
    } else {
        String::new()
    };
    outln!(
        "{passed} passed, {failed} failed, {missing} missing of {}{tail}",
        verdicts.len() - skipped
    )?;
    if let Some(dir) = &args.report {
        report::write(dir, &suite, &verdicts)?;
    }
    if args.bless {
        let blessed = bless(&suite, &manifest.entries, &verdicts)?;
        return Err(Failed(format!(
            "blessed {blessed} reference{}: look at them before keeping the change",
            if blessed == 1 { "" } else { "s" }
        ))
        .into());
    }
    if passed + skipped < verdicts.len() {
        return Err(Failed(format!(
            "{failed} failed and {missing} missing of {} entries",
            verdicts.len() - skipped
        ))
        .into());
    }
    Ok(())
}

/// The candidate for `id` in `dir`: EXR, then PFM, then PNG.
fn find_candidate(dir: &Path, id: &str) -> Option<PathBuf> {
    ["exr", "pfm", "png"]
        .iter()
        .map(|ext| dir.join(format!("{id}.{ext}")))
        .find(|p| p.is_file())
}

/// What an entry's candidate is held to in `mode`: the image, its variance file
/// and renders (if sampled), and the checks; or why there is nothing.
struct Target<'a> {
    image: String,
    variance: Option<(String, u32)>,
    checks: &'a [Check],
}

fn target(entry: &EntryRecord, mode: Mode) -> std::result::Result<Target<'_>, String> {
    let reference = || Target {
        image: entry.files.reference.clone(),
        variance: entry.files.variance.clone().map(|v| (v, entry.renders)),
        checks: &entry.checks,
    };
    let Mode::PhysicallyBased { .. } = mode else {
        return Ok(reference());
    };
    match &entry.physically_based {
        PhysicallyBased::Unchecked { none } => Err(none.clone()),
        PhysicallyBased::Checked {
            against: Against::Reference,
            checks,
        } => Ok(Target {
            checks,
            ..reference()
        }),
        PhysicallyBased::Checked {
            against: Against::GroundTruth,
            checks,
        } => Ok(Target {
            image: entry.files.ground_truth.clone().unwrap_or_default(),
            variance: entry
                .files
                .ground_truth_variance
                .clone()
                .zip(entry.ground_truth.as_ref().map(|g| g.renders)),
            checks,
        }),
    }
}

fn check_entry(suite: &Path, entry: &EntryRecord, candidates: &Path, mode: Mode) -> Verdict {
    let mut verdict = Verdict {
        id: entry.id.clone(),
        title: entry.title.clone(),
        candidate: find_candidate(candidates, &entry.id),
        checks: Vec::new(),
        flip: None,
        strict: None,
        error: None,
        against: entry.files.reference.clone(),
        skipped: None,
    };
    let target = match target(entry, mode) {
        Ok(target) => target,
        Err(why) => {
            verdict.skipped = Some(why);
            return verdict;
        }
    };
    verdict.against = target.image.clone();
    if target.image.is_empty() {
        verdict.error = Some(format!(
            "{}: held to a ground truth the manifest's files do not name",
            entry.id
        ));
        return verdict;
    }
    if let Some(path) = verdict.candidate.clone()
        && let Err(e) = measure(suite, entry, &target, &path, mode, &mut verdict)
    {
        verdict.error = Some(super::one_line(&format!("{e:#}")));
    }
    verdict
}

/// The candidate's variance file beside it (`ID.variance.exr`, or `.pfm`).
fn find_variance(candidate: &Path, id: &str) -> Result<PathBuf> {
    let dir = candidate.parent().unwrap_or(Path::new("."));
    ["exr", "pfm"]
        .iter()
        .map(|ext| dir.join(format!("{id}.variance.{ext}")))
        .find(|p| p.is_file())
        .ok_or_else(|| {
            anyhow::anyhow!(
                "no {id}.variance.exr or .pfm in {}: Welch's test needs the candidate's per-render variance",
                dir.display()
            )
        })
}

fn measure(
    suite: &Path,
    entry: &EntryRecord,
    target: &Target,
    candidate_path: &Path,
    mode: Mode,
    verdict: &mut Verdict,
) -> Result<()> {
    let reference = read_image(&suite.join(&target.image))?;
    let candidate = read_image(candidate_path)?;
    if (candidate.width, candidate.height) != (reference.width, reference.height) {
        bail!(
            "{}: is {}x{}, the reference is {}x{}",
            candidate_path.display(),
            candidate.width,
            candidate.height,
            reference.width,
            reference.height
        );
    }
    let strict = compare_images(&reference, &candidate, 1.0)?;
    verdict.strict = Some((strict.rmse, strict.max_difference));
    for check in target.checks {
        match check {
            Check::Flip { range, max_mean } => {
                let range = match range.as_str() {
                    "hdr" => FlipRange::Hdr {
                        start: None,
                        stop: None,
                        exposures: None,
                    },
                    _ => FlipRange::Ldr,
                };
                let mean = flip(&reference, &candidate, range, default_pixels_per_degree())?.mean;
                verdict.flip = Some(mean);
                let ok = mean <= *max_mean;
                let sign = if ok { "<=" } else { ">" };
                verdict
                    .checks
                    .push((ok, format!("flip {mean:.4} {sign} {max_mean}")));
            }
            Check::Statistical {
                alpha,
                min_accepted,
                same_sampler_only,
                ..
            } if matches!(mode, Mode::References { same_sampler: true })
                || (!same_sampler_only && matches!(mode, Mode::PhysicallyBased { .. })) =>
            {
                let (variance_file, renders) = target.variance.as_ref().ok_or_else(|| {
                    anyhow::anyhow!("{}: a statistical check without a variance", entry.id)
                })?;
                let moments = Moments {
                    mean: reference.clone(),
                    variance: read_image(&suite.join(variance_file))?,
                    renders: *renders,
                };
                let own = match mode {
                    Mode::PhysicallyBased { renders } => {
                        let path = find_variance(candidate_path, &entry.id)?;
                        let variance = read_image(&path)?;
                        if (variance.width, variance.height) != (candidate.width, candidate.height)
                        {
                            bail!(
                                "{}: is {}x{}, the candidate is {}x{}",
                                path.display(),
                                variance.width,
                                variance.height,
                                candidate.width,
                                candidate.height
                            );
                        }
                        Some(Moments {
                            mean: candidate.clone(),
                            variance,
                            renders,
                        })
                    }
                    Mode::References { .. } => None,
                };
                let tested = match &own {
                    Some(m) => Candidate::Moments(m),
                    None => Candidate::Render(&candidate),
                };
                let t = statistical_test(&moments, tested, *alpha, *min_accepted)?;
                let sign = if t.passed { ">=" } else { "<" };
                verdict.checks.push((
                    t.passed,
                    format!(
                        "{}-test {:.3}% accepted {sign} {}%",
                        t.test,
                        100.0 * t.accepted_share,
                        100.0 * min_accepted
                    ),
                ));
            }
            Check::Statistical { .. } => {}
        }
    }
    Ok(())
}

/// Writes each failing candidate of a deterministic entry as its new reference;
/// a sampled entry's mean and variance can only be remade by `lumiere references`.
fn bless(suite: &Path, entries: &[EntryRecord], verdicts: &[Verdict]) -> Result<usize> {
    let mut blessed = 0;
    for (entry, verdict) in entries.iter().zip(verdicts) {
        let Some(candidate) = &verdict.candidate else {
            continue;
        };
        if verdict.passed() {
            continue;
        }
        if let Some(e) = &verdict.error {
            eprintln!("warning: {}: not blessed: {e}", entry.id);
            continue;
        }
        if entry.sampled {
            eprintln!(
                "warning: {}: a sampled entry; remake its mean and variance with `lumiere references`",
                entry.id
            );
            continue;
        }
        let image: Image = read_image(candidate)?;
        write_image(&image, &suite.join(&entry.files.reference), 1.0)?;
        eprintln!("blessed {}: {}", entry.id, candidate.display());
        blessed += 1;
    }
    Ok(blessed)
}
