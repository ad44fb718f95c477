//! The solver studies: `converge`, `independence`, `work-precision`, `stiffness`. Every
//! run of a study is independent; they run on a pool of `--threads` workers and are
//! collected in order, so the files do not depend on the thread count (wall times, which
//! cannot be reproduced, go to a separate `*-timing.csv`).

use crate::artifacts::{Artifacts, Made};
use crate::commands::phenomena::with_threads;
use crate::commands::simulate::Target as Problem;
use crate::commands::system::{chosen_bodies, system_of, FILE_T_END};
use crate::error::AppError;
use crate::options::{LimitArgs, ModelOptions};
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use crate::progress::Progress;
use crate::ranges;
use clap::Args;
use friction_models::ModelId;
use integrators::Solver;
use scenarios::studies::{
    self, Case, Convergence, Independence, Method, Stiffness, StudyCase, StudyRun, SystemCase,
    WorkPrecision,
};
use scenarios::{Scenario, SwitchingKind};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// What a study's JSON says it studied, beside the study's own fields: the case as its plots
/// name it, its treatment of v = 0 and its end time.
#[derive(Serialize)]
struct StudyFile<'a, T: Serialize> {
    case: CaseRecord,
    #[serde(flatten)]
    study: &'a T,
}

/// The case of a study, as its JSON records it.
#[derive(Serialize)]
struct CaseRecord {
    description: String,
    switching: SwitchingKind,
    t_end: f64,
}

impl CaseRecord {
    fn of(case: &dyn StudyCase) -> CaseRecord {
        CaseRecord {
            description: case.describe(),
            switching: case.switching(),
            t_end: case.t_end(),
        }
    }
}

/// `study` of `case`, for its JSON.
fn study_file<'a, T: Serialize>(case: &dyn StudyCase, study: &'a T) -> StudyFile<'a, T> {
    StudyFile {
        case: CaseRecord::of(case),
        study,
    }
}

/// A cost-against-size study's JSON: the case at each size, beside the study's own fields.
#[derive(Serialize)]
struct ScalingFile<'a> {
    cases: Vec<SizedCase>,
    #[serde(flatten)]
    study: &'a studies::Scaling,
}

/// One size of a cost-against-size study and its case.
#[derive(Serialize)]
struct SizedCase {
    bodies: usize,
    #[serde(flatten)]
    case: CaseRecord,
}

/// The problem a study runs.
#[derive(Args, Debug, Clone)]
pub struct CaseArgs {
    /// A scenario (paper-block, belt, free-vibration, …), or chain (the Burridge–Knopoff
    /// chain of systems.md, its parameters by --set); omit it with --system.
    #[arg(
        value_name = "SCENARIO",
        required_unless_present = "system",
        conflicts_with = "system"
    )]
    pub scenario: Option<Problem>,
    /// A system file (TOML, shared/spec/systems.md) to study instead of a scenario.
    #[arg(long, value_name = "FILE.toml")]
    pub system: Option<PathBuf>,
    /// The friction model (scenarios and chain).
    #[arg(long, value_name = "MODEL")]
    pub model: Option<ModelId>,
    /// Systems: the bodies whose trajectories, event times and stick phases are measured
    /// (names or 1-based indices) [default: the first body]; every body's final state is.
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    pub bodies: Vec<String>,
    /// event, regularized, naive, or timestepping (Moreau–Jean at θ = 1/2, the study's one
    /// method: over the step sizes, the solver options unused; its reference is event-driven)
    /// [default: event; for `stiffness` of a rig over epsilon, regularized]
    #[arg(long, value_name = "event|regularized|naive|timestepping")]
    pub switching: Option<SwitchingKind>,
    /// End time, s [default: the scenario's; 50 for the chain; 20 for a system file].
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub t_end: Option<f64>,
    /// Folder to write into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The bounds of each run (a run past them fails, and the study says which).
    #[command(flatten)]
    pub limits: LimitArgs,
    /// Worker threads (default: all cores; more than the machine has are capped to its cores).
    /// The results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub threads: Option<i64>,
    /// The model's parameters and reading.
    #[command(flatten)]
    pub model_options: ModelOptions,
}

