//! A series' line at the fractions of a design pixel: plotters maps data to whole design pixels
//! (1/150 in), so that a PNG drawn at 300 dpi drew a gently sloping curve as stairs two pixels
//! high whatever the anti-aliasing. [`FinePath`] carries its points in design pixels with their
//! fractions, mapped by [`Mapping`] as the chart maps them, and a [`FineBackend`] draws them
//! at its own resolution: the PNG back-end at the output's pixels with their fractions
//! ([`super::smooth`]), the SVG back-end rounded to its design pixels.

use super::glyphs::Glyphs;
use super::scaled::Scaled;
use plotters::element::{Drawable, PointCollection};
use plotters::prelude::*;
use plotters_backend::{BackendColor, BackendCoord, DrawingErrorKind};

/// A back-end that draws a polyline given in design pixels with their fractions.
pub(super) trait FineBackend: DrawingBackend {
    /// Draws the polyline `points` (design pixels) in `color`, `width` design pixels wide.
    fn fine_path(
        &mut self,
        points: &[(f64, f64)],
        color: BackendColor,
        width: u32,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>>;
}

/// The SVG's coordinates are whole design pixels.
impl FineBackend for SVGBackend<'_> {
    fn fine_path(
        &mut self,
        points: &[(f64, f64)],
        color: BackendColor,
        width: u32,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let style = ShapeStyle {
            color: RGBAColor(color.rgb.0, color.rgb.1, color.rgb.2, color.alpha),
            filled: false,
            stroke_width: width,
        };
        let whole = points
            .iter()
            .map(|&(x, y)| (x.round() as i32, y.round() as i32));
        self.draw_path(whole, &style)
    }
}

/// The PNG's: the output's pixels with their fractions, the width scaled as every stroke's.
impl FineBackend for Scaled<Glyphs<'_>> {
    fn fine_path(
        &mut self,
        points: &[(f64, f64)],
        color: BackendColor,
        width: u32,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let scale = self.scale;
        let scaled: Vec<(f64, f64)> = points
            .iter()
            .map(|&(x, y)| (x * scale, y * scale))
            .collect();
        let width = self.length(width);
        self.inner.stroke(&scaled, color, width)
    }
}

/// The chart's map from data to design pixels, without rounding: affine in the data, or in
/// their logarithms on log axes, through the pixels plotters gives the ends of the ranges.
#[derive(Clone, Copy, Debug)]
pub(super) struct Mapping {
    /// The x range's ends in the data (or their logarithms) and in pixels.
    pub x: ((f64, f64), (f64, f64)),
    /// The y range's.
    pub y: ((f64, f64), (f64, f64)),
    /// Logarithmic axes.
    pub log: bool,
}

impl Mapping {
    /// `chart`'s map, its ranges `(x0, x1)` and `(y0, y1)` in the data.
    pub fn of<DB: DrawingBackend, X, Y>(
        chart: &ChartContext<'_, DB, Cartesian2d<X, Y>>,
        ((x0, x1), (y0, y1)): ((f64, f64), (f64, f64)),
        log: bool,
    ) -> Mapping
    where
        X: Ranged<ValueType = f64>,
        Y: Ranged<ValueType = f64>,
    {
        let spec = chart.as_coord_spec();
        let (a, b) = (spec.translate(&(x0, y0)), spec.translate(&(x1, y1)));
        let f = |v: f64| if log { v.ln() } else { v };
        let px = |p: BackendCoord| (f64::from(p.0), f64::from(p.1));
        let (a, b) = (px(a), px(b));
        Mapping {
            x: ((f(x0), f(x1)), (a.0, b.0)),
            y: ((f(y0), f(y1)), (a.1, b.1)),
            log,
        }
    }

    /// The design pixel of the data point `(x, y)`, with its fractions.
    pub fn at(&self, (x, y): (f64, f64)) -> (f64, f64) {
        let f = |v: f64| if self.log { v.ln() } else { v };
        let map = |v: f64, ((d0, d1), (p0, p1)): ((f64, f64), (f64, f64))| {
            if d1 == d0 {
                p0
            } else {
                p0 + (f(v) - d0) / (d1 - d0) * (p1 - p0)
            }
        };
        (map(x, self.x), map(y, self.y))
    }
}

