//! The convergence study: observed orders of every error measure against a reference, over
//! each method's asymptotic range ([`super::orders`]).

use super::orders::{orders, Fit, PairOrder, MIN_PAIRS, ORDER_AGREEMENT};
use super::{run_against_reference, ErrorMeasure, Method, Reference, StepKind};
use super::{StudyCase, StudyRun};
use crate::error::ScenarioError;
use crate::errors::Scales;
use friction_models::params::show;
use serde::ser::SerializeStruct;
use serde::{Serialize, Serializer};

/// What one method's error does under refinement of one measure: the local order of each
/// pair, and the fit over the asymptotic range, if there is one. Over step sizes the fit's
/// slope is the observed **order**; over tolerances (adaptive methods) it is the exponent of
/// **tolerance proportionality**, error ∝ tol^a, which is not an order in h and is never
/// called one.
#[derive(Clone, Debug, PartialEq)]
pub struct OrderTable {
    /// The method's label ([`Method::label`]).
    pub solver: String,
    /// Which error.
    pub measure: ErrorMeasure,
    /// What the resolutions are: step sizes (`fixed`) or tolerances (`adaptive`).
    pub step: StepKind,
    /// Each refinement pair, coarse to fine.
    pub pairs: Vec<PairOrder>,
    /// The fit over the asymptotic range; `None` where fewer than two pairs are in it.
    pub fit: Option<Fit>,
    /// The method's formal order p in the step size (error = O(h^p)), for fixed steps;
    /// `None` over tolerances, which have none.
    pub formal: Option<f64>,
}

impl OrderTable {
    /// The fitted order set beside the formal order where its 95 % interval lies wholly on
    /// one side of it, with the likely cause; `None` where the interval holds it (or holds 0,
    /// or there is no fit, or no formal order). Above: the errors are not yet asymptotic, or errors of
    /// opposite sign cancel (at a switch), so the slope overstates the order. Below: the
    /// error of the located switches, or the law's lost smoothness at v = 0 (a regularised
    /// or naive treatment), bounds the order.
    pub fn against_formal(&self) -> Option<String> {
        let (f, p) = (self.fit.as_ref()?, self.formal?);
        if f.ci[0] <= 0.0 {
            // No convergence shown: nothing to set beside an order.
            None
        } else if f.ci[0] > p {
            Some(format!(
                "above the formal order {p}: a pre-asymptotic range, or errors of opposite \
                 sign cancelling (at a switch)"
            ))
        } else if f.ci[1] < p {
            Some(format!(
                "below the formal order {p}: the switches' location error or the law's lost \
                 smoothness at v = 0 bounds it"
            ))
        } else {
            None
        }
    }

    /// The name of the fitted slope: `order` over step sizes, `tolerance_exponent` over
    /// tolerances.
    pub fn quantity(&self) -> &'static str {
        match self.step {
            StepKind::Fixed => "order",
            StepKind::Adaptive => "tolerance_exponent",
        }
    }

    /// What the table concludes, in words: the fitted order with its interval, the pairs it
    /// rests on and their range, as "order 4.00 (95 % CI 3.97 to 4.03) from 3 pairs, h 0.0025
    /// to 0.02"; "error ∝ tol^0.98 (…)" over tolerances; or "no asymptotic range" and why. An
    /// interval that holds 0 adds "no convergence shown": the error has saturated; one wholly
    /// above or below the formal order adds [`OrderTable::against_formal`].
    pub fn verdict(&self) -> String {
        let Some(f) = &self.fit else {
            return format!("no asymptotic range ({})", self.why_none());
        };
        let slope = match self.step {
            StepKind::Fixed => format!("order {:.2}", f.slope),
            StepKind::Adaptive => format!("error ∝ tol^{:.2}", f.slope),
        };
        let h = match self.step {
            StepKind::Fixed => "h",
            StepKind::Adaptive => "tol",
        };
        // Local orders that agree near 0 are an error that has saturated, not converged.
        let saturated = if f.ci[0] <= 0.0 {
            "; the interval holds 0: no convergence shown"
        } else {
            ""
        };
        let formal = self
            .against_formal()
            .map_or(String::new(), |a| format!("; {a}"));
        format!(
            "{slope} (95 % CI {:.2} to {:.2}) from {} pairs, {h} {} to {}{saturated}{formal}",
            f.ci[0],
            f.ci[1],
            f.pairs_used,
            show(f.range[0]),
            show(f.range[1])
        )
    }

    /// Why there is no fit: how many pairs were stalled, without a correct digit, at
    /// round-off or undefined, and the local orders of the usable ones, e.g. "of 4 pairs: 1
    /// stalled, 1 without a correct digit; 2 usable (3.26, 7.88), no 2 consecutive of which
    /// agree within 0.5".
    fn why_none(&self) -> String {
        if self.pairs.is_empty() {
            return "fewer than two resolutions".into();
        }
        let count = |flag: fn(&PairOrder) -> bool| self.pairs.iter().filter(|p| flag(p)).count();
        let kinds = [
            (count(|p| p.stalled), "stalled"),
            (count(|p| p.no_correct_digit), "without a correct digit"),
            (count(|p| p.round_off), "at round-off or undefined"),
        ];
        let mut named: Vec<String> = kinds
            .iter()
            .filter(|(n, _)| *n > 0)
            .map(|(n, kind)| format!("{n} {kind}"))
            .collect();
        let usable: Vec<String> = (self.pairs.iter())
            .filter(|p| p.usable())
            .map(|p| format!("{:.2}", p.order))
            .collect();
        let (n, orders) = (usable.len(), usable.join(", "));
        if n >= MIN_PAIRS {
            named.push(format!(
                "{n} usable ({orders}), no {MIN_PAIRS} consecutive of which agree within \
                 {ORDER_AGREEMENT}"
            ));
        } else if n > 0 {
            named.push(format!("{n} usable ({orders}), fewer than {MIN_PAIRS}"));
        }
        format!("of {} pairs: {}", self.pairs.len(), named.join("; "))
    }
}

