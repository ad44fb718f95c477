//! Where a plot's legend goes (a corner that covers no data, or a strip beside the plot), its
//! size, and its drawing beside the plot.

use super::axes::{bounds, Bounds};
use super::frame::{text_width, Frame, Lines};
use super::{drawn, Dash, Marker, Plot, Series};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

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

/// The room before each entry's text in a legend, for its key, pixels (plotters' legend area).
pub(super) const KEY_AREA: u32 = 58;

/// The legend box, pixels: its gap to the plotting area's corner, its width besides the
/// longest label's text (the key's area, [`KEY_AREA`], and two margins of 10), and its height
/// besides the entries and per entry (measured on the drawn figures: 86 for four entries), and
/// the margin kept around it for the markers' radius.
pub(super) const LEGEND_BOX: LegendBox = LegendBox {
    gap: 5.0,
    width: KEY_AREA as f64 + 20.0,
    height: 5.0,
    per_entry: 21.0,
    margin: 6.0,
};

/// The measures of [`LEGEND_BOX`].
pub(super) struct LegendBox {
    pub(super) gap: f64,
    pub(super) width: f64,
    pub(super) height: f64,
    pub(super) per_entry: f64,
    pub(super) margin: f64,
}

/// The legend's font.
pub(super) const LEGEND_FONT: (&str, u32) = (super::FAMILY, 15);

/// Where a plot's legend is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum LegendPlace {
    /// In a corner of the plotting area.
    Inside(Corner),
    /// Beside the plotting area, on its right, level with its top.
    Beside,
    /// Below the panel, level with the plotting area's left, in as many columns as keep it
    /// no taller than the plotting area (and the panel's width holds): for a panel narrower
    /// than [`BESIDE_MIN_WIDTH`], which a strip beside would widen past a journal's column,
    /// and for a legend taller than the panel beside it.
    Below(Arrangement),
}

/// How a legend's entries are set: in `columns` (filled column by column), each entry's text
/// broken into lines no wider than `room` pixels where a room is given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Arrangement {
    /// The columns, at least one.
    pub columns: usize,
    /// The widest line of an entry's text, pixels; `None`: each on one line.
    pub room: Option<f64>,
}

impl Arrangement {
    /// One column, each entry on one line.
    pub const ONE: Arrangement = Arrangement {
        columns: 1,
        room: None,
    };
}

/// The narrowest panel, design pixels, beside which a legend goes (4.7 in at 150 px/in); a
/// narrower one (a column figure, 3.5 in) takes it below.
pub(super) const BESIDE_MIN_WIDTH: u32 = 700;

/// The axes' ranges as [`bounds`] gives them, and where the legend goes: in the corner of
/// [`legend_corner`] if it covers no data there and fits inside the plotting area, else beside
/// the plot (a stick–slip map's grid
/// of markers; the nine methods of a chain's work–precision plot, whose curves reach every
/// corner: raising the y range above the data, as done before, left six empty decades), unless
/// it is taller than the panel below the plotting area's top; below the panel where it is
/// taller or the panel is narrow, in columns ([`LegendPlace::Below`]). The panel is `panel`
/// design pixels.
pub(super) fn layout(plot: &Plot, panel: (u32, u32)) -> (Bounds, LegendPlace) {
    let fitted = bounds(plot);
    let (corner, covered) = legend_corner(plot, fitted, panel);
    let below_top = f64::from(panel.1) - Frame::of(plot, panel).plot_top();
    let (w, h) = legend_size(plot, panel);
    let place = if covered == 0 && w <= 1.0 && h <= 1.0 {
        LegendPlace::Inside(corner)
    } else if panel.0 < BESIDE_MIN_WIDTH || legend_pixels(plot, Arrangement::ONE).1 > below_top {
        LegendPlace::Below(below_arrangement(plot, panel))
    } else {
        LegendPlace::Beside
    };
    (fitted, place)
}

