//! From world polygons to screen polygons: into the eye frame, clipped to the view
//! frustum (Sutherland–Hodgman, in eye space, before the perspective divide), then
//! projected. Each screen polygon carries its depth plane (Watkins' polygon table).

use super::View;
use crate::geometry::sutherland_hodgman::{Lerp, clip};
use crate::scene::Vertex;
use glam::{DVec2, DVec3, Vec3};

/// Number of interpolated attributes: world position (3), shading normal (3),
/// texture coordinates (2), vertex colour (3).
pub const ATTRIBUTES: usize = 11;
pub type Attributes = [f64; ATTRIBUTES];

/// A vertex in the eye frame with the attributes to interpolate.
#[derive(Clone, Copy, Debug)]
pub struct RasterVertex {
    pub eye: DVec3,
    pub attributes: Attributes,
}

impl RasterVertex {
    pub fn new(view: &View, v: &Vertex, color: Vec3) -> RasterVertex {
        let (p, n) = (v.position, v.normal);
        RasterVertex {
            eye: view.to_eye(p),
            attributes: [
                p.x,
                p.y,
                p.z,
                n.x,
                n.y,
                n.z,
                v.uv.x,
                v.uv.y,
                color.x as f64,
                color.y as f64,
                color.z as f64,
            ],
        }
    }
}

impl Lerp for RasterVertex {
    fn lerp(&self, other: &Self, t: f64) -> Self {
        let mut attributes = self.attributes;
        for (a, b) in attributes.iter_mut().zip(other.attributes) {
            *a += (b - *a) * t;
        }
        RasterVertex {
            eye: self.eye + (other.eye - self.eye) * t,
            attributes,
        }
    }
}

/// A projected vertex: screen position, ζ = 1/z (z the eye distance) and the
/// attributes divided by z, all of which vary linearly across the screen image of a
/// planar polygon (what makes perspective-correct interpolation exact).
#[derive(Clone, Copy, Debug)]
pub struct ScreenVertex {
    pub x: f64,
    pub y: f64,
    pub zeta: f64,
    pub attributes_over_z: Attributes,
}

/// ζ = 1/z as an affine function of the screen position: the polygon's plane in
/// screen space. Nearer means larger ζ. (Any z_s = A + B/z of a projection matrix
/// orders and interpolates the same way; ζ needs no far plane.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthPlane {
    pub a: f64,
    pub b: f64,
    pub c: f64,
}

impl DepthPlane {
    /// `through`, or the zero plane for a polygon seen edge-on.
    pub fn fit(vertices: &[ScreenVertex], value: impl Fn(&ScreenVertex) -> f64) -> DepthPlane {
        DepthPlane::through(vertices, value).unwrap_or(DepthPlane {
            a: 0.0,
            b: 0.0,
            c: 0.0,
        })
    }

    pub fn zeta(&self, x: f64, y: f64) -> f64 {
        self.a * x + self.b * y + self.c
    }

    /// Newell's plane through screen points (x, y, value): the affine function of
    /// the screen position a planar polygon's value follows; `None` when the polygon
    /// is seen edge-on (no screen area).
    pub fn through(
        vertices: &[ScreenVertex],
        value: impl Fn(&ScreenVertex) -> f64,
    ) -> Option<DepthPlane> {
        let points: Vec<DVec3> = vertices
            .iter()
            .map(|v| DVec3::new(v.x, v.y, value(v)))
            .collect();
        let n = crate::geometry::polygon::newell_normal(&points);
        if n.z == 0.0 || !n.z.is_finite() {
            return None;
        }
        let centre = points.iter().copied().sum::<DVec3>() / points.len() as f64;
        let (a, b) = (-n.x / n.z, -n.y / n.z);
        Some(DepthPlane {
            a,
            b,
            c: centre.z - a * centre.x - b * centre.y,
        })
    }
}

/// Index of u among the attributes (v follows).
pub const UV: usize = 6;

/// How a polygon's texture coordinates vary across the screen, for the footprint of
/// a sample in the texture (mip-map level selection): their exact screen derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvGradient {
    /// ζ = 1/z, and u and v as the scan-line pass steps them: u/z and v/z
    /// (perspective-correct), or u and v themselves (affine).
    pub zeta: DepthPlane,
    pub u: DepthPlane,
    pub v: DepthPlane,
    pub affine: bool,
}

