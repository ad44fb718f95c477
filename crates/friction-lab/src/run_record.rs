//! The one result of `simulate`, for a rig and for a system alike (a rig is a system of one
//! body), and the one path that writes it: `trajectory.csv` (or the trajectory as columns),
//! `final.csv`, `events.csv` and `summary.json`, whose schema docs/files.md gives field by
//! field. The figures differ by kind of run and are added by the command.

use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::progress::Progress;
use crate::trajectory::{RecordAs, StepDoubling, Trajectory};
use friction_models::Variant;
use friction_systems::{mode_name, BodyState, ContactEvent, EnergyBalance};
use integrators::stability::Instability;
use integrators::{MethodSwitch, SolverError, Stats, StepControl};
use scenarios::analysis::closed_loop::ClosedLoop;
pub use scenarios::rig::RIG_BODY;
use scenarios::verdict::{Status, Verdict};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;

/// What `summary.json` says about one run of a rig or a system: what was run, its status, and
/// what the integration produced, in this order (docs/files.md).
#[derive(Clone, Debug, Serialize)]
pub struct RunSummary {
    /// What was run.
    #[serde(flatten)]
    pub setup: RunSetup,
    /// `ok`, `inaccurate`, `diverged` or `failed`, and why (`status`, `reason`).
    #[serde(flatten)]
    pub verdict: Verdict,
    /// What the integration produced.
    #[serde(flatten)]
    pub integrated: Integrated,
}

impl RunSummary {
    /// The summary of the run `setup` describes, which produced `integrated`, judged: by the
    /// solver's error where it stopped, otherwise by its energy balance (systems with bodies;
    /// [`Verdict::of_energy`]).
    pub fn new(setup: RunSetup, integrated: Integrated) -> RunSummary {
        let mut verdict = Verdict::of_run(
            integrated.error.as_ref(),
            integrated.energy.as_ref().map(|e| e.relative_residual),
            integrated.instability.as_ref(),
        );
        if let (Some(d), StepControl::Fixed { h }) = (&integrated.step_doubling, setup.step) {
            verdict = verdict.and(Verdict::inaccurate(d.reason(h)));
        }
        RunSummary {
            setup,
            verdict,
            integrated,
        }
    }

    /// The failure the command exits with (1) once the files are written: the solver's error,
    /// or a divergence its verdict found.
    pub fn failure(&self) -> Option<AppError> {
        match (&self.integrated.error, &self.verdict) {
            (Some(e @ SolverError::Runaway { .. }), _) => Some(AppError::Diverged(e.to_string())),
            (Some(e), _) => Some(AppError::Solver(e.clone())),
            (
                None,
                Verdict {
                    status: Status::Diverged,
                    reason,
                },
            ) => Some(AppError::Diverged(reason.clone().unwrap_or_default())),
            _ => None,
        }
    }

    /// The warning of an inaccurate run (it still exits 0).
    pub fn caution(&self) -> Option<String> {
        (self.verdict.status == Status::Inaccurate).then(|| {
            format!(
                "the run is inaccurate: {}",
                self.verdict.reason.as_deref().unwrap_or_default()
            )
        })
    }
}

/// What a run is: everything in its summary but what the integration produced.
#[derive(Clone, Debug, Serialize)]
pub struct RunSetup {
    /// The rig's name (`belt`), the chain's (`chain of 10 coulomb`) or the system file's path.
    pub system: String,
    /// The friction law of every contact; `None` for a system file whose contacts name
    /// different laws.
    pub model: Option<String>,
    /// The reading of a law of the catalog (rigs and the chain; `None` for a system file).
    pub variant: Option<Variant>,
    /// Bodies of the system (1 for a rig).
    pub n_bodies: usize,
    /// Contacts of the system (1 for a rig).
    pub n_contacts: usize,
    /// `event-driven` or `time-stepping`.
    pub scheme: &'static str,
    /// The method that integrated: the ODE solver, or `moreau-jean`.
    pub solver: &'static str,
    /// The treatment of v = 0: `event`, `regularized`, `naive`, or `timestepping`.
    pub switching: &'static str,
    /// The step control.
    pub step: StepControl,
    /// The end time asked for, s.
    pub t_end: f64,
    /// The parameters the run read, each in the unit `friction-lab models` lists: the rig's
    /// or the chain's, its law's, and the scheme's (`epsilon` regularised, `theta`
    /// time-stepped); a system file's own parameters are in the file.
    pub parameters: BTreeMap<String, f64>,
}