impl CaseArgs {
    /// The study case: a rig, the chain, or a system file.
    pub fn case(&self) -> Result<Box<dyn StudyCase>, AppError> {
        let check_t_end = |t_end: f64| ranges::T_END.check(t_end);
        let scenario = match self.scenario {
            Some(Problem::Rig(s)) => s,
            _ => {
                let described = system_of(self.system.as_deref(), self.model, &self.model_options)?;
                described.system.validate()?;
                let default_t_end = if self.system.is_some() {
                    FILE_T_END
                } else {
                    crate::commands::system::CHAIN_T_END
                };
                let bodies = if self.bodies.is_empty() {
                    vec![0]
                } else {
                    chosen_bodies(&described.system, &self.bodies)?
                };
                return Ok(Box::new(SystemCase {
                    name: described.name,
                    system: described.system,
                    switching: self.switching.unwrap_or(SwitchingKind::Event),
                    epsilon: described.friction.epsilon,
                    t_end: check_t_end(self.t_end.unwrap_or(default_t_end))?,
                    bodies,
                    limits: self.limits.limits()?,
                }));
            }
        };
        if scenario == Scenario::VelocitySweep {
            return Err(AppError::Usage(
                "the studies integrate trajectories: velocity-sweep has none; use another scenario"
                    .into(),
            ));
        }
        if !self.bodies.is_empty() {
            return Err(AppError::Usage(
                "option `--bodies` applies to systems (chain, --system), not to a rig".into(),
            ));
        }
        let model = self.model.ok_or_else(|| {
            AppError::Usage(format!(
                "option `--model` is required for scenario {scenario}: e.g. --model CS"
            ))
        })?;
        let (friction, params) = self.model_options.params.resolve_for(Some(scenario))?;
        let t_end = check_t_end(
            self.t_end
                .unwrap_or_else(|| scenario.default_t_end(&params, &friction)),
        )?;
        Ok(Box::new(Case {
            scenario,
            law: model.into(),
            friction,
            params,
            switching: self.switching.unwrap_or(SwitchingKind::Event),
            t_end,
            limits: self.limits.limits()?,
        }))
    }
}

impl CaseArgs {
    /// Sets up the case, runs `study` (which returns its lines for the terminal), and keeps
    /// its files in memory.
    fn make(
        &self,
        study: impl FnOnce(&mut Target, &dyn StudyCase) -> Result<Vec<String>, AppError>,
    ) -> Result<Made, AppError> {
        let case = self.case()?;
        let case = case.as_ref();
        let mut files = Artifacts::default();
        let mut target = Target {
            files: &mut files,
            dir: &self.out,
            threads: ranges::threads(self.threads)?,
            failure: None,
        };
        let notes = study(&mut target, case)?;
        let failure = target.failure;
        Ok(Made {
            files,
            notes,
            failure,
            ..Made::default()
        })
    }
}

/// `--solvers` with each solver once (a study names its runs by solver).
fn distinct(solvers: &[Solver]) -> Result<(), AppError> {
    for (k, s) in solvers.iter().enumerate() {
        if solvers[..k].contains(s) {
            return Err(AppError::Usage(format!(
                "option `solvers` names `{}` twice: allowed each solver once",
                s.name()
            )));
        }
    }
    Ok(())
}

fn positive_list(name: &'static str, values: &[f64]) -> Result<(), AppError> {
    match values.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
        Some(v) => Err(AppError::Usage(format!(
            "option `{name}` has {v}: allowed values (0, inf)"
        ))),
        None if values.is_empty() => Err(AppError::Usage(format!("option `{name}` is empty"))),
        None => Ok(()),
    }
}

/// Where a study's files go, and on how many threads it runs.
pub struct Target<'a> {
    /// The files being prepared.
    pub files: &'a mut Artifacts,
    /// The folder.
    pub dir: &'a Path,
    /// Worker threads (all cores when `None`).
    pub threads: Option<usize>,
    /// A failure the files record (a level of an independence study that failed): the
    /// command writes them, then exits with it.
    pub failure: Option<AppError>,
}

/// The levels of an independence study.
#[derive(Clone, Copy, Debug)]
pub struct Refinement {
    /// The coarsest step size or tolerance.
    pub start: f64,
    /// The ratio between levels.
    pub ratio: f64,
    /// Number of levels.
    pub levels: i64,
    /// Relative tolerance of the verdict.
    pub tol: f64,
}

fn study_error(e: scenarios::ScenarioError) -> AppError {
    AppError::from(e)
}

/// The columns `h` and `tol` of a run with `resolution` of kind `step` (`fixed`: a step
/// size, `adaptive`: a tolerance): the one that applies, the other empty, so that each column
/// holds one quantity.
fn resolution_cells(step: Option<&str>, resolution: Option<f64>) -> [Cell; 2] {
    let empty = || Cell::Text(String::new());
    match (step, resolution) {
        (Some("fixed"), Some(h)) => [Cell::Num(h), empty()],
        (Some(_), Some(tol)) => [empty(), Cell::Num(tol)],
        _ => [empty(), empty()],
    }
}

