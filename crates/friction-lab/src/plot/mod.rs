//! Line plots as PNG and SVG, drawn by plotters with an embedded DejaVu Sans font so that
//! no system font package is needed: the plot and its series, drawn on linear or log axes
//! (`axes`: ranges, ticks, labels), with a legend (`legend`: where it goes); and a raster of
//! coloured cells (`raster`). Every figure is laid out on the design canvas of its
//! [`Format`] and drawn at the format's resolution (`scaled`); an SVG names its font.

mod axes;
mod check;
mod fine;
mod format;
mod frame;
mod glyphs;
mod legend;
mod raster;
mod scaled;
mod smooth;

use crate::error::AppError;
use axes::{common_decimals, fixed, log_ticks, sample_ticks, tick_label, TickForm};
pub use check::layout_faults;
use fine::{dashes, FineBackend, FinePath, Mapping};
pub use format::{Format, DESIGN_DPI, MAX_PIXELS};
use frame::{Frame, Lines, MARGIN, TICK_SIZE};
use glyphs::Glyphs;
pub use legend::Corner;
use legend::{
    draw_legend_in_strip, filled_key, is_filled, key, layout, legend_pixels, shape, Arrangement,
    LegendPlace, LegendTarget, KEY_AREA, LEGEND_BOX, LEGEND_FONT,
};
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
pub use raster::{raster_png, raster_svg, Raster};
use scaled::Scaled;
use std::path::Path;
use std::sync::Once;

/// The family of the one font of the figures, DejaVu Sans (embedded), as SVG files name it.
pub const FAMILY: &str = "DejaVu Sans";

/// The fonts an SVG names after [`FAMILY`], for a reader without DejaVu Sans: sans-serif
/// faces of close metrics.
const FALLBACK_FAMILIES: &str = "Verdana, Arial, sans-serif";

/// One polyline of a plot.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend entry; `None` keeps the series out of the legend.
    pub label: Option<String>,
    /// The points, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Line colour.
    pub color: RGBColor,
    /// Line width, pixels (0: no line, markers only).
    pub width: u32,
    /// How each point is marked.
    pub marker: Marker,
    /// How its line is drawn.
    pub dash: Dash,
}

/// How the line of a series is drawn: a pattern as well as a colour tells series apart in
/// greyscale.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Dash {
    /// A solid line.
    #[default]
    Solid,
    /// Dashes of 10 pixels, 5 apart.
    Dashed,
    /// Dots of 2 pixels, 4 apart.
    Dotted,
    /// Long dashes of 18 pixels, 6 apart.
    LongDashed,
}

impl Dash {
    /// Every pattern, in the order series take them.
    pub const ALL: [Dash; 4] = [Dash::Solid, Dash::Dashed, Dash::Dotted, Dash::LongDashed];

    /// Dash length and gap, pixels; `None` for a solid line.
    pub(super) fn pattern(self) -> Option<(u32, u32)> {
        match self {
            Dash::Solid => None,
            Dash::Dashed => Some((10, 5)),
            Dash::Dotted => Some((2, 4)),
            Dash::LongDashed => Some((18, 6)),
        }
    }
}

/// How the points of a series are marked.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Marker {
    /// Not at all (a curve).
    #[default]
    None,
    /// A filled dot (a computed run).
    Dot,
    /// A cross (a run that failed or did not reach its target).
    Cross,
    /// An open circle, drawn around a point that a [`Marker::Dot`] of another series may
    /// fill (a second branch of the same diagram).
    Ring,
    /// A filled square (a computed run, told apart from the dots in greyscale).
    Square,
    /// A filled triangle, point up.
    Triangle,
    /// A filled diamond.
    Diamond,
}

impl Marker {
    /// The filled shapes a computed run is drawn with, in the order series take them.
    pub const FILLED: [Marker; 4] = [
        Marker::Dot,
        Marker::Square,
        Marker::Triangle,
        Marker::Diamond,
    ];
}

/// A labelled line plot.
#[derive(Clone, Debug, PartialEq)]
pub struct Plot {
    /// Title above the plot.
    pub title: String,
    /// x-axis label, with unit.
    pub x_label: String,
    /// y-axis label, with unit.
    pub y_label: String,
    /// The polylines.
    pub series: Vec<Series>,
    /// Where the legend goes.
    pub legend: Corner,
    /// Logarithmic axes (x and y), with the data in their own units; non-positive values
    /// are left out. Linear axes draw the axes through the origin, as the paper's figures.
    pub log: bool,
}

/// The labels plotters' mesh puts on each axis by default (`MeshStyle`'s `n_x_labels` and
/// `n_y_labels`, 11 in plotters 0.3.7's `chart/mesh.rs`; with 10 the check of whole numbers
/// saw the ticks 5, 6, … where the mesh labelled 5, 5.5, 6, … and wrote "5, 5, 6").
const MESH_LABELS: usize = 11;

/// The colours of the figures: the paper's red for the model, blue and green beside it.
pub const RED: RGBColor = RGBColor(200, 30, 30);
/// Second series colour.
pub const BLUE: RGBColor = RGBColor(30, 80, 200);
/// Third series colour.
pub const GREEN: RGBColor = RGBColor(20, 140, 60);

/// Colours for figures with several series, in order: one for each of a study's twelve
/// methods at most (the ten solvers, and a system's regularised BDF and time-stepping).
pub const PALETTE: [RGBColor; 12] = [
    RED,
    BLUE,
    GREEN,
    RGBColor(230, 130, 0),
    RGBColor(130, 50, 170),
    RGBColor(90, 90, 90),
    RGBColor(0, 160, 170),
    RGBColor(140, 90, 40),
    RGBColor(220, 60, 150),
    RGBColor(150, 160, 0),
    RGBColor(40, 40, 120),
    RGBColor(120, 200, 230),
];

