//! Radau IIA(5) and RODAS on the standard stiff test set, against the published references:
//! the significant correct digits (scd) they reach, and that tightening the tolerance by three
//! orders buys digits.

use integrators::testset::TESTSET;
use integrators::{Mode, Options, Output, Solver};

/// scd of `solver` on every problem at tolerance `tol` (rtol = tol, atol by
/// `TestProblem::tolerances`).
fn digits(solver: Solver, tol: f64) -> Vec<(&'static str, f64)> {
    TESTSET
        .iter()
        .map(|p| {
            let (rtol, atol) = p.tolerances(tol);
            let mut o = Options::adaptive(0.0, p.t_end, rtol, atol);
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
        // RADAU5 keeps fewer digits on POLLU (tested below).
        let pairs = loose
            .iter()
            .zip(&tight)
            .filter(|((name, _), _)| *name != "pollution");
        for ((name, a), (_, b)) in pairs {
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

/// POLLU: after its fast initial transient (rate constants up to 4.4e11) RADAU5 crosses the
/// hour in a few dozen steps and keeps fewer digits than its tolerance asks (2.9 at 1e-6, 6.6
/// at 1e-10, its error spread evenly over the species); RODAS keeps more (5.2 and 9.0). Both
/// gain digits as the tolerance tightens.
#[test]
fn the_pollution_problem_meets_its_reference() {
    let at = |solver, tol| {
        digits(solver, tol)
            .into_iter()
            .find(|(name, _)| *name == "pollution")
            .unwrap()
            .1
    };
    for (solver, loose_floor, tight_floor) in
        [(Solver::RADAU5, 2.5, 6.0), (Solver::RODAS, 4.5, 8.5)]
    {
        let (loose, tight) = (at(solver, 1e-6), at(solver, 1e-10));
        assert!(
            loose > loose_floor,
            "{} at 1e-6: scd {loose:.2}",
            solver.name()
        );
        assert!(
            tight > tight_floor,
            "{} at 1e-10: scd {tight:.2}",
            solver.name()
        );
        assert!(
            tight - loose > 2.5,
            "{}: {loose:.2} → {tight:.2}",
            solver.name()
        );
    }
}
