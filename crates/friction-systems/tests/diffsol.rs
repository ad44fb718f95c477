//! diffsol's methods on friction: the switched stick–slip cycle of a belt system, and an
//! index-1 DAE with a regularised friction law against the equivalent ODE.

mod common;

use common::belt;
use friction_models::{FrictionModel, FrictionParams, ModelId, Variant};
use friction_systems::{FrictionSystem, Scheme, Switching, STICK};
use integrators::diffsol_backend::{self, DiffsolMethod};
use integrators::{
    Dopri5, ImplicitEuler, Integrator, Mode, NewtonKind, OdeProblem, Options, Solution,
    SolverError, Stepper,
};

#[test]
fn diffsol_methods_find_the_stick_slip_cycle_with_the_same_events() {
    let system = belt(ModelId::Static, 1.0, 100.0, 0.05);
    let body = FrictionSystem::new(&system, Switching::Event);
    let y0 = body.initial_state();
    let modes = body.initial_modes(0.0, &y0);
    // Closed form (see tests/stick_slip.rs): stick 0.6 s, slip (π + 2·atan(1/3))/10 s.
    let period = 0.6 + (std::f64::consts::PI + 2.0 * (1.0f64 / 3.0).atan()) / 10.0;
    for method in [
        DiffsolMethod::Bdf,
        DiffsolMethod::TrBdf2,
        DiffsolMethod::Esdirk34,
        DiffsolMethod::Tsit45,
    ] {
        let o = Options::adaptive(0.0, 6.0, 1e-10, 1e-12);
        let s: Solution = diffsol_backend::solve(&body, method, &y0, &modes, o).unwrap();
        let breaks: Vec<f64> = s
            .events
            .iter()
            .filter(|e| e.switches.iter().any(|s| s.from == STICK))
            .map(|e| e.t)
            .collect();
        assert!(
            breaks.len() >= 5,
            "{}: {} break-aways",
            method.name(),
            breaks.len()
        );
        for w in breaks.windows(2) {
            assert!(
                (w[1] - w[0] - period).abs() < 1e-6,
                "{}: period {} vs {period}",
                method.name(),
                w[1] - w[0]
            );
        }
        assert_eq!(
            s.stats.events,
            s.events.len(),
            "one contact: one function per event"
        );
    }
}

/// The paper block with regularised CVS friction as an index-1 DAE, y = [x, v, F]:
/// x' = v, m·v' = F_ex − F, 0 = F − F_reg(v); or as the ODE y = [x, v].
struct RegularisedBlock<'a> {
    model: &'a dyn FrictionModel,
    dae: bool,
}

impl RegularisedBlock<'_> {
    fn friction(&self, v: f64) -> f64 {
        self.model.force(
            0.0,
            v,
            &[],
            friction_models::SignLaw::Smooth { epsilon: 1e-2 },
        )
    }
}

impl OdeProblem for RegularisedBlock<'_> {
    fn dim(&self) -> usize {
        if self.dae {
            3
        } else {
            2
        }
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = y[1];
        if self.dae {
            f[1] = 15.0 - y[2];
            f[2] = y[2] - self.friction(y[1]);
        } else {
            f[1] = 15.0 - self.friction(y[1]);
        }
    }
    fn mass(&self) -> Option<&[f64]> {
        self.dae.then_some(&[1.0, 1.0, 0.0][..])
    }
}

#[test]
fn an_index_1_dae_agrees_with_the_equivalent_ode() {
    let p = FrictionParams::paper();
    let model = ModelId::Cvs.build(Variant::Odd, &p).unwrap();
    let ode = RegularisedBlock {
        model: model.as_ref(),
        dae: false,
    };
    let dae = RegularisedBlock {
        model: model.as_ref(),
        dae: true,
    };
    let o = Options::adaptive(0.0, 5.0, 1e-11, 1e-11);
    let reference = Integrator::new(
        &ode,
        Box::new(Dopri5::new(o.step, o.h_max(), o.max_steps, 2)),
        &[0.0, 0.0],
        &[Mode(0)],
        o,
    )
    .unwrap()
    .solve()
    .unwrap();
    let v_ref = reference.last().unwrap().1[1];
    // The velocity approaches the terminal velocity (F_ex − F_c)/mu_v = 18 m/s.
    assert!(v_ref > 10.0 && v_ref < 18.0, "{v_ref}");
    // BDF on the DAE.
    let o = Options::adaptive(0.0, 5.0, 1e-9, 1e-9);
    let s =
        diffsol_backend::solve(&dae, DiffsolMethod::Bdf, &[0.0, 0.0, 0.0], &[Mode(0)], o).unwrap();
    let y = s.last().unwrap().1;
    assert!(
        (y[1] - v_ref).abs() < 1e-5 * v_ref,
        "BDF DAE {} vs {v_ref}",
        y[1]
    );
    assert!(
        (y[2] - dae.friction(y[1])).abs() < 1e-6,
        "the constraint holds"
    );
    // Implicit Euler on the DAE and on the ODE, the same fixed steps: the same method (the
    // algebraic equation is solved in every step), so they differ only by Newton's stopping
    // tolerance, 1e-10 relative per step over 5000 steps.
    let run = |p: &dyn OdeProblem, y0: &[f64]| {
        let o = Options::fixed(0.0, 5.0, 1e-3);
        let ie: Box<dyn Stepper> = Box::new(ImplicitEuler::new(
            o.step,
            NewtonKind::Modified,
            o.h_max(),
            o.max_steps,
            y0.len(),
        ));
        Integrator::new(p, ie, y0, &[Mode(0)], o)
            .unwrap()
            .solve()
            .unwrap()
            .last()
            .unwrap()
            .1
            .to_vec()
    };
    let (a, b) = (run(&dae, &[0.0, 0.0, 0.0]), run(&ode, &[0.0, 0.0]));
    assert!(
        (a[1] - b[1]).abs() < 5000.0 * 1e-10 * b[1],
        "DAE {} vs ODE {}",
        a[1],
        b[1]
    );
    assert!(
        (a[1] - v_ref).abs() < 1e-2 * v_ref,
        "first order: {} vs {v_ref}",
        a[1]
    );
}

