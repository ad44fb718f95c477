//! The solver studies on the paper's problems: convergence on the paper block and on Coulomb
//! free vibration (stepping blindly through v = 0 and with event location), the step-size
//! independence the paper claims, work against precision on the belt, and the cost of the
//! regularisation's stiffness (`studies/`).

use super::Part;
use crate::error::AppError;
use crate::study::{
    conduct_all, ConvergenceStudy, Entry, IndependenceStudy, Output, Refinement, ReportEntry,
    StiffnessStudy, WorkPrecisionStudy,
};
use friction_models::{FrictionParams, ModelId};
use friction_systems::{Scheme, Switching};
use integrators::Solver;
use scenarios::studies::{
    Case, Convergence, ErrorMeasure, Independence, Method, Stiffness, WorkPrecision,
};
use scenarios::{Limits, Scenario};

/// A study case on the paper's parameters.
pub(super) fn case(
    scenario: Scenario,
    model: ModelId,
    friction: &FrictionParams,
    t_end: f64,
) -> Case {
    Case {
        scenario,
        law: model.into(),
        friction: *friction,
        params: scenario.defaults(),
        t_end,
        limits: Limits::default(),
    }
}

/// Each of `solvers` under `switching`, studied.
fn under(switching: Switching, solvers: &[Solver]) -> Vec<Method> {
    (solvers.iter())
        .map(|&solver| Method::of(Scheme::EventDriven { solver, switching }))
        .collect()
}

