//! The driver: steps a [`Stepper`] over a problem, records output, locates events on the
//! method's dense output, applies their actions and restarts the method cleanly after each.

use crate::error::SolverError;
use crate::events::EventWatch;
use crate::options::{Options, Output};
use crate::problem::{Control, Mode, OdeProblem};
use crate::solution::{EventRecord, Failure, Solution};
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
        /// Names of the events handled there.
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

/// An integration in progress.
pub struct Integrator<'a> {
    problem: &'a dyn OdeProblem,
    stepper: Box<dyn Stepper + 'a>,
    options: Options,
    mode: Mode,
    watch: EventWatch,
    solution: Solution,
    grid_next: usize,
    cut_at_event: usize,
    done: bool,
}

impl<'a> Integrator<'a> {
    /// Starts integrating `problem` from `y0` in `mode` at `options.t0` with `stepper`.
    pub fn new(
        problem: &'a dyn OdeProblem,
        mut stepper: Box<dyn Stepper + 'a>,
        y0: &[f64],
        mode: Mode,
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
        let ode = Ode { problem, mode };
        stepper.start(&ode, options.t0, y0)?;
        let mut watch = EventWatch::default();
        watch.start(problem, mode, options.t0, y0, &[]);
        let mut solution = Solution::new(stepper.name(), problem.dim());
        let mut grid_next = 0;
        match &options.output {
            Output::Steps => solution.push(options.t0, y0, mode),
            Output::Grid(times) => {
                while grid_next < times.len() && times[grid_next] <= options.t0 {
                    if times[grid_next] == options.t0 {
                        solution.push(options.t0, y0, mode);
                    }
                    grid_next += 1;
                }
            }
        }
        Ok(Integrator {
            problem,
            stepper,
            options,
            mode,
            watch,
            solution,
            grid_next,
            cut_at_event: 0,
            done: false,
        })
    }

    /// The current mode.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The current time.
    pub fn t(&self) -> f64 {
        self.stepper.t()
    }

    /// Records the grid points in `(t_prev, t]` from the dense output of the last step.
    fn record_grid_until(&mut self, t: f64, inclusive: bool) {
        let Output::Grid(times) = &self.options.output else {
            return;
        };
        let mut y = vec![0.0; self.problem.dim()];
        while self.grid_next < times.len() {
            let tg = times[self.grid_next];
            if tg > t || (!inclusive && tg == t) {
                break;
            }
            self.stepper.dense_output(tg, &mut y);
            self.solution.push(tg, &y, self.mode);
            self.grid_next += 1;
        }
    }

    /// Takes one step and says why it returned.
    pub fn step(&mut self) -> Result<StopReason, SolverError> {
        if self.done {
            return Ok(StopReason::EndReached);
        }
        let t_end = self.options.t_end;
        let ode = Ode {
            problem: self.problem,
            mode: self.mode,
        };
        self.stepper.step(&ode, t_end)?;
        let (t0, t1) = (self.stepper.t_prev(), self.stepper.t());
        let stepper = &self.stepper;
        let found = self
            .watch
            .check(self.problem, self.mode, t0, t1, stepper.y(), &mut |t, y| {
                stepper.dense_output(t, y)
            });
        let Some(found) = found else {
            match self.options.output {
                Output::Steps => self.solution.push(t1, self.stepper.y(), self.mode),
                Output::Grid(_) => self.record_grid_until(t1, true),
            }
            if t1 >= t_end {
                self.done = true;
                return Ok(StopReason::EndReached);
            }
            return Ok(StopReason::StepTaken { t: t1 });
        };
        self.handle(found.t, &found.indices)
    }

    /// Applies the events `indices` at `t`, records both sides and restarts the method.
    fn handle(&mut self, t: f64, indices: &[usize]) -> Result<StopReason, SolverError> {
        self.cut_at_event += 1;
        self.record_grid_until(t, false);
        let mut y_left = vec![0.0; self.problem.dim()];
        self.stepper.dense_output(t, &mut y_left);
        if let Output::Steps = self.options.output {
            self.solution.push(t, &y_left, self.mode);
        }
        let mut y = y_left.clone();
        let mut names = Vec::new();
        let mut stop = false;
        let mode_before = self.mode;
        for &i in indices {
            let name = self.problem.events(mode_before)[i].name;
            let before = y.clone();
            let control = self.problem.on_event(i, t, &mut y, mode_before);
            let mode_after = match control {
                Control::Switch(m) => m,
                Control::Continue | Control::Stop => self.mode,
            };
            self.solution.events.push(EventRecord {
                t,
                name,
                index: i,
                mode_before: self.mode,
                mode_after,
                y_left: before,
                y_right: y.clone(),
            });
            names.push(name);
            self.watch.record(t, name, &self.options.zeno)?;
            stop |= control == Control::Stop;
            self.mode = mode_after;
        }
        check_finite(&y, t, 0.0, "state after an event action")?;
        self.solution.push(t, &y, self.mode);
        if stop || t >= self.options.t_end {
            self.done = true;
            return Ok(if stop {
                StopReason::Stopped { t }
            } else {
                StopReason::EndReached
            });
        }
        let ode = Ode {
            problem: self.problem,
            mode: self.mode,
        };
        self.stepper.start(&ode, t, &y)?;
        let fired: &[usize] = if self.mode == mode_before {
            indices
        } else {
            &[]
        };
        self.watch.start(self.problem, self.mode, t, &y, fired);
        Ok(StopReason::EventFound { t, names })
    }

    /// The solution so far, with the statistics of the run.
    pub fn solution(&self) -> Solution {
        let mut s = self.solution.clone();
        s.stats = self.stepper.stats();
        s.stats.events = s.events.len();
        s.stats.cut_at_event = self.cut_at_event;
        s.stiffness_detected_at = self.stepper.stiffness_detected_at();
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
        loop {
            match self.step() {
                Ok(StopReason::EndReached | StopReason::Stopped { .. }) => {
                    return Ok(self.solution())
                }
                Ok(_) => observe(self.t()),
                Err(error) => {
                    return Err(Failure {
                        error,
                        solution: Box::new(self.solution()),
                    })
                }
            }
        }
    }
}
