//! diffsol's BDF, TR-BDF2, ESDIRK34 and Tsit45 behind the [`Stepper`] interface, so that they
//! run the same problems with the same events, mode switching and statistics as the
//! native methods. This is the only module that instantiates diffsol's generic code, with two
//! matrix types: nalgebra's dense matrix and LU, and, for a large problem whose analytic
//! Jacobian is sparse (a chain of many blocks), faer's sparse matrix and sparse LU, chosen as
//! implicit Euler chooses its linear solver ([`crate::linear::choice`]). The sparse path needs
//! a Jacobian whose pattern does not depend on the modes: diffsol finds the pattern once, by
//! probing the Jacobian-vector product with NaN columns, so a problem lists its structural
//! entries even where their value is zero.
//!
//! How the known pitfalls of diffsol 0.18 are met:
//! - implicit methods need a Jacobian-vector product: it is built from the problem's
//!   analytic Jacobian, or from a forward difference of f when there is none;
//! - Newton failures count over a solver's whole life (50 by default), not per step, and
//!   long runs reach that: a fresh solver is built at every event, a solver that has failed
//!   1000 times (`RENEW_AFTER_NEWTON_FAILURES`) is replaced by a fresh one at its next step,
//!   and the limit, raised, bounds the failures of about one step;
//! - after a root the state stays at the step end, and a BDF state handed on keeps stale
//!   history: roots are not left to diffsol at all. Events are located by this crate on
//!   diffsol's own interpolant, and the method restarts from a new state built at the event
//!   time (new y, new f(t, y), new initial step), never from the old solver's state.

use crate::error::SolverError;
use crate::integrator::Integrator;
use crate::method::OneStepMethod;
use crate::options::{Options, StepControl};
use crate::problem::{Mode, OdeProblem};
use crate::solution::{Failure, Solution};
use crate::stats::Stats;
use crate::stepper::{check_step_size, linear_interpolation, Ode, Stepper, StepperState};
use diffsol::{
    BdfState, DiffsolError, FaerSparseLU, FaerSparseMat, NalgebraLU, NalgebraMat, NonLinearOp,
    OdeBuilder, OdeEquations, OdeSolverMethod, OdeSolverProblem, OdeSolverState, RkState, Vector,
};
use std::cell::{Cell, RefCell};

type Dense = NalgebraMat<f64>;
type DenseLu = NalgebraLU<f64>;
type Sparse = FaerSparseMat<f64>;
type SparseLu = FaerSparseLU<f64>;

/// Newton failures allowed per solver instance (diffsol's default is 50).
const MAX_NEWTON_FAILURES: usize = 10_000;

/// Newton failures after which a solver is replaced, at the start of its next step, by a
/// fresh one from its last state (diffsol counts them over the solver's life: without it, GMS
/// driven at 2·v_s ± v_s with σ0 = 6 N/m failed under BDF at t = 179 s, after 130 731 steps
/// with a failure every 13 on average). A restart costs BDF its history (order 1 again) once
/// in thousands of steps.
const RENEW_AFTER_NEWTON_FAILURES: usize = 1_000;

/// diffsol's smallest step, s: none of its own (its default, an absolute 1e-13 s, stopped a
/// body of 1 mg on LuGre's bristles, whose time scale m/σ1 is 3e-9 s, at its first step). The
/// floor is instead the one every adaptive method here keeps, relative to t
/// ([`check_step_size`]), tested after each step.
const MIN_STEP: f64 = f64::MIN_POSITIVE;

/// diffsol's limits as this crate sets them on every problem it builds: Newton failures
/// ([`MAX_NEWTON_FAILURES`]) and the smallest step ([`MIN_STEP`]).
fn set_limits<Eqn: OdeEquations<T = f64>>(problem: &mut OdeSolverProblem<Eqn>) {
    problem.ode_options.max_nonlinear_solver_failures = MAX_NEWTON_FAILURES;
    problem.ode_options.min_timestep = MIN_STEP;
}

