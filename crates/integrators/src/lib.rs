//! General solvers for hybrid initial value problems, instrumented so that the claims about
//! them can be measured. Nothing here knows about friction: a problem declares its state,
//! its modes and its events through [`OdeProblem`].
//!
//!
//! - [`Rk4`]: classical Runge–Kutta, fixed step, Hermite dense output;
//! - [`Dopri5`]: Dormand–Prince 5(4) as in Hairer's `dopri5.f`;
//! - [`ImplicitEuler`]: implicit Euler with full or modified Newton, fixed or adaptive steps;
//! - diffsol's BDF, TR-BDF2, ESDIRK34 and Tsit45 behind the same [`Stepper`] interface;
//! - [`Radau5`]: Radau IIA of order 5 as in Hairer's `radau5.f`;
//! - [`Rodas`]: the Rosenbrock method RODAS as in Hairer's `rodas.f`;
//! - `auto`: Dormand–Prince and Radau IIA switched by stiffness within a run;
//! - [`testset`]: the standard stiff test problems with their published references;
//! - [`stability`]: stability of a fixed step and the spectral radius of the Jacobian (by
//!   [`power`] iteration on large systems);
//! - event location on each method's dense output, simultaneous events handled in one call,
//!   one mode per component of the discrete state.
//!
//! A problem implements [`OdeProblem`]; an [`Integrator`] drives a [`Stepper`] over it and
//! returns a [`Solution`] with its [`Stats`], or a [`Failure`] that keeps what was computed.
//! A method written elsewhere implements [`Stepper`] and [`OneStepMethod`] and runs as
//! [`Solver::own`] wherever a built-in solver runs.

pub mod auto;
pub mod counting;
pub mod decsol;
pub mod diffsol_backend;
pub mod dopri5;
pub mod error;
pub mod events;
pub mod implicit_euler;
pub mod integrator;
pub mod interrupt;
pub mod iteration_matrix;
pub mod linear;
pub mod method;
pub mod newton;
pub mod options;
pub mod power;
pub mod problem;
pub mod radau5;
pub mod rk4;
pub mod rodas;
pub mod solution;
pub mod solver;
pub mod stability;
pub mod stats;
pub mod stepper;
pub mod symmetric;
pub mod testset;

pub use diffsol_backend::DiffsolMethod;
pub use dopri5::Dopri5;
pub use error::SolverError;
pub use implicit_euler::ImplicitEuler;
pub use integrator::{Integrator, StopReason};
pub use method::OneStepMethod;
pub use newton::NewtonKind;
pub use options::{even_grid, Options, Output, StepControl, ZenoGuard};
pub use problem::{Control, Crossing, Entry, EventSpec, Mode, OdeProblem};
pub use radau5::Radau5;
pub use rk4::Rk4;
pub use rodas::Rodas;
pub use solution::{EventRecord, Failure, MethodSwitch, ModeSwitch, Solution, SwitchRule};
pub use solver::{Solver, SOLVERS};
pub use stats::{Stats, WorkWeights};
pub use stepper::{Ode, Stepper, StepperState};
