//! The figures' drawing backend: plotters' in-memory bitmap, with text set
//! glyph by glyph at each glyph's own left side bearing.
//!
//! plotters 0.3.7 draws ab_glyph text from each glyph's ink box placed at the
//! pen, dropping the bearing between the pen and the ink: a narrow glyph
//! inside a wide advance ("1", "t") then sat at the advance's left edge,
//! leaving a gap after it ("51 2²", "cons tant"). Layout (the text's box, its
//! anchor, its rotation) stays plotters', so labels keep their places.

use ab_glyph::{Font, FontRef, ScaleFont, point};
use plotters::prelude::*;
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, text_anchor,
};
use std::sync::OnceLock;

/// The one font every figure uses (egui's bundled Ubuntu Light, registered
/// with plotters as `plot::FONT` for its layout).
fn font() -> &'static FontRef<'static> {
    static FONT: OnceLock<FontRef<'static>> = OnceLock::new();
    FONT.get_or_init(|| {
        FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT).expect("egui's bundled font parses")
    })
}

/// A figure being drawn: a `BitMapBackend` whose text is set in the figures' font
/// (egui's Ubuntu Light), glyph by glyph.
pub struct Figure<'a>(pub BitMapBackend<'a>);

type Error<'a> = DrawingErrorKind<<BitMapBackend<'a> as DrawingBackend>::ErrorType>;

impl<'a> DrawingBackend for Figure<'a> {
    type ErrorType = <BitMapBackend<'a> as DrawingBackend>::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }

    fn ensure_prepared(&mut self) -> Result<(), Error<'a>> {
        self.0.ensure_prepared()
    }

    fn present(&mut self) -> Result<(), Error<'a>> {
        self.0.present()
    }

    fn draw_pixel(&mut self, point: BackendCoord, color: BackendColor) -> Result<(), Error<'a>> {
        self.0.draw_pixel(point, color)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), Error<'a>> {
        self.0.draw_line(from, to, style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), Error<'a>> {
        self.0.draw_rect(upper_left, bottom_right, style, fill)
    }

    fn blit_bitmap(&mut self, pos: BackendCoord, size: (u32, u32), src: &[u8]) -> Result<(), Error<'a>> {
        self.0.blit_bitmap(pos, size, src)
    }

    /// plotters' own text drawing (its box, anchor and rotation), each glyph
    /// outlined at its pen position so that its bearing is kept.
    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Result<(), Error<'a>> {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        let ((min_x, min_y), (max_x, max_y)) = style
            .layout_box(text)
            .map_err(|e| DrawingErrorKind::FontError(Box::new(e)))?;
        let offset = anchor_offset(style.anchor(), (max_x - min_x, max_y - min_y));
        let transform = style.transform();
        let font = font().as_scaled(style.size() as f32);
        let mut pen = 0.0f32;
        let mut previous = None;
        // A glyph's pixels, gathered before they are drawn (the outline's
        // callback cannot return the backend's error); one buffer for all.
        let mut inked = Vec::new();
        for c in text.chars() {
            let id = font.glyph_id(c);
            if let Some(previous) = previous {
                pen += font.kern(previous, id);
            }
            previous = Some(id);
            let glyph = id.with_scale_and_position(font.scale(), point(pen, 0.0));
            pen += font.h_advance(id);
            let Some(outline) = font.outline_glyph(glyph) else {
                continue;
            };
            let bounds = outline.px_bounds();
            // plotters' vertical placement, half an em below the pen, in
            // whole pixels before the glyph's own offset: plotters truncated
            // the sum, which raised a glyph whose ink box starts a row lower
            // (a "u" beside an "n") by one pixel at odd sizes.
            let top = (style.size() as f32 / 2.0).floor() as i32 + bounds.min.y as i32;
            outline.draw(|x, y, coverage| inked.push((x, y, coverage)));
            for (x, y, coverage) in inked.drain(..) {
                let (x, y) = transform.transform(
                    bounds.min.x as i32 + x as i32 + offset.0 - min_x,
                    top + y as i32 + offset.1 - min_y,
                );
                // The bitmap passes over pixels outside it.
                let ink = BackendColor {
                    alpha: color.alpha * f64::from(coverage),
                    rgb: color.rgb,
                };
                self.draw_pixel((pos.0 + x, pos.1 + y), ink)?;
            }
        }
        Ok(())
    }
}

/// Where a text box of `size` starts from its anchor point.
fn anchor_offset(anchor: text_anchor::Pos, (width, height): (i32, i32)) -> (i32, i32) {
    use text_anchor::{HPos, VPos};
    let dx = match anchor.h_pos {
        HPos::Left => 0,
        HPos::Right => -width,
        HPos::Center => -width / 2,
    };
    let dy = match anchor.v_pos {
        VPos::Top => 0,
        VPos::Center => -height / 2,
        VPos::Bottom => -height,
    };
    (dx, dy)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `text` drawn at (20, 10) in a font of `size` px: whether each pixel is inked.
    fn inked(text: &str, size: u32) -> impl Fn(u32, u32) -> bool {
        super::super::register_fonts();
        let (w, h) = (200u32, 80u32);
        let mut rgb = vec![255u8; (w * h * 3) as usize];
        {
            let root = Figure(BitMapBackend::with_buffer(&mut rgb, (w, h))).into_drawing_area();
            let style = (super::super::FONT, size).into_font().color(&BLACK);
            root.draw(&Text::new(text.to_string(), (20, 10), style)).unwrap();
            root.present().unwrap();
        }
        // Ink where a glyph covers a fifth of the pixel or more (a light
        // font's stems cover under half of a pixel at 11 px).
        move |x, y| x < w && y < h && rgb[((y * w + x) * 3) as usize] < 200
    }

    /// The leftmost and rightmost inked columns of `text` at 40 px.
    fn ink_columns(text: &str) -> (u32, u32) {
        let ink = inked(text, 40);
        let columns: Vec<u32> = (0..200).filter(|&x| (0..80).any(|y| ink(x, y))).collect();
        (columns[0], *columns.last().unwrap())
    }

    /// The lowest inked row of `text`.
    fn ink_bottom(text: &str, size: u32) -> u32 {
        let ink = inked(text, size);
        (0..80).rev().find(|&y| (0..200).any(|x| ink(x, y))).unwrap()
    }

    #[test]
    fn flat_bottomed_glyphs_sit_on_one_baseline_at_every_size() {
        for size in 11..=16 {
            let n = ink_bottom("n", size);
            for c in ["u", "m", "r", "i"] {
                assert_eq!(ink_bottom(c, size), n, "{c} against n at {size} px");
            }
        }
    }

    #[test]
    fn a_glyph_keeps_its_left_side_bearing() {
        let font = font().as_scaled(40.0);
        let one = font.glyph_id('1');
        let bearing = font.h_side_bearing(one);
        assert!(
            bearing > 3.0,
            "the test wants a glyph set well inside its advance: {bearing}"
        );
        // The ink starts one bearing past the pen (plotters put it at the pen).
        let (left, right_one) = ink_columns("1");
        assert!(
            (left as f32 - (20.0 + bearing)).abs() <= 1.0,
            "ink from column {left}, the pen at 20 and the bearing {bearing}"
        );
        // "11": the second glyph's ink one advance after the first's.
        let (_, right_two) = ink_columns("11");
        let advance = font.h_advance(one) + font.kern(one, one);
        assert!(
            (right_two as f32 - right_one as f32 - advance).abs() <= 1.0,
            "the second 1 ends {} px after the first, the advance is {advance}",
            right_two - right_one
        );
    }
}
