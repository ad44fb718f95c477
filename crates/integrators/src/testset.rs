//! The standard stiff test problems, each with its published reference solution at its end
//! time: where an analyst checks a new stiff code first (Hairer & Wanner, *Solving ODEs II*,
//! sec. IV.10; F. Mazzia and F. Iavernaro, *Test Set for IVP Solvers*, Release 2.4,
//! University of Bari, 2008, whose Fortran files give the references, computed with RADAU5
//! in quadruple precision or at tolerance 1.1e-18). [`TestProblem::scd`] measures a result
//! as the test set does: significant correct digits, −log10 of the largest relative error.

// The references as the test set publishes them, trailing zeros included.
#![allow(clippy::excessive_precision)]

use crate::problem::{Entry, Mode, OdeProblem};

/// A problem of the test set: its equations, initial values, end time and reference.
pub struct TestProblem {
    /// The name the command line takes (`friction-lab testset NAME`).
    pub name: &'static str,
    /// What it models.
    pub title: &'static str,
    /// Where its reference solution is published.
    pub source: &'static str,
    /// y(0) (the problems start at t = 0).
    pub y0: &'static [f64],
    /// The end time of the reference.
    pub t_end: f64,
    /// y(t_end), as published.
    pub reference: &'static [f64],
    /// The equations.
    pub problem: &'static dyn OdeProblem,
    /// Published values at other times than `t_end`: (t, y(t)), where the problem has any.
    pub also: &'static [(f64, &'static [f64])],
    /// The absolute tolerance of a run at relative tolerance `tol`, as a multiple of it
    /// ([`TestProblem::tolerances`]): 1, but 1e-14 for Robertson, whose y2 is of order 1e-13
    /// at its end time and would keep no correct digit under atol = tol.
    pub atol_per_rtol: f64,
}

impl TestProblem {
    /// Significant correct digits of `y` at the end time: `−log10(max_i |y_i − ref_i|/|ref_i|)`
    /// (every reference component here is non-zero).
    pub fn scd(&self, y: &[f64]) -> f64 {
        digits(y, self.reference)
    }

    /// The published values at `t`: the reference at `t_end`, or one of [`TestProblem::also`];
    /// `None` at any other time.
    pub fn reference_at(&self, t: f64) -> Option<&'static [f64]> {
        if t == self.t_end {
            return Some(self.reference);
        }
        self.also.iter().find(|(at, _)| *at == t).map(|(_, y)| *y)
    }

    /// Significant correct digits of `y` at time `t` ([`TestProblem::scd`] against
    /// [`TestProblem::reference_at`]); `None` where no values are published.
    pub fn scd_at(&self, t: f64, y: &[f64]) -> Option<f64> {
        self.reference_at(t).map(|r| digits(y, r))
    }

    /// (rtol, atol) of a work–precision run at tolerance `tol`: rtol = `tol`, atol =
    /// [`TestProblem::atol_per_rtol`]·`tol`.
    pub fn tolerances(&self, tol: f64) -> (f64, f64) {
        (tol, self.atol_per_rtol * tol)
    }
}

/// `−log10(max_i |y_i − r_i|/|r_i|)`.
fn digits(y: &[f64], reference: &[f64]) -> f64 {
    let worst = y
        .iter()
        .zip(reference)
        .map(|(y, r)| ((y - r) / r).abs())
        .fold(0.0f64, f64::max);
    -worst.log10()
}

