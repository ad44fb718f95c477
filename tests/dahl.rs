//! Dahl's differential law integrated by the solvers along the paper's motion
//! X(t) = t³/3 + t²/2 reproduces the printed closed form F_c(1 − exp(−σ|X|/F_c)).

use friction_lab::friction_models::{
    terms, FrictionModel, FrictionParams, ModelId, SignLaw, Variant,
};
use friction_lab::integrators::{Mode, OdeProblem, Options, Solver};

struct PrescribedDahl<'a>(&'a dyn FrictionModel);

impl OdeProblem for PrescribedDahl<'_> {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        let (x, v) = (t.powi(3) / 3.0 + t * t / 2.0, t * (t + 1.0));
        self.0.response(x, v, y, SignLaw::Discontinuous, f);
    }
}

#[test]
fn integrated_dahl_state_matches_the_closed_form_to_1e_10() {
    let p = FrictionParams::paper();
    for id in [ModelId::Dv, ModelId::Sd, ModelId::Sv, ModelId::Dahl] {
        let model = id.build(Variant::Odd, &p).unwrap();
        let problem = PrescribedDahl(model.as_ref());
        for (solver, options) in [
            (Solver::RK4, Options::fixed(0.0, 2.0, 1e-3)),
            (Solver::DOPRI5, Options::adaptive(0.0, 2.0, 1e-13, 1e-13)),
        ] {
            let s = solver.solve(&problem, &[0.0], &[Mode(0)], options).unwrap();
            for i in 1..s.len() {
                let t = s.t[i];
                let x = t.powi(3) / 3.0 + t * t / 2.0;
                let closed = terms::dahl_closed_form(p.sigma, p.f_c, x, 1.0);
                let z = s.y_at(i)[0];
                assert!(
                    (z - closed).abs() <= 1e-10 * closed.abs(),
                    "{id} with {}: z({t}) = {z} vs {closed}",
                    solver.name()
                );
            }
        }
    }
}
