//! `friction-lab sweep SCENARIO|chain|--system FILE --grid NAME=VALUES ... --out DIR`: one run per
//! point of a grid of parameters (the product of the `--grid` axes), in parallel, each reduced
//! to its settled-state measures (`scenarios::settled`): `sweep.csv` (one row per point) and
//! `sweep.json` (the grid, the options, the rows). The rows do not depend on `--threads`.

use crate::artifacts::{Artifacts, Made};
use crate::commands::simulate::{spec, SimulateArgs, Target};
use crate::commands::system::{
    chosen_bodies, default_t_end, grid_options, system_of, system_points, RECORD_LIMIT,
};
use crate::error::AppError;
use crate::laws::ModelChoice;
use crate::output::{counted, Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use crate::progress::Progress;
use crate::ranges;
use crate::study::regime_series;
use crate::threads::with_threads;
use clap::Args;
use friction_systems::{simulate, STICK};
use integrators::Stats;
use rayon::prelude::*;
use scenarios::settled::{spanned, until_settled, Settled, Trace};
use scenarios::stick_slip::{sliding_start, Regime};
use scenarios::Scenario;
use serde::Serialize;

/// Most values on one axis.
const MAX_AXIS: usize = 1000;
/// Most points in a grid.
const MAX_POINTS: usize = 100_000;

/// Options of `sweep`.
#[derive(Args, Debug)]
pub struct SweepArgs {
    /// What to run at every point: the rig or chain, the model, the solver and the fixed
    /// parameters, as `simulate` takes them.
    #[command(flatten)]
    pub run: SimulateArgs,
    /// One axis of the grid, repeatable: NAME=V1,V2,... (a list), NAME=START:STOP:COUNT
    /// (evenly spaced), or NAME=log:START:STOP:COUNT (evenly spaced in log); any friction,
    /// scenario or chain parameter. The grid is the product of the axes, the first varying
    /// slowest.
    #[arg(long = "grid", value_name = "NAME=VALUES", required = true)]
    pub grid: Vec<String>,
    /// The measured, settled part of each run: its last fraction (0, 1] of the time span.
    #[arg(
        long,
        value_name = "FRACTION",
        default_value_t = 0.5,
        allow_hyphen_values = true
    )]
    pub settle: f64,
    /// Worker threads (default: all cores); the results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub threads: Option<i64>,
    /// Where every run starts: `rest` (the rig's x0, v0) or `sliding` (the belt only: the
    /// body at rest at the equilibrium of steady sliding, x0 = −F(−v_belt)/k, the other half of
    /// a bifurcation diagram).
    #[arg(long, value_name = "rest|sliding", default_value = "rest")]
    pub start: Start,
    /// Run only the grid points START <= i < END (0-based, in grid order): one part of the
    /// sweep, for spreading it over machines or Dask tasks; its rows equal those of the whole
    /// sweep. Every point of the grid is still checked first.
    #[arg(long, value_name = "START:END")]
    pub point_range: Option<String>,
}

/// Where a sweep's runs start.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Start {
    /// From the rig's own initial state.
    Rest,
    /// From the equilibrium of steady sliding on the belt
    /// ([`scenarios::stick_slip::sliding_start`]).
    Sliding,
}

impl std::str::FromStr for Start {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "rest" => Ok(Start::Rest),
            "sliding" => Ok(Start::Sliding),
            _ => Err(format!("unknown start `{s}`; known: rest, sliding")),
        }
    }
}

/// The points `START:END` of a grid of `n` points.
fn point_range(text: Option<&str>, n: usize) -> Result<std::ops::Range<usize>, AppError> {
    let Some(text) = text else {
        return Ok(0..n);
    };
    let bad = || {
        AppError::Usage(format!(
            "option `point-range` = `{text}` is out of range: allowed START:END with \
             0 <= START <= END <= {n} (the grid's points)"
        ))
    };
    let (start, end) = text.split_once(':').ok_or_else(bad)?;
    let parse = |s: &str| s.trim().parse::<usize>().map_err(|_| bad());
    let (start, end) = (parse(start)?, parse(end)?);
    if start > end || end > n {
        return Err(bad());
    }
    Ok(start..end)
}