/// A diffsol method.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DiffsolMethod {
    /// Variable-order BDF (orders 1–5) with Newton's method.
    Bdf,
    /// TR-BDF2, an ESDIRK method of order 2.
    TrBdf2,
    /// ESDIRK3(4), an ESDIRK method of order 3 with an order-4 embedded estimate.
    Esdirk34,
    /// Tsitouras 5(4), explicit.
    Tsit45,
}

/// diffsol's methods run on diffsol's own driver ([`solve_observed`]): they provide
/// `solve_observed`, and make no [`Stepper`] for the [`Integrator`].
impl OneStepMethod for DiffsolMethod {
    fn name(&self) -> &'static str {
        DiffsolMethod::name(*self)
    }

    /// Their global order (BDF: its highest, 5; Tsit45: 5).
    fn order(&self) -> usize {
        match self {
            DiffsolMethod::Bdf | DiffsolMethod::Tsit45 => 5,
            DiffsolMethod::TrBdf2 => 2,
            DiffsolMethod::Esdirk34 => 3,
        }
    }

    fn is_implicit(&self) -> bool {
        *self != DiffsolMethod::Tsit45
    }

    fn is_fixed_step(&self) -> bool {
        false
    }

    /// Refused: diffsol's methods take tolerances and run on diffsol's driver.
    fn stepper(&self, _options: &Options, _dim: usize) -> Result<Box<dyn Stepper>, SolverError> {
        Err(SolverError::Unsupported {
            solver: DiffsolMethod::name(*self),
            why: "diffsol's methods run on diffsol's own driver, not on a stepper".into(),
        })
    }

    fn solve_observed(
        &self,
        problem: &dyn OdeProblem,
        y0: &[f64],
        modes: &[Mode],
        options: Options,
        observe: &mut dyn FnMut(f64),
    ) -> Result<Solution, Failure> {
        solve_observed(problem, *self, y0, modes, options, observe)
    }
}

impl DiffsolMethod {
    /// The name the command line takes.
    pub fn name(self) -> &'static str {
        match self {
            DiffsolMethod::Bdf => "bdf",
            DiffsolMethod::TrBdf2 => "tr-bdf2",
            DiffsolMethod::Esdirk34 => "esdirk34",
            DiffsolMethod::Tsit45 => "tsit45",
        }
    }

    /// The order diffsol's initial-step heuristic is told.
    fn initial_step_order(self) -> usize {
        match self {
            DiffsolMethod::Bdf => 1,
            DiffsolMethod::TrBdf2 => 2,
            DiffsolMethod::Esdirk34 => 3,
            DiffsolMethod::Tsit45 => 4,
        }
    }
}

/// What the closures handed to diffsol share with the stepper.
struct Shared<'a> {
    problem: &'a dyn OdeProblem,
    modes: RefCell<Vec<Mode>>,
    start: RefCell<Vec<f64>>,
    rhs_evals: Cell<usize>,
    jacobian_products: Cell<usize>,
    /// The most stored entries of an analytic Jacobian seen (0: none, or finite differences).
    jacobian_entries: Cell<usize>,
    jacobian: RefCell<Vec<crate::problem::Entry>>,
    /// Divide f by this regular mass diagonal (ODE path); `None` for the identity or a DAE.
    inverse_mass: Option<&'a [f64]>,
}

