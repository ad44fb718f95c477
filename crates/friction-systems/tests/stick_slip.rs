//! Stick–slip of a spring-held body on a belt with Coulomb friction and stiction
//! (F_s > F_c): an exactly periodic cycle with a closed form.
//!
//! m·ẍ + k·x = −F(ẋ − v_b). Stick ends at x = F_s/k (break-away, v = v_b); the slip phase
//! is x = F_c/k + A·cos(ωτ + φ), ω = √(k/m), A·cos φ = (F_s − F_c)/k, −A·ω·sin φ = v_b, and
//! ends when ẋ = v_b again, after τ = (π − 2φ)/ω, at x = (2F_c − F_s)/k, where the body
//! sticks; the stick phase lasts 2(F_s − F_c)/(k·v_b).

mod common;

use common::belt;
use friction_models::{FrictionParams, ModelId};
use friction_systems::{FrictionSystem, Switching, STICK};
use integrators::{
    Dopri5, ImplicitEuler, Integrator, NewtonKind, OdeProblem, Options, Rk4, Solution, StepControl,
    Stepper,
};

const M: f64 = 1.0;
const K: f64 = 100.0;
const V_BELT: f64 = 0.05;

fn closed_form(p: &FrictionParams) -> (f64, f64) {
    let omega = (K / M).sqrt();
    let phi = -(V_BELT / (omega * (p.f_s - p.f_c) / K)).atan();
    let slip = (std::f64::consts::PI - 2.0 * phi) / omega;
    let stick = 2.0 * (p.f_s - p.f_c) / (K * V_BELT);
    (stick + slip, stick)
}

/// The unknowns of the belt system: x, v and the three energy accumulators.
const DIM: usize = 5;

fn simulate(stepper: Box<dyn Stepper>, options: Options, switching: Switching) -> Solution {
    let system = belt(ModelId::Static, M, K, V_BELT);
    let problem = FrictionSystem::new(&system, switching);
    assert_eq!(problem.dim(), DIM);
    let y0 = problem.initial_state();
    let modes = problem.initial_modes(0.0, &y0);
    Integrator::new(&problem, stepper, &y0, &modes, options)
        .unwrap()
        .solve()
        .unwrap()
}

/// Periods between successive break-aways, and the stick durations before them (from the
/// second on: the first stick phase starts from the start-up transient, not from the cycle).
fn cycle(s: &Solution) -> (Vec<f64>, Vec<f64>) {
    let stick_starts: Vec<f64> = s
        .events
        .iter()
        .filter(|e| e.switches.iter().any(|s| s.to == STICK))
        .map(|e| e.t)
        .collect();
    let breaks: Vec<f64> = s
        .events
        .iter()
        .filter(|e| e.switches.iter().any(|s| s.from == STICK))
        .map(|e| e.t)
        .collect();
    let periods = breaks.windows(2).map(|w| w[1] - w[0]).collect();
    let sticks = breaks
        .iter()
        .skip(1)
        .map(|&b| b - stick_starts.iter().rev().find(|&&s| s < b).unwrap())
        .collect();
    (periods, sticks)
}

fn assert_cycle(s: &Solution, tolerance: f64) {
    let (period, stick) = closed_form(&FrictionParams::paper());
    let (periods, sticks) = cycle(s);
    assert!(periods.len() >= 8, "{} periods", periods.len());
    for p in &periods {
        assert!(
            (p - period).abs() < tolerance,
            "{}: period {p} vs {period}",
            s.solver
        );
    }
    for d in &sticks {
        assert!(
            (d - stick).abs() < tolerance,
            "{}: stick {d} vs {stick}",
            s.solver
        );
    }
}

#[test]
fn switched_dopri5_reproduces_the_period_and_stick_time_to_1e_8() {
    let mut o = Options::adaptive(0.0, 10.0, 1e-12, 1e-14);
    o.step = StepControl::Adaptive {
        rtol: 1e-12,
        atol: 1e-14,
        h0: None,
    };
    let stepper = Box::new(Dopri5::new(o.step, o.h_max(), o.max_steps, DIM));
    assert_cycle(&simulate(stepper, o, Switching::Event), 1e-8);
}