/// The JSON of a table: `solver`, `measure`, `step`, `pairs`, then the fit under its own name
/// (`order` and `order_ci`, or `tolerance_exponent` and `tolerance_exponent_ci`; `null` without
/// an asymptotic range), `pairs_used`, `asymptotic_range` (finest and coarsest resolution, or
/// `null`) and `verdict`.
impl Serialize for OrderTable {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let quantity = self.quantity();
        let mut s = serializer.serialize_struct("OrderTable", 9)?;
        s.serialize_field("solver", &self.solver)?;
        s.serialize_field("measure", &self.measure)?;
        s.serialize_field("step", &self.step)?;
        s.serialize_field("pairs", &self.pairs)?;
        let fit = self.fit.as_ref();
        s.serialize_field(quantity, &fit.map(|f| f.slope))?;
        let ci = match self.step {
            StepKind::Fixed => "order_ci",
            StepKind::Adaptive => "tolerance_exponent_ci",
        };
        s.serialize_field(ci, &fit.map(|f| f.ci))?;
        s.serialize_field("pairs_used", &fit.map_or(0, |f| f.pairs_used))?;
        s.serialize_field("asymptotic_range", &fit.map(|f| f.range))?;
        s.serialize_field("verdict", &self.verdict())?;
        s.end()
    }
}

/// A convergence study.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Convergence {
    /// The reference.
    pub reference: Reference,
    /// Every run, solver by solver, coarse to fine.
    pub runs: Vec<StudyRun>,
    /// Observed orders.
    pub orders: Vec<OrderTable>,
    /// Where the reference limits the finest runs, the sentence that says so
    /// ([`Reference::limits`]).
    pub reference_limit: Option<String>,
}

/// Runs each method over the step sizes (or tolerances) against the reference and reports
/// the observed orders of every error measure that exists for it.
pub fn convergence(
    case: &dyn StudyCase,
    methods: &[Method],
    step_sizes: &[f64],
    tolerances: &[f64],
    progress: &(dyn Fn() + Sync),
) -> Result<Convergence, ScenarioError> {
    let jobs = Method::jobs(methods, step_sizes, tolerances, true);
    let (reference, ref_measures, runs) = run_against_reference(case, methods, &jobs, progress)?;
    let scales = Scales::of(&ref_measures);
    let mut tables = Vec::new();
    for method in methods {
        let label = method.label();
        let mine: Vec<&StudyRun> = runs.iter().filter(|r| r.solver == label).collect();
        let Some(step) = mine.first().map(|r| r.step) else {
            continue;
        };
        for measure in ErrorMeasure::ORDERED {
            let points: Vec<(f64, f64)> = mine
                .iter()
                .map(|r| (r.resolution, measure.of(&r.errors)))
                .collect();
            if points.iter().all(|p| p.1.is_nan() || p.1 == 0.0) {
                continue;
            }
            let (pairs, fit) = orders(&points, measure.scale(&scales, case.t_end()));
            tables.push(OrderTable {
                solver: label.clone(),
                measure,
                step,
                pairs,
                fit,
                // A solver's order (an adaptive one run at fixed steps too), or time-stepping's.
                formal: (step == StepKind::Fixed).then(|| {
                    (method.scheme.solver()).map_or(method.order_bound(), |s| s.order() as f64)
                }),
            });
        }
    }
    Ok(Convergence {
        reference_limit: reference.limits(&runs),
        reference,
        runs,
        orders: tables,
    })
}
