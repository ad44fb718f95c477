//! The solver studies: convergence order, step-size independence, work–precision, the
//! explicit/implicit crossover and cost against size. Every study is a list of independent
//! runs evaluated on rayon's pool and collected in order, so its results do not depend on the
//! thread count. This module holds what the studies share (the methods, a run against the
//! reference and its errors); each study is in a file of its own.

mod compare;
mod convergence;
mod extend;
mod independence;
mod orders;
mod scaling;
mod stiffness;
mod testset;
mod work_precision;

use crate::batch;
pub use crate::batch::reference;
pub use crate::cases::{describe, Case, Measured, Measures, StudyCase, SystemCase, GRID_POINTS};
use crate::error::ScenarioError;
pub use crate::errors::{Quantity, Scales};
pub use crate::method::{resolution, steps_for, Method, StepKind};
pub use crate::study_run::{
    ErrorMeasure, Errors, Reference, StudyRun, WallTimes, REFERENCE_TOLERANCE,
};
pub use compare::{
    compare, parts, scheme_name, ComparePart, CompareSpec, ComparedRun, Comparison, CrossCheck,
    Crossover, EpsilonFit, Kind, ModelError, NeededWidth, Part, Regularisation, Resolutions,
    SchemeCost, Schemes, TargetCosts, TrackEnd, TrueSolution,
};
pub use convergence::{convergence, Convergence, OrderTable};
pub use extend::{next_resolution, FINEST_STEP_DIVISOR, STILL_FALLING, TIGHTEST_TOLERANCE};
pub use independence::{independence, FailedLevel, Independence, OutputCheck};
use integrators::StepControl;
pub use orders::{
    observed_order, orders, student_t_975, Fit, PairOrder, MIN_PAIRS, ORDER_AGREEMENT, ROUND_OFF,
};
pub use scaling::{scaling, Scaling, ScalingRun};
pub use stiffness::{
    crossover, reached, stiffness, winner, Cost, Reached, Stiffness, StiffnessPoint, Sweep, Winner,
};
pub use testset::{
    solve as solve_test_problem, testset_work_precision, TestRun, TestSetCounts, TestSetRun,
    TestSetWorkPrecision, MIN_CORRECT_DIGITS,
};
pub use work_precision::{work_precision, WorkPrecision};

/// Runs `case` with each (method, step) against its reference for a study of `methods`, the
/// reference runs and the runs in one list ([`batch`]).
pub fn run_against_reference(
    case: &dyn StudyCase,
    methods: &[Method],
    jobs: &[(Method, StepControl)],
    progress: &(dyn Fn() + Sync),
) -> Result<(Reference, Measures, Vec<StudyRun>), ScenarioError> {
    let posed = batch::Posed {
        case,
        reference_for: Some(methods),
        jobs,
    };
    let c = batch::run_cases(&[posed], 0, progress)?.remove(0);
    let (reference, measures) = c.reference.expect("a reference was asked for");
    Ok((reference, measures, c.runs))
}

/// The least-squares slope of `points` (NaN for fewer than two).
pub fn slope(points: &[(f64, f64)]) -> f64 {
    line(points).slope
}

/// The least-squares line through `points`: y = intercept + slope·x.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line {
    /// Its slope (NaN for fewer than two points).
    pub slope: f64,
    /// Its value at x = 0.
    pub intercept: f64,
    /// Σ (x − x̄)², which the slope's standard error divides by.
    pub sxx: f64,
}

/// The least-squares line through `points`.
pub fn line(points: &[(f64, f64)]) -> Line {
    let n = points.len() as f64;
    let (mx, my) = (
        points.iter().map(|p| p.0).sum::<f64>() / n,
        points.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let slope = if points.len() < 2 {
        f64::NAN
    } else {
        sxy / sxx
    };
    Line {
        slope,
        intercept: my - slope * mx,
        sxx,
    }
}