/// A polyline in design pixels with their fractions, drawn by a [`FineBackend`].
pub(super) struct FinePath {
    /// The points, design pixels.
    pub points: Vec<(f64, f64)>,
    /// The colour.
    pub color: RGBColor,
    /// The width, design pixels.
    pub width: u32,
}

/// A [`FinePath`] carries no point for the chart to map: it maps its own.
impl<'a> PointCollection<'a, (f64, f64)> for &'a FinePath {
    type Point = &'a (f64, f64);
    type IntoIter = std::iter::Empty<&'a (f64, f64)>;
    fn point_iter(self) -> Self::IntoIter {
        std::iter::empty()
    }
}

impl<DB: FineBackend> Drawable<DB> for FinePath {
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        _: I,
        backend: &mut DB,
        _: (u32, u32),
    ) -> Result<(), DrawingErrorKind<DB::ErrorType>> {
        let color = BackendColor {
            alpha: 1.0,
            rgb: (self.color.0, self.color.1, self.color.2),
        };
        backend.fine_path(&self.points, color, self.width)
    }
}

/// The dashes of the polyline `points` in a pattern of `on` pixels drawn and `off` pixels
/// left, measured along the line from its start.
pub(super) fn dashes(points: &[(f64, f64)], (on, off): (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let period = on + off;
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut current: Vec<(f64, f64)> = Vec::new();
    // How far into the pattern's period the line is.
    let mut phase = 0.0;
    for pair in points.windows(2) {
        let ((ax, ay), (bx, by)) = (pair[0], pair[1]);
        let length = (bx - ax).hypot(by - ay);
        let at = |s: f64| {
            let t = if length > 0.0 { s / length } else { 0.0 };
            (ax + t * (bx - ax), ay + t * (by - ay))
        };
        let mut s = 0.0;
        while s < length {
            if phase < on {
                if current.is_empty() {
                    current.push(at(s));
                }
                let step = (on - phase).min(length - s);
                (s, phase) = (s + step, phase + step);
                current.push(at(s));
                if phase >= on {
                    out.push(std::mem::take(&mut current));
                }
            } else {
                let step = (period - phase).min(length - s);
                (s, phase) = (s + step, phase + step);
                if phase >= period {
                    phase = 0.0;
                }
            }
        }
    }
    if current.len() > 1 {
        out.push(current);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_dashed_line_is_cut_into_dashes_of_its_pattern_across_its_corners() {
        // 10 on, 5 off along an L of 20 + 20 pixels: dashes at 0–10, 15–25 (round the corner),
        // 30–40.
        let l = [(0.0, 0.0), (20.0, 0.0), (20.0, 20.0)];
        let d = dashes(&l, (10.0, 5.0));
        assert_eq!(d.len(), 3, "{d:?}");
        assert_eq!(d[0], [(0.0, 0.0), (10.0, 0.0)]);
        assert_eq!(d[1], [(15.0, 0.0), (20.0, 0.0), (20.0, 5.0)]);
        assert_eq!(d[2], [(20.0, 10.0), (20.0, 20.0)]);
    }

    #[test]
    fn a_mapping_is_affine_in_the_data_or_their_logarithms() {
        let m = Mapping {
            x: ((0.0, 10.0), (100.0, 200.0)),
            y: ((1f64.ln(), 100f64.ln()), (50.0, 10.0)),
            log: true,
        };
        let m = Mapping { log: false, ..m };
        assert_eq!(m.at((2.5, 0.0)).0, 125.0);
        let log = Mapping {
            x: ((1f64.ln(), 100f64.ln()), (100.0, 200.0)),
            y: ((1f64.ln(), 100f64.ln()), (50.0, 10.0)),
            log: true,
        };
        let (x, y) = log.at((10.0, 10.0));
        assert!(
            (x - 150.0).abs() < 1e-9 && (y - 30.0).abs() < 1e-9,
            "{x} {y}"
        );
    }
}
