//! PNG text drawn glyph by glyph at the pen position the font defines. plotters 0.3.7 draws
//! each glyph of its `ab_glyph` font at the pen position rounded down and without the glyph's
//! left side bearing (`px_bounds().min.x` is left out), so letters with a wide bearing stand
//! apart ("tim e", "dopri 5"); [`Glyphs`] wraps the bitmap back-end and draws text itself:
//! every glyph outlined at its exact pen position (advances and kerning as the font gives
//! them), at the vertical position plotters uses. Lines, paths and circles are drawn
//! anti-aliased ([`smooth`]); everything else is the bitmap back-end's.

use super::smooth;
use ab_glyph::{Font, FontRef, ScaleFont};
use plotters::prelude::BitMapBackend;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingBackend, DrawingErrorKind,
};
use std::sync::OnceLock;

/// The one font of the figures, DejaVu Sans (the font registered with plotters as
/// `sans-serif`), parsed once.
fn font() -> &'static FontRef<'static> {
    static FONT: OnceLock<FontRef<'static>> = OnceLock::new();
    FONT.get_or_init(|| {
        FontRef::try_from_slice(dejavu::sans::regular())
            .unwrap_or_else(|_| unreachable!("the embedded DejaVu Sans font is valid"))
    })
}

/// Calls `put(x, y, coverage)` for every pixel of `text` at `size` pixels, x from the pen's
/// start, y as plotters places it (half the size below the top, plus the glyph's own top).
pub fn rasterize(text: &str, size: f64, mut put: impl FnMut(i32, i32, f32)) {
    let font = font().as_scaled(size as f32);
    let (mut pen, mut previous) = (0.0f32, None);
    for c in text.chars() {
        let id = font.glyph_id(c);
        if let Some(p) = previous {
            pen += font.kern(p, id);
        }
        previous = Some(id);
        let glyph = id.with_scale_and_position(font.scale(), ab_glyph::point(pen, 0.0));
        if let Some(outline) = font.outline_glyph(glyph) {
            let bounds = outline.px_bounds();
            let (x0, y0) = (
                bounds.min.x as i32,
                (size as f32 / 2.0 + bounds.min.y) as i32,
            );
            outline.draw(|x, y, coverage| put(x0 + x as i32, y0 + y as i32, coverage));
        }
        pen += font.h_advance(id);
    }
}

/// The bitmap back-end with text drawn by [`rasterize`].
pub struct Glyphs<'a>(pub BitMapBackend<'a>);

impl Glyphs<'_> {
    /// The polyline `points`, pixels with their fractions, in `color`, `width` pixels wide,
    /// anti-aliased ([`smooth::stroke`]).
    pub fn stroke(
        &mut self,
        points: &[(f64, f64)],
        color: BackendColor,
        width: u32,
    ) -> Result<(), DrawingErrorKind<<Self as DrawingBackend>::ErrorType>> {
        if color.alpha == 0.0 {
            return Ok(());
        }
        let inked = smooth::stroke(points, width, self.get_size());
        for ((x, y), coverage) in inked {
            self.0.draw_pixel((x, y), color.mix(f64::from(coverage)))?;
        }
        Ok(())
    }
}

impl DrawingBackend for Glyphs<'_> {
    type ErrorType = <BitMapBackend<'static> as DrawingBackend>::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }

    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.ensure_prepared()
    }

    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.present()
    }

    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_pixel(point, color)
    }

    /// Anti-aliased ([`smooth::stroke`]).
    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.draw_path([from, to], style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_rect(upper_left, bottom_right, style, fill)
    }

    /// Anti-aliased, with round joins and caps ([`smooth::stroke`]).
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let points: Vec<(f64, f64)> = (path.into_iter())
            .map(|(x, y)| (f64::from(x), f64::from(y)))
            .collect();
        self.stroke(&points, style.color(), style.stroke_width())
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.fill_polygon(vert, style)
    }

    /// Anti-aliased ([`smooth::circle`]).
    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        let size = self.get_size();
        let mut result = Ok(());
        smooth::circle(
            center,
            radius,
            style.stroke_width(),
            fill,
            size,
            |x, y, c| {
                if result.is_ok() {
                    result = self.0.draw_pixel((x, y), color.mix(f64::from(c)));
                }
            },
        );
        result
    }

    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        (w, h): (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.blit_bitmap(pos, (w, h), src)
    }

    /// As plotters' own `draw_text` (the anchor from the layout box, then the rotation), with
    /// the glyphs of [`rasterize`].
    fn draw_text<TStyle: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &TStyle,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        let ((min_x, min_y), (max_x, max_y)) = style
            .layout_box(text)
            .map_err(|e| DrawingErrorKind::FontError(Box::new(e)))?;
        let (width, height) = (max_x - min_x, max_y - min_y);
        let dx = match style.anchor().h_pos {
            HPos::Left => 0,
            HPos::Right => -width,
            HPos::Center => -width / 2,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0,
            VPos::Center => -height / 2,
            VPos::Bottom => -height,
        };
        let transform = style.transform();
        let (w, h) = self.get_size();
        let mut result = Ok(());
        rasterize(text, style.size(), |x, y, coverage| {
            let (x, y) = transform.transform(x + dx - min_x, y + dy - min_y);
            let (x, y) = (pos.0 + x, pos.1 + y);
            if result.is_ok() && x >= 0 && x < w as i32 && y >= 0 && y < h as i32 {
                result = self.0.draw_pixel((x, y), color.mix(f64::from(coverage)));
            }
        });
        result
    }
}

#[cfg(test)]
mod tests {
    use super::{font, rasterize};
    use ab_glyph::{Font, ScaleFont};

    /// The leftmost inked column of `text` at `size` at or right of column `from`.
    fn left_ink(text: &str, size: f64, from: i32) -> i32 {
        let mut left = i32::MAX;
        rasterize(text, size, |x, _, coverage| {
            if coverage > 0.0 && x >= from {
                left = left.min(x);
            }
        });
        left
    }

    #[test]
    fn each_glyph_is_drawn_at_its_pen_position_plus_its_side_bearing() {
        // At 100 px: every letter's ink begins where the font puts it, the advances and kerning
        // of the letters before it plus its own left side bearing (plotters' own drawing
        // leaves the bearing out: "tim e").
        let size = 100.0;
        let scaled = font().as_scaled(size as f32);
        // First letters whose ink ends well before their advance, so that only the second
        // letter is inked right of the pen.
        for text in ["iX", "lm", "ie", "l5", "i("] {
            let mut chars = text.chars();
            let (a, b) = (chars.next().unwrap(), chars.next().unwrap());
            let (a, b) = (scaled.glyph_id(a), scaled.glyph_id(b));
            let pen = scaled.h_advance(a) + scaled.kern(a, b);
            let expected = (pen + scaled.h_side_bearing(b)).floor() as i32;
            let from = pen.ceil() as i32;
            let found = left_ink(text, size, from.min(expected));
            assert!(
                (found - expected).abs() <= 1,
                "{text}: the second glyph's ink begins at {found} px, the font puts it at \
                 {expected} px (bearing {} px)",
                scaled.h_side_bearing(b)
            );
        }
    }
}
