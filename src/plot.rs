//! Line plots as PNG and SVG, drawn by plotters with an embedded DejaVu Sans font so that
//! no system font package is needed.

use crate::error::AppError;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;
use std::sync::Once;

/// Width and height of every figure, pixels.
pub const SIZE: (u32, u32) = (900, 600);

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

/// The colours of the figures: the paper's red for the model, blue and green beside it.
pub const RED: RGBColor = RGBColor(200, 30, 30);
/// Second series colour.
pub const BLUE: RGBColor = RGBColor(30, 80, 200);
/// Third series colour.
pub const GREEN: RGBColor = RGBColor(20, 140, 60);

/// Colours for figures with several series, in order: one for each of a study's nine methods
/// at most (the seven solvers, and a system's regularised BDF and time-stepping).
pub const PALETTE: [RGBColor; 10] = [
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
];

/// Where the legend goes, if its box covers no more of the data there than in any other
/// corner (else the corner whose box covers the least).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Corner {
    /// Upper left (the default: most curves here rise to the right).
    #[default]
    UpperLeft,
    /// Upper right (error-against-work plots, which fall to the right).
    UpperRight,
    /// Lower left.
    LowerLeft,
    /// Lower right.
    LowerRight,
}

/// The plotting area of one panel of [`SIZE`] inside its label areas, margins and caption,
/// pixels (measured on the drawn figures).
const PLOT_AREA: (f64, f64) = (800.0, 493.0);

/// The legend box, pixels: its gap to the plotting area's corner, its width besides the
/// longest label's text (plotters' legend area, 30, and its two margins, 10), and its height
/// besides the entries and per entry (measured on the drawn figures: 86 for four entries), and
/// the margin kept around it for the markers' radius.
const LEGEND_BOX: LegendBox = LegendBox {
    gap: 5.0,
    width: 50.0,
    height: 5.0,
    per_entry: 21.0,
    margin: 6.0,
};

/// The measures of [`LEGEND_BOX`].
struct LegendBox {
    gap: f64,
    width: f64,
    height: f64,
    per_entry: f64,
    margin: f64,
}

/// The legend's font.
const LEGEND_FONT: (&str, u32) = ("sans-serif", 15);

/// Where a plot's legend is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum LegendPlace {
    /// In a corner of the plotting area.
    Inside(Corner),
    /// Beside the plotting area, on its right, level with its top.
    Beside,
}

/// The axes' ranges as [`bounds`] gives them, and where the legend goes: in the corner of
/// [`legend_corner`] if it covers no data there, else beside the plot (a stick–slip map's grid
/// of markers; the nine methods of a chain's work–precision plot, whose curves reach every
/// corner: raising the y range above the data, as done before, left six empty decades), unless
/// it is taller than the plot, when it stays in the corner where it covers least.
fn layout(plot: &Plot) -> (Bounds, LegendPlace) {
    let fitted = bounds(plot);
    let (corner, covered) = legend_corner(plot, fitted);
    if covered == 0 || legend_size(plot).1 > 1.0 {
        (fitted, LegendPlace::Inside(corner))
    } else {
        (fitted, LegendPlace::Beside)
    }
}

/// The ranges of the x and y axes.
type Bounds = ((f64, f64), (f64, f64));

/// The legend box of `plot` with its gap and margin, as fractions of the plotting area's width
/// and height (zero without a legend).
fn legend_size(plot: &Plot) -> (f64, f64) {
    let (w, h) = legend_pixels(plot);
    (w / PLOT_AREA.0, h / PLOT_AREA.1)
}

