//! Table 2 decided by simulation ([`scenarios::phenomena`]): every protocol for every model,
//! each cell with its verdict over a grid of rig parameters, written beside the paper's claims
//! as `table2.md` and `table2.json` with the numbers that decided each cell.

use super::table2_cost;
use super::{Study, StudyFiles};
use crate::error::{field, AppError};
use crate::laws::check_read;
use friction_models::{FrictionParams, ModelId};
use integrators::Solver;
use scenarios::phenomena::cost::{Costs, RUNS_PER_LAW};
use scenarios::phenomena::{
    table, thresholds, Cell, Phenomenon, Protocol, Row, PROTOCOL_PARAMETERS,
};
use scenarios::Law;
use serde_json::{json, Map, Value};

/// Table 2 for `laws` under `protocol`, each at its own parameter set or all at `parameters`
/// (with the words that describe them).
pub struct Table2Study<'a> {
    /// The laws, in column order: models of the catalog, or laws of one's own.
    pub laws: &'a [Law],
    /// The rows, in order: [`Phenomenon::ALL`] for the paper's table, rows of one's own
    /// besides.
    pub phenomena: &'a [Phenomenon],
    /// The solver, tolerances and bounds of every protocol run.
    pub protocol: Protocol,
    /// Parameters for every model, with their description; `None`: each model at its own set.
    pub parameters: Option<(FrictionParams, String)>,
}

/// Table 2 as decided: every law's row, and every law's simulation cost.
pub struct Decided {
    /// Each law with its cells, in column order.
    pub rows: Vec<(Law, Row)>,
    /// Each law's simulation cost, and Coulomb's.
    pub cost: Costs,
}

impl Study for Table2Study<'_> {
    type Result = Decided;

    fn name(&self) -> &'static str {
        "Table 2"
    }

    fn runs(&self) -> usize {
        self.laws.len() * self.phenomena.len() + (self.laws.len() + 1) * RUNS_PER_LAW
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<Self::Result, AppError> {
        let parameters = self.parameters.as_ref().map(|p| &p.0);
        let rows = table(
            self.laws,
            self.phenomena,
            self.protocol,
            parameters,
            true,
            progress,
        )?;
        let cost = Costs::of(self.laws, parameters, &self.protocol, progress)?;
        Ok(Decided { rows, cost })
    }

    /// Cells left undecided, their protocol runs failed ([`check_decided`]): the files mark
    /// them, and the command exits 1.
    fn failure(&self, decided: &Self::Result) -> Option<AppError> {
        check_decided(&decided.rows).err()
    }

    /// `{stem}.md` (the table beside the paper's, with the protocols and their verdicts over
    /// their grids, and the simulation cost), `{stem}.json` (every cell with its evidence)
    /// and `{stem}-timing.csv` (the wall times of the simulation cost).
    fn write(&self, decided: &Self::Result, out: &mut StudyFiles) -> Result<(), AppError> {
        let (rows, cost) = (&decided.rows, &decided.cost);
        let own = own_parameters();
        let described = self
            .parameters
            .as_ref()
            .map_or(own.as_str(), |p| p.1.as_str());
        out.files.add(
            out.path(".md"),
            markdown(rows, cost, &self.protocol, described).into_bytes(),
        );
        out.files.add(
            out.path("-timing.csv"),
            table2_cost::timing_csv(self.laws, cost).into_bytes(),
        );
        out.add_json(&json!({ "models": json_table(rows, cost) }))
    }
}

