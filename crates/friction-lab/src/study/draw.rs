//! The figures' pieces the studies share: one series per solver with its failed runs drawn
//! at the top, and the guides of fitted orders.

use crate::plot::{Dash, Marker, Series, PALETTE};

/// The name of the work axis: f evaluations, with each Jacobian, LU factorisation and solve
/// weighted by its flops in f evaluations (`scenarios::studies::work`, docs/studies.md).
pub const WORK_LABEL: &str = "work (f evaluations, weighted)";
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

/// The marker and dash pattern of the `i`-th series of a figure: every pair distinct for the
/// first sixteen, the dash advancing with the marker, so that neither colour nor either alone
/// is needed to tell series apart (in greyscale).
pub fn series_style(i: usize) -> (Marker, Dash) {
    let (markers, dashes) = (Marker::FILLED.len(), Dash::ALL.len());
    (
        Marker::FILLED[i % markers],
        Dash::ALL[(i + i / markers) % dashes],
    )
}

/// What one method draws: its runs judged `ok`, those judged inaccurate, and the x of its
/// failed runs.
#[derive(PartialEq)]
struct Drawn {
    plotted: Vec<(f64, f64)>,
    judged: Vec<(f64, f64)>,
    failed: Vec<f64>,
}

/// One series per solver of the runs `keep` selects, with a marker on every run judged `ok`, a
/// cross in its colour where a run judged inaccurate lies, and, per solver with failed runs, a
/// series of crosses drawn at the top of the plot at their x (a failed run has no error to
/// plot, but it is not left out), each such solver in a row of its own ([`row_at_top`]); the
/// legend names the two kinds of cross once each, in black (the tables count them), and a
/// solver without a run judged `ok` by its crosses. Each solver has its colour, marker and dash pattern ([`series_style`]);
/// solvers whose runs draw the same points (`auto` that never switched from `dopri5`) are
/// drawn once, named for all of them ("dopri5 = auto"; past three, the first two and a count).
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
    let largest = runs
        .iter()
        .filter(drawable)
        .map(|r| y(r))
        .reduce(f64::max)
        .unwrap_or(1.0);
    // Each solver's points, and the solvers that draw the same ones, in the order of first run.
    let mut groups: Vec<(Vec<&str>, Drawn)> = Vec::new();
    for name in &names {
        let mine = || runs.iter().filter(|r| r.method() == *name);
        let drawn = Drawn {
            plotted: (mine().filter(|r| drawable(r) && r.judged_ok()))
                .map(|r| (x(r), y(r)))
                .collect(),
            judged: (mine().filter(|r| drawable(r) && !r.judged_ok()))
                .map(|r| (x(r), y(r)))
                .collect(),
            failed: mine().filter(|r| r.failed()).map(|r| x(r)).collect(),
        };
        match groups.iter_mut().find(|(_, d)| *d == drawn) {
            Some((same, _)) => same.push(name),
            None => groups.push((vec![name], drawn)),
        }
    }
    let mut series = Vec::new();
    let (mut rows, mut inaccurate) = (0, false);
    for (i, ((names, drawn), &color)) in groups.into_iter().zip(PALETTE.iter().cycle()).enumerate()
    {
        let name = match names.as_slice() {
            [first, second, _, _, ..] => {
                format!(
                    "{first} = {second} and {} more (identical)",
                    names.len() - 2
                )
            }
            _ => names.join(" = "),
        };
        let (marker, dash) = series_style(i);
        // A solver without a run to mark names its crosses, the first series it draws.
        let mut unnamed = drawn.plotted.is_empty().then(|| name.clone());
        if !drawn.plotted.is_empty() {
            series.push(Series {
                label: Some(name.clone()),
                points: drawn.plotted,
                color,
                width: 2,
                marker,
                dash,
            });
        }
        // A run judged inaccurate is data, drawn where it is, but marked apart from the dots.
        if !drawn.judged.is_empty() {
            inaccurate = true;
            series.push(Series {
                label: unnamed.take(),
                points: drawn.judged,
                color,
                width: 0,
                marker: Marker::Cross,
                dash: Dash::Solid,
            });
        }
        let top = row_at_top(largest, rows);
        if !drawn.failed.is_empty() {
            rows += 1;
            series.push(Series {
                label: unnamed.take(),
                points: drawn.failed.iter().map(|&x| (x, top)).collect(),
                color,
                width: 0,
                marker: Marker::Cross,
                dash: Dash::Solid,
            });
        }
    }
    // One legend entry for the crosses of every solver (a legend of one entry per solver and
    // kind outgrew its plot).
    let crosses = [
        (inaccurate, "inaccurate run (error ≥ solution)"),
        (rows > 0, "failed run (drawn at the top)"),
    ];
    for (_, label) in crosses.into_iter().filter(|(shown, _)| *shown) {
        series.push(Series {
            label: Some(label.into()),
            points: vec![],
            color: plotters::style::RGBColor(0, 0, 0),
            width: 0,
            marker: Marker::Cross,
            dash: Dash::Solid,
        });
    }
    series
}

