//! `reproduce` as a table of studies: a [`Report`] is a title, a preface and a list of
//! [`Part`]s, each a section of `report.md` whose studies write their files into one folder.
//! [`Paper::parts`] is the paper's table (Figures 2–7, the experiment, Table 2, the solver
//! studies, the comparison of schemes, the chain, the belt's stick–slip map, the closed loop,
//! the limit cycles as orbits); a user's own study joins a report as one more
//! part ([`Section`], `examples/own_study.rs`).

mod chain;
mod closed_loop;
mod comparison;
mod experiment;
mod figures;
mod orbits;
mod request;
mod solver_studies;
mod stick_slip;
mod table2;

pub use experiment::ExperimentStudy;
pub use figures::PaperFiguresStudy;
pub use request::ReproduceRequest;

use crate::artifacts::{stopped_banner, Artifacts};
use crate::error::AppError;
use crate::made::Made;
use crate::provenance::Provenance;
use crate::study::{conduct_all, Output, ReportEntry};
use crate::threads::with_threads;
use friction_models::FrictionParams;
use integrators::interrupt;
use scenarios::figures::{LEVEL_OFF_FRACTION, NUMERIC_TOLERANCE};
use std::path::Path;

/// A section of a report: its heading, the folder its files go into, and the studies that
/// make its text.
pub trait Part {
    /// The section's heading (`## {heading}` in `report.md`).
    fn heading(&self) -> String;

    /// The folder of its files, relative to the report's (`""` for the report's own).
    fn folder(&self) -> &'static str {
        ""
    }

    /// Checks what it will run before any part of the report runs: bad input is
    /// [`AppError::Usage`], exit code 2, with nothing written.
    fn check(&self) -> Result<(), AppError> {
        Ok(())
    }

    /// Conducts its studies into `target` and returns the section's text under its heading.
    fn conduct(&self, target: &mut Output) -> Result<String, AppError>;
}

/// A part made of studies of one's own: a heading, a paragraph, and entries conducted in order
/// into `folder` ([`conduct_all`]).
pub struct Section<'a> {
    /// The heading.
    pub heading: String,
    /// The folder of its files, relative to the report's.
    pub folder: &'static str,
    /// The paragraph before the entries' lines (ending in a blank line).
    pub intro: String,
    /// The studies, each with the stem of its files and its line.
    pub entries: Vec<&'a dyn ReportEntry>,
}

impl Part for Section<'_> {
    fn heading(&self) -> String {
        self.heading.clone()
    }

    fn folder(&self) -> &'static str {
        self.folder
    }

    fn conduct(&self, target: &mut Output) -> Result<String, AppError> {
        Ok(format!(
            "{}{}",
            self.intro,
            conduct_all(&self.entries, target)?
        ))
    }
}

/// A report: `report.md`, titled `title`, opened by the provenance and `preface`, then one
/// section a part, each part's files in its folder.
pub struct Report<'a> {
    /// The first line, a Markdown title (`# …`).
    pub title: String,
    /// What the report says before its sections: paragraphs ending in a newline, or nothing.
    pub preface: String,
    /// Its parts, in order.
    pub parts: Vec<&'a dyn Part>,
}

impl Report<'_> {
    /// Conducts every part into the folder `dir` on `threads` worker threads (all cores when
    /// `None`) and returns the files, `report.md` among them, unwritten. Every part is checked
    /// before any runs. A part that fails while running (a run it needs failed, or a signal
    /// stopped it) is said so in its section, the files of the studies that finished are kept,
    /// and the next part runs; the first such failure is [`Made::failure`]. Once a signal has
    /// stopped the command, the parts not started say "Not run".
    pub fn conduct(&self, dir: &Path, threads: Option<usize>) -> Result<Made, AppError> {
        for part in &self.parts {
            part.check()?;
        }
        let mut files = Artifacts::default();
        let mut failure = None;
        let mut sections = String::new();
        for part in &self.parts {
            let folder = dir.join(part.folder());
            let mut target = Output {
                files: &mut files,
                dir: &folder,
                threads,
                failure: None,
            };
            sections += &section(&part.heading(), &mut failure, || part.conduct(&mut target))?;
        }
        let provenance = Provenance::now(with_threads(threads, rayon::current_num_threads)?);
        let mut report = format!("{}\n\n", self.title);
        if interrupt::requested() {
            report += &stopped_banner(
                "the files of the studies it cut short mark them as failed, its section says \
                 \"Not completed\", and the sections after it say \"Not run\"",
            );
        }
        report += &format!("Computed by {}.\n", provenance.markdown());
        if !self.preface.is_empty() {
            report += &format!("\n{}", self.preface);
        }
        report += &sections;
        files.add(dir.join("report.md"), report.into_bytes());
        Ok(Made {
            files,
            notes: Vec::new(),
            warnings: Vec::new(),
            failure,
            run: None,
        })
    }
}

