//! The front ends' progress display, an observer of the library ([`friction_lab::progress`]): a
//! bar on a terminal, and without one (nohup, CI, a notebook) a one-line heartbeat on stderr at
//! least every [`HEARTBEAT_S`] seconds, whether or not anything advanced: what is done, what
//! is left, the time elapsed. The command line and the Python package install it
//! ([`friction_lab::progress::observe_with`]); the library draws nothing itself.

use friction_lab::progress::{Observer, Task, Unit};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

/// Seconds between heartbeat lines (the environment variable `FRICTION_LAB_HEARTBEAT_S`
/// overrides it; 0 prints every update and no line between updates).
pub const HEARTBEAT_S: f64 = 10.0;

/// What a heartbeat line reports, shared with the thread that prints it between updates.
struct State {
    what: String,
    unit: Unit,
    total: u64,
    /// The end time, for [`Unit::Time`].
    t_end: f64,
    done: AtomicU64,
    /// The simulated time reached, as the bits of an `f64`, for [`Unit::Time`].
    t: AtomicU64,
    start: Instant,
    /// When the last line was printed, in seconds since `start`.
    last: Mutex<f64>,
    period: f64,
}

impl State {
    /// The heartbeat line.
    fn line(&self, elapsed: f64) -> String {
        let done = self.done.load(Ordering::Relaxed);
        match self.unit {
            Unit::Count(noun) => format!(
                "{}: {done} {noun} done, {} left, {elapsed:.0} s elapsed",
                self.what,
                self.total.saturating_sub(done)
            ),
            Unit::Time => format!(
                "{}: t = {:.6} of {} s, {elapsed:.0} s elapsed",
                self.what,
                f64::from_bits(self.t.load(Ordering::Relaxed)),
                self.t_end
            ),
            Unit::Elapsed => format!("{}: {elapsed:.0} s elapsed", self.what),
        }
    }

    /// Prints the line if a period has passed since the last one.
    fn beat(&self) {
        let elapsed = self.start.elapsed().as_secs_f64();
        let mut last = self.last.lock().unwrap_or_else(|e| e.into_inner());
        if elapsed - *last < self.period {
            return;
        }
        *last = elapsed;
        eprintln!("{}", self.line(elapsed));
    }
}

/// The thread that prints a heartbeat when no update has printed one for a period.
struct Ticker {
    stop: Arc<(Mutex<bool>, Condvar)>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Ticker {
    fn start(state: Arc<State>) -> Ticker {
        let stop = Arc::new((Mutex::new(false), Condvar::new()));
        let signal = Arc::clone(&stop);
        let period = Duration::from_secs_f64(state.period);
        let thread = std::thread::spawn(move || {
            let (lock, wake) = &*signal;
            let mut stopped = lock.lock().unwrap_or_else(|e| e.into_inner());
            while !*stopped {
                let (guard, timeout) = wake
                    .wait_timeout(stopped, period)
                    .unwrap_or_else(|e| e.into_inner());
                stopped = guard;
                if !*stopped && timeout.timed_out() {
                    state.beat();
                }
            }
        });
        Ticker {
            stop,
            thread: Some(thread),
        }
    }

    fn stop(&mut self) {
        let (lock, wake) = &*self.stop;
        *lock.lock().unwrap_or_else(|e| e.into_inner()) = true;
        wake.notify_all();
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// A progress display that works with and without a terminal: one task's bar or heartbeat.
struct Shown {
    state: Arc<State>,
    bar: Option<indicatif::ProgressBar>,
    /// The heartbeat's thread, taken when it is stopped.
    ticker: Mutex<Option<Ticker>>,
}

impl Shown {
    fn new(what: &str, unit: Unit, total: u64, t_end: f64) -> Shown {
        let bar = std::io::stderr().is_terminal().then(|| {
            let template = match unit {
                Unit::Count(noun) => format!("{{msg}} [{{bar:40}}] {{pos}}/{{len}} {noun}"),
                Unit::Time => "{spinner} {msg} [{bar:40}] {percent}%".into(),
                Unit::Elapsed => "{spinner} {msg} {elapsed}".into(),
            };
            let b = indicatif::ProgressBar::new(total);
            b.set_style(
                indicatif::ProgressStyle::with_template(&template).expect("valid template"),
            );
            b.set_message(what.to_string());
            if unit == Unit::Elapsed {
                b.enable_steady_tick(Duration::from_millis(200));
            }
            b
        });
        let period = std::env::var("FRICTION_LAB_HEARTBEAT_S")
            .ok()
            .and_then(|v| v.parse::<f64>().ok())
            .filter(|p| p.is_finite() && *p >= 0.0)
            .unwrap_or(HEARTBEAT_S);
        let state = Arc::new(State {
            what: what.to_string(),
            unit,
            total,
            t_end,
            done: AtomicU64::new(0),
            t: AtomicU64::new(0.0f64.to_bits()),
            start: Instant::now(),
            last: Mutex::new(0.0),
            period,
        });
        let ticker = (bar.is_none() && period > 0.0).then(|| Ticker::start(Arc::clone(&state)));
        Shown {
            state,
            bar,
            ticker: Mutex::new(ticker),
        }
    }

    /// Shows `done` on the bar, or prints the heartbeat if a period has passed.
    fn show(&self, done: u64) {
        match &self.bar {
            Some(bar) => bar.set_position(done),
            None => self.state.beat(),
        }
    }
}

impl Task for Shown {
    fn inc(&self) {
        let done = self.state.done.fetch_add(1, Ordering::Relaxed) + 1;
        self.show(done);
    }

    fn at(&self, t: f64) {
        let done = (1000.0 * t / self.state.t_end).clamp(0.0, 1000.0) as u64;
        self.state.done.store(done, Ordering::Relaxed);
        self.state.t.store(t.to_bits(), Ordering::Relaxed);
        self.show(done);
    }

    fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
        let ticker = self.ticker.lock().unwrap_or_else(|e| e.into_inner()).take();
        if let Some(mut ticker) = ticker {
            ticker.stop();
        }
    }
}

/// The terminal's observer: a bar on stderr where it is a terminal, else a heartbeat line at
/// least every [`HEARTBEAT_S`] seconds.
pub struct Terminal;

impl Observer for Terminal {
    fn task(&self, what: &str, unit: Unit, total: u64, t_end: f64) -> Box<dyn Task> {
        Box::new(Shown::new(what, unit, total, t_end))
    }
}
