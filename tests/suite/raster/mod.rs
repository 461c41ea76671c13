//! The rasterizer (src/raster): fill rule, clipping, depth, sample patterns.

mod properties;
mod sample_pattern;
