//! Environment mapping proved against exact references: continuity of the filtered
//! lookups across the cube's seams and the latitude-longitude map's wrap, the layouts'
//! round trips, conversions between layouts of a map whose texels encode their own
//! direction, the layouts' documented orientations, Snell's law and Schlick's
//! approximation, a mirror ball, an index-matched refractor and a glass quad rendered
//! against the analytic reflected and refracted directions, and one clear error line
//! for each kind of bad environment input.

use crate::support;

use glam::{DVec2, DVec3, Vec3};
use lumiere::raster::View;
use lumiere::shading::optics::{reflect, refract, schlick};
use lumiere::texture::environment::cube_map::{self, FACE_NAMES};
use lumiere::texture::environment::sky::ProceduralEnvironment;
use lumiere::texture::environment::{
    EnvironmentMap, Layout, coordinates, lat_long, sphere_map, texel_direction,
};
use lumiere::texture::{Filter, Texels};
use lumiere::{Scene, load_scene};
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};
use support::error_line;

// ---------------------------------------------------------------------------------
// Helpers.

fn angle(a: DVec3, b: DVec3) -> f64 {
    let (a, b) = (a.normalize(), b.normalize());
    a.cross(b).length().atan2(a.dot(b))
}

/// The direction a `directions` colour (d + 1)/2 encodes.
fn decode(c: Vec3) -> DVec3 {
    (c.as_dvec3() * 2.0 - DVec3::ONE).normalize()
}

fn directions_map(layout: Layout, size: u32, filter: Filter) -> EnvironmentMap {
    EnvironmentMap::generate(layout, size, filter, |d| {
        ProceduralEnvironment::Directions.radiance(d)
    })
}

/// A direction uniformly distributed over the sphere.
fn unit() -> impl Strategy<Value = DVec3> {
    (-1.0..=1.0f64, 0.0..TAU).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    })
}

/// A vector in the cube [−1, 1]³ (a perturbation's direction and size).
fn offset() -> impl Strategy<Value = DVec3> {
    (-1.0..=1.0f64, -1.0..=1.0f64, -1.0..=1.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn random_texels(width: u32, height: u32) -> impl Strategy<Value = Texels> {
    prop::collection::vec(
        (0.0..=1.0f32, 0.0..=1.0f32, 0.0..=1.0f32),
        (width * height) as usize,
    )
    .prop_map(move |t| Texels {
        width,
        height,
        texels: t.into_iter().map(|(r, g, b)| Vec3::new(r, g, b)).collect(),
    })
}

/// Per channel, the largest difference between two of the texels.
fn spread<'a>(images: impl IntoIterator<Item = &'a Texels>) -> DVec3 {
    let (lo, hi) = images
        .into_iter()
        .flat_map(|t| t.texels.iter())
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &t| {
            (lo.min(t), hi.max(t))
        });
    (hi - lo).as_dvec3()
}

/// A scene file `text` in a fresh directory holding `files` (name, bytes), loaded.
fn load_in_dir(text: &str, files: &[(&str, Vec<u8>)]) -> lumiere::Result<Scene> {
    let dir = tempfile::tempdir().unwrap();
    for (name, bytes) in files {
        std::fs::write(dir.path().join(name), bytes).unwrap();
    }
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, text).unwrap();
    load_scene(path.to_str().unwrap(), &[])
}

fn scene(text: &str) -> Scene {
    load_in_dir(text, &[]).unwrap_or_else(|e| panic!("{}", error_line(&e)))
}

/// The eye-ray direction through pixel (x, y)'s centre (one sample per pixel).
fn eye_ray(view: &View, x: u32, y: u32) -> DVec3 {
    view.ray(x as f64 + 0.5, y as f64 + 0.5).normalize()
}

// ---------------------------------------------------------------------------------
// 1, 2. Bilinear lookups are continuous across the cube's seams and corners and
// across the latitude-longitude map's wrap.

/// Side of the random cube faces.
const N: u32 = 8;

