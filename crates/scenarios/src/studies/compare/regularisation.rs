//! The model error of a regularised law: the regularised ODE solved tightly, against the true
//! nonsmooth solution, at each width ε, fitted as `ln e = ln C + p·ln ε` (least squares, with
//! the 95 % interval of p from Student's t). Where it falls (the interval of p above 0), the
//! ε a target needs is `(target/C)^(1/p)`; where it does not, its smallest level is the
//! **floor** no tolerance goes below.

use crate::studies::{line, student_t_975};
use friction_models::params::show;
use serde::{Deserialize, Serialize};

/// The model error at one width.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ModelError {
    /// The width, m/s.
    pub epsilon: f64,
    /// The width relative to the true solution's velocity scale.
    pub relative: f64,
    /// The tight regularised solution's grid error against the true solution (NaN where it
    /// failed).
    pub error: f64,
    /// Why the tight run failed.
    pub failure: Option<String>,
}

/// The fitted order of the model error in ε.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EpsilonFit {
    /// p of `e ≈ C·ε^p`.
    pub order: f64,
    /// Its 95 % interval.
    pub interval: [f64; 2],
    /// C.
    pub constant: f64,
    /// The widths fitted.
    pub points: usize,
}

/// The width, m/s, a target needs, where the model error falls with ε.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NeededWidth {
    /// The target.
    pub target: f64,
    /// `(target/C)^(1/p)`, m/s.
    pub epsilon: f64,
}

/// What the regularisation costs in accuracy.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Regularisation {
    /// The model error at each width, wide to narrow.
    pub widths: Vec<ModelError>,
    /// The fit over the widths whose tight run ended (three at least).
    pub fit: Option<EpsilonFit>,
    /// Whether the model error falls with ε: the fit's interval lies above 0.
    pub falls: bool,
    /// The smallest model error over the widths: the floor where it does not fall.
    pub floor: f64,
    /// The width each target needs (where it falls, extrapolated beyond the widths run).
    pub needed: Vec<NeededWidth>,
    /// The conclusion in words.
    pub verdict: String,
}

/// The least number of widths a fit takes: two parameters and one degree of freedom.
pub const MIN_WIDTHS: usize = 3;

impl Regularisation {
    /// The fit of `widths` and its conclusion for `targets`; `sticks`: whether the true
    /// solution has stick phases (a regularised law cannot hold a body at rest);
    /// `resolvable`: the error below which the true solution cannot resolve a difference.
    pub fn of(
        widths: Vec<ModelError>,
        targets: &[f64],
        sticks: bool,
        resolvable: f64,
    ) -> Regularisation {
        let points: Vec<(f64, f64)> = (widths.iter())
            .filter(|w| w.error.is_finite() && w.error > 0.0)
            .map(|w| (w.epsilon.ln(), w.error.ln()))
            .collect();
        let fit = (points.len() >= MIN_WIDTHS).then(|| {
            let l = line(&points);
            let n = points.len();
            let residual: f64 = (points.iter())
                .map(|(x, y)| (y - l.intercept - l.slope * x).powi(2))
                .sum();
            let se = (residual / (n - 2) as f64 / l.sxx).sqrt();
            let half = student_t_975(n - 2) * se;
            EpsilonFit {
                order: l.slope,
                interval: [l.slope - half, l.slope + half],
                constant: l.intercept.exp(),
                points: n,
            }
        });
        let floor = (widths.iter())
            .map(|w| w.error)
            .filter(|e| e.is_finite())
            .fold(f64::INFINITY, f64::min);
        let largest = (widths.iter())
            .map(|w| w.error)
            .filter(|e| e.is_finite())
            .fold(f64::NAN, f64::max);
        // Below the true solution's resolution the differences are the tight runs', not ε's.
        let unresolved = largest < resolvable;
        let falls = !unresolved && fit.as_ref().is_some_and(|f| f.interval[0] > 0.0);
        let needed = match (&fit, falls) {
            (Some(f), true) => (targets.iter())
                .map(|&target| NeededWidth {
                    target,
                    epsilon: (target / f.constant).powf(1.0 / f.order),
                })
                .collect(),
            _ => Vec::new(),
        };
        let verdict = match (&fit, falls) {
            _ if unresolved => format!(
                "at every ε the tight regularised solution lies within what the true solution \
                 resolves (largest model error {}, resolution {}): the law has no jump at \
                 v = 0 for the regularisation to smooth",
                show3(largest),
                show3(resolvable)
            ),
            (None, _) => format!(
                "fewer than {MIN_WIDTHS} widths ended: the model error's order in ε is not fitted"
            ),
            (Some(f), true) => format!(
                "the model error falls as ε^{} (95 % interval [{}, {}], {} widths)",
                show2(f.order),
                show2(f.interval[0]),
                show2(f.interval[1]),
                f.points
            ),
            (Some(f), false) => format!(
                "the model error does not fall with ε (order {}, 95 % interval [{}, {}]): a \
                 floor at {}{}",
                show2(f.order),
                show2(f.interval[0]),
                show2(f.interval[1]),
                show3(floor),
                if sticks {
                    "; the true solution sticks, and a regularised law cannot hold a body at \
                     rest: it creeps through every stick phase, and the drift accumulates in \
                     the phase of the motion"
                } else {
                    ""
                }
            ),
        };
        Regularisation {
            widths,
            fit,
            falls,
            floor,
            needed,
            verdict,
        }
    }
}

/// An error to three significant digits.
fn show3(x: f64) -> String {
    show(format!("{x:.2e}").parse().unwrap_or(x))
}

/// An order to two decimals.
fn show2(x: f64) -> String {
    format!("{x:.2}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn width(epsilon: f64, error: f64) -> ModelError {
        ModelError {
            epsilon,
            relative: epsilon,
            error,
            failure: None,
        }
    }

    #[test]
    fn a_first_order_model_error_is_fitted_and_gives_the_width_a_target_needs() {
        // e = 3·ε exactly: order 1, C = 3; the target 3e-7 needs ε = 1e-7.
        let w = (1..=5).map(|k| width(10f64.powi(-k), 3.0 * 10f64.powi(-k)));
        let r = Regularisation::of(w.collect(), &[3e-7], false, 1e-12);
        let f = r.fit.unwrap();
        assert!((f.order - 1.0).abs() < 1e-12 && (f.constant - 3.0).abs() < 1e-9);
        assert!(r.falls);
        assert!((r.needed[0].epsilon / 1e-7 - 1.0).abs() < 1e-9);
    }

    #[test]
    fn a_plateau_is_a_floor_with_its_level_and_its_cause() {
        let errors = [0.81, 0.83, 0.82, 0.80, 0.82];
        let w = (1..=5).map(|k| width(10f64.powi(-k), errors[k as usize - 1]));
        let r = Regularisation::of(w.collect(), &[1e-3], true, 1e-8);
        assert!(!r.falls && r.needed.is_empty());
        assert_eq!(r.floor, 0.80);
        assert!(r
            .verdict
            .starts_with("the model error does not fall with ε"));
        assert!(r.verdict.contains("a floor at 0.8;"), "{}", r.verdict);
    }

    #[test]
    fn a_law_without_a_jump_has_no_model_error_to_fit() {
        // Every tight regularised run within the true solution's resolution: ε changes nothing.
        let w = (1..=5).map(|k| width(10f64.powi(-k), 1.57e-8));
        let r = Regularisation::of(w.collect(), &[1e-3], false, 8.6e-7);
        assert!(!r.falls && r.needed.is_empty());
        assert!(r.verdict.contains("no jump at v = 0"), "{}", r.verdict);
    }
}