/// One axis of the grid.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Axis {
    /// The parameter.
    pub name: String,
    /// Its values, in order.
    pub values: Vec<f64>,
}

impl Axis {
    /// Parses `NAME=V1,V2`, `NAME=START:STOP:COUNT` or `NAME=log:START:STOP:COUNT`.
    pub fn parse(text: &str) -> Result<Axis, AppError> {
        let bad = |why: String| AppError::Usage(format!("option `grid` = `{text}`: {why}"));
        let (name, values) = text
            .split_once('=')
            .ok_or_else(|| bad("expected NAME=VALUES".into()))?;
        let number = |s: &str| -> Result<f64, AppError> {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(format!("`{s}` is not a finite number")))
        };
        let (log, range) = match values.strip_prefix("log:") {
            Some(rest) => (true, Some(rest)),
            None => (false, values.contains(':').then_some(values)),
        };
        let values: Vec<f64> = match range {
            Some(r) => {
                let parts: Vec<&str> = r.split(':').collect();
                let [start, stop, count] = parts[..] else {
                    return Err(bad("a range is START:STOP:COUNT".into()));
                };
                let (start, stop) = (number(start)?, number(stop)?);
                let count = count
                    .trim()
                    .parse::<usize>()
                    .ok()
                    .filter(|c| (1..=MAX_AXIS).contains(c))
                    .ok_or_else(|| {
                        bad(format!(
                            "COUNT `{count}` is out of range: allowed [1, {MAX_AXIS}]"
                        ))
                    })?;
                if log && !(start > 0.0 && stop > 0.0) {
                    return Err(bad("a log range needs START > 0 and STOP > 0".into()));
                }
                let at = |i: usize| {
                    let s = if count == 1 {
                        0.0
                    } else {
                        i as f64 / (count - 1) as f64
                    };
                    // The ends exactly as given; the points between evenly spaced, to 15
                    // significant digits (0.1:1:10 gives 0.7, not 0.7000000000000001).
                    if i == 0 {
                        start
                    } else if i + 1 == count {
                        stop
                    } else if log {
                        significant((start.ln() + s * (stop.ln() - start.ln())).exp())
                    } else {
                        significant(start + s * (stop - start))
                    }
                };
                (0..count).map(at).collect()
            }
            None => values.split(',').map(number).collect::<Result<_, _>>()?,
        };
        if values.is_empty() || values.len() > MAX_AXIS {
            return Err(bad(format!(
                "{} values: allowed 1 to {MAX_AXIS}",
                values.len()
            )));
        }
        Ok(Axis {
            name: name.trim().to_string(),
            values,
        })
    }
}

/// Refuses an axis that names a parameter a second time (only the last would be used) or a
/// friction parameter that the run does not read ([`crate::options::check_read`]).
fn check_axes(axes: &[Axis], run: &SimulateArgs) -> Result<(), AppError> {
    let names: Vec<&str> = axes.iter().map(|a| a.name.as_str()).collect();
    if let Some((_, k)) = crate::options::first_repeat(&names) {
        return Err(AppError::Usage(format!(
            "option `grid`: parameter `{}` has two axes; give all its values in one",
            names[k]
        )));
    }
    // A point's values are applied after the --set's: a parameter in both would be swept
    // silently over the value the user set.
    let set = &run.model_options.params.set;
    if let Some((name, given)) = names.iter().find_map(|&n| {
        set.iter()
            .find(|a| crate::options::parse_assignment(a).is_ok_and(|(s, _)| s == n))
            .map(|a| (n, a))
    }) {
        return Err(AppError::Usage(format!(
            "option `grid`: parameter `{name}` is also given by --set {given}: every point \
             would override it; give its values in the axis only"
        )));
    }
    if run.system.is_some() {
        // A system file's contacts carry their own parameters: only the regularisation width
        // is shared.
        if let Some(name) = names.iter().find(|&&n| n != "epsilon") {
            return Err(AppError::Usage(format!(
                "option `grid`: parameter `{name}` cannot be swept on a system file (each \
                 contact has its own parameters): allowed epsilon, under --switching regularized"
            )));
        }
    }
    names.iter().try_for_each(|name| {
        crate::options::check_read(
            "grid",
            name,
            run.model.as_ref().and_then(ModelChoice::catalog),
            run.solver.switching(),
        )
    })
}

