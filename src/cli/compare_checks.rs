//! `lumiere compare`'s figures: printed as text or JSON, and held against the
//! thresholds, each exceeded one said with its measured value.

use anyhow::Result;
use lumiere::{Comparison, Flip, FuzzyMatch, StatisticalTest, ToleranceCheck};

/// Every figure a comparison measured.
pub struct Figures {
    pub comparison: Comparison,
    pub fuzzy: Option<FuzzyMatch>,
    /// The edge threshold and the pixels it left out.
    pub edges: Option<(f64, u64)>,
    /// FLIP and the pixels per degree it was measured at.
    pub flip: Option<(Flip, f32)>,
    pub tolerance: Option<ToleranceCheck>,
    pub statistical: Option<StatisticalTest>,
}

/// The thresholds of the strict, fuzzy and FLIP checks (the tolerance image and
/// the statistical test carry their own).
pub struct Thresholds {
    pub max_rmse: Option<f64>,
    pub max_difference: Option<u8>,
    pub max_differing: Option<f64>,
    pub max_differing_pixels: Option<u64>,
    pub pixel_delta: Option<u32>,
    pub max_flip: Option<f64>,
}

/// The percentiles of FLIP's map that are printed.
const FLIP_PERCENTILES: [f64; 4] = [50.0, 95.0, 99.0, 100.0];

/// The figures, as text or JSON, on standard output.
pub fn print(f: &Figures, json: bool) -> Result<()> {
    if json {
        return outln!("{}", serde_json::to_string_pretty(&to_json(f)?)?);
    }
    let c = &f.comparison;
    outln!("rmse            {:.6}", c.rmse)?;
    outln!("psnr            {:.2} dB", c.psnr)?;
    outln!("max difference  {}/255", c.max_difference)?;
    outln!(
        "differing       {:.4}% of pixels (> 2/255)",
        100.0 * c.differing_share
    )?;
    if let Some((threshold, masked)) = f.edges {
        outln!("edges ignored   {masked} pixels (Sobel gradient > {threshold})")?;
    }
    if let Some(z) = &f.fuzzy {
        outln!(
            "fuzzy           {} pixels differ, largest delta {}/255 (border {})",
            z.differing_pixels,
            z.largest_pixel_delta,
            z.border
        )?;
    }
    if let Some((flip, ppd)) = &f.flip {
        let range = match flip.exposures {
            Some((start, stop, n)) => format!("HDR, {n} exposures from {start:.3} to {stop:.3}"),
            None => "LDR".into(),
        };
        let percentiles: Vec<String> = FLIP_PERCENTILES
            .iter()
            .map(|&p| format!("p{p} {:.4}", flip.percentile(p)))
            .collect();
        outln!(
            "flip            {:.6} mean; {} ({range}, {ppd:.2} ppd)",
            flip.mean,
            percentiles.join(", ")
        )?;
    }
    if let Some(t) = &f.tolerance {
        outln!(
            "tolerance       {} pixels beyond, largest excess {:.6}",
            t.pixels_beyond,
            t.largest_excess
        )?;
    }
    if let Some(s) = &f.statistical {
        outln!(
            "{:<16}{:.4}% of pixels accepted ({} rejected, {} noisy; alpha {}, needs {:.4}%)",
            if s.test == "z" {
                "z-test"
            } else {
                "welch t-test"
            },
            100.0 * s.accepted_share,
            s.rejected,
            s.noisy,
            s.alpha,
            100.0 * s.level
        )?;
    }
    Ok(())
}

fn to_json(f: &Figures) -> Result<serde_json::Value> {
    let mut value = serde_json::to_value(f.comparison)?;
    if let Some((threshold, masked)) = f.edges {
        value["edges"] = serde_json::json!({ "threshold": threshold, "masked_pixels": masked });
    }
    if let Some(z) = &f.fuzzy {
        value["fuzzy"] = serde_json::to_value(z)?;
    }
    if let Some((flip, ppd)) = &f.flip {
        let mut v = serde_json::json!({
            "mean": flip.mean,
            "pixels_per_degree": ppd,
            "range": if flip.exposures.is_some() { "hdr" } else { "ldr" },
        });
        for p in FLIP_PERCENTILES {
            v[format!("p{p}")] = serde_json::json!(flip.percentile(p));
        }
        if let Some((start, stop, n)) = flip.exposures {
            v["exposures"] = serde_json::json!({ "start": start, "stop": stop, "count": n });
        }
        value["flip"] = v;
    }
    if let Some(t) = &f.tolerance {
        value["tolerance"] = serde_json::to_value(t)?;
    }
    if let Some(s) = &f.statistical {
        value["statistical"] = serde_json::to_value(s)?;
    }
    Ok(value)
}

/// Each check failed, with the measured value.
pub fn exceeded(t: &Thresholds, f: &Figures) -> Vec<String> {
    let c = &f.comparison;
    let mut beyond = Vec::new();
    if let Some(x) = t.max_rmse
        && c.rmse > x
    {
        beyond.push(format!("rmse {:.6} > --max-rmse {x}", c.rmse));
    }
    if let Some(n) = t.max_difference
        && c.max_difference > n
    {
        beyond.push(format!(
            "max difference {}/255 > --max-difference {n}",
            c.max_difference
        ));
    }
    if let Some(x) = t.max_differing
        && c.differing_share > x
    {
        beyond.push(format!(
            "differing {:.6} of pixels > --max-differing {x}",
            c.differing_share
        ));
    }
    if let (Some(n), Some(z)) = (t.max_differing_pixels, &f.fuzzy)
        && z.differing_pixels > n
    {
        beyond.push(format!(
            "{} pixels differ > --max-differing-pixels {n}",
            z.differing_pixels
        ));
    }
    if let (Some(d), Some(z)) = (t.pixel_delta, &f.fuzzy)
        && z.largest_pixel_delta > d
    {
        beyond.push(format!(
            "a pixel's delta {}/255 > --pixel-delta {d}",
            z.largest_pixel_delta
        ));
    }
    if let (Some(x), Some((flip, _))) = (t.max_flip, &f.flip)
        && flip.mean > x
    {
        beyond.push(format!("flip {:.6} > --max-flip {x}", flip.mean));
    }
    if let Some(tol) = &f.tolerance
        && tol.pixels_beyond > 0
    {
        beyond.push(format!(
            "{} pixels beyond the tolerance image (by up to {:.6})",
            tol.pixels_beyond, tol.largest_excess
        ));
    }
    if let Some(s) = &f.statistical
        && !s.passed
    {
        beyond.push(format!(
            "the {} test accepts {:.4}% of pixels < --min-accepted {}%",
            s.test,
            100.0 * s.accepted_share,
            100.0 * s.level
        ));
    }
    beyond
}
