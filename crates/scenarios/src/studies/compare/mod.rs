//! The comparison of formulations: one nonsmooth problem integrated every way a user would
//! consider at v = 0 — event-driven explicit and implicit solvers with events located,
//! the same solvers on the regularised law over a list of widths ε, naive stepping through
//! sign(0) = 0, and Moreau–Jean time-stepping — every run scored against the **true
//! nonsmooth solution**, and each scheme's cost at a list of target errors.
//!
//! The true solution is the event-driven reference ([`crate::batch::reference`]: a tight
//! explicit 5(4) pair cross-checked by another, or a tight BDF run where the case is stiff),
//! cross-checked besides by a method of another family, Radau IIA with events at
//! [`CHECK_TOLERANCE`]; the two differences are the reference's stated accuracy.
//!
//! A regularised run's error is decomposed: its **model error** — the regularised ODE solved
//! tightly ([`crate::studies::REFERENCE_TOLERANCE`] with BDF), against the true solution —
//! and its **discretisation error**, against that tight solution. The model error as a
//! function of ε is fitted as `e(ε) ≈ C·ε^p` ([`regularisation`]).
//!
//! The runs go in rounds, loose to tight: round k runs the k-th resolution of every track (a
//! scheme at one ε) still going, so that a track stops as soon as it has met the tightest
//! target, failed, or reached its regularisation floor, and is extended past its list while
//! its error still falls ([`next_resolution`]). Each round is
//! one list on the pool, so the results do not depend on the thread count.

mod cost;
pub mod regularisation;

pub use cost::{at_target, crossovers, Crossover, Kind, SchemeCost, TargetCosts, TrackRuns};
pub use regularisation::{EpsilonFit, ModelError, NeededWidth, Regularisation};

use super::extend::next_resolution;
use super::{batch, Errors, Measures, Method, Reference, StudyCase, StudyRun};
use crate::error::ScenarioError;
use crate::errors::Scales;
use crate::study_run::{REFERENCE_MARGIN, REFERENCE_TOLERANCE};
use friction_models::params::show;
use friction_systems::{Scheme, Switching};
use integrators::{Solver, StepControl};
use serde::Serialize;

/// The method of another family that cross-checks the true solution: Radau IIA (order 5,
/// implicit collocation) with events located, against the explicit 5(4) pairs of the
/// reference.
pub const CHECK_SOLVER: Solver = Solver::RADAU5;
/// The tolerance of that cross-check, rtol = atol.
pub const CHECK_TOLERANCE: f64 = 1e-11;
/// A regularised run within this factor of its model error has reached its floor.
pub const AT_FLOOR: f64 = 2.0;
/// The tolerance of the tight solution of a regularised ODE: the reference's.
pub const TIGHT_TOLERANCE: f64 = REFERENCE_TOLERANCE;
/// The solver of the tight solution of a regularised ODE (stiff for a small ε): BDF, as a
/// stiff case's reference ([`crate::batch`]).
pub const TIGHT_SOLVER: Solver = Solver::BDF;

/// The schemes a comparison runs.
#[derive(Clone, Debug, PartialEq)]
pub struct Schemes {
    /// Solvers run event-driven with events located at v = 0.
    pub event: Vec<Solver>,
    /// Solvers run on the regularised law, at every width of `epsilons`.
    pub regularised: Vec<Solver>,
    /// The widths ε, relative to the true solution's velocity scale (its largest |v|).
    pub epsilons: Vec<f64>,
    /// Solvers run through sign(0) = 0, without events.
    pub naive: Vec<Solver>,
    /// Moreau–Jean's θ, where time-stepping is compared.
    pub theta: Option<f64>,
}

/// The resolutions every scheme starts from, loose to tight.
#[derive(Clone, Debug, PartialEq)]
pub struct Resolutions {
    /// Tolerances of the adaptive solvers (rtol = atol).
    pub tolerances: Vec<f64>,
    /// Step sizes of the fixed-step solvers, s.
    pub steps: Vec<f64>,
    /// Step sizes of Moreau–Jean's scheme, s.
    pub timestepping_steps: Vec<f64>,
}

