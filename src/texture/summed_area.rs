//! Summed-area tables: F. C. Crow, "Summed-area tables for texture mapping",
//! Computer Graphics (SIGGRAPH '84) 18(3):207–212, 1984.
//!
//! S(x, y) holds the sum of every texel left of x and above y. The mean of the texture
//! over any axis-aligned rectangle then costs four lookups:
//! [S(x1, y1) − S(x0, y1) − S(x1, y0) + S(x0, y0)] / area. The rectangle is the
//! bounding box of the pixel's footprint in the texture; fractional corners are read
//! by interpolating S bilinearly (the integral of the piecewise-constant texture).
//! Footprints elongated along u or v are filtered without over-blurring the short
//! axis, unlike a mip-map's square footprint; diagonal ones are still over-blurred.
//!
//! Choices: sums are kept in f64 (Crow's "wider storage per entry": in f32 the
//! differences of large sums lose the texture's low bits). Repeat wrap is exact: S is
//! extended periodically with the whole-texture and whole-row sums. Clamp wrap clamps
//! the rectangle to the texture. A rectangle is at least one texel wide, so a magnified
//! texture comes out bilinearly interpolated.

use super::texels::{Texels, Wrap};
use glam::{DVec2, DVec3, Vec3};

#[derive(Clone, Debug)]
pub struct SummedAreaTable {
    width: u32,
    height: u32,
    /// (width + 1) × (height + 1) sums, S(0, ·) = S(·, 0) = 0.
    sums: Vec<DVec3>,
}

impl SummedAreaTable {
    pub fn build(image: &Texels) -> SummedAreaTable {
        let (w, h) = (image.width as usize, image.height as usize);
        let mut sums = vec![DVec3::ZERO; (w + 1) * (h + 1)];
        for y in 1..=h {
            let mut row = DVec3::ZERO;
            for x in 1..=w {
                row += image.texels[(y - 1) * w + (x - 1)].as_dvec3();
                sums[y * (w + 1) + x] = sums[(y - 1) * (w + 1) + x] + row;
            }
        }
        SummedAreaTable {
            width: image.width,
            height: image.height,
            sums,
        }
    }

    fn stored(&self, x: usize, y: usize) -> DVec3 {
        self.sums[y * (self.width as usize + 1) + x]
    }

    /// S at integer texel corner (x, y), extended periodically beyond the texture.
    fn corner(&self, x: i64, y: i64) -> DVec3 {
        let (w, h) = (self.width as i64, self.height as i64);
        let (qx, rx) = (x.div_euclid(w), x.rem_euclid(w) as usize);
        let (qy, ry) = (y.div_euclid(h), y.rem_euclid(h) as usize);
        let (w, h) = (w as usize, h as usize);
        self.stored(w, h) * (qx * qy) as f64
            + self.stored(w, ry) * qx as f64
            + self.stored(rx, h) * qy as f64
            + self.stored(rx, ry)
    }

    /// S at a fractional point, bilinear between the four corners around it.
    fn at(&self, p: DVec2) -> DVec3 {
        let (x, y) = (p.x.floor(), p.y.floor());
        let (fx, fy) = (p.x - x, p.y - y);
        let (x, y) = (x as i64, y as i64);
        let top = self.corner(x, y).lerp(self.corner(x + 1, y), fx);
        let bottom = self.corner(x, y + 1).lerp(self.corner(x + 1, y + 1), fx);
        top.lerp(bottom, fy)
    }

    /// The mean of the texture over the rectangle [lo, hi] in texel coordinates.
    pub fn mean(&self, lo: DVec2, hi: DVec2) -> Vec3 {
        let area = (hi.x - lo.x) * (hi.y - lo.y);
        let sum = self.at(hi) - self.at(DVec2::new(lo.x, hi.y)) - self.at(DVec2::new(hi.x, lo.y))
            + self.at(lo);
        (sum / area).as_vec3()
    }

    /// The mean over the bounding box of a pixel's footprint centred on `uv`, whose
    /// sides in the texture are the screen derivatives `derivatives` (∂/∂x, ∂/∂y).
    pub fn filter(&self, uv: DVec2, derivatives: [DVec2; 2], wrap: Wrap) -> Vec3 {
        let size = DVec2::new(self.width as f64, self.height as f64);
        let centre = DVec2::new(uv.x, 1.0 - uv.y) * size;
        let half =
            ((derivatives[0].abs() + derivatives[1].abs()) * size * 0.5).max(DVec2::splat(0.5));
        let (mut lo, mut hi) = (centre - half, centre + half);
        if wrap == Wrap::Clamp {
            // Keep at least one texel inside the texture.
            lo = lo.clamp(DVec2::ZERO, size - 1.0);
            hi = hi.clamp(lo + 1.0, size);
        }
        // A footprint wider than the whole texture averages whole copies: bound the
        // sums' magnitude by bounding the rectangle to a few periods.
        let limit = size * 4.0;
        hi = hi.min(lo + limit);
        self.mean(lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image() -> Texels {
        Texels::generate(5, 3, |uv| {
            Vec3::new(
                (uv.x * 9.0).floor() as f32,
                (uv.y * 4.0).floor() as f32,
                1.0,
            )
        })
    }

    #[test]
    fn integer_rectangles_equal_brute_force_means() {
        let img = image();
        let sat = SummedAreaTable::build(&img);
        for (x0, y0, x1, y1) in [(0, 0, 5, 3), (1, 1, 3, 2), (-2, -1, 7, 5), (4, 2, 6, 4)] {
            let mut sum = Vec3::ZERO;
            for y in y0..y1 {
                for x in x0..x1 {
                    sum += img.at(x, y, Wrap::Repeat);
                }
            }
            let brute = sum / ((x1 - x0) * (y1 - y0)) as f32;
            let lo = DVec2::new(x0 as f64, y0 as f64);
            let hi = DVec2::new(x1 as f64, y1 as f64);
            assert!((sat.mean(lo, hi) - brute).abs().max_element() < 1e-6);
        }
    }

    #[test]
    fn a_one_texel_box_is_bilinear() {
        let img = image();
        let sat = SummedAreaTable::build(&img);
        let uv = DVec2::new(0.37, 0.58);
        let got = sat.filter(uv, [DVec2::ZERO, DVec2::ZERO], Wrap::Repeat);
        assert!((got - img.bilinear(uv, Wrap::Repeat)).abs().max_element() < 1e-5);
    }
}
