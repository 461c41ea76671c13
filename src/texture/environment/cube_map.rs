//! The cube map: N. Greene, "Environment mapping and other applications of world
//! projections", IEEE CG&A 6(11):21–29, 1986.
//!
//! Six square perspective pictures of the surroundings, 90° fields of view, taken
//! from the world centre along ±x, ±y, ±z. A direction is looked up in the face of its
//! largest component (the major axis); its two other components divided by that one
//! give the position in the face. Greene's reasons for preferring it: any renderer
//! (or camera) makes the faces, each face is an ordinary picture that mip-maps as one,
//! and texels vary in solid angle by only 3^{3/2} ≈ 5.2 between a face's centre and
//! its corners.
//!
//! Orientation (our choice; Greene fixes none): each face is the picture a camera at
//! the centre takes, right = forward × up, image top = up:
//!
//! | face | forward | up | right |
//! |------|---------|----|-------|
//! | +x   | +x      | +y | +z    |
//! | −x   | −x      | +y | −z    |
//! | +y   | +y      | +z | +x    |
//! | −y   | −y      | −z | +x    |
//! | +z   | +z      | +y | −x    |
//! | −z   | −z      | +y | +x    |
//!
//! so that lumiere's own renders are faces as they are, and the horizontal cross (4:3)
//! unfolds with −x, −z, +x, +z left to right in its middle row, +y above −z and −y
//! below it.
//!
//! Filtering, our choice where Greene's pictures simply end at their edges: every
//! face of every mip level carries a one-texel border copied from its neighbours
//! (a corner's border texel is the mean of the three texels meeting there), so that
//! bilinear lookups blend across a seam and are continuous over the whole sphere.

use super::super::mip_map::{reduce, resample};
use super::super::texels::{Texels, Wrap};
use crate::settings::Filter;
use glam::{DVec2, DVec3, Vec3};

/// The faces in their storage order.
pub const FACE_NAMES: [&str; 6] = ["+x", "-x", "+y", "-y", "+z", "-z"];

/// Per face: forward, up and right (the table above).
const FRAMES: [[DVec3; 3]; 6] = [
    [DVec3::X, DVec3::Y, DVec3::Z],
    [DVec3::NEG_X, DVec3::Y, DVec3::NEG_Z],
    [DVec3::Y, DVec3::Z, DVec3::X],
    [DVec3::NEG_Y, DVec3::NEG_Z, DVec3::X],
    [DVec3::Z, DVec3::Y, DVec3::NEG_X],
    [DVec3::NEG_Z, DVec3::Y, DVec3::X],
];

/// Where each face sits in the horizontal cross, in face-size cells (column, row).
pub const CROSS_CELLS: [(u32, u32); 6] = [(2, 1), (0, 1), (1, 0), (1, 2), (3, 1), (1, 1)];

/// Face `face`'s camera: forward, up, right.
pub fn face_frame(face: usize) -> [DVec3; 3] {
    FRAMES[face]
}

/// The face of direction `d` (its major axis; ties go to the earlier face in storage
/// order) and the position (u, v) in it, in [0, 1]².
pub fn face_uv(d: DVec3) -> (usize, DVec2) {
    let a = d.abs();
    let face = if a.x >= a.y && a.x >= a.z {
        if d.x >= 0.0 { 0 } else { 1 }
    } else if a.y >= a.z {
        if d.y >= 0.0 { 2 } else { 3 }
    } else if d.z >= 0.0 {
        4
    } else {
        5
    };
    let uv = uv_on_face(face, d).unwrap_or(DVec2::splat(0.5));
    (face, uv)
}

/// The position of direction `d` on face `face`'s plane, (u, v) = ((s/m + 1)/2,
/// (t/m + 1)/2) with m the component along the face's forward axis; outside [0, 1]²
/// when `d` belongs to another face; `None` when `d` does not point into the face's
/// half-space.
pub fn uv_on_face(face: usize, d: DVec3) -> Option<DVec2> {
    let [forward, up, right] = FRAMES[face];
    let m = d.dot(forward);
    (m > 0.0).then(|| DVec2::new((d.dot(right) / m + 1.0) / 2.0, (d.dot(up) / m + 1.0) / 2.0))
}

/// The unit direction of position (u, v) on face `face` (any (u, v), not only [0, 1]²).
pub fn direction(face: usize, uv: DVec2) -> DVec3 {
    let [forward, up, right] = FRAMES[face];
    (forward + right * (2.0 * uv.x - 1.0) + up * (2.0 * uv.y - 1.0)).normalize()
}

/// Six `n × n` faces with their one-texel borders, `(n + 2)²` texels each.
#[derive(Clone, Debug)]
struct BorderedFaces {
    n: u32,
    faces: Vec<Texels>,
}