/// What a comparison runs and what it asks of them.
#[derive(Clone, Debug, PartialEq)]
pub struct CompareSpec {
    /// The schemes.
    pub schemes: Schemes,
    /// Their resolutions.
    pub resolutions: Resolutions,
    /// The target errors, loose to tight ([`Errors::grid_relative`]).
    pub targets: Vec<f64>,
    /// Timings of each run beyond the first (the wall time is their median).
    pub repeats: usize,
}

/// The second opinion on the true solution: a method of another family.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CrossCheck {
    /// The scheme (`radau5 (event)`).
    pub scheme: String,
    /// Its tolerance.
    pub tolerance: f64,
    /// Its grid error against the true solution; `None` where it failed.
    pub difference: Option<f64>,
    /// Why it failed.
    pub failure: Option<String>,
}

/// One run of the comparison.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ComparedRun {
    /// The scheme.
    pub scheme: String,
    /// Its regularisation width, m/s (regularised schemes).
    pub epsilon: Option<f64>,
    /// The run, its errors against the true solution.
    #[serde(flatten)]
    pub run: StudyRun,
    /// A regularised run's grid error against its own ODE's tight solution (its
    /// discretisation error); `None` for the other schemes.
    pub discretisation_error: Option<f64>,
}

/// Why a track stopped.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TrackEnd {
    /// The scheme.
    pub scheme: String,
    /// Its regularisation width, m/s.
    pub epsilon: Option<f64>,
    /// Why it stopped, in words; `None` where it met the tightest target.
    pub stopped: Option<String>,
}

/// A comparison of formulations (see the module).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Comparison {
    /// The true solution's source.
    pub reference: Reference,
    /// Its cross-check by another family.
    pub cross_check: CrossCheck,
    /// The error below which the reference cannot resolve a run: the larger of
    /// [`REFERENCE_MARGIN`] times its estimated error and its difference from the
    /// cross-check (infinite where the cross-check failed). A target below it is not claimed.
    pub resolvable: f64,
    /// The true solution's velocity scale (its largest |v|), m/s: what ε is relative to.
    pub velocity_scale: f64,
    /// Every run, track by track (a run's `solver` names its track: the scheme, with ε for a
    /// regularised one).
    pub runs: Vec<ComparedRun>,
    /// The regularised schemes' model error against ε; `None` where none was compared.
    pub regularisation: Option<Regularisation>,
    /// Every scheme's cost at each target, loose to tight.
    pub costs: Vec<TargetCosts>,
    /// Where the cheapest scheme changes.
    pub crossovers: Vec<Crossover>,
    /// Why each track stopped.
    pub tracks: Vec<TrackEnd>,
}

/// One scheme at one ε, and its runs so far.
struct Track {
    method: Method,
    scheme: String,
    epsilon: Option<f64>,
    planned: Vec<StepControl>,
    runs: Vec<ComparedRun>,
    /// The tight solution of its regularised ODE, and its model error.
    tight: Option<(Measures, f64)>,
    stopped: Option<Option<String>>,
}

/// The scheme's name in tables: its method and treatment (`dopri5 (event)`).
pub fn scheme_name(scheme: Scheme) -> String {
    Method::peer(scheme).label()
}

impl Track {
    fn new(scheme: Scheme, planned: Vec<StepControl>) -> Track {
        Track {
            method: Method::peer(scheme),
            scheme: scheme_name(scheme),
            epsilon: match scheme.parameter() {
                Some(("epsilon", e)) => Some(e),
                _ => None,
            },
            planned,
            runs: Vec::new(),
            tight: None,
            stopped: None,
        }
    }

    /// The name of its runs: the scheme's, with ε for a regularised one
    /// (`bdf (regularized, ε = 1.86e-5)`).
    fn label(&self) -> String {
        match self.epsilon {
            Some(e) => format!("{}, ε = {e:.2e})", self.scheme.trim_end_matches(')')),
            None => self.scheme.clone(),
        }
    }

    /// The next resolution after its last run ([`next_resolution`]); `Err` with why the
    /// track ends.
    fn next(&self) -> Result<StepControl, String> {
        let runs: Vec<&StudyRun> = self.runs.iter().map(|r| &r.run).collect();
        next_resolution(&runs, &self.planned)
    }