static FONT: Once = Once::new();

fn register_font() {
    FONT.call_once(|| {
        plotters::style::register_font(FAMILY, FontStyle::Normal, dejavu::sans::regular())
            .unwrap_or_else(|_| unreachable!("the embedded DejaVu Sans font is valid"));
    });
}

/// The points of a plot that can be drawn on its axes: finite, and positive on log axes.
fn drawable(plot: &Plot) -> impl Iterator<Item = (f64, f64)> + '_ {
    plot.series.iter().flat_map(|s| drawn(plot, s))
}

/// The points of series `s` of `plot` that can be drawn ([`drawable`]).
fn drawn<'a>(plot: &'a Plot, s: &'a Series) -> impl Iterator<Item = (f64, f64)> + 'a {
    s.points.iter().copied().filter(move |(x, y)| {
        x.is_finite() && y.is_finite() && (!plot.log || (*x > 0.0 && *y > 0.0))
    })
}

/// The design width of each panel of `plots`: a one-panel figure of `panel` pixels, and on
/// top of it the strip of a legend that goes beside the plot, so that the legend takes no
/// width from the data.
fn panel_widths(plots: &[Plot], panel: (u32, u32)) -> Vec<u32> {
    (plots.iter())
        .map(|plot| match layout(plot, panel).1 {
            LegendPlace::Beside => panel.0 + strip_width(plot),
            LegendPlace::Inside(_) | LegendPlace::Below(_) => panel.0,
        })
        .collect()
}

/// The width of the strip a legend beside `plot` takes, pixels.
fn strip_width(plot: &Plot) -> u32 {
    legend_pixels(plot, Arrangement::ONE).0.ceil() as u32 + LEGEND_BOX.gap as u32
}

/// The height of the strip a legend below `plot` set in `arrangement` takes, pixels.
fn below_height(plot: &Plot, arrangement: Arrangement) -> u32 {
    legend_pixels(plot, arrangement).1.ceil() as u32 + LEGEND_BOX.gap as u32
}

/// The most panels side by side, a page's width of column-sized panels: more wrap into rows.
pub const PANELS_PER_ROW: usize = 2;

/// The cells of a figure of panels, design pixels: the width of each column of panels (its
/// widest panel with the strip of a legend beside it) and the height of each row (a panel and
/// the tallest legend below one of its panels), [`PANELS_PER_ROW`] panels a row.
fn cells(plots: &[Plot], panel: (u32, u32)) -> (Vec<u32>, Vec<u32>) {
    let per_row = PANELS_PER_ROW.min(plots.len()).max(1);
    let widths = panel_widths(plots, panel);
    let below: Vec<u32> = (plots.iter())
        .map(|plot| match layout(plot, panel).1 {
            LegendPlace::Below(arrangement) => below_height(plot, arrangement),
            _ => 0,
        })
        .collect();
    let columns = (0..per_row)
        .map(|j| {
            (widths.iter().skip(j).step_by(per_row))
                .copied()
                .max()
                .unwrap_or(panel.0)
        })
        .collect();
    let rows = (below.chunks(per_row))
        .map(|row| panel.1 + row.iter().copied().max().unwrap_or(0))
        .collect();
    (columns, rows)
}

/// The design canvas of `plots` in `format`: its panels in rows ([`cells`]).
fn canvas(plots: &[Plot], format: &Format) -> (u32, u32) {
    let panel = format.design(1);
    let (columns, rows) = cells(plots, panel);
    (
        columns.iter().sum::<u32>().max(panel.0),
        rows.iter().sum::<u32>().max(panel.1),
    )
}

/// The pixels of the PNG of `plots` in rows of panels in `format`: its whole canvas, every panel
/// and a legend below included.
pub fn png_pixels(plots: &[Plot], format: &Format) -> f64 {
    let (w, h) = format.pixels(canvas(plots, format));
    f64::from(w) * f64::from(h)
}

/// Draws `plots` on `root` in rows of [`PANELS_PER_ROW`] ([`cells`]), each on a panel of
/// `panel` pixels and its legend's strip ([`panel_widths`]).
fn draw<DB: FineBackend>(
    root: DrawingArea<DB, Shift>,
    plots: &[Plot],
    panel: (u32, u32),
) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let (columns, rows) = cells(plots, panel);
    let breaks = |sizes: &[u32]| -> Vec<u32> {
        (sizes.iter())
            .scan(0, |x, w| {
                *x += w;
                Some(*x)
            })
            .take(sizes.len().saturating_sub(1))
            .collect()
    };
    let panels = root.split_by_breakpoints(breaks(&columns), breaks(&rows));
    for (whole, plot) in panels.iter().zip(plots) {
        let (((x0, x1), (y0, y1)), legend) = layout(plot, panel);
        // A legend beside the plot takes the strip right of the panel, one below it the strip
        // under it (every panel is as high as a one-panel figure above that strip).
        let (upper, lower) = whole.split_vertically(panel.1);
        let strip;
        let (area, target) = match legend {
            LegendPlace::Beside => {
                let (a, b) = upper.split_horizontally(panel.0);
                strip = b;
                (a, LegendTarget::Strip(&strip))
            }
            LegendPlace::Below(arrangement) => (upper, LegendTarget::Below(&lower, arrangement)),
            LegendPlace::Inside(c) => (upper, LegendTarget::Corner(c)),
        };
        let frame = Frame::of(plot, panel);
        draw_title(&area, &frame.title).map_err(err)?;
        let inner = area.margin(MARGIN + frame.title.title_height(), MARGIN, MARGIN, MARGIN);
        let mut builder = ChartBuilder::on(&inner);
        builder
            .x_label_area_size(frame.x_area)
            .y_label_area_size(frame.y_area);
        if plot.log {
            let axis = |a: f64, b: f64, ticks: Vec<f64>| {
                (a..b)
                    .log_scale()
                    .with_key_points(ticks.clone())
                    .with_light_points(ticks)
            };
            let x_ticks = sample_ticks(plot, x0, x1).unwrap_or_else(|| log_ticks(x0, x1));
            let y_ticks = log_ticks(y0, y1);
            let forms = (TickForm::of(&x_ticks), TickForm::of(&y_ticks));
            let chart = builder
                .build_cartesian_2d(axis(x0, x1, x_ticks), axis(y0, y1, y_ticks))
                .map_err(err)?;
            draw_axis_names(&chart, &inner, &frame).map_err(err)?;
            draw_on(chart, plot, target, Some(forms))?;
        } else {
            let chart = builder.build_cartesian_2d(x0..x1, y0..y1).map_err(err)?;
            draw_axis_names(&chart, &inner, &frame).map_err(err)?;
            draw_on(chart, plot, target, None)?;
        }
    }
    root.present().map_err(err)
}