/// One section of the report: `\n## {heading}\n\n` and its text; or, when the part fails while
/// running (a run it needs failed, or a signal stopped it: exit 1 or 130), a paragraph that
/// says so and why, the failure kept in `failure` (the first) for the command's exit. A
/// section is not started once a signal has stopped the command. Bad input (exit 2) still
/// ends the command before anything is written.
fn section(
    heading: &str,
    failure: &mut Option<AppError>,
    result: impl FnOnce() -> Result<String, AppError>,
) -> Result<String, AppError> {
    if interrupt::requested() {
        return Ok(format!(
            "\n## {heading}\n\nNot run: the command was stopped by a signal before it.\n"
        ));
    }
    match result() {
        Ok(text) => Ok(format!("\n## {heading}\n\n{text}")),
        Err(e) if e.kind() == crate::error::ErrorKind::BadInput => Err(e),
        Err(e) => {
            let text = format!(
                "\n## {heading}\n\nNot completed: {e}. The files of the parts that finished \
                 are written.\n"
            );
            failure.get_or_insert(e);
            Ok(text)
        }
    }
}

/// The paper reproduced at `friction` (Table 1's parameters unless changed), described as
/// `parameters` (e.g. "Parameter set `paper`").
pub struct Paper {
    /// The friction parameters of every part.
    pub friction: FrictionParams,
    /// Where they come from, as the report says it.
    pub parameters: String,
}

impl Paper {
    /// What the report and `reproduction.md` say of how the figures were made and judged.
    pub fn header(&self) -> String {
        format!(
            "Written by `friction-lab reproduce` (friction-lab {}). {}. Curves: |v| <= 1 m/s \
             for Figures 2-4; the prescribed motion X(t) = t^3/3 + t^2/2, t in [0, 2] s, and \
             its mirror image for Figures 5-7; {} samples per branch.\n\n\
             A numeric claim agrees when within {:.0} % of the paper's value (the paper reads \
             its values off its plots). A curve levels off when its slope over the last 10 % \
             of its range, times the range, is below {:.0} % of its end value.\n",
            env!("CARGO_PKG_VERSION"),
            self.parameters,
            figures::POINTS,
            100.0 * NUMERIC_TOLERANCE,
            100.0 * LEVEL_OFF_FRACTION,
        )
    }

    /// The paper's parts, in the report's order: Figures 2–7, the experiment, Table 2, the
    /// solver studies, the comparison of schemes against the true solution, the chain's studies, the belt's stick–slip map and the closed loop.
    pub fn parts(&self) -> Vec<Box<dyn Part>> {
        let friction = self.friction;
        vec![
            Box::new(figures::Figures {
                friction,
                header: self.header(),
            }),
            Box::new(experiment::Experiment { friction }),
            Box::new(table2::Table2),
            Box::new(solver_studies::SolverStudies { friction }),
            Box::new(comparison::Comparisons { friction }),
            Box::new(chain::ChainStudies { friction }),
            Box::new(stick_slip::StickSlip { friction }),
            Box::new(closed_loop::ClosedLoopPart),
            Box::new(orbits::Orbits { friction }),
        ]
    }

    /// The paper's report over `parts` (the paper's [`Paper::parts`], and any of one's own).
    pub fn report<'a>(&self, parts: Vec<&'a dyn Part>) -> Report<'a> {
        Report {
            title: "# friction-lab: reproduction of the paper".into(),
            preface: self.header(),
            parts,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{section, AppError};

    #[test]
    fn a_section_that_fails_while_running_is_named_and_its_failure_kept() {
        let mut failure = None;
        let ok = section("Studies", &mut failure, || Ok("text\n".into()));
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
        assert_eq!(usage.unwrap_err().kind(), crate::error::ErrorKind::BadInput);
        assert!(none.is_none());
    }
}
