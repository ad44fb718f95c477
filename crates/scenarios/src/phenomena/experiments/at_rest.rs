//! The phenomena of friction at rest and at break-away: stiction, pre-sliding, rising
//! static friction.

use crate::error::ScenarioError;
use crate::phenomena::{thresholds, Axes, Bench, Experiment, Verdict};
use crate::scenario::Scenario;
use std::collections::BTreeMap;

/// Stiction as the literature defines it (Armstrong-Hélouvry et al. 1994; Olsson et al.
/// 1998): under a slowly rising force the body breaks away at a static level above the
/// kinetic friction that follows. The break-away force is the peak friction before gross
/// sliding; the kinetic level is the least friction after it, while the ramp goes on.
pub struct Stiction;

impl Experiment for Stiction {
    fn name(&self) -> &'static str {
        "stiction"
    }
    fn label(&self) -> &'static str {
        "Stiction"
    }
    fn region(&self) -> Axes {
        &[("m", &[0.1, 1.0, 10.0])]
    }
    fn paper_row(&self) -> Option<[bool; 6]> {
        Some([true; 6])
    }
    fn decide(&self, bench: &Bench) -> Result<Verdict, ScenarioError> {
        let rate = thresholds::STICTION_RATE * bench.ramp_level();
        let mut evidence = BTreeMap::from([("rate_N_s", rate)]);
        let Some(b) = bench.breakaway(rate)? else {
            return Ok(Verdict {
                measured: false,
                evidence,
            });
        };
        let excess = b.force / b.kinetic.max(f64::MIN_POSITIVE) - 1.0;
        evidence.extend([
            ("breakaway_N", b.force),
            ("breakaway_time_s", b.time),
            ("kinetic_after_N", b.kinetic),
            ("static_excess", excess),
        ]);
        Ok(Verdict {
            measured: excess > thresholds::STATIC_EXCESS,
            evidence,
        })
    }
}

/// Pre-sliding (Armstrong-Hélouvry et al. 1994, §2.1; Al-Bender et al. 2005): under a
/// load below break-away (half of F_s, ramped, held, released) the body moves, and on
/// unloading most of that displacement springs back. The scale is the model's: its
/// stiffness at rest and the length F_s/k are reported beside the displacement.
pub struct Presliding;

impl Experiment for Presliding {
    fn name(&self) -> &'static str {
        "presliding"
    }
    fn label(&self) -> &'static str {
        "Pre-sliding"
    }
    fn region(&self) -> Axes {
        &[("fraction", &[0.25, 0.5, 0.75]), ("m", &[0.1, 1.0, 10.0])]
    }
    fn paper_row(&self) -> Option<[bool; 6]> {
        Some([true; 6])
    }
    fn decide(&self, bench: &Bench) -> Result<Verdict, ScenarioError> {
        let o = bench.outcome(&bench.spec(Scenario::PRESLIDING, bench.rig(), 4.0, 401))?;
        let x_max = o
            .rows
            .iter()
            .filter(|r| r.t <= 2.0)
            .map(|r| r.x.abs())
            .fold(0.0, f64::max);
        let x_end = o.last().expect("end recorded").x.abs();
        let recovered = if x_max > 0.0 {
            (x_max - x_end) / x_max
        } else {
            0.0
        };
        Ok(Verdict {
            measured: x_max > thresholds::PRESLIDING_MIN
                && recovered > thresholds::PRESLIDING_RECOVERY,
            evidence: BTreeMap::from([
                ("x_max_m", x_max),
                ("x_after_release_m", x_end),
                ("recovered_fraction", recovered),
                ("rest_stiffness_N_m", bench.rest_stiffness()),
                ("presliding_length_m", bench.presliding_length()),
            ]),
        })
    }
}

/// Rising static friction (Johannes et al. 1973; Richardson & Nolle 1976; Olsson et al.
/// 1998, §4): the break-away force is larger when the force rises slowly, i.e. the longer
/// the contact dwells under load. Force ramps whose rates are tied to the model's own
/// time scale τ (the internal state's time constant at v_s; 1 s without a state): the
/// load reaches max(F_s, F_c) (the stiction protocol's level, F_s for the paper's
/// parameters) in 1000 τ, 100 τ and 10 τ, each at most [`thresholds::LONGEST_RAMP`]
/// (no faster: a ramp on the state's own time scale measures the contact's dynamic
/// response, which a soft Dahl contact, σ = 5 N/m, shows as a 14 % lower "break-away").
/// Present if the break-away force falls
/// from the slowest rate to the fastest by more than [`thresholds::BREAKAWAY_CHANGE`];
/// a rise with the rate is the opposite effect and does not count.
pub struct RisingStaticFriction;

impl Experiment for RisingStaticFriction {
    fn name(&self) -> &'static str {
        "rising_static_friction"
    }
    fn label(&self) -> &'static str {
        "Rising static friction"
    }
    fn region(&self) -> Axes {
        &[("m", &[0.1, 1.0, 10.0])]
    }
    fn paper_row(&self) -> Option<[bool; 6]> {
        Some([false; 6])
    }
    fn decide(&self, bench: &Bench) -> Result<Verdict, ScenarioError> {
        let tau = bench.time_scale(bench.friction().v_s);
        let mut evidence = BTreeMap::from([("time_scale_s", tau)]);
        let names = [
            ("breakaway_1000tau_N", 1e-3),
            ("breakaway_100tau_N", 1e-2),
            ("breakaway_10tau_N", 1e-1),
        ];
        let mut forces = Vec::with_capacity(names.len());
        for (name, scale) in names {
            let load_time = (tau / scale).min(thresholds::LONGEST_RAMP);
            let Some(b) = bench.breakaway(bench.ramp_level() / load_time)? else {
                return Ok(Verdict {
                    measured: false,
                    evidence,
                });
            };
            evidence.insert(name, b.force);
            forces.push(b.force);
        }
        let (slow, fast) = (forces[0], forces[forces.len() - 1]);
        let fall = (slow - fast) / slow;
        evidence.insert("relative_fall", fall);
        Ok(Verdict {
            measured: fall > thresholds::BREAKAWAY_CHANGE,
            evidence,
        })
    }
}