/// The grid's points in order (the first axis varying slowest), as `NAME=VALUE` assignments.
fn points(axes: &[Axis]) -> Vec<Vec<(String, f64)>> {
    let axes: Vec<(String, &[f64])> = axes
        .iter()
        .map(|a| (a.name.clone(), a.values.as_slice()))
        .collect();
    scenarios::grid::product(&axes)
}

/// One point's result.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PointResult {
    /// The point: the value of every axis, in axis order.
    pub values: Vec<f64>,
    /// Its settled-state measures.
    pub settled: Settled,
    /// Its regime (`Regime::of`, the stick–slip map's classification, against the velocity of
    /// the surface under the measured body); `None` for a run that failed.
    pub regime: Option<Regime>,
    /// Solver statistics.
    pub stats: Stats,
    /// The solver's error, if the run failed (the measures are of what it computed).
    pub error: Option<String>,
}

/// What `sweep.json` holds.
#[derive(Serialize)]
struct SweepFile<'a> {
    target: String,
    model: Option<String>,
    start: Start,
    settle: f64,
    axes: &'a [Axis],
    /// The number of points in the whole grid.
    grid_points: usize,
    /// The points run, `[start, end)` in grid order.
    point_range: [usize; 2],
    points: &'a [PointResult],
}

/// `args` with the point's assignments added after its own `--set`s.
fn at_point(args: &SimulateArgs, point: &[(String, f64)]) -> SimulateArgs {
    let mut a = args.clone();
    a.model_options
        .params
        .set
        .extend(point.iter().map(|(n, v)| format!("{n}={v}")));
    a
}

/// `x` to 15 significant digits: the value a reader would write for a point of a range
/// (the rounding of its arithmetic, a few units in the 16th digit, left out).
fn significant(x: f64) -> f64 {
    format!("{x:.14e}").parse().unwrap_or(x)
}

/// A prepared run of one point: checked before any point runs.
enum Prepared {
    Rig(scenarios::RunSpec),
    /// The chain or a system file, and the body measured.
    System {
        described: crate::commands::system::Described,
        body: usize,
    },
}

/// Checks a point's run and sets it up, started from rest or from steady sliding (the belt
/// only: another rig or a system has no such start, refused with exit 2).
fn prepare(args: &SimulateArgs, start: Start) -> Result<Prepared, AppError> {
    let refuse = |why: &str| {
        Err(AppError::Usage(format!(
            "option `--start sliding` {why}: it starts the belt's body at the equilibrium of \
             steady sliding; use --start rest"
        )))
    };
    match (args.scenario, start) {
        (Some(Target::Rig(Scenario::Belt)), Start::Sliding) => {
            let mut spec = spec(args, Scenario::Belt)?;
            if spec.params.k <= 0.0 {
                return refuse(
                    "needs a spring, k > 0 (steady sliding has no equilibrium without one)",
                );
            }
            if (args.model_options.params.set.iter())
                .any(|a| crate::options::parse_assignment(a).is_ok_and(|(n, _)| n == "x0"))
            {
                return refuse("sets x0 itself: drop x0 from --set and --grid");
            }
            let model = spec.law.build(&spec.friction)?;
            spec.params.x0 = sliding_start(model.as_ref(), spec.params.v_belt, spec.params.k);
            spec.params.v0 = 0.0;
            Ok(Prepared::Rig(spec))
        }
        (_, Start::Sliding) => refuse("applies to the belt rig only"),
        (Some(Target::Rig(scenario)), Start::Rest) => Ok(Prepared::Rig(spec(args, scenario)?)),
        _ => {
            let described = system_of(
                args.system.as_deref(),
                args.model.as_ref(),
                &args.model_options,
            )?;
            described.system.validate()?;
            let body = chosen_bodies(&described.system, &args.bodies)?
                .first()
                .copied()
                .unwrap_or(0);
            args.solver.checked_step()?;
            Ok(Prepared::System { described, body })
        }
    }
}

