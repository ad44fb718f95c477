//! Moreau–Jean time-stepping against closed forms: exact sticking, the observed orders at
//! θ = 1/2 and θ = 1, the discrete energy balance, and chains against event-driving.

mod common;

use common::{belt, one_block_exact};
use friction_models::{FrictionParams, ModelId, Variant};
use friction_systems::chain::ChainParams;
use friction_systems::moreau_jean::{SWEEP_ATOL, SWEEP_RTOL};
use friction_systems::{simulate, End, Run, Scheme, Switching, System, STICK};
use integrators::{Options, Output, Solver, SolverError, StepControl};
use std::f64::consts::PI;
use std::sync::Arc;

const F_C: f64 = 6.0;
const F_S: f64 = 7.5;

/// The time-stepped run, recorded on `grid` (every step end if it is empty).
fn stepped<'a>(system: &'a System, theta: f64, h: f64, t_end: f64, grid: &[f64]) -> Run<'a> {
    let output = match grid {
        [] => Output::Steps,
        g => Output::Grid(g.to_vec()),
    };
    let options = Options {
        output,
        ..Options::fixed(0.0, t_end, h)
    };
    let switching = Scheme::TimeStepping { theta };
    let run = simulate(system, switching, options, &mut |_| {}).unwrap();
    assert!(run.error.is_none(), "{:?}", run.error);
    run
}

fn grid(t_end: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|i| t_end * i as f64 / n as f64).collect()
}

/// The one-block chain: mass 1, driver spring 10, driver at 0.1 m/s.
fn one_block(model: ModelId) -> System {
    let c = ChainParams {
        n_bodies: 1,
        spread: 0.0,
        ..ChainParams::default()
    };
    c.build(&FrictionParams::paper(), |p| {
        model.build(Variant::Odd, p).map(Arc::from)
    })
    .unwrap()
}

/// The one-block chain with Coulomb friction F_c alone (ω = √10, v_d = 0.1): at rest until
/// the spring force k·v_d·t reaches F_c at t_b = F_c/(k·v_d), then, the friction force being
/// continuous there, `x = v_d·t − F_c/k − (v_d/ω)·sin ω(t − t_b)` for ever (v = v_d·(1 − cos)
/// returns to zero only tangentially, where the block grazes the floor's velocity).
fn one_block_coulomb(t: f64) -> (f64, f64) {
    let (k, v_d, omega) = (10.0, 0.1, 10f64.sqrt());
    let t_b = F_C / (k * v_d);
    if t <= t_b {
        return (0.0, 0.0);
    }
    let (s, c) = (omega * (t - t_b)).sin_cos();
    (v_d * t - F_C / k - v_d / omega * s, v_d * (1.0 - c))
}

/// The one-block chain with stiction F_s > F_c: piecewise harmonic ([`one_block_exact`]).
fn one_block_static(t: f64) -> (f64, f64) {
    one_block_exact(t, 1.0, 10.0, 0.1, F_S, F_C)
}

const BELT_K: f64 = 100.0;
const BELT_V: f64 = 0.05;

/// A body (m = 1) held by a spring k = 100 to a wall on a belt at 0.05 m/s with Coulomb
/// friction F_c alone, from rest at x = 0: it slides back on the belt,
/// `x = (F_c/k)·(1 − cos ωt)`, until it reaches the belt's velocity at t_1, sticks to the belt
/// until the spring force reaches F_c at x = F_c/k (t_2), and then oscillates about F_c/k,
/// `x = F_c/k + (v_b/ω)·sin ω(t − t_2)`, touching the belt's velocity tangentially once a
/// period.
fn belt_coulomb(t: f64) -> (f64, f64) {
    let omega = BELT_K.sqrt();
    let amplitude = F_C / BELT_K;
    let t_1 = (BELT_V / (amplitude * omega)).asin() / omega;
    let x_1 = amplitude * (1.0 - (omega * t_1).cos());
    let t_2 = t_1 + (amplitude - x_1) / BELT_V;
    if t <= t_1 {
        let (s, c) = (omega * t).sin_cos();
        (amplitude * (1.0 - c), amplitude * omega * s)
    } else if t <= t_2 {
        (x_1 + BELT_V * (t - t_1), BELT_V)
    } else {
        let (s, c) = (omega * (t - t_2)).sin_cos();
        (amplitude + BELT_V / omega * s, BELT_V * c)
    }
}

