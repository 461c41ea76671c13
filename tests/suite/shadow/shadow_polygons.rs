//! Atherton, Weiler & Greenberg's shadow polygons against ray casting, point by point
//! on every polygon, in the cases Weiler & Atherton's hidden-surface recursion exists
//! for: a preliminary depth sort that is wrong, interpenetrating polygons and cyclic
//! overlap; and on random triangles, interpenetrating or not.

use crate::support;

use glam::{DVec2, DVec3};
use lumiere::Scene;
use lumiere::scene::ray_queries::segment_meets_polygon;
use lumiere::shadow::shadow_polygon_areas::receiver_shadows;
use lumiere::shadow::shadow_polygons::{DetailPolygon, lit_polygons};
use proptest::prelude::*;
use support::scene_from_text;

/// A scene of the given polygons, each its own object, and one point light.
fn scene_of(polygons: &[Vec<DVec3>], light: DVec3) -> Scene {
    let mut text = format!(
        "{}[materials.grey]\ndiffuse = [0.5, 0.5, 0.5]\n\
         [[lights]]\ntype = \"point\"\nposition = [{}, {}, {}]\nintensity = [1.0, 1.0, 1.0]\n",
        support::camera([0.0, 20.0, 0.5], [0.0, 0.0, 0.0], 40.0, 16, 16),
        light.x,
        light.y,
        light.z
    );
    for (i, p) in polygons.iter().enumerate() {
        let vertices: Vec<String> = p
            .iter()
            .map(|v| format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z))
            .collect();
        text += &format!(
            "[[objects]]\nshape = \"polygon\"\nname = \"p{i}\"\nmaterial = \"grey\"\nvertices = [{}]\n",
            vertices.join(", ")
        );
    }
    scene_from_text(&text, &[])
}

/// Whether `p`, on the plane of polygon `normal`, lies inside the detail polygons
/// (even-odd over all their contours, seen along the normal's largest axis).
fn inside_details(details: &[DetailPolygon], normal: DVec3, p: DVec3) -> bool {
    let a = normal.abs();
    let flat = |q: DVec3| {
        if a.x >= a.y && a.x >= a.z {
            DVec2::new(q.y, q.z)
        } else if a.y >= a.z {
            DVec2::new(q.z, q.x)
        } else {
            DVec2::new(q.x, q.y)
        }
    };
    let q = flat(p);
    let mut inside = false;
    for (contour, _) in details.iter().flat_map(|d| &d.contours) {
        for (i, a) in contour.iter().enumerate() {
            let (a, b) = (flat(*a), flat(contour[(i + 1) % contour.len()]));
            if (a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) * (b.x - a.x) / (b.y - a.y) {
                inside = !inside;
            }
        }
    }
    inside
}

/// Points on a grid over each polygon's fan triangles (offsets that fall on no
/// outline), as (polygon, point).
fn grid(scene: &Scene, n: usize) -> Vec<(usize, DVec3)> {
    let mut points = Vec::new();
    for (id, polygon) in scene.polygons.iter().enumerate() {
        let v: Vec<DVec3> = polygon.positions().collect();
        for k in 1..v.len() - 1 {
            let (a, b, c) = (v[0], v[k], v[k + 1]);
            for i in 0..n {
                for j in 0..n {
                    let (s, t) = ((i as f64 + 0.373) / n as f64, (j as f64 + 0.619) / n as f64);
                    if s + t < 1.0 {
                        points.push((id, a + s * (b - a) + t * (c - a)));
                    }
                }
            }
        }
    }
    points
}

/// The grid points whose polygon the shadow polygons call lit where ray casting
/// finds another polygon on the way to the light, or the other way round.
fn disagreements(scene: &Scene, light: DVec3, n: usize) -> (usize, Vec<(usize, DVec3)>) {
    let lit = lit_polygons(scene, light);
    let points = grid(scene, n);
    let wrong = points
        .iter()
        .filter(|&&(id, p)| {
            let by_details = inside_details(&lit[id], scene.polygons[id].normal, p);
            let by_rays = !scene
                .polygons
                .iter()
                .enumerate()
                .any(|(other, q)| other != id && segment_meets_polygon(p, light, q));
            by_details != by_rays
        })
        .copied()
        .collect();
    (points.len(), wrong)
}

