//! Table 2 decided by simulation: one protocol per phenomenon, each a scenario run whose
//! measured numbers decide the cell against a stated threshold (see `docs/phenomena.md`).

use crate::motion::Motion;
use crate::run::Limits;
use crate::run::{run, run_motion, settling_time, Law, RunSpec, ScenarioError, SwitchingKind};
use crate::scenario::Scenario;
use crate::ScenarioParams;
use friction_models::{FrictionModel, FrictionParams, ModelId, Parameters};
use integrators::{Solver, SolverError, StepControl};
use serde::Serialize;
use std::collections::BTreeMap;

/// A row of Table 2.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Phenomenon {
    /// The body stays put under a force below break-away.
    Stiction,
    /// A small, partly reversible displacement before sliding.
    Presliding,
    /// Steady friction falls with velocity at low speed.
    Stribeck,
    /// Steady friction grows with velocity at high speed.
    Viscous,
    /// Friction is a loop, not a single-valued function of velocity, under oscillation.
    Hysteresis,
    /// A spring-held body on a slow belt alternates between sticking and slipping.
    StickSlip,
    /// The break-away force depends on how fast the applied force rises.
    RisingStaticFriction,
}

impl Phenomenon {
    /// Every row, in the paper's order.
    pub const ALL: [Phenomenon; 7] = [
        Phenomenon::Stiction,
        Phenomenon::Presliding,
        Phenomenon::Stribeck,
        Phenomenon::Viscous,
        Phenomenon::Hysteresis,
        Phenomenon::StickSlip,
        Phenomenon::RisingStaticFriction,
    ];

    /// The name used in `table2.json`.
    pub fn name(self) -> &'static str {
        match self {
            Phenomenon::Stiction => "stiction",
            Phenomenon::Presliding => "presliding",
            Phenomenon::Stribeck => "stribeck",
            Phenomenon::Viscous => "viscous",
            Phenomenon::Hysteresis => "hysteresis",
            Phenomenon::StickSlip => "stick_slip",
            Phenomenon::RisingStaticFriction => "rising_static_friction",
        }
    }

    /// The row's label in the paper.
    pub fn label(self) -> &'static str {
        match self {
            Phenomenon::Stiction => "Stiction",
            Phenomenon::Presliding => "Pre-sliding",
            Phenomenon::Stribeck => "Stribeck effect",
            Phenomenon::Viscous => "Viscous friction",
            Phenomenon::Hysteresis => "Hysteresis",
            Phenomenon::StickSlip => "Stick-slip",
            Phenomenon::RisingStaticFriction => "Rising static friction",
        }
    }

    /// The grid of rig parameters a verdict is also decided over (docs/phenomena.md): each
    /// axis a scenario parameter with its values, the grid their product, the default rig
    /// among its points. Steady friction and prescribed motions have no rig parameter: the
    /// Stribeck, viscous and hysteresis cells have a grid of one point.
    pub fn region(self) -> &'static [(&'static str, &'static [f64])] {
        match self {
            Phenomenon::Stiction | Phenomenon::RisingStaticFriction => &[("m", &[0.1, 1.0, 10.0])],
            Phenomenon::Presliding => &[("fraction", &[0.25, 0.5, 0.75]), ("m", &[0.1, 1.0, 10.0])],
            Phenomenon::Stribeck | Phenomenon::Viscous | Phenomenon::Hysteresis => &[],
            Phenomenon::StickSlip => &[
                ("v_belt", &[0.01, 0.05, 0.2, 1.0]),
                ("k", &[10.0, 100.0, 1000.0]),
                ("c", &[0.0, 0.5, 2.0]),
            ],
        }
    }

    /// What Table 2 of the paper claims, for the paper's six models.
    pub fn paper_claim(self, model: ModelId) -> Option<bool> {
        let column = ModelId::PAPER.iter().position(|&m| m == model)?;
        let row: [u8; 6] = match self {
            Phenomenon::Stiction | Phenomenon::Presliding | Phenomenon::Hysteresis => {
                [1, 1, 1, 1, 1, 1]
            }
            Phenomenon::Stribeck => [1, 1, 1, 0, 0, 0],
            Phenomenon::Viscous => [1, 0, 1, 1, 0, 1],
            Phenomenon::StickSlip => [1, 1, 0, 0, 1, 1],
            Phenomenon::RisingStaticFriction => [0, 0, 0, 0, 0, 0],
        };
        Some(row[column] == 1)
    }
}

