//! The stiffness study: each method's cost to reach a target error, interpolated between the
//! resolutions that bracket it, over the values of a stiffness parameter, and where the
//! implicit methods overtake the explicit ones (a tie where the brackets cannot tell).

use super::extend::next_resolution;
use super::{batch, Method, Reference, StepKind, StudyCase, StudyRun};
use crate::error::ScenarioError;
use friction_models::{FrictionParams, Parameters};
use integrators::Stats;
use integrators::StepControl;
use serde::Serialize;

/// One solver at one stiffness value: how it met the target, if it did.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cost {
    /// The method's label.
    pub solver: String,
    /// Whether it is implicit.
    pub implicit: bool,
    /// How it met the target ([`reached`]); `None` (JSON `null`, empty cells) where no run
    /// did: a cost that was not paid is not a cost of 0.
    pub reached: Option<Reached>,
}

/// How a solver met a stiffness study's target: its loosest run that met it, and its cost at
/// the target itself, interpolated between the runs that bracket it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Reached {
    /// The loosest resolution that met the target: a step size or a tolerance.
    pub resolution: f64,
    /// Which that resolution is: `fixed` or `adaptive`.
    pub step: StepKind,
    /// That run's error ([`crate::errors::Errors::grid_relative`]).
    pub error: f64,
    /// That run's statistics.
    pub stats: Stats,
    /// That run's work ([`Stats::work`]).
    pub work: usize,
    /// The work at the target error: log(work) interpolated linearly in log(error) between
    /// the last run that missed the target and the first that met it (that run's work where
    /// none missed it before).
    pub work_estimate: f64,
    /// The work the bracket leaves possible: from the run that missed to the run that met;
    /// the lower bound is `None` where the loosest run already met the target (the cost is
    /// at most its work).
    pub work_bracket: [Option<f64>; 2],
}

/// Which kind of method reaches the target more cheaply at one value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Winner {
    /// The cheapest implicit method, beyond the bracket of the cheapest explicit one.
    Implicit,
    /// The cheapest explicit method, beyond the bracket of the cheapest implicit one.
    Explicit,
    /// The two cheapest are within each other's brackets: the grid of resolutions cannot
    /// tell them apart.
    Tie,
}

impl Winner {
    /// Its name, as the files write it.
    pub fn name(self) -> &'static str {
        match self {
            Winner::Implicit => "implicit",
            Winner::Explicit => "explicit",
            Winner::Tie => "tie",
        }
    }
}

/// The costs at one value of the stiffness parameter.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StiffnessPoint {
    /// The parameter's value.
    pub value: f64,
    /// One cost per solver.
    pub costs: Vec<Cost>,
    /// Which kind wins ([`winner`]); `None` where no method met the target.
    pub winner: Option<Winner>,
    /// The reference at this value, with its estimated error.
    pub reference: Reference,
    /// Where the reference limits the finest runs at this value, the sentence that says so
    /// ([`Reference::limits`]).
    pub reference_limit: Option<String>,
}

/// The kind that reaches the target more cheaply among `costs`: the cheapest estimate of each
/// kind compared, a tie where their brackets overlap (an open lower bound reaching down to 0);
/// the one kind that met it where the other did not; `None` where neither did.
pub fn winner(costs: &[Cost]) -> Option<Winner> {
    let best = |implicit: bool| {
        (costs.iter())
            .filter(|c| c.implicit == implicit)
            .filter_map(|c| c.reached.as_ref())
            .min_by(|a, b| a.work_estimate.total_cmp(&b.work_estimate))
    };
    match (best(true), best(false)) {
        (Some(i), Some(e)) => {
            let range = |r: &Reached| {
                let [lo, hi] = r.work_bracket;
                (lo.unwrap_or(0.0), hi.unwrap_or(r.work_estimate))
            };
            let ((i_lo, i_hi), (e_lo, e_hi)) = (range(i), range(e));
            Some(if i_lo.max(e_lo) <= i_hi.min(e_hi) {
                Winner::Tie
            } else if i.work_estimate < e.work_estimate {
                Winner::Implicit
            } else {
                Winner::Explicit
            })
        }
        (Some(_), None) => Some(Winner::Implicit),
        (None, Some(_)) => Some(Winner::Explicit),
        (None, None) => None,
    }
}

