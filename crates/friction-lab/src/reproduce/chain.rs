//! Many blocks: the chain of `docs/systems.md` with stiction on every block, integrated
//! event-driven, regularised and time-stepped: work against precision at N = 100 and the cost
//! per step against N (`studies/`).

use super::Part;
use crate::error::AppError;
use crate::study::solver_studies::system_peers;
use crate::study::{conduct_all, Entry, Output, ReportEntry, ScalingStudy, WorkPrecisionStudy};
use friction_models::{FrictionParams, ModelId, Variant};
use friction_systems::chain::ChainParams;
use friction_systems::Scheme;
use integrators::{Solver, StepControl};
use scenarios::studies::{Method, Scaling, StudyCase, SystemCase, WorkPrecision};
use std::sync::Arc;

/// The initial displacement of every block of the chain studies, m.
const PRELOAD_X0: f64 = -0.7;

/// The chain of `docs/systems.md` (`static` friction: stiction on every block) with `n` blocks,
/// every block started at x0 = −0.7 m (its driver spring loaded to 7 N, just below the
/// break-away level 7.5 N, so that the blocks break away within the first second), as a study
/// case over `t_end` seconds.
fn chain_case(n: usize, friction: &FrictionParams, t_end: f64) -> Result<SystemCase, AppError> {
    let mut system = ChainParams {
        n_bodies: n,
        ..ChainParams::default()
    }
    .build(friction, |p| {
        ModelId::Static.build(Variant::Odd, p).map(Arc::from)
    })?;
    for b in &mut system.bodies {
        b.x0 = PRELOAD_X0;
    }
    // Pre-loaded after it was built: not the chain its parameters build, so no `chain`.
    Ok(SystemCase::new(
        format!("chain of {n} blocks with static friction"),
        system,
        t_end,
    ))
}

/// The report's section on the chain: work–precision at N = 100 and the cost per step against
/// N up to 1000.
pub struct ChainStudies {
    /// The friction parameters.
    pub friction: FrictionParams,
}

impl Part for ChainStudies {
    fn heading(&self) -> String {
        "Many blocks: event-driving, regularisation and time-stepping".into()
    }

    fn folder(&self) -> &'static str {
        "studies"
    }

    /// The studies time-step the chain: parameters at which its law cannot be time-stepped
    /// are refused before anything runs, not after the figures and Table 2.
    fn check(&self) -> Result<(), AppError> {
        for contact in &chain_case(1, &self.friction, 1.0)?.system.contacts {
            let model = contact.model.as_ref();
            if let Some(outside) = friction_systems::moreau_jean::sliding_outside_stick(model) {
                return Err(AppError::Usage(format!(
                    "the parameters given cannot be used by reproduce: its chain studies \
                     time-step the chain (Moreau-Jean), and with them {}; reproduce takes \
                     friction parameters at which every part of it runs",
                    outside.describe(model.name())
                )));
            }
        }
        Ok(())
    }

    fn conduct(&self, target: &mut Output) -> Result<String, AppError> {
        let friction = &self.friction;
        let chain_100 = chain_case(100, friction, 5.0)?;
        let sizes = [10, 30, 100, 300, 1000];
        let cases = sizes
            .iter()
            .map(|&n| {
                Ok((
                    n,
                    Box::new(chain_case(n, friction, 4.0)?) as Box<dyn StudyCase>,
                ))
            })
            .collect::<Result<Vec<_>, AppError>>()?;
        let adaptive = StepControl::Adaptive {
            rtol: 1e-6,
            atol: 1e-6,
            h0: None,
        };
        let mut methods = vec![(Method::of(Scheme::events(Solver::DOPRI5)), adaptive)];
        methods.extend(system_peers(friction.epsilon).into_iter().map(|m| {
            let step = if m.is_fixed_step() {
                StepControl::Fixed { h: 1e-3 }
            } else {
                adaptive
            };
            (m, step)
        }));
        let epsilon = friction.epsilon;
        let chain_methods: Vec<Method> = [Solver::DOPRI5, Solver::BDF]
            .map(|s| Method::of(Scheme::events(s)))
            .into_iter()
            .chain(system_peers(epsilon))
            .collect();
        let table: [&dyn ReportEntry; 2] = [
            &Entry {
                stem: "work-precision-chain-100",
                study: WorkPrecisionStudy {
                    case: &chain_100,
                    methods: &chain_methods,
                    steps: &[0.01, 0.00464, 0.00215, 0.001, 0.000464],
                    tols: &[
                        1e-4, 4.64e-5, 2.15e-5, 1e-5, 4.64e-6, 2.15e-6, 1e-6, 4.64e-7, 2.15e-7,
                        1e-7, 4.64e-8, 2.15e-8, 1e-8,
                    ],
                    repeats: 5,
                },
                reads: |_: &WorkPrecision| {
                    format!(
                        "- [Work against precision at N = 100](studies/work-precision-chain-100.png) over 5 s: \
                         event-driven Dormand–Prince and BDF (tolerances 1e-4 to 1e-8, three a decade; wall \
                         times the median of 5 repeats), BDF on the regularised \
                         system (width epsilon = {epsilon}, sparse Jacobian; its error stops at the regularisation's), \
                         and Moreau–Jean time-stepping (theta = 1/2, h = 1e-2 to 4.64e-4; first order with \
                         stiction).\n"
                    )
                },
            },
            &Entry {
                stem: "cost-chain",
                study: ScalingStudy {
                    cases: &cases,
                    methods: &methods,
                },
                reads: |scaling: &Scaling| {
                    let exponents = (scaling.exponents.iter())
                        .map(|(label, e)| format!("{label} {e:.2}"))
                        .collect::<Vec<_>>()
                        .join(", ");
                    format!(
                        "- [Wall time per step against the number of blocks](studies/cost-chain-timing.png) \
                         (N = 10 to 1000 over 4 s; Dormand–Prince and \
                         regularised BDF at tolerance 1e-6, time-stepping at h = 1e-3; studies/cost-chain.csv \
                         has steps and work, studies/cost-chain-timing.csv the wall times). Fitted slopes of \
                         counted work per step against N: {exponents}.\n"
                    )
                },
            },
        ];
        Ok(format!(
            "The chain of `docs/systems.md` with stiction on every block (`static`), every block \
             started at x0 = -0.7 m (driver spring at 7 N, break-away at 7.5 N), one system \
             integrated three ways (docs/timestepping.md, docs/systems.md):\n\n{}",
            conduct_all(&table, target)?
        ))
    }
}