impl Shared<'_> {
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.rhs_evals.set(self.rhs_evals.get() + 1);
        self.evaluate(t, y, dy);
    }

    /// `dy = M⁻¹·f(t, y)`, not counted: for the finite-difference Jacobian products, whose
    /// cost the counted work charges as Jacobians.
    fn evaluate(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.problem.rhs(t, y, &self.modes.borrow(), dy);
        if let Some(m) = self.inverse_mass {
            dy.iter_mut().zip(m).for_each(|(d, m)| *d /= m);
        }
    }

    /// `jv = J·v` from the analytic Jacobian, or `(f(y + δv) − f(y))/δ`.
    fn jacobian_product(&self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        self.jacobian_products.set(self.jacobian_products.get() + 1);
        let mut jac = self.jacobian.borrow_mut();
        jac.clear();
        if self.problem.jacobian(t, y, &self.modes.borrow(), &mut jac) {
            self.jacobian_entries
                .set(self.jacobian_entries.get().max(jac.len()));
            jv.iter_mut().for_each(|x| *x = 0.0);
            for &(i, j, a) in jac.iter() {
                jv[i] += a * v[j];
            }
            if let Some(m) = self.inverse_mass {
                jv.iter_mut().zip(m).for_each(|(d, m)| *d /= m);
            }
            return;
        }
        let norm = |x: &[f64]| x.iter().map(|a| a * a).sum::<f64>().sqrt();
        let nv = norm(v);
        if nv == 0.0 {
            jv.iter_mut().for_each(|x| *x = 0.0);
            return;
        }
        let delta = f64::EPSILON.sqrt() * (1.0 + norm(y)) / nv;
        let shifted: Vec<f64> = y.iter().zip(v).map(|(y, v)| y + delta * v).collect();
        let mut f0 = vec![0.0; y.len()];
        self.evaluate(t, y, &mut f0);
        self.evaluate(t, &shifted, jv);
        jv.iter_mut()
            .zip(&f0)
            .for_each(|(a, b)| *a = (*a - b) / delta);
    }
}

/// A diffsol solver as a [`Stepper`]: `make` builds a fresh solver at a start time from the
/// start state in `shared`.
struct DiffsolStepper<'p, Eqn: OdeEquations, S, F> {
    method: DiffsolMethod,
    problem: &'p OdeSolverProblem<Eqn>,
    shared: &'p Shared<'p>,
    make: F,
    solver: Option<S>,
    stop_set: bool,
    /// Where the method stands (`h` read from diffsol's state after each step).
    state: StepperState,
    y_prev: Vec<f64>,
    /// Statistics of the solvers already replaced.
    finished: Stats,
}

/// A new diffsol state at time `t` from the start state: y from `init`, f(t, y) afresh (zero
/// for the algebraic components of a DAE), and diffsol's initial step size, whose estimate
/// (Hairer's, from the norms of f and of its change over a trial step) leaves out the last
/// `quadratures` components (`OdeProblem::quadratures`: an infinite absolute tolerance there).
/// Counted, a system's energy accumulators, zero at the start and weighted by atol alone,
/// drove the estimate below diffsol's smallest step (1e-13 s) where the power changes fast:
/// LuGre on a belt at 1000 m/s failed at t = 2e-14 s.
fn restart_state<Eqn, St>(
    problem: &OdeSolverProblem<Eqn>,
    t: f64,
    order: usize,
    algebraic: &[usize],
    quadratures: usize,
) -> Result<St, DiffsolError>
where
    Eqn: OdeEquations<T = f64>,
    St: OdeSolverState<Eqn::V>,
{
    let mut state = St::new_without_initialise(problem)?;
    let mut s = state.as_mut();
    *s.t = t;
    problem.eqn.rhs().call_inplace(s.y, t, s.dy);
    for &i in algebraic {
        s.dy.set_index(i, 0.0);
    }
    let mut atol = problem.atol.clone();
    let n = atol.len();
    for i in n - quadratures..n {
        atol.set_index(i, f64::INFINITY);
    }
    s.set_step_size(problem.h0, &atol, problem.rtol, &problem.eqn, order);
    Ok(state)
}

impl<'p, Eqn, S, F> DiffsolStepper<'p, Eqn, S, F>
where
    Eqn: OdeEquations<T = f64>,
    S: OdeSolverMethod<'p, Eqn>,
{
    fn stats_of(&self, s: &S) -> Stats {
        let d = s.get_statistics();
        Stats {
            steps: d.number_of_steps,
            rejected_error: d.number_of_error_test_failures,
            rejected_newton: d.number_of_nonlinear_solver_fails,
            lu_factorizations: d.number_of_linear_solver_setups,
            newton_iterations: d.number_of_nonlinear_solver_iterations,
            linear_solves: d.number_of_nonlinear_solver_iterations,
            ..Stats::default()
        }
    }

    fn error(&self, e: DiffsolError) -> SolverError {
        SolverError::Diffsol {
            solver: self.method.name(),
            t: self.state.t,
            message: e.to_string(),
        }
    }
}

