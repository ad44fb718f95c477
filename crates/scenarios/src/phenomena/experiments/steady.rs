//! The phenomena of steady sliding: the Stribeck effect and viscous friction, from steady
//! friction reached by simulation at constant velocity.

use crate::error::ScenarioError;
use crate::phenomena::{thresholds, Bench, Experiment, Verdict};
use std::collections::BTreeMap;

/// The Stribeck effect as a falling branch of steady friction anywhere at low speed
/// (Armstrong-Hélouvry et al. 1994, §2.1): steady friction at
/// [`thresholds::STRIBECK_POINTS`] velocities spaced evenly in log from 0.01·v_s to
/// 5·v_s, and the deepest fall from the highest friction at a lower velocity,
/// (F_peak − F)/F_peak.
pub struct Stribeck;

impl Experiment for Stribeck {
    fn name(&self) -> &'static str {
        "stribeck"
    }
    fn label(&self) -> &'static str {
        "Stribeck effect"
    }
    fn paper_row(&self) -> Option<[bool; 6]> {
        Some([true, true, true, false, false, false])
    }
    fn decide(&self, bench: &Bench) -> Result<Verdict, ScenarioError> {
        let n = thresholds::STRIBECK_POINTS;
        let (lo, hi) = (0.01 * bench.friction().v_s, 5.0 * bench.friction().v_s);
        let mut peak = (f64::NEG_INFINITY, 0.0);
        let mut fall = (0.0, 0.0, 0.0, 0.0);
        for i in 0..n {
            let v = (lo.ln() + (hi.ln() - lo.ln()) * i as f64 / (n - 1) as f64).exp();
            let f = bench.steady(v)?;
            if f > peak.0 {
                peak = (f, v);
            }
            let drop = (peak.0 - f) / peak.0.abs().max(f64::MIN_POSITIVE);
            if drop > fall.0 {
                fall = (drop, peak.1, v, f);
            }
        }
        let mut evidence = BTreeMap::from([("relative_fall", fall.0)]);
        if fall.0 > 0.0 {
            evidence.extend([
                ("v_peak_m_s", fall.1),
                ("v_low_m_s", fall.2),
                ("F_low_N", fall.3),
            ]);
        }
        Ok(Verdict {
            measured: fall.0 > thresholds::STEADY_CHANGE,
            evidence,
        })
    }
}

/// Viscous friction: steady friction grows by more than [`thresholds::STEADY_CHANGE`] from
/// 100·v_s to 1000·v_s.
pub struct Viscous;

impl Experiment for Viscous {
    fn name(&self) -> &'static str {
        "viscous"
    }
    fn label(&self) -> &'static str {
        "Viscous friction"
    }
    fn paper_row(&self) -> Option<[bool; 6]> {
        Some([true, false, true, true, false, true])
    }
    fn decide(&self, bench: &Bench) -> Result<Verdict, ScenarioError> {
        steady_change(
            bench,
            100.0 * bench.friction().v_s,
            1000.0 * bench.friction().v_s,
            1.0,
        )
    }
}

/// Steady friction at v1 and v2; the phenomenon is present when it changes by more than
/// the threshold in the direction `sign` (−1: falls, +1: grows).
fn steady_change(bench: &Bench, v1: f64, v2: f64, sign: f64) -> Result<Verdict, ScenarioError> {
    let (f1, f2) = (bench.steady(v1)?, bench.steady(v2)?);
    let change = (f2 - f1) / f1.abs().max(f64::MIN_POSITIVE);
    Ok(Verdict {
        measured: sign * change > thresholds::STEADY_CHANGE,
        evidence: BTreeMap::from([
            ("v_low_m_s", v1),
            ("F_low_N", f1),
            ("v_high_m_s", v2),
            ("F_high_N", f2),
            ("relative_change", change),
        ]),
    })
}