#[test]
fn switched_rk4_reproduces_the_period_and_stick_time_to_1e_8() {
    let o = Options::fixed(0.0, 10.0, 1e-3);
    assert_cycle(
        &simulate(Box::new(Rk4::new(1e-3, DIM)), o, Switching::Event),
        1e-8,
    );
}

#[test]
fn switched_implicit_euler_converges_to_the_cycle_at_first_order() {
    let o = Options::fixed(0.0, 10.0, 1e-4);
    let stepper = Box::new(ImplicitEuler::new(
        o.step,
        NewtonKind::Modified,
        o.h_max(),
        o.max_steps,
        DIM,
    ));
    assert_cycle(&simulate(stepper, o, Switching::Event), 1e-3);
}

#[test]
fn naive_stepping_misses_the_cycle_that_switching_finds() {
    let o = Options::fixed(0.0, 10.0, 1e-3);
    let s = simulate(Box::new(Rk4::new(1e-3, DIM)), o, Switching::Naive);
    // The exact solution never changes the sign of v_rel: it is negative while slipping and
    // exactly zero while stuck. Stepped blindly, v_rel chatters around zero instead.
    assert!(s.events.is_empty());
    let chatter = (1..s.len())
        .filter(|&i| (s.y_at(i)[1] - V_BELT) * (s.y_at(i - 1)[1] - V_BELT) < 0.0)
        .count();
    let cycles = 10.0 / closed_form(&FrictionParams::paper()).0;
    assert!(
        chatter as f64 > 2.0 * cycles,
        "{chatter} sign changes of v_rel in {cycles:.1} cycles"
    );
}

#[test]
fn before_each_switch_the_friction_is_that_of_the_mode_left() {
    // At a re-stick the friction jumps from the sliding force −F_c (v_rel → 0⁻) to the holding
    // force −k·x; at a break-away from the holding force −k·x = −F_s to −F_c. The recorded
    // point of a switch holds the force after it; `before_switches` the force before.
    let system = belt(ModelId::Static, M, K, V_BELT);
    let grid = integrators::even_grid(0.0, 5.0, 501);
    let options = Options {
        output: integrators::Output::Grid(grid),
        ..Options::adaptive(0.0, 5.0, 1e-10, 1e-12)
    };
    let run = friction_systems::simulate(
        &system,
        friction_systems::Scheme::EventDriven {
            solver: integrators::Solver::DOPRI5,
            switching: Switching::Event,
        },
        options,
        &mut |_| {},
    )
    .unwrap();
    let p = FrictionParams::paper();
    let switches: Vec<_> = run
        .contact_events()
        .into_iter()
        .filter(|e| e.from != e.to)
        .collect();
    let before = run.before_switches(0);
    assert!(switches.len() >= 8, "{} switches", switches.len());
    assert_eq!(before.len(), switches.len());
    let after = run.body(0);
    for (b, e) in before.iter().zip(&switches) {
        let a = after.iter().find(|a| a.t == e.t).unwrap();
        assert_eq!((b.t, b.x, b.v, b.mode), (a.t, a.x, a.v, Some(e.from)));
        assert_eq!(a.mode, Some(e.to));
        let holding = -K * a.x;
        let (f_before, f_after) = if e.to == STICK {
            (-p.f_c, holding)
        } else {
            (holding, -p.f_c)
        };
        assert!((b.friction - f_before).abs() < 1e-9, "{b:?} {e:?}");
        assert!((a.friction - f_after).abs() < 1e-9, "{a:?} {e:?}");
    }
    // At every break-away the holding force is −F_s.
    let breaks: Vec<f64> = before
        .iter()
        .filter(|b| b.mode == Some(STICK))
        .map(|b| b.friction)
        .collect();
    assert!(breaks.len() >= 4);
    for f in &breaks {
        assert!((f + p.f_s).abs() < 1e-8, "{breaks:?}");
    }
}
