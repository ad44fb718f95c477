//! `friction-lab reproduce --out DIR`: the paper's Figures 2–7 with notes on what the paper
//! says of each, what the equations give, and where the two disagree.

use crate::artifacts::Artifacts;
use crate::commands::curve::KeyValues;
use crate::error::AppError;
use crate::figure::Drawn;
use crate::laws::used_parameters;
use crate::options::ParamOptions;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use crate::provenance::Provenance;
use crate::ranges;
use crate::study::{
    check_decided, conduct, conduct_all, undecided, ConvergenceStudy, Entry, IndependenceStudy,
    Refinement, ReportEntry, ScalingStudy, StiffnessStudy, Table2Study, Target, WorkPrecisionStudy,
};
use crate::threads::with_threads;
use clap::Args;
use friction_models::{FrictionParams, ModelId, Parameters, Variant};
use friction_systems::chain::ChainParams;
use integrators::StepControl;
use integrators::{interrupt, Solver};
use scenarios::curves::{self, Curve};
use scenarios::figures::{
    assess, Finding, PaperFigure, LEVEL_OFF_FRACTION, NUMERIC_TOLERANCE, PAPER_FIGURES,
};
use scenarios::paper::{experiment, Asymptote, ExperimentFailure, ExperimentRow};
use scenarios::phenomena::Protocol;
use scenarios::studies::{Case, Method, StudyCase, SystemCase};
use scenarios::studies::{
    Convergence, ErrorMeasure, Independence, Scaling, Stiffness, WorkPrecision,
};
use scenarios::Limits;
use scenarios::{Scenario, SwitchingKind};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;
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
    /// Worker threads for the parallel parts (default: all cores; more than the machine has are
    /// capped to its cores). Results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub threads: Option<i64>,
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

/// The paper's experiment: its figure, its data and its table against the closed forms.
fn add_experiment(
    files: &mut Artifacts,
    dir: &std::path::Path,
    rows: &[Result<ExperimentRow, ExperimentFailure>],
) -> Result<String, AppError> {
    let stem = dir.join("figures/paper-experiment-velocity");
    let mut table = Table::new(&["model", "t", "v"]);
    let mut series = Vec::new();
    for (row, color) in rows.iter().zip(PALETTE) {
        let (model, velocity, label) = match row {
            Ok(r) => (r.model, &r.velocity, r.model.name().to_string()),
            Err(f) => (f.model, &f.velocity, format!("{} (failed)", f.model)),
        };
        table.rows.extend(
            velocity
                .iter()
                .map(|&(t, v)| vec![Cell::Text(model.name().into()), Cell::Num(t), Cell::Num(v)]),
        );
        series.push(Series {
            label: Some(label),
            points: velocity.clone(),
            color,
            width: 2,
            marker: Marker::None,
        });
    }
    let csv = stem.with_extension("csv");
    files.add(csv.clone(), table.to_csv(&csv)?);
    let p = Plot {
        title: "The paper's experiment: 1 kg pushed by 15 N from rest".into(),
        x_label: "time t (s)".into(),
        y_label: "velocity v (m/s)".into(),
        series,
        legend: Corner::default(),
        log: false,
    };
    files.add_plot(&stem, &p)?;
    let mut md = String::from(
        "## The paper's experiment (section 3)\n\nA 1 kg block pushed by F_ex = 15 N from rest \
         (`paper-block`), Table 1 parameters, Dormand-Prince with rtol = atol = 1e-12 and event \
         switching. Once the Stribeck term has died out and the Dahl state has saturated, the \
         friction force is a constant level plus mu_v*v: a model with a viscous term tends to \
         v_t = (F_ex - level)/mu_v, one without accelerates at a = (F_ex - level)/m (and a \
         push that does not exceed the level, or the break-away at rest, leaves the block at \
         rest).\n\n\
         ![velocity](figures/paper-experiment-velocity.png)\n\n\
         | model | closed form | simulated | relative error | v(5 s) (m/s) | x(5 s) (m) |\n|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let r = match r {
            Ok(r) => r,
            Err(f) => {
                md += &format!("| {} | failed: {} | | | | |\n", f.model, f.why);
                continue;
            }
        };
        let closed = match r.predicted {
            Asymptote::TerminalVelocity(v) => format!("v_t = {v} m/s"),
            Asymptote::Acceleration(a) => format!("a = {a} m/s^2"),
            Asymptote::Rest => "at rest (v = 0)".to_string(),
        };
        md += &format!(
            "| {} | {closed} | {:.9} | {:.1e} | {:.4} | {:.4} |\n",
            r.model, r.measured, r.relative_error, r.v_at_5s, r.x_at_5s
        );
    }
    Ok(md)
}