/// What the integration of a run produced, as its summary writes it.
#[derive(Clone, Debug, Serialize)]
pub struct Integrated {
    /// The solver's error, where it failed (written as its message: where and why).
    #[serde(serialize_with = "scenarios::study_run::message")]
    pub error: Option<SolverError>,
    /// The time of the last recorded point, s (`t_end` when the run completed; `None` when
    /// nothing was recorded).
    pub t_reached: Option<f64>,
    /// Contact switches by the mode entered (`slip+`, `slip-`, `stick`): [`event_counts`].
    pub event_counts: BTreeMap<&'static str, usize>,
    /// The solver's statistics.
    pub stats: StatsRecord,
    /// Wall time of the integration, s.
    pub wall_time_s: f64,
    /// The energy balance's residual, J (systems with bodies; its relative residual is in
    /// `energy`).
    pub energy_residual: Option<f64>,
    /// The energy balance, J (systems with bodies).
    pub energy: Option<EnergyBalance>,
    /// ∫F·v dt, J: the work done against friction (prescribed motions).
    pub friction_work: Option<f64>,
    /// ∮F dv, N·m/s: the friction–velocity loop area (prescribed motions).
    pub loop_area: Option<f64>,
    /// Where Hairer's stiffness test (Dormand–Prince) first judged the problem stiff, s.
    pub stiffness_detected_at: Option<f64>,
    /// `auto`'s switches of method: time (s), the method switched to, and the estimate h·ρ̂
    /// that decided it (empty for the other solvers).
    pub method_switches: Vec<MethodSwitch>,
    /// The stiffness along the run, summarised (rigs; `None` where it is not computed).
    pub stiffness: Option<StiffnessSummary>,
    /// The mode a fixed step makes grow, if any ([`Instability`]): a decaying mode of the
    /// Jacobian that an explicit method's step amplifies (`lambda_re`, `lambda_im` in 1/s, `h`
    /// in s, `amplification` |R(hλ)|), or a time-stepped sampled loop's multiplier (`multiplier_re`,
    /// `multiplier_im`, `abscissa` in 1/s, `h`, `t`, `amplification` |μ|): the run is then at
    /// least `inaccurate`.
    pub instability: Option<Instability>,
    /// A fixed-step run's error estimated by step doubling ([`StepDoubling`]: `relative`, `t`,
    /// `quantity`, `body`): the run is `inaccurate` above
    /// [`crate::trajectory::STEP_DOUBLING_INACCURATE`]; null for an adaptive run, a run that
    /// stopped, or one whose run at h/2 stopped.
    pub step_doubling: Option<StepDoubling>,
    /// What the closed loop did, for a run whose body a controller positions (the `servo`
    /// rig): hunting or converged, the cycle, the tracking error ([`ClosedLoop`]); left out of
    /// the summary of a run without a controller.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub closed_loop: Option<ClosedLoop>,
}

/// The stiffness along a run, `h·ρ` at its recorded points (the step that reached each
/// point times the spectral radius of the Jacobian there), summarised for `summary.json`.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct StiffnessSummary {
    /// The points measured.
    pub points: usize,
    /// The largest `h·ρ`, and where.
    pub max_h_rho: f64,
    /// Time of the largest `h·ρ`, s.
    pub t_at_max: f64,
    /// The median `h·ρ`.
    pub median_h_rho: f64,
    /// The largest spectral radius ρ, 1/s.
    pub max_rho: f64,
}

impl StiffnessSummary {
    /// The summary of `points`; `None` for none.
    pub fn of(points: &[friction_systems::StiffnessPoint]) -> Option<StiffnessSummary> {
        let top = points.iter().max_by(|a, b| a.h_rho.total_cmp(&b.h_rho))?;
        let mut values: Vec<f64> = points.iter().map(|p| p.h_rho).collect();
        values.sort_by(f64::total_cmp);
        let mid = values.len() / 2;
        let median = if values.len() % 2 == 1 {
            values[mid]
        } else {
            0.5 * (values[mid - 1] + values[mid])
        };
        Some(StiffnessSummary {
            points: points.len(),
            max_h_rho: top.h_rho,
            t_at_max: top.t,
            median_h_rho: median,
            max_rho: points.iter().map(|p| p.rho).fold(0.0, f64::max),
        })
    }
}