fn assert_agree(polygons: &[Vec<DVec3>], light: DVec3) -> Scene {
    let scene = scene_of(polygons, light);
    let (checked, wrong) = disagreements(&scene, light, 40);
    assert!(checked > 1000);
    assert!(
        wrong.is_empty(),
        "{} of {checked} points disagree with ray casting, first {:?}",
        wrong.len(),
        &wrong[..wrong.len().min(4)]
    );
    scene
}

fn quad(corners: [[f64; 3]; 4]) -> Vec<DVec3> {
    corners.iter().map(|&c| DVec3::from_array(c)).collect()
}

/// A large tilted quad reaches nearer the light (at 0.5) than a small quad above
/// its middle (at 2), so the preliminary sort puts it first although the small one
/// hides part of it: the small quad's piece becomes the clip polygon of a window
/// within the large quad's.
#[test]
fn a_wrong_preliminary_sort_is_corrected_by_the_recursion() {
    let light = DVec3::new(0.0, 5.0, 0.0);
    let tilted = |x: f64, z: f64| [x, 2.25 + 0.375 * (x + z), z];
    let big = quad([
        tilted(-3.0, -3.0),
        tilted(-3.0, 3.0),
        tilted(3.0, 3.0),
        tilted(3.0, -3.0),
    ]);
    let small = quad([
        [-1.0, 3.0, -1.0],
        [-1.0, 3.0, 0.0],
        [0.0, 3.0, 0.0],
        [0.0, 3.0, -1.0],
    ]);
    let scene = assert_agree(&[big, small], light);
    // The small quad is wholly lit; the big one loses the small one's shadow.
    let receivers = receiver_shadows(&scene, light);
    assert!((receivers[1].lit_area - 1.0).abs() < 1e-9);
    assert!(receivers[0].shadowed_area > 1.0);
}

/// Two quads crossing along x = 0, a plane through the light: each is lit on its
/// upper half and nowhere else, 2·√1.04 of its area, as the two halves of the
/// light's view are separated by that plane.
#[test]
fn interpenetrating_quads_are_split_where_their_depths_cross() {
    let light = DVec3::new(0.0, 10.0, 0.0);
    let rising = quad([
        [-1.0, 0.8, -1.0],
        [-1.0, 0.8, 1.0],
        [1.0, 1.2, 1.0],
        [1.0, 1.2, -1.0],
    ]);
    let falling = quad([
        [-1.0, 1.2, -1.0],
        [-1.0, 1.2, 1.0],
        [1.0, 0.8, 1.0],
        [1.0, 0.8, -1.0],
    ]);
    let scene = assert_agree(&[rising, falling], light);
    let half = 2.0 * 1.04f64.sqrt();
    for r in receiver_shadows(&scene, light) {
        assert!(
            (r.lit_area - half).abs() < 1e-6 * half,
            "{}: lit {} (expected {half})",
            r.object,
            r.lit_area
        );
    }
}