/// A study case on the paper's parameters.
fn case(
    scenario: Scenario,
    model: ModelId,
    switching: SwitchingKind,
    friction: &FrictionParams,
    t_end: f64,
) -> Case {
    Case {
        scenario,
        law: model.into(),
        friction: *friction,
        params: scenario.defaults(),
        switching,
        t_end,
        limits: Limits::default(),
    }
}

fn observed_orders(c: &Convergence, measure: ErrorMeasure) -> String {
    c.orders
        .iter()
        .filter(|t| t.measure == measure)
        .map(|t| {
            format!(
                "{} {}",
                t.solver,
                t.fit.map_or("- (no asymptotic range)".into(), |f| {
                    format!("{:.2} (95 % CI {:.2} to {:.2})", f.slope, f.ci[0], f.ci[1])
                })
            )
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The solver studies on the paper's problems, with their report section.
fn add_studies(
    files: &mut Artifacts,
    out: &std::path::Path,
    friction: &FrictionParams,
    threads: Option<usize>,
) -> Result<String, AppError> {
    let dir = out.join("studies");
    let mut t = Target {
        files,
        dir: &dir,
        threads,
        failure: None,
    };
    let from_paper_dt = Refinement {
        start: 1e-3,
        ratio: 2.0,
        levels: 4,
        tol: 1e-6,
    };
    let rk4 = [Solver::RK4];
    let native = [Solver::RK4, Solver::DOPRI5, Solver::IMPLICIT_EULER];
    let steps = [0.02, 0.01, 0.005, 0.0025];
    let all = Solver::ALL;
    let explicit_implicit = [
        Solver::DOPRI5,
        Solver::TSIT45,
        Solver::IMPLICIT_EULER,
        Solver::BDF,
        Solver::ESDIRK34,
    ];
    let block_cvs = case(
        Scenario::PaperBlock,
        ModelId::Cvs,
        SwitchingKind::Event,
        friction,
        5.0,
    );
    let block_av = case(
        Scenario::PaperBlock,
        ModelId::Av,
        SwitchingKind::Event,
        friction,
        5.0,
    );
    let vibration = |switching| {
        case(
            Scenario::FreeVibration,
            ModelId::Static,
            switching,
            friction,
            2.0,
        )
    };
    let (naive, switched) = (
        vibration(SwitchingKind::Naive),
        vibration(SwitchingKind::Event),
    );
    let belt = |switching, t_end| case(Scenario::Belt, ModelId::Cs, switching, friction, t_end);
    let (belt_naive, belt_event) = (
        belt(SwitchingKind::Naive, 20.0),
        belt(SwitchingKind::Event, 5.0),
    );
    let belt_regularized = belt(SwitchingKind::Regularized, 2.0);
    let independent = |i: &scenarios::studies::Independence| {
        if i.independent {
            "independent"
        } else {
            "**not** independent"
        }
    };
    let convergence = |case| ConvergenceStudy {
        case,
        solvers: &rk4,
        steps: &steps,
        tols: &[1e-6],
    };
    let table: [&dyn ReportEntry; 7] = [
        &Entry {
            stem: "converge-paper-block-CVS",
            study: ConvergenceStudy {
                solvers: &native,
                ..convergence(&block_cvs)
            },
            reads: |c: &Convergence| {
                format!(
                    "- [Convergence on the paper block (CVS)](studies/converge-paper-block-CVS.png): \
                     observed orders of the relative grid error over each method's asymptotic \
                     range {}.\n",
                    observed_orders(c, ErrorMeasure::GridRelative)
                )
            },
        },
        &Entry {
            stem: "converge-free-vibration-naive",
            study: convergence(&naive),
            reads: |c: &Convergence| {
                format!(
                    "- [Stepping blindly through v = 0](studies/converge-free-vibration-naive.png) \
                     on Coulomb free vibration (closed-form reversals every pi/omega): RK4's \
                     order is {}.\n",
                    observed_orders(c, ErrorMeasure::GridRelative)
                )
            },
        },
        &Entry {
            stem: "converge-free-vibration-event",
            study: convergence(&switched),
            reads: |c: &Convergence| {
                format!(
                    "- [The same with event-located switching](studies/converge-free-vibration-event.png): \
                     RK4's order is {}.\n",
                    observed_orders(c, ErrorMeasure::GridRelative)
                )
            },
        },
        &Entry {
            stem: "independence-paper-block-AV",
            study: IndependenceStudy {
                case: &block_av,
                solver: Solver::RK4,
                refinement: from_paper_dt,
            },
            reads: |i: &Independence| {
                format!(
                    "- [The paper's step-size claim on AV](studies/independence-paper-block-AV.png) \
                     (RK4 from dt = 1e-3, halved three times, relative tolerance 1e-6): {}.\n",
                    independent(i)
                )
            },
        },
        &Entry {
            stem: "independence-belt-CS-naive",
            study: IndependenceStudy {
                case: &belt_naive,
                solver: Solver::RK4,
                refinement: from_paper_dt,
            },
            reads: |i: &Independence| {
                format!(
                    "- [The same check on CS stick-slip stepped blindly](studies/independence-belt-CS-naive.png): {}.\n",
                    independent(i)
                )
            },
        },
        &Entry {
            stem: "work-precision-belt-CS",
            study: WorkPrecisionStudy {
                case: &belt_event,
                solvers: &all,
                steps: &[0.01, 0.003, 0.001, 0.0003],
                tols: &[
                    0.001, 0.000464, 0.000215, 0.0001, 4.64e-5, 2.15e-5, 1e-5, 4.64e-6, 2.15e-6,
                    1e-6, 4.64e-7, 2.15e-7, 1e-7, 4.64e-8, 2.15e-8, 1e-8,
                ],
                repeats: 5,
            },
            reads: |_: &WorkPrecision| {
                "- [Work against precision on the belt](studies/work-precision-belt-CS.png): \
                 relative error against counted work (f evaluations, with Jacobians, LU \
                 factorisations and back-solves weighted by their operation counts) for every \
                 solver; wall times in studies/work-precision-belt-CS-timing.csv.\n"
                    .into()
            },
        },
        &Entry {
            stem: "stiffness-belt-CS-epsilon",
            study: StiffnessStudy {
                case: &belt_regularized,
                sweep: scenarios::studies::Sweep {
                    parameter: "epsilon",
                    values: &[1.0, 1e-1, 1e-2, 1e-3, 1e-4],
                    target: 1e-3,
                },
                solvers: &explicit_implicit,
                steps: &[0.01],
                tols: &[
                    0.01, 0.00464, 0.00215, 0.001, 0.000464, 0.000215, 0.0001, 4.64e-05, 2.15e-05,
                    1e-05, 4.64e-06, 2.15e-06, 1e-06, 4.64e-07, 2.15e-07, 1e-07,
                ],
            },
            reads: |s: &Stiffness| {
                format!(
                    "- [Cost to reach relative error 1e-3 against the regularisation width](studies/stiffness-belt-CS-epsilon.png): \
                     {}.\n",
                    s.verdict()
                )
            },
        },
    ];
    let lines = conduct_all(&table, &mut t)?;
    let chain = add_chain_studies(&mut t, friction)?;
    Ok(format!(
        "\n## Solver studies\n\nThe files are in `studies/` (CSV per run, JSON summary, PNG and SVG); \
         docs/studies.md explains each study and how to read its plot.\n\n{lines}{chain}"
    ))
}

/// The chain of `systems.md` (`static` friction: stiction on every block) with `n` blocks,
/// every block started at x0 = −0.7 m (its driver spring loaded to 7 N, just below the
/// break-away level 7.5 N, so that the blocks break away within the first second), as a study
/// case over `t_end` seconds, event-driven.
/// The initial displacement of every block of the chain studies, m.
const PRELOAD_X0: f64 = -0.7;

fn chain_case(n: usize, friction: &FrictionParams, t_end: f64) -> Result<SystemCase, AppError> {
    let mut system = ChainParams {
        n_bodies: n,
        ..ChainParams::default()
    }
    .build(friction, |p| {
        ModelId::Static.build(Variant::Odd, p).map(Arc::from)
    })?;
    for b in &mut system.bodies {
        b.x0 = PRELOAD_X0;
    }
    // Pre-loaded after it was built: not the chain its parameters build, so no `chain`.
    Ok(SystemCase {
        epsilon: friction.epsilon,
        ..SystemCase::new(
            format!("chain of {n} blocks with static friction"),
            system,
            t_end,
        )
    })
}

/// Event-driving, regularisation and time-stepping on the chain: work–precision at N = 100
/// and the cost per step against N up to 1000, with their report section.
fn add_chain_studies(t: &mut Target, friction: &FrictionParams) -> Result<String, AppError> {
    let chain_100 = chain_case(100, friction, 5.0)?;
    let sizes = [10, 30, 100, 300, 1000];
    let cases = sizes
        .iter()
        .map(|&n| {
            Ok((
                n,
                Box::new(chain_case(n, friction, 4.0)?) as Box<dyn StudyCase>,
            ))
        })
        .collect::<Result<Vec<_>, AppError>>()?;
    let adaptive = StepControl::Adaptive {
        rtol: 1e-6,
        atol: 1e-6,
        h0: None,
    };
    let mut methods = vec![(Method::of(Solver::DOPRI5), adaptive)];
    methods.extend(cases[0].1.peers().into_iter().map(|m| {
        let step = if m.is_fixed_step() {
            StepControl::Fixed { h: 1e-3 }
        } else {
            adaptive
        };
        (m, step)
    }));
    let epsilon = friction.epsilon;
    let table: [&dyn ReportEntry; 2] = [
        &Entry {
            stem: "work-precision-chain-100",
            study: WorkPrecisionStudy {
                case: &chain_100,
                solvers: &[Solver::DOPRI5, Solver::BDF],
                steps: &[0.01, 0.00464, 0.00215, 0.001, 0.000464],
                tols: &[
                    1e-4, 4.64e-5, 2.15e-5, 1e-5, 4.64e-6, 2.15e-6, 1e-6, 4.64e-7, 2.15e-7, 1e-7,
                    4.64e-8, 2.15e-8, 1e-8,
                ],
                repeats: 5,
            },
            reads: |_: &WorkPrecision| {
                format!(
                    "- [Work against precision at N = 100](studies/work-precision-chain-100.png) over 5 s: \
                     event-driven Dormand–Prince and BDF (tolerances 1e-4 to 1e-8, three a decade; wall \
                     times the median of 5 repeats), BDF on the regularised \
                     system (width epsilon = {epsilon}, sparse Jacobian; its error stops at the regularisation's), \
                     and Moreau–Jean time-stepping (theta = 1/2, h = 1e-2 to 4.64e-4; first order with \
                     stiction).\n"
                )
            },
        },
        &Entry {
            stem: "cost-chain",
            study: ScalingStudy {
                cases: &cases,
                methods: &methods,
            },
            reads: |scaling: &Scaling| {
                let exponents = (scaling.exponents.iter())
                    .map(|(label, e)| format!("{label} {e:.2}"))
                    .collect::<Vec<_>>()
                    .join(", ");
                format!(
                    "- [Wall time per step against the number of blocks](studies/cost-chain-timing.png) \
                     (N = 10 to 1000 over 4 s; Dormand–Prince and \
                     regularised BDF at tolerance 1e-6, time-stepping at h = 1e-3; studies/cost-chain.csv \
                     has steps and work, studies/cost-chain-timing.csv the wall times). Fitted slopes of \
                     counted work per step against N: {exponents}.\n"
                )
            },
        },
    ];
    let lines = conduct_all(&table, t)?;
    Ok(format!(
        "\n## Many blocks: event-driving, regularisation and time-stepping\n\n\
         The chain of `systems.md` with stiction on every block (`static`), every block \
         started at x0 = -0.7 m (driver spring at 7 N, break-away at 7.5 N), one system \
         integrated three ways (docs/timestepping.md, docs/systems.md):\n\n{lines}"
    ))
}

fn report(reproduced: &[Reproduced], header: &str, provenance: &Provenance) -> String {
    let mut s = String::from("# friction-lab: reproduction of the paper\n\n");
    s += &format!("Computed by {}.\n\n", provenance.markdown());
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
    let threads = ranges::threads(args.threads)?;
    // Friction parameters only: every rig of the report runs at its own defaults.
    let rig_or_chain = |name: &str| {
        scenarios::ScenarioParams::spec(name).is_some()
            || friction_systems::chain::CHAIN_PARAMETERS
                .iter()
                .any(|p| p.0 == name)
    };
    let params = args.params.resolve_with(&[], |name, _| {
        if !rig_or_chain(name) {
            return Ok(false);
        }
        Err(AppError::Usage(format!(
            "parameter `{name}` is not a friction parameter: reproduce runs every rig and \
             the chain at their own (the paper's) settings, and takes only the friction \
             parameters (`friction-lab models` lists them); set `{name}` with simulate, \
             the studies or sweep"
        )))
    })?;
    // The chain studies time-step the chain: parameters at which its law cannot be
    // time-stepped are refused before anything runs, not after the figures and Table 2.
    for contact in &chain_case(1, &params, 1.0)?.system.contacts {
        let model = contact.model.as_ref();
        if let Some(outside) = friction_systems::moreau_jean::sliding_outside_stick(model) {
            return Err(AppError::Usage(format!(
                "the parameters given cannot be used by reproduce: its chain studies time-step \
                 the chain (Moreau-Jean), and with them {}; reproduce takes friction \
                 parameters at which every part of it runs",
                outside.describe(model.name())
            )));
        }
    }
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
    let rows = experiment(&params, &Scenario::PaperBlock.defaults()).map_err(AppError::from)?;
    let experiment_md = add_experiment(&mut files, &args.out, &rows)?;
    files.add(
        args.out.join("paper-experiment.md"),
        format!("# The paper's experiment\n\n{experiment_md}").into_bytes(),
    );
    let laws = scenarios::phenomena::catalog_laws();
    let table2 = Table2Study {
        laws: &laws,
        protocol: Protocol::default(),
        parameters: None,
    };
    let mut target = Target {
        files: &mut files,
        dir: &args.out,
        threads,
        failure: None,
    };
    let table = conduct(&table2, &mut target, "table2")?;
    let disagreements = table
        .iter()
        .flat_map(|(_, r)| r.iter())
        .filter(|(_, c)| c.disagrees())
        .count();
    let provenance = Provenance::now(with_threads(threads, rayon::current_num_threads)?);
    let mut report_md = report(&reproduced, &header, &provenance);
    report_md += &format!(
        "\n{experiment_md}\n## Table 2, decided by simulation\n\n\
        [table2.md](table2.md) (and table2.json) decides every cell of the paper's Table 2 by a \
        simulated protocol, for the six models and the reference models: {disagreements} of the \
        paper's 42 claims disagree with the simulations. The protocols are described in \
        docs/phenomena.md.\n"
    );
    let mut failure = None;
    report_md += &section("Solver studies", &mut failure, || {
        add_studies(&mut files, &args.out, &params, threads)
    })?;
    report_md += &section("Stick-slip on the belt", &mut failure, || {
        let dir = args.out.join("stick-slip");
        let mut t = Target {
            files: &mut files,
            dir: &dir,
            threads,
            failure: None,
        };
        crate::commands::stick_slip::add_stick_slip(&mut t, &params)
    })?;
    if interrupt::requested() {
        let title = report_md.find("\n\n").map_or(0, |i| i + 2);
        let banner = crate::artifacts::stopped_banner(&format!(
            "their studies' files mark them as failed, the sections after it say \
             \"Not run\", and {} of Table 2's cells are undecided",
            undecided(&table).len()
        ));
        report_md.insert_str(title, &banner);
    }
    files.add(args.out.join("report.md"), report_md.into_bytes());
    let written = with_threads(threads, || files.write(&args.out))??;
    println!(
        "{} in {:.2} s",
        written.line(),
        start.elapsed().as_secs_f64()
    );
    if let Some(note) = written.stop_note() {
        eprintln!("note: {note}");
    }
    let failed: Vec<&ExperimentFailure> = rows.iter().filter_map(|r| r.as_ref().err()).collect();
    if let Some(first) = failed.first() {
        let models: Vec<String> = failed.iter().map(|f| f.model.to_string()).collect();
        return Err(AppError::StudyRun(format!(
            "the paper's experiment failed for {} (paper-experiment.md and report.md keep the \
             other models, and the velocity each failed run reached); {}: {}",
            models.join(", "),
            first.model,
            first.why
        )));
    }
    if let Some(failure) = failure {
        return Err(failure);
    }
    check_decided(&table)
}

/// A section of the report that runs the studies: its text, or, when it fails while running
/// (a run it needs failed, or a signal stopped it: exit 1 or 130), a paragraph under `title`
/// that says so and why, the failure kept in `failure` (the first) for the command's exit.
/// The files of the studies that finished are written either way. A section is not started
/// once a signal has stopped the command. Bad input (exit 2) still ends the command before
/// anything is written.
fn section(
    title: &str,
    failure: &mut Option<AppError>,
    result: impl FnOnce() -> Result<String, AppError>,
) -> Result<String, AppError> {
    if interrupt::requested() {
        return Ok(format!(
            "\n## {title}\n\nNot run: the command was stopped by a signal before it.\n"
        ));
    }
    match result() {
        Ok(md) => Ok(md),
        Err(e) if e.exit_code() == 2 => Err(e),
        Err(e) => {
            let md = format!(
                "\n## {title}\n\nNot completed: {e}. The files of the parts that finished \
                 are written.\n"
            );
            failure.get_or_insert(e);
            Ok(md)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{section, AppError};

    #[test]
    fn a_section_that_fails_while_running_is_named_and_its_failure_kept() {
        let mut failure = None;
        let ok = section("Studies", &mut failure, || {
            Ok("\n## Studies\n\ntext\n".into())
        });
        assert_eq!(ok.unwrap(), "\n## Studies\n\ntext\n");
        assert!(failure.is_none());
        let failed = section("Studies", &mut failure, || {
            Err(AppError::StudyRun("the reference failed".into()))
        });
        assert_eq!(
            failed.unwrap(),
            "\n## Studies\n\nNot completed: the reference failed. The files of the parts that \
             finished are written.\n"
        );
        // The first failure is the one the command exits with.
        let _ = section("Map", &mut failure, || {
            Err(AppError::StudyRun("a second".into()))
        });
        assert_eq!(failure.unwrap().to_string(), "the reference failed");
        // Bad input still ends the command, writing nothing.
        let mut none = None;
        let usage = section("Map", &mut none, || Err(AppError::Usage("bad".into())));
        assert_eq!(usage.unwrap_err().exit_code(), 2);
        assert!(none.is_none());
    }
}
