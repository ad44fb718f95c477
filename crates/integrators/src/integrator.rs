//! The driver: steps a [`Stepper`] over a problem, records output, locates events on the
//! method's dense output, applies their actions and restarts the method cleanly after each.

use crate::error::SolverError;
use crate::events::EventWatch;
use crate::options::{Options, Output};
use crate::problem::{Control, Mode, OdeProblem};
use crate::solution::{EventRecord, Failure, ModeSwitch, Solution};
use crate::stepper::{check_finite, Ode, Stepper};

/// Why [`Integrator::step`] returned.
#[derive(Clone, Debug, PartialEq)]
pub enum StopReason {
    /// An ordinary step was taken; the integration goes on.
    StepTaken {
        /// Time reached.
        t: f64,
    },
    /// Events were located and handled; the integration goes on from them.
    EventFound {
        /// Time of the event.
        t: f64,
        /// Names of the event functions that fired there.
        names: Vec<&'static str>,
    },
    /// The end time was reached.
    EndReached,
    /// An event's action ended the integration.
    Stopped {
        /// Time of the event.
        t: f64,
    },
}

/// The integration as it stood before a step that may read where it ends
/// ([`Stepper::may_read_end`]): what [`Integrator::extend`] continues from.
struct Checkpoint {
    stepper: Box<dyn Stepper>,
    modes: Vec<Mode>,
    watch: EventWatch,
    /// Points and events recorded then.
    recorded: (usize, usize),
    grid_next: usize,
    cut_at_event: usize,
    steps: usize,
}

/// An integration in progress.
pub struct Integrator<'a> {
    problem: &'a dyn OdeProblem,
    stepper: Box<dyn Stepper + 'a>,
    options: Options,
    /// The chattering guard's window, s.
    zeno_window: f64,
    modes: Vec<Mode>,
    /// For a method that settles the modes itself: the modes at the start of a step that
    /// switched, and those reported inside it.
    modes_before: Vec<Mode>,
    modes_inside: Vec<Mode>,
    watch: EventWatch,
    solution: Solution,
    grid_next: usize,
    /// Scratch state for dense output at grid points.
    y_grid: Vec<f64>,
    cut_at_event: usize,
    /// Steps taken through [`Integrator::step`], for the step cap of every method.
    steps: usize,
    /// When the wall-clock limit started counting: the start of the integration, or
    /// [`Options::time_limit_since`].
    clock: std::time::Instant,
    done: bool,
    /// Whether an event's action stopped the integration.
    stopped: bool,
    /// Whether the run keeps a [`Checkpoint`] for [`Integrator::extend`].
    resumable: bool,
    checkpoint: Option<Checkpoint>,
}

impl<'a> Integrator<'a> {
    /// Starts integrating `problem` from `y0` in `modes` at `options.t0` with `stepper`.
    pub fn new(
        problem: &'a dyn OdeProblem,
        mut stepper: Box<dyn Stepper + 'a>,
        y0: &[f64],
        modes: &[Mode],
        options: Options,
    ) -> Result<Self, SolverError> {
        options.validate()?;
        if y0.len() != problem.dim() {
            return Err(SolverError::InvalidOption {
                name: "initial state length",
                value: y0.len() as f64,
                allowed: "the problem's dimension",
            });
        }
        check_finite(y0, options.t0, 0.0, "initial state")?;
        stepper.start(&Ode { problem, modes }, options.t0, y0)?;
        let mut watch = EventWatch::default();
        if stepper.locates_events() {
            watch.start(problem, modes, options.t0, y0, &[]);
        }
        let mut solution = Solution::new(stepper.name(), problem.dim(), modes.len());
        let mut grid_next = 0;
        match options.output.grid() {
            None => solution.push(options.t0, y0, modes),
            Some(times) => {
                while grid_next < times.len() && times[grid_next] <= options.t0 {
                    if times[grid_next] == options.t0 {
                        solution.push(options.t0, y0, modes);
                    }
                    grid_next += 1;
                }
            }
        }
        let clock = options
            .time_limit_since
            .unwrap_or_else(std::time::Instant::now);
        Ok(Integrator {
            problem,
            stepper,
            zeno_window: options.zeno.window_s(problem.time_scale()),
            options,
            modes: modes.to_vec(),
            modes_before: modes.to_vec(),
            modes_inside: modes.to_vec(),
            watch,
            solution,
            grid_next,
            y_grid: vec![0.0; problem.dim()],
            cut_at_event: 0,
            steps: 0,
            clock,
            done: false,
            stopped: false,
            resumable: false,
            checkpoint: None,
        })
    }

