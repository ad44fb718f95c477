//! A body at rest on a fixed surface with nothing pushing it stays at rest: x = v = 0 and
//! every internal state 0 for all t, whatever the friction law. Event-driven, a state model
//! (LuGre, Dahl, …) starts in a sliding mode exactly at v_rel = 0, with its event function
//! sitting at zero through the whole run; event location once walked back from the end of
//! the first step by its time tolerance, one evaluation at a time, and never ended (this test
//! then hangs: the run's time limit is checked between steps).

use friction_models::{FrictionParams, ModelId, Variant};
use friction_systems::{simulate, Scheme, Switching, System};
use integrators::{Options, Solver};
use std::sync::Arc;

#[test]
fn a_body_at_rest_under_no_force_stays_at_rest_with_every_model_and_solver() {
    for model in ModelId::ALL {
        let law = model
            .build(Variant::Odd, &FrictionParams::paper())
            .expect("valid parameters");
        let mut system = System::default();
        let body = system.add_body("body", 1.0, 0.0, 0.0);
        system.add_contact(body, 0.0, Arc::from(law));
        let event_driven = |solver| Scheme::EventDriven {
            solver,
            switching: Switching::Event,
        };
        for scheme in [
            event_driven(Solver::DOPRI5),
            event_driven(Solver::from_name("bdf").expect("a solver")),
            Scheme::TimeStepping { theta: 0.5 },
        ] {
            let options = match scheme {
                Scheme::TimeStepping { .. } => Options::fixed(0.0, 2.0, 1e-3),
                Scheme::EventDriven { .. } => Options::adaptive(0.0, 2.0, 1e-8, 1e-10),
            };
            let run = simulate(&system, scheme, options, &mut |_| {}).expect("a valid system");
            let case = format!("{model:?}, {scheme:?}");
            assert!(run.error.is_none(), "{case}: {:?}", run.error);
            assert_eq!(run.solution.t.last(), Some(&2.0), "{case}");
            // Every unknown at every recorded time: positions, velocities, internal states and
            // the energy accumulators.
            let moved = run.solution.y.iter().find(|&&u| u != 0.0);
            assert_eq!(moved, None, "{case}");
        }
    }
}

/// A body pushed by exactly its break-away force stays at rest: the force sits on a bound of
/// the closed stick interval for the whole run. Event-driven, the break-away function starts
/// at zero and stays there to the last bit; read as an arrival it once switched the body to
/// sliding with zero acceleration, whose velocity stayed exactly zero and was read as an
/// arrival back at rest, one switch per shortest step, until the chattering guard stopped the
/// run (docs/solvers.md, "Re-trigger guard").
#[test]
fn a_body_pushed_by_exactly_its_break_away_force_stays_at_rest() {
    let p = FrictionParams::paper();
    for (model, level) in [(ModelId::Coulomb, p.f_c), (ModelId::Static, p.f_s)] {
        let law = model.build(Variant::Odd, &p).expect("valid parameters");
        let mut system = System::default();
        let body = system.add_body("body", 1.0, 0.0, 0.0);
        system.add_contact(body, 0.0, Arc::from(law));
        system.add_force(body, level, friction_systems::Profile::None);
        for solver in [Solver::DOPRI5, Solver::from_name("bdf").expect("a solver")] {
            let scheme = Scheme::EventDriven {
                solver,
                switching: Switching::Event,
            };
            let options = Options::adaptive(0.0, 2.0, 1e-8, 1e-10);
            let run = simulate(&system, scheme, options, &mut |_| {}).expect("a valid system");
            let case = format!("{model:?} at {level} N, {solver:?}");
            assert!(run.error.is_none(), "{case}: {:?}", run.error);
            assert_eq!(run.solution.t.last(), Some(&2.0), "{case}");
            assert!(run.contact_events().is_empty(), "{case}: switched");
            let end = run.final_states()[0];
            assert_eq!((end.x, end.v), (0.0, 0.0), "{case}");
        }
    }
}