/// A decided cell: the answer and the numbers that decided it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Verdict {
    /// Whether the phenomenon was observed.
    pub measured: bool,
    /// The numbers that decided it.
    pub evidence: BTreeMap<&'static str, f64>,
}

/// The thresholds of the protocols (documented in `docs/phenomena.md`).
pub mod thresholds {
    /// Stiction: the force ramp's rate, per second, as a fraction of max(F_s, F_c): the load
    /// reaches the static level in ten seconds, slow beside every model's own time scale.
    pub const STICTION_RATE: f64 = 0.1;
    /// Stiction: the least relative excess of the break-away force over the kinetic level
    /// after it (Coulomb friction has none; the paper's F_s = 7.5 N over F_c = 6 N is 25 %).
    pub const STATIC_EXCESS: f64 = 0.01;
    /// Pre-sliding: smallest displacement under load that counts, m.
    pub const PRESLIDING_MIN: f64 = 1e-9;
    /// Pre-sliding: smallest fraction of the displacement recovered after release ("mostly
    /// recovered": more than half).
    pub const PRESLIDING_RECOVERY: f64 = 0.5;
    /// Stribeck and viscous: smallest relative change of steady friction.
    pub const STEADY_CHANGE: f64 = 0.01;
    /// Stribeck: velocities at which steady friction is sampled, 0.01·v_s to 5·v_s.
    pub const STRIBECK_POINTS: usize = 25;
    /// Hysteresis: smallest width of the friction–velocity loop under a velocity that
    /// oscillates without reversing, |∮F dv| over F_max·2a.
    pub const LAG_WIDTH: f64 = 1e-3;
    /// Hysteresis: smallest energy lost per pre-sliding cycle, ∮F dx over F_max·4A.
    pub const PRESLIDING_DISSIPATION: f64 = 1e-3;
    /// Stick–slip: length of the belt run, s (the second half is the settled part).
    pub const STICK_SLIP_T_END: f64 = 40.0;
    /// Stick–slip: stick phases (entries into stick in the switching log) needed in the
    /// settled part.
    pub const STICK_PHASES: usize = 2;
    /// Stick–slip: least number of stick phases per cycle of the settled oscillation
    /// (sustained stick–slip sticks once per cycle; a transient that dies out does not).
    pub const STICK_PER_CYCLE: f64 = 0.5;
    /// Rising static friction: smallest relative fall of the break-away force from the
    /// slowest force rate to the fastest.
    pub const BREAKAWAY_CHANGE: f64 = 0.1;
    /// Rising static friction: the longest time for the load to reach F_s, s (a Dahl contact's
    /// τ is 12 s at v_s: a ramp of 1000 τ would slide for hours at speeds where its state
    /// equation is stiff).
    pub const LONGEST_RAMP: f64 = 100.0;
    /// Rising static friction: a break-away exists only if the peak friction before gross
    /// sliding reaches this fraction of F_s.
    pub const BREAKAWAY_MIN: f64 = 0.01;
}

/// The friction parameters the protocols read themselves, whatever model they judge: F_s and
/// F_c scale the force ramps (to max(F_s, F_c)) and the break-away and pre-sliding measures,
/// v_s the velocities of the Stribeck sweep, of the velocity oscillation and of gross sliding.
/// A `--set` of one of them changes the table even for a model that does not read it.
pub const PROTOCOL_PARAMETERS: [&str; 3] = ["F_s", "F_c", "v_s"];

/// How the protocols integrate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Protocol {
    /// The solver.
    pub solver: Solver,
    /// Its step control.
    pub step: StepControl,
    /// The bounds of every run (a run that reaches one fails, and its cell is undecided).
    pub limits: Limits,
}