/// The legend box of `plot` with its gap and margin, pixels (zero without a legend).
fn legend_pixels(plot: &Plot) -> (f64, f64) {
    let labels: Vec<&str> = plot
        .series
        .iter()
        .filter_map(|s| s.label.as_deref())
        .collect();
    if labels.is_empty() {
        return (0.0, 0.0);
    }
    register_font();
    let font = (LEGEND_FONT.0, LEGEND_FONT.1).into_font();
    // The width the font gives each label (ten pixels a character if it cannot say).
    let text = labels
        .iter()
        .map(|l| {
            font.box_size(l)
                .map_or(10 * l.chars().count() as u32, |(w, _)| w)
        })
        .max()
        .unwrap_or(0);
    let b = &LEGEND_BOX;
    (
        b.gap + b.width + f64::from(text) + b.margin,
        b.gap + b.height + b.per_entry * labels.len() as f64 + b.margin,
    )
}

/// The corner for the legend of `plot` drawn over `bounds`, and how much it covers there: the
/// corner whose legend box covers the fewest of the plot's points and of the samples along its
/// lines (16 a segment), the preferred [`Plot::legend`] on a tie. (The belt's work–precision
/// plot had its implicit Euler's last point under the box in the upper right.)
fn legend_corner(plot: &Plot, ((x0, x1), (y0, y1)): Bounds) -> (Corner, usize) {
    let (w, h) = legend_size(plot);
    if w == 0.0 {
        return (plot.legend, 0);
    }
    let axis = |v: f64, (a, b): (f64, f64)| {
        let f = |v: f64| if plot.log { v.log10() } else { v };
        (f(v) - f(a)) / (f(b) - f(a))
    };
    let mut samples = Vec::new();
    for s in &plot.series {
        let points: Vec<(f64, f64)> = drawn(plot, s)
            .map(|(x, y)| (axis(x, (x0, x1)), axis(y, (y0, y1))))
            .collect();
        samples.extend(&points);
        if s.width > 0 {
            for pair in points.windows(2) {
                let ((ax, ay), (bx, by)) = (pair[0], pair[1]);
                samples.extend((1..16).map(|i| {
                    let t = f64::from(i) / 16.0;
                    (ax + t * (bx - ax), ay + t * (by - ay))
                }));
            }
        }
    }
    let covered = |corner: Corner| {
        let left = matches!(corner, Corner::UpperLeft | Corner::LowerLeft);
        let upper = matches!(corner, Corner::UpperLeft | Corner::UpperRight);
        samples
            .iter()
            .filter(|&&(u, v)| {
                (if left { u <= w } else { u >= 1.0 - w })
                    && (if upper { v >= 1.0 - h } else { v <= h })
            })
            .count()
    };
    let others = [
        Corner::UpperLeft,
        Corner::UpperRight,
        Corner::LowerLeft,
        Corner::LowerRight,
    ];
    std::iter::once(plot.legend)
        .chain(others.into_iter().filter(|&c| c != plot.legend))
        .map(|c| (c, covered(c)))
        .min_by_key(|&(_, n)| n)
        .unwrap_or((plot.legend, 0))
}

static FONT: Once = Once::new();