/// The arrangement of a legend below a panel of `panel` pixels, level with its plotting area's
/// left and within its right edge: the fewest columns that keep it no taller than the plotting
/// area, while every entry still fits its column on one line; an entry too wide for one column
/// takes two lines.
fn below_arrangement(plot: &Plot, panel: (u32, u32)) -> Arrangement {
    let frame = Frame::of(plot, panel);
    let left = f64::from(super::frame::MARGIN + frame.y_area);
    let b = &LEGEND_BOX;
    // A box of `columns` ends at left + columns·(width + text + gap) − gap: at most the
    // panel's right edge less the gap.
    let room = |columns: usize| {
        (f64::from(panel.0) - b.gap - left + COLUMN_GAP) / columns as f64 - COLUMN_GAP - b.width
    };
    let arranged = |columns| Arrangement {
        columns,
        room: Some(room(columns)),
    };
    let labels = labels(plot);
    let widest = (labels.iter())
        .map(|l| f64::from(text_width(l, LEGEND_FONT.1)))
        .fold(0.0, f64::max);
    let height = frame.plot_area(panel).1;
    let mut columns = 1;
    while columns < labels.len()
        && legend_pixels(plot, arranged(columns)).1 > height
        && widest <= room(columns + 1)
    {
        columns += 1;
    }
    arranged(columns)
}

/// The labels of the series of `plot` that have one.
fn labels(plot: &Plot) -> Vec<&str> {
    (plot.series.iter())
        .filter_map(|s| s.label.as_deref())
        .collect()
}

/// The legend box of `plot` with its gap and margin, as fractions of the plotting area's width
/// and height in a panel of `panel` pixels (zero without a legend).
fn legend_size(plot: &Plot, panel: (u32, u32)) -> (f64, f64) {
    let (w, h) = legend_pixels(plot, Arrangement::ONE);
    let (area_w, area_h) = Frame::of(plot, panel).plot_area(panel);
    (w / area_w, h / area_h)
}

/// The legend box of `plot` set in `arrangement` with its gap and margin, pixels (zero
/// without a legend).
pub(super) fn legend_pixels(plot: &Plot, arrangement: Arrangement) -> (f64, f64) {
    box_pixels(&labels(plot), arrangement)
}

/// The rows of a legend of `entries` in `columns`, filled column by column.
fn rows(entries: usize, columns: usize) -> usize {
    entries.div_ceil(columns.max(1))
}

/// A legend's entries set in `arrangement`: the lines of each entry's text, and the height of
/// each row in lines (its tallest entry's).
fn set_entries(labels: &[&str], arrangement: Arrangement) -> (Vec<Vec<String>>, Vec<usize>) {
    let size = LEGEND_FONT.1;
    let lines: Vec<Vec<String>> = (labels.iter())
        .map(|l| match arrangement.room {
            Some(room) if f64::from(text_width(l, size)) > room => {
                Lines::set(l, room.max(1.0) as u32, (size, size)).lines
            }
            _ => vec![l.to_string()],
        })
        .collect();
    let rows = rows(labels.len(), arrangement.columns);
    let heights = (0..rows)
        .map(|r| {
            (lines.iter().skip(r).step_by(rows.max(1)))
                .map(Vec::len)
                .max()
                .unwrap_or(1)
        })
        .collect();
    (lines, heights)
}

/// A legend box of `labels` set in `arrangement` with its gap and margin, pixels (zero without
/// labels): each column as wide as the widest line of an entry.
pub(super) fn box_pixels(labels: &[&str], arrangement: Arrangement) -> (f64, f64) {
    if labels.is_empty() {
        return (0.0, 0.0);
    }
    let (lines, heights) = set_entries(labels, arrangement);
    let text = widest_line(&lines);
    let b = &LEGEND_BOX;
    let columns = arrangement.columns.clamp(1, labels.len());
    (
        b.gap + column_width(text) * columns as f64 - COLUMN_GAP + b.margin,
        b.gap + b.height + b.per_entry * heights.iter().sum::<usize>() as f64 + b.margin,
    )
}

/// The width of the widest of `lines`, pixels.
fn widest_line(lines: &[Vec<String>]) -> f64 {
    (lines.iter().flatten())
        .map(|l| f64::from(text_width(l, LEGEND_FONT.1)))
        .fold(0.0, f64::max)
}

/// The space between two columns of a legend, pixels.
const COLUMN_GAP: f64 = 10.0;

/// The width of a legend's column whose widest text is `text` pixels, the gap to the next
/// column included.
fn column_width(text: f64) -> f64 {
    LEGEND_BOX.width + text + COLUMN_GAP
}