/// A whole number's tick label.
fn whole_label(v: &f64) -> String {
    format!("{}", *v as i64)
}

/// The lines of a panel's `title`, centred above its plotting area inside the margin, each
/// padded as plotters pads a caption.
fn draw_title<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &Lines,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let style =
        TextStyle::from((FAMILY, title.size).into_font()).pos(Pos::new(HPos::Center, VPos::Top));
    let centre = area.dim_in_pixel().0 as i32 / 2;
    let pitch = title.title_height() as i32 / title.lines.len().max(1) as i32;
    for (k, line) in title.lines.iter().enumerate() {
        let top = (MARGIN as i32) + 5 + k as i32 * pitch;
        area.draw(&Text::new(line.as_str(), (centre, top), &style))?;
    }
    Ok(())
}

/// The axes' names of `frame` in the label areas of `chart`, built on `root`: the x name's last line at the
/// bottom of its area, centred under the plotting area; the y name turned a quarter left, its
/// first line at the left of its area, centred beside the plotting area.
fn draw_axis_names<DB: DrawingBackend, X: Ranged, Y: Ranged>(
    chart: &ChartContext<'_, DB, Cartesian2d<X, Y>>,
    root: &DrawingArea<DB, Shift>,
    frame: &Frame,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (xs, ys) = chart.plotting_area().get_pixel_range();
    let (bx, by) = root.get_base_pixel();
    // The plotting area in the pixels of `root`, the area the chart was built on.
    let (xs, ys) = ((xs.start - bx, xs.end - bx), (ys.start - by, ys.end - by));
    let x_style = TextStyle::from((FAMILY, frame.x_name.size).into_font())
        .pos(Pos::new(HPos::Center, VPos::Bottom));
    let n = frame.x_name.lines.len() as i32;
    let pitch = frame.x_name.pitch() as i32;
    let bottom = ys.1 + frame.x_area as i32;
    for (k, line) in frame.x_name.lines.iter().enumerate() {
        let y = bottom - (n - 1 - k as i32) * pitch;
        root.draw(&Text::new(line.as_str(), ((xs.0 + xs.1) / 2, y), &x_style))?;
    }
    let y_style = TextStyle::from((FAMILY, frame.y_name.size).into_font())
        .transform(FontTransform::Rotate270)
        .pos(Pos::new(HPos::Center, VPos::Top));
    let pitch = frame.y_name.pitch() as i32;
    let left = xs.0 - frame.y_area as i32;
    for (k, line) in frame.y_name.lines.iter().enumerate() {
        let at = (left + k as i32 * pitch, (ys.0 + ys.1) / 2);
        root.draw(&Text::new(line.as_str(), at, &y_style))?;
    }
    Ok(())
}