    /// Records `run` and decides whether the track goes on.
    fn record(&mut self, run: ComparedRun, tightest: f64) {
        let r = &run.run;
        let ok = r.verdict.is_ok();
        let error = r.errors.grid_relative;
        self.stopped = match (&r.failure, r.diverged) {
            (Some(e), false) => Some(Some(format!(
                "its run at {} failed: {e}",
                show(r.resolution)
            ))),
            _ if ok && error <= tightest => Some(None),
            _ => match self.tight {
                Some((_, floor)) if floor > tightest && error <= AT_FLOOR * floor => {
                    Some(Some(format!(
                        "it reached the regularisation floor: model error {} at ε = {}",
                        show(floor),
                        show(self.epsilon.unwrap_or(f64::NAN))
                    )))
                }
                _ => None,
            },
        };
        self.runs.push(run);
    }
}

/// The planned resolutions of `scheme`.
fn planned(scheme: Scheme, r: &Resolutions) -> Vec<StepControl> {
    let fixed = |steps: &[f64]| steps.iter().map(|&h| StepControl::Fixed { h }).collect();
    match scheme.solver() {
        None => fixed(&r.timestepping_steps),
        Some(s) if s.is_fixed_step() => fixed(&r.steps),
        Some(_) => (r.tolerances.iter())
            .map(|&tol| StepControl::Adaptive {
                rtol: tol,
                atol: tol,
                h0: None,
            })
            .collect(),
    }
}

