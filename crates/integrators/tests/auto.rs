//! `auto`: Dormand–Prince until Hairer's stiffness test fires, then Radau IIA(5), and back when
//! Dormand–Prince could take Radau's steps stably; every switch recorded.

mod common;

use common::Arenstorf;
use integrators::testset;
use integrators::{Mode, OdeProblem, Options, Output, Solution, Solver};

fn solve(solver: Solver, problem: &dyn OdeProblem, y0: &[f64], t_end: f64) -> Solution {
    let mut o = Options::adaptive(0.0, t_end, 1e-6, 1e-6);
    o.output = Output::GridOnly(vec![t_end]);
    solver.solve(problem, y0, &[Mode(0)], o).unwrap()
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
    assert_eq!(first.to, "radau5");
    assert!(first.estimate > 3.25, "{first:?}");
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
        let to = if i % 2 == 0 { "radau5" } else { "dopri5" };
        assert_eq!(s.to, to, "{switches:?}");
        if to == "radau5" {
            assert!(s.estimate > 3.25, "{s:?}");
        } else {
            assert!(s.estimate <= 3.25, "{s:?}");
        }
    }
    assert!(switches.windows(2).all(|w| w[0].t < w[1].t));
    assert!(p.scd(auto.last().unwrap().1) > 5.0);
}
