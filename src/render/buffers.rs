//! A frame's named buffers (`--aov`): what the methods computed on the way to the
//! image, for teaching and debugging. Per-sample buffers come at the sample grid's
//! size (the image's times the supersampling), assembled band by band; the others
//! (shadow-map faces, hemi-cube item buffers) at their own size.

use super::integrators::{CACHE_RECORDS, ScanLine, declares_buffer};
use super::output::BufferInfo;
use super::plan::FramePlan;
use crate::error::{Error, Result};
use crate::image_io::{Buffer, BufferData};
use crate::raster::{Visibility, VisibleSurface};
use crate::scene::{Light, Scene};
use crate::settings::MediumMethod;
use crate::shading::FrameShading;
use crate::shadow::{self, CountBuffer};

/// A per-sample buffer.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Polygon,
    Element,
    Depth,
    Position,
    Normal,
    Uv,
    Visibility(usize),
    /// The count its shadow method declares (`shadow::Method::counts`).
    Counts(usize, CountBuffer),
    MipLevel,
    EnvironmentLevel,
    Radiosity,
    /// The lit intervals of each viewing ray for a light (light volumes).
    LitIntervals(usize),
    /// The medium's in-scattered radiance alone.
    Inscattered,
}

impl Kind {
    fn name(self) -> String {
        match self {
            Kind::Polygon => "polygon".into(),
            Kind::Element => "element".into(),
            Kind::Depth => "depth".into(),
            Kind::Position => "position".into(),
            Kind::Normal => "normal".into(),
            Kind::Uv => "uv".into(),
            Kind::Visibility(l) => format!("visibility-{l}"),
            Kind::Counts(l, counts) => counts.name(l),
            Kind::MipLevel => "mip-level".into(),
            Kind::EnvironmentLevel => "environment-level".into(),
            Kind::Radiosity => "radiosity".into(),
            Kind::LitIntervals(l) => format!("lit-intervals-{l}"),
            Kind::Inscattered => "inscattered".into(),
        }
    }

    fn description(self) -> String {
        match self {
            Kind::Polygon => "id of the visible polygon per sample (colour-mapped)".into(),
            Kind::Element => {
                "id of the visible radiosity element per sample (colour-mapped)".into()
            }
            Kind::Depth => "eye distance along the view axis per sample (linear)".into(),
            Kind::Position => "world position of the visible point (linear RGB = xyz)".into(),
            Kind::Normal => "interpolated shading normal (linear RGB = xyz)".into(),
            Kind::Uv => "texture coordinates (linear R = u, G = v)".into(),
            Kind::Visibility(l) => {
                format!("light {l}'s visibility: 1 lit, 0 shadowed, between partly lit")
            }
            Kind::Counts(l, counts) => counts.describe(l),
            Kind::MipLevel => {
                "mip-map level λ read per sample for its diffuse texture (-1: none)".into()
            }
            Kind::EnvironmentLevel => {
                "mip-map level λ of the environment read in the mirror direction (-1: none)".into()
            }
            Kind::Radiosity => "radiosity B of the visible element (linear, flat)".into(),
            Kind::LitIntervals(l) => format!(
                "lit intervals of each viewing ray for light {l}, between its shadow volumes (Max's light volumes; colour-mapped)"
            ),
            Kind::Inscattered => {
                "light the medium scatters towards the eye along each viewing ray (linear RGB)"
                    .into()
            }
        }
    }

    fn channels(self) -> usize {
        match self {
            Kind::Position | Kind::Normal | Kind::Uv | Kind::Radiosity | Kind::Inscattered => 3,
            Kind::Polygon
            | Kind::Element
            | Kind::Depth
            | Kind::Visibility(_)
            | Kind::Counts(..)
            | Kind::MipLevel
            | Kind::EnvironmentLevel
            | Kind::LitIntervals(_) => 1,
        }
    }
}