impl BorderedFaces {
    fn new(faces: &[Texels]) -> BorderedFaces {
        let n = faces[0].width;
        let inner = |face: usize, i: i64, j: i64| faces[face].at(i, j, Wrap::Clamp);
        // The texel of a neighbouring face just across the edge from texel (i, j) of
        // `face`, one of whose indices is −1 or n: the seam point's position on the
        // neighbour, pulled half a texel inside it.
        let across = |face: usize, i: i64, j: i64| -> Vec3 {
            let centre = |k: i64| (k as f64 + 0.5) / n as f64;
            let edge = |k: i64| {
                if k < 0 {
                    0.0
                } else if k >= n as i64 {
                    1.0
                } else {
                    centre(k)
                }
            };
            let seam = DVec2::new(edge(i), 1.0 - edge(j));
            let beyond = DVec2::new(centre(i), 1.0 - centre(j));
            let (neighbour, _) = face_uv(direction(face, beyond));
            let uv = uv_on_face(neighbour, direction(face, seam)).expect("a neighbouring face");
            let t = DVec2::new(uv.x * n as f64, (1.0 - uv.y) * n as f64);
            let k = |x: f64| (x.floor() as i64).clamp(0, n as i64 - 1);
            inner(neighbour, k(t.x), k(t.y))
        };
        let side = n as i64;
        let faces = (0..6)
            .map(|face| {
                let mut texels = Vec::with_capacity(((n + 2) * (n + 2)) as usize);
                for j in -1..=side {
                    for i in -1..=side {
                        let outside_i = i < 0 || i >= side;
                        let outside_j = j < 0 || j >= side;
                        texels.push(match (outside_i, outside_j) {
                            (false, false) => inner(face, i, j),
                            (true, true) => {
                                let (ci, cj) = (i.clamp(0, side - 1), j.clamp(0, side - 1));
                                (inner(face, ci, cj) + across(face, i, cj) + across(face, ci, j))
                                    / 3.0
                            }
                            _ => across(face, i, j),
                        });
                    }
                }
                Texels {
                    width: n + 2,
                    height: n + 2,
                    texels,
                }
            })
            .collect();
        BorderedFaces { n, faces }
    }

    fn nearest(&self, face: usize, uv: DVec2) -> Vec3 {
        let n = self.n as f64;
        let k = |x: f64| (x.floor() as i64).clamp(0, self.n as i64 - 1) + 1;
        self.faces[face].at(k(uv.x * n), k((1.0 - uv.y) * n), Wrap::Clamp)
    }

    fn bilinear(&self, face: usize, uv: DVec2) -> Vec3 {
        let n = self.n as f64;
        // Continuous bordered-texel coordinates, minus the half texel to centres:
        // in [0.5, n + 0.5], so the four texels are inside the bordered face.
        let t = DVec2::new(
            uv.x.clamp(0.0, 1.0) * n + 0.5,
            (1.0 - uv.y.clamp(0.0, 1.0)) * n + 0.5,
        );
        let (i, j) = (
            (t.x.floor() as usize).min(self.n as usize),
            (t.y.floor() as usize).min(self.n as usize),
        );
        let (fx, fy) = ((t.x - i as f64) as f32, (t.y - j as f64) as f32);
        let side = self.n as usize + 2;
        let texels = &self.faces[face].texels;
        let at = |i: usize, j: usize| texels[j * side + i];
        let top = at(i, j).lerp(at(i + 1, j), fx);
        let bottom = at(i, j + 1).lerp(at(i + 1, j + 1), fx);
        top.lerp(bottom, fy)
    }
}

/// A cube map: the faces as given, bordered, and their mip-map levels (power-of-two
/// sides, each level's faces the 2 × 2 box reduction of the one below).
#[derive(Clone, Debug)]
pub struct CubeMap {
    /// The faces as given, in storage order (`FACE_NAMES`).
    pub faces: Vec<Texels>,
    base: BorderedFaces,
    levels: Vec<BorderedFaces>,
}

impl CubeMap {
    /// A cube map of six square faces of one size (checked by the caller).
    pub fn new(faces: Vec<Texels>) -> CubeMap {
        assert!(faces.len() == 6 && faces.iter().all(|f| f.width == faces[0].width));
        let base = BorderedFaces::new(&faces);
        let n = faces[0].width;
        let mut level: Vec<Texels> = if n.is_power_of_two() {
            faces.clone()
        } else {
            let m = n.next_power_of_two();
            faces.iter().map(|f| resample(f, m, m)).collect()
        };
        let mut levels = vec![BorderedFaces::new(&level)];
        while level[0].width > 1 {
            level = level.iter().map(reduce).collect();
            levels.push(BorderedFaces::new(&level));
        }
        CubeMap {
            faces,
            base,
            levels,
        }
    }