fn observed_orders(c: &Convergence, measure: ErrorMeasure) -> String {
    c.orders
        .iter()
        .filter(|t| t.measure == measure)
        .map(|t| {
            format!(
                "{} {}",
                t.solver,
                t.fit.map_or("- (no asymptotic range)".into(), |f| {
                    let formal = t
                        .against_formal()
                        .map_or(String::new(), |a| format!(": {a}"));
                    format!(
                        "{:.2} (95 % CI {:.2} to {:.2}{formal})",
                        f.slope, f.ci[0], f.ci[1]
                    )
                })
            )
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The report's section of solver studies on the paper's problems.
pub struct SolverStudies {
    /// The friction parameters.
    pub friction: FrictionParams,
}

impl Part for SolverStudies {
    fn heading(&self) -> String {
        "Solver studies".into()
    }

    fn folder(&self) -> &'static str {
        "studies"
    }

    fn conduct(&self, target: &mut Output) -> Result<String, AppError> {
        let friction = &self.friction;
        let from_paper_dt = Refinement {
            start: 1e-3,
            ratio: 2.0,
            levels: 4,
            tol: 1e-6,
        };
        let (event, naive) = (Switching::Event, Switching::Naive);
        let regularized = Switching::Regularized {
            epsilon: friction.epsilon,
        };
        let rk4 = Method::of(Scheme::events(Solver::RK4));
        let native = under(
            event,
            &[Solver::RK4, Solver::DOPRI5, Solver::IMPLICIT_EULER],
        );
        let steps = [0.02, 0.01, 0.005, 0.0025];
        let all = under(event, &Solver::ALL);
        let explicit_implicit = under(
            regularized,
            &[
                Solver::DOPRI5,
                Solver::TSIT45,
                Solver::IMPLICIT_EULER,
                Solver::BDF,
                Solver::ESDIRK34,
            ],
        );
        let rk4_naive = under(naive, &[Solver::RK4]);
        let block_cvs = case(Scenario::PAPER_BLOCK, ModelId::Cvs, friction, 5.0);
        let block_av = case(Scenario::PAPER_BLOCK, ModelId::Av, friction, 5.0);
        let vibration = case(Scenario::FREE_VIBRATION, ModelId::Static, friction, 2.0);
        let belt = |t_end| case(Scenario::BELT, ModelId::Cs, friction, t_end);
        let (belt_naive, belt_event, belt_regularized) = (belt(20.0), belt(5.0), belt(2.0));
        let independent = |i: &scenarios::studies::Independence| {
            if i.independent {
                "independent"
            } else {
                "**not** independent"
            }
        };
        let convergence = |methods| ConvergenceStudy {
            case: &vibration,
            methods,
            steps: &steps,
            tols: &[1e-6],
        };
        let table: [&dyn ReportEntry; 7] = [
            &Entry {
                stem: "converge-paper-block-CVS",
                study: ConvergenceStudy {
                    case: &block_cvs,
                    ..convergence(&native)
                },
                reads: |c: &Convergence| {
                    format!(
                        "- [Convergence on the paper block (CVS)](studies/converge-paper-block-CVS.png): \
                         observed orders of the relative grid error over each method's asymptotic \
                         range {}.\n",
                        observed_orders(c, ErrorMeasure::GridRelative)
                    )
                },
            },
            &Entry {
                stem: "converge-free-vibration-naive",
                study: convergence(&rk4_naive),
                reads: |c: &Convergence| {
                    format!(
                        "- [Stepping blindly through v = 0](studies/converge-free-vibration-naive.png) \
                         on Coulomb free vibration (closed-form reversals every pi/omega): RK4's \
                         order is {}.\n",
                        observed_orders(c, ErrorMeasure::GridRelative)
                    )
                },
            },
            &Entry {
                stem: "converge-free-vibration-event",
                study: convergence(std::slice::from_ref(&rk4)),
                reads: |c: &Convergence| {
                    format!(
                        "- [The same with event-located switching](studies/converge-free-vibration-event.png): \
                         RK4's order is {}.\n",
                        observed_orders(c, ErrorMeasure::GridRelative)
                    )
                },
            },
            &Entry {
                stem: "independence-paper-block-AV",
                study: IndependenceStudy {
                    case: &block_av,
                    method: rk4,
                    refinement: from_paper_dt,
                },
                reads: |i: &Independence| {
                    format!(
                        "- [The paper's step-size claim on AV](studies/independence-paper-block-AV.png) \
                         (RK4 from dt = 1e-3, halved three times, relative tolerance 1e-6): {}.\n",
                        independent(i)
                    )
                },
            },
            &Entry {
                stem: "independence-belt-CS-naive",
                study: IndependenceStudy {
                    case: &belt_naive,
                    method: rk4_naive[0],
                    refinement: from_paper_dt,
                },
                reads: |i: &Independence| {
                    format!(
                        "- [The same check on CS stick-slip stepped blindly](studies/independence-belt-CS-naive.png): {}.\n",
                        independent(i)
                    )
                },
            },
            &Entry {
                stem: "work-precision-belt-CS",
                study: WorkPrecisionStudy {
                    case: &belt_event,
                    methods: &all,
                    steps: &[0.01, 0.003, 0.001, 0.0003],
                    tols: &[
                        0.001, 0.000464, 0.000215, 0.0001, 4.64e-5, 2.15e-5, 1e-5, 4.64e-6,
                        2.15e-6, 1e-6, 4.64e-7, 2.15e-7, 1e-7, 4.64e-8, 2.15e-8, 1e-8,
                    ],
                    repeats: 5,
                },
                reads: |_: &WorkPrecision| {
                    "- [Work against precision on the belt](studies/work-precision-belt-CS.png): \
                     relative error against counted work (f evaluations, with Jacobians, LU \
                     factorisations and back-solves weighted by their operation counts) for every \
                     solver; wall times in studies/work-precision-belt-CS-timing.csv.\n"
                        .into()
                },
            },
            &Entry {
                stem: "stiffness-belt-CS-epsilon",
                study: StiffnessStudy {
                    case: &belt_regularized,
                    sweep: scenarios::studies::Sweep {
                        parameter: "epsilon",
                        values: &[1.0, 1e-1, 1e-2, 1e-3, 1e-4],
                        target: 1e-3,
                    },
                    methods: &explicit_implicit,
                    steps: &[0.01],
                    tols: &[
                        0.01, 0.00464, 0.00215, 0.001, 0.000464, 0.000215, 0.0001, 4.64e-05,
                        2.15e-05, 1e-05, 4.64e-06, 2.15e-06, 1e-06, 4.64e-07, 2.15e-07, 1e-07,
                    ],
                },
                reads: |s: &Stiffness| {
                    format!(
                        "- [Cost to reach relative error 1e-3 against the regularisation width](studies/stiffness-belt-CS-epsilon.png): \
                         {}.\n",
                        s.verdict()
                    )
                },
            },
        ];
        Ok(format!(
            "The files are in `studies/` (CSV per run, JSON summary, PNG and SVG); \
             docs/studies.md explains each study and how to read its plot.\n\n{}",
            conduct_all(&table, target)?
        ))
    }
}
