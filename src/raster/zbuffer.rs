//! A brute-force z-buffer (Catmull 1974) over the same samples and fill rule: the
//! independent method the scan-line sweep is checked against. Every polygon tests
//! every sample of its bounding box by a crossing-number test along the sample's row
//! and keeps the nearest ζ; equal depths go to the polygon given first.

use super::ScreenPolygon;
use super::visible_surface::NO_POLYGON;

/// Per sample, the id of the nearest polygon (or `NO_POLYGON`).
pub fn visible_ids(polygons: &[ScreenPolygon], width: u32, height: u32) -> Vec<u32> {
    let mut ids = vec![NO_POLYGON; (width * height) as usize];
    let mut best = vec![f64::NEG_INFINITY; ids.len()];
    for polygon in polygons {
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for v in &polygon.vertices {
            (x0, x1, y0, y1) = (x0.min(v.x), x1.max(v.x), y0.min(v.y), y1.max(v.y));
        }
        let rows =
            (y0 - 0.5).ceil().max(0.0) as u32..((y1 - 0.5).ceil().max(0.0) as u32).min(height);
        for j in rows {
            for i in
                (x0 - 0.5).ceil().max(0.0) as u32..((x1 - 0.5).ceil().max(0.0) as u32).min(width)
            {
                let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
                if !covers(polygon, x, y) {
                    continue;
                }
                let k = (j * width + i) as usize;
                let zeta = polygon.plane.zeta(x, y);
                if zeta > best[k] {
                    best[k] = zeta;
                    ids[k] = polygon.id;
                }
            }
        }
    }
    ids
}

/// Whether (x, y) is covered: an odd number of edges cross the row at or left of x
/// (an edge crosses the row y when y_top ≤ y < y_bottom).
pub fn covers(polygon: &ScreenPolygon, x: f64, y: f64) -> bool {
    let n = polygon.vertices.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (&polygon.vertices[i], &polygon.vertices[(i + 1) % n]);
        let (top, bottom) = if a.y < b.y { (a, b) } else { (b, a) };
        if top.y <= y && y < bottom.y {
            let xe = top.x + (y - top.y) * (bottom.x - top.x) / (bottom.y - top.y);
            if xe <= x {
                inside = !inside;
            }
        }
    }
    inside
}
