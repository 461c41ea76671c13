//! Environment maps: the surroundings, assumed infinitely far away, stored as an
//! image indexed by direction (Blinn & Newell 1976; Greene 1986). Three layouts
//! behind one lookup: the latitude-longitude map (`lat_long`), the sphere map
//! (`sphere_map`) and the cube map (`cube_map`). A lookup takes a world direction and
//! its footprint, the offsets to the directions of the pixel's neighbours (the ray
//! differential, by finite differences); mip-mapped filters read the level whose
//! texels match the footprint, so that a small, distant mirror does not sparkle.
//!
//! Maps come from images (PNG sRGB, PFM/EXR linear), from six faces or a cross, from
//! a function of the direction (`sky`), or from a renderer (the caller's), and convert
//! between layouts by resampling with the same filtered lookups.

pub mod cube_map;
pub mod lat_long;
pub mod sky;
pub mod sphere_map;

use super::mip_map::Pyramid;
use super::texels::{Texels, Wrap};
use crate::settings::Filter;
use cube_map::CubeMap;
use glam::{DVec2, DVec3, Vec3};
use rayon::prelude::*;

/// How an environment map lays the sphere of directions out in its image(s).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Layout {
    /// One image, 2:1 usually, by the course's formula (`lat_long`).
    LatLong,
    /// One square image: a mirror ball seen from +z (`sphere_map`).
    Sphere,
    /// Six square faces (`cube_map`); as one image, the horizontal cross (4:3).
    Cube,
}

impl Layout {
    pub fn name(self) -> &'static str {
        match self {
            Layout::LatLong => "lat-long",
            Layout::Sphere => "sphere",
            Layout::Cube => "cube",
        }
    }
}

#[derive(Clone, Debug)]
enum Store {
    /// A latitude-longitude or sphere map: one image.
    Flat {
        layout: Layout,
        texels: Texels,
        pyramid: Option<Pyramid>,
    },
    Cube(CubeMap),
}

/// An environment map ready for lookups.
#[derive(Clone, Debug)]
pub struct EnvironmentMap {
    store: Store,
    pub filter: Filter,
}

/// What a filter other than nearest, bilinear, mip-nearest and trilinear gets.
pub const FILTERS: &str = "nearest, bilinear, mip-nearest or trilinear";

impl EnvironmentMap {
    /// A latitude-longitude or sphere map from its image. `filter` must be one of
    /// `FILTERS` (the caller checks).
    pub fn flat(layout: Layout, texels: Texels, filter: Filter) -> EnvironmentMap {
        assert!(layout != Layout::Cube, "a cube map has six faces");
        let pyramid = matches!(filter, Filter::MipNearest | Filter::Trilinear)
            .then(|| Pyramid::build(&texels));
        EnvironmentMap {
            store: Store::Flat {
                layout,
                texels,
                pyramid,
            },
            filter,
        }
    }

    /// A cube map from six square faces of one size, in `cube_map::FACE_NAMES` order.
    pub fn cube(faces: Vec<Texels>, filter: Filter) -> EnvironmentMap {
        EnvironmentMap {
            store: Store::Cube(CubeMap::new(faces)),
            filter,
        }
    }

    /// A cube map from a horizontal cross (4n × 3n, see `cube_map`); `Err` with what
    /// is wrong with the image's shape.
    pub fn from_cross(cross: &Texels, filter: Filter) -> Result<EnvironmentMap, String> {
        let (w, h) = (cross.width, cross.height);
        if w % 4 != 0 || h % 3 != 0 || w / 4 != h / 3 || w == 0 {
            return Err(format!(
                "a cross image must be 4:3 with square faces (4n × 3n), got {w}x{h}"
            ));
        }
        let n = w / 4;
        let faces = cube_map::CROSS_CELLS
            .iter()
            .map(|&(column, row)| {
                let mut texels = Vec::with_capacity((n * n) as usize);
                for j in 0..n {
                    let start = ((row * n + j) * w + column * n) as usize;
                    texels.extend_from_slice(&cross.texels[start..start + n as usize]);
                }
                Texels {
                    width: n,
                    height: n,
                    texels,
                }
            })
            .collect();
        Ok(EnvironmentMap::cube(faces, filter))
    }

