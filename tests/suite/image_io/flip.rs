//! lumiere's FLIP (`lumiere compare --flip`) against NVIDIA's own implementation:
//! LDR-FLIP against the C++ library (`nv-flip`, in process) on 8-bit image pairs,
//! and LDR- and HDR-FLIP against NVIDIA's Python package `flip-evaluator` on
//! linear pairs, each pair's mean to 1e-4.

use crate::support;

use lumiere::glam::Vec3;
use lumiere::image_io::{self, FlipRange, Image};
use std::path::{Path, PathBuf};
use std::process::Command;

fn golden(name: &str) -> Image {
    image_io::load(
        &Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("golden")
            .join(name),
    )
    .unwrap_or_else(|e| panic!("{name}: {}", support::error_line(&e)))
}

/// A deterministic stream of numbers in [0, 1).
fn noise(seed: u64) -> impl FnMut() -> f32 {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// `image` with noise of amplitude `amount` on every channel.
fn noisy(image: &Image, amount: f32, seed: u64) -> Image {
    let mut n = noise(seed);
    Image {
        pixels: image
            .pixels
            .iter()
            .map(|p| (*p + Vec3::new(n() - 0.5, n() - 0.5, n() - 0.5) * amount).max(Vec3::ZERO))
            .collect(),
        ..image.clone()
    }
}

/// `image` moved right by one pixel (the first column repeated).
fn shifted(image: &Image) -> Image {
    let w = image.width as usize;
    Image {
        pixels: (0..image.pixels.len())
            .map(|k| image.pixels[if k % w == 0 { k } else { k - 1 }])
            .collect(),
        ..image.clone()
    }
}

/// The image a PNG of `image` decodes to: 8-bit sRGB, read back as linear.
fn through_8_bits(image: &Image) -> Image {
    image_io::decode(
        &image_io::encode(image, image_io::Format::Png, 1.0).unwrap(),
        image_io::Format::Png,
    )
    .unwrap()
}

/// Pairs of one scene's images that differ as renders do: another method, noise,
/// a one-pixel shift, a brighter light, a colour change.
fn pairs() -> Vec<(&'static str, Image, Image)> {
    let volumes = golden("shadow-volumes.exr");
    let map = golden("shadow-map.exr");
    let texture = golden("perspective-texture.exr");
    let brighter = Image {
        pixels: volumes.pixels.iter().map(|p| *p * 1.2).collect(),
        ..volumes.clone()
    };
    let tinted = Image {
        pixels: texture
            .pixels
            .iter()
            .map(|p| *p * Vec3::new(1.0, 0.8, 1.1))
            .collect(),
        ..texture.clone()
    };
    vec![
        ("volumes-vs-map", volumes.clone(), map),
        ("noise", volumes.clone(), noisy(&volumes, 0.1, 1)),
        ("shift", volumes.clone(), shifted(&volumes)),
        ("brighter", volumes.clone(), brighter),
        ("tinted", texture.clone(), tinted),
        (
            "global-vs-radiosity",
            golden("cornell-box-global.exr"),
            golden("radiosity-shooting.exr"),
        ),
    ]
}

fn mean(map: &[f32]) -> f64 {
    map.iter().map(|&e| e as f64).sum::<f64>() / map.len() as f64
}

#[test]
fn ldr_flip_equals_nvidias_cpp_flip_on_8_bit_pairs() {
    let ppd = image_io::default_pixels_per_degree();
    assert!((ppd - support::flip::pixels_per_degree()).abs() < 1e-4);
    for (name, a, b) in pairs() {
        if (a.width, a.height) != (b.width, b.height) {
            continue;
        }
        let (a, b) = (through_8_bits(&a), through_8_bits(&b));
        let theirs = support::flip::error_map(&a, &b).to_vec();
        let ours = image_io::flip(&a, &b, FlipRange::Ldr, ppd).unwrap();
        let largest = theirs
            .iter()
            .zip(&ours.map)
            .map(|(t, o)| (t - o).abs())
            .fold(0.0f32, f32::max);
        let (t, o) = (mean(&theirs), ours.mean);
        eprintln!("{name}: NVIDIA {t:.6}, lumiere {o:.6}, largest pixel difference {largest:.2e}");
        assert!(t > 1e-3, "{name}: the pair differs");
        assert!(
            (t - o).abs() < 1e-4,
            "{name}: mean FLIP {o} against NVIDIA's {t}"
        );
        assert!(
            largest < 1e-6,
            "{name}: a pixel's FLIP differs by {largest}"
        );
    }
}

/// `image` as a PFM file for Python to read.
fn pfm(image: &Image, dir: &Path, name: &str) -> PathBuf {
    let path = dir.join(name);
    image_io::save(image, &path, 1.0).unwrap();
    path
}

/// NVIDIA's flip-evaluator on two linear PFM files: its mean and, for HDR, its
/// exposures.
fn flip_evaluator(reference: &Path, test: &Path, range: &str) -> (f64, Option<(f64, f64, u32)>) {
    let script = format!(
        r#"
import numpy as np, flip_evaluator as flip
def pfm(path):
    with open(path, 'rb') as f:
        assert f.readline().strip() == b'PF'
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype='<f4' if scale < 0 else '>f4')
    return np.ascontiguousarray(np.flipud(data.reshape(h, w, 3))).astype(np.float32)
r, t = pfm('{r}'), pfm('{t}')
if '{range}' == 'LDR':
    r, t = np.clip(r, 0, 1), np.clip(t, 0, 1)
_, mean, p = flip.evaluate(r, t, '{range}', inputsRGB=False, applyMagma=False)
print(mean, p.get('startExposure', 0), p.get('stopExposure', 0), p.get('numExposures', 0))
"#,
        r = reference.display(),
        t = test.display()
    );
    let out = Command::new("python3")
        .args(["-c", &script])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "flip-evaluator: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let v: Vec<f64> = text
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    let exposures = (range == "HDR").then_some((v[1], v[2], v[3] as u32));
    (v[0], exposures)
}

