//! `compare`: every formulation of v = 0 — events, regularisation over ε, naive stepping,
//! time-stepping — against the true nonsmooth solution, with each scheme's cost at a list of
//! target errors ([`scenarios::studies::compare`]).

use super::Problem;
use crate::error::{field, AppError, Invalid};
use crate::made::Made;
use crate::ranges;
use crate::study::{conduct, CompareStudy, Study};
use crate::threads::with_threads;
use integrators::Solver;
use scenarios::run::DEFAULT_THETA;
use scenarios::studies::{self, ComparePart, CompareSpec, Resolutions, Schemes, TrueSolution};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The explicit, implicit, regularised, naive and time-stepped runs of one problem, each
/// scored against the true nonsmooth solution (`friction-lab compare`).
#[derive(clap::Args, Clone, Debug)]
pub struct CompareRequest {
    /// The problem (its scheme options are not read: every scheme is compared).
    #[command(flatten)]
    pub problem: Problem,
    /// The target errors, each in (0, 1): `grid_relative`, the largest error on the time grid
    /// over the solution's scale in each quantity (dimensionless).
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "1e-2,1e-3,1e-4,1e-5,1e-6,1e-7,1e-8"
    )]
    pub targets: Vec<f64>,
    /// Solvers run event-driven, events located at v = 0.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "dopri5,rk4,radau5,rodas,bdf,auto"
    )]
    pub event_solvers: Vec<Solver>,
    /// Solvers run on the regularised law at every width of --epsilons.
    #[arg(long, value_delimiter = ',', default_value = "radau5,rodas,bdf,dopri5")]
    pub regularized_solvers: Vec<Solver>,
    /// The regularisation widths ε, relative to the true solution's velocity scale (its
    /// largest |v|).
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "1e-2,1e-3,1e-4,1e-5,1e-6"
    )]
    pub epsilons: Vec<f64>,
    /// Leave the regularised law out.
    #[arg(long)]
    pub no_regularized: bool,
    /// Solvers run through sign(0) = 0 without events.
    #[arg(long, value_delimiter = ',', default_value = "dopri5")]
    pub naive_solvers: Vec<Solver>,
    /// Leave naive stepping out.
    #[arg(long)]
    pub no_naive: bool,
    /// Leave Moreau–Jean time-stepping (θ = 1/2, over --ts-dt-list) out.
    #[arg(long)]
    pub no_timestepping: bool,
    /// Tolerances of the adaptive solvers, loose to tight (extended by tenths down to 1e-13
    /// while a scheme's error still falls short of the tightest target).
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "1e-2,1e-3,1e-4,1e-5,1e-6,1e-7,1e-8"
    )]
    pub tol_list: Vec<f64>,
    /// Step sizes of rk4, coarse to fine (extended by halves down to the finest over 64;
    /// coarse enough that a target is bracketed, not met by the first run, whose cost is then
    /// bounded above only).
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0.04,0.02,0.01,0.005,0.0025"
    )]
    pub dt_list: Vec<f64>,
    /// Step sizes of Moreau–Jean's scheme, coarse to fine (extended the same way).
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0.04,0.02,0.01,0.005,0.0025"
    )]
    pub ts_dt_list: Vec<f64>,
    /// Timings of each run: the median wall time and its quartiles. A run of 1e5 units of
    /// counted work or more, or one that failed, is timed once.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 3,
        allow_hyphen_values = true
    )]
    pub repeats: i64,
}

impl CompareRequest {
    /// The comparison of `problem` with every other setting at its declared default.
    pub fn new(problem: Problem) -> CompareRequest {
        CompareRequest {
            problem,
            ..crate::settings::declared_defaults()
        }
    }

    /// The schemes, resolutions and targets asked for.
    pub fn spec(&self) -> Result<CompareSpec, AppError> {
        self.problem.refuse_scheme(
            "compare",
            &format!(
                "it runs every scheme (choose them with {}, {}, {}, {} and {})",
                field("event_solvers"),
                field("regularized_solvers"),
                field("no_regularized"),
                field("no_naive"),
                field("no_timestepping"),
            ),
        )?;
        Ok(CompareSpec {
            schemes: Schemes {
                event: self.event_solvers.clone(),
                regularised: unless(self.no_regularized, &self.regularized_solvers),
                epsilons: self.epsilons.clone(),
                naive: unless(self.no_naive, &self.naive_solvers),
                theta: (!self.no_timestepping).then_some(DEFAULT_THETA),
            },
            resolutions: Resolutions {
                tolerances: self.tol_list.clone(),
                steps: self.dt_list.clone(),
                timestepping_steps: self.ts_dt_list.clone(),
            },
            targets: self.targets.clone(),
            repeats: ranges::REPEATS.count(self.repeats)? - 1,
        })
    }

