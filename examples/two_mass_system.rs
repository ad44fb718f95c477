//! A system built in code: the two-mass model of brake squeal and machine-tool chatter. Mass
//! m1 sits on a belt (moving at v_belt) with the paper's CS law (Coulomb, stiction,
//! Stribeck); it is held by a spring to the frame and coupled by a spring and damper to a
//! second mass m2 that does not touch the belt. Run event-driven, regularised, and as a work–precision study, through the
//! library alone.
//!
//! Run: `cargo run --release --example two_mass_system`.

use friction_lab::friction_models::{FrictionParams, ModelId, Variant};
use friction_lab::friction_systems::{simulate, End, Scheme, Switching, System, STICK};
use friction_lab::integrators::{Options, Solver};
use friction_lab::scenarios::studies::{self, SystemCase};
use std::sync::Arc;

/// The two-mass system.
pub fn two_masses() -> System {
    let mut s = System::default();
    let frame = s.add_anchor("frame", 0.0, 0.0);
    let m1 = s.add_body("m1", 1.0, 0.0, 0.0);
    let m2 = s.add_body("m2", 0.5, 0.0, 0.0);
    s.add_spring(End::Anchor(frame), End::Body(m1), 100.0, 0.0);
    s.add_spring(End::Body(m1), End::Body(m2), 50.0, 0.2);
    let law = ModelId::Cs
        .build(Variant::Odd, &FrictionParams::paper())
        .expect("the paper's parameters are valid");
    s.add_contact(m1, 0.1, Arc::from(law));
    s
}

/// What the example computes.
pub struct Report {
    /// Switches of m1's contact in 20 s.
    pub switches: usize,
    /// Stick phases of m1.
    pub stick_phases: usize,
    /// Relative residual of the energy balance, event-driven.
    pub energy_residual: f64,
    /// |x_event − x_regularised| of m2 at the end, regularised with ε = 1e-3 and 1e-4.
    pub regularisation_gaps: [f64; 2],
    /// Solvers of the work–precision study with their smallest error.
    pub best_errors: Vec<(&'static str, f64)>,
}

/// Simulates the system and compares solvers on it.
pub fn run() -> Report {
    let system = two_masses();
    let options = || Options::adaptive(0.0, 20.0, 1e-10, 1e-12);
    let event = simulate(
        &system,
        Scheme::EventDriven {
            solver: Solver::DOPRI5,
            switching: Switching::Event,
        },
        options(),
        &mut |_| {},
    )
    .expect("a valid system");
    let exact = event.final_states()[1].x;
    let gap = |epsilon| {
        let smooth = simulate(
            &system,
            Scheme::EventDriven {
                solver: Solver::DOPRI5,
                switching: Switching::Regularized { epsilon },
            },
            options(),
            &mut |_| {},
        )
        .expect("a valid system");
        (smooth.final_states()[1].x - exact).abs()
    };
    let events = event.contact_events();
    let case = SystemCase {
        bodies: vec![0, 1],
        ..SystemCase::new("two-mass system", system.clone(), 5.0)
    };
    let wp = studies::work_precision(
        &case,
        &[Solver::DOPRI5, Solver::IMPLICIT_EULER].map(studies::Method::events),
        &[],
        &[1e-4, 1e-6, 1e-8],
        1,
        &|| {},
    )
    .expect("the study runs");
    let best_errors = ["dopri5", "implicit-euler"]
        .into_iter()
        .map(|name| {
            let best = wp
                .runs
                .iter()
                .filter(|r| r.solver == name)
                .map(|r| r.errors.grid_relative)
                .fold(f64::INFINITY, f64::min);
            (name, best)
        })
        .collect();
    Report {
        switches: events.len(),
        stick_phases: events.iter().filter(|e| e.to == STICK).count(),
        energy_residual: event.energy().map_or(f64::NAN, |e| e.relative_residual),
        regularisation_gaps: [gap(1e-3), gap(1e-4)],
        best_errors,
    }
}

fn main() {
    let r = run();
    println!(
        "m1 switched {} times, {} stick phases",
        r.switches, r.stick_phases
    );
    println!(
        "energy balance: relative residual {:.2e}",
        r.energy_residual
    );
    println!(
        "m2's final position, event-driven against regularised: {:.2e} m apart at eps = 1e-3, \
         {:.2e} m at eps = 1e-4",
        r.regularisation_gaps[0], r.regularisation_gaps[1]
    );
    for (solver, e) in &r.best_errors {
        println!("{solver}: smallest grid error {e:.2e}");
    }
}
