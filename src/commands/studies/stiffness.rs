//! `stiffness`: the cost to reach a target error across a stiffness parameter, and where
//! the implicit solvers overtake the explicit ones.

use super::{
    distinct, positive_list, resolution_cells, row_at_top, study_error, study_file, CaseArgs,
    Target,
};
use crate::artifacts::Made;
use crate::commands::simulate::Target as Problem;
use crate::error::AppError;
use crate::options::SchemeName;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use crate::progress::Progress;
use crate::ranges;
use crate::threads::with_threads;
use clap::Args;
use integrators::Solver;
use scenarios::studies::{self, Method, Stiffness, StudyCase};
use scenarios::SwitchingKind;

/// Options of `stiffness`.
#[derive(Args, Debug)]
pub struct StiffnessArgs {
    /// The problem.
    #[command(flatten)]
    pub case: CaseArgs,
    /// The parameter swept: epsilon, sigma, sigma0, k, or any other the run reads (on the
    /// chain: k_chain, m, …, or its law's; on a system file: epsilon).
    #[arg(long, value_name = "NAME", default_value = "epsilon")]
    pub parameter: String,
    /// Its values, in sweep order.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "1e-1,1e-2,1e-3,1e-4"
    )]
    pub values: Vec<f64>,
    /// Solvers, comma-separated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "dopri5,tsit45,implicit-euler,bdf,esdirk34"
    )]
    pub solvers: Vec<Solver>,
    /// The error to reach (maximum over the time grid).
    #[arg(
        long,
        value_name = "E",
        default_value_t = 1e-3,
        allow_hyphen_values = true
    )]
    pub target: f64,
    /// Step sizes of rk4, coarse to fine.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        default_value = "0.01,0.001,0.0001"
    )]
    pub dt_list: Vec<f64>,
    /// Tolerances tried, loose to tight.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1e-2,1e-3,1e-4,1e-5,1e-6,1e-7"
    )]
    pub tol_list: Vec<f64>,
}

