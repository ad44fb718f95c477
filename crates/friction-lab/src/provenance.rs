//! Where a result comes from: the friction-lab version and git commit that computed it, when,
//! on what machine, on how many threads, and the command (or the Python call) that asked for
//! it. Every JSON file a command writes opens with it, every folder holds it beside its files
//! as [`SIDECAR`] (which lists them: the CSV files and figures carry no header of their own),
//! and `report.md` names it, so a figure or a table can be traced to what made it. The results
//! themselves do not depend on any of it but the version (they are identical on any number of
//! threads).

use serde::Serialize;
use std::time::{SystemTime, UNIX_EPOCH};

/// The provenance of a result.
#[derive(Clone, Debug, Serialize)]
pub struct Provenance {
    /// The friction-lab version (`Cargo.toml`).
    pub friction_lab: &'static str,
    /// The git commit it was built from (`unknown` outside a git checkout).
    pub commit: &'static str,
    /// When the result was computed: UTC, ISO 8601 (`2026-11-27T00:31:05Z`).
    pub date: String,
    /// The machine.
    pub machine: Machine,
    /// The worker threads the runs were spread over.
    pub threads: usize,
    /// What asked for the result: the command line (`friction-lab simulate belt --out run`),
    /// or the Python call with its keyword arguments (`friction_lab.simulate('belt',
    /// t_end=5.0)`); absent until a front end names it ([`Provenance::with_command`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub command: Option<String>,
}

/// The friction-lab version (`Cargo.toml`): `friction_lab.__version__` in Python.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The file in every output folder that names the provenance of its files and lists them, by
/// their paths inside the folder.
pub const SIDECAR: &str = "provenance.json";

/// The machine a result was computed on.
#[derive(Clone, Debug, Serialize)]
pub struct Machine {
    /// The CPU's model name (`/proc/cpuinfo`; `unknown` where it cannot be read).
    pub cpu: String,
    /// Logical cores available to the process.
    pub logical_cores: usize,
    /// Operating system and architecture (`linux x86_64`).
    pub os: String,
}

impl Provenance {
    /// The provenance of a result computed now, here, on `threads` worker threads.
    pub fn now(threads: usize) -> Provenance {
        Provenance {
            friction_lab: VERSION,
            commit: env!("FRICTION_LAB_COMMIT"),
            date: utc(SystemTime::now()),
            machine: Machine::this(),
            threads,
            command: None,
        }
    }

    /// The same provenance, made by `command` ([`Provenance::command`]).
    pub fn with_command(self, command: String) -> Provenance {
        Provenance {
            command: Some(command),
            ..self
        }
    }

    /// The provenance as a line of Markdown, for a report.
    pub fn markdown(&self) -> String {
        format!(
            "friction-lab {} (commit `{}`), {}, on {} ({} logical cores, {}), {} threads",
            self.friction_lab,
            self.commit,
            self.date,
            self.machine.cpu,
            self.machine.logical_cores,
            self.machine.os,
            self.threads
        )
    }
}

impl Machine {
    /// This machine.
    pub fn this() -> Machine {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|info| {
                info.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split_once(':'))
                    .map(|(_, name)| name.trim().to_string())
            })
            .unwrap_or_else(|| "unknown".into());
        Machine {
            cpu,
            logical_cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            os: format!("{} {}", std::env::consts::OS, std::env::consts::ARCH),
        }
    }
}

/// `words` as one line a POSIX shell reads back into the same words: a word of letters,
/// digits and `_-./:=,+@%` as it is, any other (a space, a quote, a `$`, an empty word) in
/// single quotes, each `'` in it written `'\''`.
pub fn shell_line<S: AsRef<str>>(words: &[S]) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "_-./:=,+@%".contains(c);
    let quoted = |w: &str| {
        if !w.is_empty() && w.chars().all(plain) {
            w.to_string()
        } else {
            format!("'{}'", w.replace('\'', "'\\''"))
        }
    };
    (words.iter().map(|w| quoted(w.as_ref())))
        .collect::<Vec<_>>()
        .join(" ")
}

/// `time` as UTC in ISO 8601 to the second: the civil date of its day number (Hinnant's
/// `civil_from_days`, valid for every date of the proleptic Gregorian calendar).
pub fn utc(time: SystemTime) -> String {
    let seconds = time.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs()) as i64;
    let (days, second) = (seconds.div_euclid(86_400), seconds.rem_euclid(86_400));
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1_460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z",
        second / 3600,
        second / 60 % 60,
        second % 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn dates_are_the_civil_dates_of_their_seconds() {
        let at = |s: u64| utc(UNIX_EPOCH + Duration::from_secs(s));
        assert_eq!(at(0), "1970-01-01T00:00:00Z");
        // 2000-02-29 (a leap day of a century divisible by 400), 12:34:56.
        assert_eq!(at(951_827_696), "2000-02-29T12:34:56Z");
        // 2026-11-27 00:31:05.
        assert_eq!(at(1_795_739_465), "2026-11-27T00:31:05Z");
    }

    #[test]
    fn a_command_line_quotes_only_the_words_a_shell_would_split_or_expand() {
        let line = shell_line(&["friction-lab", "simulate", "--set", "v_belt=0.1", "a b", ""]);
        assert_eq!(line, "friction-lab simulate --set v_belt=0.1 'a b' ''");
        assert_eq!(shell_line(&["it's", "$HOME"]), "'it'\\''s' '$HOME'");
    }
}
