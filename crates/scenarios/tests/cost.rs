//! The simulation cost of Table 2 (`phenomena::cost`): the cheapest adequate run of a model
//! on the two stick–slip systems meets the accuracy, is timed, and ranks the models as their
//! stiffness says.

use friction_models::ModelId;
use scenarios::phenomena::cost::{Costs, SYSTEMS, TARGET_ERROR, TIMING_REPEATS, TOLERANCES};
use scenarios::phenomena::Protocol;
use scenarios::Law;

#[test]
fn a_bristle_state_makes_stick_slip_costly_and_a_static_level_does_not() {
    let laws = [Law::from(ModelId::Static), Law::from(ModelId::LuGre)];
    let costs = Costs::of(&laws, None, &Protocol::default(), &|| {}).unwrap();
    for (name, cost) in [("static", &costs.laws[0]), ("lugre", &costs.laws[1])]
        .into_iter()
        .chain([("coulomb", &costs.coulomb)])
    {
        assert_eq!(cost.len(), SYSTEMS.len());
        for (system, run) in SYSTEMS.iter().zip(cost) {
            let run = run
                .as_ref()
                .unwrap_or_else(|e| panic!("{name} {}: {e}", system.name));
            let case = format!("{name} on the {}: {run:?}", system.description);
            assert!(run.error <= TARGET_ERROR, "{case}");
            assert!(TOLERANCES.contains(&run.tolerance), "{case}");
            let w = run.wall_time;
            assert_eq!(w.repeats, TIMING_REPEATS, "{case}");
            assert!(
                w.min <= w.median && w.median <= w.max && w.min > 0.0,
                "{case}"
            );
        }
    }
    for (s, system) in SYSTEMS.iter().enumerate() {
        // Coulomb with stiction: no state, the same switching; within a few times Coulomb's.
        let r = costs.relative_work(0, s).unwrap();
        assert!(
            (0.2..5.0).contains(&r),
            "static on {}: {r}",
            SYSTEMS[s].name
        );
        // LuGre's bristles (σ0 = 1e5 N/m, time constant 11.8 ms at v_s) make the state stiff:
        // an explicit method steps at its stability limit, an implicit one pays Jacobians and
        // factorisations; either costs more than ten times Coulomb's.
        let r = costs.relative_work(1, s).unwrap();
        assert!(r > 10.0, "lugre on {}: {r}", system.name);
    }
}
