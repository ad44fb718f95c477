//! A raster of coloured cells over time and an index: a chain's contact modes.

use super::axes::{common_decimals, fixed};
use super::legend::{box_pixels, draw_box, Arrangement, LEGEND_BOX};
use super::{render_png, render_svg, whole_label, Format, FAMILY, MESH_LABELS};
use crate::error::AppError;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

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
    /// Number of rows.
    pub rows: usize,
    /// The index each row stands for, from the bottom (one per row): a sampled field's
    /// rows name the bodies they show. Empty: row r stands for index r (1..=rows).
    pub row_index: Vec<usize>,
    /// Colour index of each cell, column after column (`rows` per column).
    pub cells: Vec<u8>,
    /// Colour and legend label of each colour index.
    pub legend: Vec<(RGBColor, String)>,
}

impl Raster {
    /// The colours the cells use, with their labels, in legend order: the legend lists
    /// nothing the picture does not show.
    fn shown(&self) -> Vec<&(RGBColor, String)> {
        (self.legend.iter().enumerate())
            .filter(|&(k, _)| self.cells.iter().any(|&c| usize::from(c) == k))
            .map(|(_, entry)| entry)
            .collect()
    }

    /// The label of row `row` (1-based) on the index axis.
    fn index_of(&self, row: f64) -> String {
        match self.row_index.get(row as usize - 1) {
            Some(index) => index.to_string(),
            None => whole_label(&row),
        }
    }

    /// The canvas: a one-panel figure of `format` for the cells and their axes, and a strip
    /// on the right for the legend, so that it covers no cell and takes no width from them.
    pub fn size(&self, format: &Format) -> (u32, u32) {
        let labels: Vec<&str> = self.shown().iter().map(|e| e.1.as_str()).collect();
        let (w, h) = format.design(1);
        (w + box_pixels(&labels, Arrangement::ONE).0.ceil() as u32, h)
    }
}

/// The rows labelled on the index axis: every row up to ten, else every k-th row from the
/// first, k the smallest of 1, 2, 5, 10, 20, 50, … that leaves at most ten labels (an index is
/// a whole number: ticks between two rows named nothing).
fn row_ticks(rows: usize) -> Vec<f64> {
    let step = (0..)
        .flat_map(|e| [1, 2, 5].map(|m| m * 10usize.pow(e)))
        .find(|k| rows.div_ceil(*k) <= 10)
        .unwrap_or(1);
    (1..=rows.max(1)).step_by(step).map(|r| r as f64).collect()
}

/// Draws `r` on `root`, the cells on its left `cells_width` pixels.
fn draw_raster<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    r: &Raster,
    cells_width: u32,
) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let (cells_area, strip) = root.split_horizontally(cells_width);
    let (x0, x1) = match (r.x_edges.first(), r.x_edges.last()) {
        (Some(&a), Some(&b)) if b > a => (a, b),
        _ => (0.0, 1.0),
    };
    let (y0, y1) = (0.5, r.rows.max(1) as f64 + 0.5);
    let mut chart = ChartBuilder::on(&cells_area)
        .caption(&r.title, (FAMILY, 22))
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
    // Time labelled with one number of decimals (none for whole seconds); the index axis
    // labelled at whole rows only ([`row_ticks`]), drawn here: plotters would label it
    // between rows.
    let x_decimals = common_decimals(&chart.as_coord_spec().x_spec().key_points(MESH_LABELS));
    let x_label = |v: &f64| fixed(*v, x_decimals.unwrap_or(0));
    let mut mesh = chart.configure_mesh();
    mesh.disable_mesh()
        .y_labels(0)
        .x_desc(r.x_label.as_str())
        .y_desc(r.y_label.as_str())
        .label_style((FAMILY, 15))
        .axis_desc_style((FAMILY, 17));
    if x_decimals.is_some() {
        mesh.x_label_formatter(&x_label);
    }
    mesh.draw().map_err(err)?;
    let label = TextStyle::from((FAMILY, 15).into_font()).pos(Pos::new(HPos::Right, VPos::Center));
    for row in row_ticks(r.rows) {
        let (px, py) = chart.backend_coord(&(x0, row));
        let tick = PathElement::new([(px - 5, py), (px, py)], BLACK);
        cells_area.draw(&tick).map_err(err)?;
        cells_area
            .draw(&Text::new(r.index_of(row), (px - 8, py), &label))
            .map_err(err)?;
    }
    let shown = r.shown();
    let labels: Vec<&str> = shown.iter().map(|e| e.1.as_str()).collect();
    // Level with the plotting area's top (both in the canvas's pixels).
    let top = chart.plotting_area().get_base_pixel().1 - strip.get_base_pixel().1;
    draw_box(
        &strip,
        &labels,
        Arrangement::ONE,
        (0, top + LEGEND_BOX.gap as i32),
        |k, (x, y)| {
            strip.draw(&Rectangle::new(
                [(x, y - 6), (x + 16, y + 6)],
                shown[k].0.filled(),
            ))
        },
    )?;
    root.present().map_err(err)
}