fn register_font() {
    FONT.call_once(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
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

/// The plot range of the data, padded by 5 % on each side (of the decades on log axes);
/// [0, 1] (or [1, 10]) on an axis with no drawable data (an empty plot must still draw, and
/// plotters cannot draw an infinite range).
fn bounds(plot: &Plot) -> Bounds {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in drawable(plot) {
        let (x, y) = (to_axis(plot, x), to_axis(plot, y));
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let pad = |a: f64, b: f64| {
        if a > b {
            return (0.0, 1.0);
        }
        let d = if b > a { 0.05 * (b - a) } else { 0.5 };
        (a - d, b + d)
    };
    (from_axis(plot, pad(x0, x1)), from_axis(plot, pad(y0, y1)))
}

/// A value in the space an axis is drawn in: its decade on a log axis.
fn to_axis(plot: &Plot, v: f64) -> f64 {
    if plot.log {
        v.log10()
    } else {
        v
    }
}

/// The range (a, b) of the drawing space ([`to_axis`]) in the data's units, kept within the
/// doubles' normal range (1e±307: a padded log range from data at 1e-300 would reach 0) and
/// of positive width.
fn from_axis(plot: &Plot, (a, b): (f64, f64)) -> (f64, f64) {
    const LIMIT: f64 = 307.0;
    let (a, b) = if plot.log {
        (a.clamp(-LIMIT, LIMIT), b.clamp(-LIMIT, LIMIT))
    } else {
        let limit = 10f64.powf(LIMIT);
        (a.clamp(-limit, limit), b.clamp(-limit, limit))
    };
    let (a, b) = if a < b {
        (a, b)
    } else {
        (b - (b.abs() + 1.0), b)
    };
    if plot.log {
        (10f64.powf(a), 10f64.powf(b))
    } else {
        (a, b)
    }
}

/// Draws `plots` side by side on `root`.
fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, plots: &[Plot]) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    for (panel, plot) in root.split_evenly((1, plots.len().max(1))).iter().zip(plots) {
        let (((x0, x1), (y0, y1)), legend) = layout(plot);
        // A legend beside the plot takes a strip on the panel's right.
        let strip;
        let (area, target) = match legend {
            LegendPlace::Beside => {
                let width = legend_pixels(plot).0.ceil() as u32 + LEGEND_BOX.gap as u32;
                let (a, b) = panel.split_horizontally(panel.dim_in_pixel().0.saturating_sub(width));
                strip = b;
                (a, LegendTarget::Strip(&strip))
            }
            LegendPlace::Inside(c) => (panel.clone(), LegendTarget::Corner(c)),
        };
        let mut builder = ChartBuilder::on(&area);
        let caption = caption_size(&plot.title, area.dim_in_pixel().0);
        builder
            .caption(&plot.title, ("sans-serif", caption))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(70);
        if plot.log {
            let axis = |a: f64, b: f64, ticks: Vec<f64>| {
                (a..b)
                    .log_scale()
                    .with_key_points(ticks.clone())
                    .with_light_points(ticks)
            };
            let x_ticks = sample_ticks(plot, x0, x1).unwrap_or_else(|| log_ticks(x0, x1));
            let chart = builder
                .build_cartesian_2d(axis(x0, x1, x_ticks), axis(y0, y1, log_ticks(y0, y1)))
                .map_err(err)?;
            draw_on(chart, plot, target)?;
        } else {
            let chart = builder.build_cartesian_2d(x0..x1, y0..y1).map_err(err)?;
            draw_on(chart, plot, target)?;
        }
    }
    root.present().map_err(err)
}

/// Where [`draw_on`] draws the legend: in a corner of the plotting area, or in a strip of the
/// panel beside it.
enum LegendTarget<'b, DB: DrawingBackend> {
    Corner(Corner),
    Strip(&'b DrawingArea<DB, Shift>),
}

/// A legend's key: a line sample and a cross, in pixels from the key's left end.
type Key = (PathElement<(i32, i32)>, Cross<(i32, i32), i32>);

/// The largest and smallest font sizes of a plot's title, pixels.
const CAPTION_SIZES: (u32, u32) = (22, 12);

/// The font size of `title` over an area `width` pixels wide: the largest of
/// [`CAPTION_SIZES`] whose text fits with 10 pixels each side (a model's title with its
/// reference, such as GMS's, ran over both edges at the largest).
fn caption_size(title: &str, width: u32) -> u32 {
    register_font();
    let (largest, smallest) = CAPTION_SIZES;
    (smallest..=largest)
        .rev()
        .find(|&size| {
            ("sans-serif", size)
                .into_font()
                .box_size(title)
                .map_or(true, |(w, _)| w + 20 <= width)
        })
        .unwrap_or(smallest)
}

/// The key of a series in a legend, relative to its left end: a line for a computed series, a
/// cross for failed runs.
fn key(color: RGBColor, marker: Marker) -> Key {
    let (cross, line) = match marker {
        Marker::Cross => (1.0, 0.0),
        _ => (0.0, 1.0),
    };
    (
        PathElement::new([(0, 0), (20, 0)], color.mix(line).stroke_width(3)),
        Cross::new((10, 0), 5, color.mix(cross).stroke_width(2)),
    )
}

/// The legend of `plot` drawn in `area`, a strip beside its plotting area, its box's top at
/// `top` pixels of the strip: the box, key and text of plotters' own legend.
fn draw_legend_beside<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    plot: &Plot,
    top: i32,
) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let b = &LEGEND_BOX;
    let labelled: Vec<&Series> = plot.series.iter().filter(|s| s.label.is_some()).collect();
    let (w, h) = legend_pixels(plot);
    let corner = |x: f64, y: f64| (x as i32, top + y as i32);
    let (x0, x1) = (0.0, w - b.gap - b.margin);
    let height = h - b.gap - b.margin;
    let frame = [corner(x0, 0.0), corner(x1, height)];
    area.draw(&Rectangle::new(frame, WHITE.mix(0.85).filled()))
        .map_err(err)?;
    area.draw(&Rectangle::new(frame, BLACK)).map_err(err)?;
    let text = TextStyle::from(LEGEND_FONT.into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    for (k, s) in labelled.iter().enumerate() {
        let y = b.height / 2.0 + b.per_entry * (k as f64 + 0.5);
        let (line, cross) = key(s.color, s.marker);
        area.draw(&(EmptyElement::at(corner(x0 + 10.0, y)) + line + cross))
            .map_err(err)?;
        let label = s.label.as_deref().unwrap_or_default();
        area.draw(&Text::new(label, corner(x0 + 40.0, y), &text))
            .map_err(err)?;
    }
    Ok(())
}

