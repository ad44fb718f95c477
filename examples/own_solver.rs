//! A one-step method written outside friction-lab, run and studied like a built-in one.
//!
//! The Bogacki–Shampine 3(2) pair (Bogacki & Shampine 1989, *Appl. Math. Lett.* 2(4); MATLAB's
//! `ode23`): three new stages a step (the fourth is the next step's first, FSAL), a
//! third-order solution with an embedded second-order one for the error estimate, and the
//! cubic Hermite interpolant of the step's ends as dense output (third order, as the method).
//! It implements the public `Stepper` and `OneStepMethod` traits; wrapped as `Solver::own`, it
//! integrates a stick–slip belt with event location on its dense output, goes through a
//! convergence study at fixed steps and a work–precision study beside Dormand–Prince,
//! without a line of friction-lab changed; registered (`Solver::register`), it is found by its
//! name as a built-in one is, here by the command line's own library call.
//!
//! Run: `cargo run --release --example own_solver`.

use clap::Parser;
use friction_lab::artifacts::Data;
use friction_lab::friction_models::{FrictionParams, ModelId, Variant};
use friction_lab::friction_systems::{simulate, End, Scheme, Switching, System};
use friction_lab::integrators::stepper::{
    check_finite, check_limits, hermite_cubic, next_grid_point, wrms,
};
use friction_lab::integrators::{
    Ode, OneStepMethod, Options, Solver, SolverError, Stats, StepControl, Stepper, StepperState,
};
use friction_lab::scenarios::studies::{self, ErrorMeasure, Method, SystemCase};
use std::sync::Arc;

// The Butcher tableau of Bogacki & Shampine (1989), Table 1: nodes, stages, third-order
// weights B (the fourth stage, at the new point, has weight 0), and E = B − B̂, the
// difference from the second-order weights B̂ = (7/24, 1/4, 1/3, 1/8).
const C2: f64 = 0.5;
const C3: f64 = 0.75;
const A21: f64 = 0.5;
const A32: f64 = 0.75;
const B1: f64 = 2.0 / 9.0;
const B2: f64 = 1.0 / 3.0;
const B3: f64 = 4.0 / 9.0;
const E1: f64 = 2.0 / 9.0 - 7.0 / 24.0;
const E2: f64 = 1.0 / 3.0 - 1.0 / 4.0;
const E3: f64 = 4.0 / 9.0 - 1.0 / 3.0;
const E4: f64 = -1.0 / 8.0;

// Step-size control: h_new = h·clamp(SAFETY·err^(−1/3), MIN_FACTOR, MAX_FACTOR), the exponent
// 1/(q+1) of the embedded order q = 2 (Hairer, Nørsett, Wanner, *Solving ODEs I*, II.4,
// eq. (4.13)), with the safety factor and limits of that section.
const SAFETY: f64 = 0.9;
const MIN_FACTOR: f64 = 0.2;
const MAX_FACTOR: f64 = 5.0;
const EXPONENT: f64 = 1.0 / 3.0;

/// The Bogacki–Shampine method as a friction-lab solver.
#[derive(Debug)]
pub struct BogackiShampine;

/// The one instance `Solver::own` refers to.
pub static BS23: BogackiShampine = BogackiShampine;

impl OneStepMethod for BogackiShampine {
    fn name(&self) -> &'static str {
        "bs23"
    }

    fn order(&self) -> usize {
        3
    }

    fn is_implicit(&self) -> bool {
        false
    }

    fn is_fixed_step(&self) -> bool {
        false
    }

    fn takes_fixed_steps(&self) -> bool {
        true
    }

    fn stepper(&self, options: &Options, dim: usize) -> Result<Box<dyn Stepper>, SolverError> {
        Ok(Box::new(Bs23Stepper::new(options, dim)))
    }
}

/// The method's state between steps.
#[derive(Debug)]
pub struct Bs23Stepper {
    control: StepControl,
    h_max: f64,
    max_steps: usize,
    attempts: usize,
    t_start: f64,
    /// Where the method stands.
    state: StepperState,
    y_prev: Vec<f64>,
    y1: Vec<f64>,
    /// k[0] = f(t, y) (FSAL), k[1], k[2] the next stages, k[3] = f(t + h, y1).
    k: [Vec<f64>; 4],
    /// f at the start of the last accepted step, for the dense output.
    f_prev: Vec<f64>,
    err: Vec<f64>,
    stats: Stats,
}

impl Bs23Stepper {
    fn new(options: &Options, dim: usize) -> Self {
        let v = || vec![0.0; dim];
        Bs23Stepper {
            control: options.step,
            h_max: options.h_max(),
            max_steps: options.max_steps,
            attempts: 0,
            t_start: 0.0,
            state: StepperState::new(dim),
            y_prev: v(),
            y1: v(),
            k: [v(), v(), v(), v()],
            f_prev: v(),
            err: v(),
            stats: Stats::default(),
        }
    }

