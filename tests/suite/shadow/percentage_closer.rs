//! Reeves, Salesin & Cook's percentage-closer filter (src/shadow/percentage_closer.rs)
//! and the box filter beside it, against exact answers: on depth images made by
//! hand, the estimate converges to the exact share of the region's area whose
//! texels pass, and the box equals a brute-force count over its texels;
//! ALGORITHMS.md's invariants (in [0, 1]; exactly 0 or 1 away from edges; one texel
//! and one point is Williams's test; a monotone profile across a straight edge);
//! footprints where they are known exactly; on rendered planes, the profile's width
//! and agreement with area-sampled ray casting.

use crate::support;

use glam::{DVec2, DVec3};
use lumiere::geometry::sampling::Stream;
use lumiere::load_scene;
use lumiere::raster::View;
use lumiere::render::visible_surface;
use lumiere::scene::{Camera, Scene};
use lumiere::settings::ShadowMethod;
use lumiere::settings::{MapFilter, PercentageCloser};
use lumiere::shadow::percentage_closer::{MAX_FOOTPRINT, Region, footprint, percentage_closer};
use lumiere::shadow::shadow_map::{CubeShadowMap, DepthImage, Lookup, MapPoint};

/// Stored depths: a texel in front of the tested point (it shadows) and one behind.
const NEAR: f32 = 0.25;
const FAR: f32 = 1.0;
/// The tested point's depth, between the two.
const DEPTH: f64 = 0.5;

/// The tested point at map position `at`, its bias unit one depth unit.
fn point(at: DVec2) -> MapPoint {
    MapPoint {
        face: 0,
        at,
        depth: DEPTH,
        slope: 1.0,
        texel: 1.0,
    }
}

fn filter(samples: u32, bias: [f64; 2]) -> PercentageCloser {
    PercentageCloser {
        samples,
        bias,
        ..Default::default()
    }
}

/// A `size²` map whose texels shadow or not at random, half and half.
fn random_map(size: u32, seed: u64) -> Vec<f32> {
    let mut s = Stream::new(seed, 0);
    (0..size * size)
        .map(|_| if s.next_f64() < 0.5 { FAR } else { NEAR })
        .collect()
}

fn region(x0: f64, y0: f64, x1: f64, y1: f64) -> Region {
    Region {
        min: DVec2::new(x0, y0),
        max: DVec2::new(x1, y1),
    }
}

/// The exact share of `region`'s area lying over texels that pass at `depth`: the
/// sum of texel ∩ region over passing texels (beyond the border, the border's
/// texel), by its own lookup.
fn exact_fraction(map: &DepthImage, r: Region, depth: f64) -> f64 {
    let last = map.size as i64 - 1;
    let mut lit = 0.0;
    for j in r.min.y.floor() as i64..r.max.y.ceil() as i64 {
        for i in r.min.x.floor() as i64..r.max.x.ceil() as i64 {
            let w = (r.max.x.min(i as f64 + 1.0) - r.min.x.max(i as f64)).max(0.0);
            let h = (r.max.y.min(j as f64 + 1.0) - r.min.y.max(j as f64)).max(0.0);
            let (u, v) = (i.clamp(0, last), j.clamp(0, last));
            if depth <= map.depth[(v * map.size as i64 + u) as usize] as f64 {
                lit += w * h;
            }
        }
    }
    let size = r.size();
    lit / (size.x * size.y)
}

/// Reeves's estimate with stream `index` of seed 7.
fn estimate(map: &DepthImage, r: Region, f: &PercentageCloser, index: u64) -> f64 {
    let at = point(0.5 * (r.min + r.max));
    percentage_closer(map, &at, r, f, &mut Stream::new(7, index)) as f64
}