/// How one method's `runs` (loose to tight) meet `target`: its first `ok` run whose grid
/// error meets it, and the cost at the target interpolated against the run before it ([`Reached`]).
/// The run before is the last that ran to its end (a failed run says nothing of its error); if
/// it was judged inaccurate, its work still bounds the cost from below, but its error is no
/// point to interpolate from: the estimate is then the work of the run that met the target.
pub fn reached(runs: &[&StudyRun], target: f64) -> Option<Reached> {
    let ended: Vec<&&StudyRun> = (runs.iter())
        .filter(|r| r.failure.is_none() && r.errors.grid_relative.is_finite())
        .collect();
    let j = (ended.iter()).position(|r| r.verdict.is_ok() && r.errors.grid_relative <= target)?;
    let met = ended[j];
    let (work_estimate, work_bracket) = match j.checked_sub(1).map(|i| ended[i]) {
        Some(missed) => {
            let (e0, w0) = (missed.errors.grid_relative.ln(), (missed.work as f64).ln());
            let (e1, w1) = (met.errors.grid_relative.ln(), (met.work as f64).ln());
            let estimate = if missed.verdict.is_ok() && e1 < e0 {
                (w0 + (target.ln() - e0) * (w1 - w0) / (e1 - e0)).exp()
            } else {
                met.work as f64
            };
            let (lo, hi) = (
                (missed.work.min(met.work)) as f64,
                (missed.work.max(met.work)) as f64,
            );
            (estimate.clamp(lo, hi), [Some(lo), Some(hi)])
        }
        None => (met.work as f64, [None, Some(met.work as f64)]),
    };
    Some(Reached {
        resolution: met.resolution,
        step: met.step,
        error: met.errors.grid_relative,
        stats: met.stats,
        work: met.work,
        work_estimate,
        work_bracket,
    })
}

/// The runs of the method labelled `label`, loose to tight: the largest step size or
/// tolerance first.
fn loose_to_tight<'a>(runs: &'a [StudyRun], label: &str) -> Vec<&'a StudyRun> {
    let mut mine: Vec<&StudyRun> = runs.iter().filter(|r| r.solver == label).collect();
    mine.sort_by(|a, b| b.resolution.total_cmp(&a.resolution));
    mine
}

/// A stiffness sweep.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stiffness {
    /// The swept parameter.
    pub parameter: String,
    /// The target error ([`crate::errors::Errors::grid_relative`]).
    pub target: f64,
    /// Every value.
    pub points: Vec<StiffnessPoint>,
    /// The crossover ([`crossover`]), as the verdict names it.
    pub crossover: Option<f64>,
}

impl StiffnessPoint {
    /// Whether some method met the target at this value (where none did, neither kind wins).
    pub fn decided(&self) -> bool {
        self.costs.iter().any(|c| c.reached.is_some())
    }

    /// Whether one kind wins outright (not a tie, not undecided).
    fn won(&self) -> bool {
        matches!(self.winner, Some(Winner::Implicit | Winner::Explicit))
    }

    /// Whether the implicit methods win outright.
    pub fn implicit_wins(&self) -> bool {
        self.winner == Some(Winner::Implicit)
    }
}

/// The first value (in sweep order) from which the implicit solvers win, where the explicit
/// ones won before it and the implicit ones win at every value from it on (values at which no
/// method met the target are passed over); `None` where one
/// kind wins at every value or the winner changes more than once (as [`Stiffness::verdict`]
/// says).
pub fn crossover(points: &[StiffnessPoint]) -> Option<f64> {
    let decided: Vec<&StiffnessPoint> = points.iter().filter(|p| p.won()).collect();
    let k = decided.iter().position(|p| p.implicit_wins())?;
    (k > 0 && decided[k..].iter().all(|p| p.implicit_wins())).then(|| decided[k].value)
}

