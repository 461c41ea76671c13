//! Textures: images and procedural patterns, how they are put on surfaces (two-part
//! mappings, interpolation of texture coordinates), how they are filtered (mip-maps,
//! summed-area tables) and how they wrinkle normals (bump maps).
//!
//! A `Texture` holds texels (decoded from a file, or a procedural pattern sampled at
//! a resolution) and whatever its filter needs, built once at load. Colour lookups
//! take the texture coordinates and their screen derivatives (the pixel's footprint);
//! heights for bump mapping come from the procedural function analytically when there
//! is one, else from the texels by central differences.

pub mod bump;
pub mod environment;
pub mod mapping;
pub mod mip_map;
pub mod procedural;
pub mod summed_area;
pub mod texels;

pub use crate::settings::Filter;
use glam::{DVec2, Vec3};
use mip_map::Pyramid;
use procedural::{Procedural, luminance};
use summed_area::SummedAreaTable;
pub use texels::{Texels, Wrap};

/// How texture coordinates are found inside a polygon (the course's two cases).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Interpolation {
    /// Projection function known: the mapping applied to each sample's surface point.
    /// Without a mapping (the mesh's own coordinates) this is `perspective`, which is
    /// then the exact inverse of the per-polygon parameterisation.
    Exact,
    /// Stored at the vertices, stepped linearly along edges and spans in screen space
    /// (like Gouraud): correct only for polygons parallel to the image plane.
    Affine,
    /// Stored at the vertices; u/z, v/z and 1/z stepped linearly, divided per sample
    /// (Heckbert 1989).
    #[default]
    Perspective,
}

pub struct Texture {
    pub name: String,
    pub texels: Texels,
    pub procedural: Option<Procedural>,
    pub wrap: Wrap,
    pub filter: Filter,
    pyramid: Option<Pyramid>,
    sat: Option<SummedAreaTable>,
}

impl std::fmt::Debug for Texture {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "Texture({}, {}x{}, {:?}, {:?})",
            self.name, self.texels.width, self.texels.height, self.wrap, self.filter
        )
    }
}

impl Texture {
    /// A texture whose pre-filtered forms (pyramid, summed-area table) are built now if
    /// its filter uses them.
    /// The bytes a `width` x `height` texture keeps under `filter`: its linear texels
    /// (12 bytes each) and the mip-map pyramid (its level 0 resampled to the next
    /// powers of two, then a third more: 16 bytes a texel of that level 0) or the
    /// summed-area table (three f64 sums, 24 bytes a texel).
    pub fn bytes_kept(width: u32, height: u32, filter: Filter) -> u64 {
        let texels = u64::from(width) * u64::from(height);
        let table = match filter {
            Filter::MipNearest | Filter::Trilinear => {
                u64::from(width.next_power_of_two()) * u64::from(height.next_power_of_two()) * 16
            }
            Filter::SummedArea => texels * 24,
            Filter::Nearest | Filter::Bilinear => 0,
        };
        texels * 12 + table
    }

    pub fn new(
        name: &str,
        texels: Texels,
        procedural: Option<Procedural>,
        wrap: Wrap,
        filter: Filter,
    ) -> Texture {
        let pyramid = matches!(filter, Filter::MipNearest | Filter::Trilinear)
            .then(|| Pyramid::build(&texels));
        let sat = (filter == Filter::SummedArea).then(|| SummedAreaTable::build(&texels));
        Texture {
            name: name.to_string(),
            texels,
            procedural,
            wrap,
            filter,
            pyramid,
            sat,
        }
    }

    /// The filtered colour at `uv`, for a sample whose footprint has the screen
    /// derivatives `derivatives` = [∂(u, v)/∂x, ∂(u, v)/∂y].
    /// The mip-map level λ its filter reads for a footprint (`None` for filters
    /// without a pyramid).
    pub fn mip_level(&self, derivatives: [DVec2; 2]) -> Option<f64> {
        self.pyramid.as_ref().map(|p| p.level(derivatives))
    }

    pub fn color(&self, uv: DVec2, derivatives: [DVec2; 2]) -> Vec3 {
        let wrap = self.wrap;
        match (self.filter, &self.pyramid, &self.sat) {
            (Filter::Nearest, ..) => self.texels.nearest(uv, wrap),
            (Filter::Bilinear, ..) => self.texels.bilinear(uv, wrap),
            (Filter::MipNearest, Some(p), _) => p.nearest_level(uv, p.level(derivatives), wrap),
            (Filter::Trilinear, Some(p), _) => p.trilinear(uv, p.level(derivatives), wrap),
            (Filter::SummedArea, _, Some(s)) => s.filter(uv, derivatives, wrap),
            (Filter::MipNearest | Filter::Trilinear, None, _) | (Filter::SummedArea, _, None) => {
                unreachable!("Texture::new builds what the filter needs")
            }
        }
    }

    /// The texture read as a height in [0, 1] (luminance) and its gradient in (u, v):
    /// analytic for a procedural pattern, else central differences of one texel step
    /// on the bilinearly interpolated texels.
    pub fn height(&self, uv: DVec2) -> (f64, DVec2) {
        if let Some(p) = &self.procedural {
            return p.height(uv);
        }
        let f = |uv: DVec2| luminance(self.texels.bilinear(uv, self.wrap));
        let step = DVec2::new(
            1.0 / self.texels.width as f64,
            1.0 / self.texels.height as f64,
        );
        let (du, dv) = (DVec2::new(step.x, 0.0), DVec2::new(0.0, step.y));
        let gradient = DVec2::new(
            (f(uv + du) - f(uv - du)) / (2.0 * step.x),
            (f(uv + dv) - f(uv - dv)) / (2.0 * step.y),
        );
        (f(uv), gradient)
    }
}
