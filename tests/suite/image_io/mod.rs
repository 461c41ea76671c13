//! Images and their comparison (src/image_io): FLIP, the statistical test.

mod flip;
mod statistical_test;
