//! Progress of long work, as an observer the front end passes in: the library opens a
//! [`Task`] for each long piece of work (a study's runs, one run's simulated time, the files
//! drawn) and tells it what advanced; what the user sees is the observer's. The command line
//! and the Python package install the terminal's (crate `terminal`: a bar, or a heartbeat line
//! without a terminal); without one, nothing is shown. The library draws nothing itself.

use std::sync::{Arc, RwLock};

/// What is counted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unit {
    /// Items counted one by one, named by the noun (`runs`, `files`).
    Count(&'static str),
    /// Simulated seconds, in thousandths of the end time.
    Time,
    /// Nothing counted: only the time elapsed (loading a file).
    Elapsed,
}

/// One piece of work being observed.
pub trait Task: Send + Sync {
    /// One more item done ([`Unit::Count`]).
    fn inc(&self);
    /// The run has reached simulated time `t` ([`Unit::Time`]).
    fn at(&self, t: f64);
    /// The work is over: whatever shows it is taken down.
    fn finish(&self);
}

/// What a front end passes in to be told of progress.
pub trait Observer: Send + Sync {
    /// A task for the work `what`, counted in `unit` up to `total` (for [`Unit::Time`]: 1000
    /// thousandths of `t_end`).
    fn task(&self, what: &str, unit: Unit, total: u64, t_end: f64) -> Box<dyn Task>;
}

/// The observer the front end installed, if any.
static OBSERVER: RwLock<Option<Arc<dyn Observer>>> = RwLock::new(None);

/// Makes `observer` the one told of every long piece of work from now on (the front end calls
/// it once, at its start).
pub fn observe_with(observer: Arc<dyn Observer>) {
    *OBSERVER.write().unwrap_or_else(|e| e.into_inner()) = Some(observer);
}

/// Progress of one piece of work, told to the installed observer (nothing where none is);
/// finished when dropped.
pub struct Progress {
    task: Option<Box<dyn Task>>,
}

impl Progress {
    /// Progress over `total` runs.
    pub fn runs(total: usize, what: &str) -> Progress {
        Progress::new(what, Unit::Count("runs"), total as u64, 0.0)
    }

    /// Progress over `total` items named by `noun` (`files`).
    pub fn count(total: usize, noun: &'static str, what: &str) -> Progress {
        Progress::new(what, Unit::Count(noun), total as u64, 0.0)
    }

    /// Progress of one run to `t_end` (shown in thousandths).
    pub fn time(t_end: f64, what: &str) -> Progress {
        Progress::new(what, Unit::Time, 1000, t_end)
    }

    /// Progress of work that counts nothing: the time elapsed only.
    pub fn elapsed(what: &str) -> Progress {
        Progress::new(what, Unit::Elapsed, 0, 0.0)
    }

    fn new(what: &str, unit: Unit, total: u64, t_end: f64) -> Progress {
        let observer = OBSERVER.read().unwrap_or_else(|e| e.into_inner()).clone();
        Progress {
            task: observer.map(|o| o.task(what, unit, total, t_end)),
        }
    }

    /// One more item done.
    pub fn inc(&self) {
        if let Some(task) = &self.task {
            task.inc();
        }
    }

    /// The run has reached simulated time `t`.
    pub fn at(&self, t: f64) {
        if let Some(task) = &self.task {
            task.at(t);
        }
    }

    /// The work is over.
    pub fn finish(&self) {
        if let Some(task) = &self.task {
            task.finish();
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.finish();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    /// Records what it is told.
    struct Recorder(Arc<Mutex<Vec<String>>>);

    struct Recorded(String, Arc<Mutex<Vec<String>>>);

    impl Task for Recorded {
        fn inc(&self) {
            self.1.lock().unwrap().push(format!("{} inc", self.0));
        }
        fn at(&self, t: f64) {
            self.1.lock().unwrap().push(format!("{} at {t}", self.0));
        }
        fn finish(&self) {
            self.1.lock().unwrap().push(format!("{} finish", self.0));
        }
    }

    impl Observer for Recorder {
        fn task(&self, what: &str, unit: Unit, total: u64, _: f64) -> Box<dyn Task> {
            let log = Arc::clone(&self.0);
            log.lock().unwrap().push(format!("{what} {unit:?} {total}"));
            Box::new(Recorded(what.to_string(), log))
        }
    }

    #[test]
    fn the_installed_observer_is_told_of_the_work() {
        let log = Arc::new(Mutex::new(Vec::new()));
        observe_with(Arc::new(Recorder(Arc::clone(&log))));
        {
            let p = Progress::runs(2, "the test's study");
            p.inc();
            p.inc();
        }
        let mine: Vec<String> = (log.lock().unwrap().iter())
            .filter(|l| l.starts_with("the test's study"))
            .cloned()
            .collect();
        assert_eq!(
            mine,
            [
                "the test's study Count(\"runs\") 2",
                "the test's study inc",
                "the test's study inc",
                "the test's study finish"
            ]
        );
    }
}