/// The same belt with stiction F_s > F_c: after the same first slip and stick, break-away at
/// x = F_s/k, then the cycle of tests/stick_slip.rs: slip about F_c/k from
/// `x = F_s/k`, `v = v_b` until v = v_b again, stick until x = F_s/k.
fn belt_static(t: f64) -> (f64, f64) {
    let omega = BELT_K.sqrt();
    let amplitude = F_C / BELT_K;
    let t_1 = (BELT_V / (amplitude * omega)).asin() / omega;
    let x_1 = amplitude * (1.0 - (omega * t_1).cos());
    if t <= t_1 {
        let (s, c) = (omega * t).sin_cos();
        return (amplitude * (1.0 - c), amplitude * omega * s);
    }
    // x − F_c/k = A·cos(ωτ + φ) with A·cos φ = (F_s − F_c)/k, −A·ω·sin φ = v_b.
    let c0 = (F_S - F_C) / BELT_K;
    let phi = -(BELT_V / (omega * c0)).atan();
    let a = c0 / phi.cos();
    let slip = (PI - 2.0 * phi) / omega;
    let stick = (F_S / BELT_K - (2.0 * F_C - F_S) / BELT_K) / BELT_V;
    let mut t_b = t_1 + (F_S / BELT_K - x_1) / BELT_V;
    if t <= t_b {
        return (x_1 + BELT_V * (t - t_1), BELT_V);
    }
    loop {
        if t <= t_b + slip {
            let arg = omega * (t - t_b) + phi;
            return (F_C / BELT_K + a * arg.cos(), -a * omega * arg.sin());
        }
        if t <= t_b + slip + stick {
            let x_stick = (2.0 * F_C - F_S) / BELT_K;
            return (x_stick + BELT_V * (t - t_b - slip), BELT_V);
        }
        t_b += slip + stick;
    }
}

/// A closed form: (x, v) at t.
type ClosedForm = fn(f64) -> (f64, f64);

/// A system, its closed form, the span.
struct Case {
    name: &'static str,
    system: System,
    exact: ClosedForm,
    t_end: f64,
}

/// The two cases with `model`, and the largest step of each order study (the belt's
/// tangential touches of the belt velocity, every 0.63 s, need steps below 2e-3 to be resolved).
fn cases(model: ModelId) -> [(Case, f64); 2] {
    let (chain, on_belt): (ClosedForm, ClosedForm) = match model {
        ModelId::Coulomb => (one_block_coulomb, belt_coulomb),
        _ => (one_block_static, belt_static),
    };
    [
        (
            Case {
                name: "one-block chain",
                system: one_block(model),
                exact: chain,
                t_end: 20.0,
            },
            1e-2,
        ),
        (
            Case {
                name: "belt",
                system: belt(model, 1.0, BELT_K, BELT_V),
                exact: on_belt,
                t_end: 2.0,
            },
            2e-3,
        ),
    ]
}

/// Largest deviation of x and v from the closed form on a grid of 400 points.
fn error(case: &Case, theta: f64, h: f64) -> f64 {
    let g = grid(case.t_end, 400);
    let run = stepped(&case.system, theta, h, case.t_end, &g);
    run.body(0).iter().fold(0.0, |worst: f64, b| {
        let (x, v) = (case.exact)(b.t);
        worst.max((b.x - x).abs()).max((b.v - v).abs())
    })
}