/// Three sticks, each lying over the next and under the one before (no two of
/// them interpenetrate): no depth order of the three exists, and no list sorted
/// once could be drawn in order; the windows within windows resolve each overlap
/// in its own window.
#[test]
fn cyclic_overlap_of_three_sticks() {
    let light = DVec3::new(0.1, 30.0, 0.2);
    let stick = |angle: f64| {
        // A stick along direction `angle`, rising from y = 1 to y = 2 along its
        // length, its centre line passing at 0.8 from the origin.
        let (d, n) = (
            DVec3::new(angle.cos(), 0.0, angle.sin()),
            DVec3::new(-angle.sin(), 0.0, angle.cos()),
        );
        let (c, w) = (n * 0.8, 0.25);
        let at = |s: f64, t: f64| {
            let p = c + d * s + n * t;
            p + DVec3::Y * (1.5 + 0.5 * s / 2.5)
        };
        vec![at(-2.5, -w), at(-2.5, w), at(2.5, w), at(2.5, -w)]
    };
    let sticks: Vec<Vec<DVec3>> = (0..3)
        .map(|k| stick(k as f64 * std::f64::consts::TAU / 3.0))
        .collect();
    let ground = quad([
        [-6.0, 0.0, -6.0],
        [-6.0, 0.0, 6.0],
        [6.0, 0.0, 6.0],
        [6.0, 0.0, -6.0],
    ]);
    let mut all = sticks;
    all.push(ground);
    let scene = assert_agree(&all, light);
    // Each stick is shadowed somewhere by the one above it: a cycle.
    let receivers = receiver_shadows(&scene, light);
    for r in &receivers[..3] {
        assert!(r.shadowed_area > 0.01, "{}: {}", r.object, r.shadowed_area);
    }
}

