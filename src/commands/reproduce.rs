//! `friction-lab reproduce --out DIR`: the paper's Figures 2–7 with notes on what the paper
//! says of each, what the equations give, and where the two disagree.

use crate::artifacts::Artifacts;
use crate::commands::curve::{used_parameters, KeyValues};
use crate::error::AppError;
use crate::figure::Drawn;
use crate::options::ParamOptions;
use clap::Args;
use friction_models::{FrictionParams, ModelId, Variant};
use scenarios::curves::{self, Curve};
use scenarios::figures::{
    assess, Finding, PaperFigure, LEVEL_OFF_FRACTION, NUMERIC_TOLERANCE, PAPER_FIGURES,
};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Instant;

/// Options of `reproduce`.
#[derive(Args, Debug)]
pub struct ReproduceArgs {
    /// Folder to write into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The parameters (Table 1 of the paper unless changed).
    #[command(flatten)]
    pub params: ParamOptions,
}

/// Samples per branch of each figure.
const POINTS: usize = 2000;

/// One reproduced figure.
#[derive(Serialize)]
struct Reproduced {
    figure: u32,
    model: &'static str,
    files: String,
    parameters: BTreeMap<&'static str, f64>,
    odd: KeyValues,
    printed: Option<KeyValues>,
    findings: Vec<Finding>,
}

/// The curve of one model under one reading, on the paper's range.
fn paper_curve(model: ModelId, variant: Variant, p: &FrictionParams) -> Result<Curve, AppError> {
    let m = model.build(variant, p)?;
    Ok(curves::curve(
        m.as_ref(),
        curves::default_extent(model.curve_axis()),
        POINTS,
    )?)
}

/// How one row of the key-value table is written.
type KeyValueText = fn(&KeyValues) -> String;

fn newton(x: f64) -> String {
    format!("{x:.4} N")
}

fn notes(fig: &PaperFigure, r: &Reproduced) -> String {
    let mut s = format!(
        "## Figure {}: {} ({}, {})\n\n![Figure {}]({}.png)\n\n",
        fig.number,
        fig.model,
        fig.model.title(),
        fig.model.source(),
        fig.number,
        r.files
    );
    s += &format!("*Caption in the paper:* \"{}\"\n\n", fig.caption);
    s += &format!("**What the paper says.** {}\n\n", fig.paper_says);
    s += "**What the equations give.**\n\n";
    let unit = match fig.model.curve_axis() {
        friction_models::CurveAxis::Velocity => "m/s",
        friction_models::CurveAxis::Displacement => "m",
    };
    let rows: [(&str, KeyValueText); 5] = [
        ("force just left of zero", |k| newton(k.left_of_zero)),
        ("force just right of zero", |k| newton(k.right_of_zero)),
        ("forces admissible at rest", |k| {
            format!("[{:.4}, {:.4}] N", k.at_rest.lower, k.at_rest.upper)
        }),
        ("force at the positive end", |k| newton(k.end_force)),
        ("force at the negative end", |k| {
            newton(k.end_force_negative)
        }),
    ];
    s += "| quantity | sign-consistent reading (default) |";
    s += if r.printed.is_some() {
        " as printed |\n|---|---|---|\n"
    } else {
        "\n|---|---|\n"
    };
    for (name, value) in rows {
        s += &format!("| {name} | {} |", value(&r.odd));
        if let Some(p) = &r.printed {
            s += &format!(" {} |", value(p));
        }
        s += "\n";
    }
    s += &format!(
        "| end of the range | {:.4} {unit} |{}\n\n",
        r.odd.end_abscissa,
        if r.printed.is_some() { " same |" } else { "" }
    );
    s += "**The paper's claims against the equations** (sign-consistent reading).\n\n";
    s += "| the paper says | the equations give | verdict |\n|---|---|---|\n";
    for f in &r.findings {
        let verdict = if f.agrees { "agrees" } else { "**disagrees**" };
        s += &format!("| {} | {} | {verdict} |\n", f.claim, f.computed);
    }
    s += &format!(
        "\n**Remarks** (for the parameters of Table 1). {}\n\n",
        fig.remarks
    );
    s
}

