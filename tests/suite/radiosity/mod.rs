//! Radiosity (src/radiosity): form factors, solutions, subdivision, light kinds.

mod light_sources;
mod solutions;
mod subdivision;
