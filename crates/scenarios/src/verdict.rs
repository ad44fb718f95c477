//! The judgement of a run: whether what it computed can be trusted. A run that ended is not
//! for that a run that is right: one whose energy balance fails by as much as the energy it
//! moved has computed nothing, and one whose error against a reference exceeds the solution
//! itself has no correct digit. Each verdict says why, in words and numbers
//! (docs/studies.md, "Verdicts").

use integrators::stability::Instability;
use integrators::SolverError;
use serde::Serialize;

/// A run's energy balance whose relative residual (|residual| over its largest term) exceeds
/// this is `inaccurate`: the energy books do not close to 1 %.
pub const ENERGY_INACCURATE: f64 = 1e-2;

/// A run whose relative energy residual exceeds this is `diverged`: the residual is as large
/// as the largest term of the balance, so the motion's energy was made by the integration,
/// not by the sources (RK4 at h = 1 s on the belt: 1.08, the block at x = −6e50 m).
pub const ENERGY_DIVERGED: f64 = 0.9;

/// What a run's result is worth.
/// Ordered from best to worst: a run's status is the worst any check gives it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Nothing found against it.
    Ok,
    /// It ran to the end, but a check failed: its numbers are kept as data and left out of
    /// every fit and crossover.
    Inaccurate,
    /// The state left every bound (non-finite, or energy made by the integration).
    Diverged,
    /// The solver stopped with an error (a limit, a Newton failure, a step too small).
    Failed,
}

impl Status {
    /// Its name, as tables and summaries write it.
    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Inaccurate => "inaccurate",
            Status::Diverged => "diverged",
            Status::Failed => "failed",
        }
    }
}

/// A status and why.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct Verdict {
    /// The status.
    pub status: Status,
    /// Why, in words and numbers (`None` for `ok`).
    pub reason: Option<String>,
}

impl Verdict {
    /// Nothing found against the run.
    pub const OK: Verdict = Verdict {
        status: Status::Ok,
        reason: None,
    };

    fn new(status: Status, reason: String) -> Verdict {
        Verdict {
            status,
            reason: Some(reason),
        }
    }

    /// The verdict on a solver's error: `diverged` for a non-finite state or a runaway
    /// (`friction_systems::Reach`), `failed` for any other; `None` where there was no error.
    pub fn of_error(error: Option<&SolverError>) -> Option<Verdict> {
        error.map(|e| match e {
            SolverError::NonFinite { .. } | SolverError::Runaway { .. } => {
                Verdict::new(Status::Diverged, e.to_string())
            }
            _ => Verdict::new(Status::Failed, e.to_string()),
        })
    }

    /// The verdict on a run: by the solver's `error` where it stopped ([`Verdict::of_error`]),
    /// otherwise by its energy balance's `relative_residual` where it keeps one
    /// ([`Verdict::of_energy`]); then `inaccurate` too where its fixed step is beyond the
    /// method's stability limit ([`Verdict::with_instability`]).
    pub fn of_run(
        error: Option<&SolverError>,
        relative_residual: Option<f64>,
        instability: Option<&Instability>,
    ) -> Verdict {
        Verdict::of_error(error)
            .unwrap_or_else(|| relative_residual.map_or(Verdict::OK, Verdict::of_energy))
            .with_instability(instability)
    }

    /// Whether the run computed nothing to measure: `diverged` or `failed`.
    pub fn is_broken(&self) -> bool {
        self.status >= Status::Diverged
    }

    /// `inaccurate` for `reason`, where there is one; `ok` otherwise.
    pub fn inaccurate(reason: Option<String>) -> Verdict {
        reason.map_or(Verdict::OK, |r| Verdict::new(Status::Inaccurate, r))
    }

    /// The verdict on a relative energy residual ([`ENERGY_INACCURATE`],
    /// [`ENERGY_DIVERGED`]).
    pub fn of_energy(relative_residual: f64) -> Verdict {
        let why = |what: &str, bound: f64| {
            format!(
                "the energy balance's residual is {} of its largest term (above {}): {what}",
                percent(relative_residual),
                percent(bound)
            )
        };
        if relative_residual > ENERGY_DIVERGED || relative_residual.is_nan() {
            Verdict::new(
                Status::Diverged,
                why(
                    "the motion's energy was made by the integration, not by the sources",
                    ENERGY_DIVERGED,
                ),
            )
        } else if relative_residual > ENERGY_INACCURATE {
            Verdict::new(
                Status::Inaccurate,
                why(
                    "the step or tolerance does not resolve the motion",
                    ENERGY_INACCURATE,
                ),
            )
        } else {
            Verdict::OK
        }
    }

    /// The verdict on a study run's largest `relative` error against a reference (over the
    /// time grid and at the end, each quantity over the solution's scale in it):
    /// `inaccurate` where the error is as large as the solution (no correct digit).
    pub fn against_reference(relative: f64) -> Verdict {
        if relative >= 1.0 {
            Verdict::new(
                Status::Inaccurate,
                format!(
                    "its relative error {} is at least 1: no correct digit",
                    friction_models::params::show(relative),
                ),
            )
        } else {
            Verdict::OK
        }
    }

    /// This verdict and `other` together: the worse status, and both reasons.
    pub fn and(self, other: Verdict) -> Verdict {
        let reason = match (self.reason, other.reason) {
            (Some(a), Some(b)) => Some(format!("{a}; {b}")),
            (a, b) => a.or(b),
        };
        Verdict {
            status: self.status.max(other.status),
            reason,
        }
    }

    /// This verdict and, where a fixed step is beyond the method's stability limit at the
    /// start ([`integrators::stability`]), `inaccurate` for that reason.
    pub fn with_instability(self, instability: Option<&Instability>) -> Verdict {
        match instability {
            Some(i) => self.and(Verdict::new(Status::Inaccurate, i.to_string())),
            None => self,
        }
    }

    /// Whether the run's numbers may enter a fit or a crossover: only an `ok` run's.
    pub fn is_ok(&self) -> bool {
        self.status == Status::Ok
    }
}

/// `x` as a percentage ("107.7 %", "1.0 %", "2.5e-3 %").
fn percent(x: f64) -> String {
    let p = 100.0 * x;
    if p >= 0.1 {
        format!("{p:.1} %")
    } else {
        format!("{p:.1e} %")
    }
}
