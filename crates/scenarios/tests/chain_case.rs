//! A study of the chain sweeps its own parameters and its law's: each value builds the chain
//! again from its source.

use friction_models::{FrictionParams, ModelId};
use friction_systems::chain::ChainParams;
use friction_systems::Scheme;
use integrators::{Solver, StepControl};
use scenarios::cases::{Measured, StudyCase, SystemCase};
use scenarios::chain::ChainSource;

fn source(n_bodies: usize, k_chain: f64) -> ChainSource {
    ChainSource {
        chain: ChainParams {
            n_bodies,
            k_chain,
            ..ChainParams::default()
        },
        law: ModelId::Cs.into(),
        friction: FrictionParams::paper(),
    }
}

fn case(source: ChainSource, t_end: f64) -> SystemCase {
    SystemCase {
        chain: Some(source.clone()),
        ..SystemCase::new(source.name(), source.build().unwrap(), t_end)
    }
}

fn run(case: &dyn StudyCase, solver: Solver, tol: f64) -> Measured {
    let step = StepControl::Adaptive {
        rtol: tol,
        atol: tol,
        h0: None,
    };
    let m = case.measure(Scheme::events(solver), step).unwrap();
    assert!(m.error.is_none(), "{:?}", m.error);
    m
}

#[test]
fn a_swept_chain_parameter_builds_the_chain_a_direct_build_gives() {
    let swept = case(source(4, 100.0), 10.0)
        .with_parameter("k_chain", 1e4)
        .unwrap();
    let direct = case(source(4, 1e4), 10.0);
    assert_eq!(swept.describe(), "chain of 4 CS");
    let (a, b) = (
        run(swept.as_ref(), Solver::DOPRI5, 1e-8),
        run(&direct, Solver::DOPRI5, 1e-8),
    );
    assert_eq!(a.measures, b.measures);
    assert_eq!(a.stats.rhs_evals, b.stats.rhs_evals);
    // And the value changed the run: the stiffer chain is another motion.
    let soft = run(&case(source(4, 100.0), 10.0), Solver::DOPRI5, 1e-8);
    assert_ne!(soft.measures.final_state, a.measures.final_state);
    // A friction parameter of the law, with the levels scaled along the chain as before.
    let f_c = case(source(4, 100.0), 10.0)
        .with_parameter("F_c", 5.0)
        .unwrap();
    let mut lower = source(4, 100.0);
    lower.friction.f_c = 5.0;
    assert_eq!(
        run(f_c.as_ref(), Solver::DOPRI5, 1e-8).measures,
        run(&case(lower, 10.0), Solver::DOPRI5, 1e-8).measures
    );
}

#[test]
fn a_parameter_the_chain_does_not_read_is_refused_by_name() {
    let c = case(source(4, 100.0), 1.0);
    let refused = |name: &str, value: f64| c.with_parameter(name, value).err().unwrap().to_string();
    assert_eq!(
        refused("sigma", 5.0),
        "parameter `sigma` is not read by model `CS` (it reads: F_c, F_s, C1, C2, v_s): every \
         value would give the same runs"
    );
    assert!(refused("bogus", 1.0)
        .starts_with("unknown parameter `bogus` of the chain; known: n_bodies, m, k_chain"));
    assert_eq!(
        refused("spread", 2.0),
        "chain: `spread` = 2 is out of range: allowed [0, 1)"
    );
    let measuring_the_fourth = SystemCase {
        bodies: vec![3],
        ..c.clone()
    };
    assert_eq!(
        measuring_the_fourth
            .with_parameter("n_bodies", 2.0)
            .err()
            .unwrap()
            .to_string(),
        "parameter `n_bodies` = 2 leaves 2 bodies: the measured body 4 is not among them"
    );
    let file = SystemCase { chain: None, ..c };
    assert_eq!(
        file.with_parameter("k_chain", 1e3)
            .err()
            .unwrap()
            .to_string(),
        "parameter `k_chain` cannot be swept on a system file (each contact has its own \
         parameters): allowed epsilon"
    );
}
