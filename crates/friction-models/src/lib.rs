//! Dry-friction models: the six composite models of "Combinations of Different Friction
//! Models: Visualisation of the Curves" (AV, CS, CVS, DV, SD, SV) as `docs/models.md`
//! reads them, the classical terms they are built from, and the reference models of the
//! literature (Dahl, Karnopp, LuGre and its variants, the generalized Maxwell-slip model).
//!
//! Every model implements [`FrictionModel`]: the force F(x, v, z) and the rate of its
//! internal states under a chosen [`SignLaw`], the admissible forces at rest
//! ([`StickInterval`]), and the analytic [`Partials`] that implicit solvers need.

pub mod catalog;
pub mod composite;
pub mod gms;
pub mod id;
pub mod lugre;
pub mod model;
pub mod params;
pub mod sign;
pub mod steady;
pub mod terms;

pub use id::ModelId;
pub use model::{
    reported_state, CurveAxis, FrictionModel, Partials, StatePartials, StickInterval,
    StictionLevels, Variant, MAX_STATES,
};
pub use params::{FrictionParams, ParamError, ParamSpec, Parameters, Range, PARAM_SETS};
pub use sign::{Branches, Direction, SignLaw};
