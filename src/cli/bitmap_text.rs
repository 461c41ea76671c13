//! Text in an 8 × 8 bitmap font (font8x8, public domain), for the viewer's overlay
//! and the contact sheet's labels.

use font8x8::UnicodeFonts;

/// Calls `lit(x, y)` for every pixel of `line` drawn `scale` times the font's size,
/// from (0, 0) at its top left; a character the font lacks is left blank.
pub fn for_each_lit_pixel(line: &str, scale: usize, mut lit: impl FnMut(usize, usize)) {
    for (column, c) in line.chars().enumerate() {
        let glyph = font8x8::BASIC_FONTS
            .get(c)
            .or_else(|| font8x8::LATIN_FONTS.get(c))
            .unwrap_or([0; 8]);
        let left = column * 8 * scale;
        for (gy, bits) in glyph.iter().enumerate() {
            for gx in (0..8).filter(|gx| bits >> gx & 1 == 1) {
                for dy in 0..scale {
                    for dx in 0..scale {
                        lit(left + gx * scale + dx, gy * scale + dy);
                    }
                }
            }
        }
    }
}
