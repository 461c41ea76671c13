//! The viewer's overlay: lines of text in an 8 × 8 bitmap font (font8x8, public
//! domain), drawn twice their size on a dark band so that they read on a
//! projector.

/// Glyphs are drawn this many times their size: twice on a wide window.
pub fn scale(width: usize) -> usize {
    if width >= 900 { 2 } else { 1 }
}

/// Characters that fit across a window `width` pixels wide.
pub fn columns(width: usize) -> usize {
    (width.saturating_sub(8) / (8 * scale(width))).max(1)
}

/// Draws `lines` from the top left of a `width` × `height` 0RGB picture.
pub fn draw(pixels: &mut [u32], width: usize, height: usize, lines: &[String]) {
    let scale = scale(width);
    let line_height = 10 * scale;
    let band = (lines.len() * line_height + 4).min(height);
    let longest = lines.iter().map(|l| l.chars().count()).max().unwrap_or(0);
    let band_width = (longest * 8 * scale + 8).min(width);
    for y in 0..band {
        for x in 0..band_width {
            let p = &mut pixels[y * width + x];
            // Darkened to a quarter: the picture still shows through.
            *p = (*p >> 2) & 0x3f3f3f;
        }
    }
    for (row, line) in lines.iter().enumerate() {
        let top = 2 + row * line_height;
        super::super::bitmap_text::for_each_lit_pixel(line, scale, |x, y| {
            let (x, y) = (4 + x, top + y);
            if x < width && y < height {
                pixels[y * width + x] = 0xf0f0f0;
            }
        });
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn text_lights_pixels_inside_its_band_only() {
        let (w, h) = (200, 60);
        let mut pixels = vec![0x808080; w * h];
        super::draw(&mut pixels, w, h, &["Hi".to_string()]);
        let lit = |y: usize| (0..w).filter(|&x| pixels[y * w + x] == 0xf0f0f0).count();
        assert!((0..10).map(lit).sum::<usize>() > 20);
        assert_eq!((14..h).map(lit).sum::<usize>(), 0);
        // Beyond the band the picture is untouched.
        assert_eq!(pixels[(h - 1) * w + w - 1], 0x808080);
    }
}