fn report(reproduced: &[Reproduced], header: &str) -> String {
    let mut s = String::from("# friction-lab: reproduction of the paper\n\n");
    s += header;
    s += "\n## Figures 2-7: the friction curves\n\n";
    s += "Each figure draws the model's equations with the parameters of Table 1 \
          (red: sign-consistent reading; wide blue: the equations exactly as printed, \
          where they differ; green: the forces admissible at rest). \
          [reproduction.md](reproduction.md) compares each with the paper's description.\n\n";
    for r in reproduced {
        let disagreements = r.findings.iter().filter(|f| !f.agrees).count();
        s += &format!(
            "- [Figure {} ({})]({}.png): {} of {} checked claims of the paper disagree with the equations.\n",
            r.figure,
            r.model,
            r.files,
            disagreements,
            r.findings.len()
        );
    }
    s
}

/// Runs `reproduce`.
pub fn run(args: &ReproduceArgs) -> Result<(), AppError> {
    let start = Instant::now();
    let params = args.params.resolve()?;
    let mut files = Artifacts::default();
    let mut reproduced = Vec::new();
    let mut md = String::new();
    for fig in &PAPER_FIGURES {
        let odd = paper_curve(fig.model, Variant::Odd, &params)?;
        let printed = fig
            .model
            .has_printed_form()
            .then(|| paper_curve(fig.model, Variant::Printed, &params))
            .transpose()?;
        let mut drawn = vec![Drawn {
            variant: Variant::Odd,
            curve: &odd,
        }];
        if let Some(p) = &printed {
            drawn.push(Drawn {
                variant: Variant::Printed,
                curve: p,
            });
        }
        let stem = format!("figure-{}-{}", fig.number, fig.model);
        let title = format!(
            "Figure {}: {} ({}), {}",
            fig.number,
            fig.model,
            fig.model.title(),
            fig.model.source()
        );
        files.add_figure(&args.out.join("figures"), &stem, title, fig.model, &drawn)?;
        let r = Reproduced {
            figure: fig.number,
            model: fig.model.name(),
            files: format!("figures/{stem}"),
            parameters: used_parameters(fig.model, &params),
            odd: KeyValues::of(&odd),
            printed: printed.as_ref().map(KeyValues::of),
            findings: fig.claims.iter().map(|&c| assess(c, &odd)).collect(),
        };
        md += &notes(fig, &r);
        reproduced.push(r);
    }
    let header = format!(
        "Written by `friction-lab reproduce` (friction-lab {}). Parameter set `{}`{}. \
         Curves: |v| <= 1 m/s for Figures 2-4; the prescribed motion X(t) = t^3/3 + t^2/2, \
         t in [0, 2] s, and its mirror image for Figures 5-7; {POINTS} samples per branch.\n\n\
         A numeric claim agrees when within {:.0} % of the paper's value (the paper reads its \
         values off its plots). A curve levels off when its slope over the last 10 % of its \
         range, times the range, is below {:.0} % of its end value.\n",
        env!("CARGO_PKG_VERSION"),
        args.params.param_set,
        if args.params.set.is_empty() && args.params.params.is_none() {
            String::new()
        } else {
            " with overrides (see figures.json)".to_string()
        },
        100.0 * NUMERIC_TOLERANCE,
        100.0 * LEVEL_OFF_FRACTION,
    );
    let reproduction =
        format!("# Figures 2-7: the paper against its own equations\n\n{header}\n{md}");
    files.add(args.out.join("reproduction.md"), reproduction.into_bytes());
    files.add_json(args.out.join("figures.json"), &reproduced)?;
    files.add(
        args.out.join("report.md"),
        report(&reproduced, &header).into_bytes(),
    );
    let written = files.write()?;
    println!(
        "wrote {} files into {} in {:.2} s",
        written.len(),
        args.out.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
