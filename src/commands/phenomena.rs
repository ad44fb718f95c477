//! `friction-lab phenomena --out DIR`: Table 2 decided by simulation for the paper's six
//! models and the reference models, beside the paper's claims, with the numbers that
//! decided each cell.

use crate::options::{LimitArgs, ParamOptions};
use clap::Args;
use friction_lab::artifacts::{Artifacts, Made};
use friction_lab::error::AppError;
use friction_lab::laws::ModelChoice;
use friction_lab::ranges;
use friction_lab::study::{conduct, reachable, unread_by_all, Table2Study, Target};
use friction_lab::threads::with_threads;
use friction_models::Variant;
use integrators::{Solver, StepControl};
use scenarios::phenomena::{catalog_laws, Protocol};
use scenarios::Law;
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
        help = crate::options::solver_help(
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
    pub params: ParamOptions,
    /// The bounds of every protocol run: a run that reaches one leaves its cell undecided.
    #[command(flatten)]
    pub limits: LimitArgs,
}

/// Runs `phenomena`: its files written, then the advice and the failure of undecided cells.
pub fn run(args: &PhenomenaArgs) -> Result<(), AppError> {
    let start = Instant::now();
    let threads = ranges::threads(args.threads)?;
    let made = make(args)?;
    let files = made.files;
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

/// Decides Table 2 as `phenomena` asks, its files in memory: `table2.md` and `table2.json`,
/// the advice about parameters no judged law reads, and the failure of undecided cells.
pub fn make(args: &PhenomenaArgs) -> Result<Made, AppError> {
    let step = StepControl::Adaptive {
        rtol: ranges::RTOL.check(args.rtol)?,
        atol: ranges::ATOL.check(args.atol)?,
        h0: None,
    };
    reachable(args.solver, args.rtol)?;
    let threads = ranges::threads(args.threads)?;
    if args.solver.is_fixed_step() {
        return Err(AppError::Usage(format!(
            "solver `{}` needs a fixed step; the protocols need an adaptive solver",
            args.solver.name()
        )));
    }
    let p = &args.params;
    let given = p.param_set != "paper" || p.params.is_some() || !p.set.is_empty();
    let parameters = if given {
        let mut described = format!("parameter set `{}`", p.param_set);
        if let Some(file) = &p.params {
            described += &format!(", file `{}`", file.display());
        }
        for s in &p.set {
            described += &format!(", `{s}`");
        }
        Some((p.source().resolve()?, described + " for every model"))
    } else {
        None
    };
    let mut files = Artifacts::default();
    let laws: Vec<Law> = if args.models.is_empty() {
        catalog_laws()
    } else {
        args.models.iter().map(|m| m.law(Variant::Odd)).collect()
    };
    let study = Table2Study {
        laws: &laws,
        protocol: Protocol {
            solver: args.solver,
            step,
            limits: args.limits.limits()?,
        },
        parameters,
    };
    let mut target = Target {
        files: &mut files,
        dir: &args.out,
        threads,
        failure: None,
    };
    conduct(&study, &mut target, "table2")?;
    let failure = target.failure;
    Ok(Made {
        files,
        notes: Vec::new(),
        warnings: unread_by_all(&p.set, &laws),
        failure,
        trajectory: None,
    })
}