/// One CSV row per run: solver, step size or tolerance, the errors, the work.
fn runs_table(runs: &[StudyRun], path: &Path) -> Result<Vec<u8>, AppError> {
    let mut t = Table::new(&[
        "solver",
        "step",
        "h",
        "tol",
        "work",
        "error_final_state",
        "error_grid_max",
        "error_event_times",
        "error_stick_durations",
        "steps",
        "rejected",
        "rhs_evals",
        "jacobian_evals",
        "lu_factorizations",
        "newton_iterations",
        "events",
        "status",
    ]);
    for r in runs {
        // A missing measure (no events to compare) is written as an empty cell, never NaN.
        let num = Cell::num;
        let s = r.stats;
        let [h, tol] = resolution_cells(Some(r.step), Some(r.resolution));
        t.rows.push(vec![
            Cell::Text(r.solver.clone()),
            Cell::Text(r.step.into()),
            h,
            tol,
            Cell::Num(r.work as f64),
            num(r.errors.final_state),
            num(r.errors.grid_max),
            num(r.errors.event_times),
            num(r.errors.stick_durations),
            Cell::Num(s.steps as f64),
            Cell::Num(s.rejected() as f64),
            Cell::Num(s.rhs_evals as f64),
            Cell::Num(s.jacobian_evals as f64),
            Cell::Num(s.lu_factorizations as f64),
            Cell::Num(s.newton_iterations as f64),
            Cell::Num(s.events as f64),
            Cell::Text(r.failure.clone().unwrap_or_else(|| "ok".into())),
        ]);
    }
    t.to_csv(path)
}

/// log10 of (x, y) pairs with both positive and finite.
/// One series per solver of the runs `keep` selects, with a dot on every run that computed,
/// and, per solver with failed runs, a series of crosses drawn at the top of the plot at their
/// x, named with their count (a failed run has no error to plot, but it is not left out).
fn per_solver_series(
    runs: &[StudyRun],
    keep: impl Fn(&StudyRun) -> bool,
    x: impl Fn(&StudyRun) -> f64,
    y: impl Fn(&StudyRun) -> f64,
) -> Vec<Series> {
    let runs: Vec<&StudyRun> = runs.iter().filter(|r| keep(r)).collect();
    let mut names: Vec<&str> = Vec::new();
    for r in &runs {
        if !names.contains(&r.solver.as_str()) {
            names.push(&r.solver);
        }
    }
    let plotted = |r: &&&StudyRun| r.failure.is_none() && y(r) > 0.0 && y(r).is_finite();
    let top = runs
        .iter()
        .filter(plotted)
        .map(|r| y(r))
        .reduce(f64::max)
        .unwrap_or(1.0)
        * 3.0;
    let mut series = Vec::new();
    for (name, &color) in names.iter().zip(PALETTE.iter().cycle()) {
        let mine = || runs.iter().filter(|r| r.solver == *name);
        let points: Vec<(f64, f64)> = mine().filter(plotted).map(|r| (x(r), y(r))).collect();
        if !points.is_empty() {
            series.push(Series {
                label: Some(name.to_string()),
                points,
                color,
                width: 2,
                marker: Marker::Dot,
            });
        }
        let failed: Vec<(f64, f64)> = mine()
            .filter(|r| r.failure.is_some())
            .map(|r| (x(r), top))
            .collect();
        if !failed.is_empty() {
            series.push(Series {
                label: Some(format!("{name}: {} failed (at the top)", failed.len())),
                points: failed,
                color,
                width: 0,
                marker: Marker::Cross,
            });
        }
    }
    series
}

/// Reference lines of slope `p` (on log–log axes) through the first point of the first
/// series, drawn only over that series' x-range.
fn slope_lines(series: &[Series], slopes: &[f64]) -> Vec<Series> {
    let Some(first) = series.iter().find(|s| s.marker == Marker::Dot) else {
        return Vec::new();
    };
    let (x0, y0) = first.points[0];
    let (lo, hi) = first
        .points
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
            (lo.min(p.0), hi.max(p.0))
        });
    slopes
        .iter()
        .zip([170u8, 120, 70].iter().cycle())
        .map(|(&p, &shade)| Series {
            label: Some(format!("slope {p}")),
            points: [lo, hi]
                .iter()
                .map(|&x| (x, y0 * (x / x0).powf(p)))
                .collect(),
            color: plotters::style::RGBColor(shade, shade, shade),
            width: 1,
            marker: Marker::None,
        })
        .collect()
}

/// Options of `converge`.
#[derive(Args, Debug)]
pub struct ConvergeArgs {
    /// The problem.
    #[command(flatten)]
    pub case: CaseArgs,
    /// Solvers, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "rk4,dopri5,implicit-euler"
    )]
    pub solvers: Vec<Solver>,
    /// Step sizes of rk4, dopri5 and implicit-euler (fixed steps), coarse to fine.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0.02,0.01,0.005,0.0025"
    )]
    pub dt_list: Vec<f64>,
    /// Tolerances of diffsol's adaptive methods, loose to tight.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "1e-4,1e-6,1e-8"
    )]
    pub tol_list: Vec<f64>,
}

