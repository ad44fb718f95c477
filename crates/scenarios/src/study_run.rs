//! One run of a study against its reference: where the reference comes from, the run's
//! errors against it, and the record a study keeps of the run.

use crate::cases::Measures;
pub use crate::errors::{ErrorMeasure, Errors};
use crate::method::StepKind;
use crate::verdict::Verdict;
use friction_models::params::show;
use integrators::{SolverError, Stats, StepControl};
use serde::Serialize;

/// Where the reference comes from.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Reference {
    /// An exact solution, by name.
    ClosedForm(String),
    /// A much tighter run of a solver.
    Run {
        /// The solver.
        solver: &'static str,
        /// Its step control.
        step: StepControl,
        /// A second tight run by an independent solver: the solver, and the largest
        /// relative difference of the two on the time grid ([`Errors::grid_relative`]), the
        /// reference's estimated error.
        cross_check: (&'static str, f64),
        /// Where Dormand–Prince's stiffness test fired in its tight run: the case is stiff,
        /// and `solver` is an implicit method cross-checked by an explicit one; `None`
        /// where it did not, and `solver` is an explicit 5(4) pair.
        stiffness_detected_at: Option<f64>,
    },
}

/// The smallest error a study may report against a reference whose estimated error is `e`:
/// `REFERENCE_MARGIN · e`. Below it, the error measured is the reference's as much as the
/// run's.
pub const REFERENCE_MARGIN: f64 = 100.0;

impl Reference {
    /// Its estimated error on the time grid: 0 for a closed form, the cross-check's
    /// difference for a tight run.
    pub fn estimated_error(&self) -> f64 {
        match self {
            Reference::ClosedForm(_) => 0.0,
            Reference::Run { cross_check, .. } => cross_check.1,
        }
    }

    /// Whether the reference limits the finest of `runs`: its estimated error above
    /// 1/[`REFERENCE_MARGIN`] of the smallest grid error of an `ok` run; `None` where it does
    /// not, or the sentence that says so.
    pub fn limits(&self, runs: &[StudyRun]) -> Option<String> {
        let finest = (runs.iter())
            .filter(|r| r.verdict.is_ok() && r.errors.grid_relative > 0.0)
            .min_by(|a, b| a.errors.grid_relative.total_cmp(&b.errors.grid_relative))?;
        let (e, smallest) = (self.estimated_error(), finest.errors.grid_relative);
        let Reference::Run {
            solver,
            cross_check,
            ..
        } = self
        else {
            return None;
        };
        (REFERENCE_MARGIN * e > smallest).then(|| {
            format!(
                "the finest runs are limited by the reference: its estimated error {} ({solver} \
                 against {} at {REFERENCE_TOLERANCE:e}) is more than 1/{REFERENCE_MARGIN} of the \
                 smallest error reported, {} ({} at {})",
                show(e),
                cross_check.0,
                show(smallest),
                finest.solver,
                show(finest.resolution)
            )
        })
    }
}

/// The tolerance of a reference run, rtol = atol.
pub const REFERENCE_TOLERANCE: f64 = 1e-13;

/// One run of a study.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StudyRun {
    /// The method's label ([`crate::method::Method::label`]): the solver, or a peer with its treatment.
    pub solver: String,
    /// The step size (fixed-step runs) or the tolerance (adaptive runs).
    pub resolution: f64,
    /// Which the resolution is: `fixed` (a step size, s) or `adaptive` (rtol = atol).
    pub step: StepKind,
    /// Errors against the reference.
    pub errors: Errors,
    /// The run's measures.
    #[serde(skip)]
    pub measures: Measures,
    /// Work done.
    pub stats: Stats,
    /// Work in right-hand-side evaluations ([`Stats::work`] at the problem's dimension).
    pub work: usize,
    /// The solver's error, if it failed (written as its message).
    #[serde(serialize_with = "message")]
    pub failure: Option<SolverError>,
    /// What its result is worth: `failed` or `diverged` where the solver stopped, `inaccurate`
    /// where its error is as large as the solution ([`Verdict::against_reference`]), else
    /// `ok`. Only an `ok` run enters a fit or a crossover.
    #[serde(flatten)]
    pub verdict: Verdict,
    /// Whether it failed as an explicit method with a fixed step past its stability limit
    /// ([`crate::run::diverged`]).
    #[serde(skip)]
    pub diverged: bool,
    /// Wall time of the run over it and its timing repeats (not deterministic: kept out of
    /// the study's main files).
    #[serde(skip)]
    pub wall_time: WallTimes,
}

/// The wall times of a run over its repeats, s: their median and spread.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct WallTimes {
    /// How many times the run was timed.
    pub repeats: usize,
    /// The median.
    pub median: f64,
    /// The smallest.
    pub min: f64,
    /// The first quartile (linear interpolation between order statistics, Hyndman & Fan's
    /// type 7, as numpy's default).
    pub q1: f64,
    /// The third quartile.
    pub q3: f64,
    /// The largest.
    pub max: f64,
}

impl WallTimes {
    /// The median and spread of `times` (at least one).
    pub fn of(times: &[f64]) -> WallTimes {
        let mut t = times.to_vec();
        t.sort_by(f64::total_cmp);
        let quantile = |p: f64| {
            let x = p * (t.len() - 1) as f64;
            let (i, f) = (x.floor() as usize, x.fract());
            t[i] + f * (t[(i + 1).min(t.len() - 1)] - t[i])
        };
        WallTimes {
            repeats: t.len(),
            median: quantile(0.5),
            min: t[0],
            q1: quantile(0.25),
            q3: quantile(0.75),
            max: t[t.len() - 1],
        }
    }
}

/// A run's failure as its message, or null: what the study files write.
pub fn message<S: serde::Serializer>(
    failure: &Option<SolverError>,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    match failure {
        Some(e) => serializer.serialize_some(&e.to_string()),
        None => serializer.serialize_none(),
    }
}