/// Every buffer a scan-line frame of `scene` by `plan` can give, with the
/// per-sample kinds first.
fn catalogue(scene: &Scene, plan: &FramePlan) -> (Vec<Kind>, Vec<Buffer>) {
    let mut kinds = vec![
        Kind::Polygon,
        Kind::Depth,
        Kind::Position,
        Kind::Normal,
        Kind::Uv,
    ];
    for (kind, name) in [(Kind::Element, "element"), (Kind::Radiosity, "radiosity")] {
        if declares_buffer(plan.declared, name) {
            kinds.push(kind);
        }
    }
    if scene
        .textures
        .iter()
        .any(|t| t.mip_level([Default::default(); 2]).is_some())
    {
        kinds.push(Kind::MipLevel);
    }
    if scene.materials.iter().any(|m| m.environment.is_some()) {
        kinds.push(Kind::EnvironmentLevel);
    }
    let mut fixed = Vec::new();
    let counts = shadow::method(scene.shadows.method).counts;
    for (l, s) in plan.shadows.iter().enumerate() {
        let Some(s) = s else { continue };
        kinds.push(Kind::Visibility(l));
        if let Some(counts) = counts {
            kinds.push(Kind::Counts(l, counts));
        }
        fixed.extend(s.buffers(&format!("shadow-map-{l}")));
    }
    if let Some(medium) = scene.medium.as_ref().filter(|m| m.extinction > 0.0) {
        kinds.push(Kind::Inscattered);
        if medium.method == MediumMethod::LightVolumes {
            for (l, light) in scene.lights.iter().enumerate() {
                let volumes = matches!(light, Light::Point(_) | Light::Spot(_) | Light::Distant(_));
                if plan.direct[l] && volumes {
                    kinds.push(Kind::LitIntervals(l));
                }
            }
        }
    }
    fixed.extend(plan.integrator.buffers(scene, plan.hemicube_element));
    (kinds, fixed)
}

/// What a fixed buffer is, for `--aov list`.
fn fixed_description(name: &str) -> String {
    if let Some(rest) = name.strip_prefix("shadow-map-") {
        format!("shadow-map depth image of light and cube face {rest} (linear)")
    } else if name == CACHE_RECORDS {
        "the irradiance cache's records: where Ward's gathers were made, per pixel (colour-mapped)"
            .into()
    } else if let Some(face) = name.strip_prefix("hemicube-") {
        format!("hemi-cube item buffer, {face} face, at the chosen element (patch ids)")
    } else {
        String::new()
    }
}

/// The buffers a scan-line frame of `scene` by `plan` can give.
pub(super) fn available(scene: &Scene, plan: &FramePlan) -> Vec<BufferInfo> {
    let (kinds, fixed) = catalogue(scene, plan);
    kinds
        .into_iter()
        .map(|k| BufferInfo {
            name: k.name(),
            description: k.description(),
        })
        .chain(fixed.iter().map(|b| BufferInfo {
            name: b.name.clone(),
            description: fixed_description(&b.name),
        }))
        .collect()
}

/// What the medium made on one band: the in-scattered radiance per sample and each
/// light's lit intervals (empty without a medium).
#[derive(Default)]
pub(super) struct MediumBand {
    pub inscattered: Vec<glam::Vec3>,
    pub lit: Vec<Option<crate::raster::LitIntervals>>,
}

/// The buffers one frame is asked for, filled band by band.
pub(super) struct FrameBuffers {
    width: u32,
    height: u32,
    columns: Vec<(Kind, Column)>,
    fixed: Vec<Buffer>,
}

/// A per-sample buffer's data as the bands add it: each kind fills the vector of
/// its type, which `finish` hands over (so that no kind can meet the wrong data).
#[derive(Default)]
struct Column {
    ids: Vec<u32>,
    counts: Vec<i32>,
    values: Vec<f32>,
}

impl FrameBuffers {
    /// Refuses a name the frame cannot give, naming those it can.
    pub fn new(scene: &Scene, plan: &FramePlan, wanted: &[String]) -> Result<FrameBuffers> {
        let n = scene.render.supersample;
        let mut frame = FrameBuffers {
            width: scene.camera.width * n,
            height: scene.camera.height * n,
            columns: Vec::new(),
            fixed: Vec::new(),
        };
        if wanted.is_empty() {
            return Ok(frame);
        }
        let (kinds, fixed) = catalogue(scene, plan);
        for name in wanted {
            if let Some(&kind) = kinds.iter().find(|k| &k.name() == name) {
                frame.columns.push((kind, Column::default()));
            } else if let Some(b) = fixed.iter().find(|b| &b.name == name) {
                frame.fixed.push(b.clone());
            } else {
                return Err(Error::UnknownBuffer {
                    name: name.clone(),
                    known: kinds
                        .iter()
                        .map(|k| k.name())
                        .chain(fixed.iter().map(|b| b.name.clone()))
                        .collect(),
                });
            }
        }
        Ok(frame)
    }

