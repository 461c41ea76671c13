//! The scan-line visible-surface pass (Watkins 1970, Bouknight 1970).
//!
//! World polygons are taken into the eye frame, clipped to the view frustum by
//! Sutherland–Hodgman (`project`), projected to the screen, entered in an edge table
//! bucketed by first scan line (`edge_table`), and swept row by row with an active
//! edge list whose spans are resolved by depth at their ends (`watkins`). The result
//! is a `VisibleSurface` buffer: per sample the visible polygon and its interpolated
//! attributes, which every later pass reads.
//!
//! Conventions, once: the screen is `width × height` samples, x to the right, y down,
//! row 0 at the top; sample (i, j) sits at (i + 0.5, j + 0.5). An edge covers row j
//! when y_top ≤ j + 0.5 < y_bottom, and a span covers pixel i when
//! x_left ≤ i + 0.5 < x_right (the top-left rule), so polygons sharing an edge cover
//! every sample on it exactly once.

mod edge_table;
mod frame;
mod project;
mod scan_out;
mod view;
mod visibility;
mod visible_surface;
mod watkins;
pub mod zbuffer;

pub use edge_table::{EdgeTable, FIXED_ONE};
pub use frame::{sample_view, screen_polygons};
pub use project::{
    ATTRIBUTES, Attributes, DepthPlane, RasterVertex, ScreenPolygon, ScreenVertex, ToPrepare, UV,
    UvGradient, prepare,
};
pub use scan_out::{Piece, ScanRow, scan_out};
pub use view::View;
pub use visibility::{LightVisibility, LitIntervals, Visibility, VisiblePart};
pub use visible_surface::{NO_POLYGON, Sample, VisibleSurface};
pub use watkins::{
    covered_samples, covered_spans, rasterize, rasterize_depth, rasterize_ids, rasterize_rows,
    spans_inside, uv_gradients,
};