/// The least-squares slope of log(error) against log(h) over steps spaced by a factor
/// √3 (not a power of two, so that the step ends do not fall at the same phase of the
/// switches for every h).
fn observed_order(case: &Case, theta: f64, h0: f64) -> f64 {
    let points: Vec<(f64, f64)> = (0..6)
        .map(|i| {
            let h = h0 / 3f64.sqrt().powi(i);
            (h.ln(), error(case, theta, h).ln())
        })
        .collect();
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let sxy: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = points.iter().map(|(x, _)| (x - mx).powi(2)).sum();
    sxy / sxx
}

#[test]
fn the_closed_forms_agree_with_event_driven_dormand_prince() {
    for model in [ModelId::Coulomb, ModelId::Static] {
        for (case, _) in cases(model) {
            let options = Options {
                output: Output::Grid(grid(case.t_end, 400)),
                ..Options::adaptive(0.0, case.t_end, 1e-12, 1e-14)
            };
            let run = simulate(
                &case.system,
                Scheme::EventDriven {
                    solver: Solver::DOPRI5,
                    switching: Switching::Event,
                },
                options,
                &mut |_| {},
            )
            .unwrap();
            let worst = run.body(0).iter().fold(0.0, |w: f64, b| {
                let (x, v) = (case.exact)(b.t);
                w.max((b.x - x).abs()).max((b.v - v).abs())
            });
            assert!(worst < 1e-8, "{} {model:?}: {worst:e}", case.name);
        }
    }
}

#[test]
fn with_continuous_friction_at_break_away_the_order_is_two_at_theta_half_and_one_at_theta_one() {
    for (case, h0) in cases(ModelId::Coulomb) {
        let half = observed_order(&case, 0.5, h0);
        let one = observed_order(&case, 1.0, h0);
        println!(
            "Coulomb {}: order {half:.2} at θ = 1/2, {one:.2} at θ = 1",
            case.name
        );
        assert!(
            (1.8..2.3).contains(&half),
            "{}: θ = 1/2 order {half}",
            case.name
        );
        assert!(
            (0.85..1.2).contains(&one),
            "{}: θ = 1 order {one}",
            case.name
        );
    }
}

#[test]
fn with_a_jump_from_stiction_to_sliding_friction_the_order_is_one_at_either_theta() {
    for (case, h0) in cases(ModelId::Static) {
        for theta in [0.5, 1.0] {
            let order = observed_order(&case, theta, h0);
            println!("stiction {}: order {order:.2} at θ = {theta}", case.name);
            assert!(
                (0.8..1.5).contains(&order),
                "{}: θ = {theta} order {order}",
                case.name
            );
        }
    }
}

#[test]
fn a_stuck_body_moves_with_its_belt_to_the_last_bit() {
    let system = belt(ModelId::Static, 1.0, BELT_K, BELT_V);
    let run = stepped(&system, 0.5, 1e-3, 2.0, &[]);
    let stuck: Vec<_> = run
        .body(0)
        .into_iter()
        .filter(|b| b.mode == Some(STICK))
        .collect();
    assert!(stuck.len() > 500, "{} stuck steps", stuck.len());
    for b in stuck {
        assert_eq!(b.v, BELT_V, "t = {}", b.t);
    }
}

#[test]
fn the_energy_balance_holds_to_rounding_at_theta_half_and_shows_the_dissipation_of_theta_one() {
    let system = belt(ModelId::Static, 1.0, BELT_K, BELT_V);
    let balance = |theta, h| stepped(&system, theta, h, 2.0, &[2.0]).energy().unwrap();
    let half = balance(0.5, 1e-3);
    assert!(half.relative_residual < 1e-12, "{half:?}");
    assert!(half.friction_work > 0.1, "{half:?}");
    // θ = 1 loses energy in proportion to h: the residual Δ(kinetic + spring) − work is
    // negative and halves with h.
    let (coarse, fine) = (balance(1.0, 2e-3), balance(1.0, 1e-3));
    assert!(coarse.residual < 0.0, "{coarse:?}");
    let ratio = coarse.residual / fine.residual;
    assert!((1.8..2.2).contains(&ratio), "ratio {ratio}");
}