/// Computes a convergence study and adds its files (`converge.csv`, `converge.json`,
/// `converge.png`/`.svg`) under `dir` with file stem `stem`.
pub fn add_convergence(
    t: &mut Target,
    stem: &str,
    case: &dyn StudyCase,
    solvers: &[Solver],
    steps: &[f64],
    tols: &[f64],
) -> Result<Convergence, AppError> {
    let (dir, threads) = (t.dir, t.threads);
    distinct(solvers)?;
    ranges::DT.list("dt-list", steps)?;
    ranges::RTOL.list("tol-list", tols)?;
    let jobs = solvers
        .iter()
        .map(|&s| studies::steps_for(s, steps, tols, true).len())
        .sum();
    let b = Progress::runs(jobs, "converge");
    let c = with_threads(threads, || {
        studies::convergence(case, solvers, steps, tols, &|| b.inc())
    })?
    .map_err(study_error)?;
    b.finish();
    let csv = dir.join(format!("{stem}.csv"));
    t.files.add(csv.clone(), runs_table(&c.runs, &csv)?);
    t.files
        .add_json(dir.join(format!("{stem}.json")), &study_file(case, &c))?;
    // Step sizes and tolerances are different things: one panel each.
    let panel = |step: &str, x_label: &str, slopes: &[f64]| {
        let mut series = per_solver_series(
            &c.runs,
            |r| r.step == step,
            |r| r.resolution,
            |r| r.errors.grid_max,
        );
        series.extend(slope_lines(&series, slopes));
        Plot {
            title: format!("Convergence ({step} steps): {}", case.describe()),
            x_label: x_label.into(),
            y_label: "max error on the time grid".into(),
            series,
            legend: Corner::default(),
            log: true,
        }
    };
    let panels: Vec<Plot> = [
        panel("fixed", "step size h (s)", &[1.0, 4.0, 5.0]),
        panel("adaptive", "tolerance (rtol = atol)", &[1.0]),
    ]
    .into_iter()
    .filter(|p| !p.series.is_empty())
    .collect();
    t.files.add_panels(&dir.join(stem), &panels)?;
    Ok(c)
}

/// Runs `converge`; its files in memory.
pub fn converge(a: &ConvergeArgs) -> Result<Made, AppError> {
    a.case.make(|t, case| {
        let c = add_convergence(t, "converge", case, &a.solvers, &a.dt_list, &a.tol_list)?;
        Ok(c.orders
            .iter()
            .map(|o| {
                let slope = o.fitted_slope.map_or("-".into(), |s| format!("{s:.3}"));
                format!("{:15} {:16} fitted slope {slope}", o.solver, o.measure)
            })
            .collect())
    })
}

/// Options of `independence`.
#[derive(Args, Debug)]
pub struct IndependenceArgs {
    /// The problem.
    #[command(flatten)]
    pub case: CaseArgs,
    /// The solver.
    #[arg(long, value_name = "SOLVER", default_value = "rk4")]
    pub solver: Solver,
    /// The coarsest step size (rk4) or tolerance (adaptive solvers).
    #[arg(
        long,
        value_name = "H",
        default_value_t = 1e-3,
        allow_hyphen_values = true
    )]
    pub start: f64,
    /// Refinement ratio between levels.
    #[arg(
        long,
        value_name = "R",
        default_value_t = 2.0,
        allow_hyphen_values = true
    )]
    pub ratio: f64,
    /// Number of levels.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 4,
        allow_hyphen_values = true
    )]
    pub levels: i64,
    /// Relative tolerance of the verdict.
    #[arg(
        long,
        value_name = "TOL",
        default_value_t = 1e-6,
        allow_hyphen_values = true
    )]
    pub tol: f64,
}

