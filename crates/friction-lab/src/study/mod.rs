//! The studies as one abstraction: a [`Study`] makes its runs (solvers on a case against a
//! reference, Table 2's protocols, the belt's settled states) into a typed result, and writes
//! that result's tables and figures.
//! [`conduct`] is what every study shares: its options checked before anything runs, its runs
//! on a pool of threads with a progress bar (collected in order, so the files do not depend on
//! the thread count), its files added to an [`Output`]. The command line, `reproduce` and a
//! user's own code conduct the same studies; each study is a file of this module.

mod branches;
mod closed_loop;
mod compare;
mod convergence;
mod draw;
mod independence;
mod orbit;
mod phenomena;
mod report;
mod scaling;
mod servo_loop;
pub mod solver_studies;
mod stick_slip;
mod stiffness;
mod table2;
mod table2_cost;
mod tables;
mod testset;
mod work_precision;

pub use branches::{branches_lines, BranchesStudy};
pub use closed_loop::{ClosedLoopStudy, ClosedLoops, Regulation, Task, Tracking, TASKS};
pub use compare::{compare_lines, figures as compare_figures, CompareStudy};
pub use convergence::ConvergenceStudy;
pub use independence::{IndependenceStudy, Refinement};
pub use orbit::{orbit_lines, OrbitStudy};
pub use phenomena::PhenomenaRequest;
pub use report::{conduct_all, Entry, ReportEntry};
pub use scaling::ScalingStudy;
pub use servo_loop::{loop_lines, LoopResult, LoopStudy};
pub use solver_studies::{
    CompareRequest, ConvergeRequest, IndependenceRequest, OrbitRequest, Problem, StiffnessRequest,
    WorkPrecisionRequest,
};
pub use stick_slip::{
    regime_series, Bifurcation, BifurcationStudy, StickSlipMap, StickSlipMapStudy, REGIMES,
};
pub use stiffness::StiffnessStudy;
pub use table2::{
    check_decided, reachable, undecided, unread_by_all, Table2Study, MAX_STEPS_PER_SECOND,
};
pub use testset::TestSetStudy;
pub use work_precision::WorkPrecisionStudy;

use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::progress::Progress;
use crate::provenance::Provenance;
use crate::threads::with_threads;
use friction_systems::{Scheme, Switching};
use integrators::Solver;
use scenarios::studies::{self, Method, StepKind, StudyCase, StudyRun};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// A study: its runs, the typed result they make, and the files that show it.
pub trait Study: Sync {
    /// What the study makes of its runs.
    type Result: Send;

    /// Its name, as its progress bar says it.
    fn name(&self) -> &'static str;

    /// Checks its options (lists, ranges) before anything runs: a bad one is
    /// [`AppError::Usage`], exit code 2.
    fn check(&self) -> Result<(), AppError> {
        Ok(())
    }

    /// How many runs it makes: the length of its progress bar.
    fn runs(&self) -> usize;

    /// Makes its runs (on the current thread pool) and their result; `progress` is called
    /// after each run.
    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<Self::Result, AppError>;

    /// A failure that the files record and the command exits with once they are written (a
    /// level of an independence study that failed); none by default.
    fn failure(&self, _result: &Self::Result) -> Option<AppError> {
        None
    }

    /// Adds its tables, JSON and figures to `out`.
    fn write(&self, result: &Self::Result, out: &mut StudyFiles) -> Result<(), AppError>;
}

/// The failure of a study none of whose `runs` measured anything: every one failed (exit 1,
/// after the files that say which and why are written). A study with one run that succeeded
/// has something to show; one with none must not end as a success.
pub fn nothing_measured(study: &str, runs: &[StudyRun]) -> Option<AppError> {
    let first = runs.first()?.failure.as_ref()?;
    runs.iter().all(|r| r.failure.is_some()).then(|| {
        AppError::StudyRun(format!(
            "{study}: every run failed ({n} of {n}), nothing was measured; the first, {} at {} = \
             {}: {first}",
            runs[0].solver,
            match runs[0].step {
                StepKind::Fixed => "h",
                StepKind::Adaptive => "tol",
            },
            friction_models::params::show(runs[0].resolution),
            n = runs.len()
        ))
    })
}

/// Where a study's files go: a folder, a file stem, and the files being prepared.
pub struct StudyFiles<'a> {
    /// The files being prepared.
    pub files: &'a mut Artifacts,
    /// The folder.
    pub dir: &'a Path,
    /// The stem every file of the study starts with (`converge` for `converge.csv`).
    pub stem: &'a str,
    /// Where the study's result comes from: its JSON opens with it.
    pub provenance: &'a Provenance,
}

impl StudyFiles<'_> {
    /// The path of the study's file `{stem}{suffix}`, e.g. `.csv` or `-timing.csv`.
    pub fn path(&self, suffix: &str) -> PathBuf {
        self.dir.join(format!("{}{suffix}", self.stem))
    }

    /// Adds the study's JSON `{stem}.json`: `provenance` ([`Provenance`]), then the fields of
    /// `value` (a JSON object).
    pub fn add_json<T: Serialize>(&mut self, value: &T) -> Result<(), AppError> {
        #[derive(Serialize)]
        struct WithProvenance<'a, T: Serialize> {
            provenance: &'a Provenance,
            #[serde(flatten)]
            value: &'a T,
        }
        let path = self.path(".json");
        self.files.add_json(
            path,
            &WithProvenance {
                provenance: self.provenance,
                value,
            },
        )
    }
}