#[test]
fn a_100_block_chain_time_stepped_converges_to_the_event_driven_solution() {
    let c = ChainParams {
        n_bodies: 100,
        ..ChainParams::default()
    };
    let system = c
        .build(&FrictionParams::paper(), |p| {
            ModelId::Coulomb.build(Variant::Odd, p).map(Arc::from)
        })
        .unwrap();
    let t_end = 20.0;
    let reference = simulate(
        &system,
        Scheme::EventDriven {
            solver: Solver::DOPRI5,
            switching: Switching::Event,
        },
        Options {
            output: Output::GridOnly(vec![t_end]),
            ..Options::adaptive(0.0, t_end, 1e-11, 1e-13)
        },
        &mut |_| {},
    )
    .unwrap();
    let deviation = |h| {
        let run = stepped(&system, 0.5, h, t_end, &[t_end]);
        let sweeps = run.solution.stats.rhs_evals as f64 / run.solution.stats.steps as f64;
        let d = run
            .final_states()
            .iter()
            .zip(reference.final_states())
            .fold(0.0, |w: f64, (a, b)| w.max((a.x - b.x).abs()));
        (d, sweeps)
    };
    let (coarse, sweeps) = deviation(1e-2);
    let (fine, _) = deviation(2.5e-3);
    assert!(fine < 2e-4, "deviation {fine:e} at h = 2.5e-3");
    assert!(coarse / fine > 8.0, "{coarse:e} -> {fine:e}");
    assert!(sweeps < 6.0, "{sweeps} Gauss–Seidel sweeps per step");
}

#[test]
fn bad_theta_and_tolerances_are_refused_with_their_range() {
    let system = belt(ModelId::Coulomb, 1.0, BELT_K, BELT_V);
    let run = |scheme, step| {
        let options = Options {
            step,
            ..Options::fixed(0.0, 1.0, 1e-3)
        };
        simulate(&system, scheme, options, &mut |_| {})
            .unwrap()
            .error
    };
    let fixed = StepControl::Fixed { h: 1e-3 };
    assert_eq!(
        run(Scheme::TimeStepping { theta: 0.3 }, fixed),
        Some(SolverError::InvalidOption {
            name: "theta",
            value: 0.3,
            allowed: "[0.5, 1]"
        })
    );
    let adaptive = StepControl::Adaptive {
        rtol: 1e-6,
        atol: 1e-8,
        h0: None,
    };
    let e = run(Scheme::TimeStepping { theta: 0.5 }, adaptive).unwrap();
    assert!(e.to_string().contains("fixed step"), "{e}");
}

/// Largest deviation of x and v from a run `reference` at the grid points `g` (both runs
/// also record their switches, at times of their own).
fn deviation(run: &Run, reference: &Run, g: &[f64]) -> f64 {
    let on_grid =
        |r: &Run| -> Vec<_> { r.body(0).into_iter().filter(|b| g.contains(&b.t)).collect() };
    let (a, b) = (on_grid(run), on_grid(reference));
    assert_eq!(a.len(), g.len());
    a.iter().zip(&b).fold(0.0, |w: f64, (a, b)| {
        w.max((a.x - b.x).abs()).max((a.v - b.v).abs())
    })
}