/// The ticks of a log axis over [a, b]: the powers of ten in it (every second, third… when
/// there are more than [`MAX_TICKS`]), or, when fewer than three, the 1-2-5 multiples of the
/// powers of ten, or all nine, whichever first gives three; the two ends of a range narrower
/// than that. (plotters' own ticks start at the first power of ten, and left a range from
/// 2e3 to 4e4 labelled only at 1e4, 2e4 and 3e4.)
fn log_ticks(a: f64, b: f64) -> Vec<f64> {
    let (k0, k1) = (a.log10().floor() as i32, b.log10().ceil() as i32);
    let within = |mantissas: &[f64]| -> Vec<f64> {
        (k0..=k1)
            // m/10^−k below one: the nearest double to m·10^k, as the labels print it.
            .flat_map(|k| {
                mantissas.iter().map(move |m| match k {
                    0.. => m * 10f64.powi(k),
                    _ => m / 10f64.powi(-k),
                })
            })
            .filter(|v| (a..=b).contains(v))
            .collect()
    };
    let decades = within(&[1.0]);
    if decades.len() >= 3 {
        let every = decades.len().div_ceil(MAX_TICKS) as i32;
        return decades
            .into_iter()
            .filter(|v| (v.log10().round() as i32).rem_euclid(every) == 0)
            .collect();
    }
    for mantissas in [
        &[1.0, 2.0, 5.0][..],
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0],
    ] {
        let ticks = within(mantissas);
        if ticks.len() >= 3 {
            return ticks;
        }
    }
    vec![a, b]
}

/// The most ticks a log axis labels with powers of ten.
const MAX_TICKS: usize = 10;

/// The most sampled values a log x axis labels one by one ([`sample_ticks`]).
const MAX_SAMPLE_TICKS: usize = 8;

/// The least distance between two labelled samples, as a fraction of the axis's length.
const MIN_SAMPLE_GAP: f64 = 0.08;