    /// Checks and runs the comparison: its files in `out` (in memory), and its answer at each
    /// target.
    pub fn run(&self, out: &Path) -> Result<Made, AppError> {
        self.conduct(out, None)
    }

    /// The comparison made of `parts` (each made by [`CompareRequest::part`] of this
    /// request, in any order, on any machine): its files in `out` (in memory), as
    /// [`CompareRequest::run`] makes them, bit for bit but for the wall times. The true
    /// solution is computed here again (the reference run and its scale).
    pub fn merge(&self, out: &Path, parts: &[Vec<u8>]) -> Result<Made, AppError> {
        let count = self.part_count()?;
        let mut seen = vec![false; count];
        let mut decoded = Vec::new();
        for bytes in parts {
            let envelope: Envelope = ciborium::from_reader(bytes.as_slice())
                .map_err(|e| not_a_part(format!("it does not decode ({e})")))?;
            if envelope.request != self.fingerprint() {
                return Err(not_a_part(format!(
                    "it was made for another request ({})",
                    envelope.request
                )));
            }
            match seen.get_mut(envelope.index) {
                Some(s) if !*s => *s = true,
                _ => {
                    return Err(not_a_part(format!(
                        "its index {} is given twice or is not below {count}",
                        envelope.index
                    )))
                }
            }
            decoded.push(envelope.part);
        }
        if let Some(missing) = seen.iter().position(|s| !s) {
            return Err(not_a_part(format!("part {missing} of {count} is missing")));
        }
        self.conduct(out, Some(decoded))
    }

    /// How many independent parts the comparison divides into ([`studies::parts`]: the
    /// cross-check, each scheme without ε, each width ε with its regularised schemes).
    pub fn part_count(&self) -> Result<usize, AppError> {
        Ok(studies::parts(&self.spec()?).len())
    }

    /// Makes part `index` of the comparison (below [`CompareRequest::part_count`]) on this
    /// process's threads, encoded (CBOR) for [`CompareRequest::merge`]: the true solution,
    /// then the part's runs.
    pub fn part(&self, index: usize) -> Result<Vec<u8>, AppError> {
        let spec = self.spec()?;
        let parts = studies::parts(&spec);
        let Some(part) = parts.get(index) else {
            return Err(AppError::Invalid(Invalid {
                field: "part",
                value: index.to_string(),
                allowed: format!("an index below the comparison's {} parts", parts.len()),
                list: false,
            }));
        };
        let setup = self.problem.case()?;
        let case = setup.case.as_ref();
        CompareStudy {
            case,
            spec: &spec,
            parts: None,
        }
        .check()?;
        let made = with_threads(ranges::threads(self.problem.threads)?, || {
            let truth = TrueSolution::of(case)?;
            truth.part(case, &spec, part, &|| {})
        })??;
        let envelope = Envelope {
            request: self.fingerprint(),
            index,
            part: made,
        };
        let mut bytes = Vec::new();
        ciborium::into_writer(&envelope, &mut bytes)
            .map_err(|e| AppError::Usage(format!("a comparison's part does not encode: {e}")))?;
        Ok(bytes)
    }

    /// What the parts of this request are checked by: the request but for its thread count
    /// (a part may run on any number of threads).
    fn fingerprint(&self) -> String {
        let mut request = self.clone();
        request.problem.threads = None;
        format!("{request:?}")
    }

    /// Conducts the comparison (of `parts` where given) into `out`.
    fn conduct(&self, out: &Path, parts: Option<Vec<ComparePart>>) -> Result<Made, AppError> {
        let spec = self.spec()?;
        self.problem.make(out, |t, setup| {
            let study = CompareStudy {
                case: setup.case.as_ref(),
                spec: &spec,
                parts,
            };
            let c = conduct(&study, t, "compare")?;
            Ok(crate::study::compare_lines(&c))
        })
    }
}

/// A part of a comparison as it travels: the request it was made for, its index, and what
/// it made.
#[derive(Serialize, Deserialize)]
struct Envelope {
    request: String,
    index: usize,
    part: ComparePart,
}

/// The refusal of a part that does not belong to the comparison being merged.
fn not_a_part(why: String) -> AppError {
    AppError::Usage(format!(
        "a part given to merge does not belong to this comparison: {why}; make every part with \
         the same request"
    ))
}

/// `solvers`, or none where their family is `left_out`.
fn unless(left_out: bool, solvers: &[Solver]) -> Vec<Solver> {
    match left_out {
        true => Vec::new(),
        false => solvers.to_vec(),
    }
}
