//! The simulation-cost row of Table 2 ([`scenarios::phenomena::cost`]): its cells, its section
//! of `table2.md`, its entries in `table2.json` and its wall times in `table2-timing.csv`.

use scenarios::phenomena::cost::{Cheapest, Costs, SYSTEMS, TARGET_ERROR, TIMING_REPEATS};
use scenarios::Law;
use serde_json::{json, Map, Value};

/// The row's label in the table.
pub const LABEL: &str = "Simulation cost (work × Coulomb's: belt, two masses)";

/// A ratio as the table prints it, `-` where a run did not reach the target.
fn ratio(r: Option<f64>) -> String {
    r.map_or_else(|| "-".into(), |r| format!("{r:.2}"))
}

/// Law `i`'s cell: its work over Coulomb's on each system.
pub fn cell(costs: &Costs, i: usize) -> String {
    (0..SYSTEMS.len())
        .map(|s| ratio(costs.relative_work(i, s)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// One cheapest run as the section's table prints it.
fn run_cells(c: &Result<Cheapest, String>) -> String {
    match c {
        Ok(c) => format!(
            "{} | {:e} | {:.2e} | {} |",
            c.solver, c.tolerance, c.error, c.work
        ),
        Err(_) => "none reached the target | - | - | - |".into(),
    }
}

/// The section of `table2.md` on the simulation cost.
pub fn section(laws: &[Law], costs: &Costs) -> String {
    let mut s = format!(
        "## Simulation cost\n\nThe paper's first criterion for choosing a model: the work of \
         simulating two stick–slip systems, from rest for 40 s, event-driven — the belt rig and \
         two masses in a row (1 kg pulled through 10 N/m by a driver at 0.1 m/s, 2 kg behind it \
         through 100 N/m) — to a grid error of {TARGET_ERROR:e} against a reference, with the cheapest \
         adequate run of Dormand–Prince, BDF and Radau IIA at rtol = atol from 1e-3 to 1e-10 \
         (docs/phenomena.md). Work counts right-hand sides, Jacobians and factorisations; each \
         law at the parameters of its column above. Wall times (median and spread of \
         {TIMING_REPEATS} runs, and over Coulomb's) are in `table2-timing.csv`: they depend on \
         the machine and are kept out of this file.\n\n\
         | model | system | solver | tolerance | grid error | work | × Coulomb |\n\
         |---|---|---|---|---|---|---|\n"
    );
    let mut line = |name: &str, c: &Result<Cheapest, String>, system: &str, rel: String| {
        s += &format!("| {name} | {system} | {} {rel} |\n", run_cells(c));
    };
    for (s_index, system) in SYSTEMS.iter().enumerate() {
        line(
            "coulomb (reference)",
            &costs.coulomb[s_index],
            system.description,
            "1".into(),
        );
    }
    for (i, law) in laws.iter().enumerate() {
        for (s_index, system) in SYSTEMS.iter().enumerate() {
            let rel = ratio(costs.relative_work(i, s_index));
            line(
                &law.to_string(),
                &costs.laws[i][s_index],
                system.description,
                rel,
            );
        }
    }
    s + "\n"
}

/// Law `i`'s `simulation_cost` in `table2.json`: by system, the cheapest adequate run
/// (solver, tolerance, error, work, stats) and its work over Coulomb's, or why there is none.
pub fn json(costs: &Costs, i: usize) -> Value {
    let mut out = Map::new();
    for (s, system) in SYSTEMS.iter().enumerate() {
        let entry = match &costs.laws[i][s] {
            Ok(c) => json!({
                "cheapest": c,
                "relative_work": costs.relative_work(i, s),
                "failed": null,
            }),
            Err(why) => json!({ "cheapest": null, "relative_work": null, "failed": why }),
        };
        out.insert(system.name.into(), entry);
    }
    Value::Object(out)
}

/// `table2-timing.csv`: each law's (and Coulomb's) adequate run on each system, its wall time
/// over the repeats and its median over Coulomb's.
pub fn timing_csv(laws: &[Law], costs: &Costs) -> String {
    let mut s = String::from(
        "model,system,solver,tolerance,repeats,wall_time_median_s,wall_time_min_s,\
         wall_time_q1_s,wall_time_q3_s,wall_time_max_s,relative_median\n",
    );
    let mut row = |name: &str, s_index: usize, c: &Result<Cheapest, String>, rel: Option<f64>| {
        if let Ok(c) = c {
            let w = c.wall_time;
            s += &format!(
                "{name},{},{},{:e},{},{:e},{:e},{:e},{:e},{:e},{}\n",
                SYSTEMS[s_index].name,
                c.solver,
                c.tolerance,
                w.repeats,
                w.median,
                w.min,
                w.q1,
                w.q3,
                w.max,
                rel.map_or_else(String::new, |r| format!("{r:e}"))
            );
        }
    };
    for s_index in 0..SYSTEMS.len() {
        row("coulomb", s_index, &costs.coulomb[s_index], Some(1.0));
    }
    for (i, law) in laws.iter().enumerate() {
        for s_index in 0..SYSTEMS.len() {
            let rel = costs.relative_wall_time(i, s_index);
            row(&law.to_string(), s_index, &costs.laws[i][s_index], rel);
        }
    }
    s
}
