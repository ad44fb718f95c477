//! The solver studies: `converge`, `independence`, `work-precision`, `stiffness`. Every
//! run of a study is independent; they run on a pool of `--threads` workers and are
//! collected in order, so the files do not depend on the thread count (wall times, which
//! cannot be reproduced, go to a separate `*-timing.csv`).

use crate::artifacts::{Artifacts, Made};
use crate::commands::simulate::Target as Problem;
use crate::commands::system::{chosen_bodies, study_t_end, system_of};
use crate::error::AppError;
use crate::options::{spelling_notes, treatment, LimitArgs, ModelOptions, SchemeName};
use crate::output::{Cell, Table};
use crate::plot::{Marker, Series, PALETTE};
use crate::ranges;
use crate::warnings::{diverged_line, unread_warnings};
use clap::Args;
use friction_models::params::show;
use friction_models::ModelId;
use integrators::Solver;
use scenarios::run::DEFAULT_THETA;
use scenarios::studies::{Case, StudyCase, StudyRun, SystemCase};
use scenarios::{Scenario, SwitchingKind};
use serde::Serialize;
use std::path::{Path, PathBuf};

mod converge;
mod independence;
mod scaling;
mod stiffness;
mod work_precision;

pub use converge::{add_convergence, converge, ConvergeArgs};
pub use independence::{add_independence, independence, IndependenceArgs};
pub use scaling::add_scaling;
pub use stiffness::{add_stiffness, stiffness, StiffnessArgs};
pub use work_precision::{add_work_precision, work_precision, WorkPrecisionArgs};

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
    /// event-driven (the solvers between located events, v = 0 treated by --switching) or
    /// time-stepping (Moreau–Jean at θ = 1/2, the study's one method: over the step sizes,
    /// the solver options unused; its reference is event-driven).
    #[arg(
        long,
        value_name = "event-driven|time-stepping",
        default_value = "event-driven"
    )]
    pub scheme: SchemeName,
    /// The treatment of v = 0 under event-driven integration: event, regularized or naive
    /// [default: event; for `stiffness` of a rig over epsilon, regularized]. (`timestepping`,
    /// the former spelling of --scheme time-stepping, is still taken, with a note.)
    #[arg(long, value_name = "event|regularized|naive")]
    pub switching: Option<SwitchingKind>,
    /// End time, s [default: the scenario's; 10 for the chain (its horizon of predictability:
    /// docs/studies.md); 20 for a system file].
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
                let bodies = if self.bodies.is_empty() {
                    vec![0]
                } else {
                    chosen_bodies(&described.system, &self.bodies)?
                };
                return Ok(Box::new(SystemCase {
                    name: described.name,
                    system: described.system,
                    switching: self.treatment()?,
                    epsilon: described.friction.epsilon,
                    t_end: check_t_end(
                        self.t_end
                            .unwrap_or_else(|| study_t_end(self.system.as_deref())),
                    )?,
                    bodies,
                    limits: self.limits.limits()?,
                    chain: described.source,
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
            switching: self.treatment()?,
            t_end,
            limits: self.limits.limits()?,
        }))
    }
}

impl CaseArgs {
    /// The treatment of v = 0 that `--scheme` and `--switching` ask for (time-stepping at
    /// θ = 1/2).
    pub fn treatment(&self) -> Result<SwitchingKind, AppError> {
        treatment(self.scheme, self.switching, DEFAULT_THETA)
    }

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
        // A study of a system under event switching also runs its regularised peer (BDF on
        // the regularised system), which reads epsilon.
        let switching = match (self.scenario, self.treatment()?) {
            (Some(Problem::Rig(_)), s) => s,
            (_, SwitchingKind::Event) => SwitchingKind::Regularized,
            (_, s) => s,
        };
        Ok(Made {
            files,
            notes,
            warnings: unread_warnings(&self.model_options.params.set, self.model, switching)
                .into_iter()
                .chain(spelling_notes(self.switching))
                .collect(),
            failure,
        })
    }
}

