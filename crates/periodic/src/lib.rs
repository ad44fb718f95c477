//! Periodic orbits of hybrid ODEs `y' = f(t, y, q)` with discrete modes `q`, events and
//! resets (an [`integrators::OdeProblem`]): for a friction system, its stick–slip cycles and
//! hunting cycles, found as orbits rather than as the end of a long simulation.
//!
//! - [`mod@flow`]: the hybrid flow over a time T from a state, as segments, each a mode sequence
//!   entry, the smooth flow's sensitivity `Φ_i` (the variational equations `Φ' = J·Φ`
//!   integrated beside the state), and the **saltation matrix** `S_i` at the switch that ends
//!   it (Aizerman & Gantmacher 1958; Leine & Nijmeijer 2004, §7.1; di Bernardo et al. 2008,
//!   §2.5):
//!
//!   ```text
//!   S = R_y + (f⁺ − R_y·f⁻ − R_t)·∇gᵀ / (∇gᵀ·f⁻ + g_t)
//!   ```
//!
//!   with `g` the event function that fired, `R` the reset (`y⁺ = R(t, y⁻)`), `f⁻` and `f⁺` the
//!   vector fields before and after. The monodromy matrix is `M = Φ_N·S_{N−1}·…·S_1·Φ_1`.
//! - [`mod@shooting`]: Newton on the period T and the initial state y₀ of the orbit, with the
//!   phase condition `nᵀ(y₀ − y_ref) = 0` on the hyperplane through a reference point normal
//!   to the flow there (a Poincaré section), to a residual `‖φ_T(y₀) − y₀‖ ≤ 1e-10` of the
//!   orbit's scale. The mode sequence is that of the flow from the guess; it must close.
//! - [`mod@floquet`]: the Floquet multipliers, the eigenvalues of M: one is 1 (the flow's
//!   direction), the others decide the orbit's stability. A stick phase collapses the
//!   velocity of the stuck body: its multiplier is 0.
//! - [`mod@guess`]: an orbit's starting guess from a long run's recorded cycle.

pub mod continuation;
pub mod error;
pub mod floquet;
pub mod flow;
pub mod guess;
pub mod saltation;
pub mod shooting;
mod variational;

pub use continuation::{
    continue_cycles, continue_equilibria, cycle_at, equilibrium_at, Branch, ContinuationOptions,
    CyclePoint, EquilibriumPoint, Family, SpecialKind, SpecialPoint,
};
pub use error::OrbitError;
pub use floquet::{Floquet, Stability};
pub use flow::{flow, FlowOptions, HybridFlow, Segment};
pub use guess::{guess_from_run, Guess};
pub use shooting::{find_orbit, PeriodicOrbit, ShootingOptions};
