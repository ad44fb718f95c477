//! Radau IIA(5) and RODAS on the standard stiff test set, against the published references:
//! the significant correct digits (scd) they reach, and that tightening the tolerance by three
//! orders buys digits.

use integrators::testset::TESTSET;
use integrators::{Mode, Options, Output, Solver};

/// scd of `solver` on every problem at tolerance `tol` (Robertson's atol scaled by 1e-14, its
/// second species being of order 1e-13 at the end).
fn digits(solver: Solver, tol: f64) -> Vec<(&'static str, f64)> {
    TESTSET
        .iter()
        .map(|p| {
            let atol = if p.name == "robertson" {
                tol * 1e-14
            } else {
                tol
            };
            let mut o = Options::adaptive(0.0, p.t_end, tol, atol);
            o.output = Output::GridOnly(vec![p.t_end]);
            let s = solver.solve(p.problem, p.y0, &[Mode(0)], o).unwrap();
            let (t, y) = s.last().unwrap();
            assert_eq!(t, p.t_end, "{}", p.name);
            (p.name, p.scd(y))
        })
        .collect()
}

#[test]
fn the_stiff_solvers_reach_the_published_references() {
    for solver in [Solver::RADAU5, Solver::RODAS] {
        let loose = digits(solver, 1e-6);
        let tight = digits(solver, 1e-9);
        for ((name, a), (_, b)) in loose.iter().zip(&tight) {
            assert!(*a > 3.5, "{} on {name} at 1e-6: scd {a:.2}", solver.name());
            assert!(*b > 6.0, "{} on {name} at 1e-9: scd {b:.2}", solver.name());
            assert!(
                b - a > 1.5,
                "{} on {name}: scd {a:.2} → {b:.2}",
                solver.name()
            );
        }
    }
}
