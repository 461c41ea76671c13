//! What Atherton, Weiler & Greenberg's shadow polygons measure: for every receiving
//! polygon, its lit detail polygons and its shadowed remainder (the polygon less the
//! lit ones, by Weiler–Atherton clipping in its own plane), with their areas in scene
//! units. A polygon the light sees from either side counts as lit there.

use super::shadow_polygons::{DetailPolygon, lit_polygons};
use crate::geometry::plane::PlaneFrame;
use crate::geometry::weiler_atherton::{self, Region, contour_area};
use crate::scene::{Polygon, Scene};
use glam::DVec3;

/// The lit and shadowed parts of one polygon. Regions are lists of contours in
/// object space; outer contours run counter-clockwise seen from the polygon's front,
/// holes clockwise.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ReceiverShadows {
    /// The polygon's index in the scene's polygons.
    pub polygon: usize,
    /// The name of its object.
    pub object: String,
    /// Unit normal of the polygon's front.
    pub normal: [f64; 3],
    /// Its area, lit and shadowed, in the scene's units squared.
    pub area: f64,
    /// The area of its lit parts.
    pub lit_area: f64,
    /// The area of its shadowed parts.
    pub shadowed_area: f64,
    /// The lit parts' contours.
    pub lit: Vec<Vec<[f64; 3]>>,
    /// The shadowed parts' contours.
    pub shadowed: Vec<Vec<[f64; 3]>>,
}

/// The lit and shadowed polygons of every scene polygon for a point light at
/// `light`, by Atherton, Weiler & Greenberg's shadow polygons.
pub fn receiver_shadows(scene: &Scene, light: DVec3) -> Vec<ReceiverShadows> {
    let lit = lit_polygons(scene, light);
    scene
        .polygons
        .iter()
        .zip(&lit)
        .enumerate()
        .map(|(id, (polygon, details))| measure(scene, id, polygon, details))
        .collect()
}

fn measure(
    scene: &Scene,
    id: usize,
    polygon: &Polygon,
    details: &[DetailPolygon],
) -> ReceiverShadows {
    let frame = PlaneFrame::new(polygon.vertices[0].position, polygon.normal);
    let whole: Region = vec![polygon.positions().map(|p| frame.coords(p)).collect()];
    let mut lit: Region = Vec::new();
    let mut shadowed = whole.clone();
    for detail in details {
        let mut region: Region = detail
            .contours
            .iter()
            .map(|(c, _)| c.iter().map(|&p| frame.coords(p)).collect())
            .collect();
        // The way back from the light may mirror a detail polygon: restore the
        // orientation of its outer contour (and so of its holes).
        let outer = detail
            .contours
            .iter()
            .position(|(_, sign)| *sign > 0.0)
            .unwrap_or(0);
        if contour_area(&region[outer]) < 0.0 {
            region.iter_mut().for_each(|c| c.reverse());
        }
        shadowed = weiler_atherton::clip(&shadowed, &region).1;
        lit.extend(region);
    }
    let lift = |r: &Region| -> Vec<Vec<[f64; 3]>> {
        r.iter()
            .map(|c| c.iter().map(|&q| frame.point(q).to_array()).collect())
            .collect()
    };
    ReceiverShadows {
        polygon: id,
        object: scene.objects[polygon.object].name.clone(),
        normal: polygon.normal.to_array(),
        area: weiler_atherton::area(&whole),
        lit_area: weiler_atherton::area(&lit),
        shadowed_area: weiler_atherton::area(&shadowed),
        lit: lift(&lit),
        shadowed: lift(&shadowed),
    }
}