    /// The stages of a step of size h from (t, y): y1, f(t + h, y1) in k[3], and the error
    /// estimate `err = h·Σ E_i·k_i`.
    fn stages(&mut self, ode: &Ode, h: f64) {
        let (t, y) = (self.state.t, &self.state.y);
        let [k1, k2, k3, k4] = &mut self.k;
        let y1 = &mut self.y1;
        for i in 0..y.len() {
            y1[i] = y[i] + h * A21 * k1[i];
        }
        ode.explicit_rhs(t + C2 * h, y1, k2, &mut self.stats);
        for i in 0..y.len() {
            y1[i] = y[i] + h * A32 * k2[i];
        }
        ode.explicit_rhs(t + C3 * h, y1, k3, &mut self.stats);
        for i in 0..y.len() {
            y1[i] = y[i] + h * (B1 * k1[i] + B2 * k2[i] + B3 * k3[i]);
        }
        ode.explicit_rhs(t + h, y1, k4, &mut self.stats);
        for i in 0..y.len() {
            self.err[i] = h * (E1 * k1[i] + E2 * k2[i] + E3 * k3[i] + E4 * k4[i]);
        }
    }

    /// Accepts the step to `t_new`: the new point, FSAL, the dense output's data.
    fn accept(&mut self, h: f64, t_new: f64) -> Result<(), SolverError> {
        check_finite(&self.y1, self.state.t, h, "Bogacki-Shampine step result")?;
        std::mem::swap(&mut self.y_prev, &mut self.state.y);
        std::mem::swap(&mut self.state.y, &mut self.y1);
        let [k1, .., k4] = &mut self.k;
        std::mem::swap(&mut self.f_prev, k1);
        std::mem::swap(k1, k4);
        self.state.t_prev = self.state.t;
        self.state.t = t_new;
        self.stats.steps += 1;
        Ok(())
    }

    /// A first step from the sizes of y and f: 1 % of the time y would take to change by its
    /// own size at the rate f (the first half of Hairer's HINIT), within the largest step.
    fn initial_step(&self, rtol: f64, atol: f64, t_stop: f64) -> f64 {
        let zero = vec![0.0; self.state.y.len()];
        let d0 = wrms(&self.state.y, &self.state.y, &zero, rtol, atol);
        let d1 = wrms(&self.k[0], &self.state.y, &zero, rtol, atol);
        let h = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        h.min(self.h_max).min(t_stop - self.state.t)
    }
}

impl Stepper for Bs23Stepper {
    fn name(&self) -> &'static str {
        BS23.name()
    }

    fn start(&mut self, ode: &Ode, t: f64, y: &[f64]) -> Result<(), SolverError> {
        ode.require_regular_mass(BS23.name())?;
        self.t_start = t;
        self.state.t_prev = t;
        self.state.t = t;
        self.state.y.copy_from_slice(y);
        self.y_prev.copy_from_slice(y);
        ode.explicit_rhs(t, y, &mut self.k[0], &mut self.stats);
        self.f_prev.copy_from_slice(&self.k[0]);
        // Zero: the initial-step estimate chooses the first step.
        self.state.h = self.control.given_step().unwrap_or(0.0);
        Ok(())
    }

    fn step(&mut self, ode: &Ode, t_stop: f64) -> Result<(), SolverError> {
        let (rtol, atol) = match self.control {
            StepControl::Fixed { h } => {
                let t_new = next_grid_point(self.t_start, h, self.state.t, t_stop);
                let step = t_new - self.state.t;
                self.attempts += 1;
                check_limits(self.attempts, self.max_steps, self.state.t, step)?;
                self.stages(ode, step);
                return self.accept(step, t_new);
            }
            StepControl::Adaptive { rtol, atol, .. } => (rtol, atol),
        };
        if self.state.h == 0.0 {
            self.state.h = self.initial_step(rtol, atol, t_stop);
        }
        loop {
            self.attempts += 1;
            check_limits(self.attempts, self.max_steps, self.state.t, self.state.h)?;
            let last = self.state.t + self.state.h >= t_stop;
            let h = if last {
                t_stop - self.state.t
            } else {
                self.state.h
            };
            self.stages(ode, h);
            let err = wrms(&self.err, &self.state.y, &self.y1, rtol, atol);
            let factor = if err.is_finite() {
                (SAFETY * err.powf(-EXPONENT)).clamp(MIN_FACTOR, MAX_FACTOR)
            } else {
                MIN_FACTOR
            };
            if err <= 1.0 {
                self.accept(h, if last { t_stop } else { self.state.t + h })?;
                self.state.h = (h * factor).min(self.h_max);
                return Ok(());
            }
            self.stats.rejected_error += 1;
            self.state.h = h * factor.min(1.0);
        }
    }

    fn state(&self) -> &StepperState {
        &self.state
    }

    /// The cubic Hermite interpolant of the step's ends (third order, as the method).
    fn dense_output(&self, t: f64, out: &mut [f64]) {
        hermite_cubic(
            (self.state.t_prev, &self.y_prev, &self.f_prev),
            (self.state.t, &self.state.y, &self.k[0]),
            t,
            out,
        );
    }

    fn stats(&self) -> Stats {
        self.stats
    }
}

