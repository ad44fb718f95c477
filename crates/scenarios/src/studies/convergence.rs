//! The convergence study: observed orders of every error measure against a reference.

use super::{
    run_against_reference, slope, ErrorMeasure, Measures, Method, Reference, StudyCase, StudyRun,
};
use crate::run::ScenarioError;
use integrators::Solver;
use serde::Serialize;

/// The observed order between two refinements: log(e_i/e_(i+1)) / log(h_i/h_(i+1)), which
/// does not assume halving.
pub fn observed_order(e: (f64, f64), h: (f64, f64)) -> f64 {
    (e.0 / e.1).ln() / (h.0 / h.1).ln()
}

/// The order of one refinement pair, with what may make it unreliable.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PairOrder {
    /// Coarser resolution.
    pub from: f64,
    /// Finer resolution.
    pub to: f64,
    /// Observed order.
    pub order: f64,
    /// The finer error is at the round-off floor (below 1e-12 of the solution's scale), or an
    /// error of the pair is missing (not finite): the pair says nothing of the order.
    pub round_off: bool,
    /// Above that floor, the finer error did not decrease: the refinement has not reached the
    /// asymptotic range, or the error has saturated (a limit cycle's phase drift, for one,
    /// holds it at the cycle's amplitude): the pair says nothing of the order either.
    pub stalled: bool,
    /// Outside the asymptotic range: the coarser error is as large as the solution's scale
    /// (the run has no correct digit: an unstable or unresolved step), or the order differs by
    /// more than 0.5 from the median of the other usable pairs.
    pub pre_asymptotic: bool,
}

/// Orders of successive pairs of (resolution, error), and the least-squares slope of
/// log(error) against log(resolution) over the pairs that are neither round-off, stalled nor
/// pre-asymptotic (see [`PairOrder`]; `scale` is the solution's).
pub fn orders(points: &[(f64, f64)], scale: f64) -> (Vec<PairOrder>, Option<f64>) {
    let mut pairs: Vec<PairOrder> = points
        .windows(2)
        .map(|w| {
            let round_off = w[1].1 <= 1e-12 * scale || !(w[0].1.is_finite() && w[1].1.is_finite());
            let stalled = !round_off && w[1].1 >= w[0].1;
            PairOrder {
                from: w[0].0,
                to: w[1].0,
                order: observed_order((w[0].1, w[1].1), (w[0].0, w[1].0)),
                round_off,
                stalled,
                pre_asymptotic: !round_off && !stalled && w[0].1 >= scale,
            }
        })
        .collect();
    let usable = |p: &PairOrder| !p.round_off && !p.stalled && !p.pre_asymptotic;
    let mut orders: Vec<f64> = pairs
        .iter()
        .filter(|p| usable(p))
        .map(|p| p.order)
        .collect();
    orders.sort_by(f64::total_cmp);
    if let Some(&median) = orders.get(orders.len() / 2) {
        for p in pairs.iter_mut().filter(|p| usable(p)) {
            p.pre_asymptotic = (p.order - median).abs() > 0.5;
        }
    }
    // Least squares over the points joined by good pairs.
    let mut xs = Vec::new();
    for (i, p) in pairs.iter().enumerate() {
        if !p.round_off && !p.stalled && !p.pre_asymptotic {
            for point in [points[i], points[i + 1]] {
                let xy = (point.0.ln(), point.1.ln());
                if !xs.contains(&xy) {
                    xs.push(xy);
                }
            }
        }
    }
    let slope = (xs.len() >= 2).then(|| slope(&xs));
    (pairs, slope)
}

/// The scale of the solution: the largest |x| or |v| of the reference.
fn scale(reference: &Measures) -> f64 {
    reference
        .grid
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0, |a: f64, b| a.max(b.abs()))
        .max(f64::MIN_POSITIVE)
}

/// Orders for one solver and one error measure.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OrderTable {
    /// The method's label ([`Method::label`]).
    pub solver: String,
    /// Which error: `final_state`, `grid_max`, `event_times`, `stick_durations`.
    pub measure: ErrorMeasure,
    /// Each refinement pair.
    pub pairs: Vec<PairOrder>,
    /// Least-squares slope over the reliable pairs.
    pub fitted_slope: Option<f64>,
}

impl OrderTable {
    /// Why there is no fitted slope (`None` when there is one): how many pairs were stalled,
    /// pre-asymptotic, or at round-off or undefined (see [`PairOrder`]), e.g. "of 3 pairs: 2
    /// stalled, 1 pre-asymptotic".
    pub fn unfitted(&self) -> Option<String> {
        if self.fitted_slope.is_some() {
            return None;
        }
        if self.pairs.is_empty() {
            return Some("fewer than two resolutions".into());
        }
        let count = |flag: fn(&PairOrder) -> bool| self.pairs.iter().filter(|p| flag(p)).count();
        let kinds = [
            (count(|p| p.stalled), "stalled"),
            (count(|p| p.pre_asymptotic), "pre-asymptotic"),
            (count(|p| p.round_off), "at round-off or undefined"),
        ];
        let named: Vec<String> = kinds
            .iter()
            .filter(|(n, _)| *n > 0)
            .map(|(n, kind)| format!("{n} {kind}"))
            .collect();
        Some(format!(
            "of {} pairs: {}",
            self.pairs.len(),
            named.join(", ")
        ))
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
}

/// Runs each solver over the step sizes (or tolerances) against the reference and reports
/// the observed orders of every error measure.
pub fn convergence(
    case: &dyn StudyCase,
    solvers: &[Solver],
    step_sizes: &[f64],
    tolerances: &[f64],
    progress: &(dyn Fn() + Sync),
) -> Result<Convergence, ScenarioError> {
    let methods = Method::studied(case.switching(), solvers);
    let jobs = Method::jobs(&methods, step_sizes, tolerances, true);
    let own = Method::own_solvers(&methods);
    let (reference, ref_measures, runs) = run_against_reference(case, &own, &jobs, progress)?;
    let sc = scale(&ref_measures);
    let mut tables = Vec::new();
    for method in &methods {
        let label = method.label();
        let mine: Vec<&StudyRun> = runs.iter().filter(|r| r.solver == label).collect();
        for measure in ErrorMeasure::ALL {
            let points: Vec<(f64, f64)> = mine
                .iter()
                .map(|r| (r.resolution, measure.of(&r.errors)))
                .collect();
            if points.iter().all(|p| p.1.is_nan() || p.1 == 0.0) {
                continue;
            }
            let (pairs, fitted_slope) = orders(&points, sc);
            tables.push(OrderTable {
                solver: label.clone(),
                measure,
                pairs,
                fitted_slope,
            });
        }
    }
    Ok(Convergence {
        reference,
        runs,
        orders: tables,
    })
}