/// The test set, in listing order.
pub const TESTSET: [TestProblem; 5] = [
    TestProblem {
        name: "van-der-pol",
        title: "Van der Pol's oscillator, y1'' = ((1 − y1²)·y1' − y1)/ε with ε = 1e-6 (Hairer's \
                scaling)",
        source: "Mazzia & Iavernaro, Test Set for IVP Solvers 2.4, problem VDPOLM (vdpolm.f, \
                 t' = 1000·t, y2 = 1000·y2'): y(2) = (1.706167732170469, −0.8928097010248125)",
        y0: &[2.0, 0.0],
        t_end: 2.0,
        reference: &[0.1706167732170469e1, -0.8928097010248125],
        problem: &VanDerPol,
        also: &[],
        atol_per_rtol: 1.0,
    },
    TestProblem {
        name: "robertson",
        title: "Robertson's autocatalytic reactions (three species, rate constants 0.04, 1e4, \
                3e7)",
        source: "Mazzia & Iavernaro, Test Set for IVP Solvers 2.4, problem ROBER (rober.f): \
                 y(1e11); y(40) as Hairer & Wanner, Solving ODEs II, give it",
        y0: &[1.0, 0.0, 0.0],
        t_end: 1e11,
        reference: &[
            0.2083340149701255e-7,
            0.8333360770334713e-13,
            0.9999999791665050,
        ],
        problem: &Robertson,
        also: &[(
            40.0,
            &[0.7158270687193, 0.9185534764529e-5, 0.2841637457462],
        )],
        atol_per_rtol: 1e-14,
    },
    TestProblem {
        name: "hires",
        title: "HIRES: the growth and differentiation of plant tissue under high irradiance \
                (Schäfer 1975), eight species",
        source: "Mazzia & Iavernaro, Test Set for IVP Solvers 2.4, problem HIRES (hires.f): \
                 y(321.8122)",
        y0: &[1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0057],
        t_end: 321.8122,
        reference: &[
            0.7371312573325668e-3,
            0.1442485726316185e-3,
            0.5888729740967575e-4,
            0.1175651343283149e-2,
            0.2386356198831331e-2,
            0.6238968252742796e-2,
            0.2849998395185769e-2,
            0.2850001604814231e-2,
        ],
        problem: &Hires,
        also: &[],
        atol_per_rtol: 1.0,
    },
    TestProblem {
        name: "orego",
        title: "OREGO: the Oregonator, Field and Noyes' model of the Belousov–Zhabotinskii \
                reaction",
        source: "Mazzia & Iavernaro, Test Set for IVP Solvers 2.4, problem OREGO (orego.f): \
                 y(360)",
        y0: &[1.0, 2.0, 3.0],
        t_end: 360.0,
        reference: &[
            0.1000814870318523e1,
            0.1228178521549917e4,
            0.1320554942846706e3,
        ],
        problem: &Orego,
        also: &[],
        atol_per_rtol: 1.0,
    },
    TestProblem {
        name: "pollution",
        title: "the pollution problem: 20 species and 25 reactions of the air-pollution model \
                of the Dutch National Institute of Public Health (Verwer 1994)",
        source: "Mazzia & Iavernaro, Test Set for IVP Solvers 2.4, problem POLLU (pollu.f): \
                 y(60), computed by RADAU5 at rtol = atol = 1.1e-18 in 19-digit arithmetic",
        y0: &[
            0.0, 0.2, 0.0, 0.04, 0.0, 0.0, 0.1, 0.3, 0.01, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
            0.007, 0.0, 0.0, 0.0,
        ],
        t_end: 60.0,
        reference: &[
            0.5646255480022769e-1,
            0.1342484130422339,
            0.4139734331099427e-8,
            0.5523140207484359e-2,
            0.2018977262302196e-6,
            0.1464541863493966e-6,
            0.7784249118997964e-1,
            0.3245075353396018,
            0.7494013383880406e-2,
            0.1622293157301561e-7,
            0.1135863833257075e-7,
            0.2230505975721359e-2,
            0.2087162882798630e-3,
            0.1396921016840158e-4,
            0.8964884856898295e-2,
            0.4352846369330103e-17,
            0.6899219696263405e-2,
            0.1007803037365946e-3,
            0.1772146513969984e-5,
            0.5682943292316392e-4,
        ],
        problem: &Pollution,
        also: &[],
        atol_per_rtol: 1.0,
    },
];