/// The ticks of a log x axis over [a, b] at the values the runs were made at, when the plot
/// samples a few of them (the step sizes of a convergence study, the widths of a stiffness
/// sweep, the block counts of a cost study): the distinct x of the marked points, if there
/// are two to [`MAX_SAMPLE_TICKS`] of them, each at least [`MIN_SAMPLE_GAP`] of the axis
/// from the next. (The powers of ten and their 1-2-5 multiples left the finest step of a
/// convergence study, h = 0.0025, without a label.)
fn sample_ticks(plot: &Plot, a: f64, b: f64) -> Option<Vec<f64>> {
    let mut xs: Vec<f64> = plot
        .series
        .iter()
        .filter(|s| s.marker != Marker::None)
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .filter(|x| (a..=b).contains(x))
        .collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let span = (b / a).log10();
    let apart = xs
        .windows(2)
        .all(|w| (w[1] / w[0]).log10() >= MIN_SAMPLE_GAP * span);
    ((2..=MAX_SAMPLE_TICKS).contains(&xs.len()) && apart).then_some(xs)
}

/// A tick label of a log axis: three significant digits, exponent form outside [1e-3, 1e4).
fn tick_label(v: f64) -> String {
    let trim = |m: String| {
        if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            m
        }
    };
    if v == 0.0 || (1e-3..1e4).contains(&v.abs()) {
        trim(format!("{v:.4}"))
    } else {
        let text = format!("{v:.2e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        format!("{}e{exponent}", trim(mantissa.to_string()))
    }
}

/// The mesh, the series with their markers, and the legend, on linear or log axes.
fn draw_on<'a, DB, X, Y>(
    mut chart: ChartContext<'a, DB, Cartesian2d<X, Y>>,
    plot: &Plot,
    legend: LegendTarget<'_, DB>,
) -> Result<(), String>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let tick = |v: &f64| tick_label(*v);
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
    let x_tick = |v: &f64| X::format(&zero(*v, &xr));
    let y_tick = |v: &f64| Y::format(&zero(*v, &yr));
    let mut mesh = chart.configure_mesh();
    mesh.light_line_style(WHITE)
        .x_desc(plot.x_label.as_str())
        .y_desc(plot.y_label.as_str())
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17));
    if plot.log {
        mesh.x_label_formatter(&tick).y_label_formatter(&tick);
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
    for s in &plot.series {
        let points: Vec<(f64, f64)> = drawn(plot, s).collect();
        let color = s.color;
        let marker = s.marker;
        let drawn = if s.width > 0 {
            let style = ShapeStyle::from(&s.color).stroke_width(s.width);
            chart
                .draw_series(LineSeries::new(points.iter().copied(), style))
                .map_err(err)?
        } else {
            chart
                .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
                .map_err(err)?
        };
        if let Some(label) = &s.label {
            drawn.label(label.as_str()).legend(move |p| {
                let (line, cross) = key(color, marker);
                EmptyElement::at(p) + line + cross
            });
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
        }
    }
    if !plot.series.iter().any(|s| s.label.is_some()) {
        return Ok(());
    }
    match legend {
        LegendTarget::Corner(corner) => chart
            .configure_series_labels()
            .label_font(LEGEND_FONT)
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
            draw_legend_beside(area, plot, top + LEGEND_BOX.gap as i32)
        }
    }
}

/// The size of a figure of `panels` plots side by side.
fn size(panels: usize) -> (u32, u32) {
    (SIZE.0 * panels.max(1) as u32, SIZE.1)
}

/// The plot as SVG text.
pub fn svg(plot: &Plot, path: &Path) -> Result<String, AppError> {
    svg_panels(std::slice::from_ref(plot), path)
}

/// Plots side by side as SVG text.
pub fn svg_panels(plots: &[Plot], path: &Path) -> Result<String, AppError> {
    register_font();
    let mut text = String::new();
    draw(
        SVGBackend::with_string(&mut text, size(plots.len())).into_drawing_area(),
        plots,
    )
    .map_err(|message| AppError::Plot {
        path: path.to_path_buf(),
        message,
    })?;
    Ok(text)
}

/// The plot as PNG bytes.
pub fn png(plot: &Plot, path: &Path) -> Result<Vec<u8>, AppError> {
    png_panels(std::slice::from_ref(plot), path)
}