/// Computes an independence study and adds its files under `dir` with stem `stem`.
pub fn add_independence(
    t: &mut Target,
    stem: &str,
    case: &dyn StudyCase,
    solver: Solver,
    r: Refinement,
) -> Result<Independence, AppError> {
    let (dir, threads) = (t.dir, t.threads);
    let Refinement {
        start,
        ratio,
        levels,
        tol,
    } = r;
    if !(0.0..=1.0).contains(&tol) || tol == 0.0 {
        return Err(AppError::Usage(format!(
            "option `tol` = {tol} is out of range: allowed (0, 1]"
        )));
    }
    if !(ratio.is_finite() && ratio > 1.0 && ratio <= 1e3) {
        return Err(AppError::Usage(format!(
            "option `ratio` = {ratio} is out of range: allowed (1, 1000]"
        )));
    }
    if !(2..=12).contains(&levels) {
        return Err(AppError::Usage(format!(
            "option `levels` = {levels} is out of range: allowed [2, 12]"
        )));
    }
    let levels = levels as usize;
    // Every level is a step size (fixed-step solvers) or a tolerance, in that option's range.
    let resolution = if solver.is_fixed_step() || case.switching().is_time_stepping() {
        ranges::DT
    } else {
        ranges::RTOL
    };
    let finest = start / ratio.powi(levels as i32 - 1);
    resolution
        .check(start)
        .and(resolution.check(finest))
        .map_err(|_| {
            AppError::Usage(format!(
                "option `start` = {} (finest level {finest:e}) is out of range for {}: every \
             level must lie in {} (the range of --{})",
                ranges::show(start),
                solver.name(),
                resolution.range,
                resolution.name
            ))
        })?;
    let b = Progress::runs(levels, "independence");
    let s = with_threads(threads, || {
        studies::independence(case, solver, start, ratio, levels, tol, &|| b.inc())
    })?
    .map_err(study_error)?;
    b.finish();
    if let Some(f) = s.failed.first() {
        t.failure.get_or_insert(AppError::StudyRun(format!(
            "{} of {levels} levels of the independence study failed, the first at level {} \
             ({:e}): {}; levels {} to {} are judged",
            s.failed.len(),
            f.level,
            f.resolution,
            f.failure,
            s.first_level,
            s.first_level + s.resolutions.len() - 1
        )));
    }
    let mut table = Table::new(&[
        "output",
        "level",
        "h",
        "tol",
        "value",
        "difference_to_previous",
        "remaining_error",
        "independent",
    ]);
    for o in &s.outputs {
        for (i, v) in o.values.iter().enumerate() {
            let [h, tol] = resolution_cells(Some(s.step), Some(s.resolutions[i]));
            table.rows.push(vec![
                Cell::Text(o.name.clone()),
                Cell::Num((s.first_level + i) as f64),
                h,
                tol,
                Cell::Num(*v),
                if i == 0 {
                    Cell::Text(String::new())
                } else {
                    Cell::Num(o.differences[i - 1])
                },
                if i + 1 == o.values.len() && o.remaining_error.is_finite() {
                    Cell::Num(o.remaining_error)
                } else {
                    Cell::Text(String::new())
                },
                Cell::Text(o.independent.to_string()),
            ]);
        }
    }
    let csv = dir.join(format!("{stem}.csv"));
    t.files.add(csv.clone(), table.to_csv(&csv)?);
    t.files
        .add_json(dir.join(format!("{stem}.json")), &study_file(case, &s))?;
    let series = s
        .trajectories
        .iter()
        .zip(&s.resolutions)
        .zip(PALETTE.iter().cycle())
        .map(|((xs, h), &color)| Series {
            label: Some(format!("{} at {h:e}", s.solver)),
            points: xs
                .iter()
                .enumerate()
                .map(|(i, &x)| (case.t_end() * i as f64 / (xs.len().max(2) - 1) as f64, x))
                .collect(),
            color,
            width: 2,
            marker: Marker::None,
        })
        .collect();
    let plot = Plot {
        title: format!(
            "Independence: {}: {}",
            case.describe(),
            if s.independent {
                "independent".to_string()
            } else if s.failed.is_empty() {
                "NOT independent".to_string()
            } else {
                format!("NOT independent ({} levels failed)", s.failed.len())
            }
        ),
        x_label: "time t (s)".into(),
        y_label: "displacement x (m)".into(),
        series,
        legend: Corner::default(),
        log: false,
    };
    t.files.add_plot(&dir.join(stem), &plot)?;
    Ok(s)
}

/// Runs `independence`; its files in memory.
pub fn independence(a: &IndependenceArgs) -> Result<Made, AppError> {
    a.case.make(|t, case| {
        let r = Refinement {
            start: a.start,
            ratio: a.ratio,
            levels: a.levels,
            tol: a.tol,
        };
        let s = add_independence(t, "independence", case, a.solver, r)?;
        let mut notes: Vec<String> = s
            .outputs
            .iter()
            .map(|o| {
                let verdict = if o.independent {
                    "independent"
                } else {
                    "NOT independent"
                };
                format!(
                    "{:24} remaining error {:.3e} {verdict}",
                    o.name, o.remaining_error
                )
            })
            .collect();
        let verdict = if s.independent {
            "independent of"
        } else {
            "not independent of"
        };
        notes.extend(s.failed.iter().map(|f| {
            format!(
                "level {} ({:e}) failed, not judged: {}",
                f.level, f.resolution, f.failure
            )
        }));
        notes.push(format!("verdict: {verdict} the step size"));
        Ok(notes)
    })
}