impl UvGradient {
    /// [∂(u, v)/∂x, ∂(u, v)/∂y] at screen point (x, y) where the coordinates are `uv`.
    /// Perspective: u = (u/z) / ζ, so ∂u/∂x = (∂(u/z)/∂x − u ∂ζ/∂x) / ζ.
    pub fn derivatives(&self, x: f64, y: f64, uv: DVec2) -> [DVec2; 2] {
        let (u, v) = (&self.u, &self.v);
        if self.affine {
            return [DVec2::new(u.a, v.a), DVec2::new(u.b, v.b)];
        }
        let zeta = self.zeta.zeta(x, y);
        let z = &self.zeta;
        [
            DVec2::new(u.a - uv.x * z.a, v.a - uv.y * z.a) / zeta,
            DVec2::new(u.b - uv.x * z.b, v.b - uv.y * z.b) / zeta,
        ]
    }
}

/// A polygon ready for the scan-line pass. `id` is what the visible-surface buffer
/// records (the scene polygon id).
#[derive(Clone, Debug)]
pub struct ScreenPolygon {
    pub id: u32,
    /// The drawn piece's id (the polygon's own, or a radiosity element's).
    pub element: u32,
    pub vertices: Vec<ScreenVertex>,
    pub plane: DepthPlane,
    /// Texture coordinates are stepped affinely in screen space (not divided by z).
    pub affine_uv: bool,
}

impl ScreenPolygon {
    /// The screen polygon of bare world points (no attributes to interpolate): shadow
    /// polygons, detail polygons.
    pub fn from_points(view: &View, id: u32, points: &[DVec3]) -> Option<ScreenPolygon> {
        let vertices = points
            .iter()
            .map(|&position| {
                let v = Vertex {
                    position,
                    normal: DVec3::Z,
                    uv: Default::default(),
                };
                RasterVertex::new(view, &v, Vec3::ZERO)
            })
            .collect();
        ScreenPolygon::new(view, id, vertices)
    }

    /// Clips an eye-space polygon to the view frustum and projects it; `None` when
    /// nothing of it is in view or it is seen edge-on.
    pub fn new(view: &View, id: u32, vertices: Vec<RasterVertex>) -> Option<ScreenPolygon> {
        let mut polygon = vertices;
        for plane in view.frustum() {
            polygon = clip(&polygon, |v| plane.truncate().dot(v.eye) + plane.w);
            if polygon.len() < 3 {
                return None;
            }
        }
        let vertices: Vec<ScreenVertex> = polygon
            .iter()
            .map(|v| {
                let (x, y) = view.project(v.eye);
                let zeta = 1.0 / v.eye.z;
                ScreenVertex {
                    x,
                    y,
                    zeta,
                    attributes_over_z: v.attributes.map(|a| a * zeta),
                }
            })
            .collect();
        let plane = DepthPlane::through(&vertices, |v| v.zeta)?;
        Some(ScreenPolygon {
            id,
            element: id,
            vertices,
            plane,
            affine_uv: false,
        })
    }

    /// The same polygon with its texture coordinates interpolated affinely in screen
    /// space (stepped as u, v rather than u/z, v/z): the course's warping demonstration.
    pub fn with_affine_uv(mut self) -> ScreenPolygon {
        for v in &mut self.vertices {
            v.attributes_over_z[UV] /= v.zeta;
            v.attributes_over_z[UV + 1] /= v.zeta;
        }
        self.affine_uv = true;
        self
    }

    /// The texture coordinates' screen gradient (planar polygon: exact).
    pub fn uv_gradient(&self) -> UvGradient {
        let fit = |k: usize| DepthPlane::fit(&self.vertices, |v| v.attributes_over_z[k]);
        UvGradient {
            zeta: self.plane,
            u: fit(UV),
            v: fit(UV + 1),
            affine: self.affine_uv,
        }
    }
}

/// A world polygon to prepare: its id, vertices, vertex colours (may be empty) and
/// whether its texture coordinates are interpolated affinely.
pub struct ToPrepare<'a> {
    pub id: u32,
    /// The piece's own id (`id` unless the polygon is drawn in pieces).
    pub element: u32,
    pub vertices: &'a [Vertex],
    pub colors: &'a [Vec3],
    pub affine_uv: bool,
}

/// Screen polygons of world polygons.
pub fn prepare<'a>(
    view: &View,
    polygons: impl Iterator<Item = ToPrepare<'a>>,
) -> Vec<ScreenPolygon> {
    polygons
        .filter_map(|p| {
            let ToPrepare {
                id,
                element,
                vertices,
                colors,
                affine_uv,
            } = p;
            let eye = vertices
                .iter()
                .enumerate()
                .map(|(k, v)| {
                    RasterVertex::new(view, v, colors.get(k).copied().unwrap_or_default())
                })
                .collect();
            let mut screen = ScreenPolygon::new(view, id, eye)?;
            screen.element = element;
            Some(if affine_uv {
                screen.with_affine_uv()
            } else {
                screen
            })
        })
        .collect()
}