/// (a) On a random map, the estimate over a region converges to the exact area
/// fraction, without bias, its RMS error falling about as N^(-3/4) (stratified
/// points over edges): measured 0.232, 0.090, 0.036, 0.0123 for N = 4 … 256.
#[test]
fn the_estimate_converges_to_the_exact_area_fraction() {
    let depth = random_map(16, 1);
    let map = DepthImage {
        size: 16,
        depth: &depth,
    };
    let regions = [
        region(3.3, 4.7, 9.1, 8.2),
        region(0.5, 0.5, 2.9, 6.4),
        region(7.25, 1.1, 15.6, 3.05),
        region(10.2, 10.2, 12.7, 15.9),
    ];
    let streams = 500;
    let mut rms = Vec::new();
    for n in [4, 16, 64, 256] {
        let f = filter(n, [0.0, 0.0]);
        let (mut squares, mut sum, mut count) = (0.0, 0.0, 0.0);
        for (r, &reg) in regions.iter().enumerate() {
            let exact = exact_fraction(&map, reg, DEPTH);
            assert!(exact > 0.2 && exact < 0.8, "region {r}: {exact}");
            for s in 0..streams {
                let v = estimate(&map, reg, &f, (r * streams + s) as u64);
                assert!((0.0..=1.0).contains(&v), "{v}");
                squares += (v - exact).powi(2);
                sum += v - exact;
                count += 1.0;
            }
        }
        let error = (squares / count).sqrt();
        let mean = sum / count;
        assert!(
            mean.abs() < 4.0 * error / count.sqrt(),
            "N = {n}: biased by {mean} (RMS {error})"
        );
        rms.push(error);
    }
    eprintln!("RMS error for N = 4, 16, 64, 256: {rms:?}");
    assert!(
        rms.windows(2).all(|w| w[1] < w[0] / 2.0),
        "not falling as N^(-3/4): {rms:?}"
    );
    for (error, bound) in rms.iter().zip([0.25, 0.1, 0.04, 0.0135]) {
        assert!(*error < bound, "{rms:?}");
    }
}

/// (b) Against a brute-force fraction over the region: regions of random sizes and
/// places, each spanning several rows and columns, within 0.03 with 1,024 points
/// (measured: at most 0.0155); the box filter equals the exact count of its
/// kernel's texels (to rounding).
#[test]
fn estimates_agree_with_a_brute_force_fraction_over_the_region() {
    let depth = random_map(12, 2);
    let map = DepthImage {
        size: 12,
        depth: &depth,
    };
    let f = filter(1024, [0.0, 0.0]);
    let mut places = Stream::new(3, 0);
    let mut worst: f64 = 0.0;
    for index in 0..200 {
        let mut draw = |lo: f64, hi: f64| lo + (hi - lo) * places.next_f64();
        let (w, h) = (draw(2.0, 7.0), draw(2.0, 7.0));
        let (x, y) = (draw(-1.0, 12.0 - w + 1.0), draw(-1.0, 12.0 - h + 1.0));
        let r = region(x, y, x + w, y + h);
        let exact = exact_fraction(&map, r, DEPTH);
        let v = estimate(&map, r, &f, index);
        worst = worst.max((v - exact).abs());
    }
    eprintln!("worst error against the brute-force fraction: {worst:.4}");
    assert!(worst < 0.03, "{worst}");
    for kernel in [1, 3, 5] {
        let r = (kernel / 2) as f64;
        for j in 0..12 {
            for i in 0..12 {
                let value = map.box_filter((i, j), kernel, DEPTH) as f64;
                let (x, y) = (i as f64, j as f64);
                let exact =
                    exact_fraction(&map, region(x - r, y - r, x + r + 1.0, y + r + 1.0), DEPTH);
                assert!(
                    (value - exact).abs() < 1e-6,
                    "box {kernel} at ({i}, {j}): {value} against {exact}"
                );
            }
        }
    }
}

