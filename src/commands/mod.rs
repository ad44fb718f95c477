//! One module per command of `friction-lab`, and what they share: a request of the library
//! with the folder its files go to ([`Writing`]).

use clap::{Args, FromArgMatches};
use std::path::PathBuf;

pub mod models;
pub mod phenomena;
pub mod reproduce;

/// No request: [`Writing`] alone, `--out`, to which a study registered at run time adds its own
/// options ([`crate::command`]).
#[derive(Args, Debug)]
pub struct Nothing {}

/// A request of the library, declared there ([`friction_lab::curve::CurveRequest`],
/// [`friction_lab::study::PhenomenaRequest`], …), and the folder its files are written into.
#[derive(Args, Debug)]
pub struct Writing<R: Args + FromArgMatches> {
    /// Folder to write into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The request.
    #[command(flatten)]
    pub request: R,
}
