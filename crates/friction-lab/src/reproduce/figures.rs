//! Figures 2–7: each of the paper's six models drawn from its equations (and as printed, where
//! the printed equations differ), with what the paper says of the figure against what the
//! equations give (`figures/`, `reproduction.md`, `figures.json`).

use super::Part;
use crate::error::AppError;
use crate::figure::{Drawn, KeyValues};
use crate::laws::used_parameters;
use crate::study::{conduct, Output, Study, StudyFiles};
use friction_models::{CurveAxis, FrictionParams, ModelId, Variant};
use scenarios::curves::{self, Curve};
use scenarios::figures::{assess, Finding, PaperFigure, PAPER_FIGURES};
use serde::Serialize;
use std::collections::BTreeMap;

/// Samples per branch of each figure.
pub const POINTS: usize = 2000;

/// The paper's six figures at `friction`, with `header` (how they were made and judged) atop
/// `reproduction.md`.
pub struct PaperFiguresStudy {
    /// The friction parameters.
    pub friction: FrictionParams,
    /// The paragraph that opens `reproduction.md`.
    pub header: String,
}

/// One figure reproduced: its curves and what they say against the paper.
pub struct Figure {
    /// The paper's figure.
    pub paper: &'static PaperFigure,
    /// The curve of the sign-consistent reading.
    pub odd: Curve,
    /// The curve of the equations as printed, where they differ.
    pub printed: Option<Curve>,
    /// Its record in `figures.json`.
    pub record: Reproduced,
}

/// One reproduced figure as `figures.json` records it.
#[derive(Serialize)]
pub struct Reproduced {
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

impl PaperFiguresStudy {
    /// Figure `fig` reproduced.
    fn figure(&self, fig: &'static PaperFigure) -> Result<Figure, AppError> {
        let p = &self.friction;
        let odd = paper_curve(fig.model, Variant::Odd, p)?;
        let printed = fig
            .model
            .has_printed_form()
            .then(|| paper_curve(fig.model, Variant::Printed, p))
            .transpose()?;
        let record = Reproduced {
            figure: fig.number,
            model: fig.model.name(),
            files: format!("figures/{}", stem(fig)),
            parameters: used_parameters(fig.model, p),
            odd: KeyValues::of(&odd),
            printed: printed.as_ref().map(KeyValues::of),
            findings: fig.claims.iter().map(|&c| assess(c, &odd)).collect(),
        };
        Ok(Figure {
            paper: fig,
            odd,
            printed,
            record,
        })
    }
}

/// The stem of a figure's files: `figure-4-CVS`.
fn stem(fig: &PaperFigure) -> String {
    format!("figure-{}-{}", fig.number, fig.model)
}

impl Study for PaperFiguresStudy {
    type Result = Vec<Figure>;

    fn name(&self) -> &'static str {
        "Figures 2-7"
    }

    /// Every model builds at the parameters given.
    fn check(&self) -> Result<(), AppError> {
        for fig in &PAPER_FIGURES {
            fig.model.build(Variant::Odd, &self.friction)?;
        }
        Ok(())
    }

    fn runs(&self) -> usize {
        PAPER_FIGURES.len()
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<Vec<Figure>, AppError> {
        PAPER_FIGURES
            .iter()
            .map(|fig| {
                let figure = self.figure(fig)?;
                progress();
                Ok(figure)
            })
            .collect()
    }

    /// `figures/figure-N-MODEL.{csv,png,svg}`, `reproduction.md` and `figures.json` in the
    /// report's folder.
    fn write(&self, figures: &Vec<Figure>, out: &mut StudyFiles) -> Result<(), AppError> {
        let mut md = String::new();
        for f in figures {
            let mut drawn = vec![Drawn {
                variant: Variant::Odd,
                curve: &f.odd,
            }];
            if let Some(p) = &f.printed {
                drawn.push(Drawn {
                    variant: Variant::Printed,
                    curve: p,
                });
            }
            let fig = f.paper;
            let title = format!(
                "Figure {}: {} ({}), {}",
                fig.number,
                fig.model,
                fig.model.title(),
                fig.model.source()
            );
            out.files.add_figure(
                &out.dir.join("figures"),
                &stem(fig),
                title,
                fig.model,
                &drawn,
            )?;
            md += &notes(fig, &f.record);
        }
        let reproduction = format!(
            "# Figures 2-7: the paper against its own equations\n\n{}\n{md}",
            self.header
        );
        out.files
            .add(out.dir.join("reproduction.md"), reproduction.into_bytes());
        let records: Vec<&Reproduced> = figures.iter().map(|f| &f.record).collect();
        out.files.add_json(out.path(".json"), &records)
    }
}

/// How one row of the key-value table is written.
type KeyValueText = fn(&KeyValues) -> String;

fn newton(x: f64) -> String {
    format!("{x:.4} N")
}

/// The section of `reproduction.md` on one figure: the paper's caption and words, the key
/// values of the curves, each claim against the equations, and remarks.
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
        CurveAxis::Velocity => "m/s",
        CurveAxis::Displacement => "m",
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

/// The report's section on Figures 2–7.
pub struct Figures {
    /// The friction parameters.
    pub friction: FrictionParams,
    /// How the figures were made and judged.
    pub header: String,
}

impl Part for Figures {
    fn heading(&self) -> String {
        "Figures 2-7: the friction curves".into()
    }

    fn check(&self) -> Result<(), AppError> {
        self.study().check()
    }

    fn conduct(&self, target: &mut Output) -> Result<String, AppError> {
        let figures = conduct(&self.study(), target, "figures")?;
        let mut s = String::from(
            "Each figure draws the model's equations with the parameters of Table 1 \
             (red: sign-consistent reading; wide blue: the equations exactly as printed, \
             where they differ; green: the forces admissible at rest). \
             [reproduction.md](reproduction.md) compares each with the paper's description.\n\n",
        );
        for f in &figures {
            let r = &f.record;
            let disagreements = r.findings.iter().filter(|f| !f.agrees).count();
            s += &format!(
                "- [Figure {} ({})]({}.png): {} of {} checked claims of the paper disagree with \
                 the equations.\n",
                r.figure,
                r.model,
                r.files,
                disagreements,
                r.findings.len()
            );
        }
        Ok(s)
    }
}

impl Figures {
    fn study(&self) -> PaperFiguresStudy {
        PaperFiguresStudy {
            friction: self.friction,
            header: self.header.clone(),
        }
    }
}