/// Each point draws its own bias: over a flat map whose depth lies inside the bias
/// range, the fraction of points that pass is the share of the range that reaches
/// behind it (here half), not 0 or 1 as a bias shared by the points would give.
#[test]
fn each_point_has_its_own_bias() {
    let depth = vec![1.0; 64];
    let map = DepthImage {
        size: 8,
        depth: &depth,
    };
    // The point lies 1.5 units behind the stored depth; biases in [1, 2].
    let at = MapPoint {
        depth: 2.5,
        ..point(DVec2::splat(4.0))
    };
    let r = region(2.0, 2.0, 6.0, 6.0);
    for (n, tolerance) in [(256, 0.15), (1024, 0.08)] {
        let f = filter(n, [1.0, 2.0]);
        let values: Vec<f64> = (0..200)
            .map(|s| percentage_closer(&map, &at, r, &f, &mut Stream::new(9, s)) as f64)
            .collect();
        let worst = values.iter().map(|v| (v - 0.5).abs()).fold(0.0, f64::max);
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        assert!(worst < tolerance, "N = {n}: a sample at {worst} from 0.5");
        assert!((mean - 0.5).abs() < 0.01, "N = {n}: mean {mean}");
    }
    // With no range, every point has the same bias: all pass or none do.
    for (bias, expected) in [(1.4, 0.0), (1.6, 1.0)] {
        let f = filter(64, [bias, bias]);
        let v = percentage_closer(&map, &at, r, &f, &mut Stream::new(9, 0));
        assert_eq!(v, expected, "bias {bias}");
    }
}

/// (c) Away from edges the result is exactly 0 or 1, for any region, number of
/// points and bias range that does not reach across the depths' gap.
#[test]
fn away_from_edges_the_result_is_exactly_zero_or_one() {
    // Columns 0 to 15 let the point pass, 16 to 31 shadow it.
    let depth: Vec<f32> = (0..32 * 32)
        .map(|k| if k % 32 < 16 { FAR } else { NEAR })
        .collect();
    let map = DepthImage {
        size: 32,
        depth: &depth,
    };
    let mut places = Stream::new(4, 0);
    for index in 0..300 {
        let mut draw = |lo: f64, hi: f64| lo + (hi - lo) * places.next_f64();
        let (w, h) = (draw(0.1, 6.0), draw(0.1, 6.0));
        let lit = index % 2 == 0;
        let x = if lit {
            draw(-2.0, 16.0 - w)
        } else {
            draw(16.0, 34.0 - w)
        };
        let y = draw(-2.0, 34.0 - h);
        let n = [1, 4, 16, 64][index as usize % 4];
        let f = filter(n, [0.0, 0.2]);
        let v = estimate(&map, region(x, y, x + w, y + h), &f, index);
        assert_eq!(v, if lit { 1.0 } else { 0.0 }, "region at ({x}, {y})");
    }
}

/// (c) Across a straight edge the profile is monotone (the same numbers at every
/// position: moving the region moves every point) and exactly 1 or 0 until the
/// region reaches the edge; averaged over streams it is the linear ramp of a box
/// region, as wide as the region.
#[test]
fn across_a_straight_edge_the_profile_is_monotone_and_as_wide_as_the_region() {
    let depth: Vec<f32> = (0..32 * 32)
        .map(|k| if k % 32 < 16 { FAR } else { NEAR })
        .collect();
    let map = DepthImage {
        size: 32,
        depth: &depth,
    };
    let (width, f) = (5.0, filter(16, [0.0, 0.2]));
    let at = |c: f64| region(c - 0.5 * width, 10.3, c + 0.5 * width, 13.3);
    for s in 0..50 {
        let mut previous = 1.0;
        for step in 0..=240 {
            let c = 10.0 + 0.05 * step as f64;
            let v = estimate(&map, at(c), &f, s);
            assert!(v <= previous, "stream {s}: rises at {c}");
            if c < 16.0 - 0.5 * width - 1e-9 {
                assert_eq!(v, 1.0, "stream {s} at {c}");
            }
            if c > 16.0 + 0.5 * width + 1e-9 {
                assert_eq!(v, 0.0, "stream {s} at {c}");
            }
            previous = v;
        }
    }
    for t in [-0.4, -0.2, 0.0, 0.2, 0.4] {
        let c = 16.0 + t * width;
        let mean = (0..400).map(|s| estimate(&map, at(c), &f, s)).sum::<f64>() / 400.0;
        assert!((mean - (0.5 - t)).abs() < 0.02, "at {t}: {mean}");
    }
}

