//! The frame (src/render): bands, threads, kept work, buffers, silent results.

mod frame;
mod silent_results;