/// Table 2 as `table2.json`: `{"<model>": {"<phenomenon>": {measured, failed, paper,
/// evidence, region}, "simulation_cost": …}}`: `measured` null and `failed` the reason for a
/// cell whose run failed, `region` the verdict over the cell's grid of rig parameters (axes,
/// points, fraction, flips, undecided); `simulation_cost` as [`table2_cost::json`] writes it.
fn json_table(rows: &[(Law, Row)], cost: &Costs) -> Value {
    let mut out = Map::new();
    for (i, (model, row)) in rows.iter().enumerate() {
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
        cells.insert("simulation_cost".into(), table2_cost::json(cost, i));
        out.insert(model.to_string(), Value::Object(cells));
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
fn regions_markdown(rows: &[(Law, Row)]) -> String {
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
    for phenomenon in phenomena(rows) {
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

/// The rows of the table, in order (every law has the same).
fn phenomena(rows: &[(Law, Row)]) -> Vec<Phenomenon> {
    rows.first()
        .map_or_else(Vec::new, |(_, row)| row.iter().map(|(p, _)| *p).collect())
}

/// Table 2 as markdown: the measured table beside the paper's, then the evidence.
pub fn markdown(
    rows: &[(Law, Row)],
    cost: &Costs,
    protocol: &Protocol,
    parameters: &str,
) -> String {
    let mut s = String::from("# Table 2, decided by simulation\n\n");
    if integrators::interrupt::requested() {
        s += &crate::artifacts::stopped_banner(&format!(
            "{} of its cells are undecided",
            undecided(rows).len()
        ));
    }
    s += &format!(
        "Written by `friction-lab phenomena` with solver {} ({}), event switching, {parameters}. \
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
    for (law, _) in rows {
        let paper = [4, 4, 4, 3, 3, 4];
        let Some(m) = law.catalog() else {
            s += " (its own) |";
            continue;
        };
        let n = m.parameters().len();
        match ModelId::PAPER.iter().position(|&p| p == m) {
            Some(i) => s += &format!(" {n} ({}) |", paper[i]),
            None => s += &format!(" {n} |"),
        }
    }
    s += "\n";
    for (i, phenomenon) in phenomena(rows).iter().enumerate() {
        s += &format!("| {} |", phenomenon.label());
        for (_, row) in rows {
            let c = &row[i].1;
            s += &format!(" {} |", mark(c));
        }
        s += "\n";
    }
    s += &format!("| {} |", table2_cost::LABEL);
    for i in 0..rows.len() {
        s += &format!(" {} |", table2_cost::cell(cost, i));
    }
    s += "\n";
    let disagreements: usize = rows
        .iter()
        .flat_map(|(_, r)| r.iter())
        .filter(|(_, c)| c.disagrees())
        .count();
    let claims = (rows.iter().flat_map(|(_, r)| r.iter()))
        .filter(|(_, c)| c.paper.is_some())
        .count();
    s +=
        &format!("\n{disagreements} of the paper's {claims} claims disagree with the simulations.");
    let failed = undecided(rows).len();
    if failed > 0 {
        s += &format!(
            " {failed} cells are undecided: a run of their protocol failed (the evidence below \
             says where and why)."
        );
    }
    s += "\n\n";
    s += &regions_markdown(rows);
    let laws: Vec<Law> = rows.iter().map(|(law, _)| law.clone()).collect();
    s += &table2_cost::section(&laws, cost);
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
         break-away force change beyond {}; hunting: the servo settled on a limit cycle over \
         the last half of {} s, none if it settled at rest or each of its last {} stops is at \
         least {} nearer the set point than the one before.\n",
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
        thresholds::HUNTING_T_END,
        thresholds::DYING_STOPS,
        thresholds::DYING_RATIO,
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

/// The cells whose protocol failed, as `model phenomenon: why`, in the table's order.
pub fn undecided(rows: &[(Law, Row)]) -> Vec<String> {
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
pub fn check_decided(rows: &[(Law, Row)]) -> Result<(), AppError> {
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
    let option = field("rtol");
    Err(AppError::Usage(format!(
        "option `{option}` = {rtol:e} is out of reach of solver `{}`, of order {order}: a \
         protocol run would take about {steps:.0e} steps per simulated second (rtol^(-1/order)), \
         more than the {MAX_STEPS_PER_SECOND:.0e} allowed; allowed with it: {option} >= {:e}, or \
         choose a method of higher order (the default, bdf)",
        solver.name(),
        MAX_STEPS_PER_SECOND.powf(-order),
    )))
}

/// The advice given for each `--set` of a friction parameter that neither the protocols
/// ([`PROTOCOL_PARAMETERS`]) nor any of the judged `models` reads under the protocols' event
/// switching ([`check_read`]; `epsilon` never): accepted, as `simulate` accepts it, but
/// said: every value would give the same table.
pub fn unread_by_all(set: &[String], laws: &[Law]) -> Vec<String> {
    let unread = |name: &str, m: ModelId| check_read("set", name, Some(m), Some("event"));
    // A law of one's own may read any friction parameter through the rigs' scales.
    let unread_by = |name: &str, law: &Law| law.catalog().is_some_and(|m| unread(name, m).is_err());
    set.iter()
        .filter_map(|s| s.split_once('=').map(|(name, _)| name.trim()))
        .filter(|name| !PROTOCOL_PARAMETERS.contains(name))
        .filter(|name| *name == "epsilon" || laws.iter().all(|law| unread_by(name, law)))
        .map(|name| match (name, laws) {
            ("epsilon", _) => format!(
                "option `{}`: parameter `epsilon` is not read by the protocols, which switch at \
                 v = 0 by events: every value would give the same table",
                field("set")
            ),
            (_, [Law::Catalog { model, .. }]) => unread(name, *model)
                .expect_err("unread by every model")
                .marked(),
            _ => format!(
                "option `{}`: parameter `{name}` is read by none of the judged models: every \
                 value would give the same table",
                field("set")
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
        let decided = vec![(
            ModelId::Cs.into(),
            vec![(Phenomenon::STICTION, cell(Ok(true)))],
        )];
        assert!(check_decided(&decided).is_ok());
        let one = vec![(
            ModelId::Cs.into(),
            vec![
                (Phenomenon::STICTION, cell(Ok(true))),
                (Phenomenon::HYSTERESIS, failed()),
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
                (Phenomenon::STICTION, failed()),
                (Phenomenon::HYSTERESIS, failed()),
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
