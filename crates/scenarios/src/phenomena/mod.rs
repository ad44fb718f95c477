//! Table 2 decided by simulation: one protocol per phenomenon, each a scenario run whose
//! measured numbers decide the cell against a stated threshold (see `docs/phenomena.md`).
//!
//! A row is a [`Phenomenon`], decided by its [`Experiment`] on a [`Bench`] (the law, its
//! parameters, the protocol's integration, the rig); the built-in rows are in
//! [`Phenomenon::ALL`] (`experiments`: one struct a row), and a row of one's own is an
//! `Experiment` run as [`Phenomenon::own`].

mod bench;
pub mod cost;
mod experiments;
mod phenomenon;
pub mod thresholds;

pub use bench::{Bench, Breakaway, Cycle};
pub use experiments::{
    Hunting, Hysteresis, Presliding, RisingStaticFriction, StickSlip, Stiction, Stribeck, Viscous,
};
pub use phenomenon::{Axes, Experiment, Phenomenon, PHENOMENA};

use crate::error::ScenarioError;
use crate::run::{Law, Limits, RunSpec};
use crate::scenario::Scenario;
use crate::ScenarioParams;
use friction_models::{FrictionParams, ModelId, Parameters};
use friction_systems::Scheme;
use integrators::{Solver, StepControl};
use serde::Serialize;
use std::collections::BTreeMap;

/// A decided cell: the answer and the numbers that decided it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Verdict {
    /// Whether the phenomenon was observed.
    pub measured: bool,
    /// The numbers that decided it.
    pub evidence: BTreeMap<&'static str, f64>,
}

/// The friction parameters the protocols read themselves, whatever model they judge: F_s and
/// F_c scale the force ramps (to max(F_s, F_c)) and the break-away and pre-sliding measures,
/// v_s the velocities of the Stribeck sweep, of the velocity oscillation and of gross sliding.
/// A `--set` of one of them changes the table even for a model that does not read it.
pub const PROTOCOL_PARAMETERS: [&str; 3] = ["F_s", "F_c", "v_s"];

/// How the protocols integrate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Protocol {
    /// The solver.
    pub solver: Solver,
    /// Its step control.
    pub step: StepControl,
    /// The bounds of every run (a run that reaches one fails, and its cell is undecided).
    pub limits: Limits,
}

impl Default for Protocol {
    /// diffsol's BDF at rtol = 1e-10, atol = 1e-12: the bristle models (LuGre, its variants,
    /// GMS) are stiff, and Dormand–Prince, which gives the same verdicts and regions, takes
    /// four times as long over the whole table (docs/performance.md).
    fn default() -> Self {
        Protocol {
            solver: Solver::BDF,
            step: StepControl::Adaptive {
                rtol: 1e-10,
                atol: 1e-12,
                h0: None,
            },
            limits: Limits::default(),
        }
    }
}

impl Protocol {
    /// A run of `scenario` with `law` at `friction` and the rig's `params` to `t_end` on
    /// `points` output points, integrated as the protocol says with event switching.
    pub fn spec(
        &self,
        scenario: Scenario,
        law: &Law,
        friction: FrictionParams,
        params: ScenarioParams,
        t_end: f64,
        points: usize,
    ) -> RunSpec {
        RunSpec {
            scenario,
            law: law.clone(),
            friction,
            params,
            scheme: Scheme::events(self.solver),
            step: self.step,
            t_end: Some(t_end),
            output_points: points,
            limits: self.limits,
        }
    }
}

/// The parameters `law` is judged at unless told otherwise: its own set for a model of the
/// catalog ([`parameters_for`]), the paper's for a law of one's own (which then set only the
/// rigs' scales).
pub fn own_parameters(law: &Law) -> FrictionParams {
    law.catalog()
        .map_or_else(FrictionParams::paper, parameters_for)
}