/// The problem of the test set called `name`.
pub fn named(name: &str) -> Result<&'static TestProblem, String> {
    TESTSET.iter().find(|p| p.name == name).ok_or_else(|| {
        let known: Vec<_> = TESTSET.iter().map(|p| p.name).collect();
        format!(
            "unknown test problem `{name}`; known problems: {}",
            known.join(", ")
        )
    })
}

/// ε of Van der Pol's equation in Hairer's scaling.
const VDP_EPS: f64 = 1e-6;

/// `y1' = y2`, `y2' = ((1 − y1²)·y2 − y1)/ε`.
pub struct VanDerPol;

impl OdeProblem for VanDerPol {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = y[1];
        f[1] = ((1.0 - y[0] * y[0]) * y[1] - y[0]) / VDP_EPS;
    }
    fn jacobian(&self, _t: f64, y: &[f64], _m: &[Mode], jac: &mut Vec<Entry>) -> bool {
        jac.extend([
            (0, 1, 1.0),
            (1, 0, (-2.0 * y[0] * y[1] - 1.0) / VDP_EPS),
            (1, 1, (1.0 - y[0] * y[0]) / VDP_EPS),
        ]);
        true
    }
}

/// `y1' = −0.04·y1 + 1e4·y2·y3`, `y2' = 0.04·y1 − 1e4·y2·y3 − 3e7·y2²`, `y3' = 3e7·y2²`.
pub struct Robertson;

impl OdeProblem for Robertson {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
        f[2] = 3e7 * y[1] * y[1];
        f[1] = -f[0] - f[2];
    }
    fn jacobian(&self, _t: f64, y: &[f64], _m: &[Mode], jac: &mut Vec<Entry>) -> bool {
        let (p1, p2, p3) = (1e4 * y[1], 1e4 * y[2], 6e7 * y[1]);
        jac.extend([
            (0, 0, -0.04),
            (0, 1, p2),
            (0, 2, p1),
            (1, 0, 0.04),
            (1, 1, -p2 - p3),
            (1, 2, -p1),
            (2, 1, p3),
        ]);
        true
    }
}

/// HIRES (hires.f's FEVAL).
pub struct Hires;

impl OdeProblem for Hires {
    fn dim(&self) -> usize {
        8
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007;
        f[1] = 1.71 * y[0] - 8.75 * y[1];
        f[2] = -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4];
        f[3] = 8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3];
        f[4] = -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6];
        f[5] = -280.0 * y[5] * y[7] + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6];
        f[6] = 280.0 * y[5] * y[7] - 1.81 * y[6];
        f[7] = -f[6];
    }
    fn jacobian(&self, _t: f64, y: &[f64], _m: &[Mode], jac: &mut Vec<Entry>) -> bool {
        jac.extend([
            (0, 0, -1.71),
            (0, 1, 0.43),
            (0, 2, 8.32),
            (1, 0, 1.71),
            (1, 1, -8.75),
            (2, 2, -10.03),
            (2, 3, 0.43),
            (2, 4, 0.035),
            (3, 1, 8.32),
            (3, 2, 1.71),
            (3, 3, -1.12),
            (4, 4, -1.745),
            (4, 5, 0.43),
            (4, 6, 0.43),
            (5, 3, 0.69),
            (5, 4, 1.71),
            (5, 5, -280.0 * y[7] - 0.43),
            (5, 6, 0.69),
            (5, 7, -280.0 * y[5]),
            (6, 5, 280.0 * y[7]),
            (6, 6, -1.81),
            (6, 7, 280.0 * y[5]),
            (7, 5, -280.0 * y[7]),
            (7, 6, 1.81),
            (7, 7, -280.0 * y[5]),
        ]);
        true
    }
}

/// OREGO (orego.f's FEVAL): `y1' = s·(y2 + y1·(1 − q·y1 − y2))`, `y2' = (y3 − (1 + y1)·y2)/s`,
/// `y3' = w·(y1 − y3)`, s = 77.27, q = 8.375e-6, w = 0.161.
pub struct Orego;

/// OREGO's constants s, q and w.
const OREGO_S: f64 = 77.27;
const OREGO_Q: f64 = 8.375e-6;
const OREGO_W: f64 = 0.161;