/// The mesh, the series with their markers, and the legend, on linear or log axes (each log
/// axis labelled in its `log_forms` form).
fn draw_on<'a, DB, X, Y>(
    mut chart: ChartContext<'a, DB, Cartesian2d<X, Y>>,
    plot: &Plot,
    legend: LegendTarget<'_, DB>,
    log_forms: Option<(TickForm, TickForm)>,
) -> Result<(), String>
where
    DB: FineBackend + 'a,
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let (x_form, y_form) = log_forms.unwrap_or((TickForm::Decimal, TickForm::Decimal));
    let x_log_tick = |v: &f64| tick_label(*v, x_form);
    let y_log_tick = |v: &f64| tick_label(*v, y_form);
    // A linear axis's tick at zero computed as a sum of steps can be a rounding below it, which
    // plotters labels "-0.0": such a tick is labelled as zero.
    let (xr, yr) = (chart.x_range(), chart.y_range());
    let zero = |v: f64, r: &std::ops::Range<f64>| {
        if v.abs() <= 1e-9 * r.start.abs().max(r.end.abs()) {
            0.0
        } else {
            v
        }
    };
    // Each linear axis writes all its labels with one number of decimals (`common_decimals`
    // of the ticks the mesh labels); plotters writes "0.0" beside "0.05", and "8.0".
    let decimals = |keys: Vec<f64>| common_decimals(&keys);
    let spec = chart.as_coord_spec();
    let (x_decimals, y_decimals) = (
        decimals(spec.x_spec().key_points(MESH_LABELS)),
        decimals(spec.y_spec().key_points(MESH_LABELS)),
    );
    let linear = |v: f64, decimals: Option<usize>, format: fn(&f64) -> String| match decimals {
        Some(d) => fixed(v, d),
        None => format(&v),
    };
    let x_tick = |v: &f64| linear(zero(*v, &xr), x_decimals, X::format);
    let y_tick = |v: &f64| linear(zero(*v, &yr), y_decimals, Y::format);
    let mut mesh = chart.configure_mesh();
    mesh.light_line_style(WHITE)
        .label_style((FAMILY, TICK_SIZE));
    if plot.log {
        mesh.x_label_formatter(&x_log_tick)
            .y_label_formatter(&y_log_tick);
    } else {
        mesh.x_label_formatter(&x_tick).y_label_formatter(&y_tick);
    }
    mesh.draw().map_err(err)?;
    if !plot.log {
        // The axes through the origin, as in the paper's figures, where the origin is in
        // range (a line far outside would map beyond the pixels plotters can address).
        let (xr, yr) = (chart.x_range(), chart.y_range());
        let axis = ShapeStyle::from(&BLACK.mix(0.4)).stroke_width(1);
        if yr.contains(&0.0) {
            chart
                .draw_series(LineSeries::new([(xr.start, 0.0), (xr.end, 0.0)], axis))
                .map_err(err)?;
        }
        if xr.contains(&0.0) {
            chart
                .draw_series(LineSeries::new([(0.0, yr.start), (0.0, yr.end)], axis))
                .map_err(err)?;
        }
    }
    let (xr, yr) = (chart.x_range(), chart.y_range());
    let mapping = Mapping::of(&chart, ((xr.start, xr.end), (yr.start, yr.end)), plot.log);
    for s in &plot.series {
        let points: Vec<(f64, f64)> = drawn(plot, s).collect();
        let (color, marker, width, dash) = (s.color, s.marker, s.width, s.dash);
        let drawn = if s.width > 0 {
            // At the fractions of a design pixel, dash by dash ([`fine`]).
            let line: Vec<(f64, f64)> = points.iter().map(|&p| mapping.at(p)).collect();
            let paths = match s.dash.pattern() {
                None => vec![line],
                Some((on, off)) => dashes(&line, (f64::from(on), f64::from(off))),
            };
            chart
                .draw_series(paths.into_iter().map(|points| FinePath {
                    points,
                    color,
                    width,
                }))
                .map_err(err)?
        } else {
            chart
                .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
                .map_err(err)?
        };
        if let Some(label) = &s.label {
            let drawn = drawn.label(label.as_str());
            if is_filled(marker) {
                drawn.legend(move |p| {
                    let (line, filled) = filled_key(color, marker, width, dash);
                    EmptyElement::at(p) + line + filled
                });
            } else {
                drawn.legend(move |p| {
                    let (line, cross, dot, ring) = key(color, marker, width);
                    EmptyElement::at(p) + line + cross + dot + ring
                });
            }
        }
        match marker {
            Marker::None => {}
            Marker::Dot => {
                chart
                    .draw_series(points.iter().map(|&p| Circle::new(p, 4, color.filled())))
                    .map_err(err)?;
            }
            Marker::Cross => {
                chart
                    .draw_series(
                        points
                            .iter()
                            .map(|&p| Cross::new(p, 6, color.stroke_width(2))),
                    )
                    .map_err(err)?;
            }
            Marker::Ring => {
                chart
                    .draw_series((points.iter()).map(|&p| Circle::new(p, 6, color.stroke_width(2))))
                    .map_err(err)?;
            }
            Marker::Square | Marker::Triangle | Marker::Diamond => {
                chart
                    .draw_series(
                        (points.iter()).map(|&p| EmptyElement::at(p) + shape(marker, color)),
                    )
                    .map_err(err)?;
            }
        }
    }
    if !plot.series.iter().any(|s| s.label.is_some()) {
        return Ok(());
    }
    match legend {
        LegendTarget::Corner(corner) => chart
            .configure_series_labels()
            .label_font(LEGEND_FONT)
            .legend_area_size(KEY_AREA)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(match corner {
                Corner::UpperLeft => SeriesLabelPosition::UpperLeft,
                Corner::UpperRight => SeriesLabelPosition::UpperRight,
                Corner::LowerLeft => SeriesLabelPosition::LowerLeft,
                Corner::LowerRight => SeriesLabelPosition::LowerRight,
            })
            .draw()
            .map_err(err),
        LegendTarget::Strip(area) => {
            // Level with the plotting area's top (both in the panel's pixels).
            let top = chart.plotting_area().get_base_pixel().1 - area.get_base_pixel().1;
            draw_legend_in_strip(
                area,
                plot,
                Arrangement::ONE,
                (0, top + LEGEND_BOX.gap as i32),
            )
        }
        LegendTarget::Below(area, arrangement) => {
            // Level with the plotting area's left.
            let left = chart.plotting_area().get_base_pixel().0 - area.get_base_pixel().0;
            draw_legend_in_strip(area, plot, arrangement, (left, 0))
        }
    }
}

/// The plot as SVG text.
pub fn svg(plot: &Plot, path: &Path, format: &Format) -> Result<String, AppError> {
    svg_panels(std::slice::from_ref(plot), path, format)
}

/// Plots in rows of panels ([`PANELS_PER_ROW`] a row) as SVG text.
pub fn svg_panels(plots: &[Plot], path: &Path, format: &Format) -> Result<String, AppError> {
    let panel = format.design(1);
    render_svg(canvas(plots, format), path, |root| draw(root, plots, panel))
}

/// The plot as PNG bytes.
pub fn png(plot: &Plot, path: &Path, format: &Format) -> Result<Vec<u8>, AppError> {
    png_panels(std::slice::from_ref(plot), path, format)
}

/// Plots in rows of panels as PNG bytes.
pub fn png_panels(plots: &[Plot], path: &Path, format: &Format) -> Result<Vec<u8>, AppError> {
    let panel = format.design(1);
    render_png(canvas(plots, format), format, path, |root| {
        draw(root, plots, panel)
    })
}

