//! The gallery's pages: per topic of the course, one scene rendered through every
//! method of the topic (each measured against the topic's reference method), the
//! intermediate buffers worth showing, and the plots.

use lumiere::catalogue::Topic;

/// One image of a topic's side-by-side comparison: a catalogue scene with some keys
/// changed, demonstrating the method of the entry `cites`.
pub struct Variant {
    pub label: &'static str,
    pub scene: &'static str,
    pub sets: &'static [&'static str],
    pub cites: &'static str,
}

/// The plots, each drawn on the page of its topic.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plot {
    SoftShadowConvergence,
    ShadowMapResolution,
    MipFilterError,
    FormFactorError,
    RadiosityResidual,
}

/// The live viewer a topic page opens: a catalogue scene with some keys changed,
/// and the methods of its first family to offer (all when empty).
pub struct Live {
    pub scene: &'static str,
    pub sets: &'static [&'static str],
    pub methods: &'static [&'static str],
}

pub struct Page {
    pub topic: Topic,
    /// The scene and methods the page's live viewer opens on.
    pub live: Live,
    /// What the page shows, in a paragraph.
    pub intro: &'static str,
    /// The side-by-side images; the first is the reference the others are measured
    /// against.
    pub variants: &'static [Variant],
    pub plots: &'static [Plot],
}

impl Page {
    /// Whether the buffer `name` explains this topic's methods (the geometric
    /// buffers every frame makes are shown only where they are the subject).
    pub fn shows_buffer(&self, name: &str) -> bool {
        let geometric = ["polygon", "depth", "position", "normal", "uv"];
        match self.topic {
            Topic::VisibleSurfaces => ["polygon", "depth", "normal"].contains(&name),
            Topic::Texture => name == "uv" || !geometric.contains(&name),
            _ => !geometric.contains(&name),
        }
    }
}

const fn variant(
    label: &'static str,
    scene: &'static str,
    sets: &'static [&'static str],
    cites: &'static str,
) -> Variant {
    Variant {
        label,
        scene,
        sets,
        cites,
    }
}