    /// A map of `layout` from one image: a latitude-longitude map, a (square) sphere
    /// map or a cube map's horizontal cross; `Err` with what is wrong with its shape.
    pub fn from_image(
        layout: Layout,
        texels: Texels,
        filter: Filter,
    ) -> Result<EnvironmentMap, String> {
        match layout {
            Layout::Cube => EnvironmentMap::from_cross(&texels, filter),
            Layout::Sphere if texels.width != texels.height => Err(format!(
                "a sphere map must be square, got {}x{}",
                texels.width, texels.height
            )),
            Layout::LatLong | Layout::Sphere => Ok(EnvironmentMap::flat(layout, texels, filter)),
        }
    }

    /// A map of `layout` whose texels are `f` averaged over 2 × 2 points of each
    /// texel. `size`: the image's height (a latitude-longitude map is 2·size wide),
    /// the sphere map's side, or a cube face's side.
    pub fn generate(
        layout: Layout,
        size: u32,
        filter: Filter,
        f: impl Fn(DVec3) -> Vec3 + Sync,
    ) -> EnvironmentMap {
        EnvironmentMap::texel_by_texel(layout, size, filter, |face, (w, h), i, j| {
            let mut sum = Vec3::ZERO;
            for (a, b) in [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)] {
                let uv = DVec2::new((i as f64 + a) / w as f64, 1.0 - (j as f64 + b) / h as f64);
                sum += f(texel_direction(layout, face, uv));
            }
            sum / 4.0
        })
    }

    /// A map of `layout` at `size` (as `generate` takes it) whose texel (i, j) of
    /// face `face`, in an image of (w, h) texels, is `texel(face, (w, h), i, j)`.
    fn texel_by_texel(
        layout: Layout,
        size: u32,
        filter: Filter,
        texel: impl Fn(usize, (u32, u32), u32, u32) -> Vec3 + Sync,
    ) -> EnvironmentMap {
        let image = |face: usize, (w, h): (u32, u32)| Texels {
            width: w,
            height: h,
            texels: (0..w * h)
                .into_par_iter()
                .map(|k| texel(face, (w, h), k % w, k / w))
                .collect(),
        };
        match layout {
            Layout::LatLong => EnvironmentMap::flat(layout, image(0, (2 * size, size)), filter),
            Layout::Sphere => EnvironmentMap::flat(layout, image(0, (size, size)), filter),
            Layout::Cube => {
                EnvironmentMap::cube((0..6).map(|f| image(f, (size, size))).collect(), filter)
            }
        }
    }

    pub fn layout(&self) -> Layout {
        match &self.store {
            Store::Flat { layout, .. } => *layout,
            Store::Cube(_) => Layout::Cube,
        }
    }

    /// Its size as `generate` takes it (height, side, or face side).
    pub fn size(&self) -> u32 {
        match &self.store {
            Store::Flat { texels, .. } => texels.height,
            Store::Cube(cube) => cube.size(),
        }
    }

    /// The filtered radiance in the unit direction `d`, for a lookup whose footprint
    /// reaches `d + footprint[0]` and `d + footprint[1]`.
    pub fn lookup(&self, d: DVec3, footprint: [DVec3; 2]) -> Vec3 {
        debug_assert!((d.length_squared() - 1.0).abs() < 1e-6, "a unit direction");
        match &self.store {
            Store::Cube(cube) => cube.filtered(d, footprint, self.filter),
            Store::Flat {
                layout,
                texels,
                pyramid,
            } => {
                let wrap = flat_wrap(*layout);
                let uv = flat_uv(*layout, d);
                match (self.filter, pyramid) {
                    (Filter::Nearest, _) => {
                        let t = texels.texel_space(uv);
                        texels.at_wrapped(t.x.floor() as i64, t.y.floor() as i64, wrap)
                    }
                    (Filter::MipNearest | Filter::Trilinear, Some(p)) => {
                        let steps = footprint.map(|o| flat_uv_step(*layout, d, o));
                        let lambda = p.level(steps);
                        if self.filter == Filter::Trilinear {
                            p.trilinear_wrapped(uv, lambda, wrap)
                        } else {
                            let k = (lambda.round() as usize).min(p.levels.len() - 1);
                            p.levels[k].bilinear_wrapped(uv, wrap)
                        }
                    }
                    (Filter::Bilinear | Filter::SummedArea, _)
                    | (Filter::MipNearest | Filter::Trilinear, None) => {
                        texels.bilinear_wrapped(uv, wrap)
                    }
                }
            }
        }
    }

    /// The mip-map level λ a lookup at unit `d` reads (`None` for filters without
    /// levels).
    pub fn level(&self, d: DVec3, footprint: [DVec3; 2]) -> Option<f64> {
        if !matches!(self.filter, Filter::MipNearest | Filter::Trilinear) {
            return None;
        }
        match &self.store {
            Store::Cube(cube) => Some(cube.level(d, footprint)),
            Store::Flat {
                layout, pyramid, ..
            } => pyramid
                .as_ref()
                .map(|p| p.level(footprint.map(|o| flat_uv_step(*layout, d, o)))),
        }
    }

    /// The same surroundings in `layout` at `size`: each texel the filtered lookup of
    /// its direction, with the texel's own footprint.
    pub fn convert(&self, layout: Layout, size: u32) -> EnvironmentMap {
        EnvironmentMap::texel_by_texel(layout, size, self.filter, |face, (w, h), i, j| {
            let at = |x: f64, y: f64| {
                texel_direction(layout, face, DVec2::new(x / w as f64, 1.0 - y / h as f64))
            };
            let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
            let d = at(x, y);
            self.lookup(d, [at(x + 1.0, y) - d, at(x, y + 1.0) - d])
        })
    }

    /// The map as one image: the latitude-longitude or sphere image, or the cube's
    /// horizontal cross (the two empty rows' unused cells black).
    pub fn to_texels(&self) -> Texels {
        match &self.store {
            Store::Flat { texels, .. } => texels.clone(),
            Store::Cube(cube) => {
                let n = cube.size();
                let (w, h) = (4 * n, 3 * n);
                let mut texels = vec![Vec3::ZERO; (w * h) as usize];
                for (face, &(column, row)) in cube_map::CROSS_CELLS.iter().enumerate() {
                    let f = &cube.faces[face];
                    for j in 0..n {
                        let start = ((row * n + j) * w + column * n) as usize;
                        let from = (j * n) as usize;
                        texels[start..start + n as usize]
                            .copy_from_slice(&f.texels[from..from + n as usize]);
                    }
                }
                Texels {
                    width: w,
                    height: h,
                    texels,
                }
            }
        }
    }
}

