//! Table 2 decided by simulation as a front end asks for it ([`PhenomenaRequest`]): the laws
//! judged, the solver and tolerances of every protocol, the parameters, the bounds.

use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::laws::ModelChoice;
use crate::made::Made;
use crate::params::{ParamSource, DEFAULT_PARAM_SET};
use crate::ranges;
use crate::settings::RunLimits;
use crate::study::{conduct, reachable, unread_by_all, Output, Table2Study};
use friction_models::Variant;
use integrators::{Solver, StepControl};
use scenarios::phenomena::{catalog_laws, Phenomenon, Protocol};
use scenarios::Law;
use std::path::Path;

/// Table 2 for some laws (`friction-lab phenomena`); its `Default` is the declared defaults.
#[derive(clap::Args, Clone, Debug)]
pub struct PhenomenaRequest {
    /// The solver every protocol uses (an adaptive one); BDF by default: the bristle models'
    /// stiff states make Dormand–Prince four times slower, with the same verdicts.
    #[arg(
        long,
        value_name = "SOLVER",
        default_value = "bdf",
        help = crate::settings::solver_help(
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
    /// Parameters for every judged law (friction parameters only); the default source (the
    /// set `paper`, no file, no assignment) leaves each model at its own set, `paper`, or
    /// `lugre-1995` for the bristle models lugre, lugre-vd, elasto-plastic and gms.
    #[command(flatten)]
    pub params: ParamSource,
    /// The bounds of every protocol run: a run that reaches one leaves its cell undecided.
    #[command(flatten)]
    pub limits: RunLimits,
}

crate::settings::default_as_declared!(PhenomenaRequest);

impl PhenomenaRequest {
    /// Decides Table 2, its files in `out` (in memory): `table2.md` and `table2.json`, the
    /// advice about parameters no judged law reads, and the failure of undecided cells.
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        let step = StepControl::Adaptive {
            rtol: ranges::RTOL.check(self.rtol)?,
            atol: ranges::ATOL.check(self.atol)?,
            h0: None,
        };
        reachable(self.solver, self.rtol)?;
        let threads = ranges::threads(self.threads)?;
        if self.solver.is_fixed_step() {
            return Err(AppError::Usage(format!(
                "solver `{}` needs a fixed step; the protocols need an adaptive solver",
                self.solver.name()
            )));
        }
        let p = &self.params;
        let given = p.set_name() != DEFAULT_PARAM_SET || p.params.is_some() || !p.set.is_empty();
        let parameters = if given {
            let mut described = format!("parameter set `{}`", p.set_name());
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
        let laws: Vec<Law> = if self.models.is_empty() {
            catalog_laws()
        } else {
            self.models.iter().map(|m| m.law(Variant::Odd)).collect()
        };
        let study = Table2Study {
            phenomena: &Phenomenon::ALL,
            laws: &laws,
            protocol: Protocol {
                solver: self.solver,
                step,
                limits: self.limits.limits()?,
            },
            parameters,
        };
        let mut target = Output {
            files: &mut files,
            dir: out,
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
            run: None,
        })
    }
}