    /// The integration kept ready to be continued to a later end ([`Integrator::extend`]):
    /// a copy of the method is kept before every step that may read the end (a few steps a
    /// run, and the first after each event).
    pub fn resumable(mut self) -> Self {
        self.resumable = true;
        self
    }

    /// Continues a run that reached its end to the later end of `options`, which must be
    /// this run's options but for the end time, the largest step and the output grid (whose
    /// points up to the old end must be the same): from before the step that read the old
    /// end, the output recorded since dropped, so that the run goes on as one from the start
    /// to the new end would, step for step. `false`, the run left as it is, where it cannot: a
    /// run not made [`Integrator::resumable`], not at its end (failed or stopped by an
    /// event), a method that cannot be copied or whose steps read the old end
    /// ([`Stepper::resume`]), or other options.
    pub fn extend(&mut self, options: Options) -> bool {
        let same_but_end = Options {
            t_end: options.t_end,
            h_max: options.h_max,
            output: options.output.clone(),
            ..self.options.clone()
        } == options;
        let Some(c) = self.checkpoint.as_mut() else {
            return false;
        };
        let grid_kept = match (&self.options.output, &options.output) {
            (Output::Steps, Output::Steps) => true,
            (Output::Grid(old), Output::Grid(new))
            | (Output::GridOnly(old), Output::GridOnly(new)) => {
                new.get(..c.grid_next) == old.get(..c.grid_next)
            }
            _ => false,
        };
        if !self.done
            || self.stopped
            || !same_but_end
            || !grid_kept
            || options.t_end <= self.options.t_end
            || !c.stepper.resume(&options)
        {
            return false;
        }
        let Some(c) = self.checkpoint.take() else {
            return false;
        };
        self.stepper = c.stepper;
        self.modes = c.modes;
        self.watch = c.watch;
        self.solution.keep_first(c.recorded.0, c.recorded.1);
        self.grid_next = c.grid_next;
        self.cut_at_event = c.cut_at_event;
        self.steps = c.steps;
        self.done = false;
        self.options = options;
        true
    }

    /// The current modes.
    pub fn modes(&self) -> &[Mode] {
        &self.modes
    }

    /// The current time.
    pub fn t(&self) -> f64 {
        self.stepper.state().t
    }

    /// Records the grid points in `(t_prev, t]` from the dense output of the last step.
    fn record_grid_until(&mut self, t: f64, inclusive: bool) {
        let Some(times) = self.options.output.grid() else {
            return;
        };
        while self.grid_next < times.len() {
            let tg = times[self.grid_next];
            if tg > t || (!inclusive && tg == t) {
                break;
            }
            self.stepper.dense_output(tg, &mut self.y_grid);
            self.solution.push(tg, &self.y_grid, &self.modes);
            self.grid_next += 1;
        }
    }

    /// The grid points at the event time `t` itself (those before it are recorded from the
    /// step's dense output): the state `y` after the event's action, which a run that ends at
    /// the event would otherwise never record. Where events are recorded, that state is
    /// already the point after the event, and the grid point is not written twice.
    fn record_grid_at_event(&mut self, t: f64, y: &[f64]) {
        let Some(times) = self.options.output.grid() else {
            return;
        };
        while self.grid_next < times.len() && times[self.grid_next] == t {
            if !self.options.output.records_events() {
                self.solution.push(t, y, &self.modes);
            }
            self.grid_next += 1;
        }
    }

