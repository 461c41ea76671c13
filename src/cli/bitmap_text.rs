//! Text in a small bitmap font of lumiere's own, for the contact sheet's labels:
//! lower-case letters, digits and the punctuation of catalogue ids, each glyph
//! 5 pixels wide and 9 tall (7 above the baseline, 2 for descenders).

/// Horizontal advance of one character, in font pixels: the glyph and a blank column.
pub const ADVANCE: usize = GLYPH_WIDTH + 1;
/// Height of a glyph, descenders included, in font pixels.
pub const HEIGHT: usize = 9;
const GLYPH_WIDTH: usize = 5;

/// The font as sheets to be read by eye: each sheet lists its characters, then the
/// nine rows of their glyphs side by side, one blank column apart ('#' is lit).
const SHEETS: [(&str, [&str; HEIGHT]); 3] = [
    (
        "abcdefghijklm",
        [
            "..... #.... ..... ....# ..... ..##. ..... #.... ..#.. ...#. #.... .##.. .....",
            "..... #.... ..... ....# ..... .#... ..... #.... ..... ..... #.... ..#.. .....",
            ".###. ####. .#### .#### .###. ####. .#### ####. .##.. ..##. #..#. ..#.. ##.#.",
            "....# #...# #.... #...# #...# .#... #...# #...# ..#.. ...#. #.#.. ..#.. #.#.#",
            ".#### #...# #.... #...# ##### .#... #...# #...# ..#.. ...#. ##... ..#.. #.#.#",
            "#...# #...# #.... #...# #.... .#... #...# #...# ..#.. ...#. #.#.. ..#.. #.#.#",
            ".#### ####. .#### .#### .#### .#... .#### #...# .###. ...#. #..#. .###. #.#.#",
            "..... ..... ..... ..... ..... ..... ....# ..... ..... #..#. ..... ..... .....",
            "..... ..... ..... ..... ..... ..... .###. ..... ..... .##.. ..... ..... .....",
        ],
    ),
    (
        "nopqrstuvwxyz",
        [
            "..... ..... ..... ..... ..... ..... .#... ..... ..... ..... ..... ..... .....",
            "..... ..... ..... ..... ..... ..... .#... ..... ..... ..... ..... ..... .....",
            "####. .###. ####. .#### #.##. .#### ####. #...# #...# #...# #...# #...# #####",
            "#...# #...# #...# #...# ##..# #.... .#... #...# #...# #.#.# .#.#. #...# ...#.",
            "#...# #...# #...# #...# #.... .###. .#... #...# #...# #.#.# ..#.. #...# ..#..",
            "#...# #...# #...# #...# #.... ....# .#... #...# .#.#. #.#.# .#.#. #...# .#...",
            "#...# .###. ####. .#### #.... ####. ..##. .#### ..#.. .#.#. #...# .#### #####",
            "..... ..... #.... ....# ..... ..... ..... ..... ..... ..... ..... ....# .....",
            "..... ..... #.... ....# ..... ..... ..... ..... ..... ..... ..... .###. .....",
        ],
    ),
    (
        "0123456789-_.",
        [
            ".###. ..#.. .###. ####. ...#. ##### ..##. ##### .###. .###. ..... ..... .....",
            "#...# .##.. #...# ....# ..##. #.... .#... ....# #...# #...# ..... ..... .....",
            "#..## ..#.. ....# ....# .#.#. ####. #.... ...#. #...# #...# ..... ..... .....",
            "#.#.# ..#.. ...#. .###. #..#. ....# ####. ..#.. .###. .#### ..... ..... .....",
            "##..# ..#.. ..#.. ....# ##### ....# #...# .#... #...# ....# .###. ..... .....",
            "#...# ..#.. .#... ....# ...#. #...# #...# .#... #...# ...#. ..... ..... .....",
            ".###. .###. ##### ####. ...#. .###. .###. .#... .###. .##.. ..... ..... ..#..",
            "..... ..... ..... ..... ..... ..... ..... ..... ..... ..... ..... ##### .....",
            "..... ..... ..... ..... ..... ..... ..... ..... ..... ..... ..... ..... .....",
        ],
    ),
];

/// The rows of `c`'s glyph, bit `x` lit where column `x` is; `None` for a character
/// the font lacks.
fn glyph(c: char) -> Option<[u8; HEIGHT]> {
    SHEETS.iter().find_map(|(chars, rows)| {
        let index = chars.chars().position(|k| k == c)?;
        let left = index * ADVANCE;
        Some(std::array::from_fn(|y| {
            rows[y].as_bytes()[left..left + GLYPH_WIDTH]
                .iter()
                .enumerate()
                .filter(|(_, b)| **b == b'#')
                .fold(0, |bits, (x, _)| bits | 1 << x)
        }))
    })
}

/// Calls `lit(x, y)` for every pixel of `line` drawn `scale` times the font's size,
/// from (0, 0) at its top left; a character the font lacks is left blank.
pub fn for_each_lit_pixel(line: &str, scale: usize, mut lit: impl FnMut(usize, usize)) {
    for (column, c) in line.chars().enumerate() {
        let Some(rows) = glyph(c) else { continue };
        let left = column * ADVANCE * scale;
        for (gy, bits) in rows.iter().enumerate() {
            for gx in (0..GLYPH_WIDTH).filter(|gx| bits >> gx & 1 == 1) {
                for dy in 0..scale {
                    for dx in 0..scale {
                        lit(left + gx * scale + dx, gy * scale + dy);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_sheet_row_holds_one_glyph_per_character() {
        for (chars, rows) in SHEETS {
            let expected = chars.chars().count() * ADVANCE - 1;
            for row in rows {
                assert_eq!(row.len(), expected, "a row of the sheet {chars:?}");
                assert!(row.bytes().all(|b| b"#. ".contains(&b)), "{row:?}");
                let gaps = row.bytes().skip(GLYPH_WIDTH).step_by(ADVANCE);
                assert!(gaps.into_iter().all(|b| b == b' '), "{row:?}");
            }
        }
    }

    #[test]
    fn every_catalogue_id_can_be_written() {
        for entry in lumiere::catalogue::entries().unwrap() {
            for c in entry.algorithm.id.chars() {
                let lit = glyph(c).map_or(0, |rows| rows.iter().filter(|r| **r != 0).count());
                assert!(lit > 0, "{c:?} of {} has no glyph", entry.algorithm.id);
            }
        }
    }

    #[test]
    fn glyphs_are_drawn_where_the_sheet_says() {
        // 'l' (.##.. then ..#.. five times then .###.) at scale 1 and 2.
        let mut pixels = Vec::new();
        for_each_lit_pixel("ol", 1, |x, y| pixels.push((x, y)));
        let l: Vec<_> = pixels.iter().filter(|(x, _)| *x >= ADVANCE).collect();
        assert_eq!(l.len(), 2 + 5 + 3);
        assert!(l.contains(&&(ADVANCE + 1, 0)) && l.contains(&&(ADVANCE + 2, 0)));
        assert!(l.contains(&&(ADVANCE + 3, 6)) && !l.contains(&&(ADVANCE, 0)));
        let mut doubled = 0;
        for_each_lit_pixel("l", 2, |x, y| {
            assert!(x < 2 * GLYPH_WIDTH && y < 2 * HEIGHT);
            doubled += 1;
        });
        assert_eq!(doubled, 4 * 10);
        let mut unknown = 0;
        for_each_lit_pixel("é~", 1, |_, _| unknown += 1);
        assert_eq!(unknown, 0);
    }
}