#[test]
fn models_with_an_internal_state_converge_at_second_order_at_theta_half() {
    // Dahl + viscous (DV), LuGre and GMS (four slip blocks, a state each) on the belt: their
    // friction is continuous in v, so there is no break-away jump; the internal states are
    // integrated by the θ-method with the velocity.
    for (model, h0) in [
        (ModelId::Dv, 2e-3),
        (ModelId::LuGre, 2e-4),
        (ModelId::Gms, 2e-4),
    ] {
        let system = belt(model, 1.0, BELT_K, BELT_V);
        let t_end = 1.0;
        let g = grid(t_end, 200);
        let reference = simulate(
            &system,
            Scheme::EventDriven {
                solver: Solver::BDF,
                switching: Switching::Event,
            },
            Options {
                output: Output::Grid(g.clone()),
                ..Options::adaptive(0.0, t_end, 1e-11, 1e-13)
            },
            &mut |_| {},
        )
        .unwrap();
        assert!(reference.error.is_none(), "{:?}", reference.error);
        let coarse = deviation(&stepped(&system, 0.5, h0, t_end, &g), &reference, &g);
        let fine = deviation(&stepped(&system, 0.5, h0 / 4.0, t_end, &g), &reference, &g);
        let order = (coarse / fine).log(4.0);
        println!("{model:?} on the belt: order {order:.2} at θ = 1/2");
        assert!(
            (1.8..2.3).contains(&order),
            "{model:?}: {coarse:e} -> {fine:e}, order {order}"
        );
    }
}

/// A catalog law behind the trait's defaults: it does not say that it ignores x, so
/// time-stepping evaluates its stick interval and its forces at v_rel = 0± at every step.
#[derive(Debug)]
struct Opaque(Box<dyn friction_models::FrictionModel>);

impl friction_models::FrictionModel for Opaque {
    fn name(&self) -> &str {
        "opaque"
    }
    fn n_states(&self) -> usize {
        self.0.n_states()
    }
    fn evaluate(
        &self,
        x: f64,
        v: f64,
        z: &[f64],
        law: friction_models::SignLaw,
        rate: &mut [f64],
        states: &mut [friction_models::StatePartials],
    ) -> (f64, friction_models::Partials) {
        self.0.evaluate(x, v, z, law, rate, states)
    }
    fn stick_interval(&self, x: f64, z: &[f64]) -> friction_models::StickInterval {
        self.0.stick_interval(x, z)
    }
}

/// The 30-block chain with `model` on every block, its law behind [`Opaque`] (the trait's
/// defaults: depends on x, not affine) if `opaque`.
fn chain_of(model: ModelId, opaque: bool) -> System {
    ChainParams {
        n_bodies: 30,
        ..ChainParams::default()
    }
    .build(&FrictionParams::paper(), |p| {
        let law = model.build(Variant::Odd, p)?;
        Ok::<_, friction_models::ParamError>(if opaque {
            Arc::new(Opaque(law)) as Arc<dyn friction_models::FrictionModel>
        } else {
            Arc::from(law)
        })
    })
    .unwrap()
}

#[test]
fn a_static_map_kept_from_step_to_step_gives_the_same_steps_bit_for_bit() {
    // CVS (stiction, Stribeck, viscous) on a 30-block chain that sticks and slips: the law
    // at rest evaluated once per run (the catalog's law says it ignores x) against once per
    // step (the same law behind the trait's defaults).
    let (kept, evaluated) = (chain_of(ModelId::Cvs, false), chain_of(ModelId::Cvs, true));
    let g = grid(30.0, 300);
    let a = stepped(&kept, 0.5, 1e-3, 30.0, &g);
    let b = stepped(&evaluated, 0.5, 1e-3, 30.0, &g);
    assert!(a.solution.stats.events > 30, "{:?}", a.solution.stats);
    assert_eq!(a.solution.y, b.solution.y);
    assert_eq!(a.solution.modes, b.solution.modes);
    assert_eq!(a.solution.stats, b.solution.stats);
}