/// What `paint` draws on an SVG canvas of `design` pixels, as text, its size stated in inches
/// and its font named with fallbacks; a drawing error names the figure's `path`.
fn render_svg(
    design: (u32, u32),
    path: &Path,
    paint: impl FnOnce(DrawingArea<SVGBackend, Shift>) -> Result<(), String>,
) -> Result<String, AppError> {
    register_font();
    let mut text = String::new();
    paint(SVGBackend::with_string(&mut text, design).into_drawing_area())
        .map_err(|message| plot_error(path, message))?;
    let named = text.replace(
        &format!("font-family=\"{FAMILY}\""),
        &format!("font-family=\"{FAMILY}, {FALLBACK_FAMILIES}\""),
    );
    Ok(Format::physical_svg(named, design))
}

/// What `paint` draws on a design canvas of `design` pixels, as PNG bytes at the resolution of
/// `format`; a drawing error names the figure's `path`.
fn render_png(
    design: (u32, u32),
    format: &Format,
    path: &Path,
    paint: impl FnOnce(DrawingArea<Scaled<Glyphs>, Shift>) -> Result<(), String>,
) -> Result<Vec<u8>, AppError> {
    register_font();
    let (w, h) = format.pixels(design);
    let mut pixels = vec![0u8; (w as usize) * (h as usize) * 3];
    let backend = Scaled {
        inner: Glyphs(BitMapBackend::with_buffer(&mut pixels, (w, h))),
        design,
        scale: format.scale(),
    };
    paint(backend.into_drawing_area()).map_err(|message| plot_error(path, message))?;
    encode_png(&pixels, (w, h), path)
}

/// The error of drawing the figure at `path`.
fn plot_error(path: &Path, message: String) -> AppError {
    AppError::Plot {
        path: path.to_path_buf(),
        message,
    }
}

