//! `friction-lab phenomena --out DIR`: Table 2 decided by simulation for the paper's six
//! models and the reference models, beside the paper's claims, with the numbers that
//! decided each cell.

use crate::options::{LimitArgs, ParamOptions};
use clap::Args;
use friction_lab::artifacts::{Artifacts, Made};
use friction_lab::error::AppError;
use friction_lab::laws::{check_read, ModelChoice};
use friction_lab::ranges;
use friction_lab::study::{conduct, Table2Study, Target};
use friction_lab::threads::with_threads;
use friction_models::{ModelId, Variant};
use integrators::{Solver, StepControl};
use scenarios::phenomena::{catalog_laws, Protocol, PROTOCOL_PARAMETERS};
use scenarios::{Law, SwitchingKind};
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

/// The most steps a protocol run may be expected to need per second of simulated time,
/// [`reachable`]'s bound: about 10 s of one core for a rig.
pub const MAX_STEPS_PER_SECOND: f64 = 1e6;

/// Refuses a method whose order cannot reach the relative tolerance `rtol` in a bounded
/// number of steps: a method of order p keeps its global error near rtol with steps of about
/// rtol^(1/p) s (on a problem whose time scale is a second, as the protocols' rigs), so a
/// protocol run takes rtol^(−1/p) steps per second: 1e10 for implicit Euler at the default
/// 1e-10. Refused above [`MAX_STEPS_PER_SECOND`], naming the smallest rtol the method reaches.
pub fn reachable(solver: Solver, rtol: f64) -> Result<(), AppError> {
    let order = solver.order() as f64;
    let steps = rtol.powf(-1.0 / order);
    if steps <= MAX_STEPS_PER_SECOND {
        return Ok(());
    }
    Err(AppError::Usage(format!(
        "option `--rtol` = {rtol:e} is out of reach of solver `{}`, of order {order}: a \
         protocol run would take about {steps:.0e} steps per simulated second (rtol^(-1/order)), \
         more than the {MAX_STEPS_PER_SECOND:.0e} allowed; allowed with it: --rtol >= {:e}, or \
         choose a method of higher order (the default, bdf)",
        solver.name(),
        MAX_STEPS_PER_SECOND.powf(-order),
    )))
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
        Some((p.resolve()?, described + " for every model"))
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

/// The advice given for each `--set` of a friction parameter that neither the protocols
/// ([`PROTOCOL_PARAMETERS`]) nor any of the judged `models` reads under the protocols' event
/// switching ([`check_read`]; `epsilon` never): accepted, as `simulate` accepts it, but
/// said: every value would give the same table.
fn unread_by_all(set: &[String], laws: &[Law]) -> Vec<String> {
    let unread = |name: &str, m: ModelId| check_read("set", name, Some(m), SwitchingKind::Event);
    // A law of one's own may read any friction parameter through the rigs' scales.
    let unread_by = |name: &str, law: &Law| law.catalog().is_some_and(|m| unread(name, m).is_err());
    set.iter()
        .filter_map(|s| s.split_once('=').map(|(name, _)| name.trim()))
        .filter(|name| !PROTOCOL_PARAMETERS.contains(name))
        .filter(|name| *name == "epsilon" || laws.iter().all(|law| unread_by(name, law)))
        .map(|name| match (name, laws) {
            ("epsilon", _) => "option `set`: parameter `epsilon` is not read by the \
                 protocols, which switch at v = 0 by events: every value would give the same \
                 table"
                .to_string(),
            (_, [Law::Catalog { model, .. }]) => unread(name, *model)
                .expect_err("unread by every model")
                .to_string(),
            _ => format!(
                "option `set`: parameter `{name}` is read by none of the judged models: every \
                 value would give the same table"
            ),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use friction_lab::study::check_decided;
    use friction_models::ModelId;
    use scenarios::phenomena::{Cell, Phenomenon};

    fn cell(measured: Result<bool, String>) -> Cell {
        Cell {
            measured,
            paper: Some(true),
            evidence: Default::default(),
            region: None,
        }
    }

    /// The failure counts the undecided cells, in the singular for one, and names the first.
    #[test]
    fn undecided_cells_are_counted_and_the_first_named() {
        let failed = || cell(Err("too many steps".into()));
        let decided = vec![(
            ModelId::Cs.into(),
            vec![(Phenomenon::Stiction, cell(Ok(true)))],
        )];
        assert!(check_decided(&decided).is_ok());
        let one = vec![(
            ModelId::Cs.into(),
            vec![
                (Phenomenon::Stiction, cell(Ok(true))),
                (Phenomenon::Hysteresis, failed()),
            ],
        )];
        assert_eq!(
            check_decided(&one).unwrap_err().to_string(),
            "1 cell of Table 2 is undecided, its protocol run failed (marked in table2.md and \
             table2.json); the first: CS hysteresis: too many steps"
        );
        let two = vec![(
            ModelId::Cs.into(),
            vec![
                (Phenomenon::Stiction, failed()),
                (Phenomenon::Hysteresis, failed()),
            ],
        )];
        let e = check_decided(&two).unwrap_err().to_string();
        assert!(
            e.starts_with("2 cells of Table 2 are undecided, their protocol runs failed"),
            "{e}"
        );
        assert!(e.ends_with("the first: CS stiction: too many steps"), "{e}");
    }
}
