//! Loading what users write (src/load.rs): fuzzed input.

mod fuzz;