/// RGB pixels of a `w × h` image as PNG bytes.
fn encode_png(pixels: &[u8], (w, h): (u32, u32), path: &Path) -> Result<Vec<u8>, AppError> {
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, w, h);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    // Fast deflate: figures are a few tens of kB either way, and Best cost a fifth of
    // `reproduce`'s instructions.
    encoder.set_compression(png::Compression::Fast);
    encoder
        .write_header()
        .and_then(|mut writer| writer.write_image_data(pixels))
        .map_err(|e| plot_error(path, e.to_string()))?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use axes::bounds;
    use legend::BESIDE_MIN_WIDTH;

    #[test]
    fn a_long_title_is_set_smaller_then_on_two_lines_to_fit_its_panel() {
        let gms = "gms: generalized Maxwell-slip (Al-Bender et al. 2005) (Al-Bender, Lampaert, \
                   Swevers (2005), IEEE TAC 50(11))";
        let plot = |title: &str| Plot {
            title: title.into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![],
            legend: Corner::default(),
            log: false,
        };
        let width = |size: u32, text: &str| (FAMILY, size).into_font().box_size(text).unwrap().0;
        // A page-wide panel (6 in, 900 px): one line, at the largest size that fits.
        let page = Frame::of(&plot(gms), (900, 600)).title;
        assert_eq!(page.lines, [gms]);
        assert!(
            width(page.size, gms) + 50 <= 900,
            "{}",
            width(page.size, gms)
        );
        assert!(
            width(page.size + 1, gms) + 50 > 900,
            "the largest that fits"
        );
        let short = Frame::of(&plot("Work-precision: belt with CS"), (900, 600)).title;
        assert_eq!(short.size, frame::TITLE_SIZES.0);
        // A column (3.5 in, 525 px): two lines at the smallest size, the whole title kept.
        let column = Format::default().design(1);
        let two = Frame::of(&plot(gms), column).title;
        assert_eq!((two.lines.len(), two.size), (2, frame::TITLE_SIZES.1));
        assert_eq!(two.lines.join(" "), gms);
        for line in &two.lines {
            assert!(width(two.size, line) + 50 <= column.0, "{line}");
        }
    }

    /// The visible circles of an SVG: plotters writes a transparent one as `opacity="0"`.
    fn visible_circles(svg: &str) -> usize {
        svg.split("<circle")
            .skip(1)
            .filter(|c| !c.split('>').next().unwrap_or("").contains("opacity=\"0\""))
            .count()
    }

    #[test]
    fn a_legend_shows_the_marker_its_series_draws() {
        // Three dots and no line: the legend's key is a dot too (it was a line), in a legend
        // inside the axes and in one beside them (a long label does not fit inside).
        for label in [
            "dots",
            &"a label too long for any corner of the plot ".repeat(4),
        ] {
            let plot = Plot {
                title: "markers".into(),
                x_label: "x".into(),
                y_label: "y".into(),
                series: vec![Series {
                    label: Some(label.to_string()),
                    points: vec![(1.0, 1.0), (2.0, 2.0), (3.0, 1.5)],
                    color: RED,
                    width: 0,
                    marker: Marker::Dot,
                    dash: crate::plot::Dash::Solid,
                }],
                legend: Corner::UpperRight,
                log: false,
            };
            let text = svg(&plot, Path::new("markers.svg"), &Format::default()).unwrap();
            assert_eq!(visible_circles(&text), 3 + 1, "{label}");
            // A curve's key is no dot.
            let curve = Plot {
                series: vec![Series {
                    marker: Marker::None,
                    dash: crate::plot::Dash::Solid,
                    width: 2,
                    ..plot.series[0].clone()
                }],
                ..plot
            };
            let text = svg(&curve, Path::new("curve.svg"), &Format::default()).unwrap();
            assert_eq!(visible_circles(&text), 0, "{label}");
        }
    }

    #[test]
    fn half_ticks_keep_their_decimals() {
        // Time from 5 to 10 s: the mesh labels every half second, so no label loses its
        // decimals ("5, 5, 6, 6" before).
        let plot = Plot {
            title: "window".into(),
            x_label: "t".into(),
            y_label: "v".into(),
            series: vec![Series {
                label: None,
                points: (0..=50).map(|i| (5.0 + 0.1 * f64::from(i), 1.0)).collect(),
                color: RED,
                width: 1,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            }],
            legend: Corner::default(),
            log: false,
        };
        let text = svg(&plot, Path::new("window.svg"), &Format::default()).unwrap();
        let texts: Vec<&str> = (text.split("<text").skip(1))
            .filter_map(|t| Some(t.split_once('>')?.1.split("</text>").next()?.trim()))
            .collect();
        assert!(
            texts.contains(&"5.5") && texts.contains(&"6.0"),
            "{texts:?}"
        );
        assert_eq!(texts.iter().filter(|t| **t == "5").count(), 0, "{texts:?}");
    }

    #[test]
    fn a_linear_axis_of_whole_numbers_is_labelled_without_decimals() {
        // Body indices 1 to 10 against time 0 to 0.6 s: the y labels read "8", not "8.0";
        // the x labels keep their decimals.
        let plot = Plot {
            title: "indices".into(),
            x_label: "t".into(),
            y_label: "body".into(),
            series: vec![Series {
                label: None,
                points: (1..=10).map(|i| (0.06 * i as f64, i as f64)).collect(),
                color: RED,
                width: 1,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            }],
            legend: Corner::default(),
            log: false,
        };
        let text = svg(&plot, Path::new("indices.svg"), &Format::default()).unwrap();
        // The texts of the SVG, each written as <text …>\nTEXT\n</text>.
        let texts: Vec<&str> = (text.split("<text").skip(1))
            .filter_map(|t| Some(t.split_once('>')?.1.split("</text>").next()?.trim()))
            .collect();
        assert!(texts.contains(&"8") && !texts.contains(&"8.0"), "{texts:?}");
        assert!(texts.contains(&"0.5"), "{texts:?}");
    }

    /// The width, height and RGB pixels of a PNG.
    fn decoded(bytes: &[u8]) -> (u32, u32, Vec<u8>) {
        let mut reader = png::Decoder::new(bytes).read_info().unwrap();
        let mut pixels = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut pixels).unwrap();
        (info.width, info.height, pixels)
    }

    /// The horizontal extent of the ink (non-white pixels) in rows `rows` of an RGB image.
    fn ink_columns((w, _, pixels): &(u32, u32, Vec<u8>), rows: std::ops::Range<u32>) -> u32 {
        let inked = |x: u32| {
            rows.clone().any(|y| {
                let i = ((y * w + x) * 3) as usize;
                pixels[i..i + 3].iter().any(|&c| c < 200)
            })
        };
        let first = (0..*w).find(|&x| inked(x)).unwrap();
        let last = (0..*w).rev().find(|&x| inked(x)).unwrap();
        last - first + 1
    }

    #[test]
    fn a_figure_at_twice_the_resolution_is_the_same_figure_at_twice_the_pixels() {
        // The title's ink spans twice the pixels at 300 dpi as at 150: text keeps its size in
        // points, and the PNG's size is the figure's in inches times its resolution.
        let plot = Plot {
            title: "time t (s), dopri5, implicit-euler".into(),
            x_label: "time t (s)".into(),
            y_label: "velocity v (m/s)".into(),
            series: vec![Series {
                label: None,
                points: vec![(0.0, 0.0), (1.0, 1.0)],
                color: RED,
                width: 2,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            }],
            legend: Corner::default(),
            log: false,
        };
        let draw = |dpi: f64| {
            let format = Format::parse(Some("3.5x2.6"), Some(dpi)).unwrap();
            decoded(&png(&plot, Path::new("t.png"), &format).unwrap())
        };
        let (one, two) = (draw(150.0), draw(300.0));
        assert_eq!((one.0, one.1), (525, 390));
        assert_eq!((two.0, two.1), (1050, 780));
        let (a, b) = (ink_columns(&one, 5..35), ink_columns(&two, 10..70));
        assert!(
            b.abs_diff(2 * a) <= 3,
            "title ink {a} px at 150 dpi, {b} px at 300"
        );
        // And the SVG states the size in inches around the design canvas, naming its font.
        let text = svg(
            &plot,
            Path::new("t.svg"),
            &Format::parse(Some("3.5x2.6"), None).unwrap(),
        )
        .unwrap();
        assert!(text.starts_with("<svg width=\"3.5in\" height=\"2.6in\" viewBox=\"0 0 525 390\""));
        assert!(text.contains("font-family=\"DejaVu Sans, Verdana, Arial, sans-serif\""));
        assert!(!text.contains("font-family=\"sans-serif\""));
    }

    /// The numbers of attribute `name` in each element `<tag …>` of an SVG.
    fn attributes(svg: &str, tag: &str, name: &str) -> Vec<f64> {
        (svg.split(&format!("<{tag} ")).skip(1))
            .filter_map(|e| {
                let e = format!(" {e}");
                let value = e.split(&format!(" {name}=\"")).nth(1)?.split('"').next()?;
                value.parse().ok()
            })
            .collect()
    }

    /// A raster of three bodies' modes over two cells of time.
    fn modes() -> Raster {
        Raster {
            title: "modes".into(),
            x_label: "time t (s)".into(),
            y_label: "body index".into(),
            x_edges: vec![0.0, 1.0, 2.0],
            rows: 3,
            row_index: vec![],
            cells: vec![0, 1, 0, 1, 0, 1],
            legend: vec![(RED, "slip+".into()), (BLUE, "stick".into())],
        }
    }

    #[test]
    fn every_figure_kind_draws_at_its_size_and_keeps_its_legend_off_the_data() {
        let dots = |label: &str, points: Vec<(f64, f64)>, color| Series {
            label: Some(label.into()),
            points,
            color,
            width: 0,
            marker: Marker::Dot,
            dash: crate::plot::Dash::Solid,
        };
        let plot = |series, log| Plot {
            title: "kind".into(),
            x_label: "time t (s)".into(),
            y_label: "velocity v (m/s)".into(),
            series,
            legend: Corner::UpperLeft,
            log,
        };
        let rising: Vec<(f64, f64)> = (1..=30).map(|i| (f64::from(i), f64::from(i))).collect();
        let falling: Vec<(f64, f64)> = (0..=12)
            .map(|i| {
                (
                    10f64.powf(f64::from(i) / 4.0),
                    10f64.powf(-f64::from(i) / 2.0),
                )
            })
            .collect();
        let grid: Vec<(f64, f64)> = (1..=15)
            .flat_map(|i| (1..=15).map(move |j| (f64::from(i), f64::from(j))))
            .collect();
        let curve = plot(vec![dots("rising", rising, RED)], false);
        let log = plot(vec![dots("falling", falling, BLUE)], true);
        let map = plot(vec![dots("a grid", grid, GREEN)], false);
        let raster = modes();
        for format in [
            Format::default(),
            Format::parse(Some("3.5x2.6"), Some(300.0)).unwrap(),
        ] {
            let kinds: [(&str, &[Plot]); 4] = [
                ("curve", std::slice::from_ref(&curve)),
                ("log", std::slice::from_ref(&log)),
                ("map", std::slice::from_ref(&map)),
                ("panels", &[curve.clone(), log.clone()]),
            ];
            for (kind, plots) in kinds {
                let design = canvas(plots, &format);
                let png = decoded(&png_panels(plots, Path::new("k.png"), &format).unwrap());
                assert_eq!((png.0, png.1), format.pixels(design), "{kind}");
                let svg = svg_panels(plots, Path::new("k.svg"), &format).unwrap();
                let view = format!("viewBox=\"0 0 {} {}\"", design.0, design.1);
                assert!(svg.contains(&view), "{kind}: {view}");
                // A legend inside the axes (the white box of opacity 0.85) covers none of the
                // data's dots (drawn before the legend's key: the first circles).
                let [one] = plots else { continue };
                let dots: usize = one.series.iter().map(|s| s.points.len()).sum();
                let (cx, cy) = (
                    attributes(&svg, "circle", "cx"),
                    attributes(&svg, "circle", "cy"),
                );
                assert!(cx.len() > dots, "{kind}: {} circles", cx.len());
                let boxes: Vec<&str> = (svg.split("<rect ").skip(1))
                    .filter(|r| r.contains("opacity=\"0.85\""))
                    .collect();
                assert_eq!(boxes.len(), 1, "{kind}: one legend");
                for b in boxes {
                    let n = |name: &str| attributes(&format!("<rect {b}"), "rect", name)[0];
                    let (x, y, w, h) = (n("x"), n("y"), n("width"), n("height"));
                    // The grid fills every corner: its legend is beside the panel or below it.
                    let (pw, ph) = format.design(1);
                    let outside = x >= f64::from(pw) || y >= f64::from(ph);
                    assert_eq!(outside, kind == "map", "{kind}: legend at ({x}, {y})");
                    for (px, py) in cx.iter().zip(&cy).take(dots) {
                        let inside = (x..=x + w).contains(px) && (y..=y + h).contains(py);
                        assert!(!inside, "{kind}: a dot at ({px}, {py}) under the legend");
                    }
                }
            }
            // The map's legend is beside a page-wide panel (the canvas wider by its strip),
            // below a column's (the canvas higher, as wide as the column).
            let (w, h) = canvas(std::slice::from_ref(&map), &format);
            let (pw, ph) = format.design(1);
            match pw >= BESIDE_MIN_WIDTH {
                true => assert!(w > pw && h == ph, "{w} x {h}"),
                false => assert!(w == pw && h > ph, "{w} x {h}"),
            }
            let png = decoded(&raster_png(&raster, Path::new("r.png"), &format).unwrap());
            assert_eq!((png.0, png.1), format.pixels(raster.size(&format)));
        }
    }

    #[test]
    fn a_legend_beside_a_page_wide_plot_widens_the_canvas_and_leaves_the_panel_whole() {
        // A grid of markers everywhere: its legend goes beside, on a strip added to the panel.
        let grid: Vec<(f64, f64)> = (1..=20)
            .flat_map(|i| (1..=20).map(move |j| (f64::from(i), f64::from(j))))
            .collect();
        let map = Plot {
            title: "map".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![Series {
                label: Some("stick-slip".into()),
                points: grid,
                color: RED,
                width: 0,
                marker: Marker::Dot,
                dash: crate::plot::Dash::Solid,
            }],
            legend: Corner::UpperRight,
            log: false,
        };
        let format = Format::parse(Some("6x4"), Some(150.0)).unwrap();
        let (w, h) = canvas(std::slice::from_ref(&map), &format);
        assert_eq!(h, 600);
        assert_eq!(w, 900 + strip_width(&map));
        assert!(strip_width(&map) > 100);
    }

    #[test]
    fn an_empty_plot_draws_on_a_unit_range() {
        let plot = Plot {
            title: "nothing".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![Series {
                label: None,
                points: vec![(f64::NAN, 1.0)],
                color: RED,
                width: 1,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            }],
            legend: Corner::default(),
            log: false,
        };
        assert_eq!(bounds(&plot), ((0.0, 1.0), (0.0, 1.0)));
        assert!(svg(&plot, Path::new("empty.svg"), &Format::default())
            .unwrap()
            .contains("nothing"));
    }

    #[test]
    fn degenerate_plots_draw_on_linear_and_log_axes() {
        let cases: [Vec<(f64, f64)>; 6] = [
            vec![],
            vec![(1.0, 1.0)],
            vec![(2.0, 3.0); 5],
            vec![(-1.0, 0.0), (0.0, -1.0), (f64::INFINITY, 1.0)],
            vec![(1e-300, 1e-300), (1e300, 1e300)],
            vec![(1e-5, 1.0), (1.0000001e-5, 1.0000001)],
        ];
        for points in cases {
            for (log, labels) in [(false, 1), (true, 1), (false, 40), (true, 40)] {
                let plot = Plot {
                    title: "edge".into(),
                    x_label: "x".into(),
                    y_label: "y".into(),
                    series: (0..labels)
                        .map(|i| Series {
                            label: Some(format!("series {i}")),
                            points: points.clone(),
                            color: RED,
                            width: 2,
                            marker: Marker::Dot,
                            dash: crate::plot::Dash::Solid,
                        })
                        .collect(),
                    legend: Corner::UpperRight,
                    log,
                };
                let ((x0, x1), (y0, y1)) = layout(&plot, (900, 600)).0;
                assert!(x0 < x1 && y0 < y1, "{points:?} {log}: {x0} {x1} {y0} {y1}");
                assert!(
                    [x0, x1, y0, y1].iter().all(|v| v.is_finite()),
                    "{points:?} {log}: {x0} {x1} {y0} {y1}"
                );
                assert!(
                    svg(&plot, Path::new("edge.svg"), &Format::default()).is_ok(),
                    "{points:?} {log}"
                );
            }
        }
    }

    #[test]
    fn every_figure_kind_sets_its_text_no_smaller_than_the_ticks_whole_inside_and_apart() {
        // The figures' longest names, a study's twelve methods with crosses, a map whose
        // legend goes beside or below, seven panels in rows, and a raster, in a column and on
        // a page.
        let styled = |i: usize, points: Vec<(f64, f64)>| Series {
            label: Some(format!("method {i} with a long name")),
            points,
            color: PALETTE[i % PALETTE.len()],
            width: 2,
            marker: Marker::FILLED[i % 4],
            dash: Dash::ALL[(i + i / 4) % 4],
        };
        let plot = |title: &str, x: &str, y: &str, series, log| Plot {
            title: title.into(),
            x_label: x.into(),
            y_label: y.into(),
            series,
            legend: Corner::UpperRight,
            log,
        };
        let study = plot(
            "Cost to reach error 1e-3 against epsilon: paper-block with CS (regularized switching)",
            "work (f evaluations, weighted)",
            "relative error on the grid, max over x, v, z of |Δ|/max|reference| (1)",
            (0..12)
                .map(|i| {
                    let points = (0..8)
                        .map(|k| {
                            let k = f64::from(k);
                            (
                                10f64.powf(2.0 + k / 2.0 + i as f64 / 6.0),
                                10f64.powf(-k - 1.0),
                            )
                        })
                        .collect();
                    styled(i, points)
                })
                .collect(),
            true,
        );
        let curve = plot(
            "CVS: Coulomb + viscous + static + Stribeck (paper eq. (7))",
            "velocity v (m/s)",
            "friction force F (N)",
            vec![styled(
                0,
                (0..100)
                    .map(|k| (f64::from(k) / 50.0 - 1.0, f64::from(k % 7)))
                    .collect(),
            )],
            false,
        );
        let grid: Vec<(f64, f64)> = (1..=15)
            .flat_map(|i| (1..=15).map(move |j| (f64::from(i), f64::from(j) * 0.0025)))
            .collect();
        let map = plot(
            "Belt with CVS from rest: settled regime (c = 0, m = 1)",
            "belt speed v_belt (m/s)",
            "spring stiffness k (N/m)",
            vec![Series {
                width: 0,
                ..styled(1, grid)
            }],
            false,
        );
        let panels: Vec<Plot> = (0..7)
            .map(|i| Plot {
                title: format!("Servo with plant {i} at its set point"),
                ..curve.clone()
            })
            .collect();
        let raster = Raster {
            title: "Chain of 100 blocks: stick and slip of every block".into(),
            ..modes()
        };
        for size in ["3.5x2.6", "6x4"] {
            let format = Format::parse(Some(size), Some(150.0)).unwrap();
            let figures: [(&str, &[Plot]); 4] = [
                ("study", std::slice::from_ref(&study)),
                ("curve", std::slice::from_ref(&curve)),
                ("map", std::slice::from_ref(&map)),
                ("panels", &panels),
            ];
            for (kind, plots) in figures {
                let svg = svg_panels(plots, Path::new("k.svg"), &format).unwrap();
                let faults = layout_faults(&svg);
                assert!(faults.is_empty(), "{kind} at {size}: {faults:#?}");
            }
            let svg = raster_svg(&raster, Path::new("r.svg"), &format).unwrap();
            assert_eq!(
                layout_faults(&svg),
                Vec::<String>::new(),
                "raster at {size}"
            );
        }
        // The check sees what it is for: a text below the tick size, one cut short, one out of
        // the canvas, two on top of each other.
        let bad = "<svg viewBox=\"0 0 100 100\">\
                   <text x=\"10\" y=\"10\" font-size=\"8\">small</text>\
                   <text x=\"10\" y=\"40\" font-size=\"13\">cut…</text>\
                   <text x=\"90\" y=\"70\" font-size=\"13\">outside</text>\
                   <text x=\"12\" y=\"41\" font-size=\"13\">on it</text></svg>";
        let faults = layout_faults(bad);
        for words in [
            "below the tick labels",
            "cut short",
            "out of the",
            "overlaps",
        ] {
            assert!(
                faults.iter().any(|f| f.contains(words)),
                "{words}: {faults:#?}"
            );
        }
    }
}
