//! `friction-lab phenomena --out DIR`: Table 2 decided by simulation for the paper's six
//! models and the reference models, beside the paper's claims, with the numbers that
//! decided each cell.

use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::options::{check_read, LimitArgs, ParamOptions};
use crate::ranges;
use crate::threads::with_threads;
use clap::Args;
use friction_models::{FrictionParams, ModelId};
use integrators::{Solver, StepControl};
use scenarios::phenomena::{
    table, thresholds, Cell, Phenomenon, Protocol, Row, PROTOCOL_PARAMETERS,
};
use scenarios::SwitchingKind;
use serde_json::{json, Map, Value};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Options of `phenomena`.
#[derive(Args, Debug)]
pub struct PhenomenaArgs {
    /// Folder to write into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The solver every protocol uses (adaptive solvers only; BDF by default: the bristle
    /// models' stiff states make Dormand-Prince four times slower, with the same verdicts).
    #[arg(long, value_name = "SOLVER", default_value = "bdf")]
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
    /// The models to judge, repeatable [default: every model].
    #[arg(long = "model", value_name = "MODEL")]
    pub models: Vec<ModelId>,
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

/// Table 2 as `table2.json`: `{"<model>": {"<phenomenon>": {measured, failed, paper,
/// evidence, region}}}`: `measured` null and `failed` the reason for a cell whose run failed,
/// `region` the verdict over the cell's grid of rig parameters (axes, points, fraction,
/// flips, undecided).
fn json_table(rows: &[(ModelId, Row)]) -> Value {
    let mut out = Map::new();
    for (model, row) in rows {
        let mut cells = Map::new();
        for (p, c) in row {
            cells.insert(
                p.name().into(),
                json!({
                    "measured": c.measured.as_ref().ok(),
                    "failed": c.measured.as_ref().err(),
                    "paper": c.paper,
                    "evidence": c.evidence,
                    "region": c.region,
                }),
            );
        }
        out.insert(model.name().into(), Value::Object(cells));
    }
    Value::Object(out)
}

fn mark(c: &Cell) -> String {
    let Ok(measured) = c.measured else {
        return match c.paper {
            Some(p) => format!("failed, paper {}", u8::from(p)),
            None => "failed".into(),
        };
    };
    let m = u8::from(measured);
    let mark = match c.paper {
        Some(p) if p != measured => format!("**{m}** ≠ {}", u8::from(p)),
        Some(p) => format!("{m} = {}", u8::from(p)),
        None => m.to_string(),
    };
    match &c.region {
        Some(r) if r.depends() => format!("{mark} (depends: {:.0} %)", 100.0 * r.fraction),
        _ => mark,
    }
}

/// Most flipping points listed per cell in `table2.md` (all are in `table2.json`).
const FLIPS_LISTED: usize = 4;

/// The section of `table2.md` on the verdicts over the grids of rig parameters.
fn regions_markdown(rows: &[(ModelId, Row)]) -> String {
    if !rows
        .iter()
        .any(|(_, r)| r.iter().any(|(_, c)| c.region.is_some()))
    {
        return String::new();
    }
    let mut s = String::from(
        "## Over the rig's parameters\n\nEach cell is also decided at every point of a grid of \
         the rig's parameters, the default rig among them; a cell marked `depends: P %` holds on \
         P % of its grid (`table2.json` lists every point where it flips). The grids:\n\n",
    );
    for phenomenon in Phenomenon::ALL {
        let axes: Vec<String> = phenomenon
            .region()
            .iter()
            .map(|(name, values)| {
                let v: Vec<String> = values.iter().map(|v| v.to_string()).collect();
                format!("{name} ∈ {{{}}}", v.join(", "))
            })
            .collect();
        s += &format!(
            "- {}: {}\n",
            phenomenon.label(),
            if axes.is_empty() {
                "no rig parameter (steady friction or a prescribed motion): the default rig only"
                    .to_string()
            } else {
                axes.join(" × ")
            }
        );
    }
    s += "\n";
    for (model, row) in rows {
        for (phenomenon, c) in row {
            let (Ok(measured), Some(r)) = (
                c.measured.as_ref(),
                c.region
                    .as_ref()
                    .filter(|r| r.depends() || !r.undecided.is_empty()),
            ) else {
                continue;
            };
            let point = |p: &std::collections::BTreeMap<&str, f64>| {
                p.iter()
                    .map(|(k, v)| format!("{k} = {v}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            let mut flips: Vec<String> = r.flips.iter().take(FLIPS_LISTED).map(point).collect();
            if r.flips.len() > FLIPS_LISTED {
                flips.push(format!("{} more", r.flips.len() - FLIPS_LISTED));
            }
            s += &format!(
                "- {model}, {}: {} on {:.0} % of {} points; not {} at ({})",
                phenomenon.label(),
                u8::from(*measured),
                100.0
                    * (if *measured {
                        r.fraction
                    } else {
                        1.0 - r.fraction
                    }),
                r.points - r.undecided.len(),
                u8::from(*measured),
                flips.join("; ")
            );
            if !r.undecided.is_empty() {
                s += &format!("; {} points undecided (the run failed)", r.undecided.len());
            }
            s += "\n";
        }
    }
    s + "\n"
}

/// Table 2 as markdown: the measured table beside the paper's, then the evidence.
pub fn markdown(rows: &[(ModelId, Row)], protocol: &Protocol, parameters: &str) -> String {
    let mut s = String::from("# Table 2, decided by simulation\n\n");
    s += &format!(
        "Written by `friction-lab phenomena` with solver {} ({:?}), event switching, {parameters}. \
         Each cell reads `measured = paper`; a disagreement is \
         bold, `measured ≠ paper`. The protocols and thresholds are in docs/phenomena.md.\n\n",
        protocol.solver.name(),
        protocol.step
    );
    s += "| phenomenon |";
    for (m, _) in rows {
        s += &format!(" {m} |");
    }
    s += "\n|---|";
    s += &"---|".repeat(rows.len());
    s += "\n| parameters read (paper's count) |";
    for (m, _) in rows {
        let paper = [4, 4, 4, 3, 3, 4];
        let n = m.parameters().len();
        match ModelId::PAPER.iter().position(|p| p == m) {
            Some(i) => s += &format!(" {n} ({}) |", paper[i]),
            None => s += &format!(" {n} |"),
        }
    }
    s += "\n";
    for (i, phenomenon) in Phenomenon::ALL.iter().enumerate() {
        s += &format!("| {} |", phenomenon.label());
        for (_, row) in rows {
            let c = &row[i].1;
            s += &format!(" {} |", mark(c));
        }
        s += "\n";
    }
    let disagreements: usize = rows
        .iter()
        .flat_map(|(_, r)| r.iter())
        .filter(|(_, c)| c.disagrees())
        .count();
    s += &format!("\n{disagreements} of the paper's 42 claims disagree with the simulations.");
    let failed = undecided(rows).len();
    if failed > 0 {
        s += &format!(
            " {failed} cells are undecided: a run of their protocol failed (the evidence below \
             says where and why)."
        );
    }
    s += "\n\n";
    s += &regions_markdown(rows);
    s += "## Evidence\n\n";
    for (model, row) in rows {
        s += &format!(
            "### {model}\n\n| phenomenon | measured | paper | evidence |\n|---|---|---|---|\n"
        );
        for (p, c) in row {
            let evidence: Vec<String> = c
                .evidence
                .iter()
                .map(|(k, v)| format!("{k} = {v:.6e}"))
                .collect();
            let paper = c.paper.map_or("-".to_string(), |p| u8::from(p).to_string());
            let (measured, evidence) = match &c.measured {
                Ok(m) => (u8::from(*m).to_string(), evidence.join(", ")),
                Err(why) => ("failed".to_string(), why.clone()),
            };
            s += &format!("| {} | {measured} | {paper} | {evidence} |\n", p.label());
        }
        s += "\n";
    }
    s += &format!(
        "Thresholds: stiction: break-away force under a ramp of {}·max(F_s, F_c) per second \
         above the kinetic level after it by more than {}; pre-sliding x_max > {} m and recovery > {}; Stribeck \
         and viscous relative change beyond {}; hysteresis: a friction–velocity loop wider than {} \
         in sliding or a pre-sliding loss above {} per cycle; stick–slip: at \
         least {} stick phases in the settled half and {} per cycle; rising static friction: \
         break-away force change beyond {}.\n",
        thresholds::STICTION_RATE,
        thresholds::STATIC_EXCESS,
        thresholds::PRESLIDING_MIN,
        thresholds::PRESLIDING_RECOVERY,
        thresholds::STEADY_CHANGE,
        thresholds::LAG_WIDTH,
        thresholds::PRESLIDING_DISSIPATION,
        thresholds::STICK_PHASES,
        thresholds::STICK_PER_CYCLE,
        thresholds::BREAKAWAY_CHANGE,
    );
    s
}

/// The parameters of Table 2 when none are given: each model at its own set
/// ([`phenomena::parameters_for`]).
fn own_parameters() -> String {
    let lugre: Vec<&str> = ModelId::ALL
        .iter()
        .filter(|&&m| scenarios::phenomena::parameters_for(m) == FrictionParams::lugre_1995())
        .map(|m| m.name())
        .collect();
    format!(
        "parameter set `paper` (`lugre-1995` for {})",
        lugre.join(", ")
    )
}

/// Which models Table 2 is decided for, and at which parameters.
pub struct Judged<'a> {
    /// The models, in column order.
    pub models: &'a [ModelId],
    /// Parameters for every model, with their description; `None`: each model at its own set.
    pub parameters: Option<(FrictionParams, String)>,
}

impl Default for Judged<'_> {
    /// Every model, each at its own parameter set.
    fn default() -> Self {
        Judged {
            models: &ModelId::ALL,
            parameters: None,
        }
    }
}

/// The cells whose protocol failed, as `model phenomenon: why`, in the table's order.
pub fn undecided(rows: &[(ModelId, Row)]) -> Vec<String> {
    rows.iter()
        .flat_map(|(m, row)| row.iter().map(move |(p, c)| (m, p, c)))
        .filter_map(|(m, p, c)| {
            let why = c.measured.as_ref().err()?;
            Some(format!("{m} {}: {why}", p.name()))
        })
        .collect()
}

/// The failure of a command whose Table 2 has undecided cells (exit 1, after its files are
/// written), or `Ok` if every cell was decided.
pub fn check_decided(rows: &[(ModelId, Row)]) -> Result<(), AppError> {
    let failed = undecided(rows);
    match failed.first() {
        None => Ok(()),
        Some(first) => {
            let count = match failed.len() {
                1 => "1 cell of Table 2 is undecided, its protocol run".to_string(),
                n => format!("{n} cells of Table 2 are undecided, their protocol runs"),
            };
            Err(AppError::StudyRun(format!(
                "{count} failed (marked in table2.md and table2.json); the first: {first}"
            )))
        }
    }
}

/// Computes Table 2 and adds `table2.md` and `table2.json` in `dir` to `files`.
pub fn add_table(
    files: &mut Artifacts,
    dir: &Path,
    protocol: Protocol,
    judged: &Judged,
    threads: Option<usize>,
) -> Result<Vec<(ModelId, Row)>, AppError> {
    let parameters = judged.parameters.as_ref();
    let rows = with_threads(threads, || {
        table(judged.models, protocol, parameters.map(|p| &p.0), true)
    })?
    .map_err(AppError::from)?;
    let own = own_parameters();
    let described = parameters.map_or(own.as_str(), |p| p.1.as_str());
    files.add(
        dir.join("table2.md"),
        markdown(&rows, &protocol, described).into_bytes(),
    );
    files.add_json(dir.join("table2.json"), &json_table(&rows))?;
    Ok(rows)
}

/// Runs `phenomena`.
pub fn run(args: &PhenomenaArgs) -> Result<(), AppError> {
    let step = StepControl::Adaptive {
        rtol: ranges::RTOL.check(args.rtol)?,
        atol: ranges::ATOL.check(args.atol)?,
        h0: None,
    };
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
    let start = Instant::now();
    let mut files = Artifacts::default();
    let models = if args.models.is_empty() {
        ModelId::ALL.to_vec()
    } else {
        args.models.clone()
    };
    let rows = add_table(
        &mut files,
        &args.out,
        Protocol {
            solver: args.solver,
            step,
            limits: args.limits.limits()?,
        },
        &Judged {
            models: &models,
            parameters,
        },
        threads,
    )?;
    let written = with_threads(threads, || files.write(&args.out))??;
    println!(
        "wrote {} files into {} in {:.1} s",
        written.len(),
        args.out.display(),
        start.elapsed().as_secs_f64()
    );
    for warning in unread_by_all(&p.set, &models) {
        eprintln!("note: {warning}");
    }
    check_decided(&rows)
}

/// The advice given for each `--set` of a friction parameter that neither the protocols
/// ([`PROTOCOL_PARAMETERS`]) nor any of the judged `models` reads under the protocols' event
/// switching ([`check_read`]; `epsilon` never): accepted, as `simulate` accepts it, but
/// said: every value would give the same table.
fn unread_by_all(set: &[String], models: &[ModelId]) -> Vec<String> {
    let unread = |name: &str, m: ModelId| check_read("set", name, Some(m), SwitchingKind::Event);
    set.iter()
        .filter_map(|s| s.split_once('=').map(|(name, _)| name.trim()))
        .filter(|name| !PROTOCOL_PARAMETERS.contains(name))
        .filter(|name| models.iter().all(|&m| unread(name, m).is_err()))
        .map(|name| match (name, models) {
            ("epsilon", _) => "option `set`: parameter `epsilon` is not read by the \
                 protocols, which switch at v = 0 by events: every value would give the same \
                 table"
                .to_string(),
            (_, [m]) => unread(name, *m)
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
    use super::check_decided;
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
        let decided = vec![(ModelId::Cs, vec![(Phenomenon::Stiction, cell(Ok(true)))])];
        assert!(check_decided(&decided).is_ok());
        let one = vec![(
            ModelId::Cs,
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
            ModelId::Cs,
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
