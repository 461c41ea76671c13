//! The geometric core (src/geometry): degenerate input.

mod degenerate;
