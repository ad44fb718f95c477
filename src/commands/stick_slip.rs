//! The report section of the belt's stick–slip map and bifurcation diagram
//! ([`crate::study::StickSlipMapStudy`], [`crate::study::BifurcationStudy`]), as `reproduce`
//! writes them into `stick-slip/`.

use crate::error::AppError;
use crate::study::{conduct, BifurcationStudy, StickSlipMapStudy, Target};
use friction_models::{FrictionParams, ModelId};
use scenarios::stick_slip::{belt_run, log_space, Regime};

/// The measured, settled part of each run (its last half).
const SETTLE: f64 = 0.5;

/// Conducts the map (belt speed × stiffness, from rest) and the bifurcation diagram (at
/// k = 100 N/m, from rest and from steady sliding) of the belt with CVS into `t` (`map.*`,
/// `bifurcation.*`), and returns the report section.
pub fn add_stick_slip(t: &mut Target, friction: &FrictionParams) -> Result<String, AppError> {
    // CVS: Coulomb, viscous, static and Stribeck, a falling branch and a rising one.
    let base = belt_run(ModelId::Cvs, friction);
    let ks = log_space(10.0, 1000.0, 9);
    let map = StickSlipMapStudy {
        base: &base,
        v_belt_range: (3e-3, 1.0),
        v_belt_count: 16,
        ks: &ks,
        settle: SETTLE,
    };
    let map = conduct(&map, t, "map")?;
    // The bifurcation diagram at k = 100 N/m.
    let speeds: Vec<f64> = (1..=40).map(|i| 0.02 * i as f64).collect();
    let bifurcation = BifurcationStudy {
        base: &base,
        v_belts: &speeds,
        settle: SETTLE,
    };
    let bifurcation = conduct(&bifurcation, t, "bifurcation")?;
    let (points, branches, boundary) = (&map.points, &bifurcation.branches, &map.boundary);
    let coexist: Vec<f64> = branches
        .iter()
        .filter(|b| {
            Regime::of(&b.from_rest, b.v_belt) == Regime::StickSlip
                && Regime::of(&b.from_sliding, b.v_belt) == Regime::SteadySliding
        })
        .map(|b| b.v_belt)
        .collect();
    let stick_slip = points
        .iter()
        .filter(|p| p.regime == Regime::StickSlip)
        .count();
    let decided: Vec<_> = points
        .iter()
        .filter(|p| p.regime != Regime::Stuck)
        .collect();
    let agree = decided
        .iter()
        .filter(|p| p.linearly_unstable == (p.regime != Regime::SteadySliding))
        .count();
    let span = |v: &[f64]| match (v.first(), v.last()) {
        (Some(a), Some(b)) => format!("{a:.4} to {b:.4} m/s"),
        _ => "nowhere".into(),
    };
    Ok(format!(
        "\n## Stick-slip on the belt: the map and the bifurcation diagram\n\n\
         The belt rig with CVS at the paper's parameters (m = 1, c = 0, 40 s, the last 20 s \
         measured; `scenarios::stick_slip`, docs/sweep.md):\n\n\
         - [The settled regime over belt speed and stiffness](stick-slip/map.png), from rest: \
         stick-slip at {stick_slip} of {} points ({} carried by the belt through the whole \
         run: their cycle is longer than 40 s); linear stability theory (steady sliding \
         unstable where c + dF/dv < 0 at v = -v_belt, here for v_belt from {}) agrees with the \
         regime at {agree} of the {} others: the rest are stick-slip reached from rest where \
         sliding is stable.\n\
         - [The bifurcation diagram at k = 100 N/m](stick-slip/bifurcation.png): the settled \
         amplitude from rest and from steady sliding; the two coexist (stick-slip from rest, \
         steady sliding kept) from {}: a subcritical boundary, where the paper's reading of \
         stick-slip as a property of the model alone does not hold.\n",
        points.len(),
        points.len() - decided.len(),
        span(boundary),
        decided.len(),
        span(&coexist),
    ))
}