    /// Appends one band's rows.
    pub fn add_band(
        &mut self,
        band: &VisibleSurface,
        visibility: &Visibility,
        counts: &[Option<Vec<i32>>],
        medium: &MediumBand,
        integrator: &dyn ScanLine,
        shading: &FrameShading,
    ) {
        let scene = shading.scene();
        let samples = || band.samples.iter().enumerate();
        let n = band.samples.len();
        for (kind, column) in &mut self.columns {
            let Column {
                ids,
                counts: counted,
                values,
            } = column;
            match *kind {
                Kind::Polygon => ids.extend(band.samples.iter().map(|s| s.polygon)),
                Kind::Element => ids.extend(band.samples.iter().map(|s| s.element)),
                Kind::Counts(l, _) => match &counts[l] {
                    Some(found) => counted.extend(found),
                    None => counted.extend(std::iter::repeat_n(0, n)),
                },
                Kind::LitIntervals(l) => match medium.lit.get(l).and_then(Option::as_ref) {
                    Some(lit) => counted.extend((0..lit.len()).map(|k| lit.of(k).len() as i32)),
                    None => counted.extend(std::iter::repeat_n(0, n)),
                },
                Kind::Depth => values.extend(
                    band.samples
                        .iter()
                        .map(|s| if s.is_empty() { 0.0 } else { s.depth as f32 }),
                ),
                Kind::Position => values.extend(
                    band.samples
                        .iter()
                        .flat_map(|s| s.position.as_vec3().to_array()),
                ),
                Kind::Normal => {
                    values.extend(band.samples.iter().flat_map(|s| s.normal.to_array()))
                }
                Kind::Uv => values.extend(
                    band.samples
                        .iter()
                        .flat_map(|s| [s.uv.x as f32, s.uv.y as f32, 0.0]),
                ),
                Kind::Visibility(l) => values.extend(samples().map(|(k, s)| {
                    if s.is_empty() {
                        0.0
                    } else {
                        visibility.fraction(l, k)
                    }
                })),
                Kind::MipLevel => values.extend((0..n).map(|k| mip_level(scene, band, k))),
                Kind::EnvironmentLevel => values.extend((0..n).map(|k| {
                    shading
                        .environment_level(band, k)
                        .map_or(-1.0, |l| l as f32)
                })),
                Kind::Inscattered => values.extend((0..n).flat_map(|k| {
                    medium
                        .inscattered
                        .get(k)
                        .copied()
                        .unwrap_or_default()
                        .to_array()
                })),
                Kind::Radiosity => values.extend(band.samples.iter().flat_map(|s| {
                    match s.is_empty() {
                        true => [0.0; 3],
                        false => integrator
                            .element_radiosity(s.element)
                            .unwrap_or_default()
                            .to_array(),
                    }
                })),
            }
        }
    }

    pub fn finish(self) -> Vec<Buffer> {
        let (width, height) = (self.width, self.height);
        self.columns
            .into_iter()
            .map(|(kind, column)| Buffer {
                name: kind.name(),
                width,
                height,
                data: match kind {
                    Kind::Polygon | Kind::Element => BufferData::Ids(column.ids),
                    Kind::Counts(..) | Kind::LitIntervals(_) => BufferData::Counts(column.counts),
                    Kind::Depth
                    | Kind::Position
                    | Kind::Normal
                    | Kind::Uv
                    | Kind::Visibility(_)
                    | Kind::MipLevel
                    | Kind::EnvironmentLevel
                    | Kind::Radiosity
                    | Kind::Inscattered => BufferData::Values {
                        channels: kind.channels(),
                        data: column.values,
                    },
                },
            })
            .chain(self.fixed)
            .collect()
    }
}

/// λ read at sample `k` for its material's diffuse texture, −1 where none.
fn mip_level(scene: &Scene, band: &VisibleSurface, k: usize) -> f32 {
    let s = &band.samples[k];
    if s.is_empty() {
        return -1.0;
    }
    let material = scene.material_of(s.polygon as usize);
    material
        .diffuse_texture
        .and_then(|t| scene.textures[t].mip_level(band.uv_derivatives(k)))
        .map_or(-1.0, |l| l as f32)
}
