//! A system's run (the chain, a system file, a system built in code): its files (trajectory
//! of the bodies chosen, summary, events) and figures (velocities, the space–time picture of
//! the contact modes, stiffness along the run).

use super::delivered::{made_of_record, Advice};
use super::motion::{add_motion, spread, LINE_BODIES};
use super::space_time::Sampling;
use super::spectra::{add_spectra, no_spectrum_note, system_velocities};
use super::stiffness::add_stiffness;
use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::made::Made;
use crate::output::counted;
use crate::progress::Progress;
use crate::ranges;
use crate::run_record::{
    event_counts, Integrated, RunRecord, RunSetup, RunSummary, StiffnessSummary,
};
use crate::trajectory::{RecordAs, Trajectory};
use crate::window::Window;
use friction_models::{FrictionParams, Variant};
use friction_systems::file::SystemSource;
use friction_systems::{Scheme, System};
use integrators::{Options, StepControl};
use scenarios::analysis::closed_loop::ClosedLoop;
use scenarios::chain::ChainSource;
use std::collections::BTreeMap;
use std::path::Path;

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

/// Reads the system `source` declares (a file, or JSON text), each number at a path of
/// `assignments` (`TABLE.WHICH.KEY`, docs/systems.md) set first, with a heartbeat, on a thread
/// of its own: a signal stops the command at once ([`AppError::Stopped`]; the parse cannot be
/// stopped inside, so it is left to end with the process), where a file of 10⁶ bodies takes
/// seconds to parse.
pub fn load(
    source: &SystemSource,
    assignments: &[(String, f64)],
) -> Result<friction_systems::System, AppError> {
    let what = source.name();
    let progress = Progress::elapsed(&format!("loading {what}"));
    let (send, receive) = std::sync::mpsc::channel();
    let owned = source.clone();
    let assignments = assignments.to_vec();
    std::thread::spawn(move || {
        let _ = send.send(owned.read_with(&assignments));
    });
    let poll = std::time::Duration::from_secs_f64(LOAD_POLL_S);
    loop {
        if integrators::interrupt::requested() {
            return Err(AppError::Stopped(format!("loading {what}")));
        }
        match receive.recv_timeout(poll) {
            Ok(read) => {
                progress.finish();
                return Ok(read?);
            }
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {}
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
                return Err(AppError::StudyRun(format!(
                    "loading {what} ended without a result"
                )))
            }
        }
    }
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

/// A system's run as its front end describes it.
pub struct SystemRun<'a> {
    /// The system, its name and parameters.
    pub described: &'a Described,
    /// The scheme.
    pub scheme: Scheme,
    /// The step control, bounds and output grid; its `t_end` is the run's.
    pub options: Options,
    /// The bodies written to `trajectory.csv` (0-based); the line figures draw a few spread over
    /// them ([`spread`]).
    pub bodies: &'a [usize],
    /// The reading of a catalog model named for every contact (the chain's), if one was.
    pub variant: Option<Variant>,
    /// The span of time the figures draw and the spectra measure; `None`: the whole run (the
    /// spectra its last half).
    pub window: Option<Window>,
}

/// Simulates `run` and its files into `out`, in memory: `trajectory.csv` (or its columns) of
/// the bodies chosen, `summary.json`, `events.csv`, their velocities, the space–time picture of
/// the contact modes, and the stiffness along the run. The warnings are the run's: its
/// stiffness, a step too coarse for its time scale, why it failed, a chain's spread that a law
/// of one's own does not read.
pub fn simulate_system(run: SystemRun, out: &Path, record_as: RecordAs) -> Result<Made, AppError> {
    let SystemRun {
        described,
        scheme,
        options,
        bodies,
        variant,
        window,
    } = run;
    let Described {
        system,
        name,
        parameters,
        source,
        ..
    } = described;
    let mut parameters = parameters.clone();
    parameters.extend(scheme.parameter().map(|(k, v)| (k.to_string(), v)));
    let t_end = options.t_end;
    let step = options.step;
    let method = scheme.method_name();
    let bar = Progress::time(t_end, &format!("{name} {method}"));
    // The times each step reached, for the step size at the points where the stiffness is
    // measured.
    let mut step_ends = Vec::new();
    let half = options.clone();
    let run = friction_systems::simulate(system, scheme, options, &mut |t| {
        bar.at(t);
        step_ends.push(t);
    })?;
    bar.finish();
    let trajectory = Trajectory::of_run(&run, bodies);
    let step_doubling = match (step, &run.error) {
        (StepControl::Fixed { h }, None) => {
            let bar = Progress::time(
                t_end,
                &format!("{name} {method} at h/2 (its error estimate)"),
            );
            let half = Options {
                step: StepControl::Fixed { h: h / 2.0 },
                ..half
            };
            let fine = friction_systems::simulate(system, scheme, half, &mut |t| bar.at(t))?;
            bar.finish();
            (fine.error.is_none())
                .then(|| trajectory.doubling_difference(&Trajectory::of_run(&fine, bodies)))
                .flatten()
        }
        _ => None,
    };
    let stiffness = run.stiffness(&step_ends);
    drop(step_ends);

    let title = format!(
        "{name} ({method}, {} switching{})",
        scheme.treatment_name(),
        Window::note(window)
    );
    let mut files = Artifacts::default();
    add_stiffness(&mut files, out, &stiffness, &title, window)?;
    if !run.solution.is_empty() {
        let sampling = Sampling::of(&run, window);
        let (raster, table) = sampling.modes(&run, &title);
        files.add_table(out.join("space-time.csv"), table)?;
        files.add_raster(&out.join("space-time"), &raster)?;
        let velocities = sampling.velocities(&run, &title);
        files.add_raster(&out.join("velocity-space-time"), &velocities)?;
    }
    // The line figures and the spectra: a few bodies spread over those written, one colour
    // each.
    let shown = spread(bodies, LINE_BODIES);
    add_motion(
        &mut files,
        out,
        &run,
        (&shown, bodies.len()),
        &title,
        window,
    )?;
    let spectra = match system_velocities(&run, system, &shown, window) {
        Some(measured) => add_spectra(&mut files, out, &measured, &title)?,
        None => vec![no_spectrum_note(window)],
    };
    let setup = RunSetup {
        system: name.clone(),
        model: common_model(system),
        variant,
        n_bodies: system.bodies.len(),
        n_contacts: system.contacts.len(),
        scheme: scheme.name(),
        solver: method,
        switching: scheme.treatment_name(),
        step,
        t_end,
        parameters,
    };
    let events = run.contact_events();
    let energy = run.energy();
    let measured_loop = ClosedLoop::of_run(&run, system);
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
        step_doubling,
        closed_loop: measured_loop,
    };
    let record = RunRecord {
        summary: RunSummary::new(setup, integrated),
        bodies: system.bodies.iter().map(|b| b.name.clone()).collect(),
        trajectory,
        finals: run.final_states(),
        events,
    };
    let advice = Advice {
        scheme,
        period: run.problem.system.shortest_period(true),
        own: source.as_ref().and_then(unspread_warning),
    };
    let notes = std::iter::once(format!(
        "{}, {}, {}, {:.3} s",
        counted(system.bodies.len(), "body", "bodies"),
        counted(run.solution.stats.steps, "step", "steps"),
        counted(run.solution.stats.events, "event", "events"),
        run.wall_time_s
    ))
    .chain(spectra)
    .chain(measured_loop.iter().map(|c| c.to_string()))
    .collect();
    made_of_record(record, files, out, record_as, advice, notes)
}
