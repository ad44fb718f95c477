//! How a command's files are written, as every front end writes them: the figures' size and
//! resolution, whether a folder holding files friction-lab did not write is replaced, and the
//! command (or the Python call) their provenance names.

use crate::artifacts::{Artifacts, Written};
use crate::error::AppError;
use crate::plot::Format;
use crate::provenance::Provenance;
use std::path::Path;

/// How a command's files are written.
#[derive(Clone, Debug)]
pub struct Delivery {
    /// The figures' size and resolution.
    pub format: Format,
    /// `replace`: the output folder is replaced even where it holds files friction-lab did not
    /// write (they are deleted with it).
    pub replace: bool,
    /// What asked for the files, as their provenance names it ([`Provenance::command`]).
    pub command: String,
}

impl Delivery {
    /// `figure_size` (`WxH` in inches), `dpi` and `replace`, checked ([`Format::parse`]), for
    /// the files of `command`.
    pub fn parse(
        figure_size: Option<&str>,
        dpi: Option<f64>,
        replace: bool,
        command: &str,
    ) -> Result<Delivery, AppError> {
        Ok(Delivery {
            format: Format::parse(figure_size, dpi)?,
            replace,
            command: command.to_string(),
        })
    }

    /// Writes `files` as the folder `out` ([`Artifacts::write`]), figures drawn on `threads`
    /// threads (all cores when `None`), stamped with their provenance ([`Artifacts::stamp`]).
    pub fn write(
        &self,
        mut files: Artifacts,
        out: &Path,
        threads: Option<usize>,
    ) -> Result<Written, AppError> {
        files.set_format(self.format);
        files.set_replace(self.replace);
        crate::threads::with_threads(threads, || {
            let provenance = Provenance::now(crate::threads::current());
            files.stamp(out, &provenance.with_command(self.command.clone()))?;
            files.write(out)
        })?
    }
}