#[test]
fn an_affine_law_in_closed_form_takes_newtons_steps_without_a_newton_iteration() {
    // Coulomb (69 switches) and Karnopp (Coulomb, viscous and stiction: 768) on the 30-block
    // chain over 30 s: the sliding equation in closed form against Newton's iteration on the
    // same law behind the trait's defaults. The same sweeps, switches and modes; the states
    // within the sweeps' tolerance; no Newton iteration in closed form.
    for model in [ModelId::Coulomb, ModelId::Karnopp] {
        let (closed, newton) = (chain_of(model, false), chain_of(model, true));
        let g = grid(30.0, 300);
        let a = stepped(&closed, 0.5, 1e-3, 30.0, &g);
        let b = stepped(&newton, 0.5, 1e-3, 30.0, &g);
        let (sa, sb) = (&a.solution.stats, &b.solution.stats);
        assert!(sa.events > 50, "{model:?}: {sa:?}");
        assert_eq!(sa.newton_iterations, 0, "{model:?}");
        assert!(sb.newton_iterations > sa.steps, "{model:?}: {sb:?}");
        assert_eq!(
            (sa.steps, sa.rhs_evals, sa.events),
            (sb.steps, sb.rhs_evals, sb.events),
            "{model:?}"
        );
        assert_eq!(a.solution.modes, b.solution.modes, "{model:?}");
        let gap = a
            .solution
            .y
            .iter()
            .zip(&b.solution.y)
            .map(|(p, q)| (p - q).abs() / p.abs().max(1.0))
            .fold(0.0, f64::max);
        assert!(gap < 1e-10, "{model:?}: {gap:e}");
    }
}

/// A law whose sliding force at rest (10 N) lies outside its stick interval [−1, 1] N.
#[derive(Debug)]
struct Inconsistent;

impl friction_models::FrictionModel for Inconsistent {
    fn name(&self) -> &str {
        "inconsistent"
    }
    fn n_states(&self) -> usize {
        0
    }
    fn evaluate(
        &self,
        _x: f64,
        v: f64,
        _z: &[f64],
        law: friction_models::SignLaw,
        _rate: &mut [f64],
        _states: &mut [friction_models::StatePartials],
    ) -> (f64, friction_models::Partials) {
        (
            10.0 * law.branches(v).sign(),
            friction_models::Partials::default(),
        )
    }
    fn stick_interval(&self, _x: f64, _z: &[f64]) -> friction_models::StickInterval {
        friction_models::StickInterval {
            lower: -1.0,
            upper: 1.0,
        }
    }
}

#[test]
fn a_contact_without_a_solution_fails_the_step_with_where_and_why() {
    // The driver spring (10 N/m at 0.1 m/s) needs 1 N after 1 s: then neither rest nor
    // sliding forwards (10 N at once) balances it.
    let system = ChainParams {
        n_bodies: 1,
        ..ChainParams::default()
    }
    .build(&FrictionParams::paper(), |_| {
        Ok::<_, friction_models::ParamError>(Arc::new(Inconsistent) as _)
    })
    .unwrap();
    let options = Options::fixed(0.0, 3.0, 1e-3);
    let scheme = Scheme::TimeStepping { theta: 0.5 };
    let run = simulate(&system, scheme, options, &mut |_| {}).unwrap();
    let Some(SolverError::ContactProblem { t, why, .. }) = &run.error else {
        panic!("{:?}", run.error);
    };
    assert!((*t - 1.0).abs() < 2e-3, "failed at t = {t}");
    assert!(
        why.contains("contact 1") && why.contains("no sliding solution in direction Positive"),
        "{why}"
    );
    assert!(why.contains("stick interval [-1, 1]"), "{why}");
    // What was computed before the failure is kept, and what it cost: a single body, one
    // sweep in each step it took and one in the step that failed.
    assert!(
        run.solution.t.last().is_some_and(|&last| last > 0.99),
        "{:?}",
        run.solution.t.last()
    );
    let stats = &run.solution.stats;
    assert_eq!(stats.rhs_evals, stats.steps + 1, "{stats:?}");
}

