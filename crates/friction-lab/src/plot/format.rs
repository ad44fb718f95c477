//! The size and resolution of the figures ([`Format`]): a figure is laid out on a design canvas
//! of its size at [`DESIGN_DPI`], where its text has a fixed size in points (axis labels 7.2 pt,
//! axis names 8.2 pt, titles up to 10.6 pt); a PNG is drawn from it at the format's resolution,
//! an SVG states the size in inches.

use crate::error::AppError;

/// The resolution of the design canvas, pixels per inch: the font sizes, margins and line
/// widths of the figures are chosen in its pixels.
pub const DESIGN_DPI: f64 = 150.0;

/// The widths a figure may take, inches (a one-panel figure; panels side by side multiply it).
pub const WIDTH_RANGE: (f64, f64) = (2.0, 20.0);
/// The heights a figure may take, inches.
pub const HEIGHT_RANGE: (f64, f64) = (1.5, 20.0);
/// The resolutions a PNG may take, pixels per inch.
pub const DPI_RANGE: (f64, f64) = (50.0, 1200.0);
/// The most pixels a PNG may hold (three bytes each while drawn).
pub const MAX_PIXELS: f64 = 100e6;

/// The size of a one-panel figure and the resolution of its PNG.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Format {
    /// Width and height of a one-panel figure, inches.
    pub size: (f64, f64),
    /// Resolution of the PNG, pixels per inch.
    pub dpi: f64,
}

impl Default for Format {
    /// A journal's column: 3.5 × 2.6 in (89 mm wide) at 300 dpi, 1050 × 780 pixels (a legend
    /// that covers data goes below the axes and makes the figure higher, not wider).
    fn default() -> Self {
        Format {
            size: (3.5, 2.6),
            dpi: 300.0,
        }
    }
}

impl Format {
    /// The format of `figure_size` `WxH` (inches) and `dpi`, each defaulting to
    /// [`Format::default`]'s; an error names the setting with its value (spelled by each front
    /// end: `--figure-size 3.5`, `figure_size='3.5'`) and the allowed range.
    pub fn parse(size: Option<&str>, dpi: Option<f64>) -> Result<Self, AppError> {
        let default = Format::default();
        let bad = |option: &str, value: &str, allowed: String| {
            AppError::Usage(format!(
                "{}: {allowed}",
                crate::error::setting(option, value)
            ))
        };
        let size = match size {
            None => default.size,
            Some(text) => {
                let shape = || {
                    bad(
                        "figure_size",
                        text,
                        "expected WIDTHxHEIGHT in inches, such as 3.5x2.6".into(),
                    )
                };
                let (w, h) = text.split_once(['x', 'X']).ok_or_else(shape)?;
                let number = |s: &str| s.trim().parse::<f64>().map_err(|_| shape());
                let (w, h) = (number(w)?, number(h)?);
                for (name, v, (lo, hi)) in [("width", w, WIDTH_RANGE), ("height", h, HEIGHT_RANGE)]
                {
                    if !(lo..=hi).contains(&v) {
                        return Err(bad(
                            "figure_size",
                            text,
                            format!("the {name} {v} in is outside [{lo}, {hi}] in"),
                        ));
                    }
                }
                (w, h)
            }
        };
        let dpi = dpi.unwrap_or(default.dpi);
        let (lo, hi) = DPI_RANGE;
        if !(lo..=hi).contains(&dpi) {
            return Err(bad(
                "dpi",
                &friction_models::params::show(dpi),
                format!("outside [{lo}, {hi}]"),
            ));
        }
        let format = Format { size, dpi };
        let (w, h) = format.pixels(format.design(1));
        if f64::from(w) * f64::from(h) > MAX_PIXELS {
            return Err(bad(
                "dpi",
                &friction_models::params::show(dpi),
                format!(
                    "a {}x{} in figure would be {w} x {h} pixels, over the {} million allowed",
                    size.0,
                    size.1,
                    MAX_PIXELS / 1e6
                ),
            ));
        }
        Ok(format)
    }

    /// The design canvas of `panels` one-panel figures side by side, pixels at [`DESIGN_DPI`].
    pub fn design(&self, panels: usize) -> (u32, u32) {
        let px = |inches: f64| (inches * DESIGN_DPI).round() as u32;
        (px(self.size.0) * panels.max(1) as u32, px(self.size.1))
    }

    /// Output pixels per design pixel.
    pub fn scale(&self) -> f64 {
        self.dpi / DESIGN_DPI
    }

    /// The PNG's pixels for a design canvas of `design` pixels.
    pub fn pixels(&self, (w, h): (u32, u32)) -> (u32, u32) {
        let s = |v: u32| (f64::from(v) * self.scale()).round() as u32;
        (s(w), s(h))
    }

    /// An SVG of the design canvas `design` stated in inches: its `width` and `height`
    /// attributes (plotters writes them in pixels) become the figure's size, the canvas
    /// staying its `viewBox`.
    pub fn physical_svg(svg: String, design: (u32, u32)) -> String {
        let inches = |v: u32| f64::from(v) / DESIGN_DPI;
        let (from, to) = (
            format!("width=\"{}\" height=\"{}\"", design.0, design.1),
            format!(
                "width=\"{}in\" height=\"{}in\"",
                inches(design.0),
                inches(design.1)
            ),
        );
        svg.replacen(&from, &to, 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_size_and_a_resolution_are_read_and_checked() {
        let f = Format::parse(Some("3.5x2.6"), Some(300.0)).unwrap();
        assert_eq!(f.design(1), (525, 390));
        assert_eq!(f.pixels(f.design(1)), (1050, 780));
        assert_eq!(f.design(2), (1050, 390));
        assert_eq!(Format::parse(None, None).unwrap(), Format::default());
        assert_eq!(Format::default().design(1), (525, 390));
        let page = Format::parse(Some("6x4"), Some(150.0)).unwrap();
        assert_eq!(page.pixels(page.design(1)), (900, 600));
        let message = |size: Option<&str>, dpi: Option<f64>| {
            Format::parse(size, dpi)
                .unwrap_err()
                .message(&crate::error::as_option)
        };
        assert!(message(Some("3.5"), None).contains("--figure-size 3.5: expected WIDTHxHEIGHT"));
        assert!(message(Some("1x3"), None).contains("the width 1 in is outside [2, 20] in"));
        assert!(message(Some("4x30"), None).contains("the height 30 in is outside [1.5, 20] in"));
        assert!(message(None, Some(10.0)).contains("--dpi 10: outside [50, 1200]"));
        assert!(message(Some("20x20"), Some(1200.0)).contains("over the 100 million allowed"));
        assert!(message(Some("NaNx3"), None).contains("outside"));
    }
}