/// (c) A one-texel region with one point and no bias range is Williams's binary
/// test, at every visible sample of the curved scene, on its real cube map.
#[test]
fn one_texel_and_one_point_is_williamss_test() {
    let scene = load_scene(
        "ray-cast-shadows-curved",
        &["camera.width=128".into(), "camera.height=96".into()],
    )
    .unwrap();
    let (_, surface) = visible_surface(&scene);
    let light = scene.lights[0].position().unwrap();
    let lookup = Lookup {
        bias: 1.5,
        ..Lookup::of(&scene.shadows, 0)
    };
    let map = CubeShadowMap::build(&scene, light, 256, lookup);
    let f = filter(1, [1.5, 1.5]);
    let (mut lit, mut dark) = (0, 0);
    for (k, s) in surface.samples.iter().enumerate() {
        if s.is_empty() {
            continue;
        }
        let n = scene.polygons[s.polygon as usize].normal;
        let at = map.locate(s.position, n);
        let image = map.image(at.face);
        let (i, j) = image.texel(at.at);
        let mut stream = Stream::new(5, k as u64);
        let reeves = percentage_closer(&image, &at, Region::texel(i, j), &f, &mut stream);
        let williams = map.box_filter(s.position, n, 1);
        assert_eq!(reeves, williams, "sample {k}");
        lit += (williams == 1.0) as u32;
        dark += (williams == 0.0) as u32;
    }
    assert!(lit > 5000 && dark > 500, "{lit} lit, {dark} dark");
}

/// A camera at `eye` looking down −z with a 60° field of view on a `size²` grid.
fn square_view(eye: DVec3, size: u32) -> View {
    let camera = Camera {
        eye,
        look_at: eye + DVec3::NEG_Z,
        up: DVec3::Y,
        fov_y: 60.0,
        width: size,
        height: size,
        near: 0.01,
    };
    View::new(&camera, size, size)
}

/// The footprint where it is known exactly: seen from the light itself through the
/// same grid, a cell is its own texel; through a grid half as fine, two texels
/// square; a plane the eye grazes, or one behind the eye, gives the capped square.
#[test]
fn footprints_where_they_are_known_exactly() {
    let light = square_view(DVec3::ZERO, 64);
    let (p, n) = (
        DVec3::new(0.3, -0.2, -5.0),
        DVec3::new(0.1, 0.2, 1.0).normalize(),
    );
    for (eye, scale) in [
        (square_view(DVec3::ZERO, 64), 1.0),
        (square_view(DVec3::ZERO, 32), 2.0),
    ] {
        for (x, y) in [(0, 0), (5, 17), (20, 31), (31, 8)] {
            let centre = DVec2::new(x as f64 + 0.5, y as f64 + 0.5) * scale;
            let r = footprint(&eye, (x, y), p, n, &light, centre);
            let expected = region(
                x as f64 * scale,
                y as f64 * scale,
                (x + 1) as f64 * scale,
                (y + 1) as f64 * scale,
            );
            assert!(
                (r.min - expected.min).abs().max_element() < 1e-9
                    && (r.max - expected.max).abs().max_element() < 1e-9,
                "cell ({x}, {y}) at scale {scale}: {r:?}"
            );
        }
    }
    // Low over the ground y = 0, looking along it, lit from straight above.
    let eye = square_view(DVec3::new(0.0, 1.0, 0.0), 64);
    let above = View::new(
        &Camera {
            eye: DVec3::new(0.0, 5.0, -30.0),
            look_at: DVec3::new(0.0, 0.0, -30.0),
            up: DVec3::NEG_Z,
            fov_y: 60.0,
            width: 64,
            height: 64,
            near: 0.01,
        },
        64,
        64,
    );
    let own = |x: f64, y: f64| {
        let (o, d) = eye.ray_through(x, y);
        let hit = o + (-o.y / d.y) * d;
        let (u, v) = above.project(above.to_eye(hit));
        DVec2::new(u, v)
    };
    // Rays through the horizon row's upper corners pass above it (or along it).
    let at = DVec2::new(32.0, 32.0);
    let horizon = footprint(&eye, (32, 31), DVec3::ZERO, DVec3::Y, &above, at);
    assert_eq!(horizon, Region::square(at, MAX_FOOTPRINT));
    // A plane behind the eye.
    let behind = footprint(
        &eye,
        (10, 10),
        DVec3::new(0.0, 0.0, 3.0),
        DVec3::Z,
        &above,
        at,
    );
    assert_eq!(behind, Region::square(at, MAX_FOOTPRINT));
    // A cell just under the horizon: hundreds of texels long, clipped to the cap
    // about the sample's own position along that axis only.
    let at = own(32.5, 33.5);
    let steep = footprint(&eye, (32, 33), DVec3::ZERO, DVec3::Y, &above, at);
    assert!((steep.size().y - MAX_FOOTPRINT).abs() < 1e-9, "{steep:?}");
    assert!(
        (steep.min.y - (at.y - 0.5 * MAX_FOOTPRINT)).abs() < 1e-9,
        "{steep:?}"
    );
    assert!(
        steep.size().x > 1.0 && steep.size().x < MAX_FOOTPRINT,
        "{steep:?}"
    );
    assert!(steep.min.x <= at.x && at.x <= steep.max.x, "{steep:?}");
}