/// A guide for each table's fit, drawn through its asymptotic range only (grey, dashed, dotted
/// or long-dashed in turn): the fitted line
/// error = e^intercept · h^slope from the finest to the coarsest resolution it rests on, named
/// with the solver, the slope and its 95 % interval (tables without a fit draw none).
pub fn fitted_guides(tables: &[&OrderTable]) -> Vec<Series> {
    tables
        .iter()
        .filter_map(|t| Some((t, t.fit?)))
        .zip([120u8, 160, 80].iter().cycle())
        .zip(
            [Dash::Dashed, Dash::Dotted, Dash::LongDashed]
                .iter()
                .cycle(),
        )
        .map(|(((t, f), &shade), &dash)| {
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
                dash,
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
            .filter(|s| s.marker == Marker::Cross && !s.points.is_empty())
            .map(|s| s.points[0])
            .collect();
        assert_eq!(crosses, [(0.02, 3e-2), (0.02, 3e-2 * 1.5)]);
    }

    #[test]
    fn sixteen_series_each_have_their_own_marker_and_dash_the_first_four_each_their_own_dash() {
        let pairs: std::collections::HashSet<String> =
            (0..16).map(|i| format!("{:?}", series_style(i))).collect();
        assert_eq!(pairs.len(), 16);
        let dashes: std::collections::HashSet<String> =
            (0..4).map(|i| format!("{:?}", series_style(i).1)).collect();
        assert_eq!(dashes.len(), 4);
        assert_eq!(series_style(0), (Marker::Dot, Dash::Solid));
    }

    #[test]
    fn a_solver_drawing_the_same_points_as_another_is_drawn_once_named_for_both() {
        // auto that never switched from dopri5: the same runs, one series "dopri5 = auto".
        let runs = [
            run("dopri5", 1e-4, 1e-5, None),
            run("dopri5", 1e-6, 1e-7, None),
            run("rk4", 1e-4, 1e-3, None),
            run("auto", 1e-4, 1e-5, None),
            run("auto", 1e-6, 1e-7, None),
        ];
        let series = per_solver_series(
            &runs,
            |_| true,
            |r| r.resolution,
            |r| r.errors.final_relative,
        );
        let labels: Vec<&str> = series.iter().filter_map(|s| s.label.as_deref()).collect();
        assert_eq!(labels, ["dopri5 = auto", "rk4"]);
        // One point apart, and they are two.
        let mut apart = runs.to_vec();
        apart[4].errors.final_relative = 2e-7;
        let series = per_solver_series(
            &apart,
            |_| true,
            |r| r.resolution,
            |r| r.errors.final_relative,
        );
        assert_eq!(series.len(), 3);
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
        let runs: Vec<StudyRun> = (names.iter().enumerate())
            .map(|(i, n)| run(n, 0.01, 1e-4 * (i + 1) as f64, None))
            .collect();
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
