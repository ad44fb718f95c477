//! No heap allocation on a Moreau–Jean step that neither records nor switches: a counting
//! global allocator (counting only on the test's own thread) watches 1000 steps after 50 of
//! warm-up, on a system that exercises every path of the step: springs between bodies and to
//! anchors with dampers, an external force with a profile, and contacts solved in closed form
//! (Coulomb), by Newton's method (CVS), with an internal state (LuGre) and with several (GMS,
//! four slip blocks); and, with stiff springs between the blocks, Newton's correction of the
//! sweeps at every step.

use friction_models::{FrictionParams, ModelId, Variant};
use friction_systems::{simulate, End, Profile, Scheme, System};
use integrators::counting::Counting;
use integrators::{Options, Output};
use std::sync::Arc;

#[global_allocator]
static GLOBAL: Counting = Counting;

const WARM_UP: usize = 50;
const WATCHED: usize = 1000;

/// Five blocks on a belt running at −5 m/s (so each slides forward throughout), each held by
/// a damped spring to a wall, neighbours joined by damped springs, the middle one pushed by a
/// ramp; laws Coulomb, CVS, LuGre, GMS, Coulomb; neighbours joined with stiffness
/// `k_neighbours`, N/m.
fn sliding_chain(k_neighbours: f64) -> System {
    let p = FrictionParams::paper();
    let mut s = System::default();
    let wall = s.add_anchor("wall", 0.0, 0.0);
    let laws = [
        ModelId::Coulomb,
        ModelId::Cvs,
        ModelId::LuGre,
        ModelId::Gms,
        ModelId::Coulomb,
    ];
    for (i, law) in laws.into_iter().enumerate() {
        let body = s.add_body(format!("b{i}"), 1.0, 0.0, 0.0);
        s.add_spring(End::Anchor(wall), End::Body(body), 100.0, 0.5);
        if i > 0 {
            s.add_spring(End::Body(body - 1), End::Body(body), k_neighbours, 0.2);
        }
        let model = law.build(Variant::Odd, &p).expect("paper parameters");
        s.add_contact(body, -5.0, Arc::from(model));
    }
    s.add_force(2, 1.0, Profile::Ramp { rate: 0.5 });
    s
}

/// Allocations during steps WARM_UP + 1 ..= WARM_UP + WATCHED of the time-stepped run at θ
/// of the chain joined by `k_neighbours`, the run's number of switching steps and of Newton's
/// corrections.
fn allocations(theta: f64, k_neighbours: f64) -> (usize, usize, usize) {
    let system = sliding_chain(k_neighbours);
    let (h, t_end) = (1e-3, 2.0);
    let options = Options {
        output: Output::GridOnly(vec![t_end]),
        ..Options::fixed(0.0, t_end, h)
    };
    let (mut steps, mut allocations) = (0, usize::MAX);
    let mut observe = |_t: f64| {
        steps += 1;
        if steps == WARM_UP {
            Counting::start();
        } else if steps == WARM_UP + WATCHED {
            allocations = Counting::stop();
        }
    };
    let scheme = Scheme::TimeStepping { theta };
    let run = simulate(&system, scheme, options, &mut observe).expect("valid");
    assert!(run.error.is_none(), "{:?}", run.error);
    assert_eq!(run.solution.stats.steps, 2000);
    let stats = &run.solution.stats;
    (allocations, stats.events, stats.lu_factorizations)
}

#[test]
fn a_step_that_neither_records_nor_switches_allocates_nothing() {
    for theta in [0.5, 1.0] {
        let (allocations, switches, corrections) = allocations(theta, 50.0);
        assert_eq!(switches, 0, "θ = {theta}: every block slides throughout");
        assert_eq!(corrections, 0, "θ = {theta}: weak coupling, no correction");
        assert_eq!(
            allocations, 0,
            "θ = {theta}: allocations in {WATCHED} steps"
        );
    }
}

#[test]
fn a_step_with_newtons_correction_allocates_nothing() {
    // h²θ²k/m = 25 at θ = 1/2: Gauss–Seidel alone would need tens of sweeps a step.
    for theta in [0.5, 1.0] {
        let (allocations, switches, corrections) = allocations(theta, 1e8);
        assert_eq!(switches, 0, "θ = {theta}: every block slides throughout");
        assert!(
            corrections >= WATCHED,
            "θ = {theta}: {corrections} corrections"
        );
        assert_eq!(
            allocations, 0,
            "θ = {theta}: allocations in {WATCHED} steps"
        );
    }
}
