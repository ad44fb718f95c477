//! A rig is a system of one body: the same system written as a file runs to the same numbers.

use friction_models::{FrictionParams, ModelId};
use friction_systems::Scheme;
use friction_systems::{file, simulate};
use integrators::{Solver, StepControl};
use scenarios::run::options;
use scenarios::{run, Limits, RunSpec, Scenario};

#[test]
fn a_one_body_system_file_equals_the_belt_rig() {
    let spec = RunSpec {
        scenario: Scenario::BELT,
        law: ModelId::Cvs.into(),
        friction: FrictionParams::paper(),
        params: Scenario::BELT.defaults(),
        scheme: Scheme::events(Solver::DOPRI5),
        step: StepControl::Adaptive {
            rtol: 1e-9,
            atol: 1e-11,
            h0: None,
        },
        t_end: Some(10.0),
        output_points: 101,
        limits: Limits::default(),
    };
    let rig = run(&spec, &mut |_| {}).unwrap();
    let text = r#"
        [[body]]
        name = "block"
        m = 1.0
        [[anchor]]
        name = "wall"
        [[spring]]
        between = ["block", "wall"]
        k = 100.0
        [[contact]]
        body = "block"
        surface_velocity = 0.05
        model = "CVS"
    "#;
    let system = file::parse(text).unwrap();
    let sys = simulate(&system, spec.scheme, options(&spec, 10.0), &mut |_| {}).unwrap();
    let body = sys.body(0);
    assert_eq!(body.len(), rig.rows.len());
    for (b, r) in body.iter().zip(&rig.rows) {
        assert_eq!((b.t, b.x, b.v, b.friction), (r.t, r.x, r.v, r.friction));
    }
    assert_eq!(sys.solution.stats, rig.stats);
    assert!(rig.events.len() > 10, "{} events", rig.events.len());
}
