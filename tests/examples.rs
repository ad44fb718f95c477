//! The examples run as part of the test suite, and what they print is checked.

#[allow(dead_code)]
#[path = "../examples/own_friction_law.rs"]
mod own_friction_law;

#[allow(dead_code)]
#[path = "../examples/own_solver.rs"]
mod own_solver;

#[allow(dead_code)]
#[path = "../examples/own_study.rs"]
mod own_study;

#[allow(dead_code)]
#[path = "../examples/own_rig.rs"]
mod own_rig;

#[allow(dead_code)]
#[path = "../examples/two_mass_system.rs"]
mod two_mass_system;

#[test]
fn an_own_friction_law_runs_through_simulation_and_a_study() {
    let r = own_friction_law::run();
    // Carried by the belt from x = 0 until the spring force k·v_belt·t reaches F_s.
    let (t, exact) = r.first_break_away;
    assert!((t - exact).abs() < 1e-9, "{t} vs {exact}");
    assert!(r.stick_phases >= 5, "{} stick phases", r.stick_phases);
    assert!(r.energy_residual < 1e-8, "{}", r.energy_residual);
    let order = r.rk4_order.expect("an order is observed");
    assert!((order - 4.0).abs() < 0.5, "RK4 order {order}");
    // The belt rig runs the law too (Law::Own), and breaks away at F_s/(k·v_belt).
    let (t, exact) = r.rig_break_away;
    assert!((t - exact).abs() < 1e-9, "rig: {t} vs {exact}");
    // Table 2's protocols judge it by what its equation says: a static level above the
    // kinetic one, a falling Stribeck branch, a viscous term and the stick-slip they make on
    // the belt, and with the static level the hunting of a PID-positioned mass; no internal
    // state, hence no pre-sliding, no frictional lag, no dwell time.
    let expected = [
        ("stiction", true),
        ("presliding", false),
        ("stribeck", true),
        ("viscous", true),
        ("hysteresis", false),
        ("stick_slip", true),
        ("rising_static_friction", false),
        ("hunting", true),
    ];
    let measured: Vec<(&str, bool)> = r.table2.iter().map(|(p, m)| (p.name(), *m)).collect();
    assert_eq!(measured, expected);
}

#[test]
fn an_own_two_mass_system_runs_event_driven_regularised_and_in_a_study() {
    let r = two_mass_system::run();
    assert!(r.stick_phases >= 3, "{} stick phases", r.stick_phases);
    assert!(r.switches >= 2 * r.stick_phases, "{} switches", r.switches);
    assert!(r.energy_residual < 1e-8, "{}", r.energy_residual);
    // A narrower regularisation comes closer to the switched solution.
    let [wide, narrow] = r.regularisation_gaps;
    assert!(narrow < wide / 2.0, "gaps {wide} (1e-3), {narrow} (1e-4)");
    // At tolerances down to 1e-8: Dormand–Prince's relative error on the grid follows the
    // tolerance; implicit Euler's, controlled per step, falls only like its square root
    // (docs/solvers.md).
    let [(_, dopri5), (_, implicit_euler)] = r.best_errors[..] else {
        panic!("two solvers")
    };
    assert!(dopri5 < 1e-5, "dopri5: {dopri5}");
    assert!(implicit_euler < 2e-2, "implicit-euler: {implicit_euler}");
    assert!(dopri5 < implicit_euler / 100.0);
}

#[test]
fn a_registered_solver_is_found_by_name_by_the_command_line() {
    let (solver, status) = own_solver::by_name();
    assert_eq!((solver.as_str(), status.as_str()), ("bs23", "ok"));
}

#[test]
fn an_own_solver_runs_through_simulation_and_two_studies() {
    let r = own_solver::run();
    // Both methods find the same stick-slip history, and agree to their tolerance 1e-8.
    assert_eq!(r.switches.0, r.switches.1);
    assert!(r.switches.0 >= 30, "{} switches", r.switches.0);
    assert!(r.final_gap < 1e-6, "{}", r.final_gap);
    // Third order at fixed steps, on the event times (located on its Hermite dense output)
    // as on the final state.
    for order in [r.event_order, r.final_order] {
        let order = order.expect("an order is observed");
        assert!((order - 3.0).abs() < 0.3, "bs23 order {order}");
    }
    // At 1e-8 the fifth-order pair reaches a smaller error with fewer evaluations.
    let [(e3, w3), (e5, w5)] = r.at_1e8;
    assert!(e3 < 1e-6 && e5 < 1e-7, "errors {e3}, {e5}");
    assert!(e5 < e3 && w5 < w3, "bs23 {e3} in {w3}, dopri5 {e5} in {w5}");
}