fn triangle() -> impl Strategy<Value = Vec<DVec3>> {
    prop::collection::vec((-2.0..2.0f64, 0.2..3.0f64, -2.0..2.0f64), 3).prop_filter_map(
        "a triangle with area",
        |v| {
            let p: Vec<DVec3> = v.iter().map(|&(x, y, z)| DVec3::new(x, y, z)).collect();
            ((p[1] - p[0]).cross(p[2] - p[0]).length() > 0.05).then_some(p)
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// Random triangles over a ground, free to interpenetrate, under a light inside
    /// their box or above it: the shadow polygons agree with ray casting at every
    /// grid point.
    #[test]
    fn random_triangles_agree_with_ray_casting(
        triangles in prop::collection::vec(triangle(), 2..7),
        light in (-1.0..1.0f64, 2.0..6.0f64, -1.0..1.0f64),
    ) {
        let light = DVec3::new(light.0, light.1, light.2);
        let mut polygons = triangles;
        polygons.push(quad([
            [-4.0, 0.0, -4.0],
            [-4.0, 0.0, 4.0],
            [4.0, 0.0, 4.0],
            [4.0, 0.0, -4.0],
        ]));
        let scene = scene_of(&polygons, light);
        let (checked, wrong) = disagreements(&scene, light, 24);
        prop_assert!(
            wrong.is_empty(),
            "{} of {checked} points disagree, first {:?}",
            wrong.len(),
            &wrong[..wrong.len().min(4)]
        );
    }
}

/// Random triangles over the ground of the random search, under `light`, agree
/// with ray casting.
fn found_by_random_search(triangles: &[[[f64; 3]; 3]], light: [f64; 3]) {
    let mut polygons: Vec<Vec<DVec3>> = triangles
        .iter()
        .map(|t| t.iter().map(|&c| DVec3::from_array(c)).collect())
        .collect();
    polygons.push(quad([
        [-4.0, 0.0, -4.0],
        [-4.0, 0.0, 4.0],
        [4.0, 0.0, 4.0],
        [4.0, 0.0, -4.0],
    ]));
    assert_agree(&polygons, DVec3::from_array(light));
}

/// A case random triangles found (the first, second and fourth triangles suffice):
/// a piece cut where its depth crosses another's is concave, and cutting it with
/// Sutherland–Hodgman joined its two parts by edges running both ways along the
/// cut, on which the next window's clipping went wrong and a part of the second
/// triangle came out visible twice.
#[test]
fn a_concave_piece_cut_where_depths_cross() {
    found_by_random_search(
        &[
            [
                [-1.513051368472026, 0.5086467897861822, 0.39914240314212107],
                [0.0, 2.354808536971918, 1.4813554603822268],
                [-0.47085459881840847, 2.176709226241322, 0.0],
            ],
            [
                [-0.8465547161092521, 2.158196854875791, 0.0],
                [0.4599006753169106, 2.0999856784691913, -0.11526721499598816],
                [-0.5939134025728026, 0.2, 1.4482158651457293],
            ],
            [
                [1.5540227880129014, 1.930400348464727, 1.8910177361623943],
                [-1.83501560731577, 1.6674900989569568, 0.07274052247878804],
                [0.7379205718226431, 1.5373417304150552, -1.1031419341021014],
            ],
            [
                [1.7186192990831675, 1.121935353742644, -0.31034868092997725],
                [-0.9938587545298203, 2.4560988998890165, 0.33905073521301127],
                [0.0, 0.7433920083855485, -1.8714697846445745],
            ],
            [
                [0.0, 0.2, 0.0],
                [0.0, 0.2, 1.035429056637656],
                [0.0, 0.30152795960855244, 0.0],
            ],
        ],
        [-0.9422921034886366, 4.22477735019112, 0.3102367389974278],
    );
}

/// A second case random triangles found: a piece cut by an earlier clip runs out
/// and back along one of its own edges (a bridge of width 5e-9), on which the
/// next clip finds every crossing twice.
#[test]
fn four_triangles_in_a_cycle() {
    found_by_random_search(
        &[
            [
                [-0.4009116103392408, 0.3032167578948333, -0.7161044961827134],
                [-0.5626707131626856, 1.9516753907681308, 1.948433942984488],
                [
                    -0.8640501064402839,
                    2.3336728504243713,
                    -0.20044577197790103,
                ],
            ],
            [
                [1.4029901072135926, 1.1749373435933044, -1.7763489612938137],
                [-1.5251978558355055, 1.558936179472465, 1.7409529874722096],
                [0.23517570491257442, 2.107224871259576, 1.1700330180054046],
            ],
            [
                [-0.34674404172844353, 2.82809646038046, 0.42441485133349843],
                [-1.1516272908314946, 0.9715188322910085, 1.8395135430948129],
                [0.8353115910704498, 1.9263408504970927, -0.8437630994770351],
            ],
            [
                [
                    0.6696189887258612,
                    1.6498667374600018,
                    -0.005110064203854625,
                ],
                [-1.7487134848665935, 2.1579328174908574, 0.3256376165037934],
                [1.8365440207305475, 1.3437106883975312, 0.45592287983292296],
            ],
        ],
        [-0.9428270605316551, 5.893139428914944, 0.06590101142989761],
    );
}

/// A third case random triangles found, still wrong: a hole of the ground's lit
/// piece comes out of one clip touching its outer contour at a corner, a hair
/// outside it, and the clip of that piece by a triangle whose piece has the same
/// hole fails under every perturbation. About one random scene in 6,000 meets a
/// case like it (5 of 30,000, against 49 before bridges were cut).
#[test]
#[ignore = "a known defect of the clipper's robustness, kept to be fixed"]
fn six_triangles_over_the_ground() {
    found_by_random_search(
        &[
            [
                [-0.37939325218128434, 0.2, 1.269480347071485],
                [1.7667223440628186, 1.9583511327823275, 1.8750708034031434],
                [1.2016718059469058, 0.2, -1.7866499132968037],
            ],
            [
                [0.5644142148655428, 1.7302261236035046, -1.6927170097585624],
                [-1.7043305564421116, 2.5359607434238987, 1.1105120519834606],
                [
                    -0.0516091773490698,
                    1.4286767125713458,
                    -0.19086619330089052,
                ],
            ],
            [
                [-1.1251342603224361, 1.6261423041954122, 1.827085506172871],
                [1.8077569735941874, 2.740155065502405, -1.5407214794284168],
                [0.05391447938454753, 1.4130123617661279, -0.3664855561576339],
            ],
            [
                [-0.5253337232102673, 2.1000184234864614, 0.22952631743088725],
                [-0.6531854008590876, 0.9208254860359957, -0.5434371186975352],
                [1.3201274807431653, 1.4835973310306882, 0.7568658799909819],
            ],
            [
                [1.458367749524214, 2.2601764902317996, 1.698881253723271],
                [-1.497781171420865, 1.1310615744625352, 1.2800360186219388],
                [
                    -0.7347408994147357,
                    0.7365844059946886,
                    -0.48012462782668214,
                ],
            ],
            [
                [
                    -0.0398464604805752,
                    2.7668697940477194,
                    0.004439096015993039,
                ],
                [-1.5689171632817083, 0.7402255148544856, 1.8467264029936092],
                [-0.6354656895656113, 1.9891439551918983, 0.387464837416587],
            ],
        ],
        [0.6185926341042418, 4.147801669065433, -0.9951991637251243],
    );
}

/// A fourth case random triangles found: pieces whose vertex count grew with
/// every clip, then a part visible twice.
#[test]
fn five_triangles_whose_pieces_grew() {
    found_by_random_search(
        &[
            [
                [1.2620402949540082, 0.2, 1.719655656403123],
                [0.83981820891099, 2.018963141044506, -1.849450822229323],
                [-1.751016755272439, 0.2, 0.2684367856579623],
            ],
            [
                [0.0, 2.416375228500924, 0.0],
                [-0.08655898621551711, 0.884222284616297, 0.6638280158541114],
                [1.4355888284907607, 1.5233526627724658, -1.531502379544015],
            ],
            [
                [-1.601255423017515, 2.8282806463614967, 1.938337212470945],
                [0.641224194802904, 2.3237779416685878, -1.2029829626357962],
                [0.6828386472742971, 0.33627734623427114, -0.9986705429992734],
            ],
            [
                [-0.8118824924253196, 0.308291721938904, -0.575641433387399],
                [1.9179107817970449, 2.601362849010911, -0.3269484081395984],
                [1.904828928014152, 0.5618716463607617, 1.0640294503829544],
            ],
            [
                [1.4683489901169704, 2.6995270094222947, 1.225581269216145],
                [1.1568713722926742, 1.4362203771545965, -0.39490621949334165],
                [-1.74159610881451, 1.3164042387616475, 0.21821510191931642],
            ],
        ],
        [0.9644930989467639, 3.1979853792207398, 0.3080493516747084],
    );
}

/// A light's view crowded with 900 polygons is cut into windows before the removal
/// (a face with more than 256 pieces is quartered, pieces crossing a seam clipped to
/// each side): the shadows still agree with ray casting at every grid point, on the
/// ground and on the triangles, which shade one another across the seams.
#[test]
fn a_crowded_light_view_cut_into_windows() {
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut polygons = vec![quad([
        [-3.0, 0.0, -3.0],
        [-3.0, 0.0, 3.0],
        [3.0, 0.0, 3.0],
        [3.0, 0.0, -3.0],
    ])];
    for k in 0..900 {
        // Level triangles, each at its own height, so none interpenetrate.
        let height = 0.5 + 1.5 * k as f64 / 900.0;
        let centre = DVec3::new(5.0 * next() - 2.5, height, 5.0 * next() - 2.5);
        let size = 0.1 + 0.25 * next();
        let turn = std::f64::consts::TAU * next();
        polygons.push(
            (0..3)
                .map(|i| {
                    let a = turn - std::f64::consts::TAU * i as f64 / 3.0;
                    centre + size * DVec3::new(a.cos(), 0.0, a.sin())
                })
                .collect(),
        );
    }
    let light = DVec3::new(0.3, 6.0, 0.2);
    let scene = scene_of(&polygons, light);
    let (checked, wrong) = disagreements(&scene, light, 8);
    assert!(checked > 20_000, "{checked} points");
    assert!(
        wrong.is_empty(),
        "{} of {checked} points disagree with ray casting, first {:?}",
        wrong.len(),
        &wrong[..wrong.len().min(4)]
    );
}