/// The parameter set a model is judged with: the paper's for the six and the classical
/// terms, the LuGre paper's for the bristle models (LuGre, its two variants and GMS), whose
/// stiffness σ0 = 1e5 N/m sets a micrometre pre-sliding scale only with its levels.
pub fn parameters_for(model: ModelId) -> FrictionParams {
    if matches!(
        model,
        ModelId::LuGre | ModelId::LuGreVd | ModelId::ElastoPlastic | ModelId::Gms
    ) {
        FrictionParams::lugre_1995()
    } else {
        FrictionParams::paper()
    }
}

/// Decides one cell: `phenomenon` for `law` (a model of the catalog, or a law of the user's
/// own) with `p` (the catalog model's parameters, and the scales of the protocols: F_s, F_c,
/// v_s), integrated as `protocol` says, on the rigs of docs/phenomena.md.
pub fn decide(
    phenomenon: Phenomenon,
    law: &Law,
    p: &FrictionParams,
    protocol: Protocol,
) -> Result<Verdict, ScenarioError> {
    decide_at(phenomenon, law, p, protocol, &ScenarioParams::default())
}

/// Decides one cell on rigs with the parameters `rig` (mass `m`, belt `v_belt`, spring `k`,
/// damper `c`, pre-sliding load `fraction`; the protocols set their own ramp rates and
/// motions).
pub fn decide_at(
    phenomenon: Phenomenon,
    law: &Law,
    p: &FrictionParams,
    protocol: Protocol,
    rig: &ScenarioParams,
) -> Result<Verdict, ScenarioError> {
    let built = law.build(p)?;
    let bench = Bench::new(law, built.as_ref(), *p, protocol, *rig);
    phenomenon.experiment().decide(&bench)
}

/// One cell of the measured Table 2.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cell {
    /// What the simulation shows: `Ok(observed)`, or `Err(why)` when a run of its protocol
    /// failed in the solver or reached a limit (the cell is undecided, its evidence empty).
    pub measured: Result<bool, String>,
    /// What the paper claims (`None` for models it does not cover).
    pub paper: Option<bool>,
    /// The numbers that decided it.
    pub evidence: BTreeMap<&'static str, f64>,
    /// The verdict over the grid of rig parameters, when asked for.
    pub region: Option<Region>,
}

/// A verdict over the grid of [`Experiment::region`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Region {
    /// The grid's axes: parameter and values.
    pub axes: BTreeMap<&'static str, &'static [f64]>,
    /// Points of the grid.
    pub points: usize,
    /// The fraction of the decided points where the phenomenon is observed.
    pub fraction: f64,
    /// The points whose verdict differs from the verdict on the default rig, each as its
    /// parameter values.
    pub flips: Vec<BTreeMap<&'static str, f64>>,
    /// Points whose run failed (left out of the fraction), with the failure.
    pub undecided: Vec<(BTreeMap<&'static str, f64>, String)>,
}

impl Cell {
    /// Whether the simulation decided the cell and the paper claims otherwise.
    pub fn disagrees(&self) -> bool {
        matches!((&self.measured, self.paper), (Ok(m), Some(p)) if *m != p)
    }
}

impl Region {
    /// Whether the verdict depends on the rig: observed on some points and not on others.
    pub fn depends(&self) -> bool {
        self.fraction > 0.0 && self.fraction < 1.0
    }
}

