//! The branches of equilibria and cycles of a rig or a system over one parameter
//! ([`scenarios::orbit::follow`]): every point with its stability, the special points where it
//! changes, and the bifurcation diagram.

use super::{Study, StudyFiles};
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Dash, Marker, Plot, Series, BLUE, RED};
use friction_models::params::show;
use scenarios::orbit::{follow, BranchRow, Branches, OrbitSettings};
use scenarios::studies::StudyCase;

/// The branches of `case` over `parameter` ∈ `range`.
pub struct BranchesStudy<'a> {
    /// The problem: a rig with a body, the chain.
    pub case: &'a dyn StudyCase,
    /// The parameter's name.
    pub parameter: &'a str,
    /// Its range, from the start of the branches to their end.
    pub range: (f64, f64),
    /// Values at which each branch that passes them adds a row computed exactly there.
    pub at: &'a [f64],
    /// How the cycle at the start is found.
    pub settings: OrbitSettings,
}

/// The lines a front end prints of the branches: what was followed, and each special point.
pub fn branches_lines(b: &Branches) -> Vec<String> {
    let mut lines = b.notes.clone();
    for (on, s) in &b.special {
        lines.push(format!(
            "{} of the {on} branch at {} = {}",
            kind_name(s.kind),
            b.parameter,
            show(s.p)
        ));
    }
    lines
}

/// A special point's kind as the files name it (`fold`, `hopf`, `period-doubling`, …).
fn kind_name(kind: periodic::SpecialKind) -> String {
    serde_json::to_value(kind)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

/// A spectrum as text: `re` or `re±imi`, space-separated.
fn spectrum_text(spectrum: &[(f64, f64)]) -> String {
    (spectrum.iter())
        .map(|&(re, im)| match im {
            0.0 => show(re + 0.0),
            im if im > 0.0 => format!("{}+{}i", show(re + 0.0), show(im)),
            im => format!("{}-{}i", show(re + 0.0), show(-im)),
        })
        .collect::<Vec<_>>()
        .join(" ")
}

impl Study for BranchesStudy<'_> {
    type Result = Branches;

    fn name(&self) -> &'static str {
        "continue"
    }

    fn runs(&self) -> usize {
        1
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<Branches, AppError> {
        let branches = follow(
            self.case,
            self.parameter,
            (self.range, self.at),
            &self.settings,
        )?;
        progress();
        Ok(branches)
    }

    /// `branch.csv` (a row a computed point: `kind`, the parameter under its name, `at`, `period`,
    /// `amplitude`, `spectrum`, `stable`, `segments`), `special_points.csv` (`kind`, `branch`,
    /// the parameter), `{stem}.json` and the diagram `{stem}` (amplitude against the
    /// parameter, stable solid, unstable dashed, special points marked).
    fn write(&self, b: &Branches, out: &mut StudyFiles) -> Result<(), AppError> {
        let p = b.parameter.as_str();
        let mut rows = Table::new(&[
            "kind",
            p,
            "at",
            "period",
            "amplitude",
            "spectrum",
            "stable",
            "segments",
        ]);
        for r in &b.rows {
            rows.rows.push(vec![
                Cell::Text(r.kind.into()),
                Cell::Num(r.p),
                Cell::Text(r.at.to_string()),
                r.period.map_or(Cell::empty(), Cell::Num),
                Cell::num(r.amplitude),
                Cell::Text(spectrum_text(&r.spectrum)),
                Cell::Text(r.stable.to_string()),
                Cell::Text(r.segments.clone()),
            ]);
        }
        out.files.add_table(out.dir.join("branch.csv"), rows)?;
        let mut special = Table::new(&["kind", "branch", p]);
        for (on, s) in &b.special {
            special.rows.push(vec![
                Cell::Text(kind_name(s.kind)),
                Cell::Text((*on).into()),
                Cell::Num(s.p),
            ]);
        }
        out.files
            .add_table(out.dir.join("special_points.csv"), special)?;
        out.add_json(&super::study_file(self.case, &[], b))?;
        out.files.add_plot(&out.path(""), &diagram(b, self.case))
    }
}

/// Amplitude against the parameter: each branch in runs of one stability, stable solid and
/// unstable dashed (equilibria blue, cycles red), the special points as black squares.
fn diagram(b: &Branches, case: &dyn StudyCase) -> Plot {
    let mut series = Vec::new();
    for (kind, color) in [("equilibrium", BLUE), ("cycle", RED)] {
        let rows: Vec<&BranchRow> = (b.rows.iter())
            .filter(|r| r.kind == kind && !r.at)
            .collect();
        let mut start = 0;
        for k in 1..=rows.len() {
            if k == rows.len() || rows[k].stable != rows[start].stable {
                // Each run shares its last point with the next, so the line is unbroken.
                let end = (k + 1).min(rows.len());
                let label = match (start, rows[start].stable) {
                    _ if series.iter().any(|s: &Series| {
                        s.label.as_deref() == Some(&legend(kind, rows[start].stable))
                    }) =>
                    {
                        None
                    }
                    _ => Some(legend(kind, rows[start].stable)),
                };
                series.push(Series {
                    label,
                    points: rows[start..end]
                        .iter()
                        .map(|r| (r.p, r.amplitude))
                        .collect(),
                    color,
                    width: 2,
                    marker: Marker::None,
                    dash: if rows[start].stable {
                        Dash::Solid
                    } else {
                        Dash::Dashed
                    },
                });
                start = k;
            }
        }
    }
    let marks: Vec<(f64, f64)> = (b.special.iter())
        .map(|(on, s)| {
            let amplitude = (b.rows.iter())
                .filter(|r| r.kind == *on)
                .min_by(|a, c| (a.p - s.p).abs().total_cmp(&(c.p - s.p).abs()))
                .map_or(0.0, |r| r.amplitude);
            (s.p, amplitude)
        })
        .collect();
    if !marks.is_empty() {
        series.push(Series {
            label: Some("special points".into()),
            points: marks,
            color: plotters::style::BLACK,
            width: 0,
            marker: Marker::FILLED[1],
            dash: Dash::Solid,
        });
    }
    Plot {
        title: format!("Branches of {} over {}", case.describe(), b.parameter),
        x_label: b.parameter.clone(),
        y_label: "amplitude of x (m)".into(),
        series,
        legend: Corner::UpperRight,
        log: false,
    }
}

/// The legend entry of a branch's run.
fn legend(kind: &str, stable: bool) -> String {
    let kind = if kind == "cycle" {
        "cycles"
    } else {
        "equilibria"
    };
    format!("{} {kind}", if stable { "stable" } else { "unstable" })
}
