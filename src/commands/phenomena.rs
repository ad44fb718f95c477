//! `friction-lab phenomena --out DIR`: Table 2 decided by simulation for the paper's six
//! models and the reference models, beside the paper's claims, with the numbers that
//! decided each cell.

use clap::Args;
use friction_lab::error::AppError;
use friction_lab::laws::ModelChoice;
use friction_lab::params::ParamSource;
use friction_lab::plot::Format;
use friction_lab::ranges;
use friction_lab::settings::RunLimits;
use friction_lab::study::Phenomena;
use friction_lab::threads::with_threads;
use integrators::Solver;
use std::path::PathBuf;
use std::time::Instant;

/// Options of `phenomena`.
#[derive(Args, Debug)]
pub struct PhenomenaArgs {
    /// Folder to write into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The solver every protocol uses (its help lists the built-in solvers).
    #[arg(
        long,
        value_name = "SOLVER",
        default_value = "bdf",
        help = friction_lab::settings::solver_help(
            "The solver every protocol uses, one of",
            "(adaptive solvers only; BDF by default: the bristle models' stiff states make \
             Dormand-Prince four times slower, with the same verdicts)"
        )
    )]
    pub solver: Solver,
    /// Relative tolerance.
    #[arg(
        long,
        value_name = "R",
        allow_hyphen_values = true,
        default_value = "1e-10"
    )]
    pub rtol: f64,
    /// Absolute tolerance.
    #[arg(
        long,
        value_name = "A",
        allow_hyphen_values = true,
        default_value = "1e-12"
    )]
    pub atol: f64,
    /// Worker threads (default: all cores; more than the machine has are capped to its cores).
    /// The table does not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub threads: Option<i64>,
    /// The models to judge, repeatable: names `friction-lab models` lists, or laws registered
    /// by name (from Python: docs/python.md) [default: every model of the catalog].
    #[arg(long = "model", value_name = "MODEL")]
    pub models: Vec<ModelChoice>,
    /// Parameters for every judged model (`--param-set`, `--params`, `--set`, friction
    /// parameters only) [default: each model at its own set, `paper`, or `lugre-1995` for
    /// the bristle models lugre, lugre-vd, elasto-plastic and gms]. Naming `--param-set paper`
    /// alone is the default.
    #[command(flatten)]
    pub params: ParamSource,
    /// The bounds of every protocol run: a run that reaches one leaves its cell undecided.
    #[command(flatten)]
    pub limits: RunLimits,
}

/// Runs `phenomena`: its files written, then the advice and the failure of undecided cells.
/// `format`: the figures' size and resolution.
pub fn run(args: &PhenomenaArgs, format: Format) -> Result<(), AppError> {
    let start = Instant::now();
    let threads = ranges::threads(args.threads)?;
    let made = args.study().run(&args.out)?;
    let mut files = made.files;
    files.set_format(format);
    let written = with_threads(threads, || files.write(&args.out))??;
    println!(
        "{} in {:.1} s",
        written.line(),
        start.elapsed().as_secs_f64()
    );
    for warning in made.warnings.iter().chain(written.stop_note().iter()) {
        eprintln!("note: {warning}");
    }
    made.failure.map_or(Ok(()), Err)
}

impl PhenomenaArgs {
    /// Table 2 as the library takes it.
    pub fn study(&self) -> Phenomena {
        Phenomena {
            solver: self.solver,
            rtol: self.rtol,
            atol: self.atol,
            threads: self.threads,
            models: self.models.clone(),
            params: self.params.clone(),
            limits: self.limits,
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::{Cli, Command};
    use clap::Parser;
    use friction_lab::study::Phenomena;

    #[test]
    fn the_options_default_to_the_librarys_settings() {
        let cli = Cli::try_parse_from(["fl", "phenomena", "--out", "x"]).unwrap();
        let Command::Phenomena(args) = cli.command else {
            unreachable!()
        };
        let (given, library) = (args.study(), Phenomena::default());
        assert_eq!((given.rtol, given.atol), (library.rtol, library.atol));
        assert_eq!(given.solver.name(), library.solver.name());
        assert_eq!(given.params.param_set, library.params.param_set);
        assert_eq!(given.limits.max_steps, library.limits.max_steps);
    }
}
