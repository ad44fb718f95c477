//! The comparison of formulations against the true nonsmooth solution
//! ([`scenarios::studies::compare`]): its runs, its cost-at-target table, the regularisation's
//! model error against ε, and the figures of error against work and against wall time.

use super::draw::per_solver_series;
use super::tables::{resolution_cells, runs_table, timing_table};
use super::{positive_list, target_list, Study, StudyFiles};
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, BLUE};
use plotters::style::{RGBColor, BLACK};

/// The colour of the targets' lines and the fit: behind the schemes' own.
const GREY: RGBColor = RGBColor(150, 150, 150);
use friction_models::params::show;
use scenarios::studies::{
    self, ComparePart, CompareSpec, ComparedRun, Comparison, ErrorMeasure, StudyCase, StudyRun,
};

/// Every scheme of `spec` on `case`, against the true solution.
pub struct CompareStudy<'a> {
    /// The problem.
    pub case: &'a dyn StudyCase,
    /// What is compared.
    pub spec: &'a CompareSpec,
    /// The parts of the comparison made elsewhere, to be merged; `None`: every run is made
    /// here ([`studies::compare`]).
    pub parts: Option<Vec<ComparePart>>,
}

/// The lines a front end prints of a comparison: the true solution's accuracy, the model
/// error's conclusion, and at each target the cheapest scheme, by what factor, and which kind
/// wins; then the crossovers.
pub fn compare_lines(c: &Comparison) -> Vec<String> {
    let mut lines = vec![format!(
        "true solution: {} (cross-checked by {}: {}); errors below {} are not resolved",
        match &c.reference {
            studies::Reference::ClosedForm(name) => name.clone(),
            studies::Reference::Run {
                solver,
                cross_check,
                ..
            } => format!(
                "{solver} with events at tol 1e-13, {} apart from {}",
                fmt(cross_check.1),
                cross_check.0
            ),
        },
        c.cross_check.scheme,
        c.cross_check.difference.map_or_else(
            || format!("failed: {}", c.cross_check.failure.as_deref().unwrap_or("")),
            |d| format!("{} apart", fmt(d))
        ),
        fmt(c.resolvable)
    )];
    if let Some(r) = &c.regularisation {
        lines.push(format!("regularisation: {}", r.verdict));
    }
    for t in &c.costs {
        let factor = (t.implicit_over_explicit).map_or(String::new(), |f| {
            format!(", implicit/explicit work {}", fmt(f))
        });
        let kind = match t.kind {
            None => "neither kind met it".to_string(),
            Some(studies::Winner::Tie) => format!("explicit and implicit tie{factor}"),
            Some(k) => format!("{} cheaper{factor}", k.name()),
        };
        let cheapest = match (&t.cheapest, &t.runner_up, t.tie) {
            (None, _, _) => "no scheme met it".to_string(),
            (Some(a), Some(b), true) => format!("{a} and {b} tie"),
            (Some(a), Some(b), false) => format!(
                "{a} cheapest, {} times less work than {b}",
                fmt(t.factor.unwrap_or(f64::NAN))
            ),
            (Some(a), None, _) => format!("only {a} met it"),
        };
        let unresolved = match t.resolved {
            true => "",
            false => " (below what the true solution resolves: not a claim)",
        };
        lines.push(format!(
            "at {}{unresolved}: {cheapest}; {kind}",
            show(t.target)
        ));
    }
    for x in &c.crossovers {
        lines.push(format!(
            "crossover: {} → {} between {} and {}{}",
            x.from,
            x.to,
            show(x.between[0]),
            show(x.between[1]),
            x.at.map_or(String::new(), |a| format!(", at about {}", fmt(a)))
        ));
    }
    lines
}

/// A ratio or a target to three significant digits.
fn fmt(x: f64) -> String {
    show(format!("{x:.2e}").parse().unwrap_or(x))
}

