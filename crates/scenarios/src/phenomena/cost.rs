//! The paper's first criterion for choosing a model: what it costs to simulate stick–slip
//! with it. On each of two stick–slip systems ([`SYSTEMS`]: the belt rig and two masses in a
//! row), every solver of [`SOLVERS`] runs at the tolerances [`TOLERANCES`], loose to tight,
//! against a reference ([`batch::reference`]); a solver's adequate run is its loosest whose
//! error on the time grid is at most [`TARGET_ERROR`] ([`reached`]), and the
//! model's cost on the system is the least work among them (right-hand-side evaluations,
//! Jacobians and factorisations counted as [`integrators::Stats::work`] says), with that
//! run's wall time over [`TIMING_REPEATS`] runs. Table 2 divides both by Coulomb's.

use super::{own_parameters, Protocol};
use crate::batch;
use crate::cases::{Case, StudyCase, SystemCase};
use crate::error::ScenarioError;
use crate::method::Method;
use crate::run::Law;
use crate::scenario::Scenario;
use crate::studies::reached;
use crate::study_run::{StudyRun, WallTimes};
use crate::ScenarioParams;
use friction_models::{FrictionParams, ModelId};
use friction_systems::{End, Scheme, System};
use integrators::{Solver, Stats, StepControl};
use serde::Serialize;

/// The largest error on the common time grid ([`crate::errors::Errors::grid_relative`],
/// relative to the solution's scale) a run must reach: figure accuracy, 0.1 %, a curve drawn
/// from the run indistinguishable from the reference's.
pub const TARGET_ERROR: f64 = 1e-3;
/// The tolerances (rtol = atol) each solver tries, loose to tight.
pub const TOLERANCES: [f64; 8] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
/// The solvers tried: an explicit Runge–Kutta pair, a multistep and an implicit Runge–Kutta
/// method, each the representative of its family.
pub const SOLVERS: [Solver; 3] = [Solver::DOPRI5, Solver::BDF, Solver::RADAU5];
/// How many times the adequate run is timed for its median and spread.
pub const TIMING_REPEATS: usize = 5;
/// How long each system runs, s (the stick–slip protocol's length).
pub const T_END: f64 = 40.0;

/// How a [`CostSystem`] is built for a law at its parameters, bounded by a protocol.
type Build = fn(&Law, &FrictionParams, &Protocol) -> Result<Box<dyn StudyCase>, ScenarioError>;

/// A stick–slip system the cost is measured on.
pub struct CostSystem {
    /// Its name in `table2.json`.
    pub name: &'static str,
    /// What it is, for the table.
    pub description: &'static str,
    case: Build,
}

impl CostSystem {
    /// The system with `law` at `p`, bounded as `protocol` says.
    pub fn case(
        &self,
        law: &Law,
        p: &FrictionParams,
        protocol: &Protocol,
    ) -> Result<Box<dyn StudyCase>, ScenarioError> {
        (self.case)(law, p, protocol)
    }
}

/// The two systems: the belt rig (m = 1 kg, k = 100 N/m, v_belt = 0.05 m/s) and two masses
/// in a row (1 kg pulled through 10 N/m by a driver at 0.1 m/s, 2 kg behind it through
/// 100 N/m, each on the floor with the law), both from rest for [`T_END`] seconds,
/// event-driven.
pub const SYSTEMS: [CostSystem; 2] = [
    CostSystem {
        name: "belt",
        description: "belt rig",
        case: belt,
    },
    CostSystem {
        name: "two_mass",
        description: "two masses",
        case: two_mass,
    },
];

fn belt(
    law: &Law,
    p: &FrictionParams,
    protocol: &Protocol,
) -> Result<Box<dyn StudyCase>, ScenarioError> {
    Ok(Box::new(Case {
        scenario: Scenario::BELT,
        law: law.clone(),
        friction: *p,
        params: ScenarioParams::default(),
        t_end: T_END,
        limits: protocol.limits,
    }))
}

fn two_mass(
    law: &Law,
    p: &FrictionParams,
    protocol: &Protocol,
) -> Result<Box<dyn StudyCase>, ScenarioError> {
    let model = law.build(p)?;
    let mut s = System::default();
    let driver = s.add_anchor("driver", 0.0, TWO_MASS_DRIVER);
    let near = s.add_body("near", 1.0, 0.0, 0.0);
    let far = s.add_body("far", 2.0, 0.0, 0.0);
    s.add_spring(End::Anchor(driver), End::Body(near), 10.0, 0.0);
    s.add_spring(End::Body(near), End::Body(far), 100.0, 0.0);
    s.add_contact(near, 0.0, model.clone());
    s.add_contact(far, 0.0, model);
    Ok(Box::new(SystemCase {
        bodies: vec![near, far],
        limits: protocol.limits,
        ..SystemCase::new(format!("two masses with {law}"), s, T_END)
    }))
}

/// The speed of the two-mass system's driver, m/s.
const TWO_MASS_DRIVER: f64 = 0.1;

/// The cheapest adequate run on one system.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cheapest {
    /// The solver.
    pub solver: String,
    /// Its tolerance (rtol = atol).
    pub tolerance: f64,
    /// Its error on the time grid.
    pub error: f64,
    /// Its work ([`Stats::work`]).
    pub work: usize,
    /// Its statistics.
    pub stats: Stats,
    /// Its wall time over [`TIMING_REPEATS`] runs, s (not deterministic: kept out of
    /// `table2.json`).
    #[serde(skip)]
    pub wall_time: WallTimes,
}

/// A law's cost on each of [`SYSTEMS`], in order: the cheapest adequate run, or why there is
/// none (no solver reached the target, or the reference failed).
pub type SimulationCost = Vec<Result<Cheapest, String>>;

