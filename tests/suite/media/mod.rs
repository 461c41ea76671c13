//! Participating media (src/media): light volumes.

mod light_volumes;