impl<'p, Eqn, S, F> DiffsolStepper<'p, Eqn, S, F>
where
    Eqn: OdeEquations<T = f64>,
    S: OdeSolverMethod<'p, Eqn>,
    F: Fn(&'p OdeSolverProblem<Eqn>, f64) -> Result<S, DiffsolError>,
{
    /// A fresh solver at the stepper's time and state (its statistics kept in `finished`).
    fn renew(&mut self) -> Result<(), SolverError> {
        self.shared.start.replace(self.state.y.clone());
        if let Some(old) = self.solver.take() {
            self.finished += self.stats_of(&old);
        }
        let solver = (self.make)(self.problem, self.state.t).map_err(|e| self.error(e))?;
        self.state.h = solver.state().h;
        self.solver = Some(solver);
        self.stop_set = false;
        Ok(())
    }
}

impl<'p, Eqn, S, F> Stepper for DiffsolStepper<'p, Eqn, S, F>
where
    Eqn: OdeEquations<T = f64>,
    S: OdeSolverMethod<'p, Eqn>,
    F: Fn(&'p OdeSolverProblem<Eqn>, f64) -> Result<S, DiffsolError>,
{
    fn name(&self) -> &'static str {
        self.method.name()
    }

    fn start(&mut self, ode: &Ode, t: f64, y: &[f64]) -> Result<(), SolverError> {
        self.shared.modes.replace(ode.modes.to_vec());
        self.state.t_prev = t;
        self.state.t = t;
        self.state.y = y.to_vec();
        self.y_prev = y.to_vec();
        self.renew()
    }

    fn step(&mut self, _ode: &Ode, t_stop: f64) -> Result<(), SolverError> {
        let failures = |s: &S| s.get_statistics().number_of_nonlinear_solver_fails;
        if self.solver.as_ref().map(failures) >= Some(RENEW_AFTER_NEWTON_FAILURES) {
            // The last step's interpolant is no longer needed: the driver has used it.
            self.renew()?;
        }
        let solver = self.solver.as_mut().expect("started");
        let result = if self.stop_set {
            Ok(())
        } else {
            solver.set_stop_time(t_stop)
        }
        .and_then(|_| solver.step());
        if let Err(e) = result {
            // The step size diffsol had reached when it failed, for the error report.
            self.state.h = solver.state().h;
            return Err(self.error(e));
        }
        self.stop_set = true;
        let state = self.solver.as_ref().expect("started").state();
        // (Not at the stop time, where diffsol may have shortened the last step to land on it.)
        if state.t < t_stop {
            check_step_size(state.t, state.h)?;
        }
        self.state.t_prev = self.state.t;
        self.state.t = state.t;
        std::mem::swap(&mut self.y_prev, &mut self.state.y);
        self.state.y = state.y.clone_as_vec();
        self.state.h = state.h;
        Ok(())
    }

    fn state(&self) -> &StepperState {
        &self.state
    }

    fn dense_output(&self, t: f64, out: &mut [f64]) {
        match self.solver.as_ref().map(|s| s.interpolate(t)) {
            Some(Ok(v)) => out.copy_from_slice(&v.clone_as_vec()),
            // Outside diffsol's interpolation window (never expected): the linear interpolant.
            _ => linear_interpolation(
                self.state.t_prev,
                &self.y_prev,
                self.state.t,
                &self.state.y,
                t,
                out,
            ),
        }
    }

    fn stats(&self) -> Stats {
        let mut s = self.finished;
        if let Some(solver) = &self.solver {
            s += self.stats_of(solver);
        }
        let n = self.state.y.len().max(1);
        s.rhs_evals = self.shared.rhs_evals.get();
        // A dense Jacobian costs n products; report whole Jacobians.
        s.jacobian_evals = self.shared.jacobian_products.get().div_ceil(n);
        if s.lu_factorizations > 0 {
            // The matrix factorised is n × n with the Jacobian's pattern (dense where the
            // Jacobian comes from finite differences).
            s.matrix_order = n;
            s.matrix_entries = match self.shared.jacobian_entries.get() {
                0 => n * n,
                entries => entries,
            };
        }
        s
    }
}

/// Where and how a run starts.
struct Start<'r> {
    y0: &'r [f64],
    modes: &'r [Mode],
    options: Options,
    observe: &'r mut dyn FnMut(f64),
}