/// Options of `work-precision`.
#[derive(Args, Debug)]
pub struct WorkPrecisionArgs {
    /// The problem.
    #[command(flatten)]
    pub case: CaseArgs,
    /// Solvers, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "rk4,dopri5,implicit-euler,bdf,tr-bdf2,esdirk34,tsit45"
    )]
    pub solvers: Vec<Solver>,
    /// Step sizes of rk4, coarse to fine.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0.01,0.003,0.001,0.0003"
    )]
    pub dt_list: Vec<f64>,
    /// Tolerances of the adaptive solvers, loose to tight.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1e-3,1e-4,1e-5,1e-6,1e-7,1e-8"
    )]
    pub tol_list: Vec<f64>,
    /// Repetitions of each run for the median wall time.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 3,
        allow_hyphen_values = true
    )]
    pub repeats: i64,
}

/// Computes a work–precision study and adds its files under `dir` with stem `stem`.
pub fn add_work_precision(
    t: &mut Target,
    stem: &str,
    case: &dyn StudyCase,
    solvers: &[Solver],
    steps: &[f64],
    tols: &[f64],
    repeats: usize,
) -> Result<WorkPrecision, AppError> {
    let (dir, threads) = (t.dir, t.threads);
    distinct(solvers)?;
    ranges::DT.list("dt-list", steps)?;
    ranges::RTOL.list("tol-list", tols)?;
    let methods: Vec<Method> = Method::studied(case, solvers)
        .into_iter()
        .chain(case.peers())
        .collect();
    let jobs = Method::jobs(&methods, steps, tols, false).len();
    let b = Progress::runs(jobs * repeats, "work-precision");
    let w = with_threads(threads, || {
        studies::work_precision(case, &methods, steps, tols, repeats, &|| b.inc())
    })?
    .map_err(study_error)?;
    b.finish();
    let csv = dir.join(format!("{stem}.csv"));
    t.files.add(csv.clone(), runs_table(&w.runs, &csv)?);
    let mut timing = Table::new(&["solver", "h", "tol", "wall_time_median_s"]);
    for r in &w.runs {
        let [h, tol] = resolution_cells(Some(r.step), Some(r.resolution));
        timing.rows.push(vec![
            Cell::Text(r.solver.clone()),
            h,
            tol,
            Cell::Num(r.wall_time_s),
        ]);
    }
    let timing_csv = dir.join(format!("{stem}-timing.csv"));
    t.files.add(timing_csv.clone(), timing.to_csv(&timing_csv)?);
    t.files
        .add_json(dir.join(format!("{stem}.json")), &study_file(case, &w))?;
    let plot = Plot {
        title: format!("Work-precision: {}", case.describe()),
        x_label: "work (f evaluations + dim per Jacobian)".into(),
        y_label: "max error on the time grid".into(),
        series: per_solver_series(&w.runs, |_| true, |r| r.work as f64, |r| r.errors.grid_max),
        legend: Corner::UpperRight,
        log: true,
    };
    t.files.add_plot(&dir.join(stem), &plot)?;
    Ok(w)
}

/// Runs `work-precision`; its files in memory.
pub fn work_precision(a: &WorkPrecisionArgs) -> Result<Made, AppError> {
    a.case.make(|t, case| {
        add_work_precision(
            t,
            "work-precision",
            case,
            &a.solvers,
            &a.dt_list,
            &a.tol_list,
            ranges::REPEATS.count(a.repeats)?,
        )?;
        Ok(Vec::new())
    })
}

/// Options of `stiffness`.
#[derive(Args, Debug)]
pub struct StiffnessArgs {
    /// The problem.
    #[command(flatten)]
    pub case: CaseArgs,
    /// The parameter swept: epsilon, sigma, sigma0, k, or any other.
    #[arg(long, value_name = "NAME", default_value = "epsilon")]
    pub parameter: String,
    /// Its values, in sweep order.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "1e-1,1e-2,1e-3,1e-4"
    )]
    pub values: Vec<f64>,
    /// Solvers, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "dopri5,tsit45,implicit-euler,bdf,esdirk34"
    )]
    pub solvers: Vec<Solver>,
    /// The error to reach (maximum over the time grid).
    #[arg(
        long,
        value_name = "E",
        default_value_t = 1e-3,
        allow_hyphen_values = true
    )]
    pub target: f64,
    /// Step sizes of rk4, coarse to fine.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0.01,0.001,0.0001"
    )]
    pub dt_list: Vec<f64>,
    /// Tolerances tried, loose to tight.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1e-2,1e-3,1e-4,1e-5,1e-6,1e-7"
    )]
    pub tol_list: Vec<f64>,
}

