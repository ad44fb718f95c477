//! The phenomena of motion: frictional hysteresis under prescribed oscillations, and
//! stick–slip on the belt.

use crate::error::ScenarioError;
use crate::motion::Motion;
use crate::phenomena::{thresholds, Axes, Bench, Experiment, Verdict};
use crate::scenario::Scenario;
use std::collections::BTreeMap;

/// Frictional hysteresis, the two faces the literature names (Hess & Soom 1990;
/// Canudas de Wit et al. 1995; Al-Bender et al. 2005):
/// - frictional lag in sliding: under v = v̄ + a·cos ωt with v̄ = 2·v_s, a = v_s (the
///   velocity never reverses), the width of the settled friction–velocity loop, |∮F dv|
///   over F_max·2a, the largest over ω = 10^k/τ, k = −2…2, τ the internal state's time
///   constant at v̄ (1 s for a model without state), after at least 20 τ. Zero for any
///   single-valued F(v).
/// - a dissipative pre-sliding loop: under x = A·sin 2πt with A half the pre-sliding
///   length (models with a bristle state), the energy lost per cycle ∮F dx over F_max·4A.
///   Zero for an elastic element without loss, such as a Dahl contact whose F_c is so
///   large that it stays a spring.
pub struct Hysteresis;

impl Experiment for Hysteresis {
    fn name(&self) -> &'static str {
        "hysteresis"
    }
    fn label(&self) -> &'static str {
        "Hysteresis"
    }
    fn paper_row(&self) -> Option<[bool; 6]> {
        Some([true; 6])
    }
    fn decide(&self, bench: &Bench) -> Result<Verdict, ScenarioError> {
        let (mean, amplitude) = (2.0 * bench.friction().v_s, bench.friction().v_s);
        let tau = bench.time_scale(mean);
        let mut lag = (0.0_f64, 0.0);
        for k in -2..=2 {
            let omega = 10f64.powi(k) / tau;
            let period = 2.0 * std::f64::consts::PI / omega;
            let motion = Motion::VelocityOscillation {
                mean,
                amplitude,
                omega,
            };
            // Settled first: at least 20 time constants, and five periods.
            let cycles = (20.0 * tau / period).ceil().max(5.0);
            let c = bench.last_cycle(Scenario::VELOCITY_OSCILLATION, motion, period, cycles)?;
            let f_max = c.range.0.abs().max(c.range.1.abs());
            let width = c.area.abs() / (f_max * 2.0 * amplitude).max(f64::MIN_POSITIVE);
            if width > lag.0 {
                lag = (width, omega);
            }
        }
        let length = bench.presliding_length();
        let dissipation = if length > 0.0 {
            let a = 0.5 * length;
            let omega = 2.0 * std::f64::consts::PI;
            let motion = Motion::Sine {
                amplitude: a,
                omega,
            };
            let c = bench.last_cycle(Scenario::OSCILLATION, motion, 1.0, 3.0)?;
            let f_max = c.range.0.abs().max(c.range.1.abs());
            c.work.abs() / (f_max * 4.0 * a).max(f64::MIN_POSITIVE)
        } else {
            0.0
        };
        Ok(Verdict {
            measured: lag.0 > thresholds::LAG_WIDTH
                || dissipation > thresholds::PRESLIDING_DISSIPATION,
            evidence: BTreeMap::from([
                ("lag_width", lag.0),
                ("lag_omega_rad_s", lag.1),
                ("presliding_amplitude_m", 0.5 * length),
                ("presliding_dissipation", dissipation),
            ]),
        })
    }
}

/// Sustained stick–slip (Armstrong-Hélouvry et al. 1994, §2.3): on the belt rig (m = 1
/// kg, k = 100 N/m, v_belt = 0.05 m/s, from rest), the stick phases the switching log
/// records over the second half of 40 s, after the transient, and how many of the settled
/// oscillation's cycles stick ([`crate::analysis::settled`], the measures `sweep` writes).
pub struct StickSlip;

impl Experiment for StickSlip {
    fn name(&self) -> &'static str {
        "stick_slip"
    }
    fn label(&self) -> &'static str {
        "Stick-slip"
    }
    fn region(&self) -> Axes {
        &[
            ("v_belt", &[0.01, 0.05, 0.2, 1.0]),
            ("k", &[10.0, 100.0, 1000.0]),
            ("c", &[0.0, 0.5, 2.0]),
        ]
    }
    fn paper_row(&self) -> Option<[bool; 6]> {
        Some([true, true, false, false, true, true])
    }
    fn decide(&self, bench: &Bench) -> Result<Verdict, ScenarioError> {
        let o = bench.outcome(&bench.spec(
            Scenario::BELT,
            bench.rig(),
            thresholds::STICK_SLIP_T_END,
            4001,
        ))?;
        let s = crate::analysis::settled::Settled::of(
            &crate::analysis::settled::Trace::of_outcome(&o),
            0.5,
        );
        let per_cycle = if s.stick_per_cycle.is_nan() {
            0.0
        } else {
            s.stick_per_cycle
        };
        Ok(Verdict {
            measured: s.stick_phases >= thresholds::STICK_PHASES
                && per_cycle >= thresholds::STICK_PER_CYCLE,
            evidence: BTreeMap::from([
                ("stick_phases_settled", s.stick_phases as f64),
                ("stick_per_cycle", per_cycle),
                ("period_s", if s.period.is_nan() { 0.0 } else { s.period }),
            ]),
        })
    }
}
