//! The space–time pictures of a system's run, readable at any number of bodies: body index
//! against time, sampled on at most [`RASTER`] columns and rows, coloured by contact mode
//! (`space-time.png`, with its cells as `space-time.csv`) and by velocity
//! (`velocity-space-time.png`, in [`VELOCITY_COLORS`] bands of equal width).

use crate::output::{Cell, Table};
use crate::plot::{self, Raster};
use crate::window::Window;
use friction_systems::{mode_name, Run, SLIP_NEGATIVE, SLIP_POSITIVE};
use plotters::style::RGBColor;

/// Most columns and rows of a space–time picture.
const RASTER: (usize, usize) = (300, 200);

/// The colour of a body without a contact in the modes' picture: sand, seen on the white page
/// (white left such a body invisible).
const NO_CONTACT: RGBColor = RGBColor(230, 195, 110);

/// The colours of the velocity bands, slowest first: eight samples of the viridis map, whose
/// lightness rises steadily (readable in grey and by colour-blind readers).
pub const VELOCITY_COLORS: [RGBColor; 8] = [
    RGBColor(68, 1, 84),
    RGBColor(70, 50, 126),
    RGBColor(54, 92, 141),
    RGBColor(39, 127, 142),
    RGBColor(31, 161, 135),
    RGBColor(74, 193, 109),
    RGBColor(160, 218, 57),
    RGBColor(253, 231, 37),
];

/// Where a run is sampled for its space–time pictures: column edges in time, the recorded
/// point each column shows (the first at or after its left edge), and the bodies the rows show.
pub struct Sampling {
    x_edges: Vec<f64>,
    points: Vec<usize>,
    rows: usize,
    bodies: usize,
}

impl Sampling {
    /// The sampling of `run`, whose solution holds a point, over `window` (else its span).
    pub fn of(run: &Run, window: Option<Window>) -> Self {
        let s = &run.solution;
        let bodies = run.problem.system.bodies.len();
        let (first, last) = (
            s.t.first().copied().unwrap_or(0.0),
            s.t.last().copied().unwrap_or(1.0),
        );
        let (t0, t1) = window.map_or((first, last), |w| (w.from.max(first), w.to.min(last)));
        let (t0, t1) = if t1 > t0 { (t0, t1) } else { (first, last) };
        let columns = RASTER.0.min(s.len().saturating_sub(1)).max(1);
        let x_edges: Vec<f64> = (0..=columns)
            .map(|c| t0 + (t1 - t0) * c as f64 / columns as f64)
            .collect();
        let mut k = 0;
        let points = (0..columns)
            .map(|c| {
                while k + 1 < s.len() && s.t[k] < x_edges[c] {
                    k += 1;
                }
                k
            })
            .collect();
        Sampling {
            x_edges,
            points,
            rows: bodies.min(RASTER.1),
            bodies,
        }
    }

    /// The body (0-based) row `r` shows.
    fn body_of_row(&self, r: usize) -> usize {
        r * self.bodies / self.rows
    }

    /// A picture of `cells` (colour indices, column after column) with `legend`.
    fn raster(&self, title: String, cells: Vec<u8>, legend: Vec<(RGBColor, String)>) -> Raster {
        Raster {
            title,
            x_label: "time t (s)".into(),
            y_label: if self.rows < self.bodies {
                format!("body index ({} of {} bodies)", self.rows, self.bodies)
            } else {
                "body index".into()
            },
            x_edges: self.x_edges.clone(),
            rows: self.rows,
            row_index: (0..self.rows).map(|r| self.body_of_row(r) + 1).collect(),
            cells,
            legend,
        }
    }

    /// The contact modes' picture, with its cells as a table.
    pub fn modes(&self, run: &Run, title: &str) -> (Raster, Table) {
        let s = &run.solution;
        let mut cells = Vec::with_capacity(self.points.len() * self.rows);
        let mut table = Table::new(&["t_start", "t_end", "body", "mode"]);
        for (c, &k) in self.points.iter().enumerate() {
            let modes = s.modes_at(k);
            for r in 0..self.rows {
                let i = self.body_of_row(r);
                let mode = run.problem.layout.contact[i]
                    .map(|j| run.problem.reported_mode(j, s.y_at(k), modes));
                cells.push(match mode {
                    None => 3,
                    Some(SLIP_POSITIVE) => 0,
                    Some(SLIP_NEGATIVE) => 1,
                    Some(_) => 2,
                });
                table.rows.push(vec![
                    Cell::Num(self.x_edges[c]),
                    Cell::Num(self.x_edges[c + 1]),
                    Cell::Text(run.problem.system.bodies[i].name.clone()),
                    Cell::Text(mode.map_or("none", mode_name).into()),
                ]);
            }
        }
        let legend = vec![
            (plot::RED, "slip+".into()),
            (plot::BLUE, "slip-".into()),
            (RGBColor(170, 170, 170), "stick".into()),
            (NO_CONTACT, "no contact".into()),
        ];
        (
            self.raster(format!("{title}: contact modes"), cells, legend),
            table,
        )
    }

    /// The velocities' picture: each cell the band of [`VELOCITY_COLORS`] its body's velocity
    /// falls in, the bands of equal width from the slowest to the fastest cell.
    pub fn velocities(&self, run: &Run, title: &str) -> Raster {
        let v: Vec<f64> = (self.points.iter())
            .flat_map(|&k| (0..self.rows).map(move |r| (k, r)))
            .map(|(k, r)| run.body_at(self.body_of_row(r), k).v)
            .collect();
        let (lo, hi) = (v.iter()).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
        let bands = VELOCITY_COLORS.len();
        let width = (hi - lo) / bands as f64;
        let band = |x: f64| match width > 0.0 {
            true => (((x - lo) / width) as usize).min(bands - 1),
            false => 0,
        };
        let cells = v.iter().map(|&x| band(x) as u8).collect();
        let legend = (0..bands)
            .map(|b| {
                let label = match width > 0.0 {
                    true => format!(
                        "{} to {} m/s",
                        short(lo + b as f64 * width),
                        short(lo + (b + 1) as f64 * width)
                    ),
                    false => format!("{} m/s", short(lo)),
                };
                (VELOCITY_COLORS[b], label)
            })
            .collect();
        self.raster(format!("{title}: velocities"), cells, legend)
    }
}

/// `x` to three significant digits, as a legend shows a band's edge.
fn short(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.digits$}")
}

#[cfg(test)]
mod tests {
    use super::short;

    #[test]
    fn a_band_edge_is_shown_to_three_significant_digits() {
        assert_eq!(short(0.123456), "0.123");
        assert_eq!(short(-1.5), "-1.50");
        assert_eq!(short(123.4), "123");
        assert_eq!(short(0.0), "0");
        assert_eq!(short(2.5e-4), "0.000250");
    }
}
