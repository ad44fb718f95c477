//! `auto`: Dormand–Prince until a trial step of Radau IIA five times as long is accepted
//! (LSODA's rule) or Hairer's stiffness test fires, then Radau IIA(5), and back when
//! Dormand–Prince could take Radau's steps stably; every switch recorded.

mod common;

use common::Arenstorf;
use integrators::auto::TRIAL_HLAMB;
use integrators::testset;
use integrators::{MethodSwitch, Mode, OdeProblem, Options, Output, Solution, Solver, SwitchRule};

fn solve(solver: Solver, problem: &dyn OdeProblem, y0: &[f64], t_end: f64) -> Solution {
    solve_at(solver, problem, (y0, t_end), 1e-6, 1e-6)
}

fn solve_at(
    solver: Solver,
    problem: &dyn OdeProblem,
    (y0, t_end): (&[f64], f64),
    rtol: f64,
    atol: f64,
) -> Solution {
    let mut o = Options::adaptive(0.0, t_end, rtol, atol);
    o.output = Output::GridOnly(vec![t_end]);
    solver.solve(problem, y0, &[Mode(0)], o).unwrap()
}

/// A switch to Radau IIA is decided by a trial step, where h·ρ̂ reached the trial threshold,
/// or by Hairer's test, where it passed 3.25.
fn check_switch_to_radau(s: &MethodSwitch) {
    assert_eq!(s.to, "radau5", "{s:?}");
    match s.rule {
        SwitchRule::StepRatio => assert!(s.estimate >= TRIAL_HLAMB, "{s:?}"),
        SwitchRule::StiffnessTest => assert!(s.estimate > 3.25, "{s:?}"),
        SwitchRule::StabilityBound => panic!("{s:?}"),
    }
}

#[test]
fn a_problem_that_is_never_stiff_is_dormand_prince_alone() {
    // The Arenstorf orbit: auto takes Dormand–Prince's steps, value for value.
    let t_end = common::ARENSTORF_T_END;
    let auto = solve(Solver::AUTO, &Arenstorf, &common::ARENSTORF_Y0, t_end);
    let dopri5 = solve(Solver::DOPRI5, &Arenstorf, &common::ARENSTORF_Y0, t_end);
    assert!(
        auto.method_switches.is_empty(),
        "{:?}",
        auto.method_switches
    );
    assert_eq!(auto.y, dopri5.y);
    assert_eq!(auto.stats, dopri5.stats);
    assert_eq!(auto.stiffness_detected_at, None);
}

#[test]
fn a_stiff_problem_switches_to_radau_and_costs_what_radau_costs() {
    let p = testset::named("van-der-pol").unwrap();
    let auto = solve(Solver::AUTO, p.problem, p.y0, p.t_end);
    let radau = solve(Solver::RADAU5, p.problem, p.y0, p.t_end);
    let first = auto.method_switches[0];
    check_switch_to_radau(&first);
    assert_eq!(auto.stiffness_detected_at, Some(first.t));
    // Within a factor two of Radau's evaluations (Dormand–Prince alone needs over a million
    // steps here), and as accurate as the tolerance asks.
    assert!(
        auto.stats.rhs_evals < 2 * radau.stats.rhs_evals,
        "{} against {}",
        auto.stats.rhs_evals,
        radau.stats.rhs_evals
    );
    assert!(p.scd(auto.last().unwrap().1) > 5.0);
}

#[test]
fn the_oregonator_switches_both_ways_and_every_switch_is_recorded() {
    // OREGO's relaxation oscillation is stiff on its slow branches and not during the fast
    // jumps: auto goes back to Dormand–Prince and returns, alternating.
    let p = testset::named("orego").unwrap();
    let auto = solve(Solver::AUTO, p.problem, p.y0, p.t_end);
    let switches = &auto.method_switches;
    assert!(switches.len() >= 3, "{switches:?}");
    for (i, s) in switches.iter().enumerate() {
        if i % 2 == 0 {
            check_switch_to_radau(s);
        } else {
            assert_eq!(
                (s.to, s.rule),
                ("dopri5", SwitchRule::StabilityBound),
                "{s:?}"
            );
            assert!(s.estimate <= 3.25, "{s:?}");
        }
    }
    assert!(switches.windows(2).all(|w| w[0].t < w[1].t));
    assert!(p.scd(auto.last().unwrap().1) > 5.0);
}

#[test]
fn robertson_switches_within_its_transient_and_costs_what_radau_costs() {
    // Issue 58's case: at rtol 1e-10 Hairer's test alone fired only at t = 39.81, after
    // 245,709 evaluations of f; h·ρ̂ stayed below 3.25 while stability bounded the step.
    // The trial step switches within the initial transient (t < 0.1).
    let p = testset::named("robertson").unwrap();
    let (rtol, atol) = (1e-10, 1e-16);
    let auto = solve_at(Solver::AUTO, p.problem, (p.y0, 40.0), rtol, atol);
    let radau = solve_at(Solver::RADAU5, p.problem, (p.y0, 40.0), rtol, atol);
    let first = auto.method_switches[0];
    check_switch_to_radau(&first);
    assert_eq!(first.rule, SwitchRule::StepRatio, "{first:?}");
    assert!(first.t < 0.1, "{first:?}");
    assert!(
        auto.stats.rhs_evals < 2 * radau.stats.rhs_evals,
        "{} against {}",
        auto.stats.rhs_evals,
        radau.stats.rhs_evals
    );
}