/// The direction at (u, v) of face `face` (0 for the one-image layouts).
pub fn texel_direction(layout: Layout, face: usize, uv: DVec2) -> DVec3 {
    match layout {
        Layout::LatLong => lat_long::direction(uv),
        Layout::Sphere => sphere_map::direction(uv),
        Layout::Cube => cube_map::direction(face, uv),
    }
}

/// The (face, u, v) where a layout stores direction `d`.
pub fn coordinates(layout: Layout, d: DVec3) -> (usize, DVec2) {
    match layout {
        Layout::LatLong => (0, lat_long::uv(d)),
        Layout::Sphere => (0, sphere_map::uv(d)),
        Layout::Cube => cube_map::face_uv(d),
    }
}

fn flat_uv(layout: Layout, d: DVec3) -> DVec2 {
    coordinates(layout, d).1
}

fn flat_uv_step(layout: Layout, d: DVec3, offset: DVec3) -> DVec2 {
    match layout {
        Layout::LatLong => lat_long::uv_step(d, offset),
        Layout::Sphere | Layout::Cube => sphere_map::uv_step(d, offset),
    }
}

/// Longitude repeats; everything else clamps.
fn flat_wrap(layout: Layout) -> [Wrap; 2] {
    match layout {
        Layout::LatLong => [Wrap::Repeat, Wrap::Clamp],
        Layout::Sphere | Layout::Cube => [Wrap::Clamp, Wrap::Clamp],
    }
}