/// A ground plane under a point light at (0, 6, 0), a strip at height 3 over
/// x ∈ [1, 2] casting a straight-edged shadow over x ∈ [2, 4], seen straight down
/// from (3, 10, 0) at 128 × 96, with `shadows` settings.
fn strip_scene(shadows: &[&str]) -> Scene {
    let text = support::camera_with(
        [3.0, 10.0, 0.0],
        [3.0, 0.0, 0.0],
        25.0,
        128,
        96,
        "up = [0.0, 0.0, -1.0]",
    ) + "[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\
                [[lights]]\ntype = \"point\"\nposition = [0.0, 6.0, 0.0]\nintensity = [10.0, 10.0, 10.0]\n\
                [[objects]]\nshape = \"quad\"\nname = \"ground\"\nmaterial = \"grey\"\ntransform = [{ scale = 12.0 }]\n\
                [[objects]]\nshape = \"quad\"\nname = \"strip\"\nmaterial = \"grey\"\n\
                transform = [{ scale = [1.0, 1.0, 12.0] }, { translate = [1.5, 3.0, 0.0] }]\n";
    let sets: Vec<String> = shadows.iter().map(|s| format!("shadows.{s}")).collect();
    support::scene_from_text(&text, &sets)
}

/// The light's visibility on the ground along x, averaged over the image's rows, at
/// each column: (x, mean).
fn ground_profile(scene: &Scene) -> Vec<(f64, f64)> {
    let (view, surface) = visible_surface(scene);
    let v = lumiere::shadow::compute(scene, &view, &surface, ShadowMethod::ShadowMap).unwrap();
    let ground = scene
        .objects
        .iter()
        .position(|o| o.name == "ground")
        .unwrap();
    (0..surface.width)
        .filter_map(|x| {
            let (mut sum, mut xs, mut n) = (0.0, 0.0, 0.0);
            for y in 0..surface.height {
                let k = (y * surface.width + x) as usize;
                let s = &surface.samples[k];
                if !s.is_empty() && scene.polygons[s.polygon as usize].object == ground {
                    sum += v.fraction(0, k) as f64;
                    xs += s.position.x;
                    n += 1.0;
                }
            }
            (n == surface.height as f64).then(|| (xs / n, sum / n))
        })
        .collect()
}

/// Where a falling profile crosses `level`, interpolated.
fn crossing(profile: &[(f64, f64)], level: f64) -> f64 {
    let w = profile
        .windows(2)
        .find(|w| w[0].1 >= level && w[1].1 < level)
        .expect("the profile crosses the level");
    let t = (w[0].1 - level) / (w[0].1 - w[1].1);
    w[0].0 + t * (w[1].0 - w[0].0)
}

