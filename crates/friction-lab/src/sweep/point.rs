//! One point of a sweep: its run, set up and checked, run until it settles, and reduced to its
//! settled-state measures ([`scenarios::analysis::settled`]) and regime.

use crate::error::AppError;
use crate::trajectory::step_doubling;
use friction_systems::{simulate, Layout, Run, Scheme, System, STICK};
use integrators::{even_grid, Options, Output, Stats, StepControl};
use scenarios::analysis::closed_loop::ClosedLoop;
use scenarios::analysis::settled::{spanned, until_settled, Settled, Trace};
use scenarios::simulate_until;
use scenarios::stick_slip::Regime;
use scenarios::verdict::Verdict;
use scenarios::{Limits, RunSpec};
use serde::Serialize;

/// The most numbers (points × unknowns) a system's run may record: 2.5e8, about 2 GB; more
/// would exhaust the memory of a workstation.
pub const RECORD_LIMIT: usize = 250_000_000;

/// The run at one point of a sweep.
pub enum PointRun {
    /// A rig.
    Rig(RunSpec),
    /// The chain or a system file.
    System(SystemPoint),
}

/// The run of a system (the chain or a system file) at one point of a sweep.
pub struct SystemPoint {
    /// The system.
    pub system: System,
    /// How it is integrated.
    pub scheme: Scheme,
    /// The step control.
    pub step: StepControl,
    /// The bounds of the run.
    pub limits: Limits,
    /// The end time, s.
    pub t_end: f64,
    /// Evenly spaced output points on [0, t_end].
    pub points: usize,
    /// The body measured (0-based).
    pub body: usize,
}

impl SystemPoint {
    /// The options of the run over `factor` times its span: the output spacing kept, within
    /// the numbers a run may record ([`RECORD_LIMIT`]).
    fn options(&self, factor: u32) -> Options {
        let dim = Layout::of(&self.system).dim();
        let points = ((self.points - 1) * factor as usize + 1).min(RECORD_LIMIT / dim.max(1));
        let span = self.t_end * f64::from(factor);
        grid_options(self.step, &self.limits, span, points)
    }

    /// The measured body of `run`, judged by [`Verdict::of_run`].
    fn measured(&self, run: &Run) -> Measured {
        Measured {
            trace: body_trace(run, self.body),
            stats: run.solution.stats,
            verdict: Verdict::of_run(
                run.error.as_ref(),
                run.energy().map(|e| e.relative_residual),
                run.instability(&self.scheme, self.step).as_ref(),
            ),
            surface_velocity: (self.system.contacts.iter())
                .find(|c| c.body == self.body)
                .map_or(0.0, |c| c.surface_velocity),
            closed_loop: None,
        }
    }
}

/// The options of a system's run over [0, `t_end`] with `points` evenly spaced output times
/// (a system records its grid only), its step control and bounds.
pub fn grid_options(step: StepControl, limits: &Limits, t_end: f64, points: usize) -> Options {
    Options {
        step,
        max_steps: limits.max_steps,
        time_limit: limits.time_limit,
        time_limit_since: limits.time_limit_since,
        output: Output::GridOnly(even_grid(0.0, t_end, points)),
        ..Options::adaptive(0.0, t_end, 1e-8, 1e-10)
    }
}

/// One point's result.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PointResult {
    /// The point: the value of every axis, in axis order.
    pub values: Vec<f64>,
    /// Its settled-state measures.
    pub settled: Settled,
    /// Its regime (`Regime::of`, the stick–slip map's classification, against the velocity of
    /// the surface under the measured body; for a rig whose body a controller positions,
    /// `Regime::of_closed_loop`); `None` for a run that failed.
    pub regime: Option<Regime>,
    /// What the closed loop did, for a rig whose body a controller positions (the `servo`):
    /// its settled state is then the loop's, read off the position error.
    pub closed_loop: Option<ClosedLoop>,
    /// Solver statistics.
    pub stats: Stats,
    /// What the run is worth, and why ([`Verdict::of_run`]): a `diverged` or `failed` point
    /// has no measures (NaN, no closed loop) and no regime.
    pub verdict: Verdict,
}

/// Body `body` of a system's `run` as a trace: its recorded points and its switches into stick.
fn body_trace(run: &Run, body: usize) -> Trace {
    let mut trace = Trace::default();
    for b in run.body(body) {
        trace.t.push(b.t);
        trace.x.push(b.x);
        trace.v.push(b.v);
        trace.friction.push(b.friction);
    }
    trace.stick_entries = run
        .contact_events()
        .iter()
        .filter(|e| e.body == body && e.to == STICK && e.from != STICK)
        .map(|e| e.t)
        .collect();
    trace
}

/// The verdict of a point run at a fixed step `h` by step doubling: its `trace` against
/// `fine`, the same run at h/2 ([`step_doubling`]), `inaccurate` above
/// [`crate::trajectory::STEP_DOUBLING_INACCURATE`]; `ok` where the run at h/2 stopped.
fn doubling_verdict(trace: &Trace, fine: Option<&Trace>, h: f64) -> Verdict {
    let estimate = fine
        .and_then(|f| step_doubling((&trace.t, &trace.x, &trace.v), (&f.t, &f.x, &f.v), 1, None));
    Verdict::inaccurate(estimate.and_then(|d| d.reason(h)))
}

