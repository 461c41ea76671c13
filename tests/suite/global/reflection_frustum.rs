//! The two-pass method's reflection frustum (Wallace, Cohen & Greenberg 1987) against
//! a quadrature written here: a glossy floor seen at 45° reflects an emitting disc
//! centred on its mirror direction. The frustum's weights are the lobe cosⁿγ times
//! each cell's solid angle, normalised over its square window (out to where the lobe
//! is 1% of its peak), so the pixel is ρ_s L ∫_disc cosⁿ⁺³γ dA / ∫_window cosⁿ⁺³γ dA
//! over the plane at unit distance along the mirror direction (dω = cos³γ dA there).
//! The frustum's estimate converges to it as its resolution grows.

use crate::support;

use glam::DVec3;
use lumiere::Renderer;
use std::f64::consts::{FRAC_1_SQRT_2, PI};
use support::{error_line, polygon, scene_from_text};

const EXPONENT: f64 = 100.0;
const MIRROR: f64 = 0.5;
/// The disc's angular radius from the mirror point.
const DISC: f64 = 0.14;
const SIDES: usize = 64;

/// The centre pixel of the glossy floor's image with a frustum of `resolution`
/// cells a side.
fn centre_pixel(resolution: u32) -> f64 {
    let r = DVec3::new(0.0, FRAC_1_SQRT_2, FRAC_1_SQRT_2);
    let (a, b) = (DVec3::X, DVec3::new(0.0, FRAC_1_SQRT_2, -FRAC_1_SQRT_2));
    let disc: Vec<String> = (0..SIDES)
        .map(|k| {
            let phi = 2.0 * PI * k as f64 / SIDES as f64;
            let p = r + (a * phi.cos() + b * phi.sin()) * DISC;
            format!("[{}, {}, {}]", p.x, p.y, p.z)
        })
        .collect();
    let mut text = format!(
        "{}[render]\nsupersample = 1\n\n[global]\nmethod = \"two-pass\"\nfrustum_resolution = {resolution}\n\n[radiosity]\nsolver = \"gathering\"\n\n[materials.floor]\ndiffuse = [0.0, 0.0, 0.0]\nmirror = [{MIRROR}, {MIRROR}, {MIRROR}]\ngloss = {EXPONENT}\n\n[materials.glow]\ndiffuse = [0.0, 0.0, 0.0]\nemission = [1.0, 1.0, 1.0]\n\n",
        support::camera([0.0, 1.0, -1.0], [0.0, 0.0, 0.0], 5.0, 15, 15)
    );
    text += &polygon(
        "floor",
        "floor",
        [
            DVec3::new(-2.0, 0.0, -2.0),
            DVec3::new(2.0, 0.0, -2.0),
            DVec3::new(2.0, 0.0, 2.0),
            DVec3::new(-2.0, 0.0, 2.0),
        ],
        DVec3::Y,
    );
    // The disc faces the mirror point.
    let mut vertices = disc.clone();
    vertices.reverse();
    text += &format!(
        "[[objects]]\nshape = \"polygon\"\nname = \"disc\"\nmaterial = \"glow\"\nvertices = [{}]\n\n",
        vertices.join(", ")
    );
    let image = Renderer::new(scene_from_text(&text, &[]))
        .render()
        .unwrap_or_else(|e| panic!("{}", error_line(&e)));
    image.pixels[7 * 15 + 7].x as f64
}

/// ∫ cosⁿ⁺³γ dA over the points of the window [−t, t]² that `inside` keeps, by the
/// midpoint rule on `n` × `n` cells.
fn quadrature(t: f64, n: usize, inside: impl Fn(f64, f64) -> bool) -> f64 {
    let h = 2.0 * t / n as f64;
    let mut sum = 0.0;
    for j in 0..n {
        let y = -t + (j as f64 + 0.5) * h;
        for i in 0..n {
            let x = -t + (i as f64 + 0.5) * h;
            if inside(x, y) {
                sum += (1.0 + x * x + y * y).powf(-(EXPONENT + 3.0) / 2.0);
            }
        }
    }
    sum * h * h
}

/// The regular 64-gon of circumradius `DISC`, its first corner on the x axis.
fn in_disc(x: f64, y: f64) -> bool {
    let apothem = DISC * (PI / SIDES as f64).cos();
    (0..SIDES).all(|k| {
        let mid = 2.0 * PI * (k as f64 + 0.5) / SIDES as f64;
        x * mid.cos() + y * mid.sin() <= apothem
    })
}

#[test]
fn a_glossy_reflection_converges_to_the_lobe_weighted_quadrature() {
    // The window: cos θ_f = 0.01^(1/n).
    let t = 0.01f64.powf(1.0 / EXPONENT).acos().tan();
    assert!(
        DISC < t,
        "the disc lies inside the window's inscribed circle"
    );
    let window = quadrature(t, 3000, |_, _| true);
    let disc = quadrature(t, 3000, in_disc);
    let expected = MIRROR * disc / window;
    let errors: Vec<f64> = [4, 16, 64]
        .iter()
        .map(|&n| {
            let got = centre_pixel(n);
            let error = (got - expected).abs() / expected;
            println!(
                "{n} x {n}: {got:.6} against {expected:.6} ({:.3}%)",
                100.0 * error
            );
            error
        })
        .collect();
    assert!(errors[2] < 0.005, "64 x 64: {:.4}", errors[2]);
    assert!(errors[2] < errors[0] / 4.0, "{errors:?}");
    // Not the ideal mirror's: the disc fills the mirror direction.
    assert!(expected < 0.8 * MIRROR, "{expected}");
}