/// Runs the comparison `spec` on `case` (see the module); `progress` is told of every run.
pub fn compare(
    case: &dyn StudyCase,
    spec: &CompareSpec,
    progress: &(dyn Fn() + Sync),
) -> Result<Comparison, ScenarioError> {
    let s = &spec.schemes;
    let tightest = spec.targets.iter().copied().fold(f64::INFINITY, f64::min);
    // The true solution: the event-driven reference of a study of an implicit solver (the
    // explicit pairs are then free to be the reference).
    let (reference, truth) = batch::reference(case, &[Method::events(CHECK_SOLVER)])?;
    let velocity_scale = Scales::of(&truth).v;
    // A solution at rest throughout has no scale to be relative to, and no jump is crossed.
    if velocity_scale.is_nan() || velocity_scale <= 0.0 {
        return Err(ScenarioError::Invalid(format!(
            "{} does not move on [0, {}] s (its largest |v| is {}): there is no motion to \
             compare the schemes on; integrate longer, or start it moving",
            case.describe(),
            show(case.t_end()),
            show(velocity_scale)
        )));
    }
    let epsilons: Vec<f64> = s.epsilons.iter().map(|e| e * velocity_scale).collect();

    // The cross-check and the tight regularised solutions, one list.
    let check = Scheme::events(CHECK_SOLVER);
    let tight_step = |tol: f64| StepControl::Adaptive {
        rtol: tol,
        atol: tol,
        h0: None,
    };
    let mut first: Vec<[(Method, StepControl); 1]> =
        vec![[(Method::peer(check), tight_step(CHECK_TOLERANCE))]];
    if !s.regularised.is_empty() {
        for &epsilon in &epsilons {
            let scheme = Scheme::EventDriven {
                solver: TIGHT_SOLVER,
                switching: Switching::Regularized { epsilon },
            };
            first.push([(Method::peer(scheme), tight_step(TIGHT_TOLERANCE))]);
        }
    }
    let posed: Vec<batch::Posed> = (first.iter())
        .map(|jobs| batch::Posed {
            case,
            reference_for: None,
            jobs,
        })
        .collect();
    let mut tight = batch::run_cases(&posed, 0, &|| {})?
        .into_iter()
        .map(|c| c.runs.into_iter().next().expect("one job a case"));
    let check_run = tight.next().expect("the cross-check runs first");
    let cross_check = CrossCheck {
        scheme: scheme_name(check),
        tolerance: CHECK_TOLERANCE,
        difference: check_run
            .failure
            .is_none()
            .then(|| Errors::between(&check_run.measures, &truth).grid_relative),
        failure: check_run.failure.map(|e| e.to_string()),
    };
    let model_errors: Vec<ModelError> = (epsilons.iter().zip(&s.epsilons))
        .zip(tight.by_ref())
        .map(|((&epsilon, &relative), run)| ModelError {
            epsilon,
            relative,
            error: match run.failure {
                None => Errors::between(&run.measures, &truth).grid_relative,
                Some(_) => f64::NAN,
            },
            failure: run.failure.as_ref().map(|e| e.to_string()),
            measures: run.measures,
        })
        .collect();

    // The tracks.
    let mut tracks = Vec::new();
    let events = (s.event.iter()).map(|&solver| Scheme::events(solver));
    let naive = (s.naive.iter()).map(|&solver| Scheme::EventDriven {
        solver,
        switching: Switching::Naive,
    });
    let stepping = (s.theta.iter()).map(|&theta| Scheme::TimeStepping { theta });
    for scheme in events.chain(naive).chain(stepping) {
        tracks.push(Track::new(scheme, planned(scheme, &spec.resolutions)));
    }
    for &solver in &s.regularised {
        for m in &model_errors {
            let scheme = Scheme::EventDriven {
                solver,
                switching: Switching::Regularized { epsilon: m.epsilon },
            };
            let mut t = Track::new(scheme, planned(scheme, &spec.resolutions));
            t.tight = m.failure.is_none().then(|| (m.measures.clone(), m.error));
            tracks.push(t);
        }
    }

    // The rounds.
    loop {
        let mut round: Vec<(usize, [(Method, StepControl); 1])> = Vec::new();
        for (i, t) in tracks.iter_mut().enumerate() {
            if t.stopped.is_some() {
                continue;
            }
            match t.next() {
                Ok(step) => round.push((i, [(t.method, step)])),
                Err(why) => t.stopped = Some(Some(why)),
            }
        }
        if round.is_empty() {
            break;
        }
        let posed: Vec<batch::Posed> = (round.iter())
            .map(|(_, jobs)| batch::Posed {
                case,
                reference_for: None,
                jobs,
            })
            .collect();
        let done = batch::run_cases(&posed, spec.repeats, progress)?;
        for ((i, _), c) in round.iter().zip(done) {
            let t = &mut tracks[*i];
            let mut run = c.runs.into_iter().next().expect("one job a case");
            batch::judge(&mut run, &truth);
            run.solver = t.label();
            let discretisation_error = (t.tight.as_ref())
                .filter(|_| run.failure.is_none())
                .map(|(m, _)| Errors::between(&run.measures, m).grid_relative);
            let compared = ComparedRun {
                scheme: t.scheme.clone(),
                epsilon: t.epsilon,
                run,
                discretisation_error,
            };
            t.record(compared, tightest);
        }
    }

    // The cross-check's difference bounds the reference's error where the reference is the
    // more accurate of the two; its own estimate needs the margin of every study.
    let resolvable = (REFERENCE_MARGIN * reference.estimated_error())
        .max(cross_check.difference.unwrap_or(f64::INFINITY));
    let mut names: Vec<String> = Vec::new();
    for t in &tracks {
        if !names.contains(&t.scheme) {
            names.push(t.scheme.clone());
        }
    }
    let track_runs: Vec<TrackRuns> = (tracks.iter())
        .map(|t| TrackRuns {
            scheme: &t.scheme,
            kind: match t.method.scheme.solver() {
                Some(s) if s == Solver::AUTO => Kind::Switching,
                _ if t.method.is_implicit() => Kind::Implicit,
                _ => Kind::Explicit,
            },
            epsilon: t.epsilon,
            runs: t.runs.iter().map(|r| &r.run).collect(),
            stopped: t.stopped.clone().flatten(),
        })
        .collect();
    let mut targets = spec.targets.clone();
    targets.sort_by(|a, b| b.total_cmp(a));
    let costs: Vec<TargetCosts> = (targets.iter())
        .map(|&target| TargetCosts {
            resolved: target >= resolvable,
            ..at_target(&names, &track_runs, target)
        })
        .collect();
    let crossovers = crossovers(&costs);
    let sticks = !truth.stick_durations.is_empty();
    let regularisation = (!s.regularised.is_empty())
        .then(|| Regularisation::of(model_errors, &spec.targets, sticks, resolvable));
    Ok(Comparison {
        reference,
        cross_check,
        resolvable,
        velocity_scale,
        costs,
        crossovers,
        regularisation,
        tracks: (tracks.iter())
            .map(|t| TrackEnd {
                scheme: t.scheme.clone(),
                epsilon: t.epsilon,
                stopped: t.stopped.clone().flatten(),
            })
            .collect(),
        runs: tracks.into_iter().flat_map(|t| t.runs).collect(),
    })
}