    /// Takes one step and says why it returned.
    pub fn step(&mut self) -> Result<StopReason, SolverError> {
        if self.done {
            return Ok(StopReason::EndReached);
        }
        let t_end = self.options.t_end;
        self.steps += 1;
        if self.steps > self.options.max_steps {
            return Err(SolverError::TooManySteps {
                t: self.stepper.state().t,
                h: self.stepper.state().h,
                max: self.options.max_steps,
            });
        }
        if let Some(limit) = self.options.time_limit {
            if self.clock.elapsed().as_secs_f64() > limit {
                return Err(SolverError::TimeLimit {
                    t: self.stepper.state().t,
                    limit,
                });
            }
        }
        if crate::interrupt::requested() {
            return Err(SolverError::Interrupted {
                t: self.stepper.state().t,
            });
        }
        // A copy whose steps read the end already cannot be continued: the last one that
        // can is kept instead.
        let copy = (self.resumable && self.stepper.may_read_end(t_end))
            .then(|| self.stepper.copy())
            .flatten()
            .and_then(|mut copy| copy.resume(&self.options).then_some(copy));
        if let Some(stepper) = copy {
            self.checkpoint = Some(Checkpoint {
                stepper,
                modes: self.modes.clone(),
                watch: self.watch.clone(),
                recorded: (self.solution.len(), self.solution.events.len()),
                grid_next: self.grid_next,
                cut_at_event: self.cut_at_event,
                // This step is counted already; a continued run counts it again.
                steps: self.steps - 1,
            });
        }
        let ode = Ode {
            problem: self.problem,
            modes: &self.modes,
        };
        self.stepper.step(&ode, t_end)?;
        let (t0, t1) = (self.stepper.state().t_prev, self.stepper.state().t);
        if !self.stepper.locates_events() {
            return Ok(self.record_own_switches(t1));
        }
        let stepper = &self.stepper;
        let found = self.watch.check(
            self.problem,
            &self.modes,
            t0,
            t1,
            &stepper.state().y,
            &mut |t, y| stepper.dense_output(t, y),
        );
        let Some(found) = found else {
            match self.options.output {
                Output::Steps => self.solution.push(t1, &self.stepper.state().y, &self.modes),
                _ => self.record_grid_until(t1, true),
            }
            if t1 >= t_end {
                self.done = true;
                return Ok(StopReason::EndReached);
            }
            return Ok(StopReason::StepTaken { t: t1 });
        };
        self.handle(found.t, found.indices)
    }

    /// After a step of a method that settles the modes itself (time-stepping) to `t1`: its
    /// switches applied and recorded as an event at the step's end, the output inside the step
    /// recorded with [`Stepper::modes_inside`], and, where events are recorded, the end of a
    /// step that switched.
    fn record_own_switches(&mut self, t1: f64) -> StopReason {
        let record = self.stepper.take_switches();
        // The modes inside the step: those through it, or, where it switched, the method's
        // reading of before and after (buffers kept: no allocation a step).
        if let Some(r) = &record {
            self.modes_before.copy_from_slice(&self.modes);
            for s in &r.switches {
                self.modes[s.component] = s.to;
            }
            self.stepper
                .modes_inside(&self.modes_before, &self.modes, &mut self.modes_inside);
        } else {
            self.modes_inside.copy_from_slice(&self.modes);
        }
        match self.options.output.grid() {
            None => self.solution.push(t1, &self.stepper.state().y, &self.modes),
            Some(times) => {
                while self.grid_next < times.len() && times[self.grid_next] <= t1 {
                    let tg = times[self.grid_next];
                    if tg == t1 {
                        self.solution.push(t1, &self.stepper.state().y, &self.modes);
                    } else {
                        self.stepper.dense_output(tg, &mut self.y_grid);
                        self.solution.push(tg, &self.y_grid, &self.modes_inside);
                    }
                    self.grid_next += 1;
                }
            }
        }
        if let Some(record) = record {
            let end_recorded = self.solution.t.last() == Some(&t1);
            if self.options.output.records_events() && !end_recorded {
                self.solution.push(t1, &self.stepper.state().y, &self.modes);
            }
            self.solution.events.push(record);
        }
        if t1 >= self.options.t_end {
            self.done = true;
            return StopReason::EndReached;
        }
        StopReason::StepTaken { t: t1 }
    }

