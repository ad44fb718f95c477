//! A drawing back-end that draws a figure laid out on its design canvas ([`Format::design`],
//! at [`DESIGN_DPI`]) at another resolution: every coordinate, stroke width, radius and font
//! size is multiplied by dpi / [`DESIGN_DPI`] on the way to the back-end it wraps, so that a
//! figure's layout, and the size of its text in points, do not depend on the resolution.

use plotters_backend::text_anchor::Pos;
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingBackend, DrawingErrorKind,
    FontFamily, FontStyle, FontTransform,
};

/// A back-end drawing at `scale` times the coordinates it is given.
pub struct Scaled<B> {
    /// The back-end drawn on, `scale` times the design canvas.
    pub inner: B,
    /// The design canvas, pixels at [`DESIGN_DPI`].
    pub design: (u32, u32),
    /// Output pixels per design pixel.
    pub scale: f64,
}

impl<B> Scaled<B> {
    /// A point of the design canvas on the output's.
    fn at(&self, (x, y): BackendCoord) -> BackendCoord {
        (
            (x as f64 * self.scale).round() as i32,
            (y as f64 * self.scale).round() as i32,
        )
    }
    /// A length in design pixels in output pixels: at least 1 where it was.
    pub fn length(&self, l: u32) -> u32 {
        ((l as f64 * self.scale).round() as u32).max(l.min(1))
    }

    /// `style` with its width scaled.
    fn stroke<'a, S: BackendStyle>(&self, style: &'a S) -> Stroke<'a, S> {
        Stroke {
            style,
            width: self.length(style.stroke_width()),
        }
    }
}

/// A line style with its width scaled.
struct Stroke<'a, S> {
    style: &'a S,
    width: u32,
}

impl<S: BackendStyle> BackendStyle for Stroke<'_, S> {
    fn color(&self) -> BackendColor {
        self.style.color()
    }
    fn stroke_width(&self) -> u32 {
        self.width
    }
}

/// A text style with its size and layout scaled.
struct Lettering<'a, T> {
    style: &'a T,
    scale: f64,
}

impl<T: BackendTextStyle> BackendTextStyle for Lettering<'_, T> {
    type FontError = T::FontError;
    fn color(&self) -> BackendColor {
        self.style.color()
    }
    fn size(&self) -> f64 {
        self.style.size() * self.scale
    }
    fn transform(&self) -> FontTransform {
        self.style.transform()
    }
    fn style(&self) -> FontStyle {
        self.style.style()
    }
    fn anchor(&self) -> Pos {
        self.style.anchor()
    }
    fn family(&self) -> FontFamily<'_> {
        self.style.family()
    }
    fn layout_box(&self, text: &str) -> Result<((i32, i32), (i32, i32)), Self::FontError> {
        let ((x0, y0), (x1, y1)) = self.style.layout_box(text)?;
        let s = |v: i32| (v as f64 * self.scale).round() as i32;
        Ok(((s(x0), s(y0)), (s(x1), s(y1))))
    }
    fn draw<E, F: FnMut(i32, i32, BackendColor) -> Result<(), E>>(
        &self,
        text: &str,
        pos: BackendCoord,
        draw: F,
    ) -> Result<Result<(), E>, Self::FontError> {
        // Only a back-end that leaves text to its style calls this: at the design size.
        self.style.draw(text, pos, draw)
    }
}

impl<B: DrawingBackend> DrawingBackend for Scaled<B> {
    type ErrorType = B::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.design
    }

    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.ensure_prepared()
    }

    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.present()
    }

    /// A design pixel: the block of output pixels it covers.
    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let (a, b) = (self.at(point), self.at((point.0 + 1, point.1 + 1)));
        if b.0 - a.0 <= 1 && b.1 - a.1 <= 1 {
            return self.inner.draw_pixel(a, color);
        }
        self.inner.draw_rect(a, (b.0 - 1, b.1 - 1), &color, true)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let stroke = self.stroke(style);
        self.inner.draw_line(self.at(from), self.at(to), &stroke)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let stroke = self.stroke(style);
        self.inner
            .draw_rect(self.at(upper_left), self.at(bottom_right), &stroke, fill)
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let stroke = self.stroke(style);
        let points: Vec<BackendCoord> = path.into_iter().map(|p| self.at(p)).collect();
        self.inner.draw_path(points, &stroke)
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let stroke = self.stroke(style);
        self.inner
            .draw_circle(self.at(center), self.length(radius), &stroke, fill)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let points: Vec<BackendCoord> = vert.into_iter().map(|p| self.at(p)).collect();
        self.inner.fill_polygon(points, style)
    }

    fn draw_text<T: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &T,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let lettering = Lettering {
            style,
            scale: self.scale,
        };
        self.inner.draw_text(text, &lettering, self.at(pos))
    }

    fn estimate_text_size<T: BackendTextStyle>(
        &self,
        text: &str,
        style: &T,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        self.inner.estimate_text_size(text, style)
    }
}
