//! The catalog listed: every model with its equations and parameters, every friction and
//! scenario parameter with its unit, range, default and named sets, as `models` prints it
//! (text or JSON) and the Python package returns it.

use friction_models::{
    CurveAxis, FrictionParams, ModelId, ParamSpec, Parameters, Variant, PARAM_SETS,
};
use scenarios::{Scenario, ScenarioParams};
use serde::Serialize;
use std::collections::BTreeMap;

/// One model as listed.
#[derive(Serialize)]
struct ModelEntry {
    name: &'static str,
    title: &'static str,
    source: &'static str,
    in_paper: bool,
    equation: &'static str,
    equation_printed: Option<&'static str>,
    parameters: &'static [&'static str],
    curve_axis: CurveAxis,
}

/// One parameter as listed, with its value in every named set.
#[derive(Serialize)]
struct ParamEntry {
    #[serde(flatten)]
    spec: ParamSpec,
    range_text: String,
    default: f64,
    sets: BTreeMap<&'static str, f64>,
}

/// A scenario parameter as listed, with the scenarios that read it.
#[derive(Serialize)]
struct ScenarioParamEntry {
    #[serde(flatten)]
    spec: ParamSpec,
    range_text: String,
    default: f64,
    scenarios: Vec<&'static str>,
}

/// The whole listing.
#[derive(Serialize)]
struct Listing {
    models: Vec<ModelEntry>,
    parameters: Vec<ParamEntry>,
    scenario_parameters: Vec<ScenarioParamEntry>,
    parameter_sets: Vec<&'static str>,
    variants: [&'static str; 2],
}

fn listing() -> Listing {
    let models = ModelId::ALL
        .into_iter()
        .map(|m| ModelEntry {
            name: m.name(),
            title: m.title(),
            source: m.source(),
            in_paper: m.in_paper(),
            equation: m.equation(Variant::Odd),
            equation_printed: m.has_printed_form().then(|| m.equation(Variant::Printed)),
            parameters: m.parameters(),
            curve_axis: m.curve_axis(),
        })
        .collect();
    let sets: Vec<(&str, FrictionParams)> = PARAM_SETS
        .iter()
        .map(|&n| (n, FrictionParams::named(n).expect("listed sets exist")))
        .collect();
    let parameters = FrictionParams::specs()
        .iter()
        .map(|spec| ParamEntry {
            spec: *spec,
            range_text: spec.range.to_string(),
            default: FrictionParams::paper()
                .value(spec.name)
                .expect("spec has slot"),
            sets: sets
                .iter()
                .map(|(n, p)| (*n, p.value(spec.name).expect("spec has slot")))
                .collect(),
        })
        .collect();
    let scenario_parameters = ScenarioParams::specs()
        .iter()
        .map(|spec| ScenarioParamEntry {
            spec: *spec,
            range_text: spec.range.to_string(),
            default: ScenarioParams::default()
                .value(spec.name)
                .expect("spec has slot"),
            scenarios: Scenario::ALL
                .iter()
                .filter(|s| s.parameters().contains(&spec.name))
                .map(|s| s.name())
                .collect(),
        })
        .collect();
    Listing {
        models,
        parameters,
        scenario_parameters,
        parameter_sets: PARAM_SETS.to_vec(),
        variants: ["odd", "printed"],
    }
}

/// A value in at most 12 characters: exact when it fits, else rounded to 6 decimals (the
/// JSON listing keeps every digit).
fn short(x: f64) -> String {
    let exact = x.to_string();
    if exact.len() <= 12 {
        exact
    } else {
        format!("{x:.6}")
    }
}

/// The listing as `models` prints it: every model with its equation, then the friction and
/// scenario parameters with their units, values, ranges and meanings.
pub fn text() -> String {
    let l = &listing();
    let mut out = String::from("Models (sign(0) = 0; S(v) = C1*exp(-(v/v_s)^2) for v > 0, -C2*exp(-(v/v_s)^2) for v < 0)\n\n");
    for m in &l.models {
        let origin = if m.in_paper { "paper" } else { "reference" };
        out += &format!("{:<9} {} [{origin}; {}]\n", m.name, m.title, m.source);
        out += &format!("          {}\n", m.equation);
        if let Some(printed) = m.equation_printed {
            out += &format!("          as printed (--variant printed): {printed}\n");
        }
        out += &format!(
            "          parameters: {}; curve against {}\n\n",
            m.parameters.join(", "),
            match m.curve_axis {
                CurveAxis::Velocity => "velocity",
                CurveAxis::Displacement => "displacement",
            }
        );
    }
    out += "Parameters (--set NAME=VALUE, --params FILE.toml, --param-set NAME)\n\n";
    out += &format!(
        "{:<8} {:<6} {:>12} {:>12}  {:<12} meaning\n",
        "name", "unit", "paper", "lugre-1995", "range"
    );
    for p in &l.parameters {
        out += &format!(
            "{:<8} {:<6} {:>12} {:>12}  {:<12} {}\n",
            p.spec.name,
            p.spec.unit,
            short(p.sets["paper"]),
            short(p.sets["lugre-1995"]),
            p.range_text,
            p.spec.meaning
        );
    }
    out +=
        "\nScenario parameters (simulate and the studies; defaults as most scenarios use them)\n\n";
    out += &format!(
        "{:<10} {:<6} {:>12}  {:<12} scenarios\n",
        "name", "unit", "default", "range"
    );
    for p in &l.scenario_parameters {
        out += &format!(
            "{:<10} {:<6} {:>12}  {:<12} {}\n",
            p.spec.name,
            p.spec.unit,
            short(p.default),
            p.range_text,
            p.scenarios.join(", ")
        );
    }
    out += "(free-vibration starts from x0 = 0.5 m, as docs/scenarios.md sets it)\n";
    out += &format!(
        "\nNamed parameter sets: {}\nVariants: odd (default), printed\n",
        l.parameter_sets.join(", ")
    );
    out
}

/// The listing as JSON, as `models --json` prints it.
pub fn json() -> String {
    serde_json::to_string_pretty(&listing()).expect("the listing serialises")
}
