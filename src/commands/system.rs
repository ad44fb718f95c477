//! `friction-lab simulate chain` and `friction-lab simulate --system FILE.toml`: one system of
//! many bodies (`shared/spec/systems.md`), written as `final.csv`, `events.csv`, the tidy
//! `trajectory.csv` of chosen bodies, `summary.json` and two figures (space–time picture of
//! the contact modes; velocities of chosen bodies).

use crate::artifacts::{Artifacts, Made};
use crate::commands::simulate::{add_stiffness, SimulateArgs};
use crate::error::AppError;
use crate::laws::ModelChoice;
use crate::options::{ModelOptions, SchemeName};
use crate::output::{counted, Cell, Table};
use crate::plot::{self, Corner, Marker, Plot, Raster, Series, PALETTE};
use crate::progress::Progress;
use crate::ranges;
use crate::run_record::{
    event_counts, scheme_parameters, Integrated, RunRecord, RunSetup, RunSummary, StiffnessSummary,
};
use crate::sweep::RECORD_LIMIT;
use crate::trajectory::{Trajectory, TrajectoryAs};
use friction_models::FrictionParams;
use friction_systems::chain::{ChainParams, CHAIN_PARAMETERS};
use friction_systems::{mode_name, Run, System, SLIP_NEGATIVE, SLIP_POSITIVE};
use integrators::Options;
use scenarios::chain::ChainSource;
use std::collections::BTreeMap;
use std::path::Path;

/// The most bodies a system's velocity figure draws, one colour each.
const DRAWN_BODIES: usize = 10;

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
/// Most columns and rows of the space–time picture.
const RASTER: (usize, usize) = (300, 200);

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

/// What the arguments describe: the system, its name, the parameters the summary reports, and
/// the friction parameters (whose `epsilon` the regularised treatment reads).
pub struct Described {
    /// The system.
    pub system: System,
    /// Its name, for titles.
    pub name: String,
    /// The parameters the summary reports.
    pub parameters: BTreeMap<String, f64>,
    /// The friction parameters of the command line.
    pub friction: FrictionParams,
    /// What the chain was built from (`None` for a system file).
    pub source: Option<ChainSource>,
}

/// How often [`load`] looks for a signal, s.
const LOAD_POLL_S: f64 = 0.05;