/// Where a study's files go, and on how many threads it runs.
pub struct Output<'a> {
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

/// Conducts `study` into `target` under the file stem `stem`: checks its options, makes its
/// runs on `target`'s threads with a progress bar, records its failure if it has one, and adds
/// its files. Returns its result.
pub fn conduct<S: Study>(
    study: &S,
    target: &mut Output,
    stem: &str,
) -> Result<S::Result, AppError> {
    study.check()?;
    let bar = Progress::runs(study.runs(), study.name());
    let (result, threads) = with_threads(target.threads, || {
        (study.run(&|| bar.inc()), rayon::current_num_threads())
    })?;
    let result = result?;
    bar.finish();
    if let Some(failure) = study.failure(&result) {
        target.failure.get_or_insert(failure);
    }
    study.write(
        &result,
        &mut StudyFiles {
            files: target.files,
            dir: target.dir,
            stem,
            provenance: &Provenance::now(threads),
        },
    )?;
    Ok(result)
}

/// What a study's JSON says it studied, beside the study's own fields: the case as its plots
/// name it, its treatment of v = 0 and its end time.
#[derive(Serialize)]
pub struct StudyFile<'a, T: Serialize> {
    case: CaseRecord,
    #[serde(flatten)]
    study: &'a T,
}

/// The case of a study, as its JSON records it.
#[derive(Serialize)]
pub struct CaseRecord {
    description: String,
    switching: TreatmentRecord,
    t_end: f64,
}

/// The studied treatment of v = 0 as a study's JSON writes it: `"event"`, `"regularized"`,
/// `"naive"`, or `{"timestepping": {"theta": θ}}`.
#[derive(Serialize)]
#[serde(rename_all = "lowercase")]
enum TreatmentRecord {
    Event,
    Regularized,
    Naive,
    TimeStepping { theta: f64 },
}

impl CaseRecord {
    /// The record of `case` studied with `methods`.
    pub fn of(case: &dyn StudyCase, methods: &[Method]) -> CaseRecord {
        let switching = match Method::first_studied(methods).map(|m| m.scheme) {
            Some(Scheme::TimeStepping { theta }) => TreatmentRecord::TimeStepping { theta },
            Some(Scheme::EventDriven {
                switching: Switching::Regularized { .. },
                ..
            }) => TreatmentRecord::Regularized,
            Some(Scheme::EventDriven {
                switching: Switching::Naive,
                ..
            }) => TreatmentRecord::Naive,
            _ => TreatmentRecord::Event,
        };
        CaseRecord {
            description: studies::describe(case, methods),
            switching,
            t_end: case.t_end(),
        }
    }
}

/// `study` of `case` with `methods`, for its JSON.
pub fn study_file<'a, T: Serialize>(
    case: &dyn StudyCase,
    methods: &[Method],
    study: &'a T,
) -> StudyFile<'a, T> {
    StudyFile {
        case: CaseRecord::of(case, methods),
        study,
    }
}

/// `--solvers` with each solver once (a study names its runs by solver).
pub fn distinct(solvers: &[Solver]) -> Result<(), AppError> {
    match crate::ranges::first_repeat(solvers) {
        Some((_, k)) => Err(AppError::Usage(format!(
            "option `{}` names `{}` twice: allowed each solver once",
            crate::error::field("solvers"),
            solvers[k].name()
        ))),
        None => Ok(()),
    }
}

/// The options of a study of `methods` at the step sizes `steps` and the tolerances `tols`:
/// each solver once, every step size and tolerance in its range (`--dt-list`, `--tol-list`).
pub fn check_lists(methods: &[Method], steps: &[f64], tols: &[f64]) -> Result<(), AppError> {
    distinct(&Method::own_solvers(methods))?;
    crate::ranges::DT.list("dt_list", steps)?;
    crate::ranges::RTOL.list("tol_list", tols)?;
    Ok(())
}

/// Refuses a list of target errors (relative to the solution's scale) with a value outside
/// (0, 1): a relative error of 1 or more is no correct digit ([`positive_list`] first).
pub fn target_list(name: &'static str, values: &[f64]) -> Result<(), AppError> {
    positive_list(name, values)?;
    match values.iter().find(|v| **v >= 1.0) {
        Some(v) => Err(AppError::Invalid(crate::error::Invalid {
            field: name,
            value: friction_models::params::show(*v),
            allowed: "values (0, 1): a relative error of 1 or more has no correct digit".into(),
            list: true,
        })),
        None => Ok(()),
    }
}

/// A list option of positive finite numbers, not empty.
pub fn positive_list(name: &'static str, values: &[f64]) -> Result<(), AppError> {
    let invalid = |value: String, allowed: &str| {
        Err(AppError::Invalid(crate::error::Invalid {
            field: name,
            value,
            allowed: allowed.into(),
            list: true,
        }))
    };
    match values.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
        Some(v) => invalid(v.to_string(), "values (0, inf)"),
        None if values.is_empty() => invalid("no value".into(), "1 value or more"),
        None => Ok(()),
    }
}