/// Computes a stiffness sweep and adds its files under `dir` with stem `stem`.
pub fn add_stiffness(
    t: &mut Target,
    stem: &str,
    case: &dyn StudyCase,
    sweep: studies::Sweep,
    solvers: &[Solver],
    steps: &[f64],
    tols: &[f64],
) -> Result<Stiffness, AppError> {
    let (dir, threads) = (t.dir, t.threads);
    let studies::Sweep {
        parameter,
        values,
        target,
    } = sweep;
    positive_list("values", values)?;
    positive_list("target", &[target])?;
    distinct(solvers)?;
    ranges::DT.list("dt-list", steps)?;
    ranges::RTOL.list("tol-list", tols)?;
    if values.len() > 50 {
        return Err(AppError::Usage(format!(
            "option `values` has {} values: allowed 1 to 50",
            values.len()
        )));
    }
    let methods: Vec<Method> = Method::studied(case, solvers)
        .into_iter()
        .chain(case.peers())
        .collect();
    let per_value = Method::jobs(&methods, steps, tols, false).len();
    let b = Progress::runs(per_value * values.len(), "stiffness");
    let s = with_threads(threads, || {
        studies::stiffness(
            case,
            studies::Sweep {
                parameter,
                values,
                target,
            },
            &methods,
            steps,
            tols,
            &|| b.inc(),
        )
    })?
    .map_err(study_error)?;
    b.finish();
    let mut table = Table::new(&[
        "value",
        "solver",
        "implicit",
        "reached",
        "h",
        "tol",
        "error",
        "rhs_evals",
        "jacobian_evals",
        "lu_factorizations",
        "implicit_wins",
    ]);
    for p in &s.points {
        for c in &p.costs {
            // Numeric columns hold numbers or nothing: `reached` says why both are empty.
            let [h, tol] = resolution_cells(c.step, c.resolution);
            table.rows.push(vec![
                Cell::Num(p.value),
                Cell::Text(c.solver.clone()),
                Cell::Text(c.implicit.to_string()),
                Cell::Text(c.resolution.is_some().to_string()),
                h,
                tol,
                Cell::num(c.error),
                Cell::Num(c.stats.rhs_evals as f64),
                Cell::Num(c.stats.jacobian_evals as f64),
                Cell::Num(c.stats.lu_factorizations as f64),
                Cell::Text(p.implicit_wins.to_string()),
            ]);
        }
    }
    let csv = dir.join(format!("{stem}.csv"));
    t.files.add(csv.clone(), table.to_csv(&csv)?);
    t.files
        .add_json(dir.join(format!("{stem}.json")), &study_file(case, &s))?;
    // A solver that met the target at a value: a dot at its cost; one that did not: a cross
    // at the top of the plot, named.
    let reached: Vec<(f64, f64)> = s
        .points
        .iter()
        .flat_map(|p| {
            p.costs
                .iter()
                .filter(|c| c.resolution.is_some())
                .map(|c| (p.value, c.work as f64))
        })
        .collect();
    let top = reached.iter().map(|p| p.1).fold(1.0, f64::max) * 3.0;
    let mut series = Vec::new();
    for (method, &color) in methods.iter().zip(PALETTE.iter().cycle()) {
        let label = method.label();
        let costs = || {
            s.points
                .iter()
                .filter_map(|p| Some((p.value, p.costs.iter().find(|c| c.solver == label)?)))
        };
        let met: Vec<(f64, f64)> = costs()
            .filter(|(_, c)| c.resolution.is_some())
            .map(|(v, c)| (v, c.work as f64))
            .collect();
        let missed: Vec<(f64, f64)> = costs()
            .filter(|(_, c)| c.resolution.is_none())
            .map(|(v, _)| (v, top))
            .collect();
        if !met.is_empty() {
            series.push(Series {
                label: Some(label.clone()),
                points: met,
                color,
                width: 2,
                marker: Marker::Dot,
            });
        }
        if !missed.is_empty() {
            series.push(Series {
                label: Some(format!(
                    "{label}: target not reached at {} value(s) (at the top)",
                    missed.len()
                )),
                points: missed,
                color,
                width: 0,
                marker: Marker::Cross,
            });
        }
    }
    let plot = Plot {
        title: format!(
            "Cost to reach error {target:e} against {parameter}: {}",
            case.describe()
        ),
        x_label: parameter.to_string(),
        y_label: "work (f evaluations + dim per Jacobian)".into(),
        series,
        legend: Corner::UpperRight,
        log: true,
    };
    t.files.add_plot(&dir.join(stem), &plot)?;
    Ok(s)
}