/// Plots side by side as PNG bytes.
pub fn png_panels(plots: &[Plot], path: &Path) -> Result<Vec<u8>, AppError> {
    register_font();
    let fail = |message: String| AppError::Plot {
        path: path.to_path_buf(),
        message,
    };
    let (w, h) = size(plots.len());
    let mut pixels = vec![0u8; (w * h * 3) as usize];
    draw(
        BitMapBackend::with_buffer(&mut pixels, (w, h)).into_drawing_area(),
        plots,
    )
    .map_err(fail)?;
    encode_png(&pixels, (w, h), path)
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
        .map_err(|e| AppError::Plot {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    Ok(bytes)
}

/// A picture of a discrete field over time and an index, as a raster of coloured cells: for
/// a chain, body index against time coloured by contact mode.
#[derive(Clone, Debug, PartialEq)]
pub struct Raster {
    /// Title above the plot.
    pub title: String,
    /// x-axis label.
    pub x_label: String,
    /// y-axis label.
    pub y_label: String,
    /// Edges of the columns along x (one more than the columns).
    pub x_edges: Vec<f64>,
    /// Number of rows (indices 1..=rows).
    pub rows: usize,
    /// Colour index of each cell, column after column (`rows` per column).
    pub cells: Vec<u8>,
    /// Colour and legend label of each colour index.
    pub legend: Vec<(RGBColor, String)>,
}

fn draw_raster<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, r: &Raster) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let (x0, x1) = match (r.x_edges.first(), r.x_edges.last()) {
        (Some(&a), Some(&b)) if b > a => (a, b),
        _ => (0.0, 1.0),
    };
    let (y0, y1) = (0.5, r.rows.max(1) as f64 + 0.5);
    let mut chart = ChartBuilder::on(&root)
        .caption(&r.title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(err)?;
    let columns = r.x_edges.len().saturating_sub(1);
    let cells = (0..columns).flat_map(|c| {
        (0..r.rows).map(move |row| {
            let color = r.legend[r.cells[c * r.rows + row] as usize].0;
            Rectangle::new(
                [
                    (r.x_edges[c], row as f64 + 0.5),
                    (r.x_edges[c + 1], row as f64 + 1.5),
                ],
                color.filled(),
            )
        })
    });
    chart.draw_series(cells).map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(r.x_label.as_str())
        .y_desc(r.y_label.as_str())
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .draw()
        .map_err(err)?;
    for (color, label) in &r.legend {
        let color = *color;
        chart
            .draw_series(std::iter::empty::<Rectangle<(f64, f64)>>())
            .map_err(err)?
            .label(label.as_str())
            .legend(move |(x, y)| Rectangle::new([(x, y - 6), (x + 16, y + 6)], color.filled()));
    }
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 15))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(err)?;
    root.present().map_err(err)
}

/// The raster as SVG text.
pub fn raster_svg(r: &Raster, path: &Path) -> Result<String, AppError> {
    register_font();
    let mut text = String::new();
    draw_raster(
        SVGBackend::with_string(&mut text, SIZE).into_drawing_area(),
        r,
    )
    .map_err(|message| AppError::Plot {
        path: path.to_path_buf(),
        message,
    })?;
    Ok(text)
}