/// Reads the system file at `path` with a heartbeat, on a thread of its own: a signal stops the
/// command at once ([`AppError::Stopped`]; the parse cannot be stopped inside, so it is left to
/// end with the process), where a file of 10⁶ bodies takes seconds to parse.
fn load(path: &Path) -> Result<friction_systems::System, AppError> {
    let progress = Progress::elapsed(&format!("loading {}", path.display()));
    let (send, receive) = std::sync::mpsc::channel();
    let owned = path.to_path_buf();
    std::thread::spawn(move || {
        let _ = send.send(friction_systems::file::read(&owned));
    });
    let poll = std::time::Duration::from_secs_f64(LOAD_POLL_S);
    loop {
        if integrators::interrupt::requested() {
            return Err(AppError::Stopped(format!("loading {}", path.display())));
        }
        match receive.recv_timeout(poll) {
            Ok(read) => {
                progress.finish();
                return Ok(read?);
            }
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {}
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
                return Err(AppError::StudyRun(format!(
                    "loading {} ended without a result",
                    path.display()
                )))
            }
        }
    }
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
        options.params.check_for_system_file()?;
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
            friction: options.params.resolve()?,
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
    if let Some((j, k)) = crate::options::first_repeat(&indices) {
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

/// The space–time picture: body index against time, coloured by contact mode, sampled on at
/// most [`RASTER`] columns and rows; with its data as a CSV table. The solution must hold a
/// point (a run that failed before its first one has no picture).
fn space_time(run: &Run, title: &str, path: &Path) -> Result<(Raster, Vec<u8>), AppError> {
    let s = &run.solution;
    let n = run.problem.system.bodies.len();
    let (t0, t1) = (
        s.t.first().copied().unwrap_or(0.0),
        s.t.last().copied().unwrap_or(1.0),
    );
    let columns = RASTER.0.min(s.len().saturating_sub(1)).max(1);
    let rows = n.min(RASTER.1);
    let x_edges: Vec<f64> = (0..=columns)
        .map(|c| t0 + (t1 - t0) * c as f64 / columns as f64)
        .collect();
    let body_of_row = |r: usize| r * n / rows;
    let mut cells = Vec::with_capacity(columns * rows);
    let mut table = Table::new(&["t_start", "t_end", "body", "mode"]);
    let mut k = 0;
    for c in 0..columns {
        while k + 1 < s.len() && s.t[k] < x_edges[c] {
            k += 1;
        }
        let modes = s.modes_at(k);
        for r in 0..rows {
            let i = body_of_row(r);
            let mode = run.problem.layout.contact[i]
                .map(|j| run.problem.reported_mode(j, s.y_at(k), modes));
            cells.push(match mode {
                None => 3,
                Some(SLIP_POSITIVE) => 0,
                Some(SLIP_NEGATIVE) => 1,
                Some(_) => 2,
            });
            table.rows.push(vec![
                Cell::Num(x_edges[c]),
                Cell::Num(x_edges[c + 1]),
                Cell::Text(run.problem.system.bodies[i].name.clone()),
                Cell::Text(mode.map_or("none", mode_name).into()),
            ]);
        }
    }
    let raster = Raster {
        title: format!("{title}: contact modes"),
        x_label: "time t (s)".into(),
        y_label: if rows < n {
            format!("body index ({rows} of {n} bodies)")
        } else {
            "body index".into()
        },
        x_edges,
        rows,
        cells,
        legend: vec![
            (plot::RED, "slip+".into()),
            (plot::BLUE, "slip-".into()),
            (plotters::style::RGBColor(170, 170, 170), "stick".into()),
            (plotters::style::WHITE, "no contact".into()),
        ],
    };
    Ok((raster, table.to_csv(path)?))
}

/// The advice for a chain of a law of the user's own with a `spread` above 0: the spread
/// scales the force levels of a law of the catalog, and an own law is the same on every block.
fn unspread_warning(source: &ChainSource) -> Option<String> {
    let spread = source.chain.spread;
    (source.law.catalog().is_none() && spread > 0.0).then(|| {
        format!(
            "the chain's `spread` = {} scales the force levels of the catalog's laws; law `{}` \
             is your own and acts the same on every block (set spread=0 to say so)",
            ranges::show(spread),
            source.law
        )
    })
}

/// The friction law of every contact of `system`, by name; `None` when they differ.
fn common_model(system: &System) -> Option<String> {
    let mut names = system.contacts.iter().map(|c| c.model.name());
    let first = names.next()?;
    names.all(|n| n == first).then(|| first.to_string())
}

/// The options of a system run from the command line: its step control and limits, checked,
/// and `points` evenly spaced output times on [0, t_end] ([`crate::sweep::grid_options`]).
pub fn grid_options(args: &SimulateArgs, t_end: f64, points: usize) -> Result<Options, AppError> {
    let limits = args.solver.checked_limits()?;
    Ok(crate::sweep::grid_options(
        args.solver.checked_step()?,
        &limits,
        t_end,
        points,
    ))
}

/// Runs `simulate` on a system: its files in memory, its trajectory as the file or as columns.
pub fn make(args: &SimulateArgs, trajectory_as: TrajectoryAs) -> Result<Made, AppError> {
    let Described {
        system,
        name,
        mut parameters,
        friction,
        source,
    } = system_of(
        args.system.as_deref(),
        args.model.as_ref(),
        &args.model_options,
    )?;
    args.solver.checked_step()?;
    let switching = args.solver.switching();
    parameters.extend(scheme_parameters(switching, &friction));
    system.validate()?;
    let bodies = chosen_bodies(&system, &args.bodies)?;
    let scheme = switching.scheme(args.solver.solver(), &friction);
    let t_end = args
        .checked_t_end()?
        .unwrap_or_else(|| default_t_end(args.system.as_deref()));
    let points = system_points(args, friction_systems::Layout::of(&system).dim())?;
    let options = grid_options(args, t_end, points)?;
    let step = options.step;
    let method = scheme.method_name();
    let bar = Progress::time(t_end, &format!("{name} {method}"));
    // The times each step reached, for the step size at the points where the stiffness is
    // measured.
    let mut step_ends = Vec::new();
    let run = friction_systems::simulate(&system, scheme, options, &mut |t| {
        bar.at(t);
        step_ends.push(t);
    })?;
    bar.finish();
    let stiffness = run.stiffness(&step_ends);
    drop(step_ends);

    let title = format!("{name} ({method}, {} switching)", switching.name());
    let mut files = Artifacts::default();
    add_stiffness(&mut files, &args.out, &stiffness, &title)?;
    if !run.solution.is_empty() {
        let (raster, data) = space_time(&run, &title, &args.out.join("space-time.csv"))?;
        files.add(args.out.join("space-time.csv"), data);
        files.add_raster(&args.out.join("space-time"), &raster)?;
    }
    // One colour each: the first bodies written, at most ten.
    let drawn = bodies.len().min(DRAWN_BODIES);
    let velocity = Plot {
        title: if drawn < bodies.len() {
            format!(
                "{title}: velocities of the first {drawn} of {} bodies written",
                bodies.len()
            )
        } else {
            format!("{title}: velocities")
        },
        x_label: "time t (s)".into(),
        y_label: "velocity v (m/s)".into(),
        series: bodies
            .iter()
            .take(drawn)
            .enumerate()
            .map(|(c, &i)| Series {
                label: Some(system.bodies[i].name.clone()),
                points: run.body(i).iter().map(|b| (b.t, b.v)).collect(),
                color: PALETTE[c],
                width: 2,
                marker: Marker::None,
            })
            .collect(),
        legend: Corner::UpperRight,
        log: false,
    };
    files.add_plot(&args.out.join("velocity"), &velocity)?;
    let setup = RunSetup {
        system: name,
        model: common_model(&system),
        variant: args
            .model
            .as_ref()
            .and_then(ModelChoice::catalog)
            .map(|_| args.model_options.variant),
        n_bodies: system.bodies.len(),
        n_contacts: system.contacts.len(),
        scheme: SchemeName::of(switching).name(),
        solver: method,
        switching: switching.name(),
        step,
        t_end,
        parameters,
    };
    let events = run.contact_events();
    let energy = run.energy();
    let integrated = Integrated {
        error: run.error.clone(),
        t_reached: run.solution.t.last().copied(),
        event_counts: event_counts(&events),
        stats: run.solution.stats.into(),
        wall_time_s: run.wall_time_s,
        energy_residual: energy.map(|e| e.residual),
        energy,
        friction_work: None,
        loop_area: None,
        stiffness_detected_at: run.solution.stiffness_detected_at,
        method_switches: run.solution.method_switches.clone(),
        stiffness: StiffnessSummary::of(&stiffness),
        instability: run.instability(&scheme, step),
    };
    let record = RunRecord {
        summary: RunSummary::new(setup, integrated),
        bodies: system.bodies.iter().map(|b| b.name.clone()).collect(),
        trajectory: Trajectory::of_run(&run, &bodies),
        finals: run.final_states(),
        events,
    };
    let (failure, caution) = (record.summary.failure(), record.summary.caution());
    let columns = record.add_files(&mut files, &args.out, trajectory_as)?;
    let period = integrators::OdeProblem::time_scale(&run.problem);
    Ok(Made {
        files,
        trajectory: columns,
        notes: vec![format!(
            "{}, {}, {}, {:.3} s",
            counted(system.bodies.len(), "body", "bodies"),
            counted(run.solution.stats.steps, "step", "steps"),
            counted(run.solution.stats.events, "event", "events"),
            run.wall_time_s
        )],
        warnings: run
            .solution
            .stiffness_detected_at
            .map(|t| crate::warnings::stiffness_warning(method, t))
            .into_iter()
            .chain(crate::warnings::coarse_step_warning(step, period))
            .chain(crate::warnings::failure_warnings(
                args.solver.solver(),
                switching,
                step,
                t_end,
                period,
                run.error.as_ref(),
            ))
            .chain(crate::warnings::unread_warnings(
                &args.model_options.params.set,
                args.model.as_ref().and_then(ModelChoice::catalog),
                switching,
            ))
            .chain(args.solver.scheme.spelling_notes())
            .chain(source.as_ref().and_then(unspread_warning))
            .chain(caution)
            .collect(),
        failure,
    })
}