impl Study for CompareStudy<'_> {
    type Result = Comparison;

    fn name(&self) -> &'static str {
        "compare"
    }

    fn check(&self) -> Result<(), AppError> {
        let r = &self.spec.resolutions;
        target_list("targets", &self.spec.targets)?;
        if !self.spec.schemes.regularised.is_empty() {
            positive_list("epsilons", &self.spec.schemes.epsilons)?;
        }
        crate::ranges::RTOL.list("tol_list", &r.tolerances)?;
        crate::ranges::DT.list("dt_list", &r.steps)?;
        crate::ranges::DT.list("ts_dt_list", &r.timestepping_steps)
    }

    /// The planned runs (a scheme stops early or is extended, so the bar is a guide).
    fn runs(&self) -> usize {
        let (s, r) = (&self.spec.schemes, &self.spec.resolutions);
        let adaptive = s.event.len() + s.naive.len() + s.regularised.len() * s.epsilons.len();
        let stepped = s.theta.map_or(0, |_| r.timestepping_steps.len());
        (adaptive * r.tolerances.len() + stepped) * (self.spec.repeats + 1)
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<Comparison, AppError> {
        Ok(match &self.parts {
            None => studies::compare(self.case, self.spec, progress)?,
            Some(parts) => {
                let truth = studies::TrueSolution::of(self.case)?;
                truth.merge(self.spec, parts.clone())?
            }
        })
    }

    fn failure(&self, c: &Comparison) -> Option<AppError> {
        let runs: Vec<studies::StudyRun> = c.runs.iter().map(|r| r.run.clone()).collect();
        super::nothing_measured("compare", &runs)
    }

    /// `{stem}.csv` (a row per run, with its scheme, ε and discretisation error),
    /// `{stem}-cost.csv` (each scheme at each target), `{stem}-cost-timing.csv` (the wall
    /// time at each target met), `{stem}-epsilon.csv` (the model error against ε),
    /// `{stem}-timing.csv`, `{stem}.json`, and the figures `{stem}` (error against
    /// work: every scheme's runs judged ok, a regularised scheme's at the widths its costs
    /// were met at), `{stem}-timing` (against wall time), `{stem}-regularized` (every
    /// regularised run judged ok) and `{stem}-epsilon` (the model error against ε).
    fn write(&self, c: &Comparison, out: &mut StudyFiles) -> Result<(), AppError> {
        let runs: Vec<studies::StudyRun> = c.runs.iter().map(|r| r.run.clone()).collect();
        let mut table = runs_table(&runs);
        table
            .header
            .splice(1..1, ["scheme".to_string(), "epsilon".to_string()]);
        table.header.push("discretisation_error".into());
        for (row, r) in table.rows.iter_mut().zip(&c.runs) {
            row.splice(
                1..1,
                [
                    Cell::Text(r.scheme.clone()),
                    r.epsilon.map_or(Cell::empty(), Cell::Num),
                ],
            );
            row.push(r.discretisation_error.map_or(Cell::empty(), Cell::num));
        }
        out.files.add_table(out.path(".csv"), table)?;
        out.files.add_table(out.path("-cost.csv"), cost_table(c))?;
        out.files
            .add_table(out.path("-cost-timing.csv"), cost_timing_table(c))?;
        let timing = timing_table(
            &["solver", "h", "tol"],
            runs.iter().map(|r| {
                let [h, tol] = resolution_cells(Some(r.step), Some(r.resolution));
                (vec![Cell::Text(r.solver.clone()), h, tol], r.wall_time)
            }),
        );
        out.files.add_table(out.path("-timing.csv"), timing)?;
        if let Some(reg) = &c.regularisation {
            let mut t = Table::new(&["epsilon_relative", "epsilon", "model_error", "failure"]);
            for w in &reg.widths {
                t.rows.push(vec![
                    Cell::Num(w.relative),
                    Cell::Num(w.epsilon),
                    Cell::num(w.error),
                    Cell::Text(w.failure.clone().unwrap_or_default()),
                ]);
            }
            out.files.add_table(out.path("-epsilon.csv"), t)?;
            out.files
                .add_plot(&out.path("-epsilon"), &epsilon_plot(c, self.case))?;
        }
        out.add_json(&super::study_file(self.case, &[], c))?;
        for (suffix, plot) in figures(c, self.case) {
            out.files.add_plot(&out.path(suffix), &plot)?;
        }
        Ok(())
    }
}

/// A comparison's figures, by the suffix of their stem: `""` error against work (every
/// scheme's runs judged ok, a regularised scheme's at the widths its costs were met at),
/// `-timing` against the median wall time, `-regularized` every regularised run judged ok
/// (none without one). The targets are grey lines; a crossover is a black line at the target
/// where it lies, named in the legend.
pub fn figures(c: &Comparison, case: &dyn StudyCase) -> Vec<(&'static str, Plot)> {
    let chosen: Vec<(&str, f64)> = (c.costs.iter())
        .flat_map(|t| &t.costs)
        .filter_map(|s| Some((s.scheme.as_str(), s.epsilon?)))
        .collect();
    let main = |r: &ComparedRun| {
        r.run.verdict.is_ok()
            && (r.epsilon).is_none_or(|e| chosen.contains(&(r.scheme.as_str(), e)))
    };
    let regularised = |r: &ComparedRun| r.run.verdict.is_ok() && r.epsilon.is_some();
    let drawn = |keep: &dyn Fn(&ComparedRun) -> bool| -> Vec<StudyRun> {
        (c.runs.iter())
            .filter(|r| keep(r))
            .map(|r| r.run.clone())
            .collect()
    };
    let (main, regularised) = (drawn(&main), drawn(&regularised));
    let work: fn(&StudyRun) -> f64 = |r| r.work as f64;
    let work_label = super::draw::WORK_LABEL;
    [
        ("", &main, "Error against work", work_label, work),
        (
            "-timing",
            &main,
            "Error against wall time",
            "wall time, median (s)",
            |r: &StudyRun| r.wall_time.median,
        ),
        (
            "-regularized",
            &regularised,
            "Regularised schemes, every ε, error against work",
            work_label,
            work,
        ),
    ]
    .into_iter()
    .filter(|(_, runs, ..)| !runs.is_empty())
    .map(|(suffix, runs, what, x_label, x)| {
        let v: Vec<f64> = runs.iter().map(x).filter(|x| *x > 0.0).collect();
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(0.0, f64::max);
        let line = |y: f64| vec![(lo, y), (hi, y)];
        let mut series: Vec<Series> = (c.costs.iter())
            .map(|t| Series {
                label: None,
                points: line(t.target),
                color: GREY,
                width: 1,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            })
            .collect();
        series.extend(c.crossovers.iter().filter_map(|x| {
            let at = x.at?;
            Some(Series {
                label: Some(format!("crossover {} → {} at {at:.1e}", x.from, x.to)),
                points: line(at),
                color: BLACK,
                width: 2,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            })
        }));
        series.extend(per_solver_series(
            runs,
            |_| true,
            x,
            |r| r.errors.grid_relative,
        ));
        let plot = Plot {
            title: format!(
                "{what}: {}, every scheme against the true nonsmooth solution",
                case.describe()
            ),
            x_label: x_label.into(),
            y_label: ErrorMeasure::GridRelative.label().into(),
            series,
            legend: Corner::UpperRight,
            log: true,
        };
        (suffix, plot)
    })
    .collect()
}