pub const PAGES: [Page; 8] = [
    Page {
        topic: Topic::VisibleSurfaces,
        live: Live {
            scene: "shading-modes",
            sets: &[],
            methods: &[],
        },
        intro: "The scan-line pass finds, for every sample, the polygon in front (Watkins 1970): \
                its id, depth and normal are the buffers below. Shading then evaluates the light \
                once per polygon (flat), at the vertices (Gouraud) or at every sample with an \
                interpolated normal (Phong). The curved scene without shadows, measured against \
                Phong shading.",
        variants: &[
            variant(
                "Phong shading",
                "ray-cast-shadows-curved",
                &["shadows.method=\"none\"", "render.shading=\"phong\""],
                "shading-modes",
            ),
            variant(
                "Gouraud shading",
                "ray-cast-shadows-curved",
                &["shadows.method=\"none\"", "render.shading=\"gouraud\""],
                "shading-modes",
            ),
            variant(
                "flat shading",
                "ray-cast-shadows-curved",
                &["shadows.method=\"none\"", "render.shading=\"flat\""],
                "shading-modes",
            ),
        ],
        plots: &[],
    },
    Page {
        topic: Topic::HardShadows,
        live: Live {
            scene: "cornell-box-point",
            sets: &["shadows.method=\"shadow-volumes\""],
            methods: &[
                "ray-cast",
                "scanline",
                "shadow-polygons",
                "shadow-volumes",
                "stencil-shadow-volumes",
                "shadow-map",
                "none",
            ],
        },
        intro: "The point-lit Cornell box through every hard-shadow method. The exact ones \
                (scan-line shadows, shadow polygons, shadow volumes and their stencil form) agree \
                with ray casting sample for sample, which the test suite proves; the shadow map \
                samples the light's view and differs along the edges, by its resolution.",
        variants: &[
            variant(
                "ray casting",
                "cornell-box-point",
                &["shadows.method=\"ray-cast\""],
                "ray-cast-shadows",
            ),
            variant(
                "scan-line shadows",
                "cornell-box-point",
                &["shadows.method=\"scanline\""],
                "scanline-shadows",
            ),
            variant(
                "shadow polygons",
                "cornell-box-point",
                &["shadows.method=\"shadow-polygons\""],
                "shadow-polygons",
            ),
            variant(
                "shadow volumes",
                "cornell-box-point",
                &["shadows.method=\"shadow-volumes\""],
                "shadow-volumes",
            ),
            variant(
                "stencil shadow volumes",
                "cornell-box-point",
                &["shadows.method=\"stencil-shadow-volumes\""],
                "stencil-shadow-volumes",
            ),
            variant(
                "shadow map",
                "cornell-box-point",
                &["shadows.method=\"shadow-map\""],
                "shadow-map",
            ),
            variant(
                "no shadows",
                "cornell-box-point",
                &["shadows.method=\"none\""],
                "cornell-box-point",
            ),
        ],
        plots: &[Plot::ShadowMapResolution],
    },
    Page {
        topic: Topic::SoftShadows,
        live: Live {
            scene: "cornell-box",
            sets: &["shadows.method=\"umbra-penumbra\""],
            methods: &["umbra-penumbra", "soft-shadow-volumes", "ray-cast", "none"],
        },
        intro: "The Cornell box under its quad light. Nishita & Nakamae's umbra and penumbra \
                polygons give the exact visible part of the light, the reference; Brotman & \
                Badler's soft shadow volumes and stratified ray casting sample the light and \
                converge to it, as the plot shows.",
        variants: &[
            variant(
                "umbra and penumbra (exact)",
                "cornell-box",
                &["shadows.method=\"umbra-penumbra\""],
                "umbra-penumbra",
            ),
            variant(
                "soft shadow volumes, 16 points",
                "cornell-box",
                &[
                    "shadows.method=\"soft-shadow-volumes\"",
                    "shadows.light_points=16",
                ],
                "soft-shadow-volumes",
            ),
            variant(
                "ray casting, 4 × 4 samples",
                "cornell-box",
                &["shadows.method=\"ray-cast\"", "shadows.light_samples=4"],
                "cornell-box-ray-cast-soft",
            ),
            variant(
                "no shadows",
                "cornell-box",
                &["shadows.method=\"none\""],
                "cornell-box",
            ),
        ],
        plots: &[Plot::SoftShadowConvergence],
    },
    Page {
        topic: Topic::LightVolumes,
        live: Live {
            scene: "light-volumes-cornell",
            sets: &[],
            methods: &[],
        },
        intro: "A scattering medium in the point-lit Cornell box. Max's light volumes cut each \
                viewing ray into lit and dark intervals at the shadow volumes' polygons and \
                integrate single scattering over the lit ones; ray marching, a shadow ray at \
                every step, is the reference.",
        variants: &[
            variant(
                "ray marching",
                "light-volumes-cornell",
                &["medium.method=\"ray-marching\""],
                "light-volumes-cornell",
            ),
            variant(
                "light volumes",
                "light-volumes-cornell",
                &["medium.method=\"light-volumes\""],
                "light-volumes-cornell",
            ),
        ],
        plots: &[],
    },
    Page {
        topic: Topic::Texture,
        live: Live {
            scene: "mip-mapping",
            sets: &[],
            methods: &[],
        },
        intro: "A checkerboard plane running to the horizon, through every texture filter, \
                measured against point sampling at 16 × 16 samples per pixel. Point sampling \
                aliases into moiré; the mip-map (Williams 1983) and the summed-area table (Crow \
                1984) average the footprint, and over-blur where it is long and thin.",
        variants: &[
            variant(
                "point sampling, 16 × 16 per pixel",
                "mip-mapping",
                &[
                    "textures.point.filter=\"nearest\"",
                    "textures.trilinear.filter=\"nearest\"",
                    "render.supersample=16",
                ],
                "mip-mapping",
            ),
            variant(
                "nearest",
                "mip-mapping",
                &[
                    "textures.point.filter=\"nearest\"",
                    "textures.trilinear.filter=\"nearest\"",
                ],
                "mip-mapping",
            ),
            variant(
                "bilinear",
                "mip-mapping",
                &[
                    "textures.point.filter=\"bilinear\"",
                    "textures.trilinear.filter=\"bilinear\"",
                ],
                "mip-mapping",
            ),
            variant(
                "mip-map, nearest level",
                "mip-mapping",
                &[
                    "textures.point.filter=\"mip-nearest\"",
                    "textures.trilinear.filter=\"mip-nearest\"",
                ],
                "mip-mapping",
            ),
            variant(
                "mip-map, trilinear",
                "mip-mapping",
                &[
                    "textures.point.filter=\"trilinear\"",
                    "textures.trilinear.filter=\"trilinear\"",
                ],
                "mip-mapping",
            ),
            variant(
                "summed-area table",
                "mip-mapping",
                &[
                    "textures.point.filter=\"summed-area\"",
                    "textures.trilinear.filter=\"summed-area\"",
                ],
                "mip-mapping",
            ),
        ],
        plots: &[Plot::MipFilterError],
    },
    Page {
        topic: Topic::EnvironmentMapping,
        live: Live {
            scene: "reflection-mapping",
            sets: &[],
            methods: &[],
        },
        intro: "Forty small chrome balls reflecting a cube-mapped sky, through each filter of \
                the environment lookup, measured against point sampling at 16 × 16 samples per \
                pixel: the mip level follows the footprint of the reflected direction between \
                neighbouring samples.",
        variants: &[
            variant(
                "point sampling, 16 × 16 per pixel",
                "reflection-mapping-filtering",
                &[
                    "environments.sky-nearest.filter=\"nearest\"",
                    "environments.sky-trilinear.filter=\"nearest\"",
                    "render.supersample=16",
                ],
                "reflection-mapping-filtering",
            ),
            variant(
                "nearest",
                "reflection-mapping-filtering",
                &[
                    "environments.sky-nearest.filter=\"nearest\"",
                    "environments.sky-trilinear.filter=\"nearest\"",
                ],
                "reflection-mapping-filtering",
            ),
            variant(
                "bilinear",
                "reflection-mapping-filtering",
                &[
                    "environments.sky-nearest.filter=\"bilinear\"",
                    "environments.sky-trilinear.filter=\"bilinear\"",
                ],
                "reflection-mapping-filtering",
            ),
            variant(
                "trilinear",
                "reflection-mapping-filtering",
                &[
                    "environments.sky-nearest.filter=\"trilinear\"",
                    "environments.sky-trilinear.filter=\"trilinear\"",
                ],
                "reflection-mapping-filtering",
            ),
        ],
        plots: &[],
    },
    Page {
        topic: Topic::Radiosity,
        live: Live {
            scene: "radiosity-shooting",
            sets: &[],
            methods: &[],
        },
        intro: "The Cornell box lit by radiosity alone: the full system gathered by Gauss–Seidel \
                with form factors from Lambert's point-to-polygon formula (the reference: exact \
                where nothing lies between, its occlusion sampled at five points of the patch), \
                the hemi-cube and the Nusselt analog, and progressive shooting to 1% unshot power. \
                The hemi-cube's item buffers are shown for element 0.",
        variants: &[
            variant(
                "gathering, analytic form factors",
                "radiosity-gathering",
                &["radiosity.form_factors=\"analytic\""],
                "radiosity-gathering",
            ),
            variant(
                "gathering, hemi-cube",
                "radiosity-gathering",
                &["radiosity.form_factors=\"hemicube\""],
                "radiosity-gathering",
            ),
            variant(
                "gathering, Nusselt analog",
                "radiosity-gathering",
                &["radiosity.form_factors=\"nusselt\""],
                "radiosity-gathering",
            ),
            variant(
                "progressive shooting, hemi-cube",
                "radiosity-gathering",
                &["radiosity.solver=\"shooting\"", "radiosity.unshot=0.01"],
                "radiosity-shooting",
            ),
        ],
        plots: &[Plot::FormFactorError, Plot::RadiosityResidual],
    },
    Page {
        topic: Topic::GlobalIllumination,
        live: Live {
            scene: "ray-tracing-cornell",
            sets: &[],
            methods: &[],
        },
        intro: "Wallace, Cohen & Greenberg's two-pass method on the Cornell box with mirrors, one \
                transfer mechanism at a time, measured against all of them together.",
        variants: &[
            variant("every mechanism", "two-pass", &[], "two-pass"),
            variant(
                "diffuse to diffuse",
                "two-pass-diffuse-diffuse",
                &[],
                "two-pass-diffuse-diffuse",
            ),
            variant(
                "specular to diffuse",
                "two-pass-specular-diffuse",
                &[],
                "two-pass-specular-diffuse",
            ),
            variant(
                "diffuse to specular",
                "two-pass-diffuse-specular",
                &[],
                "two-pass-diffuse-specular",
            ),
        ],
        plots: &[],
    },
];

pub fn page(topic: Topic) -> &'static Page {
    PAGES
        .iter()
        .find(|p| p.topic == topic)
        .expect("every topic has a page")
}