/// Decides `phenomenon` for `law` at every point of its [`Experiment::region`]; `measured`
/// is the verdict on the default rig, against which the flips are listed.
pub fn region(
    phenomenon: Phenomenon,
    law: &Law,
    p: &FrictionParams,
    protocol: Protocol,
    measured: bool,
) -> Result<Region, ScenarioError> {
    let axes = phenomenon.region();
    let grid: Vec<BTreeMap<&'static str, f64>> = crate::grid::product(axes)
        .into_iter()
        .map(|point| point.into_iter().collect())
        .collect();
    use rayon::prelude::*;
    let verdicts: Vec<Result<Verdict, ScenarioError>> = grid
        .par_iter()
        .map(|point| {
            let mut rig = ScenarioParams::default();
            for (name, value) in point {
                rig.set(name, *value)?;
            }
            decide_at(phenomenon, law, p, protocol, &rig)
        })
        .collect();
    let (mut observed, mut decided) = (0usize, 0usize);
    let mut flips = Vec::new();
    let mut undecided = Vec::new();
    for (point, verdict) in grid.iter().zip(verdicts) {
        match verdict {
            Ok(v) => {
                decided += 1;
                observed += usize::from(v.measured);
                if v.measured != measured {
                    flips.push(point.clone());
                }
            }
            Err(e) => undecided.push((point.clone(), e.to_string())),
        }
    }
    Ok(Region {
        axes: axes.iter().copied().collect(),
        points: grid.len(),
        fraction: if decided > 0 {
            observed as f64 / decided as f64
        } else {
            f64::NAN
        },
        flips,
        undecided,
    })
}

/// Every model of the catalog, in its sign-consistent reading: the columns of the paper's
/// Table 2 and of the reference models.
pub fn catalog_laws() -> Vec<Law> {
    ModelId::ALL.iter().map(|&m| Law::from(m)).collect()
}

/// One model's row of Table 2: each phenomenon with its cell.
pub type Row = Vec<(Phenomenon, Cell)>;

/// Table 2 for `laws` and the rows `phenomena` ([`Phenomenon::ALL`]: the paper's): every
/// protocol for every law, run in parallel on rayon's pool
/// (the result does not depend on the number of threads: each cell is computed alone and
/// collected in order).
///
/// With `regions`, each cell is also decided over its grid of rig parameters
/// ([`region`]): about 20 times the work. A cell whose protocol fails in the solver is kept,
/// undecided ([`Cell::measured`] holds why), and the others are decided; bad input fails the
/// table. `progress` is called after each cell.
///
/// A law of the catalog is judged at `parameters` or its own set ([`parameters_for`]) and
/// beside the paper's claim; a law of one's own at `parameters` or the paper's set (which then
/// sets only the rigs' scales), with no claim.
pub fn table(
    laws: &[Law],
    phenomena: &[Phenomenon],
    protocol: Protocol,
    parameters: Option<&FrictionParams>,
    regions: bool,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<(Law, Row)>, ScenarioError> {
    use rayon::prelude::*;
    let jobs: Vec<(&Law, Phenomenon)> = laws
        .iter()
        .flat_map(|law| phenomena.iter().map(move |&p| (law, p)))
        .collect();
    let cells: Vec<Result<Cell, ScenarioError>> = jobs
        .par_iter()
        .map(|&(law, phenomenon)| {
            let p = parameters.copied().unwrap_or_else(|| own_parameters(law));
            let paper = law.catalog().and_then(|m| phenomenon.paper_claim(m));
            let cell = match decide(phenomenon, law, &p, protocol) {
                Ok(v) => Ok(Cell {
                    region: regions
                        .then(|| region(phenomenon, law, &p, protocol, v.measured))
                        .transpose()?,
                    measured: Ok(v.measured),
                    paper,
                    evidence: v.evidence,
                }),
                Err(e @ (ScenarioError::Solver { .. } | ScenarioError::RunFailed(_))) => Ok(Cell {
                    measured: Err(e.to_string()),
                    paper,
                    evidence: BTreeMap::new(),
                    region: None,
                }),
                Err(e) => Err(e),
            };
            progress();
            cell
        })
        .collect();
    let mut cells = cells.into_iter();
    laws.iter()
        .map(|law| {
            let row = phenomena
                .iter()
                .map(|&p| Ok((p, cells.next().expect("one cell per job")?)))
                .collect::<Result<Vec<_>, ScenarioError>>()?;
            Ok((law.clone(), row))
        })
        .collect()
}
