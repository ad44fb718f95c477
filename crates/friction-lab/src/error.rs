//! Every way a command can fail, each with a message that names what was wrong.

use friction_models::ParamError;
use friction_systems::file::SystemFileError;
use friction_systems::SystemError;
use integrators::SolverError;
use scenarios::curves::CurveError;
use scenarios::ScenarioError;
use std::path::PathBuf;
use thiserror::Error;

/// A failed command.
#[derive(Debug, Error)]
pub enum AppError {
    /// A parameter was rejected.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// A system (file, chain or rig) was rejected.
    #[error(transparent)]
    System(#[from] SystemError),
    /// A system file could not be read or declares no valid system.
    #[error(transparent)]
    SystemFile(#[from] SystemFileError),
    /// A curve option was rejected.
    #[error(transparent)]
    Curve(#[from] CurveError),
    /// A value of a request outside what it allows, as data ([`Invalid`]).
    #[error("{}", .0.message(&|field| field.to_string()))]
    Invalid(Invalid),
    /// A value that does not parse or does not apply, or a combination refused; the options it
    /// names are marked ([`field`]) for each front end to spell.
    #[error("{}", spell_fields(.0, &as_declared))]
    Usage(String),
    /// A parameter file that is not valid TOML or holds something other than numbers (the
    /// options its message names marked, as [`AppError::Usage`]'s).
    #[error("parameter file {path} ({}): {}", as_declared("params"), spell_fields(.message, &as_declared))]
    ParamFile {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// An output that would contain NaN or an infinity.
    #[error("refusing to write {path}: {what} is not finite ({value})")]
    NonFinite {
        /// The file that was to be written.
        path: PathBuf,
        /// Which value.
        what: String,
        /// The value.
        value: f64,
    },
    /// The output folder cannot be written as asked (bad input: exit 2).
    #[error("output folder {path}: {why}")]
    OutputFolder {
        /// The folder.
        path: PathBuf,
        /// Why.
        why: String,
    },
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The solver failed; the files written say how far it got.
    #[error("{}", solver_failure(.0))]
    Solver(SolverError),
    /// A run that a study needs failed in the solver (the options it names marked, as
    /// [`AppError::Usage`]'s).
    #[error("{}", spell_fields(.0, &as_declared))]
    StudyRun(String),
    /// A run ended without a solver error, but its result diverged (the verdict's reason).
    #[error("the run diverged: {0} (summary.json and trajectory.csv keep what was computed)")]
    Diverged(String),
    /// The output folder could not be written (a full disk): the files were staged in a
    /// temporary folder beside it, which is removed, and the folder is left as it was.
    #[error(
        "writing the output folder {folder} failed at {file}: {source}; its {files} files need \
         {} in all, and nothing was written (the folder is as it was)",
        bytes(*.needed)
    )]
    Write {
        /// The output folder.
        folder: PathBuf,
        /// The file that failed, by its path inside the folder.
        file: PathBuf,
        /// The number of files.
        files: usize,
        /// The bytes of all the files.
        needed: u64,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// A signal stopped the command before anything was computed (while loading its input):
    /// nothing was written.
    #[error("stopped while {0}: nothing was run or written")]
    Stopped(String),
    /// A plot could not be drawn.
    #[error("drawing {path}: {message}")]
    Plot {
        /// The figure being drawn.
        path: PathBuf,
        /// The drawing back-end's error.
        message: String,
    },
}

/// A value a request does not allow, as data: the field as the request declares it (`t_end`,
/// `dt_list`), the value as given, and what is allowed. Each front end spells the field its
/// own way ([`Invalid::message`]): the command line as its option (`--t-end`), Python as its
/// keyword (`t_end`).
#[derive(Clone, Debug, PartialEq)]
pub struct Invalid {
    /// The field of the request.
    pub field: &'static str,
    /// The value given, as the message shows it (`-1`; for a list, the value or the pair of
    /// values at fault: `0.005 then 0.01`).
    pub value: String,
    /// What is allowed (`[1e-6, 1e6] s`, `values from coarse to fine, each below the one
    /// before`).
    pub allowed: String,
    /// Whether the field is a list (the message says "has VALUE" for the value at fault, not
    /// "= VALUE").
    pub list: bool,
}

impl Invalid {
    /// The message with the field spelled by `spell`: "option `--t-end` = -1 is out of range:
    /// allowed [1e-6, 1e6] s", or for a list "option `--dt-list` has -1: allowed values
    /// [1e-10, 10] s".
    pub fn message(&self, spell: &dyn Fn(&str) -> String) -> String {
        let field = spell(self.field);
        match self.list {
            false => format!(
                "option `{field}` = {} is out of range: allowed {}",
                self.value, self.allowed
            ),
            true => format!(
                "option `{field}` has {}: allowed {}",
                self.value, self.allowed
            ),
        }
    }
}

impl AppError {
    /// The message with every request field it names spelled by `spell` (a front end's
    /// spelling of [`Invalid::field`] and of the fields marked by [`field`]).
    pub fn message(&self, spell: &dyn Fn(&str) -> String) -> String {
        match self {
            AppError::Invalid(invalid) => invalid.message(spell),
            AppError::Usage(m) | AppError::StudyRun(m) => spell_fields(m, spell),
            AppError::OutputFolder { path, why } => format!(
                "output folder {}: {}",
                path.display(),
                spell_fields(why, spell)
            ),
            AppError::ParamFile { path, message } => format!(
                "parameter file {} ({}): {}",
                path.display(),
                spell("params"),
                spell_fields(message, spell)
            ),
            other => other.to_string(),
        }
    }

    /// The message with the fields it names still marked ([`field`]): for a message passed
    /// on as advice, which each front end spells when it shows it.
    pub fn marked(&self) -> String {
        self.message(&|name| field(name))
    }

    /// What kind of failure it is: bad input, a failure while running, or a stop by a signal
    /// before anything was computed (each front end says it its own way: the command line as
    /// its exit code 2, 1 or 130, Python as `ValueError` or `SolverError`).
    pub fn kind(&self) -> ErrorKind {
        match self {
            AppError::Param(_)
            | AppError::System(_)
            | AppError::SystemFile(_)
            | AppError::Curve(_)
            | AppError::OutputFolder { .. }
            | AppError::Invalid(_)
            | AppError::Usage(_)
            | AppError::ParamFile { .. } => ErrorKind::BadInput,
            AppError::NonFinite { .. }
            | AppError::Io { .. }
            | AppError::Plot { .. }
            | AppError::Write { .. }
            | AppError::Solver(_)
            | AppError::StudyRun(_)
            | AppError::Diverged(_) => ErrorKind::Failed,
            AppError::Stopped(_) => ErrorKind::Stopped,
        }
    }
}

/// What kind of failure an [`AppError`] is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    /// Bad input (an option, a parameter, a file, the output folder): nothing was run or
    /// written.
    BadInput,
    /// A failure while running (a solver error, a limit, a write): what was computed is kept.
    Failed,
    /// A signal stopped the command before it computed anything.
    Stopped,
}

impl From<ScenarioError> for AppError {
    /// Bad input stays bad input (exit 2); a failed run is a failure (exit 1).
    fn from(e: ScenarioError) -> AppError {
        match e {
            ScenarioError::Param(p) => AppError::Param(p),
            ScenarioError::System(s) => AppError::System(s),
            ScenarioError::Invalid(m) => AppError::Usage(m),
            e @ (ScenarioError::Solver { .. }
            | ScenarioError::RunFailed(_)
            | ScenarioError::Orbit(_)) => AppError::StudyRun(e.to_string()),
        }
    }
}

/// Where a marked field begins, in a message ([`field`]).
const FIELD_OPEN: char = '\u{27E8}';
/// Where it ends.
const FIELD_CLOSE: char = '\u{27E9}';

/// A request's field (`t_end`, `switching`, `set`), named inside a message, an advice or a
/// note for each front end to spell its own way ([`spell_fields`]): the command line as its
/// option (`--t-end`), Python as its keyword (`t_end`). The library names options only so.
pub fn field(name: &str) -> String {
    format!("{FIELD_OPEN}{name}{FIELD_CLOSE}")
}

/// Where a marked setting's value begins ([`setting`]).
const VALUE_SEPARATOR: char = '\u{1F}';

/// A request's field with the value it was given (`solver` = `bdf`), named inside a message
/// for each front end to spell as its user writes it ([`spell_fields`]): the command line as
/// `--solver bdf`, Python as `solver='bdf'` (a number bare, a comma list as a list).
pub fn setting(name: &str, value: &str) -> String {
    format!("{FIELD_OPEN}{name}{VALUE_SEPARATOR}{value}{FIELD_CLOSE}")
}

/// `text` with every field marked by [`field`] spelled by `spell`, and every setting marked
/// by [`setting`] as its field so spelled with its value: after a space where the field is
/// spelled as an option (`--solver bdf`), else as a keyword argument (`solver='bdf'`).
pub fn spell_fields(text: &str, spell: &dyn Fn(&str) -> String) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(start) = rest.find(FIELD_OPEN) {
        let after = &rest[start + FIELD_OPEN.len_utf8()..];
        let Some(end) = after.find(FIELD_CLOSE) else {
            break;
        };
        out += &rest[..start];
        out += &match after[..end].split_once(VALUE_SEPARATOR) {
            None => spell(&after[..end]),
            Some((name, value)) => match spell(name) {
                option if option.starts_with("--") => format!("{option} {value}"),
                keyword => format!("{keyword}={}", keyword_value(value)),
            },
        };
        rest = &after[end + FIELD_CLOSE.len_utf8()..];
    }
    out + rest
}

/// A setting's value as a keyword argument takes it: a number bare, a name quoted, a comma
/// list as a list (`0.7`, `'bdf'`, `['rk4', 'bdf']`).
fn keyword_value(value: &str) -> String {
    let one = |v: &str| match v.parse::<f64>() {
        Ok(_) => v.to_string(),
        Err(_) => format!("'{v}'"),
    };
    match value.contains(',') {
        true => format!(
            "[{}]",
            value.split(',').map(one).collect::<Vec<_>>().join(", ")
        ),
        false => one(value),
    }
}

/// A field as its request declares it (`t_end`): how the library's own `Display` spells
/// the fields its messages mark.
fn as_declared(name: &str) -> String {
    name.to_string()
}

/// The command line's spelling of a field: its long option, `t_end` as `--t-end`.
pub fn as_option(name: &str) -> String {
    format!("--{}", name.replace('_', "-"))
}

/// A size in bytes as a reader takes it in: `512 bytes`, `3.4 MB` (decimal units).
fn bytes(n: u64) -> String {
    match n {
        0..1_000 => format!("{n} bytes"),
        1_000..1_000_000 => format!("{:.1} kB", n as f64 / 1e3),
        1_000_000..1_000_000_000 => format!("{:.1} MB", n as f64 / 1e6),
        _ => format!("{:.2} GB", n as f64 / 1e9),
    }
}

/// The message of a run that ended in the solver: stopped by a signal
/// ([`SolverError::Interrupted`]), or failed.
fn solver_failure(e: &SolverError) -> String {
    match e {
        SolverError::Interrupted { .. } => {
            format!("stopped: {e} (summary.json and trajectory.csv keep the run up to there)")
        }
        _ => format!(
            "the solver failed: {e} (summary.json and trajectory.csv keep the run up to the \
             failure)"
        ),
    }
}

/// The longest word a message repeats whole, in bytes: PATH_MAX, so that every path a
/// message names is whole; a longer word (a 5 MB model name, a file pasted by mistake) is
/// shortened by [`bounded`].
pub const MAX_ECHO: usize = 4096;

/// `message` with every word (a run of non-whitespace) longer than [`MAX_ECHO`] bytes cut to
/// its first 100 and last 20 characters around `…[N bytes]…`: what a user typed is echoed in
/// a message, never megabytes of it.
pub fn bounded(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(64 * 1024));
    let mut rest = message;
    while !rest.is_empty() {
        let word_end = rest.find(char::is_whitespace).unwrap_or(rest.len());
        let (word, after) = rest.split_at(word_end);
        if word.len() > MAX_ECHO {
            let head: String = word.chars().take(100).collect();
            let tail: Vec<char> = word.chars().rev().take(20).collect();
            let tail: String = tail.into_iter().rev().collect();
            out += &format!("{head}…[{} bytes]…{tail}", word.len());
        } else {
            out += word;
        }
        let space_end = after
            .find(|c: char| !c.is_whitespace())
            .unwrap_or(after.len());
        out += &after[..space_end];
        rest = &after[space_end..];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{as_option, bounded, field, setting, spell_fields, AppError, MAX_ECHO};

    #[test]
    fn a_setting_is_spelled_as_each_front_end_writes_it() {
        let text = format!(
            "option `{}`, `{}`, `{}`",
            setting("solver", "bdf"),
            setting("theta", "0.7"),
            setting("solvers", "rk4,bdf")
        );
        assert_eq!(
            spell_fields(&text, &as_option),
            "option `--solver bdf`, `--theta 0.7`, `--solvers rk4,bdf`"
        );
        assert_eq!(
            spell_fields(&text, &|name: &str| name.to_string()),
            "option `solver='bdf'`, `theta=0.7`, `solvers=['rk4', 'bdf']`"
        );
    }

    #[test]
    fn each_front_end_spells_the_marked_fields_its_own_way() {
        let e = AppError::Usage(format!(
            "option `{} 0.5` applies to {} time-stepping",
            field("theta"),
            field("scheme")
        ));
        assert_eq!(
            e.message(&as_option),
            "option `--theta 0.5` applies to --scheme time-stepping"
        );
        let keyword = |name: &str| name.to_string();
        assert_eq!(
            e.message(&keyword),
            "option `theta 0.5` applies to scheme time-stepping"
        );
        assert_eq!(e.to_string(), e.message(&keyword));
        assert_eq!(as_option("t_end"), "--t-end");
        // An unclosed mark is left as it is.
        assert_eq!(spell_fields("a \u{27E8}b", &as_option), "a \u{27E8}b");
    }

    #[test]
    fn a_long_word_is_cut_and_the_rest_kept() {
        let name = "x".repeat(5_000_000);
        let message = format!("unknown model `{name}`; known:\n  CS, CVS");
        let cut = bounded(&message);
        assert_eq!(
            cut,
            format!(
                "unknown model `{}…[5000003 bytes]…{}`; known:\n  CS, CVS",
                "x".repeat(99),
                "x".repeat(18)
            )
        );
        // Words up to the limit, and every space, are kept as they are.
        let fits = format!("a  {} \tb\n", "y".repeat(MAX_ECHO));
        assert_eq!(bounded(&fits), fits);
    }
}