/// One row per target and scheme: its cost there, or why it has none.
fn cost_table(c: &Comparison) -> Table {
    let mut t = Table::new(&[
        "target",
        "scheme",
        "kind",
        "reached",
        "epsilon",
        "h",
        "tol",
        "error",
        "work_estimate",
        "work_low",
        "work_high",
        "cheapest",
        "reason",
    ]);
    for target in &c.costs {
        for s in &target.costs {
            let r = s.reached.as_ref();
            let [h, tol] = resolution_cells(r.map(|r| r.step), r.map(|r| r.resolution));
            let cheapest = target.cheapest.as_deref() == Some(&s.scheme);
            t.rows.push(vec![
                Cell::Num(target.target),
                Cell::Text(s.scheme.clone()),
                Cell::Text(format!("{:?}", s.kind).to_lowercase()),
                Cell::Text(r.is_some().to_string()),
                s.epsilon.map_or(Cell::empty(), Cell::Num),
                h,
                tol,
                r.map_or(Cell::empty(), |r| Cell::num(r.error)),
                r.map_or(Cell::empty(), |r| Cell::Num(r.work_estimate)),
                r.and_then(|r| r.work_bracket[0])
                    .map_or(Cell::empty(), Cell::Num),
                r.and_then(|r| r.work_bracket[1])
                    .map_or(Cell::empty(), Cell::Num),
                Cell::Text(match (cheapest, target.tie) {
                    (true, true) => "tie".into(),
                    (true, false) => "yes".into(),
                    _ => String::new(),
                }),
                Cell::Text(s.reason.clone().unwrap_or_default()),
            ]);
        }
    }
    t
}

/// One row per target and scheme that met it: the wall time there (not deterministic, apart
/// from the cost table).
fn cost_timing_table(c: &Comparison) -> Table {
    let mut t = Table::new(&[
        "target",
        "scheme",
        "wall_time_s",
        "wall_time_q1_s",
        "wall_time_q3_s",
    ]);
    for target in &c.costs {
        for s in &target.costs {
            if let (Some(wall), Some([q1, q3])) = (s.wall_time, s.wall_spread) {
                t.rows.push(vec![
                    Cell::Num(target.target),
                    Cell::Text(s.scheme.clone()),
                    Cell::Num(wall),
                    Cell::Num(q1),
                    Cell::Num(q3),
                ]);
            }
        }
    }
    t
}

/// The model error against ε (log–log), with the fitted line where the error falls.
fn epsilon_plot(c: &Comparison, case: &dyn StudyCase) -> Plot {
    let reg = c.regularisation.as_ref().expect("a regularised comparison");
    let points: Vec<(f64, f64)> = (reg.widths.iter())
        .filter(|w| w.error.is_finite() && w.error > 0.0)
        .map(|w| (w.epsilon, w.error))
        .collect();
    let mut series = vec![Series {
        label: Some("model error (tight regularised solution against the true one)".into()),
        points: points.clone(),
        color: BLUE,
        width: 2,
        marker: Marker::Dot,
        dash: crate::plot::Dash::Solid,
    }];
    if let (Some(f), true) = (&reg.fit, reg.falls) {
        series.push(Series {
            label: Some(format!(
                "fit C·ε^p, p = {:.2} ({:.2} to {:.2})",
                f.order, f.interval[0], f.interval[1]
            )),
            points: points
                .iter()
                .map(|&(e, _)| (e, f.constant * e.powf(f.order)))
                .collect(),
            color: GREY,
            width: 1,
            marker: Marker::None,
            dash: crate::plot::Dash::Solid,
        });
    }
    Plot {
        title: format!(
            "Regularisation's model error against ε: {}",
            case.describe()
        ),
        x_label: "ε (m/s)".into(),
        y_label: ErrorMeasure::GridRelative.label().into(),
        series,
        legend: Corner::UpperLeft,
        log: true,
    }
}
