//! The frame (src/render): bands, threads, kept work, buffers, silent results.

mod frame;
mod integrators;
mod silent_results;