/// Runs one prepared point and measures its settled state: its span doubled (the output
/// spacing kept) while the run ends without an error and has not settled
/// ([`Settled::settled`]; [`until_settled`]).
fn run_point(
    args: &SimulateArgs,
    prepared: Prepared,
    settle: f64,
) -> Result<PointResult, AppError> {
    until_settled(
        |factor| run_spanned(args, &prepared, settle, factor),
        |point| point.settled.settled || point.error.is_some(),
    )
}

/// Runs one prepared point over `factor` times its span, with `factor` times its output
/// intervals, and measures its settled state.
fn run_spanned(
    args: &SimulateArgs,
    prepared: &Prepared,
    settle: f64,
    factor: u32,
) -> Result<PointResult, AppError> {
    let (trace, stats, error, surface_velocity) = match prepared {
        Prepared::Rig(spec) => {
            let o = scenarios::run(&spanned(spec, factor), &mut |_| {})?;
            // The belt under the body, where the rig has one; the floor otherwise.
            let surface = match spec.scenario.parameters().contains(&"v_belt") {
                true => spec.params.v_belt,
                false => 0.0,
            };
            (
                Trace::of_outcome(&o),
                o.stats,
                o.error.map(|e| e.to_string()),
                surface,
            )
        }
        Prepared::System { described, body } => {
            let body = *body;
            let t_end = args
                .checked_t_end()?
                .unwrap_or_else(|| default_t_end(args.system.as_deref()));
            let dim = friction_systems::Layout::of(&described.system).dim();
            // The output spacing kept, within the numbers a run may record.
            let points = ((system_points(args, dim)? - 1) * factor as usize + 1)
                .min(RECORD_LIMIT / dim.max(1));
            let options = grid_options(args, t_end * f64::from(factor), points)?;
            let scheme = args
                .solver
                .switching()
                .scheme(args.solver.solver(), &described.friction);
            let run = simulate(&described.system, scheme, options, &mut |_| {})?;
            let mut trace = Trace::default();
            for b in run.body(body) {
                trace.t.push(b.t);
                trace.x.push(b.x);
                trace.v.push(b.v);
                trace.friction.push(b.friction);
            }
            trace.stick_entries = run
                .contact_events()
                .iter()
                .filter(|e| e.body == body && e.to == STICK && e.from != STICK)
                .map(|e| e.t)
                .collect();
            let surface = (described.system.contacts.iter())
                .find(|c| c.body == body)
                .map_or(0.0, |c| c.surface_velocity);
            (
                trace,
                run.solution.stats,
                run.error.map(|e| e.to_string()),
                surface,
            )
        }
    };
    let mut settled = Settled::of(&trace, settle);
    // A run that failed stopped short of its span: whatever its window shows, it is no
    // settled state, and it has no regime.
    settled.settled &= error.is_none();
    let regime = error
        .is_none()
        .then(|| Regime::of(&settled, surface_velocity));
    Ok(PointResult {
        values: Vec::new(),
        settled,
        regime,
        stats,
        error,
    })
}

/// The labels of the regimes in a sweep's figure.
const REGIMES: [(Regime, &str); 5] = [
    (Regime::StickSlip, "stick-slip"),
    (Regime::Oscillation, "oscillation without stick"),
    (Regime::SteadySliding, "steady sliding"),
    (Regime::Stuck, "carried by the surface all along"),
    (Regime::Unsettled, "not settled (a transient)"),
];