impl Stiffness {
    /// The study's conclusion in words: a crossover only where the winner changes inside the
    /// sweep; "no crossover in this range" where one kind wins at every value; no winner where
    /// only one kind of method was studied, or at a value where no method met the target
    /// (named after the verdict).
    pub fn verdict(&self) -> String {
        let studied = |implicit: bool| {
            let mut names: Vec<&str> = Vec::new();
            for c in self.points.iter().flat_map(|p| &p.costs) {
                if c.implicit == implicit && !names.contains(&c.solver.as_str()) {
                    names.push(&c.solver);
                }
            }
            names
        };
        let (implicit, explicit) = (studied(true), studied(false));
        if !self.points.is_empty() && (implicit.is_empty() || explicit.is_empty()) {
            let (kind, names) = if implicit.is_empty() {
                ("explicit", explicit)
            } else {
                ("implicit", implicit)
            };
            return format!(
                "only {kind} methods were studied ({}): nothing to compare them with; their cost \
                 against {} is in stiffness.csv",
                names.join(", "),
                self.parameter
            );
        }
        let undecided: Vec<String> = self
            .points
            .iter()
            .filter(|p| !p.decided())
            .map(|p| p.value.to_string())
            .collect();
        let decided: Vec<&StiffnessPoint> = self.points.iter().filter(|p| p.decided()).collect();
        if !self.points.is_empty() && decided.is_empty() {
            return format!(
                "no method met the target at any {} of the sweep",
                self.parameter
            );
        }
        let won: Vec<&StiffnessPoint> = decided.iter().copied().filter(|p| p.won()).collect();
        let ties: Vec<String> = (decided.iter())
            .filter(|p| p.winner == Some(Winner::Tie))
            .map(|p| p.value.to_string())
            .collect();
        let mut verdict = if won.is_empty() {
            format!(
                "a tie at every {} where a method met the target: the cheapest implicit and \
                 explicit methods are within each other's brackets",
                self.parameter
            )
        } else {
            self.winners(&won)
        };
        if !won.is_empty() && !ties.is_empty() {
            verdict += &format!(
                "; a tie (within the brackets of the resolutions) at {} = {}",
                self.parameter,
                ties.join(", ")
            );
        }
        if !undecided.is_empty() {
            verdict += &format!(
                "; no method met the target at {} = {}",
                self.parameter,
                undecided.join(", ")
            );
        }
        verdict
    }

    /// Which kind wins over the `decided` values (each won outright): everywhere, from a
    /// crossover on, or by turns.
    fn winners(&self, decided: &[&StiffnessPoint]) -> String {
        let wins: Vec<bool> = decided.iter().map(|p| p.implicit_wins()).collect();
        let values = |implicit: bool| {
            decided
                .iter()
                .filter(|p| p.implicit_wins() == implicit)
                .map(|p| p.value.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        };
        match (wins.iter().all(|&w| w), wins.iter().any(|&w| w)) {
            _ if wins.is_empty() => "no values were swept".into(),
            (true, _) => format!(
                "the implicit solvers win at every {} of the sweep: no crossover in this range",
                self.parameter
            ),
            (false, false) => format!(
                "the explicit solvers win at every {} of the sweep: no crossover in this range",
                self.parameter
            ),
            _ => {
                let k = wins.iter().position(|&w| w).expect("some value is won");
                if wins[k..].iter().all(|&w| w) {
                    format!(
                        "the implicit solvers overtake the explicit ones from {} = {}",
                        self.parameter, decided[k].value
                    )
                } else {
                    format!(
                        "the winner changes more than once: implicit solvers win at {} = {}, \
                         explicit ones at {}",
                        self.parameter,
                        values(true),
                        values(false)
                    )
                }
            }
        }
    }
}

/// What a stiffness study sweeps, and the error each solver must reach.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sweep<'a> {
    /// The parameter (a friction or a scenario parameter).
    pub parameter: &'a str,
    /// Its values, in sweep order.
    pub values: &'a [f64],
    /// The error to reach ([`crate::errors::Errors::grid_relative`]).
    pub target: f64,
}

