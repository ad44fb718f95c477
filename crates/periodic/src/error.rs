//! Why a periodic orbit was not found.

use integrators::SolverError;

/// Why the flow or the shooting failed.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum OrbitError {
    /// The integration of a segment failed.
    #[error("the integration failed at t = {t}: {error}")]
    Solver {
        /// Where, s.
        t: f64,
        /// The solver's error.
        error: SolverError,
    },
    /// The problem is not one whose orbits are computed here.
    #[error("{0}")]
    Unsupported(String),
    /// Two or more event functions fired at one instant.
    #[error("at t = {t} the events {fired:?} fire at once: a switch of two contacts together is not handled (its saltation needs each surface's crossing order)")]
    SimultaneousEvents {
        /// Where, s.
        t: f64,
        /// The event functions, by index.
        fired: Vec<usize>,
    },
    /// The flow meets an event surface tangentially (∇gᵀ·f⁻ ≈ 0): a grazing, where the
    /// saltation matrix is unbounded.
    #[error("at t = {t} the flow grazes the surface of event {event} (∇g·f = {rate:e}): the saltation matrix is unbounded there")]
    Grazing {
        /// Where, s.
        t: f64,
        /// The event function, by index.
        event: usize,
        /// ∇gᵀ·f⁻ + g_t.
        rate: f64,
    },
    /// More switches than allowed in one flow (a Zeno or chattering run).
    #[error("more than {0} switches in one flow: the run chatters")]
    TooManySwitches(usize),
    /// Newton's iteration did not converge.
    #[error("Newton's iteration on the orbit did not converge in {iterations} iterations: residual {residual:e} (wanted {wanted:e})")]
    NoConvergence {
        /// Iterations made.
        iterations: usize,
        /// The last residual, relative to the orbit's scale.
        residual: f64,
        /// The residual asked for.
        wanted: f64,
    },
    /// The modes at the end of the orbit are not those at its start.
    #[error("the mode sequence does not close: the flow ends in modes {end:?}, not {start:?}")]
    ModesDoNotClose {
        /// The modes at the start.
        start: Vec<u8>,
        /// The modes at the end.
        end: Vec<u8>,
    },
    /// A singular Newton matrix (the orbit is not isolated, or the section not transversal).
    #[error("the shooting matrix is singular: the orbit is not isolated on its section")]
    Singular,
    /// No cycle in the run to start from.
    #[error("{0}")]
    NoGuess(String),
}