/// Whether `values` are drawn on a log axis: all positive and spanning a decade or more.
fn log_axis(values: &[f64]) -> bool {
    let (lo, hi) = values.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &v| {
        (lo.min(v), hi.max(v))
    });
    values.iter().all(|&v| v > 0.0) && hi >= 10.0 * lo
}

/// The figure of a sweep of one or two axes (none for more): over one axis the settled
/// amplitude of x − v̄·t at every point, over two the plane of the axes, each point in the
/// colour and marker of its regime; a failed point is a cross of its own (on the axis, for
/// one axis).
fn figure(axes: &[Axis], results: &[PointResult], title: &str) -> Option<Plot> {
    let failed = |at: &dyn Fn(&PointResult) -> (f64, f64)| Series {
        label: Some("failed (sweep.csv says why)".into()),
        points: results
            .iter()
            .filter(|r| r.regime.is_none())
            .map(at)
            .collect(),
        color: PALETTE[5],
        width: 0,
        marker: Marker::Cross,
    };
    let by_regime = |at: &dyn Fn(&PointResult) -> (f64, f64)| {
        let mut series: Vec<Series> = (REGIMES.iter())
            .map(|&(regime, label)| {
                let mine = results.iter().filter(|r| r.regime == Some(regime));
                regime_series(regime, label, mine.map(at).collect())
            })
            .chain([failed(at)])
            .collect();
        series.retain(|s| !s.points.is_empty());
        series
    };
    let label = |a: &Axis| {
        use friction_models::{FrictionParams, Parameters};
        let unit = (FrictionParams::spec(&a.name).map(|s| s.unit))
            .or_else(|| scenarios::ScenarioParams::spec(&a.name).map(|s| s.unit))
            .or_else(|| {
                let chain = friction_systems::chain::CHAIN_PARAMETERS;
                chain.iter().find(|p| p.0 == a.name).map(|p| p.2)
            });
        match unit {
            Some(u) if !u.is_empty() && u != "1" => format!("{} ({u})", a.name),
            _ => a.name.clone(),
        }
    };
    match axes {
        [x] => Some(Plot {
            title: format!("{title}: settled amplitude"),
            x_label: label(x),
            y_label: "half the range of x − v̄·t over the settled window (m)".into(),
            series: by_regime(&|r| (r.values[0], r.settled.x_amplitude.max(0.0))),
            legend: Corner::UpperRight,
            log: false,
        }),
        [x, y] => Some(Plot {
            title: format!("{title}: settled regime"),
            x_label: label(x),
            y_label: label(y),
            series: by_regime(&|r| (r.values[0], r.values[1])),
            legend: Corner::UpperRight,
            log: log_axis(&x.values) && log_axis(&y.values),
        }),
        _ => None,
    }
}