#[test]
#[cfg_attr(
    skip_system_tests,
    ignore = "needs NVIDIA's flip-evaluator (LUMIERE_SKIP_SYSTEM_TESTS)"
)]
fn ldr_and_hdr_flip_equal_nvidias_flip_evaluator() {
    support::peers::ready();
    let dir = tempfile::tempdir().unwrap();
    let ppd = image_io::default_pixels_per_degree();
    for (name, a, b) in pairs() {
        if (a.width, a.height) != (b.width, b.height) {
            continue;
        }
        let (ra, rb) = (
            pfm(&a, dir.path(), &format!("{name}-a.pfm")),
            pfm(&b, dir.path(), &format!("{name}-b.pfm")),
        );
        let (ldr, _) = flip_evaluator(&ra, &rb, "LDR");
        let ours = image_io::flip(&a, &b, FlipRange::Ldr, ppd).unwrap();
        eprintln!("{name} LDR: NVIDIA {ldr:.6}, lumiere {:.6}", ours.mean);
        assert!(
            (ldr - ours.mean).abs() < 1e-4,
            "{name}: LDR {} against {ldr}",
            ours.mean
        );

        let (hdr, exposures) = flip_evaluator(&ra, &rb, "HDR");
        let hdr_range = FlipRange::Hdr {
            start: None,
            stop: None,
            exposures: None,
        };
        let ours = image_io::flip(&a, &b, hdr_range, ppd).unwrap();
        let (start, stop, count) = ours.exposures.unwrap();
        let (their_start, their_stop, their_count) = exposures.unwrap();
        eprintln!(
            "{name} HDR: NVIDIA {hdr:.6} ({their_start:.4} to {their_stop:.4}, {their_count}), lumiere {:.6} ({start:.4} to {stop:.4}, {count})",
            ours.mean
        );
        assert!(
            (start as f64 - their_start).abs() < 1e-4 && (stop as f64 - their_stop).abs() < 1e-4
        );
        assert_eq!(count, their_count);
        assert!(
            (hdr - ours.mean).abs() < 1e-4,
            "{name}: HDR {} against {hdr}",
            ours.mean
        );
    }
}