    /// Texels per face side.
    pub fn size(&self) -> u32 {
        self.base.n
    }

    /// The texel containing direction `d` (point sampling).
    pub fn nearest(&self, d: DVec3) -> Vec3 {
        let (face, uv) = face_uv(d);
        self.base.nearest(face, uv)
    }

    /// Bilinear interpolation on `d`'s face, across its seams.
    pub fn bilinear(&self, d: DVec3) -> Vec3 {
        let (face, uv) = face_uv(d);
        self.base.bilinear(face, uv)
    }

    /// The mip-map level λ for a lookup at unit `d` whose footprint reaches the directions
    /// `d + footprint[0]` and `d + footprint[1]` (Blinn & Newell's corners mapped onto
    /// the face, here the pixel's neighbours): the longer side in level-0 texels,
    /// log₂. A corner behind the face's plane covers the whole face.
    pub fn level(&self, d: DVec3, footprint: [DVec3; 2]) -> f64 {
        let (face, uv) = face_uv(d);
        self.level_on_face(face, uv, d, footprint)
    }

    /// `level` for a direction already placed at (face, uv).
    fn level_on_face(&self, face: usize, uv: DVec2, d: DVec3, footprint: [DVec3; 2]) -> f64 {
        let n = self.levels[0].n as f64;
        let side2 = |offset: DVec3| {
            uv_on_face(face, d + offset).map_or(f64::INFINITY, |o| (o - uv).length_squared())
        };
        let texels2 = side2(footprint[0]).max(side2(footprint[1])) * n * n;
        if texels2.is_nan() || texels2 <= 1.0 {
            return 0.0;
        }
        (0.5 * texels2.log2()).min((self.levels.len() - 1) as f64)
    }

    /// The lookup `filter` makes at `d` with `footprint`, the face found once.
    pub fn filtered(&self, d: DVec3, footprint: [DVec3; 2], filter: Filter) -> Vec3 {
        let (face, uv) = face_uv(d);
        match filter {
            Filter::Nearest => self.base.nearest(face, uv),
            Filter::MipNearest | Filter::Trilinear => {
                let lambda = self.level_on_face(face, uv, d, footprint);
                if filter == Filter::MipNearest {
                    let k = (lambda.round() as usize).min(self.levels.len() - 1);
                    self.levels[k].bilinear(face, uv)
                } else {
                    self.trilinear_on_face(face, uv, lambda)
                }
            }
            Filter::Bilinear | Filter::SummedArea => self.base.bilinear(face, uv),
        }
    }

    /// Bilinear in the two levels bracketing λ, blended (Williams 1983, per face).
    pub fn trilinear(&self, d: DVec3, lambda: f64) -> Vec3 {
        let (face, uv) = face_uv(d);
        self.trilinear_on_face(face, uv, lambda)
    }

    fn trilinear_on_face(&self, face: usize, uv: DVec2, lambda: f64) -> Vec3 {
        let l0 = (lambda.floor() as usize).min(self.levels.len() - 1);
        let l1 = (l0 + 1).min(self.levels.len() - 1);
        let f = (lambda - l0 as f64).clamp(0.0, 1.0) as f32;
        let a = self.levels[l0].bilinear(face, uv);
        if f == 0.0 || l1 == l0 {
            return a;
        }
        a.lerp(self.levels[l1].bilinear(face, uv), f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_face_is_a_right_handed_camera() {
        for [forward, up, right] in FRAMES {
            assert_eq!(forward.cross(up), right);
        }
    }

    #[test]
    fn the_cross_unfolds_along_shared_edges() {
        // The right edge of each middle-row face is the left edge of the next.
        let row = [1, 5, 0, 4];
        for w in row.windows(2) {
            for t in [0.1, 0.5, 0.9] {
                let a = direction(w[0], DVec2::new(1.0, t));
                let b = direction(w[1], DVec2::new(0.0, t));
                assert!(
                    (a - b).length() < 1e-12,
                    "{} | {}",
                    FACE_NAMES[w[0]],
                    FACE_NAMES[w[1]]
                );
            }
        }
        // +y above −z, −y below it.
        for s in [0.1, 0.5, 0.9] {
            let top = direction(5, DVec2::new(s, 1.0));
            assert!((top - direction(2, DVec2::new(s, 0.0))).length() < 1e-12);
            let bottom = direction(5, DVec2::new(s, 0.0));
            assert!((bottom - direction(3, DVec2::new(s, 1.0))).length() < 1e-12);
        }
    }
}