/// Computes a stiffness sweep and adds its files under `dir` with stem `stem`.
pub fn add_stiffness(
    t: &mut Target,
    stem: &str,
    case: &dyn StudyCase,
    sweep: studies::Sweep,
    solvers: &[Solver],
    steps: &[f64],
    tols: &[f64],
) -> Result<Stiffness, AppError> {
    let (dir, threads) = (t.dir, t.threads);
    let studies::Sweep {
        parameter,
        values,
        target,
    } = sweep;
    positive_list("values", values)?;
    positive_list("target", &[target])?;
    distinct(solvers)?;
    ranges::DT.list("dt-list", steps)?;
    ranges::RTOL.list("tol-list", tols)?;
    if values.len() > 50 {
        return Err(AppError::Usage(format!(
            "option `values` has {} values: allowed 1 to 50",
            values.len()
        )));
    }
    let methods: Vec<Method> = Method::studied(case.switching(), solvers)
        .into_iter()
        .chain(case.peers())
        .collect();
    let per_value = Method::jobs(&methods, steps, tols, false).len();
    let b = Progress::runs(per_value * values.len(), "stiffness");
    let s = with_threads(threads, || {
        studies::stiffness(
            case,
            studies::Sweep {
                parameter,
                values,
                target,
            },
            &methods,
            steps,
            tols,
            &|| b.inc(),
        )
    })?
    .map_err(study_error)?;
    b.finish();
    let mut table = Table::new(&[
        "value",
        "solver",
        "implicit",
        "reached",
        "h",
        "tol",
        "error",
        "rhs_evals",
        "jacobian_evals",
        "lu_factorizations",
        "implicit_wins",
    ]);
    for p in &s.points {
        for c in &p.costs {
            // Numeric columns hold numbers or nothing: `reached` says why both are empty.
            let [h, tol] = resolution_cells(c.step, c.resolution);
            table.rows.push(vec![
                Cell::Num(p.value),
                Cell::Text(c.solver.clone()),
                Cell::Text(c.implicit.to_string()),
                Cell::Text(c.resolution.is_some().to_string()),
                h,
                tol,
                Cell::num(c.error),
                Cell::Num(c.stats.rhs_evals as f64),
                Cell::Num(c.stats.jacobian_evals as f64),
                Cell::Num(c.stats.lu_factorizations as f64),
                Cell::Text(p.implicit_wins.to_string()),
            ]);
        }
    }
    let csv = dir.join(format!("{stem}.csv"));
    t.files.add(csv.clone(), table.to_csv(&csv)?);
    t.files
        .add_json(dir.join(format!("{stem}.json")), &study_file(case, &s))?;
    // A solver that met the target at a value: a dot at its cost; one that did not: a cross
    // at the top of the plot, named, each such solver in a row of its own.
    let reached: Vec<(f64, f64)> = s
        .points
        .iter()
        .flat_map(|p| {
            p.costs
                .iter()
                .filter(|c| c.resolution.is_some())
                .map(|c| (p.value, c.work as f64))
        })
        .collect();
    let largest = reached.iter().map(|p| p.1).fold(1.0, f64::max);
    let mut series = Vec::new();
    let mut rows = 0;
    for (method, &color) in methods.iter().zip(PALETTE.iter().cycle()) {
        let label = method.label();
        let costs = || {
            s.points
                .iter()
                .filter_map(|p| Some((p.value, p.costs.iter().find(|c| c.solver == label)?)))
        };
        let met: Vec<(f64, f64)> = costs()
            .filter(|(_, c)| c.resolution.is_some())
            .map(|(v, c)| (v, c.work as f64))
            .collect();
        let top = row_at_top(largest, rows);
        let missed: Vec<(f64, f64)> = costs()
            .filter(|(_, c)| c.resolution.is_none())
            .map(|(v, _)| (v, top))
            .collect();
        if !met.is_empty() {
            series.push(Series {
                label: Some(label.clone()),
                points: met,
                color,
                width: 2,
                marker: Marker::Dot,
            });
        }
        if !missed.is_empty() {
            rows += 1;
            series.push(Series {
                label: Some(format!(
                    "{label}: target not reached at {} value(s) (at the top)",
                    missed.len()
                )),
                points: missed,
                color,
                width: 0,
                marker: Marker::Cross,
            });
        }
    }
    let plot = Plot {
        title: format!(
            "Cost to reach error {target:e} against {parameter}: {}",
            case.describe()
        ),
        x_label: parameter.to_string(),
        y_label: "work (f evaluations + dim per Jacobian)".into(),
        series,
        legend: Corner::UpperRight,
        log: true,
    };
    t.files.add_plot(&dir.join(stem), &plot)?;
    Ok(s)
}

/// Runs `stiffness`; its files in memory. Without `--switching`, a rig swept over `epsilon`
/// is regularized: the width changes nothing else (under event switching every value would
/// give the same runs), while a system keeps event switching, whose regularised BDF peer is
/// the method that depends on it.
pub fn stiffness(a: &StiffnessArgs) -> Result<Made, AppError> {
    let mut case = a.case.clone();
    if case.switching.is_none()
        && case.scheme == SchemeName::EventDriven
        && a.parameter == "epsilon"
        && matches!(case.scenario, Some(Problem::Rig(_)))
    {
        case.switching = Some(SwitchingKind::Regularized);
    }
    // A rig's run reads only what its model and switching read. A system's case checks its
    // parameter itself (`StudyCase::with_parameter`): epsilon, which under event switching
    // its regularised peer reads, and on the chain the chain's parameters and its law's.
    if let Some(Problem::Rig(_)) = case.scenario {
        crate::options::check_read("parameter", &a.parameter, case.model, case.treatment()?)?;
    }
    case.make(|t, case| {
        let sweep = studies::Sweep {
            parameter: &a.parameter,
            values: &a.values,
            target: a.target,
        };
        let s = add_stiffness(
            t,
            "stiffness",
            case,
            sweep,
            &a.solvers,
            &a.dt_list,
            &a.tol_list,
        )?;
        Ok(vec![s.verdict()])
    })
}
