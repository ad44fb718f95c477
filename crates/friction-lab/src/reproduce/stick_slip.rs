//! The belt's stick–slip map and bifurcation diagram ([`crate::study::StickSlipMapStudy`],
//! [`crate::study::BifurcationStudy`]) with CVS, and their report section (`stick-slip/`).

use super::Part;
use crate::error::AppError;
use crate::study::{
    conduct_all, Bifurcation, BifurcationStudy, Entry, Output, ReportEntry, StickSlipMap,
    StickSlipMapStudy,
};
use friction_models::{FrictionParams, ModelId};
use scenarios::stick_slip::{belt_run, log_space, MapPoint, Regime};

/// The measured, settled part of each run (its last half).
const SETTLE: f64 = 0.5;

/// The belt speeds `speeds` as the report says them: "from A to B m/s", or "nowhere".
fn span(speeds: &[f64]) -> String {
    match (speeds.first(), speeds.last()) {
        (Some(a), Some(b)) => format!("{a:.4} to {b:.4} m/s"),
        _ => "nowhere".into(),
    }
}

/// The map's bullet: the regimes counted, and linear stability theory against them.
fn reads_map(map: &StickSlipMap) -> String {
    let points = &map.points;
    let count = |keep: &dyn Fn(&&MapPoint) -> bool| points.iter().filter(keep).count();
    let stick_slip = count(&|p| p.regime == Regime::StickSlip);
    let (stuck, unsettled) = (
        count(&|p| p.regime == Regime::Stuck),
        count(&|p| p.regime == Regime::Unsettled),
    );
    let settled = points.len() - stuck - unsettled;
    // Linear theory against the settled regimes, each way it can disagree counted.
    let decided = |p: &&MapPoint| !p.regime.is_transient();
    let moving_where_stable =
        count(&|p| decided(p) && !p.linearly_unstable && p.regime != Regime::SteadySliding);
    let sliding_where_unstable =
        count(&|p| decided(p) && p.linearly_unstable && p.regime == Regime::SteadySliding);
    let agree = settled - moving_where_stable - sliding_where_unstable;
    let max_span = points.iter().map(|p| p.settled.to).fold(0.0, f64::max);
    format!(
        "- [The settled regime over belt speed and stiffness](stick-slip/map.png), from rest: \
         stick-slip at {stick_slip} of {} points; {settled} settled, {stuck} carried by the belt \
         through the whole run (a first stick phase longer than the run) and {unsettled} not \
         settled (a transient at the longest run, {}): both counted apart. Linear stability \
         theory (steady sliding unstable where c + dF/dv < 0 at v = -v_belt, here for v_belt \
         from {}) agrees with the settled regime at {agree} of the {settled}; \
         {moving_where_stable} are stick-slip or an oscillation reached from rest where sliding \
         is stable, and {sliding_where_unstable} steady sliding where it is unstable.\n",
        points.len(),
        if unsettled > 0 {
            format!("{max_span} s")
        } else {
            "none".into()
        },
        span(&map.boundary),
    )
}

/// The bifurcation diagram's bullet: where stick–slip from rest and steady sliding coexist.
fn reads_bifurcation(bifurcation: &Bifurcation) -> String {
    let coexist: Vec<f64> = (bifurcation.branches.iter())
        .filter(|b| {
            Regime::of(&b.from_rest, b.v_belt) == Regime::StickSlip
                && Regime::of(&b.from_sliding, b.v_belt) == Regime::SteadySliding
        })
        .map(|b| b.v_belt)
        .collect();
    format!(
        "- [The bifurcation diagram at k = 100 N/m](stick-slip/bifurcation.png): the settled \
         amplitude from rest and from steady sliding (a run that did not settle is a cross of \
         its own); the two coexist (stick-slip from rest, steady sliding kept) from {}: a \
         subcritical boundary, where the paper's reading of stick-slip as a property of the \
         model alone does not hold.\n",
        span(&coexist),
    )
}

/// The report's section on the belt's stick–slip: the map (belt speed × stiffness, from rest)
/// and the bifurcation diagram (at k = 100 N/m, from rest and from steady sliding) of the belt
/// with CVS (`map.*`, `bifurcation.*`).
pub struct StickSlip {
    /// The friction parameters.
    pub friction: FrictionParams,
}

impl Part for StickSlip {
    fn heading(&self) -> String {
        "Stick-slip on the belt: the map and the bifurcation diagram".into()
    }

    fn folder(&self) -> &'static str {
        "stick-slip"
    }

    fn conduct(&self, target: &mut Output) -> Result<String, AppError> {
        // CVS: Coulomb, viscous, static and Stribeck, a falling branch and a rising one.
        let base = belt_run(ModelId::Cvs, &self.friction);
        let ks = log_space(10.0, 1000.0, 9);
        // The bifurcation diagram at k = 100 N/m.
        let speeds: Vec<f64> = (1..=40).map(|i| 0.02 * i as f64).collect();
        let table: [&dyn ReportEntry; 2] = [
            &Entry {
                stem: "map",
                study: StickSlipMapStudy {
                    base: &base,
                    v_belt_range: (3e-3, 1.0),
                    v_belt_count: 16,
                    ks: &ks,
                    settle: SETTLE,
                },
                reads: reads_map,
            },
            &Entry {
                stem: "bifurcation",
                study: BifurcationStudy {
                    base: &base,
                    v_belts: &speeds,
                    settle: SETTLE,
                },
                reads: reads_bifurcation,
            },
        ];
        Ok(format!(
            "The belt rig with CVS at the paper's parameters (m = 1, c = 0; each run 40 s, the \
             last half measured, and doubled up to {} times while it has not settled: \
             `scenarios::stick_slip`, docs/sweep.md):\n\n{}",
            scenarios::analysis::settled::MAX_EXTENSION,
            conduct_all(&table, target)?
        ))
    }
}