#[test]
fn diffsol_refuses_fixed_steps_and_explicit_daes() {
    let p = FrictionParams::paper();
    let model = ModelId::Cvs.build(Variant::Odd, &p).unwrap();
    let dae = RegularisedBlock {
        model: model.as_ref(),
        dae: true,
    };
    let f = diffsol_backend::solve(
        &dae,
        DiffsolMethod::Bdf,
        &[0.0; 3],
        &[Mode(0)],
        Options::fixed(0.0, 1.0, 0.1),
    )
    .unwrap_err();
    assert!(
        matches!(f.error, SolverError::Unsupported { solver: "bdf", .. }),
        "{}",
        f.error
    );
    let f = diffsol_backend::solve(
        &dae,
        DiffsolMethod::Tsit45,
        &[0.0; 3],
        &[Mode(0)],
        Options::adaptive(0.0, 1.0, 1e-6, 1e-6),
    )
    .unwrap_err();
    assert_eq!(
        f.error.to_string(),
        "tsit45 cannot integrate this problem: an explicit method cannot integrate a DAE (zeros on the mass diagonal)"
    );
}

#[test]
fn diffsol_implicit_methods_run_a_chain_on_the_sparse_path_and_agree_with_dopri5() {
    use friction_systems::chain::ChainParams;
    use friction_systems::simulate;
    let system = ChainParams {
        n_bodies: 200,
        ..ChainParams::default()
    }
    .build(&FrictionParams::paper(), |p| {
        ModelId::Static
            .build(Variant::Odd, p)
            .map(std::sync::Arc::from)
    })
    .unwrap();
    let problem = FrictionSystem::new(&system, Switching::Event);
    let y0 = problem.initial_state();
    let modes = problem.initial_modes(0.0, &y0);
    assert!(diffsol_backend::sparse_jacobian(&problem, 0.0, &y0, &modes));
    let finals = |solver: &str, tol: f64| {
        let o = Options::adaptive(0.0, 10.0, tol, tol * 1e-2);
        let solver = integrators::Solver::from_name(solver).unwrap();
        let r = simulate(
            &system,
            Scheme::EventDriven {
                solver,
                switching: Switching::Event,
            },
            o,
            &mut |_| {},
        )
        .unwrap();
        assert!(r.error.is_none(), "{:?}", r.error);
        r.final_states()
    };
    let reference = finals("dopri5", 1e-11);
    for method in ["bdf", "esdirk34"] {
        let worst = finals(method, 1e-8)
            .iter()
            .zip(&reference)
            .map(|(a, b)| (a.x - b.x).abs().max((a.v - b.v).abs()))
            .fold(0.0, f64::max);
        assert!(worst < 1e-4, "{method}: {worst:e}");
    }
}

#[test]
fn bdf_steps_below_diffsols_absolute_floor_on_a_body_of_one_milligram() {
    // A body of 1 mg on LuGre's bristles: the time scale m/σ1 is about 3e-9 s, and
    // diffsol's initial-step estimate starts BDF near 2e-14 s, below diffsol's own absolute
    // floor of 1e-13 s, where BDF failed at its first step. With the floor relative to t, as
    // every adaptive method here keeps it, BDF runs, and agrees with TR-BDF2 at 1e-10
    // (measured: 1.2e-10 m of x = 0.020 m and 2.9e-11 m/s of v = 0.0999 m/s at 0.2 s).
    let system = belt(ModelId::LuGre, 1e-6, 100.0, 0.1);
    let body = FrictionSystem::new(&system, Switching::Event);
    let y0 = body.initial_state();
    let modes = body.initial_modes(0.0, &y0);
    let end = |method, tol: f64| {
        let o = Options::adaptive(0.0, 0.2, tol, tol * 1e-2);
        let s = diffsol_backend::solve(&body, method, &y0, &modes, o).expect("no failure");
        let y = s.y_at(s.len() - 1);
        (y[0], y[1])
    };
    let (x, v) = end(DiffsolMethod::Bdf, 1e-8);
    let (x_ref, v_ref) = end(DiffsolMethod::TrBdf2, 1e-10);
    assert!(
        (x - x_ref).abs() < 1e-7 * x_ref.abs(),
        "x {x}, TR-BDF2 {x_ref}"
    );
    assert!(
        (v - v_ref).abs() < 1e-8 * v_ref.abs(),
        "v {v}, TR-BDF2 {v_ref}"
    );
}