impl OdeProblem for Orego {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = OREGO_S * (y[1] + y[0] * (1.0 - OREGO_Q * y[0] - y[1]));
        f[1] = (y[2] - (1.0 + y[0]) * y[1]) / OREGO_S;
        f[2] = OREGO_W * (y[0] - y[2]);
    }
    fn jacobian(&self, _t: f64, y: &[f64], _m: &[Mode], jac: &mut Vec<Entry>) -> bool {
        jac.extend([
            (0, 0, OREGO_S * (1.0 - 2.0 * OREGO_Q * y[0] - y[1])),
            (0, 1, OREGO_S * (1.0 - y[0])),
            (1, 0, -y[1] / OREGO_S),
            (1, 1, -(1.0 + y[0]) / OREGO_S),
            (1, 2, 1.0 / OREGO_S),
            (2, 0, OREGO_W),
            (2, 2, -OREGO_W),
        ]);
        true
    }
}

/// One reaction of a mass-action scheme: rate `k·Π y[reactants]`, taking one of each reactant
/// and giving one of each product (a species listed twice is taken or given twice).
struct Reaction {
    k: f64,
    reactants: &'static [usize],
    products: &'static [usize],
}

/// The 25 reactions of the pollution problem (Verwer 1994; Mazzia & Iavernaro's pollu.f,
/// `feval`), species numbered from 0: y1 is index 0.
#[rustfmt::skip]
const POLLUTION_REACTIONS: [Reaction; 25] = [
    Reaction { k: 0.35, reactants: &[0], products: &[1, 2] },
    Reaction { k: 0.266e2, reactants: &[1, 3], products: &[0] },
    Reaction { k: 0.123e5, reactants: &[4, 1], products: &[0, 5] },
    Reaction { k: 0.86e-3, reactants: &[6], products: &[4, 4, 7] },
    Reaction { k: 0.82e-3, reactants: &[6], products: &[7] },
    Reaction { k: 0.15e5, reactants: &[6, 5], products: &[4, 7] },
    Reaction { k: 0.13e-3, reactants: &[8], products: &[4, 7, 9] },
    Reaction { k: 0.24e5, reactants: &[8, 5], products: &[10] },
    Reaction { k: 0.165e5, reactants: &[10, 1], products: &[0, 9, 11] },
    Reaction { k: 0.9e4, reactants: &[10, 0], products: &[12] },
    Reaction { k: 0.22e-1, reactants: &[12], products: &[0, 10] },
    Reaction { k: 0.12e5, reactants: &[9, 1], products: &[0, 13] },
    Reaction { k: 0.188e1, reactants: &[13], products: &[4, 6] },
    Reaction { k: 0.163e5, reactants: &[0, 5], products: &[14] },
    Reaction { k: 0.48e7, reactants: &[2], products: &[3] },
    Reaction { k: 0.35e-3, reactants: &[3], products: &[15] },
    Reaction { k: 0.175e-1, reactants: &[3], products: &[2] },
    Reaction { k: 0.1e9, reactants: &[15], products: &[5, 5] },
    Reaction { k: 0.444e12, reactants: &[15], products: &[2] },
    Reaction { k: 0.124e4, reactants: &[16, 5], products: &[4, 17] },
    Reaction { k: 0.21e1, reactants: &[18], products: &[1] },
    Reaction { k: 0.578e1, reactants: &[18], products: &[0, 2] },
    Reaction { k: 0.474e-1, reactants: &[0, 3], products: &[18] },
    Reaction { k: 0.178e4, reactants: &[18, 0], products: &[19] },
    Reaction { k: 0.312e1, reactants: &[19], products: &[0, 18] },
];

/// The pollution problem: 20 species of the air-pollution model of the Dutch National
/// Institute of Public Health (RIVM) under 25 mass-action reactions
/// (the table `POLLUTION_REACTIONS`), `y' = Σ_r k_r·Π y[reactants]·(products − reactants)`.
pub struct Pollution;