impl Default for Protocol {
    /// diffsol's BDF at rtol = 1e-10, atol = 1e-12: the bristle models (LuGre, its variants,
    /// GMS) are stiff, and Dormand–Prince, which gives the same verdicts and regions, takes
    /// four times as long over the whole table (docs/performance.md).
    fn default() -> Self {
        Protocol {
            solver: Solver::BDF,
            step: StepControl::Adaptive {
                rtol: 1e-10,
                atol: 1e-12,
                h0: None,
            },
            limits: Limits::default(),
        }
    }
}

/// The parameter set a model is judged with: the paper's for the six and the classical
/// terms, the LuGre paper's for the bristle models (LuGre, its two variants and GMS), whose
/// stiffness σ0 = 1e5 N/m sets a micrometre pre-sliding scale only with its levels.
pub fn parameters_for(model: ModelId) -> FrictionParams {
    if matches!(
        model,
        ModelId::LuGre | ModelId::LuGreVd | ModelId::ElastoPlastic | ModelId::Gms
    ) {
        FrictionParams::lugre_1995()
    } else {
        FrictionParams::paper()
    }
}

/// One period of a prescribed periodic motion.
struct Cycle {
    /// ∮F dx: the work done against friction, J.
    work: f64,
    /// ∮F dv: the friction–velocity loop's area, N·m/s.
    area: f64,
    /// The least and the largest friction, N.
    range: (f64, f64),
}

/// A break-away under a force ramp.
struct Breakaway {
    /// The peak friction before gross sliding, N.
    force: f64,
    /// When gross sliding started, s.
    time: f64,
    /// The least friction after it, N.
    kinetic: f64,
}

struct Judge<'a> {
    law: &'a Law,
    built: &'a dyn FrictionModel,
    p: FrictionParams,
    protocol: Protocol,
    /// The rig's parameters the protocols start from (mass, belt, spring, load).
    rig: ScenarioParams,
}