/// The raster as PNG bytes.
pub fn raster_png(r: &Raster, path: &Path) -> Result<Vec<u8>, AppError> {
    register_font();
    let (w, h) = SIZE;
    let mut pixels = vec![0u8; (w * h * 3) as usize];
    draw_raster(
        BitMapBackend::with_buffer(&mut pixels, SIZE).into_drawing_area(),
        r,
    )
    .map_err(|message| AppError::Plot {
        path: path.to_path_buf(),
        message,
    })?;
    encode_png(&pixels, SIZE, path)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A plot of dotted runs at `xs` (y = x) on log axes.
    fn runs_at(xs: &[f64]) -> Plot {
        Plot {
            title: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            series: vec![Series {
                label: None,
                points: xs.iter().map(|&x| (x, x)).collect(),
                color: RED,
                width: 2,
                marker: Marker::Dot,
            }],
            legend: Corner::default(),
            log: true,
        }
    }

    #[test]
    fn a_log_x_axis_is_labelled_at_a_few_sampled_values() {
        // A convergence study's steps: every one labelled, the finest included.
        let steps = [0.02, 0.01, 0.005, 0.0025];
        assert_eq!(
            sample_ticks(&runs_at(&steps), 0.0022, 0.023),
            Some(vec![0.0025, 0.005, 0.01, 0.02])
        );
        // Too many values (a work–precision plot's errors), or two too close to label apart:
        // the powers of ten and their multiples instead.
        let many: Vec<f64> = (1..=9).map(|k| 10f64.powi(-k)).collect();
        assert_eq!(sample_ticks(&runs_at(&many), 1e-10, 1.0), None);
        assert_eq!(
            sample_ticks(&runs_at(&[1e-3, 1.1e-3, 1e-1]), 1e-4, 1.0),
            None
        );
        // A curve without markers (a reference slope) is not a sample.
        let mut slope = runs_at(&[0.01, 0.1]);
        slope.series[0].marker = Marker::None;
        assert_eq!(sample_ticks(&slope, 1e-3, 1.0), None);
    }

    #[test]
    fn a_log_axis_has_at_least_three_ticks_and_at_most_ten_powers_of_ten() {
        // The work axis of the 100-block chain's work–precision plot.
        assert_eq!(log_ticks(1.8e3, 3.8e4), [2e3, 5e3, 1e4, 2e4]);
        assert_eq!(log_ticks(0.5, 50.0), [0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0]);
        assert_eq!(log_ticks(0.15, 0.6), [0.2, 0.3, 0.4, 0.5, 0.6]);
        assert_eq!(log_ticks(0.9, 20.0), [1.0, 2.0, 5.0, 10.0, 20.0]);
        assert_eq!(log_ticks(3.1e4, 3.2e4), [3.1e4, 3.2e4]);
        let many = log_ticks(1e-12, 1e12);
        assert_eq!(many.len(), 9, "{many:?}");
        assert!(many.iter().all(|v| (v.log10().round() as i32) % 3 == 0));
        assert_eq!(log_ticks(2e-11, 0.5).len(), 10);
    }

    #[test]
    fn the_legend_goes_to_the_preferred_corner_unless_it_would_cover_data() {
        let line = |points: Vec<(f64, f64)>| Series {
            label: Some("a run".into()),
            points,
            color: RED,
            width: 2,
            marker: Marker::Dot,
        };
        let plot = |points, legend| Plot {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![line(points)],
            legend,
            log: false,
        };
        // A line from the lower left to the upper right: the upper left is free.
        let rising = plot(vec![(0.0, 0.0), (1.0, 1.0)], Corner::UpperRight);
        assert_eq!(legend_corner(&rising, bounds(&rising)).0, Corner::UpperLeft);
        let kept = plot(vec![(0.0, 0.0), (1.0, 1.0)], Corner::LowerRight);
        assert_eq!(legend_corner(&kept, bounds(&kept)).0, Corner::LowerRight);
        // Falling, with a point in each corner but the lower left: the lower left.
        let falling = plot(
            vec![(0.0, 1.0), (0.5, 0.5), (1.0, 0.0), (1.0, 1.0)],
            Corner::UpperLeft,
        );
        assert_eq!(
            legend_corner(&falling, bounds(&falling)).0,
            Corner::LowerLeft
        );
        // On log axes the corners are taken in decades: a point at (1e3, 1e-3) of
        // [1, 1e3] × [1e-3, 1] is in the lower right.
        let log = Plot {
            log: true,
            ..plot(vec![(1.0, 1.0), (1e3, 1e-3)], Corner::LowerRight)
        };
        assert_eq!(legend_corner(&log, bounds(&log)).0, Corner::UpperRight);
        // A grid of markers everywhere: the legend goes beside the plot, the ranges those of
        // the data; its text is drawn right of every marker.
        let grid: Vec<(f64, f64)> = (1..=20)
            .flat_map(|i| (1..=20).map(move |j| (f64::from(i), f64::from(j))))
            .collect();
        for log in [false, true] {
            let map = Plot {
                log,
                series: vec![Series {
                    width: 0,
                    ..line(grid.clone())
                }],
                ..plot(vec![], Corner::UpperLeft)
            };
            assert!(legend_corner(&map, bounds(&map)).1 > 0);
            assert_eq!(layout(&map), (bounds(&map), LegendPlace::Beside));
            let svg = svg(&map, Path::new("map.svg")).unwrap();
            let rightmost = svg
                .split("<circle cx=\"")
                .skip(1)
                .filter_map(|e| e.split('"').next()?.parse::<f64>().ok())
                .fold(0.0, f64::max);
            let text = svg.find("a run").unwrap();
            let label_x = svg[..text].rsplit("<text x=\"").next().unwrap();
            let label_x: f64 = label_x.split('"').next().unwrap().parse().unwrap();
            assert!(rightmost > 100.0, "the markers are drawn: {rightmost}");
            assert!(label_x > rightmost + 10.0, "{label_x} {rightmost}");
            assert!(label_x < f64::from(SIZE.0), "{label_x}");
        }
        // A legend of thirty entries is taller than the plot: it stays in the corner where it
        // covers least, over the data's ranges.
        let many = Plot {
            series: (0..30).map(|_| line(grid.clone())).collect(),
            ..plot(vec![], Corner::UpperLeft)
        };
        assert_eq!(layout(&many).0, bounds(&many));
        assert!(matches!(layout(&many).1, LegendPlace::Inside(_)));
    }

    #[test]
    fn a_long_title_is_set_smaller_to_fit_its_panel() {
        let gms = "gms: generalized Maxwell-slip (Al-Bender et al. 2005) (Al-Bender, Lampaert, \
                   Swevers (2005), IEEE TAC 50(11))";
        let size = caption_size(gms, SIZE.0);
        assert!((CAPTION_SIZES.1..CAPTION_SIZES.0).contains(&size), "{size}");
        let width = |size: u32| ("sans-serif", size).into_font().box_size(gms).unwrap().0;
        assert!(width(size) + 20 <= SIZE.0, "{}", width(size));
        assert!(width(size + 1) + 20 > SIZE.0, "the largest that fits");
        assert_eq!(
            caption_size("Work-precision: belt with CS", SIZE.0),
            CAPTION_SIZES.0
        );
    }

    #[test]
    fn log_tick_labels_are_short() {
        assert_eq!(tick_label(9.999999999999999e-6), "1e-5");
        assert_eq!(tick_label(0.02), "0.02");
        assert_eq!(tick_label(2.5e7), "2.5e7");
        assert_eq!(tick_label(1000.0), "1000");
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
            }],
            legend: Corner::default(),
            log: false,
        };
        assert_eq!(bounds(&plot), ((0.0, 1.0), (0.0, 1.0)));
        assert!(svg(&plot, Path::new("empty.svg"))
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
                        })
                        .collect(),
                    legend: Corner::UpperRight,
                    log,
                };
                let ((x0, x1), (y0, y1)) = layout(&plot).0;
                assert!(x0 < x1 && y0 < y1, "{points:?} {log}: {x0} {x1} {y0} {y1}");
                assert!(
                    [x0, x1, y0, y1].iter().all(|v| v.is_finite()),
                    "{points:?} {log}: {x0} {x1} {y0} {y1}"
                );
                assert!(
                    svg(&plot, Path::new("edge.svg")).is_ok(),
                    "{points:?} {log}"
                );
            }
        }
    }
}