/// `--solvers` with each solver once (a study names its runs by solver).
fn distinct(solvers: &[Solver]) -> Result<(), AppError> {
    match crate::options::first_repeat(solvers) {
        Some((_, k)) => Err(AppError::Usage(format!(
            "option `solvers` names `{}` twice: allowed each solver once",
            solvers[k].name()
        ))),
        None => Ok(()),
    }
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

/// The height of the `row`-th row of crosses above the data of a log plot, whose largest value
/// is `largest`: three times it, then 1.5 times higher for each row, one row per solver with
/// failed runs (drawn at one height, the crosses of one hid those of another).
pub(super) fn row_at_top(largest: f64, row: i32) -> f64 {
    largest * 3.0 * 1.5f64.powi(row)
}

/// One series per solver of the runs `keep` selects, with a dot on every run that computed,
/// and, per solver with failed runs, a series of crosses drawn at the top of the plot at their
/// x, named with their count (a failed run has no error to plot, but it is not left out), each
/// such solver in a row of its own ([`row_at_top`]).
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
    let largest = runs
        .iter()
        .filter(plotted)
        .map(|r| y(r))
        .reduce(f64::max)
        .unwrap_or(1.0);
    let mut series = Vec::new();
    let mut rows = 0;
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
        let top = row_at_top(largest, rows);
        let failed: Vec<(f64, f64)> = mine()
            .filter(|r| r.failure.is_some())
            .map(|r| (x(r), top))
            .collect();
        if !failed.is_empty() {
            rows += 1;
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

/// One line for each method with failed runs of a study (an unstable step, a limit): how many,
/// and the first's resolution and error (their status in the study's `csv`). Their errors are
/// missing, which `converge`'s order lines count with round-off; this says why. A last line
/// says why, when a run of an explicit method diverged with its fixed step.
pub fn failures(runs: &[StudyRun], csv: &str) -> Vec<String> {
    let diverged = runs
        .iter()
        .any(|r| r.diverged)
        .then(|| diverged_line("step in --dt-list"));
    // A study's runs come method by method (`Method::jobs`), each method once.
    runs.chunk_by(|a, b| a.solver == b.solver)
        .filter_map(|mine| {
            let failed: Vec<&StudyRun> = mine.iter().filter(|r| r.failure.is_some()).collect();
            let first = failed.first()?;
            let at = if first.step == "fixed" { "h" } else { "tol" };
            Some(format!(
                "{:15} {} of {} runs failed (status in {csv}); the first, at {at} = {}: {}",
                first.solver,
                failed.len(),
                mine.len(),
                show(first.resolution),
                first.failure.as_deref().unwrap_or_default()
            ))
        })
        .chain(diverged)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use integrators::Stats;
    use scenarios::studies::Errors;

    fn run(solver: &str, h: f64, error: f64, failure: Option<&str>) -> StudyRun {
        StudyRun {
            solver: solver.into(),
            resolution: h,
            step: "fixed",
            errors: Errors {
                final_state: error,
                ..Errors::UNMEASURED
            },
            measures: Default::default(),
            stats: Stats::default(),
            work: 0,
            failure: failure.map(str::to_string),
            diverged: false,
            wall_time_s: 0.0,
        }
    }

    #[test]
    fn the_failed_runs_of_each_solver_are_drawn_in_a_row_of_their_own() {
        // Two solvers failing at the same step: at one height, the second's crosses hid the
        // first's.
        let runs = [
            run("rk4", 0.02, f64::NAN, Some("diverged")),
            run("rk4", 0.01, 1e-4, None),
            run("dopri5", 0.02, f64::NAN, Some("diverged")),
            run("dopri5", 0.01, 1e-6, None),
            run("implicit-euler", 0.02, 1e-2, None),
        ];
        let series = per_solver_series(&runs, |_| true, |r| r.resolution, |r| r.errors.final_state);
        let crosses: Vec<(f64, f64)> = series
            .iter()
            .filter(|s| s.marker == Marker::Cross)
            .map(|s| s.points[0])
            .collect();
        assert_eq!(crosses, [(0.02, 3e-2), (0.02, 3e-2 * 1.5)]);
    }

    #[test]
    fn every_solver_of_a_system_study_has_a_colour_of_its_own() {
        // The seven solvers and a system's two peers: with eight colours, time-stepping took
        // RK4's red, and the chain's default work-precision plot drew them alike.
        let names = [
            "rk4",
            "dopri5",
            "implicit-euler",
            "bdf",
            "tr-bdf2",
            "esdirk34",
            "tsit45",
            "bdf (regularized)",
            "moreau-jean (timestepping)",
        ];
        let runs: Vec<StudyRun> = names.iter().map(|n| run(n, 0.01, 1e-4, None)).collect();
        let series = per_solver_series(&runs, |_| true, |r| r.resolution, |r| r.errors.final_state);
        assert_eq!(series.len(), names.len());
        for (i, a) in series.iter().enumerate() {
            for b in &series[..i] {
                assert_ne!(a.color, b.color, "{:?} and {:?}", a.label, b.label);
            }
        }
    }
}