/// What the example computes.
pub struct Report {
    /// Contact switches of the belt over 10 s at rtol = atol = 1e-8 by BS23, and by
    /// Dormand–Prince.
    pub switches: (usize, usize),
    /// The largest difference of the final (x, v) of the two at 1e-8.
    pub final_gap: f64,
    /// The fitted order of BS23's event times at fixed steps.
    pub event_order: Option<f64>,
    /// The fitted order of its final state at fixed steps.
    pub final_order: Option<f64>,
    /// Work–precision at rtol = atol = 1e-8: (error of the final state, right-hand sides) of
    /// BS23 and of Dormand–Prince.
    pub at_1e8: [(f64, usize); 2],
}

/// The switched belt of the speed issue: a block (m = 1 kg) on a spring (k = 100 N/m) to a
/// wall, on a belt at 0.5 m/s, with CVS at the paper's parameters, from rest.
pub fn belt() -> System {
    let mut s = System::default();
    let body = s.add_body("block", 1.0, 0.0, 0.0);
    let wall = s.add_anchor("wall", 0.0, 0.0);
    s.add_spring(End::Body(body), End::Anchor(wall), 100.0, 0.0);
    let law = ModelId::Cvs
        .build(Variant::Odd, &FrictionParams::paper())
        .expect("the paper's parameters");
    s.add_contact(body, 0.5, Arc::from(law));
    s
}

/// Simulates the belt with BS23 and Dormand–Prince, then studies BS23's convergence and its
/// work–precision beside Dormand–Prince.
pub fn run() -> Report {
    let system = belt();
    let bs23 = Solver::own(&BS23);
    let simulated = [bs23, Solver::DOPRI5].map(|solver| {
        let options = Options::adaptive(0.0, 10.0, 1e-8, 1e-8);
        let r = simulate(
            &system,
            Scheme::EventDriven {
                solver,
                switching: Switching::Event,
            },
            options,
            &mut |_| {},
        )
        .expect("a valid system");
        assert!(r.error.is_none(), "{solver:?}: {:?}", r.error);
        let b = r.final_states()[0];
        (r.contact_events().len(), [b.x, b.v])
    });
    let [(n_bs23, a), (n_dopri5, b)] = simulated;
    let case = SystemCase::new("switched belt, CVS", system, 3.0);
    let steps = [0.01, 0.005, 0.0025, 0.00125];
    let convergence = studies::convergence(&case, &[Method::events(bs23)], &steps, &[], &|| {})
        .expect("the study runs");
    let fitted = |measure: ErrorMeasure| {
        convergence
            .orders
            .iter()
            .find(|o| o.measure == measure)
            .and_then(|o| o.fit.map(|f| f.slope))
    };
    let methods = [Method::events(bs23), Method::events(Solver::DOPRI5)];
    let tolerances = [1e-4, 1e-6, 1e-8];
    let wp = studies::work_precision(&case, &methods, &[], &tolerances, 0, &|| {})
        .expect("the study runs");
    let at = |name: &str| {
        let r = wp
            .runs
            .iter()
            .find(|r| r.solver == name && r.resolution == 1e-8)
            .expect("a run at 1e-8");
        (r.errors.final_relative, r.work)
    };
    Report {
        switches: (n_bs23, n_dopri5),
        final_gap: (a[0] - b[0]).abs().max((a[1] - b[1]).abs()),
        event_order: fitted(ErrorMeasure::EventTimes),
        final_order: fitted(ErrorMeasure::FinalRelative),
        at_1e8: [at("bs23"), at("dopri5")],
    }
}

/// Registers BS23 and runs `friction-lab simulate belt --model CVS --solver bs23` through the
/// command line's own library call, as a user's program built on it would: the solver is
/// found by its name, as a built-in one is. Returns the summary's solver and status.
pub fn by_name() -> (String, String) {
    Solver::register(&BS23).expect("bs23 is a name of its own");
    let words = [
        "friction-lab",
        "simulate",
        "belt",
        "--model",
        "CVS",
        "--solver",
        "bs23",
        "--t-end",
        "5",
        "--out",
        "by-name",
    ];
    let cli = friction_lab_cli::Cli::try_parse_from(words).expect("bs23 is a solver's name");
    let made = friction_lab_cli::make(&cli.command).expect("the run is made");
    let Some(Data::Json(summary)) = made.files.get("summary.json") else {
        panic!("a summary");
    };
    let field = |k: &str| summary[k].as_str().unwrap_or_default().to_string();
    (field("solver"), field("status"))
}

fn main() {
    let (solver, status) = by_name();
    println!("simulate belt --solver {solver}: {status}");
    let r = run();
    println!(
        "belt over 10 s at 1e-8: {} switches (bs23), {} (dopri5); final states differ by {:.2e}",
        r.switches.0, r.switches.1, r.final_gap
    );
    println!(
        "bs23 at fixed steps: observed order {:?} on the event times, {:?} on the final state",
        r.event_order, r.final_order
    );
    let [(e3, w3), (e5, w5)] = r.at_1e8;
    println!("at 1e-8: bs23 error {e3:.2e} in {w3} evaluations, dopri5 {e5:.2e} in {w5}");
}
