//! The figures' pieces the studies share: one series per solver with its failed runs drawn
//! at the top, and the guides of fitted orders.

use crate::plot::{Marker, Series, PALETTE};
use scenarios::studies::{OrderTable, StepKind, StudyRun, TestSetRun};
use scenarios::verdict::Status;

/// The height of the `row`-th row of crosses above the data of a log plot, whose largest value
/// is `largest`: three times it, then 1.5 times higher for each row, one row per solver with
/// failed runs (drawn at one height, the crosses of one hid those of another).
pub fn row_at_top(largest: f64, row: i32) -> f64 {
    largest * 3.0 * 1.5f64.powi(row)
}

/// A run as the per-solver figures draw it: a friction study's [`StudyRun`], a test-set
/// run ([`TestSetRun`]).
pub trait DrawnRun {
    /// The method's label: one series each.
    fn method(&self) -> &str;
    /// Whether it failed (it has no error to draw).
    fn failed(&self) -> bool;
    /// Whether its result is judged `ok` (drawn as a dot) rather than inaccurate (a cross).
    fn judged_ok(&self) -> bool;
}

impl DrawnRun for StudyRun {
    fn method(&self) -> &str {
        &self.solver
    }
    fn failed(&self) -> bool {
        self.failure.is_some()
    }
    fn judged_ok(&self) -> bool {
        self.verdict.is_ok()
    }
}

/// A test-set run is judged by [`TestSetRun::status`].
impl DrawnRun for TestSetRun {
    fn method(&self) -> &str {
        self.solver
    }
    fn failed(&self) -> bool {
        self.failure.is_some()
    }
    fn judged_ok(&self) -> bool {
        self.status == Status::Ok
    }
}

/// One series per solver of the runs `keep` selects, with a dot on every run judged `ok`, a
/// cross where a run judged inaccurate lies, and, per solver with failed runs, a series of
/// crosses drawn at the top of the plot at their x, named with their count (a failed run has
/// no error to plot, but it is not left out), each such solver in a row of its own
/// ([`row_at_top`]).
pub fn per_solver_series<R: DrawnRun>(
    runs: &[R],
    keep: impl Fn(&R) -> bool,
    x: impl Fn(&R) -> f64,
    y: impl Fn(&R) -> f64,
) -> Vec<Series> {
    let runs: Vec<&R> = runs.iter().filter(|r| keep(r)).collect();
    let mut names: Vec<&str> = Vec::new();
    for r in &runs {
        if !names.contains(&r.method()) {
            names.push(r.method());
        }
    }
    let drawable = |r: &&&R| !r.failed() && y(r) > 0.0 && y(r).is_finite();
    let plotted = |r: &&&R| drawable(r) && r.judged_ok();
    let inaccurate = |r: &&&R| drawable(r) && !r.judged_ok();
    let largest = runs
        .iter()
        .filter(drawable)
        .map(|r| y(r))
        .reduce(f64::max)
        .unwrap_or(1.0);
    let mut series = Vec::new();
    let mut rows = 0;
    for (name, &color) in names.iter().zip(PALETTE.iter().cycle()) {
        let mine = || runs.iter().filter(|r| r.method() == *name);
        let points: Vec<(f64, f64)> = mine().filter(plotted).map(|r| (x(r), y(r))).collect();
        if !points.is_empty() {
            series.push(Series {
                label: Some(name.to_string()),
                points,
                color,
                width: 2,
                marker: Marker::Dot,
                dash: crate::plot::Dash::Solid,
            });
        }
        // A run judged inaccurate is data, drawn where it is, but marked apart from the dots.
        let judged: Vec<(f64, f64)> = mine().filter(inaccurate).map(|r| (x(r), y(r))).collect();
        if !judged.is_empty() {
            series.push(Series {
                label: Some(format!(
                    "{name}: {} inaccurate (error ≥ solution)",
                    judged.len()
                )),
                points: judged,
                color,
                width: 0,
                marker: Marker::Cross,
                dash: crate::plot::Dash::Solid,
            });
        }
        let top = row_at_top(largest, rows);
        let failed: Vec<(f64, f64)> = mine().filter(|r| r.failed()).map(|r| (x(r), top)).collect();
        if !failed.is_empty() {
            rows += 1;
            series.push(Series {
                label: Some(format!("{name}: {} failed (at the top)", failed.len())),
                points: failed,
                color,
                width: 0,
                marker: Marker::Cross,
                dash: crate::plot::Dash::Solid,
            });
        }
    }
    series
}

