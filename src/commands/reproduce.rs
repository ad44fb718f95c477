//! `friction-lab reproduce --out DIR`: the paper reproduced into one folder
//! ([`friction_lab::reproduce`]): Figures 2–7 with notes, the experiment, Table 2, the solver
//! studies, the chain's and the belt's stick–slip map, and a report that links them.

use clap::Args;
use friction_lab::error::AppError;
use friction_lab::params::ParamSource;
use friction_lab::ranges;
use friction_lab::reproduce::Paper;
use friction_lab::threads::with_threads;
use friction_models::Parameters;
use std::path::PathBuf;
use std::time::Instant;

/// Options of `reproduce`.
#[derive(Args, Debug)]
pub struct ReproduceArgs {
    /// Folder to write into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The parameters (Table 1 of the paper unless changed).
    #[command(flatten)]
    pub params: ParamSource,
    /// Worker threads for the parallel parts (default: all cores; more than the machine has are
    /// capped to its cores). Results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub threads: Option<i64>,
}

/// Runs `reproduce`.
/// `delivery`: the figures' size and resolution, and `--replace`.
pub fn run(args: &ReproduceArgs, delivery: crate::Delivery) -> Result<(), AppError> {
    let start = Instant::now();
    let threads = ranges::threads(args.threads)?;
    // Friction parameters only: every rig of the report runs at its own defaults.
    let rig_or_chain = |name: &str| {
        scenarios::ScenarioParams::spec(name).is_some()
            || friction_systems::chain::CHAIN_PARAMETERS
                .iter()
                .any(|p| p.0 == name)
    };
    let params = args.params.resolve_with(&[], |name, _| {
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
    let paper = Paper {
        friction: params,
        parameters: format!(
            "Parameter set `{}`{}",
            args.params.set_name(),
            if args.params.set.is_empty() && args.params.params.is_none() {
                ""
            } else {
                " with overrides (see figures.json)"
            }
        ),
    };
    let parts = paper.parts();
    let made = paper
        .report(parts.iter().map(|p| p.as_ref()).collect())
        .conduct(&args.out, threads)?;
    let mut files = made.files;
    delivery.apply(&mut files);
    let written = with_threads(threads, || files.write(&args.out))??;
    println!(
        "{} in {:.2} s",
        written.line(),
        start.elapsed().as_secs_f64()
    );
    if let Some(note) = written.stop_note() {
        crate::print_note(&note);
    }
    made.failure.map_or(Ok(()), Err)
}