impl PointRun {
    /// Runs the point and measures its settled state over its last fraction `settle`: its span
    /// doubled (the output spacing kept) while the run ends without an error and has not
    /// settled ([`Settled::settled`]; [`until_settled`]). At adaptive steps each longer run
    /// continues the one before ([`scenarios::run_until`], [`simulate_until`]); at a fixed step,
    /// judged by step doubling, each span is run from the start.
    pub fn run(&self, settle: f64) -> Result<PointResult, AppError> {
        let done = |point: &PointResult| point.settled.settled || point.verdict.is_broken();
        match self {
            PointRun::Rig(spec) if !matches!(spec.step, StepControl::Fixed { .. }) => {
                let measured = |o: &scenarios::Outcome| Measured::of_rig(spec, o).result(settle);
                let o = scenarios::run_until(spec, &mut |o| done(&measured(o)))?;
                Ok(measured(&o))
            }
            PointRun::System(p) if !matches!(p.step, StepControl::Fixed { .. }) => {
                let measured = |run: &Run| p.measured(run).result(settle);
                let options = |factor| p.options(factor);
                let run = simulate_until(&p.system, p.scheme, &options, &mut |_, run| {
                    done(&measured(run))
                })?;
                Ok(measured(&run))
            }
            _ => until_settled(|factor| self.spanned(settle, factor), done),
        }
    }

    /// Runs the point over `factor` times its span, with `factor` times its output intervals,
    /// and measures its settled state.
    fn spanned(&self, settle: f64, factor: u32) -> Result<PointResult, AppError> {
        let measured = match self {
            PointRun::Rig(spec) => {
                let o = scenarios::run(&spanned(spec, factor), &mut |_| {})?;
                let mut measured = Measured::of_rig(spec, &o);
                let (trace, verdict) = (&measured.trace, measured.verdict.clone());
                measured.verdict = match (spec.step, &o.error) {
                    (StepControl::Fixed { h }, None) => {
                        let half = RunSpec {
                            step: StepControl::Fixed { h: h / 2.0 },
                            ..spanned(spec, factor)
                        };
                        let fine = scenarios::run(&half, &mut |_| {})?;
                        let fine = fine.error.is_none().then(|| Trace::of_outcome(&fine));
                        verdict.and(doubling_verdict(trace, fine.as_ref(), h))
                    }
                    _ => verdict,
                };
                measured
            }
            PointRun::System(p) => {
                let options = p.options(factor);
                let run = simulate(&p.system, p.scheme, options.clone(), &mut |_| {})?;
                let mut measured = p.measured(&run);
                if let (StepControl::Fixed { h }, None) = (p.step, &run.error) {
                    let half = Options {
                        step: StepControl::Fixed { h: h / 2.0 },
                        ..options
                    };
                    let fine = simulate(&p.system, p.scheme, half, &mut |_| {})?;
                    let fine = fine.error.is_none().then(|| body_trace(&fine, p.body));
                    let doubling = doubling_verdict(&measured.trace, fine.as_ref(), h);
                    measured.verdict = measured.verdict.and(doubling);
                }
                measured
            }
        };
        Ok(measured.result(settle))
    }
}

/// What a point's run gives its measures from: the measured body's trace, the counts, the
/// verdict, the velocity of the surface under the body and, for a rig whose body a
/// controller positions, the closed loop.
struct Measured {
    trace: Trace,
    stats: Stats,
    verdict: Verdict,
    surface_velocity: f64,
    closed_loop: Option<ClosedLoop>,
}

impl Measured {
    /// A rig's outcome `o` of `spec`, judged by [`Verdict::of_run`].
    fn of_rig(spec: &RunSpec, o: &scenarios::Outcome) -> Measured {
        Measured {
            trace: Trace::of_outcome(o),
            stats: o.stats,
            verdict: Verdict::of_run(
                o.error.as_ref(),
                o.energy.map(|e| e.relative_residual),
                o.instability.as_ref(),
            ),
            // The belt under the body, where the rig has one; the floor otherwise.
            surface_velocity: match spec.scenario.parameters().contains(&"v_belt") {
                true => spec.params.v_belt,
                false => 0.0,
            },
            closed_loop: ClosedLoop::of_outcome(o),
        }
    }

    /// The point's result: its settled state over the last fraction `settle` and its regime.
    fn result(self, settle: f64) -> PointResult {
        let Measured {
            trace,
            stats,
            verdict,
            surface_velocity,
            closed_loop,
        } = self;
        let mut settled = Settled::of(&trace, settle);
        // A closed loop has settled when its position error has; its cycle is read off that
        // error (`closed_loop`), not off the velocity's crossings, which a body creeping
        // while it sticks (LuGre) crosses at random.
        if let Some(c) = &closed_loop {
            settled.settled = c.settled;
            settled.period = c.period;
            settled.x_amplitude = c.amplitude;
            // The velocity's drift is not the loop's criterion.
            settled.drift = f64::NAN;
        }
        // A run that failed stopped short of its span, and one that diverged computed its
        // motion from the integration: whatever its window shows is no measure of the point,
        // no settled state and no regime.
        let broken = verdict.is_broken();
        if broken {
            settled = settled.undefined();
        }
        let regime = (!broken).then(|| match &closed_loop {
            Some(c) => Regime::of_closed_loop(c),
            None => Regime::of(&settled, surface_velocity),
        });
        PointResult {
            values: Vec::new(),
            settled,
            regime,
            closed_loop: closed_loop.filter(|_| !broken),
            stats,
            verdict,
        }
    }
}
