//! Textures (src/texture): mapping, filtering, environment and reflection mapping.

mod environment;
mod mapping;
mod reflection_mapping;
