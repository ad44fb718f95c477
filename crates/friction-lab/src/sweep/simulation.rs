//! The sweep of a [`SimulationRequest`]: the run `simulate` would make, each point's values assigned
//! after the run's own parameters ([`SweepRequest`]); its checks, its grid and its files.

use super::{points, Axis, Grid, PointRun, Start, SweepStudy, SystemPoint};
use crate::artifacts::Artifacts;
use crate::error::{field, AppError};
use crate::laws::ModelChoice;
use crate::made::Made;
use crate::output::counted;
use crate::params::{is_file_path, parse_assignment};
use crate::ranges::{self, first_repeat};
use crate::simulate::{chosen_bodies, SimulationRequest, Target};
use crate::study::{conduct, Output};
use crate::sweep::PointResult;
use friction_systems::Layout;
use scenarios::stick_slip::sliding_start;
use scenarios::Scenario;
use std::ops::Range;
use std::path::Path;
use std::time::Instant;

/// The measured part of each run of a sweep unless told otherwise: its last half.
pub const DEFAULT_SETTLE: f64 = 0.5;

/// A sweep of a run over a grid of its parameters (`friction-lab sweep`).
#[derive(clap::Args, Clone, Debug)]
pub struct SweepRequest {
    /// What to run at every point, before the point's values are assigned: the rig or chain,
    /// the model, the solver and the fixed parameters, as `simulate` takes them.
    #[command(flatten)]
    pub simulation: SimulationRequest,
    /// One axis of the grid, repeatable: NAME=V1,V2,... (a list), NAME=START:STOP:COUNT
    /// (evenly spaced), or NAME=log:START:STOP:COUNT (evenly spaced in log); any friction,
    /// scenario or chain parameter. The grid is the product of the axes, the first varying
    /// slowest.
    #[arg(long = "grid", value_name = "NAME=VALUES", required = true)]
    pub axes: Vec<Axis>,
    /// The measured, settled part of each run: its last fraction (0, 1] of the time span.
    #[arg(
        long,
        value_name = "FRACTION",
        default_value_t = DEFAULT_SETTLE,
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
    #[arg(long = "point-range", value_name = "START:END", value_parser = point_range)]
    pub range: Option<Range<usize>>,
}

impl SweepRequest {
    /// Checks the sweep, runs its points and makes its files in `out` (in memory): a failed
    /// point is a row that says why, and the sweep's failure.
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        let threads = ranges::threads(self.threads)?;
        let mut files = Artifacts::default();
        let mut target = Output {
            files: &mut files,
            dir: out,
            threads,
            failure: None,
        };
        let results = self.conduct(&mut target, "sweep")?;
        let failure = target.failure;
        let failed = results.iter().filter(|r| r.verdict.is_broken()).count();
        Ok(Made {
            files,
            notes: vec![format!(
                "{}, {failed} failed or diverged",
                counted(results.len(), "point", "points")
            )],
            warnings: self.simulation.warnings(),
            failure,
            run: None,
        })
    }

    /// Checks the sweep and conducts it into `target` as the study `{stem}` (its files
    /// `{stem}.csv`, `{stem}.json`, `{stem}.png`), returning every point's result: how
    /// `reproduce` draws its hunting map.
    pub fn conduct(&self, target: &mut Output, stem: &str) -> Result<Vec<PointResult>, AppError> {
        if let Some(window) = &self.simulation.window {
            return Err(AppError::Usage(format!(
                "option `{}` = {window} applies to simulate, whose figures it draws over \
                 time: a sweep measures each point's settled part (`{}`)",
                field("window"),
                field("settle")
            )));
        }
        check_axes(&self.axes, &self.simulation)?;
        let n = points(&self.axes).len();
        let range = match &self.range {
            Some(r) => check_point_range(r.clone(), n)?,
            None => 0..n,
        };
        // The time limit bounds the whole sweep: every point counts from here.
        let grid = SimulationGrid {
            simulation: &self.simulation,
            start: self.start,
            since: Instant::now(),
        };
        let study = SweepStudy {
            grid: &grid,
            axes: &self.axes,
            settle: self.settle,
            range,
            target: self.simulation.target()?.name(),
            model: (self.simulation.model.as_ref()).map(|m| m.name().to_string()),
            start: self.start,
        };
        conduct(&study, target, stem)
    }
}

/// The error of a point range `text` outside a grid of `n` points.
fn point_range_error(text: &str, n: usize) -> AppError {
    AppError::Invalid(crate::error::Invalid {
        field: "point_range",
        value: format!("`{text}`"),
        allowed: format!("START:END with 0 <= START <= END <= {n} (the grid's points)"),
        list: false,
    })
}

/// `range`, if it lies within a grid of `n` points (START <= END <= n).
pub fn check_point_range(range: Range<usize>, n: usize) -> Result<Range<usize>, AppError> {
    if range.start > range.end || range.end > n {
        return Err(point_range_error(
            &format!("{}:{}", range.start, range.end),
            n,
        ));
    }
    Ok(range)
}

/// The points `START:END` from the text `START:END`, two whole numbers; checked against the
/// grid when the sweep runs ([`check_point_range`]).
pub fn point_range(text: &str) -> Result<Range<usize>, String> {
    let parse = |s: &str| s.trim().parse::<usize>().ok();
    match text.split_once(':').map(|(a, b)| (parse(a), parse(b))) {
        Some((Some(start), Some(end))) => Ok(start..end),
        _ => Err(format!(
            "option `{}` = `{text}` is not START:END: allowed two whole numbers \
             0 <= START <= END, at most the grid's points",
            field("point_range")
        )),
    }
}

