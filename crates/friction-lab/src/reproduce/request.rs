//! `reproduce` as a request: the friction parameters the paper's rigs run with, and the
//! threads; every front end reads it (the command line's options, Python's keywords).

use super::Paper;
use crate::error::AppError;
use crate::made::Made;
use crate::params::ParamSource;
use crate::ranges;
use friction_models::Parameters;
use std::path::Path;

/// The paper reproduced into one folder (`friction-lab reproduce`, `friction_lab.reproduce`).
#[derive(clap::Args, Clone, Debug, Default)]
pub struct ReproduceRequest {
    /// The parameters (Table 1 of the paper unless changed).
    #[command(flatten)]
    pub params: ParamSource,
    /// Worker threads for the parallel parts (default: all cores; more than the machine has are
    /// capped to its cores). Results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub threads: Option<i64>,
}

impl ReproduceRequest {
    /// The worker threads asked for, checked (`None`: all cores).
    pub fn threads(&self) -> Result<Option<usize>, AppError> {
        ranges::threads(self.threads)
    }

    /// The paper asked for: Table 1's friction parameters, changed by the request's. A rig's
    /// or the chain's parameter is refused, naming it: every rig of the report runs at its own
    /// (the paper's) settings.
    pub fn paper(&self) -> Result<Paper, AppError> {
        let rig_or_chain = |name: &str| {
            scenarios::ScenarioParams::spec(name).is_some()
                || friction_systems::chain::CHAIN_PARAMETERS
                    .iter()
                    .any(|p| p.0 == name)
        };
        let friction = self.params.resolve_with(&[], |name, _| {
            if !rig_or_chain(name) {
                return Ok(false);
            }
            Err(AppError::Usage(format!(
                "parameter `{name}` is not a friction parameter: reproduce runs every rig and \
                 the chain at their own (the paper's) settings, and takes only the friction \
                 parameters (`friction-lab models` lists them); set `{name}` with simulate, \
                 the studies or sweep"
            )))
        })?;
        let changed = !self.params.set.is_empty() || self.params.params.is_some();
        Ok(Paper {
            friction,
            parameters: format!(
                "Parameter set `{}`{}",
                self.params.set_name(),
                if changed {
                    " with overrides (see figures.json)"
                } else {
                    ""
                }
            ),
        })
    }

    /// Reproduces the paper into the folder `out`: its files, unwritten ([`Report::conduct`]).
    ///
    /// [`Report::conduct`]: super::Report::conduct
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        let threads = self.threads()?;
        let paper = self.paper()?;
        let parts = paper.parts();
        paper
            .report(parts.iter().map(|p| p.as_ref()).collect())
            .conduct(out, threads)
    }
}
