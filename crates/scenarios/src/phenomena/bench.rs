//! The bench on which an experiment judges a law: the law, its parameters, how the protocols
//! integrate, the rig's parameters, and the measurements the experiments share (steady
//! friction, a periodic motion's last cycle, a break-away under a force ramp).

use super::thresholds;
use super::Protocol;
use crate::error::ScenarioError;
use crate::motion::Motion;
use crate::run::{run, run_motion, settling_time, Law, RunSpec};
use crate::scenario::Scenario;
use crate::ScenarioParams;
use friction_models::{FrictionModel, FrictionParams};
use integrators::SolverError;

/// One period of a prescribed periodic motion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cycle {
    /// ∮F dx: the work done against friction, J.
    pub work: f64,
    /// ∮F dv: the friction–velocity loop's area, N·m/s.
    pub area: f64,
    /// The least and the largest friction, N.
    pub range: (f64, f64),
}

/// A break-away under a force ramp.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Breakaway {
    /// The peak friction before gross sliding, N.
    pub force: f64,
    /// When gross sliding started, s.
    pub time: f64,
    /// The least friction after it, N.
    pub kinetic: f64,
}

/// A law set up for judging: what every experiment reads, and the runs they share.
pub struct Bench<'a> {
    law: &'a Law,
    built: &'a dyn FrictionModel,
    p: FrictionParams,
    protocol: Protocol,
    rig: ScenarioParams,
}

impl<'a> Bench<'a> {
    /// `law`, built as `built` from the friction parameters `p`, judged with runs integrated
    /// as `protocol` says on rigs with the parameters `rig`.
    pub fn new(
        law: &'a Law,
        built: &'a dyn FrictionModel,
        p: FrictionParams,
        protocol: Protocol,
        rig: ScenarioParams,
    ) -> Bench<'a> {
        Bench {
            law,
            built,
            p,
            protocol,
            rig,
        }
    }

    /// The law judged.
    pub fn law(&self) -> &Law {
        self.law
    }

    /// The law, built.
    pub fn model(&self) -> &dyn FrictionModel {
        self.built
    }

    /// The friction parameters: the law's (for a model of the catalog) and the scales the
    /// protocols read (F_s, F_c, v_s).
    pub fn friction(&self) -> &FrictionParams {
        &self.p
    }

    /// The rig's parameters the protocols start from (mass, belt, spring, load).
    pub fn rig(&self) -> ScenarioParams {
        self.rig
    }

    /// A run of `scenario` with `params` to `t_end` on `points` output points, integrated as
    /// the protocol says with event switching.
    pub fn spec(
        &self,
        scenario: Scenario,
        params: ScenarioParams,
        t_end: f64,
        points: usize,
    ) -> RunSpec {
        (self.protocol).spec(scenario, self.law, self.p, params, t_end, points)
    }

    /// The failure of the run `what` of this law's protocol (not bad input: the cell is
    /// undecided).
    pub fn failed(&self, what: impl std::fmt::Display, error: &SolverError) -> ScenarioError {
        ScenarioError::Solver {
            what: format!("{} {what}", self.law),
            error: error.clone(),
        }
    }

    /// The run `spec`, or its failure ([`Bench::failed`]).
    pub fn outcome(&self, spec: &RunSpec) -> Result<crate::Outcome, ScenarioError> {
        let o = run(spec, &mut |_| {})?;
        match &o.error {
            Some(e) => Err(self.failed(spec.scenario, e)),
            None => Ok(o),
        }
    }

    /// Steady friction at constant velocity v, reached by simulation.
    pub fn steady(&self, v: f64) -> Result<f64, ScenarioError> {
        let spec = self.spec(Scenario::VELOCITY_SWEEP, ScenarioParams::default(), 0.0, 2);
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
    pub fn rest_stiffness(&self) -> f64 {
        friction_models::steady::rest_stiffness(self.built, 1e-9 * self.p.v_s)
    }

    /// The pre-sliding length the model sets: F_s over its stiffness at rest (zero for a
    /// rigid contact).
    pub fn presliding_length(&self) -> f64 {
        let k = self.rest_stiffness();
        if k > 0.0 {
            self.p.f_s / k
        } else {
            0.0
        }
    }

    /// The level the force ramps are scaled to: max(F_s, F_c), the larger of the static and
    /// kinetic levels (F_s at the paper's parameters).
    pub fn ramp_level(&self) -> f64 {
        self.p.f_s.max(self.p.f_c)
    }

    /// The time constant τ of the internal state at velocity v (the law's own time scale),
    /// 1 s for a law without state.
    pub fn time_scale(&self, v: f64) -> f64 {
        if self.built.n_states() > 0 {
            settling_time(self.built, v) / 20.0
        } else {
            1.0
        }
    }

    /// The last of `cycles` periods of the prescribed periodic `motion` (period `period`):
    /// the work done against friction ∮F dx, the loop area ∮F dv (both integrated by the
    /// solver, as the difference of a run over `cycles` and one over `cycles − 1` periods) and
    /// the range of the friction force over that period.
    pub fn last_cycle(
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

    /// Break-away under a force ramp up to 1.5·max(F_s, F_c): gross sliding starts when |v|
    /// first exceeds v_s (the model's own velocity scale) beyond the pre-sliding length
    /// ([`Bench::presliding_length`]); the break-away force is the peak
    /// friction before that, the kinetic level the least friction after it. `None` when the
    /// body never breaks away (or its peak friction stays under
    /// [`thresholds::BREAKAWAY_MIN`] of F_s: no static level at all).
    pub fn breakaway(&self, rate: f64) -> Result<Option<Breakaway>, ScenarioError> {
        let params = ScenarioParams { rate, ..self.rig };
        // The ramp ends at 1.5 times the larger level: a body that has not broken away by
        // then does not break away (and a stiff LuGre run costs in proportion to its length).
        let t_end = 1.5 * self.ramp_level() / rate;
        let o = self.outcome(&self.spec(Scenario::FORCE_RAMP, params, t_end, 20001))?;
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
}
