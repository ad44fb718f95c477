//! `friction-lab simulate chain` and `friction-lab simulate --system FILE.toml`: one system of
//! many bodies (`docs/systems.md`), written as `final.csv`, `events.csv`, the tidy
//! `trajectory.csv` of chosen bodies, `summary.json` and two figures (space–time picture of
//! the contact modes; velocities of chosen bodies).

use crate::commands::simulate::SimulateArgs;
use crate::options::ModelOptions;
use friction_lab::artifacts::Made;
use friction_lab::error::AppError;
use friction_lab::laws::ModelChoice;
use friction_lab::ranges;
use friction_lab::simulate::{load, simulate_system, Described, SystemRun};
use friction_lab::sweep::RECORD_LIMIT;
use friction_lab::trajectory::TrajectoryAs;
use friction_systems::chain::{ChainParams, CHAIN_PARAMETERS};
use friction_systems::System;
use integrators::Options;
use scenarios::chain::ChainSource;
use std::collections::BTreeMap;
use std::path::Path;

/// Bodies written to the trajectory when none are chosen: all of a chain this long or shorter,
/// otherwise this many evenly spaced.
pub const DEFAULT_TRAJECTORY_BODIES: usize = 20;
/// The largest number of recorded numbers (points × unknowns) by default: about 80 MB.
pub const RECORD_BUDGET: usize = 10_000_000;
/// Default end time of the chain, s.
pub const CHAIN_T_END: f64 = 50.0;
/// Default end time of a system file, s.
pub const FILE_T_END: f64 = 20.0;

/// Default end time of a solver study of the chain, s: within its horizon of predictability.
/// Over [`CHAIN_T_END`] a perturbation of the size of a step's error grows to the size of the
/// motion (the chain of 10 blocks with CS, CVS or Karnopp's law: fixed-step errors near a
/// saturated level, fitted "orders" of RK4 from −0.07 to 1.2), and a convergence study
/// measures that growth, not the solvers; over 10 s RK4 shows 3.7–4.3 and Dormand–Prince
/// 4.2–5.4 on every measure (docs/studies.md).
pub const CHAIN_STUDY_T_END: f64 = 10.0;

/// The default end time of a system: [`FILE_T_END`] for a system `file`, else (the chain)
/// [`CHAIN_T_END`].
pub fn default_t_end(file: Option<&Path>) -> f64 {
    file.map_or(CHAIN_T_END, |_| FILE_T_END)
}

/// The default end time of a solver study of a system: [`FILE_T_END`] for a system `file`,
/// else (the chain) [`CHAIN_STUDY_T_END`].
pub fn study_t_end(file: Option<&Path>) -> f64 {
    file.map_or(CHAIN_STUDY_T_END, |_| FILE_T_END)
}

/// The default number of output points for a system of `dim` unknowns: 2001, fewer for a
/// large system so that the recorded states stay within [`RECORD_BUDGET`] numbers.
pub fn default_points(dim: usize) -> usize {
    (RECORD_BUDGET / dim.max(1)).clamp(101, 2001)
}

/// The output points of a system of `dim` unknowns: `--points`, checked against its range
/// and against [`RECORD_LIMIT`] numbers in all, or [`default_points`].
pub fn system_points(args: &SimulateArgs, dim: usize) -> Result<usize, AppError> {
    let Some(points) = args.checked_points()? else {
        return Ok(default_points(dim));
    };
    if points.saturating_mul(dim) > RECORD_LIMIT {
        return Err(AppError::Usage(format!(
            "option `points` = {points} would record {} numbers for the system's {dim} \
             unknowns: allowed at most {} numbers, so at most {} points",
            ranges::show((points as f64) * (dim as f64)),
            ranges::show(RECORD_LIMIT as f64),
            RECORD_LIMIT / dim.max(1)
        )));
    }
    Ok(points)
}

/// The system of `--system FILE` or, without one, the chain with `model` and the parameters
/// of `options` (chain parameters by `--set` too).
pub fn system_of(
    file: Option<&Path>,
    model: Option<&ModelChoice>,
    options: &ModelOptions,
) -> Result<Described, AppError> {
    if let Some(path) = file {
        if model.is_some() {
            return Err(AppError::Usage(
                "option `--model` does not apply to --system: each [[contact]] of the file \
                 names its model"
                    .into(),
            ));
        }
        options.params.source().check_for_system_file()?;
        if options.variant != friction_models::Variant::Odd {
            return Err(AppError::Usage(
                "option `--variant` does not apply to --system: each [[contact]] of the file \
                 names its variant"
                    .into(),
            ));
        }
        return Ok(Described {
            system: load(path)?,
            name: path.display().to_string(),
            parameters: BTreeMap::new(),
            friction: options.params.source().resolve()?,
            source: None,
        });
    }
    let model = model.ok_or_else(|| {
        AppError::Usage("option `--model` is required for the chain: e.g. --model coulomb".into())
    })?;
    let mut chain = ChainParams::default();
    let names = CHAIN_PARAMETERS.map(|(name, _, _)| name);
    let friction = options
        .params
        .source()
        .resolve_with(&names, |name, value| Ok(chain.set(name, value)?))?;
    let source = ChainSource {
        chain,
        law: model.law(options.variant),
        friction,
    };
    let system = source.build()?;
    let mut reported = model.parameters_read(&friction);
    for (name, _, _) in CHAIN_PARAMETERS {
        let value = match name {
            "n_bodies" => chain.n_bodies as f64,
            "m" => chain.m,
            "k_chain" => chain.k_chain,
            "k_driver" => chain.k_driver,
            "v_driver" => chain.v_driver,
            _ => chain.spread,
        };
        reported.insert(name.to_string(), value);
    }
    Ok(Described {
        system,
        name: source.name(),
        parameters: reported,
        friction,
        source: Some(source),
    })
}