impl OdeProblem for Pollution {
    fn dim(&self) -> usize {
        20
    }

    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f.fill(0.0);
        for r in &POLLUTION_REACTIONS {
            let rate = r.reactants.iter().fold(r.k, |p, &i| p * y[i]);
            r.reactants.iter().for_each(|&i| f[i] -= rate);
            r.products.iter().for_each(|&i| f[i] += rate);
        }
    }

    /// ∂rate/∂y_j for each reactant j (the product of k and the other reactants), taken from
    /// each reactant and given to each product; entries repeated are summed.
    fn jacobian(&self, _t: f64, y: &[f64], _m: &[Mode], jac: &mut Vec<Entry>) -> bool {
        for r in &POLLUTION_REACTIONS {
            for (a, &j) in r.reactants.iter().enumerate() {
                let d = (r.reactants.iter().enumerate())
                    .filter(|&(b, _)| b != a)
                    .fold(r.k, |p, (_, &i)| p * y[i]);
                r.reactants.iter().for_each(|&i| jac.push((i, j, -d)));
                r.products.iter().for_each(|&i| jac.push((i, j, d)));
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_analytic_jacobian_agrees_with_differences() {
        // At a point off the initial values (so that every entry is exercised), each column
        // against a central difference of f, exact for these right-hand sides (at most
        // quadratic in each unknown) but for rounding, which the tolerance allows: 1e-14 of
        // the largest |f| over the step.
        for p in &TESTSET {
            let n = p.problem.dim();
            let y: Vec<f64> = (0..n).map(|i| 0.3 + 0.1 * i as f64).collect();
            let mut jac = Vec::new();
            assert!(p.problem.jacobian(0.0, &y, &[], &mut jac));
            let mut f = vec![0.0; n];
            p.problem.rhs(0.0, &y, &[], &mut f);
            let f_max = f.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let mut dense = vec![0.0; n * n];
            for (i, j, v) in jac {
                dense[i * n + j] += v;
            }
            for j in 0..n {
                let h = 1e-2;
                let (mut up, mut down) = (y.clone(), y.clone());
                up[j] += h;
                down[j] -= h;
                let (mut fu, mut fd) = (vec![0.0; n], vec![0.0; n]);
                p.problem.rhs(0.0, &up, &[], &mut fu);
                p.problem.rhs(0.0, &down, &[], &mut fd);
                for i in 0..n {
                    let fd = (fu[i] - fd[i]) / (2.0 * h);
                    let tol = 1e-9 * (1.0 + fd.abs()) + 1e-14 * f_max / h;
                    assert!(
                        (dense[i * n + j] - fd).abs() < tol,
                        "{} J[{i}][{j}] = {} against {fd}",
                        p.name,
                        dense[i * n + j]
                    );
                }
            }
        }
    }

    #[test]
    fn the_problems_are_found_by_name_and_scd_counts_digits() {
        let p = named("hires").unwrap();
        assert_eq!(p.problem.dim(), p.y0.len());
        assert_eq!(p.reference.len(), p.y0.len());
        // A relative error of 1e-7 in the worst component is 7 digits.
        let y: Vec<f64> = p.reference.iter().map(|r| r * (1.0 + 1e-7)).collect();
        assert!((p.scd(&y) - 7.0).abs() < 1e-6);
        assert_eq!(p.scd_at(p.t_end, &y), Some(p.scd(&y)));
        assert_eq!(p.scd_at(100.0, &y), None);
        // Robertson's values at 40 as well as at its end time.
        let r = named("robertson").unwrap();
        let at_40: Vec<f64> = r.also[0].1.iter().map(|v| v * (1.0 - 1e-5)).collect();
        assert!((r.scd_at(40.0, &at_40).unwrap() - 5.0).abs() < 1e-6);
        assert_eq!(r.scd_at(41.0, &at_40), None);
        assert_eq!(
            named("e5").err().unwrap(),
            "unknown test problem `e5`; known problems: van-der-pol, robertson, hires, orego, pollution"
        );
    }
}