/// (c) On a rendered plane: across the strip's straight shadow edge the profile
/// falls monotonically (within the noise left after averaging 96 rows), centred on
/// the edge, and as wide as the region projected on the ground: a pixel there is
/// 0.0462 units, its footprint about 2 texels of the 512-texel map, the region 6
/// footprints: 0.277 units, whose linear ramp is 0.8 × 0.277 = 0.222 wide between
/// 90% and 10% (measured 0.223).
#[test]
fn on_a_plane_the_edge_profile_is_as_wide_as_the_footprint_scaled() {
    let scene = strip_scene(&[
        "method=\"shadow-map\"",
        "map_resolution=512",
        "map_filter=\"percentage-closer\"",
        "pcf_samples=64",
        "pcf_scale=6.0",
    ]);
    let profile: Vec<(f64, f64)> = ground_profile(&scene)
        .into_iter()
        .filter(|(x, _)| (1.6..3.0).contains(x))
        .collect();
    assert!(profile.len() > 20, "{} columns", profile.len());
    for w in profile.windows(2) {
        assert!(
            w[1].1 <= w[0].1 + 0.02,
            "rises at x = {}: {profile:?}",
            w[1].0
        );
    }
    assert_eq!(profile[0].1, 1.0);
    assert_eq!(profile[profile.len() - 1].1, 0.0);
    let pixel = 2.0 * 10.0 * (12.5f64).to_radians().tan() / 96.0;
    let ramp = 0.8 * 6.0 * pixel;
    let (high, half, low) = (
        crossing(&profile, 0.9),
        crossing(&profile, 0.5),
        crossing(&profile, 0.1),
    );
    eprintln!(
        "90%–10% width {:.4} (expected {ramp:.4}), middle at {half:.4}",
        low - high
    );
    assert!(
        ((low - high) / ramp - 1.0).abs() < 0.05,
        "width {} against {ramp}",
        low - high
    );
    assert!((half - 2.0).abs() < 0.25 * pixel, "centred at {half}");
}

/// The curved scene's ground, each pixel's own footprint as the region (no
/// enlargement) on a 1024-texel map, against the share of the pixel that ray
/// casting finds lit on 8 × 8 subsamples: on the pixels a shadow edge crosses, the
/// RMS error is a quarter of Williams's single test's (measured 0.068 against 0.273
/// on 239 pixels).
#[test]
fn footprints_antialias_like_area_sampled_ray_casting() {
    let size = [
        "camera.width=128".to_string(),
        "camera.height=96".to_string(),
    ];
    let fine: Vec<String> = [&size[..], &["render.supersample=8".to_string()]].concat();
    let reference = load_scene("ray-cast-shadows-curved", &fine).unwrap();
    let (_, fine_surface) = visible_surface(&reference);
    let (fine_view, _) = visible_surface(&reference);
    let exact =
        lumiere::shadow::compute(&reference, &fine_view, &fine_surface, ShadowMethod::RayCast)
            .unwrap();
    let ground = reference
        .objects
        .iter()
        .position(|o| o.name == "ground")
        .unwrap();
    let on_ground = |s: &lumiere::raster::Sample| {
        !s.is_empty() && reference.polygons[s.polygon as usize].object == ground
    };
    let filtered = |filter: &str| {
        let mut sets = size.to_vec();
        sets.extend([
            "shadows.method=\"shadow-map\"".to_string(),
            "shadows.map_resolution=1024".to_string(),
            format!("shadows.map_filter=\"{filter}\""),
            "shadows.pcf_samples=64".to_string(),
        ]);
        let scene = load_scene("ray-cast-shadows-curved", &sets).unwrap();
        let (view, surface) = visible_surface(&scene);
        let v = lumiere::shadow::compute(&scene, &view, &surface, ShadowMethod::ShadowMap).unwrap();
        (0..surface.samples.len())
            .map(|k| v.fraction(0, k) as f64)
            .collect::<Vec<f64>>()
    };
    let (reeves, williams) = (filtered("percentage-closer"), filtered("none"));
    let (mut e_reeves, mut e_williams, mut n) = (0.0, 0.0, 0.0);
    for py in 0..96 {
        for px in 0..128 {
            let subsamples: Vec<usize> = (0..64)
                .map(|s| ((py * 8 + s / 8) * 1024 + px * 8 + s % 8) as usize)
                .collect();
            if !subsamples
                .iter()
                .all(|&k| on_ground(&fine_surface.samples[k]))
            {
                continue;
            }
            let share = subsamples
                .iter()
                .map(|&k| exact.fraction(0, k) as f64)
                .sum::<f64>()
                / 64.0;
            if share == 0.0 || share == 1.0 {
                continue;
            }
            let k = (py * 128 + px) as usize;
            e_reeves += (reeves[k] - share).powi(2);
            e_williams += (williams[k] - share).powi(2);
            n += 1.0;
        }
    }
    let (e_reeves, e_williams) = ((e_reeves / n).sqrt(), (e_williams / n).sqrt());
    eprintln!("{n} edge pixels: RMS {e_reeves:.4} percentage-closer, {e_williams:.4} Williams");
    assert!(n > 200.0, "{n} edge pixels");
    assert!(
        e_reeves < 0.08 && e_reeves < 0.4 * e_williams,
        "{e_reeves} against {e_williams}"
    );
}

