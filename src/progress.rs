//! Progress of a long command: a bar on a terminal, and without one (nohup, CI, a notebook) a
//! one-line heartbeat on stderr every [`HEARTBEAT_S`] seconds: what is done, what is left, the
//! time elapsed.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::Instant;

/// Seconds between heartbeat lines (the environment variable `FRICTION_LAB_HEARTBEAT_S`
/// overrides it).
pub const HEARTBEAT_S: f64 = 10.0;

/// What is counted: runs of a study, or simulated time of one run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unit {
    /// Runs, counted one by one.
    Runs,
    /// Simulated seconds, in thousandths of the end time.
    Time,
}

/// A progress display that works with and without a terminal.
pub struct Progress {
    what: String,
    unit: Unit,
    total: u64,
    /// The end time, for [`Unit::Time`].
    t_end: f64,
    done: AtomicU64,
    bar: Option<indicatif::ProgressBar>,
    start: Instant,
    last: Mutex<f64>,
    period: f64,
}

impl Progress {
    /// Progress over `total` runs.
    pub fn runs(total: usize, what: &str) -> Progress {
        Progress::new(what, Unit::Runs, total as u64, 0.0)
    }

    /// Progress of one run to `t_end` (shown in thousandths).
    pub fn time(t_end: f64, what: &str) -> Progress {
        Progress::new(what, Unit::Time, 1000, t_end)
    }

    fn new(what: &str, unit: Unit, total: u64, t_end: f64) -> Progress {
        let bar = std::io::stderr().is_terminal().then(|| {
            let template = match unit {
                Unit::Runs => "{msg} [{bar:40}] {pos}/{len} runs",
                Unit::Time => "{spinner} {msg} [{bar:40}] {percent}%",
            };
            let b = indicatif::ProgressBar::new(total);
            b.set_style(indicatif::ProgressStyle::with_template(template).expect("valid template"));
            b.set_message(what.to_string());
            b
        });
        let period = std::env::var("FRICTION_LAB_HEARTBEAT_S")
            .ok()
            .and_then(|v| v.parse::<f64>().ok())
            .filter(|p| p.is_finite() && *p >= 0.0)
            .unwrap_or(HEARTBEAT_S);
        Progress {
            what: what.to_string(),
            unit,
            total,
            t_end,
            done: AtomicU64::new(0),
            bar,
            start: Instant::now(),
            last: Mutex::new(0.0),
            period,
        }
    }

    /// One more run done.
    pub fn inc(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        self.show(done, 0.0);
    }

    /// The run has reached simulated time `t`.
    pub fn at(&self, t: f64) {
        let done = (1000.0 * t / self.t_end).clamp(0.0, 1000.0) as u64;
        self.done.store(done, Ordering::Relaxed);
        self.show(done, t);
    }

    /// Shows `done` (runs, or thousandths of the end time) or, for a run, the time `t`.
    fn show(&self, done: u64, t: f64) {
        if let Some(bar) = &self.bar {
            bar.set_position(done);
            return;
        }
        let elapsed = self.start.elapsed().as_secs_f64();
        let mut last = self.last.lock().unwrap_or_else(|e| e.into_inner());
        if elapsed - *last < self.period {
            return;
        }
        *last = elapsed;
        let line = match self.unit {
            Unit::Runs => format!(
                "{}: {done} runs done, {} left, {elapsed:.0} s elapsed",
                self.what,
                self.total.saturating_sub(done)
            ),
            Unit::Time => format!(
                "{}: t = {t:.6} of {} s, {elapsed:.0} s elapsed",
                self.what, self.t_end
            ),
        };
        eprintln!("{line}");
    }

    /// Removes the bar (the heartbeat needs no clearing).
    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
