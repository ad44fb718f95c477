//! A report as a table of studies: each [`Entry`] is a study, the stem of its files and the
//! Markdown its result reads as; [`conduct_all`] conducts a table of them in order into one
//! folder and joins their lines. `reproduce`'s solver studies are such tables, and a user's
//! own study joins one with a line of its own (`examples/own_study.rs`).

use super::{conduct, Output, Study};
use crate::error::AppError;

/// A study of a report, whatever its result's type: conducted into a target, it gives its
/// lines of the report.
pub trait ReportEntry {
    /// Conducts the study into `target` and returns its Markdown. A failure its files record
    /// (a level of an independence study that failed, a study none of whose runs measured
    /// anything) is returned as the error once they are added: a report does not read a
    /// result that is not one.
    fn reproduce(&self, target: &mut Output) -> Result<String, AppError>;
}

/// A study, the stem of its files (`converge-paper-block-CVS` for
/// `converge-paper-block-CVS.csv`, …) and how its result reads in the report.
pub struct Entry<S: Study, F: Fn(&S::Result) -> String> {
    /// The stem of the study's files.
    pub stem: &'static str,
    /// The study.
    pub study: S,
    /// Its result as the report says it (a Markdown bullet, usually linking the figure).
    pub reads: F,
}

impl<S: Study, F: Fn(&S::Result) -> String> ReportEntry for Entry<S, F> {
    fn reproduce(&self, target: &mut Output) -> Result<String, AppError> {
        let result = conduct(&self.study, target, self.stem)?;
        match target.failure.take() {
            Some(failure) => Err(failure),
            None => Ok((self.reads)(&result)),
        }
    }
}

/// Conducts every entry of `table` in order into `target`, and joins their Markdown; the
/// first failure ends it (the files of the studies before it, and of the failed one, are
/// added).
pub fn conduct_all(table: &[&dyn ReportEntry], target: &mut Output) -> Result<String, AppError> {
    table.iter().map(|entry| entry.reproduce(target)).collect()
}