/// `pcf = 5` alone still means the 5 × 5 box; the entries ask for what they say;
/// every new key's bad value is one line naming the key and the value.
#[test]
fn scene_keys() {
    let with = |sets: &[&str]| {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        load_scene("shadow-map-curved", &sets)
    };
    let s = with(&["shadows.pcf=5"]).unwrap().shadows;
    assert_eq!((s.map_filter, s.pcf), (MapFilter::Box, 5));
    assert_eq!(with(&[]).unwrap().shadows.map_filter, MapFilter::None);
    let box_entry = load_scene("shadow-map-box", &[]).unwrap().shadows;
    assert_eq!((box_entry.map_filter, box_entry.pcf), (MapFilter::Box, 5));
    let reeves = load_scene("shadow-map-pcf", &[]).unwrap().shadows;
    assert_eq!(reeves.map_filter, MapFilter::PercentageCloser);
    assert_eq!(
        reeves.percentage_closer,
        PercentageCloser {
            samples: 25,
            bias: [1.0, 2.0],
            scale: 1.0,
            min_size: 5.0
        }
    );
    for (set, message) in [
        (
            "shadows.pcf_samples=20",
            "shadows.pcf_samples must be a square number from 1 to 1024 (n x n jittered points), got 20",
        ),
        (
            "shadows.pcf_samples=0",
            "shadows.pcf_samples must be a square number from 1 to 1024 (n x n jittered points), got 0",
        ),
        (
            "shadows.pcf_bias=[2.0, 1.0]",
            "shadows.pcf_bias must be [min, max] with 0 <= min <= max (slope-scaled texels), got [2, 1]",
        ),
        (
            "shadows.pcf_bias=[-1.0, 1.0]",
            "shadows.pcf_bias must be [min, max] with 0 <= min <= max (slope-scaled texels), got [-1, 1]",
        ),
        (
            "shadows.pcf_scale=0.0",
            "shadows.pcf_scale must be a positive number up to 64, got 0",
        ),
        (
            "shadows.pcf_min_size=-1.0",
            "shadows.pcf_min_size must be between 0 and 64 texels, got -1",
        ),
        (
            "shadows.map_filter=\"gaussian\"",
            "unknown variant `gaussian`",
        ),
    ] {
        let line = support::error_line(&with(&[set]).unwrap_err());
        assert!(line.contains(message), "{set}: {line}");
        assert!(!line.contains('\n'), "{set}: {line}");
    }
}