/// Sweeps the parameter over its values (every value's runs in one list) and finds, for each
/// solver, its cost to reach the target ([`reached`]) among `step_sizes` (or `tolerances`),
/// the list extended past its end while the method's error still falls short of the target
/// ([`next_resolution`]), and at each value which kind wins ([`winner`]).
pub fn stiffness(
    case: &dyn StudyCase,
    sweep: Sweep,
    methods: &[Method],
    step_sizes: &[f64],
    tolerances: &[f64],
    progress: &(dyn Fn() + Sync),
) -> Result<Stiffness, ScenarioError> {
    let Sweep {
        parameter,
        values,
        target,
    } = sweep;
    // The regularisation width is the schemes' (each value changes the methods that read it);
    // any other parameter the case's.
    let scheme_parameter = parameter == "epsilon";
    if scheme_parameter && !methods.iter().any(Method::reads_epsilon) {
        return Err(ScenarioError::Invalid(format!(
            "parameter `epsilon` is read only under regularized switching (or by a \
             regularised peer); not {}: every value would give the same runs",
            Method::treatment_name(methods)
        )));
    }
    let mut cases = Vec::new();
    let mut jobs = Vec::new();
    for &value in values {
        if scheme_parameter {
            FrictionParams::paper().set(parameter, value)?;
            let at: Vec<Method> = methods.iter().map(|m| m.regularised_at(value)).collect();
            jobs.push((at.clone(), Method::jobs(&at, step_sizes, tolerances, false)));
            cases.push(None);
        } else {
            jobs.push((
                methods.to_vec(),
                Method::jobs(methods, step_sizes, tolerances, false),
            ));
            cases.push(Some(case.with_parameter(parameter, value)?));
        }
    }
    let posed: Vec<batch::Posed> = (cases.iter().zip(&jobs))
        .map(|(c, (methods, jobs))| batch::Posed {
            case: c.as_deref().unwrap_or(case),
            reference_for: Some(methods),
            jobs,
        })
        .collect();
    // Every value's runs and references in one list: no value waits for the last run of
    // the one before.
    let mut done = batch::run_cases(&posed, 0, progress)?;
    // A method that falls short of the target with its error still falling at the end of
    // its list is run on, a round at a time ([`next_resolution`]): a too-short list decides
    // no winner.
    loop {
        let mut extra: Vec<(usize, [(Method, StepControl); 1])> = Vec::new();
        for (i, c) in done.iter().enumerate() {
            for m in &jobs[i].0 {
                let mine = loose_to_tight(&c.runs, &m.label());
                if reached(&mine, target).is_some() {
                    continue;
                }
                let listed = m.steps(step_sizes, tolerances, false);
                if let Ok(step) = next_resolution(&mine, &listed) {
                    extra.push((i, [(*m, step)]));
                }
            }
        }
        if extra.is_empty() {
            break;
        }
        let posed: Vec<batch::Posed> = (extra.iter())
            .map(|(i, jobs)| batch::Posed {
                case: cases[*i].as_deref().unwrap_or(case),
                reference_for: None,
                jobs,
            })
            .collect();
        let more = batch::run_cases(&posed, 0, progress)?;
        for ((i, _), c) in extra.iter().zip(more) {
            let batch::CaseRuns { reference, runs } = &mut done[*i];
            let (_, measures) = reference.as_ref().expect("a stiffness study asks for them");
            for mut run in c.runs {
                batch::judge(&mut run, measures);
                runs.push(run);
            }
        }
    }
    let mut points = Vec::new();
    for (&value, batch::CaseRuns { runs, reference }) in values.iter().zip(done) {
        let (reference, _) = reference.expect("a stiffness study asks for its references");
        let costs: Vec<Cost> = methods
            .iter()
            .map(|m| {
                let label = m.label();
                let mine = loose_to_tight(&runs, &label);
                Cost {
                    solver: label,
                    implicit: m.is_implicit(),
                    reached: reached(&mine, target),
                }
            })
            .collect();
        points.push(StiffnessPoint {
            value,
            winner: winner(&costs),
            costs,
            reference_limit: reference.limits(&runs),
            reference,
        });
    }
    Ok(Stiffness {
        parameter: parameter.to_string(),
        target,
        crossover: crossover(&points),
        points,
    })
}