/// The bodies chosen with `--bodies` (names or 1-based indices), or the default choice.
pub fn chosen_bodies(system: &System, chosen: &[String]) -> Result<Vec<usize>, AppError> {
    let n = system.bodies.len();
    if chosen.is_empty() {
        let k = n.min(DEFAULT_TRAJECTORY_BODIES);
        return Ok(if k <= 1 {
            vec![0]
        } else {
            (0..k).map(|j| j * (n - 1) / (k - 1)).collect()
        });
    }
    let indices: Vec<usize> = chosen
        .iter()
        .map(|token| {
            if let Some(i) = system.bodies.iter().position(|b| &b.name == token) {
                return Ok(i);
            }
            match token.parse::<usize>() {
                Ok(i) if (1..=n).contains(&i) => Ok(i - 1),
                _ => Err(no_body(system, token)),
            }
        })
        .collect::<Result<_, _>>()?;
    // A body chosen twice would repeat its rows in the tidy trajectory.csv.
    if let Some((j, k)) = friction_lab::ranges::first_repeat(&indices) {
        return Err(AppError::Usage(format!(
            "option `--bodies`: `{}` and `{}` are the same body, {}: choose each body once",
            chosen[j], chosen[k], system.bodies[indices[k]].name
        )));
    }
    Ok(indices)
}

/// The error for a `--bodies` token that is no body's name or index. The option splits at
/// commas, so a body whose name has one is chosen by its index: said, with the index.
fn no_body(system: &System, token: &str) -> AppError {
    let n = system.bodies.len();
    let hint: String = system
        .bodies
        .iter()
        .enumerate()
        .filter(|(_, b)| b.name.contains(','))
        .map(|(i, b)| {
            let name = &b.name;
            format!(
                "; body \"{name}\" has a comma: choose it by its index, {}",
                i + 1
            )
        })
        .collect();
    AppError::Usage(format!(
        "option `--bodies`: `{token}` is no body: allowed a body's name or an index in [1, {n}]{hint}"
    ))
}

/// The options of a system run from the command line: its step control and limits, checked,
/// and `points` evenly spaced output times on [0, t_end] ([`friction_lab::sweep::grid_options`]).
pub fn grid_options(args: &SimulateArgs, t_end: f64, points: usize) -> Result<Options, AppError> {
    let limits = args.solver.checked_limits()?;
    Ok(friction_lab::sweep::grid_options(
        args.solver.checked_step()?,
        &limits,
        t_end,
        points,
    ))
}

/// Runs `simulate` on a system: its files in memory, its trajectory as the file or as columns.
pub fn make(args: &SimulateArgs, trajectory_as: TrajectoryAs) -> Result<Made, AppError> {
    let described = system_of(
        args.system.as_deref(),
        args.model.as_ref(),
        &args.model_options,
    )?;
    args.solver.checked_step()?;
    let switching = args.solver.switching();
    described.system.validate()?;
    let bodies = chosen_bodies(&described.system, &args.bodies)?;
    let t_end = args
        .checked_t_end()?
        .unwrap_or_else(|| default_t_end(args.system.as_deref()));
    let points = system_points(args, friction_systems::Layout::of(&described.system).dim())?;
    let options = grid_options(args, t_end, points)?;
    let run = SystemRun {
        described: &described,
        switching,
        solver: args.solver.solver(),
        options,
        bodies: &bodies,
        variant: (args.model.as_ref())
            .and_then(ModelChoice::catalog)
            .map(|_| args.model_options.variant),
    };
    let mut made = simulate_system(run, &args.out, trajectory_as)?;
    made.warnings.extend(
        friction_lab::warnings::unread_warnings(
            &args.model_options.params.set,
            args.model.as_ref().and_then(ModelChoice::catalog),
            switching,
        )
        .into_iter()
        .chain(args.solver.scheme.spelling_notes()),
    );
    Ok(made)
}
