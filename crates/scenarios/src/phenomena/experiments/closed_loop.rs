//! The phenomenon of a closed loop: hunting, the limit cycle of a PID-positioned mass against
//! friction (the paper's second criterion for choosing a model).

use crate::analysis::closed_loop::ClosedLoop;
use crate::error::ScenarioError;
use crate::phenomena::{thresholds, Axes, Bench, Experiment, Verdict};
use crate::scenario::Scenario;
use crate::Outcome;
use friction_systems::STICK;

/// Hunting (Canudas de Wit et al. 1995; Armstrong-Hélouvry et al. 1994, §4): on the `servo`
/// rig (a unit mass on the floor positioned by the 1995 example's PID, kp = 3 N/m, ki = 4
/// N/(m·s), kd = 6 N·s/m, to a set point 1 m, from rest), the last half of
/// [`thresholds::HUNTING_T_END`] settles on a limit cycle of the position error e = r − x
/// ([`crate::analysis::closed_loop`]). It does not hunt if the loop settles at rest, or if the body's
/// stops close in on the set point: the error at each of the last
/// [`thresholds::DYING_STOPS`] entries into stick at most (1 − [`thresholds::DYING_RATIO`])
/// times the one before (Coulomb friction under integral action: each stop nearer, each
/// stick longer, never settled in a finite run). Otherwise the cell is undecided.
pub struct Hunting;

impl Experiment for Hunting {
    fn name(&self) -> &'static str {
        "hunting"
    }
    fn label(&self) -> &'static str {
        "Closed-loop hunting"
    }
    fn region(&self) -> Axes {
        &[("ki", &[4.0, 8.0, 12.0])]
    }
    fn decide(&self, bench: &Bench) -> Result<Verdict, ScenarioError> {
        let spec = bench.spec(
            Scenario::SERVO,
            bench.rig(),
            thresholds::HUNTING_T_END,
            thresholds::HUNTING_POINTS,
        );
        let o = bench.outcome(&spec)?;
        let c = ClosedLoop::of_outcome(&o).expect("the servo's body is controlled");
        let stops = stop_errors(&o);
        let ratio = stops
            .windows(2)
            .rev()
            .take(thresholds::DYING_STOPS)
            .map(|w| w[1] / w[0])
            .fold(f64::NAN, f64::max);
        let dying = stops.len() > thresholds::DYING_STOPS && ratio <= 1.0 - thresholds::DYING_RATIO;
        let measured = match c.hunting {
            Some(hunting) => hunting,
            None if dying => false,
            None => {
                return Err(ScenarioError::RunFailed(format!(
                    "{} servo: the loop has not settled by t = {} s (neither a limit cycle nor \
                     at rest) and its stops do not close in on the set point",
                    bench.law(),
                    thresholds::HUNTING_T_END
                )))
            }
        };
        // The cycle's measures where they are defined (a converged loop has no period).
        let evidence = [
            ("settled", f64::from(u8::from(c.settled))),
            ("period_s", c.period),
            ("amplitude_m", c.amplitude),
            ("stick_time_per_cycle_s", c.stick_time_per_cycle),
            ("final_error_m", c.final_error),
            ("stops", stops.len() as f64),
            ("stop_error_ratio", ratio),
        ];
        Ok(Verdict {
            measured,
            evidence: evidence
                .into_iter()
                .filter(|(_, x)| x.is_finite())
                .collect(),
        })
    }
}

/// |r − x| at each entry of the body into stick, in order.
fn stop_errors(o: &Outcome) -> Vec<f64> {
    let reference = o
        .reference
        .as_ref()
        .expect("the servo's body is controlled");
    (o.events.iter())
        .filter(|e| e.to == STICK)
        .filter_map(|e| o.rows.iter().rev().find(|r| r.t == e.t))
        .map(|r| (reference.at(r.t).0 - r.x).abs())
        .collect()
}
