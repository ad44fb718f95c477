//! `friction-lab sweep SCENARIO|chain|--system FILE --grid NAME=VALUES ... --out DIR`: the
//! sweep of [`friction_lab::sweep`] over the run `simulate` would make, each point's values set as
//! `--set` would set them.

use crate::commands::simulate::{spec, SimulateArgs, Target};
use crate::commands::system::{chosen_bodies, default_t_end, system_of, system_points};
use clap::Args;
use friction_lab::artifacts::Made;
use friction_lab::error::AppError;
use friction_lab::laws::ModelChoice;
use friction_lab::output::counted;
use friction_lab::ranges;
use friction_lab::study::{conduct, Target as StudyTarget};
use friction_lab::sweep::{points, Axis, Grid, PointRun, Start, SweepStudy};
use friction_systems::Layout;
use scenarios::stick_slip::sliding_start;
use scenarios::Scenario;
use std::time::Instant;

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

/// Refuses an axis that names a parameter a second time (only the last would be used) or a
/// friction parameter that the run does not read ([`friction_lab::laws::check_read`]).
fn check_axes(axes: &[Axis], run: &SimulateArgs) -> Result<(), AppError> {
    let names: Vec<&str> = axes.iter().map(|a| a.name.as_str()).collect();
    if let Some((_, k)) = friction_lab::ranges::first_repeat(&names) {
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
            .find(|a| friction_lab::params::parse_assignment(a).is_ok_and(|(s, _)| s == n))
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
        friction_lab::laws::check_read(
            "grid",
            name,
            run.model.as_ref().and_then(ModelChoice::catalog),
            run.solver.switching(),
        )
    })
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

/// Checks a point's run and sets it up, started from rest or from steady sliding (the belt
/// only: another rig or a system has no such start, refused with exit 2).
fn prepare(args: &SimulateArgs, start: Start) -> Result<PointRun, AppError> {
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
                .any(|a| friction_lab::params::parse_assignment(a).is_ok_and(|(n, _)| n == "x0"))
            {
                return refuse("sets x0 itself: drop x0 from --set and --grid");
            }
            let model = spec.law.build(&spec.friction)?;
            spec.params.x0 = sliding_start(model.as_ref(), spec.params.v_belt, spec.params.k);
            spec.params.v0 = 0.0;
            Ok(PointRun::Rig(spec))
        }
        (_, Start::Sliding) => refuse("applies to the belt rig only"),
        (Some(Target::Rig(scenario)), Start::Rest) => Ok(PointRun::Rig(spec(args, scenario)?)),
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
            let step = args.solver.checked_step()?;
            let t_end = args
                .checked_t_end()?
                .unwrap_or_else(|| default_t_end(args.system.as_deref()));
            let points = system_points(args, Layout::of(&described.system).dim())?;
            let scheme =
                (args.solver.switching()).scheme(args.solver.solver(), &described.friction);
            Ok(PointRun::System {
                system: described.system,
                scheme,
                step,
                limits: args.solver.checked_limits()?,
                t_end,
                points,
                body,
            })
        }
    }
}

/// The command line's sweep: `simulate`'s options, each point's values added after its own
/// `--set`s, every run's time limit counted from `since` (the command's start).
struct CommandGrid<'a> {
    run: &'a SimulateArgs,
    start: Start,
    since: Instant,
}

impl Grid for CommandGrid<'_> {
    fn run_at(&self, point: &[(String, f64)]) -> Result<PointRun, AppError> {
        let mut args = at_point(self.run, point);
        args.solver.limits.since = Some(self.since);
        prepare(&args, self.start)
    }
}

/// Runs `sweep`; its files in memory.
pub fn make(args: &SweepArgs) -> Result<Made, AppError> {
    let threads = ranges::threads(args.threads)?;
    let axes: Vec<Axis> = args
        .grid
        .iter()
        .map(|g| Axis::parse(g))
        .collect::<Result<_, _>>()?;
    check_axes(&axes, &args.run)?;
    let range = point_range(args.point_range.as_deref(), points(&axes).len())?;
    let target = match (args.run.scenario, &args.run.system) {
        (Some(Target::Rig(s)), _) => s.name().to_string(),
        (_, Some(file)) => file.display().to_string(),
        _ => "chain".into(),
    };
    // `--time-limit` bounds the whole sweep: every point counts from here.
    let grid = CommandGrid {
        run: &args.run,
        start: args.start,
        since: Instant::now(),
    };
    let study = SweepStudy {
        grid: &grid,
        axes: &axes,
        settle: args.settle,
        range,
        target,
        model: args.run.model.as_ref().map(|m| m.name().to_string()),
        start: args.start,
    };
    let mut files = friction_lab::artifacts::Artifacts::default();
    let mut target = StudyTarget {
        files: &mut files,
        dir: &args.run.out,
        threads,
        failure: None,
    };
    let results = conduct(&study, &mut target, "sweep")?;
    let failure = target.failure;
    let failed = results.iter().filter(|r| r.error.is_some()).count();
    Ok(Made {
        files,
        notes: vec![format!(
            "{}, {failed} failed",
            counted(results.len(), "point", "points")
        )],
        warnings: friction_lab::warnings::unread_warnings(
            &args.run.model_options.params.set,
            args.run.model.as_ref().and_then(ModelChoice::catalog),
            args.run.solver.switching(),
        )
        .into_iter()
        .chain(args.run.solver.scheme.spelling_notes())
        .collect(),
        failure,
        trajectory: None,
    })
}