/// The corner for the legend of `plot` drawn over `bounds`, and how much it covers there: the
/// corner whose legend box covers the fewest of the plot's points and of the samples along its
/// lines (16 a segment), the preferred [`Plot::legend`] on a tie. (The belt's work–precision
/// plot had its implicit Euler's last point under the box in the upper right.)
fn legend_corner(plot: &Plot, ((x0, x1), (y0, y1)): Bounds, panel: (u32, u32)) -> (Corner, usize) {
    let (w, h) = legend_size(plot, panel);
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

/// Where [`draw_on`] draws the legend: in a corner of the plotting area, or in a strip of the
/// panel beside it.
pub(super) enum LegendTarget<'b, DB: DrawingBackend> {
    Corner(Corner),
    Strip(&'b DrawingArea<DB, Shift>),
    Below(&'b DrawingArea<DB, Shift>, Arrangement),
}

/// The corners of a filled square, triangle or diamond of `marker`'s shape about
/// (`x`, `y`), pixels; none for another marker.
fn corners(marker: Marker, (x, y): (i32, i32)) -> Vec<(i32, i32)> {
    let shape: &[(i32, i32)] = match marker {
        Marker::Square => &[(-4, -4), (4, -4), (4, 4), (-4, 4)],
        Marker::Triangle => &[(0, -5), (5, 4), (-5, 4)],
        Marker::Diamond => &[(0, -5), (5, 0), (0, 5), (-5, 0)],
        _ => &[],
    };
    shape.iter().map(|&(dx, dy)| (x + dx, y + dy)).collect()
}

/// A filled square, triangle or diamond of `marker`'s shape about the origin, pixels (an
/// empty polygon for another marker).
pub(super) fn shape(marker: Marker, color: RGBColor) -> Polygon<(i32, i32)> {
    Polygon::new(corners(marker, (0, 0)), color.filled())
}

/// Whether `marker` is a filled shape ([`Marker::Square`], `Triangle`, `Diamond`), whose
/// key is [`filled_key`].
pub(super) fn is_filled(marker: Marker) -> bool {
    matches!(marker, Marker::Square | Marker::Triangle | Marker::Diamond)
}

/// A legend's key: a line sample, a cross and a dot, in pixels from the key's left end, the
/// ones a series does not draw made transparent.
type Key = (
    PathElement<(i32, i32)>,
    Cross<(i32, i32), i32>,
    Circle<(i32, i32), i32>,
    Circle<(i32, i32), i32>,
);

/// The key of a series in a legend, relative to its left end, showing what the series draws:
/// a line where it draws one (a curve, or a line through its points), and its marker, a dot,
/// a cross or a ring ([`filled_key`] for a filled shape).
pub(super) fn key(color: RGBColor, marker: Marker, width: u32) -> Key {
    let shown = |on: bool| if on { 1.0 } else { 0.0 };
    let line = shown(width > 0 || marker == Marker::None);
    let cross = shown(marker == Marker::Cross);
    let dot = shown(marker == Marker::Dot);
    let ring = shown(marker == Marker::Ring);
    (
        PathElement::new([(0, 0), (20, 0)], color.mix(line).stroke_width(3)),
        Cross::new((10, 0), 5, color.mix(cross).stroke_width(2)),
        Circle::new((10, 0), 4, color.mix(dot).filled()),
        Circle::new((10, 0), 5, color.mix(ring).stroke_width(2)),
    )
}

/// The length of a filled shape's key line, pixels: two periods of the longest dash pattern
/// ([`Dash::LongDashed`], 18 on and 6 off), so that every pattern shows as itself on both
/// sides of the shape at its middle.
const FILLED_KEY_LENGTH: i32 = 48;

/// A filled shape's key: a line sample in the series' dash pattern and the shape, in pixels
/// from the key's left end.
type FilledKey = (
    DashedPathElement<std::array::IntoIter<(i32, i32), 2>, u32>,
    Polygon<(i32, i32)>,
);

/// The key of a series marked by a filled shape: a line sample where it draws one, in its
/// dash pattern, and the shape at the sample's middle.
pub(super) fn filled_key(color: RGBColor, marker: Marker, width: u32, dash: Dash) -> FilledKey {
    let line = if width > 0 { 1.0 } else { 0.0 };
    let (on, off) = dash.pattern().unwrap_or((FILLED_KEY_LENGTH as u32, 0));
    (
        DashedPathElement::new(
            [(0, 0), (FILLED_KEY_LENGTH, 0)],
            on,
            off,
            color.mix(line).stroke_width(3),
        ),
        Polygon::new(corners(marker, (FILLED_KEY_LENGTH / 2, 0)), color.filled()),
    )
}

/// The legend of `plot` drawn in `area`, a strip beside or below its plotting area, its
/// box's upper left corner at `at` pixels of the strip: the box, key and text of plotters' own
/// legend.
pub(super) fn draw_legend_in_strip<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    plot: &Plot,
    arrangement: Arrangement,
    at: (i32, i32),
) -> Result<(), String> {
    let labelled: Vec<&Series> = plot.series.iter().filter(|s| s.label.is_some()).collect();
    let labels: Vec<&str> = labelled.iter().filter_map(|s| s.label.as_deref()).collect();
    draw_box(area, &labels, arrangement, at, |k, at| {
        let s = labelled[k];
        if is_filled(s.marker) {
            let (line, filled) = filled_key(s.color, s.marker, s.width, s.dash);
            return area.draw(&(EmptyElement::at(at) + line + filled));
        }
        let (line, cross, dot, ring) = key(s.color, s.marker, s.width);
        area.draw(&(EmptyElement::at(at) + line + cross + dot + ring))
    })
}

/// A legend box of `labels` set in `arrangement` drawn in `area`, its upper left corner at
/// (`left`, `top`) pixels of the area: the box of plotters' own legend, each label's key drawn
/// by `key(k, left end of the key)` level with its first line, then its text.
pub(super) fn draw_box<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    labels: &[&str],
    arrangement: Arrangement,
    (left, top): (i32, i32),
    key: impl Fn(usize, (i32, i32)) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>,
) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let b = &LEGEND_BOX;
    let (w, h) = box_pixels(labels, arrangement);
    let corner = |x: f64, y: f64| (left + x as i32, top + y as i32);
    let (x0, x1) = (0.0, w - b.gap - b.margin);
    let height = h - b.gap - b.margin;
    let frame = [corner(x0, 0.0), corner(x1, height)];
    area.draw(&Rectangle::new(frame, WHITE.mix(0.85).filled()))
        .map_err(err)?;
    area.draw(&Rectangle::new(frame, BLACK)).map_err(err)?;
    let text = TextStyle::from(LEGEND_FONT.into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    let (lines, heights) = set_entries(labels, arrangement);
    let rows = heights.len().max(1);
    let widest = widest_line(&lines);
    for (k, entry) in lines.iter().enumerate() {
        let (column, row) = (k / rows, k % rows);
        let x = x0 + column_width(widest) * column as f64;
        let above: usize = heights[..row].iter().sum();
        for (i, line) in entry.iter().enumerate() {
            let y = b.height / 2.0 + b.per_entry * ((above + i) as f64 + 0.5);
            if i == 0 {
                key(k, corner(x + 10.0, y)).map_err(err)?;
            }
            area.draw(&Text::new(
                line.as_str(),
                corner(x + 10.0 + f64::from(KEY_AREA), y),
                &text,
            ))
            .map_err(err)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::{svg, Format, RED};
    use std::path::Path;

    /// A one-panel figure of the default format.
    const PANEL: (u32, u32) = (900, 600);

    #[test]
    fn the_legend_goes_to_the_preferred_corner_unless_it_would_cover_data() {
        let line = |points: Vec<(f64, f64)>| Series {
            label: Some("a run".into()),
            points,
            color: RED,
            width: 2,
            marker: Marker::Dot,
            dash: crate::plot::Dash::Solid,
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
        assert_eq!(
            legend_corner(&rising, bounds(&rising), PANEL).0,
            Corner::UpperLeft
        );
        let kept = plot(vec![(0.0, 0.0), (1.0, 1.0)], Corner::LowerRight);
        assert_eq!(
            legend_corner(&kept, bounds(&kept), PANEL).0,
            Corner::LowerRight
        );
        // Falling, with a point in each corner but the lower left: the lower left.
        let falling = plot(
            vec![(0.0, 1.0), (0.5, 0.5), (1.0, 0.0), (1.0, 1.0)],
            Corner::UpperLeft,
        );
        assert_eq!(
            legend_corner(&falling, bounds(&falling), PANEL).0,
            Corner::LowerLeft
        );
        // On log axes the corners are taken in decades: a point at (1e3, 1e-3) of
        // [1, 1e3] × [1e-3, 1] is in the lower right.
        let log = Plot {
            log: true,
            ..plot(vec![(1.0, 1.0), (1e3, 1e-3)], Corner::LowerRight)
        };
        assert_eq!(
            legend_corner(&log, bounds(&log), PANEL).0,
            Corner::UpperRight
        );
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
            assert!(legend_corner(&map, bounds(&map), PANEL).1 > 0);
            assert_eq!(layout(&map, PANEL), (bounds(&map), LegendPlace::Beside));
            let page = Format::parse(Some("6x4"), Some(150.0)).unwrap();
            let svg = svg(&map, Path::new("map.svg"), &page).unwrap();
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
            // Beside the data's panel, on a canvas widened for it.
            assert!(label_x > f64::from(PANEL.0), "{label_x}");
        }
        // A legend of thirty entries is taller than the plot: it goes below, in as many columns
        // as keep it no taller than the plotting area, over the data's ranges.
        let many = Plot {
            series: (0..30).map(|_| line(grid.clone())).collect(),
            ..plot(vec![], Corner::UpperLeft)
        };
        assert_eq!(layout(&many, PANEL).0, bounds(&many));
        let LegendPlace::Below(arranged) = layout(&many, PANEL).1 else {
            panic!("{:?}", layout(&many, PANEL).1)
        };
        let height = Frame::of(&many, PANEL).plot_area(PANEL).1;
        let fewer = Arrangement {
            columns: arranged.columns - 1,
            ..arranged
        };
        assert!(legend_pixels(&many, arranged).1 <= height, "{arranged:?}");
        assert!(legend_pixels(&many, fewer).1 > height, "the fewest");
    }
    #[test]
    fn a_filled_shapes_key_draws_its_series_dash_pattern() {
        // The strokes of the key's line, in pixels.
        let key_strokes = |dash: Dash| {
            let plot = Plot {
                title: "t".into(),
                x_label: "x".into(),
                y_label: "y".into(),
                series: vec![Series {
                    label: Some("a scheme".into()),
                    points: vec![(0.0, 0.0), (1.0, 1.0), (2.0, 4.0)],
                    color: RED,
                    width: 2,
                    marker: Marker::Square,
                    dash,
                }],
                legend: Corner::UpperLeft,
                log: false,
            };
            let page = Format::parse(Some("6x4"), Some(150.0)).unwrap();
            let svg = svg(&plot, Path::new("key.svg"), &page).unwrap();
            let mut lengths = Vec::new();
            for element in svg.split("<polyline").skip(1) {
                let element = &element[..element.find("/>").unwrap()];
                // The key's line is 3 pixels wide, the series' own 2.
                if !element.contains("stroke=\"#C81E1E\" stroke-width=\"3\"") {
                    continue;
                }
                let points = element.split("points=\"").nth(1).unwrap();
                let xy: Vec<(f64, f64)> = (points.split('"').next().unwrap().split_whitespace())
                    .map(|p| {
                        let (x, y) = p.split_once(',').unwrap();
                        (x.parse().unwrap(), y.parse().unwrap())
                    })
                    .collect();
                assert!(xy.iter().all(|p| p.1 == xy[0].1), "{element}");
                lengths.push(xy[xy.len() - 1].0 - xy[0].0);
            }
            lengths
        };
        assert_eq!(key_strokes(Dash::Solid), vec![48.0]);
        // 10 on, 5 off over 48 pixels: three dashes and the start of a fourth.
        assert_eq!(key_strokes(Dash::Dashed), vec![10.0, 10.0, 10.0, 3.0]);
        // 2 on, 4 off: eight dots.
        assert_eq!(key_strokes(Dash::Dotted).len(), 8);
        // 18 on, 6 off: two long dashes.
        assert_eq!(key_strokes(Dash::LongDashed), vec![18.0, 18.0]);
    }
}