/// The simulation cost of `law` at `p`, its runs bounded by `protocol`'s limits; `progress`
/// is told of every run.
pub fn simulation_cost(
    law: &Law,
    p: &FrictionParams,
    protocol: &Protocol,
    progress: &(dyn Fn() + Sync),
) -> Result<SimulationCost, ScenarioError> {
    let methods: Vec<Method> = SOLVERS
        .iter()
        .map(|&s| Method::of(Scheme::events(s)))
        .collect();
    SYSTEMS
        .iter()
        .map(|system| {
            let case = system.case(law, p, protocol)?;
            cheapest(case.as_ref(), &methods, progress)
        })
        .collect()
}

/// The cheapest adequate run of `methods` on `case`, timed: the reference once, then each
/// method (in parallel) at its tolerances loose to tight until a run meets the target (the
/// tighter ones are not run: the loosest that meets it is the adequate run).
fn cheapest(
    case: &dyn StudyCase,
    methods: &[Method],
    progress: &(dyn Fn() + Sync),
) -> Result<Result<Cheapest, String>, ScenarioError> {
    use rayon::prelude::*;
    let reference = match batch::reference(case, methods) {
        Ok((_, measures)) => measures,
        Err(e @ (ScenarioError::Solver { .. } | ScenarioError::RunFailed(_))) => {
            return Ok(Err(e.to_string()))
        }
        Err(e) => return Err(e),
    };
    let adequate = methods
        .par_iter()
        .map(|&method| {
            let mut runs: Vec<StudyRun> = Vec::new();
            for (k, &tolerance) in TOLERANCES.iter().enumerate() {
                let job = (method, tolerance_step(tolerance));
                let mut run = batch::run_jobs(case, &[job], 0, progress)?.remove(0);
                batch::judge(&mut run, &reference);
                runs.push(run);
                let all: Vec<&StudyRun> = runs.iter().collect();
                if let Some(r) = reached(&all, TARGET_ERROR) {
                    // The tighter tolerances are not run: count them done.
                    (k + 1..TOLERANCES.len()).for_each(|_| progress());
                    return Ok(Some((method, r)));
                }
            }
            Ok(None)
        })
        .collect::<Result<Vec<_>, ScenarioError>>()?;
    let best = (adequate.into_iter().flatten()).min_by_key(|(_, r)| r.work);
    let Some((method, r)) = best else {
        return Ok(Err(format!(
            "no solver of {} reached a grid error of {TARGET_ERROR:e} at rtol = atol down to \
             {:e}",
            SOLVERS.map(|s| s.name()).join(", "),
            TOLERANCES[TOLERANCES.len() - 1]
        )));
    };
    let job = (method, tolerance_step(r.resolution));
    let timed = batch::run_jobs(case, &[job], TIMING_REPEATS - 1, progress)?;
    Ok(Ok(Cheapest {
        solver: method.label(),
        tolerance: r.resolution,
        error: r.error,
        work: r.work,
        stats: r.stats,
        wall_time: timed[0].wall_time,
    }))
}

/// Adaptive steps at rtol = atol = `tolerance`.
fn tolerance_step(tolerance: f64) -> StepControl {
    StepControl::Adaptive {
        rtol: tolerance,
        atol: tolerance,
        h0: None,
    }
}

/// The runs one law's cost takes (progress counts them): every solver at every tolerance and
/// the adequate run's timing repeats, on each system.
pub const RUNS_PER_LAW: usize = SYSTEMS.len() * (SOLVERS.len() * TOLERANCES.len() + TIMING_REPEATS);

/// The simulation costs of a table's laws, and of Coulomb friction, which they are divided by.
#[derive(Clone, Debug, PartialEq)]
pub struct Costs {
    /// Each law's, in the table's order.
    pub laws: Vec<SimulationCost>,
    /// Coulomb friction's, at the parameters the laws are judged at (`paper` when each is at
    /// its own set).
    pub coulomb: SimulationCost,
}

impl Costs {
    /// The cost of `laws` (and of Coulomb friction), each at `parameters` or its own
    /// ([`own_parameters`]), computed in parallel on
    /// rayon's pool and collected in order.
    pub fn of(
        laws: &[Law],
        parameters: Option<&FrictionParams>,
        protocol: &Protocol,
        progress: &(dyn Fn() + Sync),
    ) -> Result<Costs, ScenarioError> {
        use rayon::prelude::*;
        let coulomb = Law::from(ModelId::Coulomb);
        let all: Vec<&Law> = laws.iter().chain([&coulomb]).collect();
        let mut costs = all
            .par_iter()
            .map(|law| {
                let p = parameters.copied().unwrap_or_else(|| own_parameters(law));
                simulation_cost(law, &p, protocol, progress)
            })
            .collect::<Result<Vec<_>, _>>()?;
        let coulomb = costs.pop().expect("Coulomb's is the last");
        Ok(Costs {
            laws: costs,
            coulomb,
        })
    }

    /// The work of law `i` on system `s` over Coulomb's, where both reached the target.
    pub fn relative_work(&self, i: usize, s: usize) -> Option<f64> {
        self.relative(i, s, |c| c.work as f64)
    }

    /// The median wall time of law `i` on system `s` over Coulomb's, where both reached the
    /// target.
    pub fn relative_wall_time(&self, i: usize, s: usize) -> Option<f64> {
        self.relative(i, s, |c| c.wall_time.median)
    }

    /// `measure` of law `i`'s cheapest run on system `s` over Coulomb's, where both reached
    /// the target.
    fn relative(&self, i: usize, s: usize, measure: fn(&Cheapest) -> f64) -> Option<f64> {
        let (a, b) = (
            self.laws[i][s].as_ref().ok()?,
            self.coulomb[s].as_ref().ok()?,
        );
        Some(measure(a) / measure(b))
    }
}