/// Runs `sweep`; its files in memory.
pub fn make(args: &SweepArgs) -> Result<Made, AppError> {
    let threads = ranges::threads(args.threads)?;
    if !(args.settle > 0.0 && args.settle <= 1.0) {
        return Err(AppError::Usage(format!(
            "option `settle` = {} is out of range: allowed (0, 1]",
            ranges::show(args.settle)
        )));
    }
    let axes: Vec<Axis> = args
        .grid
        .iter()
        .map(|g| Axis::parse(g))
        .collect::<Result<_, _>>()?;
    check_axes(&axes, &args.run)?;
    let grid = points(&axes);
    if grid.len() > MAX_POINTS {
        return Err(AppError::Usage(format!(
            "option `grid` makes {} points: allowed at most {MAX_POINTS}",
            grid.len()
        )));
    }
    // Every point is checked (names, ranges, combinations) before any runs.
    // `--time-limit` bounds the whole sweep: every point counts from here.
    let since = std::time::Instant::now();
    let runs: Vec<SimulateArgs> = grid
        .iter()
        .map(|p| {
            let mut a = at_point(&args.run, p);
            a.solver.limits.since = Some(since);
            a
        })
        .collect();
    for a in &runs {
        prepare(a, args.start)?;
    }
    let range = point_range(args.point_range.as_deref(), grid.len())?;
    let b = Progress::runs(range.len(), "sweep");
    let results: Vec<PointResult> = with_threads(threads, || {
        runs[range.clone()]
            .par_iter()
            .zip(&grid[range.clone()])
            .map(|(a, point)| {
                let r = run_point(a, prepare(a, args.start)?, args.settle);
                b.inc();
                r.map(|r| PointResult {
                    values: point.iter().map(|(_, v)| *v).collect(),
                    ..r
                })
            })
            .collect::<Result<Vec<_>, AppError>>()
    })??;
    b.finish();
    let mut header: Vec<&str> = axes.iter().map(|a| a.name.as_str()).collect();
    header.extend([
        "stick_phases",
        "stick_per_cycle",
        "period",
        "x_amplitude",
        "v_amplitude",
        "v_amplitude_ratio",
        "v_mean",
        "friction_mean",
        "friction_peak",
        "settled",
        "regime",
        "drift",
        "t_end",
        "steps",
        "rhs_evals",
        "events",
        "status",
    ]);
    let mut table = Table::new(&header);
    // An undefined measure (no oscillation) is an empty cell, never NaN.
    let num = Cell::num;
    for r in &results {
        let s = &r.settled;
        let mut row: Vec<Cell> = r.values.iter().map(|&v| Cell::Num(v)).collect();
        row.extend([
            Cell::Num(s.stick_phases as f64),
            num(s.stick_per_cycle),
            num(s.period),
            num(s.x_amplitude),
            num(s.v_amplitude),
            num(s.v_amplitude_ratio),
            num(s.v_mean),
            num(s.friction_mean),
            num(s.friction_peak),
            Cell::Text(s.settled.to_string()),
            Cell::Text(r.regime.map(|g| format!("{g:?}")).unwrap_or_default()),
            num(s.drift),
            Cell::Num(s.to),
            Cell::Num(r.stats.steps as f64),
            Cell::Num(r.stats.rhs_evals as f64),
            Cell::Num(r.stats.events as f64),
            Cell::Text(r.error.clone().unwrap_or_else(|| "ok".into())),
        ]);
        table.rows.push(row);
    }
    let mut files = Artifacts::default();
    let csv = args.run.out.join("sweep.csv");
    files.add(csv.clone(), table.to_csv(&csv)?);
    let target = match (args.run.scenario, &args.run.system) {
        (Some(Target::Rig(s)), _) => s.name().to_string(),
        (_, Some(file)) => file.display().to_string(),
        _ => "chain".into(),
    };
    let title = match &args.run.model {
        Some(m) => format!("{target} with {}", m.name()),
        None => target.clone(),
    };
    if let Some(plot) = figure(&axes, &results, &title) {
        files.add_plot(&args.run.out.join("sweep"), &plot)?;
    }
    files.add_json(
        args.run.out.join("sweep.json"),
        &SweepFile {
            target,
            model: args.run.model.as_ref().map(|m| m.name().to_string()),
            start: args.start,
            settle: args.settle,
            axes: &axes,
            grid_points: grid.len(),
            point_range: [range.start, range.end],
            points: &results,
        },
    )?;
    let failed = results.iter().filter(|r| r.error.is_some()).count();
    Ok(Made {
        files,
        notes: vec![format!(
            "{}, {failed} failed",
            counted(results.len(), "point", "points")
        )],
        warnings: crate::warnings::unread_warnings(
            &args.run.model_options.params.set,
            args.run.model.as_ref().and_then(ModelChoice::catalog),
            args.run.solver.switching(),
        )
        .into_iter()
        .chain(args.run.solver.scheme.spelling_notes())
        .collect(),
        failure: (failed > 0).then(|| {
            AppError::StudyRun(format!(
                "{failed} of {} runs failed; sweep.csv says which and why",
                results.len()
            ))
        }),
        trajectory: None,
    })
}
