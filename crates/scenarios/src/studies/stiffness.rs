//! The stiffness study: the cheapest run of each method that meets a target error, over the
//! values of a stiffness parameter, and where the implicit methods overtake the explicit ones.

use super::{batch, Method, StepKind, StudyCase};
use crate::run::ScenarioError;
use integrators::Stats;
use serde::Serialize;

/// One solver at one stiffness value: its cheapest run that met the target, if one did.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cost {
    /// The method's label.
    pub solver: String,
    /// Whether it is implicit.
    pub implicit: bool,
    /// Its cheapest run that met the target; `None` (JSON `null`, empty cells) where no run
    /// did: a cost that was not paid is not a cost of 0.
    pub reached: Option<Reached>,
}

/// The cheapest run of a solver that met a stiffness study's target.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Reached {
    /// Its resolution: a step size or a tolerance.
    pub resolution: f64,
    /// Which that resolution is: `fixed` or `adaptive`.
    pub step: StepKind,
    /// Its error (maximum over the time grid).
    pub error: f64,
    /// Its statistics.
    pub stats: Stats,
    /// Its work ([`Stats::work`]).
    pub work: usize,
}

/// The costs at one value of the stiffness parameter.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StiffnessPoint {
    /// The parameter's value.
    pub value: f64,
    /// One cost per solver.
    pub costs: Vec<Cost>,
    /// Whether the cheapest implicit solver beats the cheapest explicit one in work
    /// ([`Stats::work`]).
    pub implicit_wins: bool,
}

/// A stiffness sweep.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stiffness {
    /// The swept parameter.
    pub parameter: String,
    /// The target error (grid maximum).
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
}

/// The first value (in sweep order) from which the implicit solvers win, where the explicit
/// ones won before it and the implicit ones win at every value from it on (values at which no
/// method met the target are passed over); `None` where one
/// kind wins at every value or the winner changes more than once (as [`Stiffness::verdict`]
/// says).
pub fn crossover(points: &[StiffnessPoint]) -> Option<f64> {
    let decided: Vec<&StiffnessPoint> = points.iter().filter(|p| p.decided()).collect();
    let k = decided.iter().position(|p| p.implicit_wins)?;
    (k > 0 && decided[k..].iter().all(|p| p.implicit_wins)).then(|| decided[k].value)
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
        let verdict = self.winners(&decided);
        if undecided.is_empty() {
            verdict
        } else {
            format!(
                "{verdict}; no method met the target at {} = {}",
                self.parameter,
                undecided.join(", ")
            )
        }
    }

    /// Which kind wins over the `decided` values: everywhere, from a crossover on, or by turns.
    fn winners(&self, decided: &[&StiffnessPoint]) -> String {
        let wins: Vec<bool> = decided.iter().map(|p| p.implicit_wins).collect();
        let values = |implicit: bool| {
            decided
                .iter()
                .filter(|p| p.implicit_wins == implicit)
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
    /// The error to reach (maximum over the time grid).
    pub target: f64,
}

/// Sweeps the parameter over its values (every value's runs in one list) and finds, for each solver, the cheapest
/// resolution in `step_sizes` (or `tolerances`) whose grid error meets the target.
pub fn stiffness(
    case: &dyn StudyCase,
    sweep: Sweep,
    methods: &[Method],
    step_sizes: &[f64],
    tolerances: &[f64],
    progress: &(dyn Fn() + Sync),
) -> Result<Stiffness, ScenarioError> {
    let own = Method::own_solvers(methods);
    let Sweep {
        parameter,
        values,
        target,
    } = sweep;
    let cases = values
        .iter()
        .map(|&value| case.with_parameter(parameter, value))
        .collect::<Result<Vec<_>, _>>()?;
    let cases: Vec<&dyn StudyCase> = cases.iter().map(|c| c.as_ref()).collect();
    let jobs = Method::jobs(methods, step_sizes, tolerances, false);
    // Every value's runs and references in one list: no value waits for the last run of
    // the one before.
    let done = batch::run_cases(&cases, Some(&own), &jobs, 0, progress)?;
    let mut points = Vec::new();
    for (&value, batch::CaseRuns { runs, .. }) in values.iter().zip(done) {
        let costs: Vec<Cost> = methods
            .iter()
            .map(|m| {
                let label = m.label();
                let met = runs
                    .iter()
                    .filter(|r| {
                        r.solver == label && r.verdict.is_ok() && r.errors.grid_max <= target
                    })
                    .min_by_key(|r| r.work);
                Cost {
                    solver: label,
                    implicit: m.is_implicit(),
                    reached: met.map(|r| Reached {
                        resolution: r.resolution,
                        step: r.step,
                        error: r.errors.grid_max,
                        stats: r.stats,
                        work: r.work,
                    }),
                }
            })
            .collect();
        let best = |implicit: bool| {
            costs
                .iter()
                .filter(|c| c.implicit == implicit)
                .filter_map(|c| c.reached.as_ref().map(|r| r.work))
                .min()
        };
        let implicit_wins = match (best(true), best(false)) {
            (Some(i), Some(e)) => i < e,
            (Some(_), None) => true,
            _ => false,
        };
        points.push(StiffnessPoint {
            value,
            costs,
            implicit_wins,
        });
    }
    Ok(Stiffness {
        parameter: parameter.to_string(),
        target,
        crossover: crossover(&points),
        points,
    })
}
