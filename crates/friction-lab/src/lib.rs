//! friction-lab: the library under the command line, the Python package and a Rust user's own
//! code, and a facade over the workspace's crates.
//!
//! - [`friction_models`]: the paper's six models, the classical terms, Dahl, Karnopp, LuGre;
//! - [`integrators`]: the solvers (RK4, Dormand–Prince, implicit Euler, Radau IIA, RODAS,
//!   diffsol's);
//! - [`friction_systems`]: bodies, springs and contacts as hybrid problems, one mode per
//!   contact;
//! - [`scenarios`]: the rigs, the paper's experiments and the solver studies.
//!
//! Above them, what every front end shares: a run with its files and figures
//! ([`simulate`]), the studies as one abstraction ([`study`]), the sweep ([`sweep`]), the
//! paper reproduced as a table of studies ([`reproduce`]), and the output they write
//! ([`artifacts`], [`plot`]): typed options in, typed results and files out.

pub use friction_models;
pub use friction_systems;
pub use integrators;
pub use scenarios;

pub mod artifacts;
pub mod columns;
pub mod curve;
pub mod delivery;
pub mod destination;
pub mod error;
pub mod figure;
pub mod laws;
pub mod listing;
pub mod made;
pub mod output;
pub mod params;
pub mod plot;
pub mod progress;
pub mod provenance;
pub mod ranges;
pub mod reproduce;
pub mod run_record;
pub mod scheme;
pub mod settings;
pub mod simulate;
pub mod study;
pub mod sweep;
pub mod testset;
pub mod threads;
pub mod trajectory;
pub mod warnings;
pub mod window;
