//! A raster of coloured cells over time and an index: a chain's contact modes.

use super::{render_png, render_svg, SIZE};
use crate::error::AppError;
use plotters::coord::Shift;
use plotters::prelude::*;
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
    render_svg(SIZE, path, |root| draw_raster(root, r))
}

/// The raster as PNG bytes.
pub fn raster_png(r: &Raster, path: &Path) -> Result<Vec<u8>, AppError> {
    render_png(SIZE, path, |root| draw_raster(root, r))
}