/// The switches `events` counted by the mode each one entered.
pub fn event_counts(events: &[ContactEvent]) -> BTreeMap<&'static str, usize> {
    let mut counts = BTreeMap::new();
    for e in events {
        *counts.entry(mode_name(e.to)).or_insert(0) += 1;
    }
    counts
}

/// The solver's statistics as `summary.json` writes them: [`Stats`]' counts and their sum
/// `rejected` = `rejected_error + rejected_newton`.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct StatsRecord {
    /// The counts.
    #[serde(flatten)]
    pub counts: Stats,
    /// Rejected steps, whatever the cause.
    pub rejected: usize,
}

impl From<Stats> for StatsRecord {
    fn from(counts: Stats) -> Self {
        StatsRecord {
            counts,
            rejected: counts.rejected(),
        }
    }
}

/// One run of a rig or a system: its summary, its trajectory, every body's final state and
/// every switch of a contact.
#[derive(Clone, Debug)]
pub struct RunRecord {
    /// What `summary.json` holds.
    pub summary: RunSummary,
    /// Every body's name, by index.
    pub bodies: Vec<String>,
    /// The trajectory of the bodies written.
    pub trajectory: Trajectory,
    /// Every body at the last recorded point (none when nothing was recorded).
    pub finals: Vec<BodyState>,
    /// Every switch of a contact, in time order.
    pub events: Vec<ContactEvent>,
}

impl RunRecord {
    /// Whether some body's law has an internal state (the tables then have a `z` column).
    fn has_states(&self) -> bool {
        self.trajectory.z.is_some()
    }

    /// `final.csv`: `body, x, v, friction, mode[, z]`, one row per body.
    pub fn final_table(&self) -> Table {
        let states = self.has_states();
        let columns = ["body", "x", "v", "friction", "mode", "z"];
        let mut t = Table::new(&columns[..columns.len() - usize::from(!states)]);
        for (name, b) in self.bodies.iter().zip(&self.finals) {
            let mut row = vec![
                Cell::Text(name.clone()),
                Cell::Num(b.x),
                Cell::Num(b.v),
                Cell::Num(b.friction),
                Cell::Text(b.mode.map_or("none", mode_name).into()),
            ];
            if states {
                row.push(Cell::num(b.z.unwrap_or(f64::NAN)));
            }
            t.rows.push(row);
        }
        t
    }

    /// `events.csv`: `t, body, from, to`, one row per switch of a contact.
    pub fn events_table(&self) -> Table {
        let mut t = Table::new(&["t", "body", "from", "to"]);
        for e in &self.events {
            t.rows.push(vec![
                Cell::Num(e.t),
                Cell::Text(self.bodies[e.body].clone()),
                Cell::Text(mode_name(e.from).into()),
                Cell::Text(mode_name(e.to).into()),
            ]);
        }
        t
    }

    /// The record as `record_as` asks: its files in `out` added to `files` (`summary.json`,
    /// `final.csv`, `events.csv`, `trajectory.csv`), or its values, returned.
    pub fn deliver(
        self,
        files: &mut Artifacts,
        out: &Path,
        record_as: RecordAs,
    ) -> Result<Option<RunValues>, AppError> {
        if record_as == RecordAs::Values {
            return Ok(Some(RunValues {
                finals: self.final_table(),
                events: self.events_table(),
                summary: self.summary,
                trajectory: self.trajectory,
            }));
        }
        files.add_table(out.join("final.csv"), self.final_table())?;
        files.add_table(out.join("events.csv"), self.events_table())?;
        files.add_json(out.join("summary.json"), &self.summary)?;
        let path = out.join("trajectory.csv");
        let progress = Progress::elapsed("formatting trajectory.csv");
        let bytes = self.trajectory.to_csv(&path)?;
        progress.finish();
        files.add(path, bytes);
        Ok(None)
    }
}

/// A run's record as values, for a front end that makes its own arrays and tables of them
/// (Python): what the command line writes as `summary.json`, `trajectory.csv`, `final.csv`
/// and `events.csv`.
#[derive(Clone, Debug)]
pub struct RunValues {
    /// The summary.
    pub summary: RunSummary,
    /// The trajectory of the bodies written, as columns.
    pub trajectory: Trajectory,
    /// Every body at the last recorded point: `body, x, v, friction, mode[, z]`.
    pub finals: Table,
    /// Every switch of a contact: `t, body, from, to`.
    pub events: Table,
}