impl Judge<'_> {
    fn spec(
        &self,
        scenario: Scenario,
        params: ScenarioParams,
        t_end: f64,
        points: usize,
    ) -> RunSpec {
        RunSpec {
            scenario,
            law: self.law.clone(),
            friction: self.p,
            params,
            solver: self.protocol.solver,
            switching: SwitchingKind::Event,
            step: self.protocol.step,
            t_end: Some(t_end),
            output_points: points,
            limits: self.protocol.limits,
        }
    }

    /// The failure of the run `what` of this law's protocol (not bad input: the cell is
    /// undecided).
    fn failed(&self, what: impl std::fmt::Display, error: &SolverError) -> ScenarioError {
        ScenarioError::Solver {
            what: format!("{} {what}", self.law),
            error: error.clone(),
        }
    }

    fn outcome(&self, spec: &RunSpec) -> Result<crate::Outcome, ScenarioError> {
        let o = run(spec, &mut |_| {})?;
        match &o.error {
            Some(e) => Err(self.failed(spec.scenario, e)),
            None => Ok(o),
        }
    }

    /// Steady friction at constant velocity v, reached by simulation.
    fn steady(&self, v: f64) -> Result<f64, ScenarioError> {
        let spec = self.spec(Scenario::VelocitySweep, ScenarioParams::default(), 0.0, 2);
        let o = run_motion(
            &spec,
            self.built,
            Motion::Constant { v },
            settling_time(self.built, v),
            &mut |_| {},
        );
        match &o.error {
            Some(e) => Err(self.failed(format_args!("steady state at v = {v}"), e)),
            None => Ok(o.last().expect("end recorded").friction),
        }
    }

    /// The contact's stiffness at rest, dF/dx along a small motion from the unloaded state,
    /// (∂F/∂z)·(ż/v) at z = 0, v → 0⁺: σ for the Dahl models, σ0 for LuGre; zero for a model
    /// without internal state (it is rigid below break-away).
    fn rest_stiffness(&self) -> f64 {
        friction_models::steady::rest_stiffness(self.built, 1e-9 * self.p.v_s)
    }

    /// The pre-sliding length the model sets: F_s over its stiffness at rest (zero for a
    /// rigid contact).
    fn presliding_length(&self) -> f64 {
        let k = self.rest_stiffness();
        if k > 0.0 {
            self.p.f_s / k
        } else {
            0.0
        }
    }

    /// The level the force ramps are scaled to: max(F_s, F_c), the larger of the static and
    /// kinetic levels (F_s at the paper's parameters).
    fn ramp_level(&self) -> f64 {
        self.p.f_s.max(self.p.f_c)
    }

    /// Stiction as the literature defines it (Armstrong-Hélouvry et al. 1994; Olsson et al.
    /// 1998): under a slowly rising force the body breaks away at a static level above the
    /// kinetic friction that follows. The break-away force is the peak friction before gross
    /// sliding; the kinetic level is the least friction after it, while the ramp goes on.
    fn stiction(&self) -> Result<Verdict, ScenarioError> {
        let rate = thresholds::STICTION_RATE * self.ramp_level();
        let mut evidence = BTreeMap::from([("rate_N_s", rate)]);
        let Some(b) = self.breakaway(rate)? else {
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

    /// Pre-sliding (Armstrong-Hélouvry et al. 1994, §2.1; Al-Bender et al. 2005): under a
    /// load below break-away (half of F_s, ramped, held, released) the body moves, and on
    /// unloading most of that displacement springs back. The scale is the model's: its
    /// stiffness at rest and the length F_s/k are reported beside the displacement.
    fn presliding(&self) -> Result<Verdict, ScenarioError> {
        let o = self.outcome(&self.spec(Scenario::Presliding, self.rig, 4.0, 401))?;
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
                ("rest_stiffness_N_m", self.rest_stiffness()),
                ("presliding_length_m", self.presliding_length()),
            ]),
        })
    }

    /// Steady friction at v1 and v2; the phenomenon is present when it changes by more than
    /// the threshold in the direction `sign` (−1: falls, +1: grows).
    fn steady_change(&self, v1: f64, v2: f64, sign: f64) -> Result<Verdict, ScenarioError> {
        let (f1, f2) = (self.steady(v1)?, self.steady(v2)?);
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

    /// The Stribeck effect as a falling branch of steady friction anywhere at low speed
    /// (Armstrong-Hélouvry et al. 1994, §2.1): steady friction at
    /// [`thresholds::STRIBECK_POINTS`] velocities spaced evenly in log from 0.01·v_s to
    /// 5·v_s, and the deepest fall from the highest friction at a lower velocity,
    /// (F_peak − F)/F_peak.
    fn stribeck(&self) -> Result<Verdict, ScenarioError> {
        let n = thresholds::STRIBECK_POINTS;
        let (lo, hi) = (0.01 * self.p.v_s, 5.0 * self.p.v_s);
        let mut peak = (f64::NEG_INFINITY, 0.0);
        let mut fall = (0.0, 0.0, 0.0, 0.0);
        for i in 0..n {
            let v = (lo.ln() + (hi.ln() - lo.ln()) * i as f64 / (n - 1) as f64).exp();
            let f = self.steady(v)?;
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

    fn viscous(&self) -> Result<Verdict, ScenarioError> {
        self.steady_change(100.0 * self.p.v_s, 1000.0 * self.p.v_s, 1.0)
    }

    /// The last of `cycles` periods of the prescribed periodic `motion` (period `period`):
    /// the work done against friction ∮F dx, the loop area ∮F dv (both integrated by the
    /// solver, as the difference of a run over `cycles` and one over `cycles − 1` periods) and
    /// the range of the friction force over that period.
    fn last_cycle(
        &self,
        scenario: Scenario,
        motion: Motion,
        period: f64,
        cycles: f64,
    ) -> Result<Cycle, ScenarioError> {
        let spec = self.spec(scenario, ScenarioParams::default(), 0.0, 2001);
        let run = |t_end: f64| {
            let o = run_motion(&spec, self.built, motion, t_end, &mut |_| {});
            match &o.error {
                Some(e) => Err(self.failed(scenario, e)),
                None => Ok(o),
            }
        };
        let (whole, before) = (run(cycles * period)?, run((cycles - 1.0) * period)?);
        let integral = |o: &crate::Outcome, f: fn(&crate::Outcome) -> Option<f64>| {
            f(o).expect("motion runs report their integrals")
        };
        let last: Vec<f64> = whole
            .rows
            .iter()
            .filter(|r| r.t >= (cycles - 1.0) * period)
            .map(|r| r.friction)
            .collect();
        let (lo, hi) = last
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &f| {
                (lo.min(f), hi.max(f))
            });
        Ok(Cycle {
            work: integral(&whole, |o| o.friction_work) - integral(&before, |o| o.friction_work),
            area: integral(&whole, |o| o.loop_area) - integral(&before, |o| o.loop_area),
            range: (lo, hi),
        })
    }

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
    fn hysteresis(&self) -> Result<Verdict, ScenarioError> {
        let (mean, amplitude) = (2.0 * self.p.v_s, self.p.v_s);
        let tau = if self.built.n_states() > 0 {
            settling_time(self.built, mean) / 20.0
        } else {
            1.0
        };
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
            let c = self.last_cycle(Scenario::VelocityOscillation, motion, period, cycles)?;
            let f_max = c.range.0.abs().max(c.range.1.abs());
            let width = c.area.abs() / (f_max * 2.0 * amplitude).max(f64::MIN_POSITIVE);
            if width > lag.0 {
                lag = (width, omega);
            }
        }
        let length = self.presliding_length();
        let dissipation = if length > 0.0 {
            let a = 0.5 * length;
            let omega = 2.0 * std::f64::consts::PI;
            let motion = Motion::Sine {
                amplitude: a,
                omega,
            };
            let c = self.last_cycle(Scenario::Oscillation, motion, 1.0, 3.0)?;
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

    /// Sustained stick–slip (Armstrong-Hélouvry et al. 1994, §2.3): on the belt rig (m = 1
    /// kg, k = 100 N/m, v_belt = 0.05 m/s, from rest), the stick phases the switching log
    /// records over the second half of 40 s, after the transient, and how many of the settled
    /// oscillation's cycles stick ([`crate::settled`], the measures `sweep` writes).
    fn stick_slip(&self) -> Result<Verdict, ScenarioError> {
        let o =
            self.outcome(&self.spec(Scenario::Belt, self.rig, thresholds::STICK_SLIP_T_END, 4001))?;
        let s = crate::settled::Settled::of(&crate::settled::Trace::of_outcome(&o), 0.5);
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

    /// Break-away under a force ramp up to 1.5·max(F_s, F_c): gross sliding starts when |v|
    /// first exceeds v_s (the model's own velocity scale) beyond the pre-sliding length
    /// ([`Self::presliding_length`]); the break-away force is the peak
    /// friction before that, the kinetic level the least friction after it. `None` when the
    /// body never breaks away (or its peak friction stays under
    /// [`thresholds::BREAKAWAY_MIN`] of F_s: no static level at all).
    fn breakaway(&self, rate: f64) -> Result<Option<Breakaway>, ScenarioError> {
        let params = ScenarioParams { rate, ..self.rig };
        // The ramp ends at 1.5 times the larger level: a body that has not broken away by
        // then does not break away (and a stiff LuGre run costs in proportion to its length).
        let t_end = 1.5 * self.ramp_level() / rate;
        let o = self.outcome(&self.spec(Scenario::ForceRamp, params, t_end, 20001))?;
        // Gross sliding: faster than v_s and beyond the pre-sliding range (a soft contact's
        // pre-sliding motion alone can exceed v_s under a fast ramp).
        let length = self.presliding_length();
        let Some(end) = o
            .rows
            .iter()
            .position(|r| r.v.abs() > self.p.v_s && r.x.abs() > length)
        else {
            return Ok(None);
        };
        let magnitude = |rows: &[crate::Row], fold: fn(f64, f64) -> f64, start: f64| {
            rows.iter().map(|r| r.friction.abs()).fold(start, fold)
        };
        let force = magnitude(&o.rows[..=end], f64::max, 0.0);
        let kinetic = magnitude(&o.rows[end..], f64::min, f64::INFINITY);
        Ok(
            (force >= thresholds::BREAKAWAY_MIN * self.p.f_s).then_some(Breakaway {
                force,
                time: o.rows[end].t,
                kinetic,
            }),
        )
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
    fn rising_static_friction(&self) -> Result<Verdict, ScenarioError> {
        let tau = if self.built.n_states() > 0 {
            settling_time(self.built, self.p.v_s) / 20.0
        } else {
            1.0
        };
        let mut evidence = BTreeMap::from([("time_scale_s", tau)]);
        let names = [
            ("breakaway_1000tau_N", 1e-3),
            ("breakaway_100tau_N", 1e-2),
            ("breakaway_10tau_N", 1e-1),
        ];
        let mut forces = Vec::with_capacity(names.len());
        for (name, scale) in names {
            let load_time = (tau / scale).min(thresholds::LONGEST_RAMP);
            let Some(b) = self.breakaway(self.ramp_level() / load_time)? else {
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

/// Decides one cell: `phenomenon` for `law` (a model of the catalog, or a law of the user's
/// own) with `p` (the catalog model's parameters, and the scales of the protocols: F_s, F_c,
/// v_s), integrated as `protocol` says, on the rigs of docs/phenomena.md.
pub fn decide(
    phenomenon: Phenomenon,
    law: &Law,
    p: &FrictionParams,
    protocol: Protocol,
) -> Result<Verdict, ScenarioError> {
    decide_at(phenomenon, law, p, protocol, &ScenarioParams::default())
}

/// Decides one cell on rigs with the parameters `rig` (mass `m`, belt `v_belt`, spring `k`,
/// damper `c`, pre-sliding load `fraction`; the protocols set their own ramp rates and
/// motions).
pub fn decide_at(
    phenomenon: Phenomenon,
    law: &Law,
    p: &FrictionParams,
    protocol: Protocol,
    rig: &ScenarioParams,
) -> Result<Verdict, ScenarioError> {
    let built = law.build(p)?;
    let judge = Judge {
        law,
        built: built.as_ref(),
        p: *p,
        protocol,
        rig: *rig,
    };
    match phenomenon {
        Phenomenon::Stiction => judge.stiction(),
        Phenomenon::Presliding => judge.presliding(),
        Phenomenon::Stribeck => judge.stribeck(),
        Phenomenon::Viscous => judge.viscous(),
        Phenomenon::Hysteresis => judge.hysteresis(),
        Phenomenon::StickSlip => judge.stick_slip(),
        Phenomenon::RisingStaticFriction => judge.rising_static_friction(),
    }
}

/// One cell of the measured Table 2.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cell {
    /// What the simulation shows: `Ok(observed)`, or `Err(why)` when a run of its protocol
    /// failed in the solver or reached a limit (the cell is undecided, its evidence empty).
    pub measured: Result<bool, String>,
    /// What the paper claims (`None` for models it does not cover).
    pub paper: Option<bool>,
    /// The numbers that decided it.
    pub evidence: BTreeMap<&'static str, f64>,
    /// The verdict over the grid of rig parameters, when asked for.
    pub region: Option<Region>,
}

/// A verdict over the grid of [`Phenomenon::region`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Region {
    /// The grid's axes: parameter and values.
    pub axes: BTreeMap<&'static str, &'static [f64]>,
    /// Points of the grid.
    pub points: usize,
    /// The fraction of the decided points where the phenomenon is observed.
    pub fraction: f64,
    /// The points whose verdict differs from the verdict on the default rig, each as its
    /// parameter values.
    pub flips: Vec<BTreeMap<&'static str, f64>>,
    /// Points whose run failed (left out of the fraction), with the failure.
    pub undecided: Vec<(BTreeMap<&'static str, f64>, String)>,
}

impl Cell {
    /// Whether the simulation decided the cell and the paper claims otherwise.
    pub fn disagrees(&self) -> bool {
        matches!((&self.measured, self.paper), (Ok(m), Some(p)) if *m != p)
    }
}

impl Region {
    /// Whether the verdict depends on the rig: observed on some points and not on others.
    pub fn depends(&self) -> bool {
        self.fraction > 0.0 && self.fraction < 1.0
    }
}

/// Decides `phenomenon` for `law` at every point of its [`Phenomenon::region`]; `measured`
/// is the verdict on the default rig, against which the flips are listed.
pub fn region(
    phenomenon: Phenomenon,
    law: &Law,
    p: &FrictionParams,
    protocol: Protocol,
    measured: bool,
) -> Result<Region, ScenarioError> {
    let axes = phenomenon.region();
    let grid: Vec<BTreeMap<&'static str, f64>> = crate::grid::product(axes)
        .into_iter()
        .map(|point| point.into_iter().collect())
        .collect();
    use rayon::prelude::*;
    let verdicts: Vec<Result<Verdict, ScenarioError>> = grid
        .par_iter()
        .map(|point| {
            let mut rig = ScenarioParams::default();
            for (name, value) in point {
                rig.set(name, *value)?;
            }
            decide_at(phenomenon, law, p, protocol, &rig)
        })
        .collect();
    let (mut observed, mut decided) = (0usize, 0usize);
    let mut flips = Vec::new();
    let mut undecided = Vec::new();
    for (point, verdict) in grid.iter().zip(verdicts) {
        match verdict {
            Ok(v) => {
                decided += 1;
                observed += usize::from(v.measured);
                if v.measured != measured {
                    flips.push(point.clone());
                }
            }
            Err(e) => undecided.push((point.clone(), e.to_string())),
        }
    }
    Ok(Region {
        axes: axes.iter().copied().collect(),
        points: grid.len(),
        fraction: if decided > 0 {
            observed as f64 / decided as f64
        } else {
            f64::NAN
        },
        flips,
        undecided,
    })
}

/// Every model of the catalog, in its sign-consistent reading: the columns of the paper's
/// Table 2 and of the reference models.
pub fn catalog_laws() -> Vec<Law> {
    ModelId::ALL.iter().map(|&m| Law::from(m)).collect()
}

/// One model's row of Table 2: each phenomenon with its cell.
pub type Row = Vec<(Phenomenon, Cell)>;

/// Table 2 for `laws`: every protocol for every law, run in parallel on rayon's pool
/// (the result does not depend on the number of threads: each cell is computed alone and
/// collected in order).
///
/// With `regions`, each cell is also decided over its grid of rig parameters
/// ([`region`]): about 20 times the work. A cell whose protocol fails in the solver is kept,
/// undecided ([`Cell::measured`] holds why), and the others are decided; bad input fails the
/// table. `progress` is called after each cell.
///
/// A law of the catalog is judged at `parameters` or its own set ([`parameters_for`]) and
/// beside the paper's claim; a law of one's own at `parameters` or the paper's set (which then
/// sets only the rigs' scales), with no claim.
pub fn table(
    laws: &[Law],
    protocol: Protocol,
    parameters: Option<&FrictionParams>,
    regions: bool,
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<(Law, Row)>, ScenarioError> {
    use rayon::prelude::*;
    let jobs: Vec<(&Law, Phenomenon)> = laws
        .iter()
        .flat_map(|law| Phenomenon::ALL.iter().map(move |&p| (law, p)))
        .collect();
    let cells: Vec<Result<Cell, ScenarioError>> = jobs
        .par_iter()
        .map(|&(law, phenomenon)| {
            let p = parameters.copied().unwrap_or_else(|| {
                law.catalog()
                    .map_or_else(FrictionParams::paper, parameters_for)
            });
            let paper = law.catalog().and_then(|m| phenomenon.paper_claim(m));
            let cell = match decide(phenomenon, law, &p, protocol) {
                Ok(v) => Ok(Cell {
                    region: regions
                        .then(|| region(phenomenon, law, &p, protocol, v.measured))
                        .transpose()?,
                    measured: Ok(v.measured),
                    paper,
                    evidence: v.evidence,
                }),
                Err(e @ (ScenarioError::Solver { .. } | ScenarioError::RunFailed(_))) => Ok(Cell {
                    measured: Err(e.to_string()),
                    paper,
                    evidence: BTreeMap::new(),
                    region: None,
                }),
                Err(e) => Err(e),
            };
            progress();
            cell
        })
        .collect();
    let mut cells = cells.into_iter();
    laws.iter()
        .map(|law| {
            let row = Phenomenon::ALL
                .iter()
                .map(|&p| Ok((p, cells.next().expect("one cell per job")?)))
                .collect::<Result<Vec<_>, ScenarioError>>()?;
            Ok((law.clone(), row))
        })
        .collect()
}
