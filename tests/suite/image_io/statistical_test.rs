//! The statistical test of `lumiere compare` (a per-pixel Z- or Welch t-test against
//! a reference's mean and variance over renders) tells noise from bias on a
//! sampled method: jittered soft shadows, rendered with different seeds.
//!
//! Measured: over 32 seeds the false-positive rate on the noisy pixels is about
//! 2 alpha (pixel values have heavier tails than the normal, and a rare occlusion
//! the 16 reference renders never saw makes a noiseless pixel differ); asserted
//! under 3 alpha.
//!
//! The reference's moments are computed here by hand (a mean and an unbiased
//! variance per channel), not by the library's `Moments::of`.

use lumiere::image_io::{Candidate, Image, Moments, statistical_test};
use lumiere::{load_scene, render};

const ALPHA: f64 = 0.001;
const LEVEL: f64 = 0.9975;

fn jittered(seed: u64, radiance: f32) -> Image {
    let sets = [
        "camera.width=128".to_string(),
        "camera.height=96".to_string(),
        format!("shadows.seed={seed}"),
        format!("lights.0.radiance=[{radiance},{radiance},{radiance}]"),
    ];
    render(&load_scene("jittered-soft-shadows", &sets).unwrap()).unwrap()
}

/// Mean and unbiased variance per pixel and channel, in double precision.
fn moments(renders: &[Image]) -> Moments {
    let n = renders.len() as f64;
    let first = &renders[0];
    let mut mean = first.clone();
    let mut variance = first.clone();
    for k in 0..first.pixels.len() {
        for c in 0..3 {
            let values: Vec<f64> = renders.iter().map(|r| r.pixels[k][c] as f64).collect();
            let m = values.iter().sum::<f64>() / n;
            let v = values.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0);
            mean.pixels[k][c] = m as f32;
            variance.pixels[k][c] = v as f32;
        }
    }
    Moments {
        mean,
        variance,
        renders: renders.len() as u32,
    }
}

fn scaled(image: &Image, factor: f32) -> Image {
    Image {
        pixels: image.pixels.iter().map(|p| *p * factor).collect(),
        ..image.clone()
    }
}

#[test]
fn the_z_test_accepts_other_seeds_at_its_rate_and_rejects_a_brighter_light() {
    let reference: Vec<Image> = (0..16).map(|s| jittered(s, 9.0)).collect();
    let reference = moments(&reference);
    let mut rejected = 0;
    let mut tested = 0;
    let mut noisy = 0;
    for seed in 100..132 {
        let candidate = jittered(seed, 9.0);
        let t = statistical_test(&reference, Candidate::Render(&candidate), ALPHA, LEVEL).unwrap();
        assert!(t.passed, "seed {seed}: {t:?}");
        rejected += t.rejected;
        tested += t.pixels;
        noisy = t.noisy;
    }
    // Only noisy pixels can be rejected by chance; their false-positive rate is
    // alpha if the test is calibrated (Student's t for the estimated variance).
    let rate = rejected as f64 / (32 * noisy) as f64;
    eprintln!(
        "{rejected} of {tested} pixels rejected over 32 seeds; {noisy} noisy pixels a render; false-positive rate {rate:.5} (alpha {ALPHA})"
    );
    assert!(noisy > 500, "the penumbra is noisy: {noisy} pixels");
    assert!(
        rate < 3.0 * ALPHA,
        "false-positive rate {rate} for alpha {ALPHA}"
    );

    let brighter = jittered(100, 9.0 * 1.02);
    let t = statistical_test(&reference, Candidate::Render(&brighter), ALPHA, LEVEL).unwrap();
    eprintln!("light 2% brighter: {:.4} accepted", t.accepted_share);
    assert!(!t.passed, "{t:?}");

    // Power: the smallest brightening of the picture found, over the whole image
    // (its noiseless pixels find any bias) and over the noisy pixels alone.
    let candidate = jittered(100, 9.0);
    let noisy_only = |image: &Image| -> Image {
        let pixels: Vec<_> = (0..image.pixels.len())
            .filter(|&k| reference.variance.pixels[k].max_element() > 0.0)
            .map(|k| image.pixels[k])
            .collect();
        Image {
            width: pixels.len() as u32,
            height: 1,
            pixels,
        }
    };
    let noisy_reference = Moments {
        mean: noisy_only(&reference.mean),
        variance: noisy_only(&reference.variance),
        renders: reference.renders,
    };
    let biases = [0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2];
    let smallest = |reference: &Moments, image: &Image| {
        biases.into_iter().find(|&b| {
            !statistical_test(
                reference,
                Candidate::Render(&scaled(image, 1.0 + b as f32)),
                ALPHA,
                LEVEL,
            )
            .unwrap()
            .passed
        })
    };
    let whole = smallest(&reference, &candidate);
    let penumbra = smallest(&noisy_reference, &noisy_only(&candidate));
    eprintln!(
        "smallest bias found at 16 seeds: {whole:?} over the image, {penumbra:?} over the noisy pixels alone"
    );
    assert_eq!(whole, Some(0.001));
    assert!(penumbra.is_some_and(|b| b <= 0.1), "{penumbra:?}");
}

#[test]
fn welchs_test_accepts_another_set_of_seeds_and_rejects_a_brighter_one() {
    let reference = moments(&(0..8).map(|s| jittered(s, 9.0)).collect::<Vec<_>>());
    let same = moments(&(50..58).map(|s| jittered(s, 9.0)).collect::<Vec<_>>());
    let t = statistical_test(&reference, Candidate::Moments(&same), ALPHA, LEVEL).unwrap();
    eprintln!("welch, same light: {t:?}");
    assert!(t.passed && t.test == "welch", "{t:?}");
    let brighter = moments(
        &(50..58)
            .map(|s| jittered(s, 9.0 * 1.02))
            .collect::<Vec<_>>(),
    );
    let t = statistical_test(&reference, Candidate::Moments(&brighter), ALPHA, LEVEL).unwrap();
    assert!(!t.passed, "{t:?}");
}