/// The raster as SVG text.
pub fn raster_svg(r: &Raster, path: &Path, format: &Format) -> Result<String, AppError> {
    let cells = format.design(1).0;
    render_svg(r.size(format), path, |root| draw_raster(root, r, cells))
}

/// The raster as PNG bytes.
pub fn raster_png(r: &Raster, path: &Path, format: &Format) -> Result<Vec<u8>, AppError> {
    let cells = format.design(1).0;
    render_png(r.size(format), format, path, |root| {
        draw_raster(root, r, cells)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `x` of each `<text …>label</text>` of an SVG whose text is one of `labels`.
    fn text_x(svg: &str, label: &str) -> Vec<f64> {
        svg.split("<text")
            .skip(1)
            .filter(|t| {
                t.split('>')
                    .nth(1)
                    .is_some_and(|s| s.trim_start().starts_with(label))
            })
            .filter_map(|t| {
                let x = t.split("x=\"").nth(1)?.split('"').next()?;
                x.parse().ok()
            })
            .collect()
    }

    #[test]
    fn the_index_axis_labels_whole_rows_at_most_ten() {
        assert_eq!(row_ticks(2), [1.0, 2.0]);
        assert_eq!(row_ticks(10).len(), 10);
        assert_eq!(row_ticks(11), [1.0, 3.0, 5.0, 7.0, 9.0, 11.0]);
        assert_eq!(row_ticks(200).first(), Some(&1.0));
        assert_eq!(row_ticks(200)[1], 21.0);
        assert!(row_ticks(200).len() <= 10);
    }

    #[test]
    fn a_sampled_row_is_labelled_by_the_index_it_shows() {
        let raster = Raster {
            title: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            x_edges: vec![0.0, 1.0],
            rows: 2,
            row_index: vec![1, 151],
            cells: vec![0, 0],
            legend: vec![(RED, "slip+".into())],
        };
        assert_eq!(raster.index_of(2.0), "151");
        let svg = raster_svg(&raster, Path::new("rows.svg"), &Format::default()).unwrap();
        assert_eq!(text_x(&svg, "151").len(), 1);
        let unsampled = Raster {
            row_index: vec![],
            ..raster
        };
        assert_eq!(unsampled.index_of(2.0), "2");
    }

    #[test]
    fn the_legend_lists_the_colours_shown_beside_the_cells() {
        // Two of four modes occur: the legend lists those two, in a strip right of the cells
        // (the canvas is widened for it), and none of its text lies over a cell.
        let legend = ["slip+", "slip-", "stick", "no contact"];
        let raster = Raster {
            title: "modes".into(),
            x_label: "t".into(),
            y_label: "body".into(),
            x_edges: vec![0.0, 1.0, 2.0, 3.0],
            rows: 2,
            row_index: vec![],
            cells: vec![0, 2, 2, 2, 0, 0],
            legend: (legend.iter().zip([RED, BLUE, GREEN, WHITE]))
                .map(|(l, c)| (c, l.to_string()))
                .collect(),
        };
        let svg = raster_svg(&raster, Path::new("modes.svg"), &Format::default()).unwrap();
        // The canvas's width in design pixels, from the viewBox (its width is in inches).
        let view = svg.split("viewBox=\"0 0 ").nth(1).unwrap();
        let width: f64 = view.split(' ').next().unwrap().parse().unwrap();
        assert!(
            width > f64::from(Format::default().design(1).0) + 60.0,
            "{width}"
        );
        for shown in ["slip+", "stick"] {
            let x = text_x(&svg, shown);
            assert_eq!(x.len(), 1, "{shown}: {x:?}");
            assert!(
                x[0] > f64::from(Format::default().design(1).0),
                "{shown} at x = {}",
                x[0]
            );
        }
        for absent in ["slip-", "no contact"] {
            assert!(text_x(&svg, absent).is_empty(), "{absent} is listed");
        }
    }
}