/// A face and a point (u, v) on its boundary: on one of its four edges, or a corner.
fn face_boundary() -> impl Strategy<Value = (usize, DVec2)> {
    (0usize..6, 0usize..8, 0.0..=1.0f64).prop_map(|(face, kind, t)| {
        let uv = match kind {
            0 => DVec2::new(0.0, t),
            1 => DVec2::new(1.0, t),
            2 => DVec2::new(t, 0.0),
            3 => DVec2::new(t, 1.0),
            k => DVec2::new(((k - 4) & 1) as f64, ((k - 4) >> 1) as f64),
        };
        (face, uv)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Bilinear lookups on a cube map of random texels change by no more than a
    /// Lipschitz bound times the angle between two directions on either side of a
    /// seam or around a corner.
    ///
    /// The bound: inside a (bordered) face the lookup is bilinear in (u, v) between
    /// texel centres 1/n apart, so per channel |∂f/∂u|, |∂f/∂v| ≤ nΔ, Δ the channel's
    /// largest difference between two texels (the borders copy texels, and a corner's
    /// border is a mean of three, so no bordered texel leaves [min, max]). A face is the
    /// gnomonic projection onto the plane at distance 1, which stretches an angle dθ to
    /// at most r²·dθ on the plane (r² = 1 + s² + t² ≤ 3 at the corners), and
    /// (u, v) = (plane + 1)/2, so |d(u, v)/dθ| ≤ 3/2 and |df/dθ| ≤ nΔ(|u'| + |v'|) ≤
    /// √2 · 3/2 · nΔ. If the lookup is continuous over the whole sphere that holds along
    /// the great-circle arc between the two directions, through whichever faces it
    /// crosses: |f(d₁) − f(d₂)| ≤ (3/√2) nΔ θ. A seam where the two faces' values differ
    /// (no border, a border copied from the wrong neighbour texel, a corner that is not
    /// the three faces' mean) breaks it by a fixed amount however small θ is. Slack 1e-5
    /// for f32 arithmetic.
    #[test]
    fn cube_map_lookups_are_continuous_across_seams_and_corners(
        faces in prop::collection::vec(random_texels(N, N), 6),
        (face, uv) in face_boundary(),
        a in offset(), b in offset(), e in 2.5..9.0f64,
    ) {
        let delta = spread(&faces);
        let lipschitz = delta * (3.0 / 2f64.sqrt()) * N as f64;
        let map = EnvironmentMap::cube(faces, Filter::Bilinear);
        let eps = 10f64.powf(-e);
        let seam = cube_map::direction(face, uv);
        // A pair perturbed at random around the seam point, and a pair straddling the
        // boundary along the face's plane (the second on a neighbouring face).
        let inward = DVec2::splat(0.5) - uv;
        let pairs = [
            ((seam + eps * a).normalize(), (seam + eps * b).normalize()),
            (
                cube_map::direction(face, uv + eps * inward),
                cube_map::direction(face, uv - eps * inward),
            ),
        ];
        for (d1, d2) in pairs {
            let theta = angle(d1, d2);
            let (f1, f2) = (
                map.lookup(d1, [DVec3::ZERO; 2]).as_dvec3(),
                map.lookup(d2, [DVec3::ZERO; 2]).as_dvec3(),
            );
            let bound = lipschitz * theta + DVec3::splat(1e-5);
            prop_assert!(
                ((f1 - f2).abs() - bound).max_element() <= 0.0,
                "{} at {uv}: {d1} ({:?}) → {f1}, {d2} ({:?}) → {f2}, θ = {theta:e}, \
                 bound {bound}",
                FACE_NAMES[face],
                cube_map::face_uv(d1),
                cube_map::face_uv(d2)
            );
        }
    }

    /// The same for a latitude-longitude map across its seam u = 0/1 (the half plane
    /// x = 0, z > 0: map frame X = −z, atan2 = ±π). Bilinear in (u, v) with texel
    /// centres 1/w and 1/h apart: |∂f/∂u| ≤ wΔ, |∂f/∂v| ≤ hΔ. u = (1 + φ/π)/2 with
    /// |dφ/dθ| ≤ 1/r (r = √(1 − R_z²), the distance from the polar axis) and
    /// v = (R_z + 1)/2 with |dR_z/dθ| ≤ 1, so |df/dθ| ≤ Δ(w/(2πr) + h/2), r taken at
    /// its smallest along the arc (≥ the endpoints' smaller r minus θ). Clamping u
    /// instead of repeating it, or an offset between the seam's two sides, breaks it.
    #[test]
    fn lat_long_lookups_are_continuous_across_the_wrap(
        texels in random_texels(2 * N, N),
        v in 0.05..0.95f64, a in offset(), b in offset(), e in 2.5..9.0f64,
        du in prop::sample::select(vec![0.0, 1.0]),
    ) {
        let delta = spread([&texels]);
        let (w, h) = (texels.width as f64, texels.height as f64);
        let map = EnvironmentMap::flat(Layout::LatLong, texels, Filter::Bilinear);
        let eps = 10f64.powf(-e);
        let seam = lat_long::direction(DVec2::new(du, v));
        prop_assert!(seam.x.abs() < 1e-12 && seam.z > 0.0, "{seam}");
        let pairs = [
            ((seam + eps * a).normalize(), (seam + eps * b).normalize()),
            (
                lat_long::direction(DVec2::new(eps * a.x.abs(), v + eps * a.y)),
                lat_long::direction(DVec2::new(1.0 - eps * b.x.abs(), v + eps * b.y)),
            ),
        ];
        for (d1, d2) in pairs {
            let theta = angle(d1, d2);
            let r = |d: DVec3| (1.0 - d.y * d.y).max(0.0).sqrt();
            let r_min = r(d1).min(r(d2)) - theta;
            let lipschitz = delta * (w / (2.0 * PI * r_min) + h / 2.0);
            let (f1, f2) = (
                map.lookup(d1, [DVec3::ZERO; 2]).as_dvec3(),
                map.lookup(d2, [DVec3::ZERO; 2]).as_dvec3(),
            );
            let bound = lipschitz * theta + DVec3::splat(1e-5);
            prop_assert!(
                ((f1 - f2).abs() - bound).max_element() <= 0.0,
                "{d1} (uv {}) → {f1}, {d2} (uv {}) → {f2}, θ = {theta:e}, bound {bound}",
                lat_long::uv(d1), lat_long::uv(d2)
            );
        }
    }
}

// ---------------------------------------------------------------------------------
// 3. Round trips direction → (face, u, v) → direction.

/// A direction exactly on a cube edge (two components of equal magnitude, the third
/// no larger) or corner, scaled (coordinates take directions of any length).
fn cube_edge_or_corner() -> impl Strategy<Value = DVec3> {
    (
        0usize..3,
        any::<[bool; 3]>(),
        -1.0..=1.0f64,
        any::<bool>(),
        0.1..10.0f64,
    )
        .prop_map(|(axis, signs, t, corner, scale)| {
            let mut c = [1.0, 1.0, if corner { 1.0 } else { t }];
            for (c, negative) in c.iter_mut().zip(signs) {
                if negative {
                    *c = -*c;
                }
            }
            let v = [c[axis % 3], c[(axis + 1) % 3], c[(axis + 2) % 3]];
            DVec3::from(v) * scale
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Cube: the face is the major axis (ties to the earlier face), (u, v) is in
    /// [0, 1]², and the face's direction there is the direction, also exactly on edges
    /// and corners.
    #[test]
    fn cube_coordinates_round_trip(
        d in prop_oneof![
            (unit(), 0.1..10.0f64).prop_map(|(d, s)| d * s),
            cube_edge_or_corner(),
        ],
    ) {
        let (face, uv) = coordinates(Layout::Cube, d);
        prop_assert!((0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y), "{uv}");
        let [forward, _, _] = cube_map::face_frame(face);
        prop_assert_eq!(d.dot(forward), d.abs().max_element(), "{} for {}", FACE_NAMES[face], d);
        let earlier_tie = (0..face).any(|f| d.dot(cube_map::face_frame(f)[0]) == d.dot(forward));
        prop_assert!(!earlier_tie, "{d}: a tie goes to the earlier face, not {}", FACE_NAMES[face]);
        let back = texel_direction(Layout::Cube, face, uv);
        prop_assert!(
            (back - d.normalize()).length() < 1e-12,
            "{d} → {} {uv} → {back}",
            FACE_NAMES[face]
        );
    }

    /// Latitude-longitude, away from the poles: (u, v) in [0, 1]² and back.
    #[test]
    fn lat_long_coordinates_round_trip(
        d in unit().prop_filter("off the poles", |d| d.y.abs() < 0.999),
    ) {
        let (face, uv) = coordinates(Layout::LatLong, d);
        prop_assert_eq!(face, 0);
        prop_assert!((0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y), "{uv}");
        let back = texel_direction(Layout::LatLong, 0, uv);
        prop_assert!((back - d).length() < 1e-12, "{d} → {uv} → {back}");
    }

    /// Sphere map, away from its rim direction −z: (u, v) inside the inscribed disc and
    /// back.
    #[test]
    fn sphere_coordinates_round_trip(d in unit().prop_filter("off −z", |d| d.z > -0.999)) {
        let (face, uv) = coordinates(Layout::Sphere, d);
        prop_assert_eq!(face, 0);
        prop_assert!((uv - DVec2::splat(0.5)).length() <= 0.5 + 1e-15, "{uv}");
        let back = texel_direction(Layout::Sphere, 0, uv);
        prop_assert!((back - d).length() < 1e-12, "{d} → {uv} → {back}");
    }

    /// Through all three: cube coordinates and back, then sphere, then
    /// latitude-longitude, returns the starting direction.
    #[test]
    fn cube_sphere_lat_long_chain_returns_the_direction(
        d in unit().prop_filter("off the poles and −z", |d| d.y.abs() < 0.999 && d.z > -0.999),
    ) {
        let mut at = d;
        for layout in [Layout::Cube, Layout::Sphere, Layout::LatLong] {
            let (face, uv) = coordinates(layout, at);
            at = texel_direction(layout, face, uv);
        }
        prop_assert!((at - d).length() < 1e-12, "{d} → {at}");
    }
}

// ---------------------------------------------------------------------------------
// Orientation: the layouts put the world where their documentation says.

#[test]
fn layouts_are_oriented_as_documented() {
    // The cube's table (forward, up, right), written out independently.
    let table = [
        ("+x", DVec3::X, DVec3::Y, DVec3::Z),
        ("-x", DVec3::NEG_X, DVec3::Y, DVec3::NEG_Z),
        ("+y", DVec3::Y, DVec3::Z, DVec3::X),
        ("-y", DVec3::NEG_Y, DVec3::NEG_Z, DVec3::X),
        ("+z", DVec3::Z, DVec3::Y, DVec3::NEG_X),
        ("-z", DVec3::NEG_Z, DVec3::Y, DVec3::X),
    ];
    let n = 4;
    // Each face's texel (i, j) holds (i, j, face) (row j = 0 at the top of the image).
    let faces: Vec<Texels> = (0..6)
        .map(|f| Texels {
            width: n,
            height: n,
            texels: (0..n * n)
                .map(|k| Vec3::new((k % n) as f32, (k / n) as f32, f as f32))
                .collect(),
        })
        .collect();
    let map = EnvironmentMap::cube(faces.clone(), Filter::Nearest);
    for (face, (name, forward, up, right)) in table.into_iter().enumerate() {
        assert_eq!(FACE_NAMES[face], name);
        assert_eq!(cube_map::face_frame(face), [forward, up, right], "{name}");
        let close = |a: DVec3, b: DVec3| (a - b.normalize()).length() < 1e-12;
        assert!(close(
            cube_map::direction(face, DVec2::new(1.0, 0.5)),
            forward + right
        ));
        assert!(close(
            cube_map::direction(face, DVec2::new(0.5, 1.0)),
            forward + up
        ));
        // The image's top-right texel is up and to the right, its bottom-left the
        // opposite.
        let top_right = map.lookup(
            (forward + 0.9 * right + 0.9 * up).normalize(),
            [DVec3::ZERO; 2],
        );
        assert_eq!(top_right, Vec3::new(3.0, 0.0, face as f32), "{name}");
        let bottom_left = map.lookup(
            (forward - 0.9 * right - 0.9 * up).normalize(),
            [DVec3::ZERO; 2],
        );
        assert_eq!(bottom_left, Vec3::new(0.0, 3.0, face as f32), "{name}");
    }
    // The horizontal cross: −x, −z, +x, +z left to right in the middle row, +y above
    // −z and −y below it; to_texels lays it out again.
    let cells = [
        ("+x", 2, 1),
        ("-x", 0, 1),
        ("+y", 1, 0),
        ("-y", 1, 2),
        ("+z", 3, 1),
        ("-z", 1, 1),
    ];
    let mut cross = Texels {
        width: 4 * n,
        height: 3 * n,
        texels: vec![Vec3::splat(-1.0); (12 * n * n) as usize],
    };
    for (face, (name, column, row)) in cells.into_iter().enumerate() {
        assert_eq!(FACE_NAMES[face], name);
        for j in 0..n {
            for i in 0..n {
                let k = ((row * n + j) * 4 * n + column * n + i) as usize;
                cross.texels[k] = faces[face].texels[(j * n + i) as usize];
            }
        }
    }
    let from_cross = EnvironmentMap::from_cross(&cross, Filter::Nearest).unwrap();
    for (face, (name, forward, up, right)) in table.into_iter().enumerate() {
        let d = (forward + 0.9 * right + 0.9 * up).normalize();
        assert_eq!(
            from_cross.lookup(d, [DVec3::ZERO; 2]),
            Vec3::new(3.0, 0.0, face as f32),
            "{name} in the cross"
        );
    }
    let unfolded = from_cross.to_texels();
    assert_eq!((unfolded.width, unfolded.height), (4 * n, 3 * n));
    for (a, b) in unfolded.texels.iter().zip(&cross.texels) {
        assert!(*a == *b || (b.x < 0.0 && *a == Vec3::ZERO));
    }

    // The sphere map: the ball seen from +z, image right +x, top +y; −z on the rim.
    let r = 0.5 + 2f64.sqrt() / 4.0;
    let close = |a: DVec2, b: DVec2| (a - b).length() < 1e-12;
    assert!(close(sphere_map::uv(DVec3::Z), DVec2::splat(0.5)));
    assert!(close(sphere_map::uv(DVec3::X), DVec2::new(r, 0.5)));
    assert!(close(sphere_map::uv(DVec3::Y), DVec2::new(0.5, r)));
    assert!(close(
        sphere_map::uv(DVec3::NEG_X),
        DVec2::new(1.0 - r, 0.5)
    ));
    assert!(
        (sphere_map::uv(DVec3::new(1e-9, 0.0, -1.0)) - DVec2::splat(0.5)).length() > 0.5 - 1e-6
    );
    // The latitude-longitude map: −z in the centre, the zenith +y on the top row, −x
    // at u = ¾, +x at ¼, +z on the seam.
    assert!(close(lat_long::uv(DVec3::NEG_Z), DVec2::new(0.5, 0.5)));
    assert!(close(lat_long::uv(DVec3::NEG_X), DVec2::new(0.75, 0.5)));
    assert!(close(lat_long::uv(DVec3::X), DVec2::new(0.25, 0.5)));
    assert!((lat_long::uv(DVec3::Y).y - 1.0).abs() < 1e-12);
    assert!((lat_long::uv(DVec3::NEG_Y).y).abs() < 1e-12);
    let seam = lat_long::uv(DVec3::Z).x;
    assert!(seam.abs() < 1e-12 || (seam - 1.0).abs() < 1e-12, "{seam}");
    // Image rows: row 0 is the top (v = 1, the zenith).
    let rows = Texels::generate(8, 4, |uv| Vec3::splat(uv.y as f32));
    let map = EnvironmentMap::flat(Layout::LatLong, rows, Filter::Nearest);
    assert_eq!(map.lookup(DVec3::Y, [DVec3::ZERO; 2]), Vec3::splat(0.875));
}

// ---------------------------------------------------------------------------------
// 4. Converting a map whose texels encode their own direction.

/// Sides of the maps of the conversion chain.
const CUBE_SIDE: u32 = 64;
const SPHERE_SIDE: u32 = 256;
const LAT_LONG_HEIGHT: u32 = 128;

/// The largest angle a texel of any of the chain's maps spans at direction `d`: a
/// cube face's 2/n (at its centre; less towards its corners), the sphere map's
/// 4/(S cos θ/2) (conformal, θ the angle from +z: 4/S at the centre, 8/S at 120°), and
/// the latitude-longitude map's larger side, πr/H along the parallel or 2/(Hr) along
/// the meridian (r the distance from the polar axis y).
fn texel_angle(d: DVec3) -> f64 {
    let cube = 2.0 / CUBE_SIDE as f64;
    let sphere = 4.0 / (SPHERE_SIDE as f64 * ((1.0 + d.z) / 2.0).sqrt());
    let r = (1.0 - d.y * d.y).sqrt();
    let h = LAT_LONG_HEIGHT as f64;
    let lat_long = (PI * r / h).max(2.0 / (h * r));
    cube.max(sphere).max(lat_long)
}

/// `count` directions spread evenly over the sphere (a Fibonacci lattice).
fn fibonacci(count: usize) -> impl Iterator<Item = DVec3> {
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..count).map(move |k| {
        let z = 1.0 - 2.0 * (k as f64 + 0.5) / count as f64;
        let (r, phi) = ((1.0 - z * z).sqrt(), k as f64 * golden);
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    })
}

/// A cube map of `directions` (generated), converted by `convert` to a sphere map and
/// that to a latitude-longitude map, bilinear throughout: a lookup in each decodes to
/// the direction looked up, away from −z (within 60° of it the sphere map's texels
/// grow past 8/S, to the whole rim) and from the poles (|y| ≤ 0.9).
///
/// Tolerance: a quarter of `texel_angle` (the coarsest of the three maps there,
/// 1.8°–3.6°) at every direction, and a mean below 0.02°. Bilinear interpolation of a
/// function linear in the direction is exact up to the layouts' curvature; measured,
/// the worst is 0.11 texel (0.19°, near a cube corner, where the border texels sit half
/// a texel inside the neighbour) and the means 0.005°–0.006° per map. A texel centre
/// off by half a texel, or a row order flipped, anywhere in the chain shows as ½ texel.
#[test]
fn converted_directions_maps_decode_to_the_direction() {
    let cube = directions_map(Layout::Cube, CUBE_SIDE, Filter::Bilinear);
    let sphere = cube.convert(Layout::Sphere, SPHERE_SIDE);
    let lat_long = sphere.convert(Layout::LatLong, LAT_LONG_HEIGHT);
    assert_eq!(
        (sphere.layout(), sphere.size()),
        (Layout::Sphere, SPHERE_SIDE)
    );
    assert_eq!(
        (lat_long.layout(), lat_long.size()),
        (Layout::LatLong, LAT_LONG_HEIGHT)
    );
    let t = lat_long.to_texels();
    assert_eq!((t.width, t.height), (2 * LAT_LONG_HEIGHT, LAT_LONG_HEIGHT));
    let queries: Vec<DVec3> = fibonacci(20_000)
        .filter(|d| d.z >= -0.5 && d.y.abs() <= 0.9)
        .collect();
    for (name, map) in [
        ("cube", &cube),
        ("sphere", &sphere),
        ("lat-long", &lat_long),
    ] {
        let mut sum = 0.0;
        for &d in &queries {
            let found = decode(map.lookup(d, [DVec3::ZERO; 2]));
            let error = angle(found, d);
            let alpha = texel_angle(d);
            assert!(
                error <= 0.25 * alpha,
                "{name}: {d} → {found}: {:.3}° ({:.3} texel)",
                error.to_degrees(),
                error / alpha
            );
            sum += error.to_degrees();
        }
        let mean = sum / queries.len() as f64;
        assert!(mean < 0.02, "{name}: mean error {mean:.4}°");
    }
}

// ---------------------------------------------------------------------------------
// 5. Cube and sphere maps of one sky agree.

/// A cube map (faces of 256) and a sphere map (512, the same texel angle 2/n = 4/S at
/// +z) generated from the procedural sky, bilinear. +z is on the horizon, the sky's
/// discontinuity (sky above, hazy ground below); both maps straddle it alike and give
/// the same value (measured: 2.4e-7). Within 10° of +z: above the horizon the sky is
/// smooth and the maps agree to 3e-3 (measured 9.2e-4); below it the ground's checks
/// have edges, where any two resolutions differ, and each lookup is a mean of texels
/// that are means of the sky within ~1.5 texels, so the two differ by no more than the
/// sky's own range within 3 texels of the direction (measured: at most 0.43 of it).
#[test]
fn cube_and_sphere_maps_of_one_sky_agree_around_plus_z() {
    let sky = |d: DVec3| ProceduralEnvironment::Sky.radiance(d);
    let (n, s) = (256, 512);
    let cube = EnvironmentMap::generate(Layout::Cube, n, Filter::Bilinear, sky);
    let sphere = EnvironmentMap::generate(Layout::Sphere, s, Filter::Bilinear, sky);
    let at = |map: &EnvironmentMap, d: DVec3| map.lookup(d, [DVec3::ZERO; 2]).as_dvec3();
    let centre = (at(&cube, DVec3::Z) - at(&sphere, DVec3::Z)).abs();
    assert!(centre.max_element() < 1e-4, "at +z: {centre}");
    let rho = 3.0 * (2.0 / n as f64).max(4.0 / s as f64);
    let count = 2000;
    for k in 0..count {
        // Evenly over the cap within 10° of +z.
        let a = (k as f64 / count as f64).sqrt() * 10f64.to_radians();
        let phi = k as f64 * PI * (3.0 - 5f64.sqrt());
        let d = DVec3::new(a.sin() * phi.cos(), a.sin() * phi.sin(), a.cos());
        let diff = (at(&cube, d) - at(&sphere, d)).abs();
        if d.y > 0.0 {
            assert!(diff.max_element() < 3e-3, "{d}: {diff}");
            continue;
        }
        let (u, w) = d.any_orthonormal_pair();
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for ring in 0..=4 {
            for j in 0..24 {
                let t = j as f64 / 24.0 * TAU;
                let offset = rho * ring as f64 / 4.0 * (t.cos() * u + t.sin() * w);
                let v = sky((d + offset).normalize()).as_dvec3();
                (lo, hi) = (lo.min(v), hi.max(v));
            }
        }
        let range = hi - lo;
        assert!(
            (diff - range).max_element() <= 1e-4,
            "{d}: cube {} sphere {}, the sky's range {range}",
            at(&cube, d),
            at(&sphere, d)
        );
    }
}

// ---------------------------------------------------------------------------------
// 6. Optics.

/// Indices of refraction from vacuum to diamond's.
fn index() -> impl Strategy<Value = f64> {
    1.0..2.5f64
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Snell's law for random incidences: η₁ sin θ₁ = η₂ sin θ₂, T unit, in the plane of
    /// I and N, on the far side of the surface, its tangential part along I's; `None`
    /// exactly when η₁ sin θ₁ > η₂ (total internal reflection).
    #[test]
    fn refraction_obeys_snells_law(
        n in unit(), i in unit(), eta1 in index(), eta2 in index(),
    ) {
        // I travels towards the surface: against the normal.
        let i = if i.dot(n) > 0.0 { -i } else { i };
        prop_assume!(i.dot(n) < -1e-6);
        let sin1 = i.cross(n).length();
        match refract(i, n, eta1 / eta2) {
            Some(t) => {
                prop_assert!((t.length() - 1.0).abs() < 1e-12, "|T| = {}", t.length());
                let sin2 = t.cross(n).length();
                prop_assert!((eta1 * sin1 - eta2 * sin2).abs() < 1e-12,
                    "η₁ sin θ₁ = {} but η₂ sin θ₂ = {}", eta1 * sin1, eta2 * sin2);
                prop_assert!(t.dot(n) <= 0.0, "T = {t} is on the incident side");
                let plane = i.cross(n).normalize_or_zero();
                prop_assert!(plane.dot(t).abs() < 1e-12, "T out of the plane");
                let (ti, tt) = (i - i.dot(n) * n, t - t.dot(n) * n);
                prop_assert!(ti.dot(tt) >= -1e-15, "T bends back: {ti} vs {tt}");
                prop_assert!(eta1 * sin1 <= eta2 * (1.0 + 1e-12));
            }
            None => prop_assert!(eta1 * sin1 > eta2 * (1.0 - 1e-12),
                "no refraction at η₁ sin θ₁ = {} < η₂ = {eta2}", eta1 * sin1),
        }
    }

    /// Total internal reflection starts at the critical angle asin(η₂/η₁): just below
    /// it the ray refracts (grazing), just above it does not.
    #[test]
    fn total_internal_reflection_starts_at_the_critical_angle(
        eta1 in 1.05..2.5f64, ratio in 0.4..0.95f64, n in unit(), phi in 0.0..TAU,
    ) {
        let eta2 = eta1 * ratio;
        let critical = (eta2 / eta1).asin();
        let (a, b) = n.any_orthonormal_pair();
        let tangent = phi.cos() * a + phi.sin() * b;
        let incident = |theta: f64| theta.sin() * tangent - theta.cos() * n;
        let below = refract(incident(critical - 1e-7), n, eta1 / eta2);
        prop_assert!(below.is_some(), "no refraction just below the critical angle");
        prop_assert!(below.unwrap().dot(n).abs() < 1e-2, "not grazing: {}", below.unwrap());
        prop_assert!(refract(incident(critical + 1e-7), n, eta1 / eta2).is_none());
        // Schlick: reflectance 1 beyond it, close to 1 just below.
        prop_assert_eq!(schlick((critical + 1e-7).cos(), eta1, eta2), 1.0);
        prop_assert!(schlick((critical - 1e-7).cos(), eta1, eta2) > 0.95);
        prop_assert_eq!(schlick(0.0, eta1, eta2), 1.0);
    }

    /// Index-matched, the ray goes straight through.
    #[test]
    fn refraction_at_eta_one_is_the_identity(n in unit(), i in unit()) {
        let i = if i.dot(n) > 0.0 { -i } else { i };
        let t = refract(i, n, 1.0).expect("no total internal reflection at η = 1");
        // √k = √(1 − (1 − c²)) carries the rounding of 1 − c² divided by 2c.
        let c = -i.dot(n);
        prop_assert!((t - i).length() < 1e-15 + 1e-15 / c, "{i} → {t}");
    }

    /// The mirror direction: unit, N·R = N·V, and R + V along N (so R is in the plane
    /// of V and N, on the other side of N).
    #[test]
    fn reflection_is_the_mirror_direction(n in unit(), v in unit()) {
        let v = if v.dot(n) < 0.0 { -v } else { v };
        let r = reflect(v, n);
        prop_assert!((r.length() - 1.0).abs() < 1e-12);
        prop_assert!((n.dot(r) - n.dot(v)).abs() < 1e-12);
        prop_assert!((r + v).cross(n).length() < 1e-12);
        prop_assert!((r - v).dot(n).abs() < 1e-12);
    }

    /// Schlick: F₀ = ((n − 1)/(n + 1))² at normal incidence from either side, 1 at
    /// grazing incidence, growing with the angle in between; 0 between equal indices.
    #[test]
    fn schlick_at_normal_and_grazing_incidence(
        eta in index(), c1 in 0.0..1.0f64, c2 in 0.0..1.0f64,
    ) {
        let f0 = ((eta - 1.0) / (eta + 1.0)).powi(2);
        prop_assert!((schlick(1.0, 1.0, eta) - f0).abs() < 1e-15);
        prop_assert!((schlick(1.0, eta, 1.0) - f0).abs() < 1e-15);
        prop_assert!((schlick(0.0, 1.0, eta) - 1.0).abs() < 1e-15);
        let (lo, hi) = if c1 < c2 { (c1, c2) } else { (c2, c1) };
        prop_assert!(schlick(lo, 1.0, eta) >= schlick(hi, 1.0, eta));
        prop_assert_eq!(schlick(c1, eta, eta), 0.0);
    }
}

// ---------------------------------------------------------------------------------
// 7. A mirror ball against the analytic one.

/// A camera at z = 3.2 looking at the unit sphere (chrome, nothing else: no lights,
/// no diffuse) in a fine `directions` cube map.
fn mirror_ball(resolution: u32) -> String {
    format!(
        r#"{}
        [environments.env]
        procedural = "directions"
        layout = "cube"
        resolution = 512
        filter = "bilinear"
        [materials.chrome]
        mirror = [1.0, 1.0, 1.0]
        environment = "env"
        [[objects]]
        shape = "sphere"
        material = "chrome"
        resolution = {resolution}
        [render]
        backdrop = "env"
        "#,
        support::camera([0.0, 0.0, 3.2], [0.0, 0.0, 0.0], 40.0, 160, 160)
    )
}

/// Per pixel whose eye ray meets the analytic unit sphere well inside its silhouette
/// (N·V ≥ ½, 60° from grazing), the rendered colour decodes to the analytic mirror
/// direction R = 2(N·V)N − V at the analytic hit point. The tessellated sphere (128
/// segments, 64 rings, Phong-interpolated vertex normals) sits inside the true one and
/// interpolates its normals, so R is off a little; measured over 12 024 pixels: mean
/// 0.036°, max 0.114° (64 segments: 0.144°, 0.455°; 256: 0.009°, 0.029°). Asserted:
/// mean < 0.06°, max < 0.2°. A flat normal, a wrong sign in R or V, or a map indexed
/// the wrong way round gives degrees to tens of degrees.
#[test]
fn a_mirror_ball_reflects_the_analytic_directions() {
    let scene = scene(&mirror_ball(128));
    let image = lumiere::render(&scene).unwrap();
    let view = View::new(&scene.camera, image.width, image.height);
    let (mut sum, mut count, mut worst) = (0.0, 0, 0.0f64);
    for y in 0..image.height {
        for x in 0..image.width {
            let w = eye_ray(&view, x, y);
            let found = decode(image.pixels[(y * image.width + x) as usize]);
            // |e + tw| = 1: t² + 2(e·w)t + |e|² − 1 = 0, the nearer root.
            let (e, b) = (view.eye, view.eye.dot(w));
            let disc = b * b - (e.length_squared() - 1.0);
            if disc <= 0.0 {
                // The backdrop: the eye ray's own direction.
                if disc < -0.05 {
                    assert!(angle(found, w) < 1e-3, "backdrop at ({x}, {y})");
                }
                continue;
            }
            let n = (e + w * (-b - disc.sqrt())).normalize();
            if n.dot(-w) < 0.5 {
                continue;
            }
            // The mirror direction of the eye ray, written out (not `reflect`).
            let a = angle(found, w - 2.0 * w.dot(n) * n).to_degrees();
            (sum, count, worst) = (sum + a, count + 1, worst.max(a));
        }
    }
    let mean = sum / count as f64;
    assert!(count > 10_000, "{count} pixels");
    assert!(
        mean < 0.06 && worst < 0.2,
        "mean {mean:.4}°, max {worst:.4}°"
    );
}

// ---------------------------------------------------------------------------------
// 8. An index-matched refractor shows the backdrop straight through.

/// A quad filling the middle of the view, ior 1, transmittance 1, mirror 0, in front
/// of a `directions` backdrop (`filter`), or the backdrop alone.
fn index_matched(filter: &str, quad: bool) -> String {
    let quad = if quad {
        r#"
        [materials.water]
        ior = 1.0
        transmittance = [1.0, 1.0, 1.0]
        environment = "env"
        [[objects]]
        shape = "quad"
        material = "water"
        transform = [{ rotate = { axis = [1.0, 0.0, 0.0], degrees = 90.0 } }, { scale = 1.5 }]
        "#
    } else {
        ""
    };
    format!(
        r#"{}
        [environments.env]
        procedural = "directions"
        resolution = 128
        filter = "{filter}"
        [render]
        backdrop = "env"
        {quad}
        "#,
        support::camera([0.0, 0.0, 3.0], [0.0, 0.0, 0.0], 40.0, 96, 72)
    )
}

/// At η = 1 the refracted ray is the eye ray and there is no interface to reflect
/// (Fresnel 0; Schlick's formula alone would still give (1 − cos θ)⁵, 6e-7 at this
/// view's largest incidence, 19.5°), so the refractor shows exactly the backdrop behind
/// it: the same pixels as the backdrop alone (trilinear too, so the refracted
/// footprint must be the eye rays' own), decoding to the eye ray's direction.
/// Measured: the two images are bit-identical; asserted within 1e-6.
#[test]
fn an_index_matched_refractor_shows_the_backdrop_straight_through() {
    for filter in ["bilinear", "trilinear"] {
        let with = scene(&index_matched(filter, true));
        let without = scene(&index_matched(filter, false));
        let (a, b) = (
            lumiere::render(&with).unwrap(),
            lumiere::render(&without).unwrap(),
        );
        let view = View::new(&with.camera, a.width, a.height);
        let (_, surface) = lumiere::render::visible_surface(&with);
        let mut covered = 0;
        for y in 0..a.height {
            for x in 0..a.width {
                let k = (y * a.width + x) as usize;
                let diff = (a.pixels[k] - b.pixels[k]).abs().max_element();
                assert!(
                    diff < 1e-6,
                    "{filter} ({x}, {y}): {} vs {}",
                    a.pixels[k],
                    b.pixels[k]
                );
                if !surface.samples[k].is_empty() {
                    covered += 1;
                    let found = decode(a.pixels[k]);
                    let error = angle(found, eye_ray(&view, x, y));
                    // Bilinear in a 128² cube map (texels 0.9°): far below a texel.
                    assert!(error < 2e-3, "{filter} ({x}, {y}): {found}, {error}");
                }
            }
        }
        assert!(covered > 1000, "the quad covers {covered} pixels");
    }
}

/// A glass quad (ior 1.5, transmittance 1, mirror 0) tilted 35° about y, seen from its
/// front (`back` false) or its back, in front of a `directions` cube map.
fn glass_quad(back: bool) -> String {
    let degrees = if back { -90.0 } else { 90.0 };
    format!(
        r#"{}
        [environments.env]
        procedural = "directions"
        resolution = 256
        filter = "bilinear"
        [materials.glass]
        ior = 1.5
        transmittance = [1.0, 1.0, 1.0]
        environment = "env"
        [[objects]]
        shape = "quad"
        material = "glass"
        transform = [{{ rotate = {{ axis = [1.0, 0.0, 0.0], degrees = {degrees} }} }}, {{ rotate = {{ axis = [0.0, 1.0, 0.0], degrees = 35.0 }} }}, {{ scale = 3.0 }}]
        "#,
        support::camera([0.0, 0.0, 3.0], [0.0, 0.0, 0.0], 40.0, 96, 72)
    )
}

/// Refraction mapping through one flat interface, from both sides: each pixel is
/// Schlick's F times the environment at the mirror direction plus (1 − F) times the
/// environment at Snell's direction (the mirror direction beyond the critical angle,
/// from inside), all written out here from the geometry: the hit point on the plane,
/// V, the normal turned towards the eye, the indices in the order the side gives,
/// T's tangential part η₁/η₂ times I's. Within 1e-4 per channel (measured: 9.1e-6 from
/// the front, 8.9e-6 from the back, where 1560 of the 5688 pixels reflect totally):
/// the bilinear lookups of a 256² `directions` map and f32 colours.
#[test]
fn a_glass_quad_blends_reflection_and_refraction_by_schlick() {
    let colour = |d: DVec3| (d.normalize() + DVec3::ONE) / 2.0;
    for back in [false, true] {
        let scene = scene(&glass_quad(back));
        let image = lumiere::render(&scene).unwrap();
        let view = View::new(&scene.camera, image.width, image.height);
        let (_, surface) = lumiere::render::visible_surface(&scene);
        let plane = &scene.polygons[0];
        let (mut covered, mut total_reflection) = (0, 0);
        for y in 0..image.height {
            for x in 0..image.width {
                let k = (y * image.width + x) as usize;
                if surface.samples[k].is_empty() {
                    continue;
                }
                covered += 1;
                let w = eye_ray(&view, x, y);
                let t = (plane.positions().next().unwrap() - view.eye).dot(plane.normal)
                    / w.dot(plane.normal);
                let v = (view.eye - (view.eye + t * w)).normalize();
                let front = plane.normal.dot(v) > 0.0;
                assert_eq!(front, !back);
                let n = if front { plane.normal } else { -plane.normal };
                let (eta1, eta2) = if front { (1.0, 1.5) } else { (1.5, 1.0) };
                let cos = n.dot(v);
                let r = 2.0 * cos * n - v;
                let tangential = -(v - cos * n) * (eta1 / eta2);
                let sin2 = tangential.length_squared();
                let f0 = ((eta1 - eta2) / (eta1 + eta2)).powi(2);
                let expected = if sin2 > 1.0 {
                    total_reflection += 1;
                    colour(r)
                } else {
                    let t = tangential - (1.0 - sin2).sqrt() * n;
                    let cos_thin = if front { cos } else { (1.0 - sin2).sqrt() };
                    let f = f0 + (1.0 - f0) * (1.0 - cos_thin).powi(5);
                    f * colour(r) + (1.0 - f) * colour(t)
                };
                let found = image.pixels[k].as_dvec3();
                assert!(
                    (found - expected).abs().max_element() < 1e-4,
                    "back {back} ({x}, {y}): {found} vs {expected}"
                );
            }
        }
        assert!(covered > 2000, "{covered}");
        // Seen from inside, the steeper side of the tilted quad reflects totally.
        assert_eq!(
            total_reflection > 100,
            back,
            "{total_reflection} of {covered}"
        );
    }
}

// ---------------------------------------------------------------------------------
// 9. Bad input: one clear line naming the key.

fn png(width: u32, height: u32) -> Vec<u8> {
    let mut bytes = Vec::new();
    image::RgbImage::from_pixel(width, height, image::Rgb([200, 100, 50]))
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    bytes
}

/// A valid scene around an `[environments.env]` given by `environment`, a material
/// `material`, and `render` lines.
fn environment_scene(environment: &str, material: &str, render: &str) -> String {
    format!(
        "{}[render]\n{render}\n\n[environments.env]\n{environment}\n\n\
         [materials.shiny]\n{material}\n\n[[objects]]\nshape = \"sphere\"\nmaterial = \"shiny\"\n",
        support::camera([0.0, 0.0, 3.0], [0.0, 0.0, 0.0], 40.0, 16, 12)
    )
}

const CHROME: &str = "mirror = [1.0, 1.0, 1.0]\nenvironment = \"env\"";

#[test]
fn bad_environment_input_is_one_clear_error_line() {
    let files = || {
        vec![
            ("face.png", png(4, 4)),
            ("big.png", png(8, 8)),
            ("wide.png", png(4, 3)),
            ("cross.png", png(8, 4)),
        ]
    };
    let faces = |px: &str, nx: &str, nz: bool| {
        let nz = if nz { ", nz = \"face.png\"" } else { "" };
        format!(
            "faces = {{ px = \"{px}\", nx = \"{nx}\", py = \"face.png\", ny = \"face.png\", \
             pz = \"face.png\"{nz} }}"
        )
    };
    let sky = "procedural = \"sky\"\nresolution = 8";
    let cases = [
        (
            environment_scene(&faces("face.png", "face.png", false), CHROME, ""),
            &["environments.env.faces", "nz"][..],
        ),
        (
            environment_scene(&faces("wide.png", "face.png", true), CHROME, ""),
            &["environments.env.faces.px", "square", "4x3"],
        ),
        (
            environment_scene(&faces("face.png", "big.png", true), CHROME, ""),
            &["environments.env.faces.nx", "one size", "8x8", "4x4"],
        ),
        (
            environment_scene("image = \"cross.png\"\nlayout = \"cube\"", CHROME, ""),
            &["environments.env.image", "4:3", "8x4"],
        ),
        (
            environment_scene(sky, "ior = 0.0\nenvironment = \"env\"", ""),
            &["materials.shiny.ior", "positive"],
        ),
        (
            environment_scene(sky, "ior = -1.5\nenvironment = \"env\"", ""),
            &["materials.shiny.ior", "-1.5"],
        ),
        (
            environment_scene(sky, "mirror = [0.5, 0.5, 0.5]", ""),
            &["materials.shiny.environment"],
        ),
        (
            environment_scene(sky, CHROME, "backdrop = \"skye\""),
            &["render.backdrop", "skye"],
        ),
    ];
    for (text, fragments) in cases {
        let dir = tempfile::tempdir().unwrap();
        for (name, bytes) in files() {
            std::fs::write(dir.path().join(name), bytes).unwrap();
        }
        std::fs::write(dir.path().join("scene.toml"), &text).unwrap();
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_lumiere"))
            .args(["render", "scene.toml", "-o", "out.png"])
            .current_dir(dir.path())
            .output()
            .expect("the binary runs");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "should fail: {text}");
        assert!(!stderr.contains("panicked"), "panic: {stderr}");
        let lines: Vec<&str> = stderr.lines().collect();
        assert_eq!(lines.len(), 1, "one line expected, got: {stderr}");
        assert!(lines[0].starts_with("error: "), "{}", lines[0]);
        for fragment in fragments {
            assert!(
                lines[0].contains(fragment),
                "`{fragment}` not in: {}",
                lines[0]
            );
        }
        assert!(!dir.path().join("out.png").exists(), "out.png was written");
        eprintln!("MEASURE {}", lines[0]);
    }
    // The same scenes with the defects removed load.
    for text in [
        environment_scene(&faces("face.png", "face.png", true), CHROME, ""),
        environment_scene("image = \"face.png\"\nlayout = \"lat-long\"", CHROME, ""),
        environment_scene(
            sky,
            "ior = 1.33\nenvironment = \"env\"",
            "backdrop = \"env\"",
        ),
    ] {
        load_in_dir(&text, &files()).unwrap_or_else(|e| panic!("{}", error_line(&e)));
    }
}