/// A guide for each table's fit, drawn through its asymptotic range only: the fitted line
/// error = e^intercept · h^slope from the finest to the coarsest resolution it rests on, named
/// with the solver, the slope and its 95 % interval (tables without a fit draw none).
pub fn fitted_guides(tables: &[&OrderTable]) -> Vec<Series> {
    tables
        .iter()
        .filter_map(|t| Some((t, t.fit?)))
        .zip([120u8, 160, 80].iter().cycle())
        .map(|((t, f), &shade)| {
            let slope = match t.step {
                StepKind::Fixed => "order",
                StepKind::Adaptive => "tol exponent",
            };
            Series {
                label: Some(format!(
                    "{}: {slope} {:.2} ({:.2} to {:.2}), {} pairs",
                    t.solver, f.slope, f.ci[0], f.ci[1], f.pairs_used
                )),
                points: f.range.iter().map(|&h| (h, f.at(h))).collect(),
                color: plotters::style::RGBColor(shade, shade, shade),
                width: 1,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use integrators::Stats;
    use scenarios::studies::Errors;
    use scenarios::verdict::Verdict;

    fn run(solver: &str, h: f64, error: f64, failure: Option<f64>) -> StudyRun {
        // A run that left the finite numbers at time t.
        let failure = failure.map(|t| integrators::SolverError::NonFinite {
            t,
            h,
            what: "state".into(),
        });
        StudyRun {
            solver: solver.into(),
            resolution: h,
            step: scenarios::studies::StepKind::Fixed,
            errors: Errors {
                final_relative: error,
                ..Errors::UNMEASURED
            },
            measures: Default::default(),
            stats: Stats::default(),
            work: 0,
            verdict: Verdict::of_error(failure.as_ref()).unwrap_or(Verdict::OK),
            failure,
            diverged: false,
            wall_time: Default::default(),
        }
    }

    #[test]
    fn the_failed_runs_of_each_solver_are_drawn_in_a_row_of_their_own() {
        // Two solvers failing at the same step: at one height, the second's crosses hid the
        // first's.
        let runs = [
            run("rk4", 0.02, f64::NAN, Some(0.1)),
            run("rk4", 0.01, 1e-4, None),
            run("dopri5", 0.02, f64::NAN, Some(0.1)),
            run("dopri5", 0.01, 1e-6, None),
            run("implicit-euler", 0.02, 1e-2, None),
        ];
        let series = per_solver_series(
            &runs,
            |_| true,
            |r| r.resolution,
            |r| r.errors.final_relative,
        );
        let crosses: Vec<(f64, f64)> = series
            .iter()
            .filter(|s| s.marker == Marker::Cross)
            .map(|s| s.points[0])
            .collect();
        assert_eq!(crosses, [(0.02, 3e-2), (0.02, 3e-2 * 1.5)]);
    }

    #[test]
    fn every_solver_of_a_system_study_has_a_colour_of_its_own() {
        // The ten solvers and a system's two peers: with eight colours, time-stepping took
        // RK4's red, and the chain's default work-precision plot drew them alike.
        let names = [
            "rk4",
            "dopri5",
            "implicit-euler",
            "bdf",
            "tr-bdf2",
            "esdirk34",
            "tsit45",
            "radau5",
            "rodas",
            "auto",
            "bdf (regularized)",
            "moreau-jean (timestepping)",
        ];
        let runs: Vec<StudyRun> = names.iter().map(|n| run(n, 0.01, 1e-4, None)).collect();
        let series = per_solver_series(
            &runs,
            |_| true,
            |r| r.resolution,
            |r| r.errors.final_relative,
        );
        assert_eq!(series.len(), names.len());
        for (i, a) in series.iter().enumerate() {
            for b in &series[..i] {
                assert_ne!(a.color, b.color, "{:?} and {:?}", a.label, b.label);
            }
        }
    }
}