/// Williams's post-pass: the shadow is applied to the finished image, each light's
/// contribution keeping a quarter where its map finds shadow (the documented
/// 25%, highlights included). On the point-lit shadow-map entry (one light, nothing
/// emitting in view of the shadowed floor), a sample the map calls shadowed is a
/// quarter of the unshadowed render's, a lit one all of it.
#[test]
fn the_post_pass_keeps_a_quarter_of_the_light_in_shadow() {
    let sets = |extra: &[&str]| -> Vec<String> {
        ["camera.width=64", "camera.height=48"]
            .iter()
            .chain(extra)
            .map(|s| s.to_string())
            .collect()
    };
    let load = |extra: &[&str]| load_scene("shadow-map", &sets(extra)).unwrap();
    let wanted = ["visibility-0".to_string()];
    let frame = lumiere::Renderer::new(load(&[]))
        .render_with_buffers(&wanted)
        .unwrap();
    let lumiere::BufferData::Values { data, channels } =
        &frame.buffer("visibility-0").unwrap().data
    else {
        panic!("values")
    };
    let post = lumiere::render(&load(&["shadows.post_pass=true"])).unwrap();
    let open = lumiere::render(&load(&["shadows.method=\"none\""])).unwrap();
    let (mut shadowed, mut lit) = (0, 0);
    for (k, (p, o)) in post.pixels.iter().zip(&open.pixels).enumerate() {
        let v = data[k * channels];
        let expected = if v == 0.0 {
            shadowed += 1;
            *o * 0.25
        } else if v == 1.0 {
            lit += 1;
            *o
        } else {
            continue;
        };
        assert!(
            (*p - expected).abs().max_element() <= 1e-6 * expected.max_element().max(1e-3),
            "sample {k}: {p} with the post-pass, {expected} expected"
        );
    }
    assert!(
        shadowed > 100 && lit > 100,
        "{shadowed} shadowed, {lit} lit"
    );
}

/// Williams's test reads the texel the point falls in: texel (i, j) covers
/// [i, i + 1] × [j, j + 1] of the map, so a point at (2.7, 1.2) reads texel (2, 1)
/// (not the nearest texel centre, (3, 1)); beyond the border, the border's.
#[test]
fn a_map_position_reads_the_texel_it_falls_in() {
    let depth = vec![0.0f32; 16];
    let image = DepthImage {
        size: 4,
        depth: &depth,
    };
    for (at, expected) in [
        ((2.7, 1.2), (2, 1)),
        ((0.0, 3.99), (0, 3)),
        ((3.5, 0.5), (3, 0)),
        ((-0.5, 4.5), (0, 3)),
    ] {
        assert_eq!(image.texel(DVec2::new(at.0, at.1)), expected, "at {at:?}");
    }
}

/// Each cube face is a 90° frustum on a resolution² grid: its axis lands on the
/// image's centre and its edges (45° off the axis) on the image's borders.
#[test]
fn each_cube_face_spans_its_image_exactly() {
    use lumiere::shadow::cube_faces::{FACES, face_view};
    let scene = load_scene("shadow-map", &[]).unwrap();
    let light = DVec3::new(0.3, 2.0, -0.4);
    for resolution in [16, 64, 512] {
        let half = resolution as f64 / 2.0;
        for &(axis, up) in &FACES {
            let view = face_view(&scene, light, (axis, up), resolution);
            let at = |d: DVec3| view.project(view.to_eye(light + d));
            let (x, y) = at(axis);
            assert!(
                (x - half).abs() < 1e-9 && (y - half).abs() < 1e-9,
                "axis {axis}"
            );
            for (d, edge) in [(up, 0.0), (-up, 2.0 * half)] {
                let (x, y) = at(axis + d);
                assert!(
                    (y - edge).abs() < 1e-9 && (x - half).abs() < 1e-9,
                    "{axis} {d}"
                );
            }
            let (x, _) = at(axis + axis.cross(up));
            assert!(
                ((x - half).abs() - half).abs() < 1e-9,
                "side of {axis}: {x}"
            );
        }
    }
}