/// Runs `stiffness`; its files in memory. Without `--switching`, a rig swept over `epsilon`
/// is regularized: the width changes nothing else (under event switching every value would
/// give the same runs), while a system keeps event switching, whose regularised BDF peer is
/// the method that depends on it.
pub fn stiffness(a: &StiffnessArgs) -> Result<Made, AppError> {
    let mut case = a.case.clone();
    if case.switching.is_none()
        && a.parameter == "epsilon"
        && matches!(case.scenario, Some(Problem::Rig(_)))
    {
        case.switching = Some(SwitchingKind::Regularized);
    }
    // A system's regularised peer reads epsilon whatever the switching; a rig's run reads
    // only what its model and switching read.
    if let Some(Problem::Rig(_)) = case.scenario {
        crate::options::check_read(
            "parameter",
            &a.parameter,
            case.model,
            case.switching.unwrap_or(SwitchingKind::Event),
        )?;
    }
    case.make(|t, case| {
        let sweep = studies::Sweep {
            parameter: &a.parameter,
            values: &a.values,
            target: a.target,
        };
        let s = add_stiffness(
            t,
            "stiffness",
            case,
            sweep,
            &a.solvers,
            &a.dt_list,
            &a.tol_list,
        )?;
        Ok(vec![s.verdict()])
    })
}

/// Computes a cost-against-size study (every method at one resolution on each case) and adds
/// its files under `dir` with stem `stem`: the runs (CSV, JSON: steps, work, work per step
/// and its fitted exponent in N), and their wall times (`-timing.csv`) with wall time per step
/// against the number of bodies on log–log axes (`-timing.png`, `.svg`): the files that vary
/// between runs.
pub fn add_scaling(
    t: &mut Target,
    stem: &str,
    cases: &[(usize, Box<dyn StudyCase>)],
    methods: &[(Method, integrators::StepControl)],
) -> Result<studies::Scaling, AppError> {
    let (dir, threads) = (t.dir, t.threads);
    let b = Progress::runs(2 * cases.len() * methods.len(), "cost against size");
    let s = with_threads(threads, || studies::scaling(cases, methods, &|| b.inc()))?
        .map_err(study_error)?;
    b.finish();
    let mut table = Table::new(&[
        "bodies",
        "solver",
        "h",
        "tol",
        "steps",
        "work",
        "work_per_step",
        "rhs_evals",
        "jacobian_evals",
        "lu_factorizations",
        "events",
        "status",
    ]);
    let mut timing = Table::new(&["bodies", "solver", "h", "tol", "wall_time_s"]);
    for r in &s.runs {
        let [h, tol] = resolution_cells(Some(r.step), Some(r.resolution));
        table.rows.push(vec![
            Cell::Num(r.size as f64),
            Cell::Text(r.solver.clone()),
            h.clone(),
            tol.clone(),
            Cell::Num(r.stats.steps as f64),
            Cell::Num(r.work as f64),
            Cell::Num(r.work_per_step),
            Cell::Num(r.stats.rhs_evals as f64),
            Cell::Num(r.stats.jacobian_evals as f64),
            Cell::Num(r.stats.lu_factorizations as f64),
            Cell::Num(r.stats.events as f64),
            Cell::Text(r.failure.clone().unwrap_or_else(|| "ok".into())),
        ]);
        timing.rows.push(vec![
            Cell::Num(r.size as f64),
            Cell::Text(r.solver.clone()),
            h,
            tol,
            Cell::Num(r.wall_time_s),
        ]);
    }
    let csv = dir.join(format!("{stem}.csv"));
    t.files.add(csv.clone(), table.to_csv(&csv)?);
    let timing_csv = dir.join(format!("{stem}-timing.csv"));
    t.files.add(timing_csv.clone(), timing.to_csv(&timing_csv)?);
    let file = ScalingFile {
        cases: cases
            .iter()
            .map(|(bodies, case)| SizedCase {
                bodies: *bodies,
                case: CaseRecord::of(case.as_ref()),
            })
            .collect(),
        study: &s,
    };
    t.files.add_json(dir.join(format!("{stem}.json")), &file)?;
    // Wall time per step against N, with each method's fitted slope: the one figure of the
    // study that varies between runs (hence `-timing`).
    let mut series = Vec::new();
    for ((label, _), &color) in s.exponents.iter().zip(PALETTE.iter().cycle()) {
        let points: Vec<(f64, f64)> = s
            .runs
            .iter()
            .filter(|r| &r.solver == label && r.failure.is_none() && r.stats.steps > 0)
            .map(|r| (r.size as f64, r.wall_time_s / r.stats.steps as f64))
            .collect();
        let logs: Vec<(f64, f64)> = points.iter().map(|p| (p.0.ln(), p.1.ln())).collect();
        series.push(Series {
            label: Some(format!("{label} (slope {:.2})", studies::slope(&logs))),
            points,
            color,
            width: 2,
            marker: Marker::Dot,
        });
    }
    let plot = Plot {
        title: "Wall time per step against the number of bodies".into(),
        x_label: "bodies".into(),
        y_label: "wall time per step (s)".into(),
        series,
        legend: Corner::UpperLeft,
        log: true,
    };
    t.files
        .add_plot(&dir.join(format!("{stem}-timing")), &plot)?;
    Ok(s)
}