/// Runs the driver with a diffsol stepper whose solvers `make` builds.
fn drive<'p, Eqn, S, F>(
    method: DiffsolMethod,
    problem: &'p OdeSolverProblem<Eqn>,
    shared: &'p Shared<'p>,
    make: F,
    start: Start,
) -> Result<Solution, Failure>
where
    Eqn: OdeEquations<T = f64>,
    S: OdeSolverMethod<'p, Eqn> + 'p,
    F: Fn(&'p OdeSolverProblem<Eqn>, f64) -> Result<S, DiffsolError> + 'p,
{
    let Start {
        y0,
        modes,
        options,
        observe,
    } = start;
    let n = y0.len();
    let stepper = DiffsolStepper {
        method,
        problem,
        shared,
        make,
        solver: None,
        stop_set: false,
        state: StepperState {
            t_prev: options.t0,
            t: options.t0,
            ..StepperState::new(n)
        },
        y_prev: vec![0.0; n],
        finished: Stats::default(),
    };
    let failure = |error| Failure {
        error,
        solution: Box::new(Solution::new(method.name(), n, modes.len())),
    };
    Integrator::new(shared.problem, Box::new(stepper), y0, modes, options)
        .map_err(failure)?
        .solve_observed(observe)
}

/// Runs the implicit `method` on the built diffsol problem `ds` with the linear solver `lu`
/// (a macro rather than a generic function: it instantiates diffsol's solvers for the concrete
/// equation and matrix types of each call site, whose trait bounds are long to spell out).
macro_rules! drive_implicit {
    ($method:expr, $ds:expr, $shared:expr, $algebraic:expr, $start:expr, $lu:ty) => {{
        let (method, algebraic): (DiffsolMethod, &[usize]) = ($method, $algebraic);
        let (order, quadratures) = (method.initial_step_order(), $shared.problem.quadratures());
        match method {
            DiffsolMethod::Bdf => drive(
                method,
                $ds,
                $shared,
                move |p, t| {
                    p.bdf_solver::<$lu>(restart_state::<_, BdfState<_>>(
                        p,
                        t,
                        order,
                        algebraic,
                        quadratures,
                    )?)
                },
                $start,
            ),
            DiffsolMethod::TrBdf2 => drive(
                method,
                $ds,
                $shared,
                move |p, t| {
                    p.tr_bdf2_solver::<$lu>(restart_state::<_, RkState<_>>(
                        p,
                        t,
                        order,
                        algebraic,
                        quadratures,
                    )?)
                },
                $start,
            ),
            DiffsolMethod::Esdirk34 | DiffsolMethod::Tsit45 => drive(
                method,
                $ds,
                $shared,
                move |p, t| {
                    p.esdirk34_solver::<$lu>(restart_state::<_, RkState<_>>(
                        p,
                        t,
                        order,
                        algebraic,
                        quadratures,
                    )?)
                },
                $start,
            ),
        }
    }};
}

/// Integrates `problem` from `y0` in `modes` with a diffsol method, events and mode switching
/// handled as for the native methods. Only adaptive stepping exists for diffsol's methods.
pub fn solve(
    problem: &dyn OdeProblem,
    method: DiffsolMethod,
    y0: &[f64],
    modes: &[Mode],
    options: Options,
) -> Result<Solution, Failure> {
    solve_observed(problem, method, y0, modes, options, &mut |_| {})
}

/// As [`solve`], telling `observe` the time reached after every step.
pub fn solve_observed(
    problem: &dyn OdeProblem,
    method: DiffsolMethod,
    y0: &[f64],
    modes: &[Mode],
    options: Options,
    observe: &mut dyn FnMut(f64),
) -> Result<Solution, Failure> {
    let n = problem.dim();
    let fail = |error| Failure {
        error,
        solution: Box::new(Solution::new(method.name(), n, modes.len())),
    };
    options.validate().map_err(fail)?;
    let StepControl::Adaptive { rtol, atol, h0 } = options.step else {
        return Err(fail(SolverError::Unsupported {
            solver: method.name(),
            why: "diffsol's methods choose their own steps: give tolerances, not a fixed step"
                .into(),
        }));
    };
    let mass = problem.mass();
    let algebraic: Vec<usize> = mass
        .map(|m| (0..n).filter(|&i| m[i] == 0.0).collect())
        .unwrap_or_default();
    let dae = !algebraic.is_empty();
    if dae && method == DiffsolMethod::Tsit45 {
        return Err(fail(SolverError::Unsupported {
            solver: method.name(),
            why: "an explicit method cannot integrate a DAE (zeros on the mass diagonal)".into(),
        }));
    }
    let start = Start {
        y0,
        modes,
        options: options.clone(),
        observe,
    };
    let shared = Shared {
        problem,
        modes: RefCell::new(modes.to_vec()),
        start: RefCell::new(y0.to_vec()),
        rhs_evals: Cell::new(0),
        jacobian_products: Cell::new(0),
        jacobian_entries: Cell::new(0),
        jacobian: RefCell::new(Vec::new()),
        inverse_mass: if dae { None } else { mass },
    };
    // One builder for both matrix types: the same closures, the same tolerances.
    macro_rules! builder {
        ($matrix:ty) => {
            OdeBuilder::<$matrix>::new()
                .t0(options.t0)
                .h0(h0.unwrap_or(1.0))
                .rtol(rtol)
                .atol(vec![atol; n])
                .rhs_implicit(
                    |y: &[f64], _p: &[f64], t: f64, dy: &mut [f64]| shared.rhs(t, y, dy),
                    |y: &[f64], _p: &[f64], t: f64, v: &[f64], jv: &mut [f64]| {
                        shared.jacobian_product(t, y, v, jv)
                    },
                )
                .init(
                    |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(&shared.start.borrow()),
                    n,
                )
        };
    }
    let build_error = |e: DiffsolError| {
        fail(SolverError::Diffsol {
            solver: method.name(),
            t: options.t0,
            message: e.to_string(),
        })
    };
    if dae {
        let diagonal = mass.expect("a DAE has a mass matrix");
        let mut ds = builder!(Dense)
            .mass(|v: &[f64], _p: &[f64], _t: f64, beta: f64, y: &mut [f64]| {
                for i in 0..v.len() {
                    y[i] = diagonal[i] * v[i] + beta * y[i];
                }
            })
            .build()
            .map_err(build_error)?;
        set_limits(&mut ds);
        return drive_implicit!(method, &ds, &shared, &algebraic, start, DenseLu);
    }
    if method == DiffsolMethod::Tsit45 {
        let mut ds = builder!(Dense).build().map_err(build_error)?;
        set_limits(&mut ds);
        let (order, quadratures) = (method.initial_step_order(), problem.quadratures());
        return drive(
            method,
            &ds,
            &shared,
            move |p, t| {
                p.tsit45_solver(restart_state::<_, RkState<_>>(
                    p,
                    t,
                    order,
                    &[],
                    quadratures,
                )?)
            },
            start,
        );
    }
    if sparse_jacobian(problem, options.t0, y0, modes) {
        let mut ds = builder!(Sparse).build().map_err(build_error)?;
        set_limits(&mut ds);
        return drive_implicit!(method, &ds, &shared, &[], start, SparseLu);
    }
    let mut ds = builder!(Dense).build().map_err(build_error)?;
    set_limits(&mut ds);
    drive_implicit!(method, &ds, &shared, &[], start, DenseLu)
}

/// Whether the problem's analytic Jacobian at the start is large and sparse enough for faer's
/// sparse LU (the rule of [`crate::linear::choice`]).
pub fn sparse_jacobian(problem: &dyn OdeProblem, t0: f64, y0: &[f64], modes: &[Mode]) -> bool {
    let mut jac = Vec::new();
    problem.jacobian(t0, y0, modes, &mut jac)
        && crate::linear::choice(problem.dim(), jac.len()) == "faer sparse LU"
}
