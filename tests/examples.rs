//! The examples run as part of the test suite, and what they print is checked.

#[allow(dead_code)]
#[path = "../examples/own_friction_law.rs"]
mod own_friction_law;

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
    // At tolerances down to 1e-8: Dormand–Prince's error follows the tolerance; implicit
    // Euler's, controlled per step, falls only like its square root (docs/solvers.md).
    let [(_, dopri5), (_, implicit_euler)] = r.best_errors[..] else {
        panic!("two solvers")
    };
    assert!(dopri5 < 1e-5, "dopri5: {dopri5}");
    assert!(implicit_euler < 1e-2, "implicit-euler: {implicit_euler}");
    assert!(dopri5 < implicit_euler / 100.0);
}