#[test]
fn a_registered_study_is_a_command_of_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("by-name");
    own_study::by_name(&out).unwrap();
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("step-counts.json")).unwrap()).unwrap();
    assert_eq!(json["orders"].as_array().map(Vec::len), Some(2));
    let names = friction_lab::study::solver_studies::STUDIES.names();
    assert_eq!(
        names,
        [
            "converge",
            "independence",
            "work-precision",
            "stiffness",
            "compare",
            "orbit",
            "continue",
            "closed-loop",
            "step-counts"
        ]
    );
}

#[test]
fn an_own_study_is_conducted_and_writes_its_files_and_figure() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("step-counts");
    let o = own_study::run(&out).unwrap();
    assert_eq!(
        o.files,
        [
            "report.md",
            "step-counts.csv",
            "step-counts.json",
            "step-counts.png",
            "step-counts.svg"
        ]
    );
    // The study's result as its JSON keeps it.
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("step-counts.json")).unwrap()).unwrap();
    // The order of each error estimate from its step counts: Dormand–Prince's embedded
    // solution is of order 4 (its slope approaches 1/5 from below as the tolerance falls: a
    // fixed cost of the start weighs less; 4.5 from 1e-7 to 1e-12), implicit Euler's
    // step-doubling estimate of order 1.
    let order = |name: &str| {
        let orders = json["orders"].as_array().unwrap();
        let o = orders.iter().find(|o| o[0] == name).unwrap();
        o[2].as_f64().unwrap()
    };
    let dopri5 = order("dopri5");
    assert!((3.8..5.0).contains(&dopri5), "{dopri5}");
    let implicit_euler = order("implicit-euler");
    assert!((implicit_euler - 1.0).abs() < 0.2, "{implicit_euler}");
    // The report is the study's section, its line reading the result.
    assert!(
        o.report.contains(
            " threads.\n\n## Step counts against the tolerance\n\npaper-block with viscous \
             (event switching), adaptive solvers, rtol = atol.\n\n- [Steps against the \
             tolerance](step-counts.png)"
        ),
        "{}",
        o.report
    );
    assert!(
        o.report.contains(&format!(
            "from the slope of its step counts: dopri5 {dopri5:.2}, implicit-euler \
             {implicit_euler:.2}.\n"
        )),
        "{}",
        o.report
    );
    // Dormand–Prince meets its tolerance within a small factor (tolerance proportionality);
    // implicit Euler, controlled per step, only its square root (docs/solvers.md).
    let runs = |name: &'static str| {
        json["runs"]
            .as_array()
            .unwrap()
            .iter()
            .filter(move |r| r["solver"] == name)
            .map(|r| (r["tol"].as_f64().unwrap(), r["error"].as_f64().unwrap()))
    };
    for (tol, error) in runs("dopri5") {
        assert!(error < 10.0 * tol, "{tol}: {error}");
    }
    let logs: Vec<(f64, f64)> = runs("implicit-euler")
        .map(|(tol, error)| (tol.ln(), error.ln()))
        .collect();
    let slope = friction_lab::scenarios::studies::slope(&logs);
    assert!((slope - 0.5).abs() < 0.1, "error ~ tol^{slope}");
    let csv = std::fs::read_to_string(out.join("step-counts.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 6 + 5);
}

#[test]
fn a_registered_rig_is_found_by_name_by_the_command_line() {
    let (scenario, status, x) = own_rig::by_name();
    assert_eq!((scenario.as_str(), status.as_str()), ("slope", "ok"));
    // Stopped for good at 2·(m·g·sin θ − F_c)/k (m = 1 kg, k = 100 N/m, F_c = 6 N).
    let exact = 2.0 * (own_rig::SLOPE.downhill(1.0) - 6.0) / 100.0;
    assert!((x - exact).abs() < 1e-9, "x {x} vs {exact}");
}

#[test]
fn an_own_rig_runs_and_is_studied_like_a_built_in_one() {
    let r = own_rig::run();
    // Coulomb friction: one half-period of sliding down to 2·(m·g·sin θ − F_c)/k, then stuck.
    let ((x, t), (x_exact, t_exact)) = r.coulomb_stop;
    assert!((x - x_exact).abs() < 1e-9 * x_exact, "x {x} vs {x_exact}");
    assert!((t - t_exact).abs() < 1e-9, "t {t} vs {t_exact}");
    assert_eq!(r.coulomb_final_mode, friction_lab::friction_systems::STICK);
    // Stiction above the downhill force: the body never moves.
    assert_eq!(r.static_largest_x, 0.0);
    // Dormand–Prince is of order 5 on the stop position.
    let order = r.dopri5_order.expect("an order is observed");
    assert!((order - 5.0).abs() < 0.5, "Dormand–Prince order {order}");
}