/// Refuses an axis that names a parameter a second time (only the last would be used), a
/// parameter the run also assigns (every point would override it), a parameter of a system
/// file other than `epsilon`, or a friction parameter that the run does not read
/// ([`crate::laws::check_read`]).
fn check_axes(axes: &[Axis], run: &SimulationRequest) -> Result<(), AppError> {
    let names: Vec<&str> = axes.iter().map(|a| a.name.as_str()).collect();
    if let Some((_, k)) = first_repeat(&names) {
        return Err(AppError::Usage(format!(
            "option `{}`: parameter `{}` has two axes; give all its values in one",
            field("grid"),
            names[k]
        )));
    }
    let set = &run.model_settings.params.set;
    if let Some((name, given)) = names.iter().find_map(|&n| {
        set.iter()
            .find(|a| parse_assignment(a).is_ok_and(|(s, _)| s == n))
            .map(|a| (n, a))
    }) {
        return Err(AppError::Usage(format!(
            "option `{}`: parameter `{name}` is also given by {} {given}: every point \
             would override it; give its values in the axis only",
            field("grid"),
            field("set")
        )));
    }
    if run.system.is_some() {
        // A system file's contacts carry their own parameters: the regularisation width is
        // shared, any other number is swept by its path in the file.
        if let Some(name) = names.iter().find(|&&n| n != "epsilon" && !is_file_path(n)) {
            return Err(AppError::Usage(format!(
                "option `{}`: parameter `{name}` cannot be swept on a system file (each \
                 contact has its own parameters): allowed epsilon, under {} \
                 regularized, or a number of the file by its path TABLE.WHICH.KEY, e.g. \
                 contact.pad.surface_velocity, spring.2.k, body.caliper.m (docs/systems.md)",
                field("grid"),
                field("switching")
            )));
        }
    }
    names.iter().try_for_each(|name| {
        crate::laws::check_read(
            "grid",
            name,
            run.model.as_ref().and_then(ModelChoice::catalog),
            run.solver.scheme.unread_epsilon(),
        )
    })
}

/// A [`SimulationRequest`] swept: each point's values assigned after the run's own, every run's time
/// limit counted from `since` (the sweep's start).
struct SimulationGrid<'a> {
    simulation: &'a SimulationRequest,
    start: Start,
    since: Instant,
}

impl Grid for SimulationGrid<'_> {
    fn run_at(&self, point: &[(String, f64)]) -> Result<PointRun, AppError> {
        let mut run = self.simulation.clone();
        (run.model_settings.params.set).extend(point.iter().map(|(n, v)| format!("{n}={v}")));
        run.solver.limits.since = Some(self.since);
        prepare(&run, self.start)
    }
}

/// Checks a point's run and sets it up, started from rest or from steady sliding (the belt
/// only: another rig or a system has no such start, refused with exit 2).
fn prepare(run: &SimulationRequest, start: Start) -> Result<PointRun, AppError> {
    let refuse = |why: &str| {
        let start = field("start");
        Err(AppError::Usage(format!(
            "option `{start} sliding` {why}: it starts the belt's body at the equilibrium of \
             steady sliding; use {start} rest"
        )))
    };
    match (run.target()?, start) {
        (Target::Rig(scenario), Start::Sliding) if scenario == Scenario::BELT => {
            let mut spec = run.rig_spec(Scenario::BELT)?;
            if spec.params.k <= 0.0 {
                return refuse(
                    "needs a spring, k > 0 (steady sliding has no equilibrium without one)",
                );
            }
            if (run.model_settings.params.set.iter())
                .any(|a| parse_assignment(a).is_ok_and(|(n, _)| n == "x0"))
            {
                return refuse(&format!(
                    "sets x0 itself: drop x0 from {} and {}",
                    field("set"),
                    field("grid")
                ));
            }
            let model = spec.law.build(&spec.friction)?;
            spec.params.x0 = sliding_start(model.as_ref(), spec.params.v_belt, spec.params.k);
            spec.params.v0 = 0.0;
            Ok(PointRun::Rig(spec))
        }
        (_, Start::Sliding) => refuse("applies to the belt rig only"),
        (Target::Rig(scenario), Start::Rest) => Ok(PointRun::Rig(run.rig_spec(scenario)?)),
        _ => {
            let described = run.described()?;
            described.system.validate()?;
            // The first body chosen, else the first with a contact: a body without one has no
            // surface to stick to, so its regime says nothing of friction.
            let body = match run.bodies.is_empty() {
                false => chosen_bodies(&described.system, &run.bodies)?[0],
                true => (described.system.contacts.iter().map(|c| c.body))
                    .min()
                    .unwrap_or(0),
            };
            let step = run.solver.checked_step()?;
            let t_end = run.system_t_end()?;
            let points = run.system_points(Layout::of(&described.system).dim())?;
            let scheme = run.solver.scheme(described.friction.epsilon)?;
            Ok(PointRun::System(SystemPoint {
                system: described.system,
                scheme,
                step,
                limits: run.solver.checked_limits()?,
                t_end,
                points,
                body,
            }))
        }
    }
}