    /// Applies the events `fired` at `t`, records both sides and restarts the method.
    fn handle(&mut self, t: f64, fired: Vec<usize>) -> Result<StopReason, SolverError> {
        self.cut_at_event += 1;
        self.record_grid_until(t, false);
        let mut y = vec![0.0; self.problem.dim()];
        self.stepper.dense_output(t, &mut y);
        if let Output::Steps = self.options.output {
            self.solution.push(t, &y, &self.modes);
        }
        let names: Vec<&'static str> = fired
            .iter()
            .map(|&i| self.watch.spec(i).expect("a fired event is watched").name)
            .collect();
        let before = self.modes.clone();
        let control = self.problem.on_events(&fired, t, &mut y, &mut self.modes);
        let switches: Vec<ModeSwitch> = before
            .iter()
            .zip(&self.modes)
            .enumerate()
            .filter(|(_, (a, b))| a != b)
            .map(|(component, (&from, &to))| ModeSwitch {
                component,
                from,
                to,
            })
            .collect();
        // A fired function watched as before after the action is re-armed by its first sign.
        let rearm: Vec<usize> = fired
            .iter()
            .copied()
            .filter(|&i| self.problem.event_spec(i, &self.modes) == self.watch.spec(i))
            .collect();
        self.watch
            .record(t, names[0], &self.options.zeno, self.zeno_window)?;
        self.solution.events.push(EventRecord {
            t,
            fired,
            names: names.clone(),
            switches,
        });
        check_finite(&y, t, 0.0, "state after an event action")?;
        if self.options.output.records_events() {
            self.solution.push(t, &y, &self.modes);
        }
        self.record_grid_at_event(t, &y);
        let stop = control == Control::Stop;
        if stop || t >= self.options.t_end {
            self.done = true;
            self.stopped = stop;
            return Ok(if stop {
                StopReason::Stopped { t }
            } else {
                StopReason::EndReached
            });
        }
        let ode = Ode {
            problem: self.problem,
            modes: &self.modes,
        };
        self.stepper.start(&ode, t, &y)?;
        self.watch.start(self.problem, &self.modes, t, &y, &rearm);
        Ok(StopReason::EventFound { t, names })
    }

    /// The solution so far, with the statistics of the run.
    pub fn solution(&self) -> Solution {
        self.with_stats(self.solution.clone())
    }

    /// `s` with the statistics of the run so far.
    fn with_stats(&self, mut s: Solution) -> Solution {
        s.stats = self.stepper.stats();
        if self.stepper.locates_events() {
            s.stats.events = s.events.iter().map(|e| e.fired.len()).sum();
        }
        s.stats.cut_at_event = self.cut_at_event;
        s.stiffness_detected_at = self.stepper.stiffness_detected_at();
        s.method_switches = self.stepper.method_switches().to_vec();
        s
    }

    /// Integrates to the end (or to a stopping event). A failure keeps the solution computed
    /// before it.
    pub fn solve(self) -> Result<Solution, Failure> {
        self.solve_observed(&mut |_| {})
    }

    /// As [`Integrator::solve`], telling `observe` the time reached after every step (for a
    /// progress display).
    pub fn solve_observed(mut self, observe: &mut dyn FnMut(f64)) -> Result<Solution, Failure> {
        match self.advance(observe) {
            Ok(()) => Ok(self.into_solution()),
            Err(error) => Err(Failure {
                error,
                solution: Box::new(self.into_solution()),
            }),
        }
    }

    /// Steps to the end (or to a stopping event), telling `observe` the time reached after
    /// every step; the integration stays, to be read ([`Integrator::solution`]) and extended
    /// ([`Integrator::extend`]). A failure keeps what was computed before it.
    pub fn advance(&mut self, observe: &mut dyn FnMut(f64)) -> Result<(), SolverError> {
        loop {
            match self.step()? {
                StopReason::EndReached | StopReason::Stopped { .. } => return Ok(()),
                _ => observe(self.t()),
            }
        }
    }

    /// The solution, without copying it.
    fn into_solution(mut self) -> Solution {
        let empty = Solution::new(self.solution.solver, 0, 0);
        let s = std::mem::replace(&mut self.solution, empty);
        self.with_stats(s)
    }
}