/// Two free bodies (no contact) joined by a spring, m1 = 1 kg at 1 m/s and m2 = 2 kg at rest:
/// the centre of mass moves at V = 1/3 m/s and the separation r = x2 − x1 oscillates,
/// r = −sin(ω t)/ω with ω = √(k/μ), μ = m1·m2/(m1 + m2). Returns the system and (x1, x2) at t.
fn free_pair() -> (System, impl Fn(f64) -> (f64, f64)) {
    let (m1, m2, k) = (1.0, 2.0, 50.0);
    let mut s = System::default();
    let a = s.add_body("a", m1, 0.0, 1.0);
    let b = s.add_body("b", m2, 0.0, 0.0);
    s.add_spring(End::Body(a), End::Body(b), k, 0.0);
    let (total, mu) = (m1 + m2, m1 * m2 / (m1 + m2));
    let omega = (k / mu).sqrt();
    let exact = move |t: f64| {
        let (centre, r) = (t / 3.0, -(omega * t).sin() / omega);
        (centre - m2 / total * r, centre + m1 / total * r)
    };
    (s, exact)
}

#[test]
fn free_bodies_keep_momentum_and_energy_to_the_sweeps_tolerance_and_converge_at_order_two() {
    let (system, exact) = free_pair();
    let t_end = 2.0;
    let deviation = |h: f64| {
        let run = stepped(&system, 0.5, h, t_end, &[]);
        let (a, b) = (run.body(0), run.body(1));
        // The scheme conserves momentum; the sweeps leave each step a residual below
        // Σ Ŵ_i·(SWEEP_ATOL + SWEEP_RTOL·|v_i|) ≤ 3·(1e-14 + 1e-12) (Ŵ ≈ m, |v| ≤ 1).
        let per_step = 3.0 * (SWEEP_ATOL + SWEEP_RTOL);
        let mut worst: f64 = 0.0;
        for (k, (pa, pb)) in a.iter().zip(&b).enumerate() {
            let drift = (pa.v + 2.0 * pb.v - 1.0).abs();
            assert!(
                drift <= k as f64 * per_step,
                "momentum drift {drift:e} after {k} steps"
            );
            let (xa, xb) = exact(pa.t);
            worst = worst.max((pa.x - xa).abs()).max((pb.x - xb).abs());
        }
        // The same residuals, times velocities of at most 1 m/s, are the energy balance's.
        let balance = run.energy().unwrap();
        let steps = a.len() - 1;
        assert!(
            balance.residual.abs() <= steps as f64 * per_step,
            "{balance:?}"
        );
        worst
    };
    let (coarse, fine) = (deviation(2e-3), deviation(1e-3));
    let order = (coarse / fine).log2();
    assert!(
        (1.9..2.1).contains(&order),
        "order {order} ({coarse:e}, {fine:e})"
    );
}

#[test]
fn a_stiff_chain_keeps_the_energy_balance_through_newtons_corrections() {
    // 30 Coulomb blocks, k_chain = 1e8 N/m (h²θ²k/m = 25), 10 s of which the last 4 slide:
    // the corrections change how a step's velocities are found, not what they are, so the
    // discrete balance still holds to rounding and the sweeps' tolerance at θ = 1/2.
    let system = ChainParams {
        n_bodies: 30,
        k_chain: 1e8,
        ..ChainParams::default()
    }
    .build(&FrictionParams::paper(), |p| {
        ModelId::Coulomb.build(Variant::Odd, p).map(Arc::from)
    })
    .unwrap();
    let run = stepped(&system, 0.5, 1e-3, 10.0, &grid(10.0, 11));
    let stats = &run.solution.stats;
    assert!(stats.lu_factorizations > 1000, "{stats:?}");
    assert!(stats.rhs_evals < 3 * stats.steps, "{stats:?}");
    let balance = run.energy().unwrap();
    // Observed: 2.6e-14, with 4 688 corrections and 2.4 sweeps a step.
    assert!(balance.relative_residual < 1e-12, "{balance:?}");
}
