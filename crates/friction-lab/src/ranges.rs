//! The allowed range of every numeric field of a request, in one table, checked before any
//! work starts: an error ([`Invalid`]) names the field, the value and the range, and each front
//! end spells the field its own way (exit code 2 on the command line).

use crate::error::{AppError, Invalid};
use friction_models::params::Range;

/// A numeric field of a request: its name as the request declares it, its unit and its range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OptionRange {
    /// The field (`t_end`: the option `--t-end`, Python's keyword `t_end`).
    pub name: &'static str,
    /// Unit of the value ("" for a count).
    pub unit: &'static str,
    /// The allowed values.
    pub range: Range,
}

const fn closed(min: f64, max: f64) -> Range {
    Range {
        min,
        min_inclusive: true,
        max,
        max_inclusive: true,
    }
}

const fn left_open(min: f64, max: f64) -> Range {
    Range {
        min,
        min_inclusive: false,
        max,
        max_inclusive: true,
    }
}

/// End time: 1 µs to 1e6 s (11 days of simulated time).
pub const T_END: OptionRange = OptionRange {
    name: "t_end",
    unit: "s",
    range: closed(1e-6, 1e6),
};
/// End time of a test-set problem (`testset --t-end`): up to 1e12, beyond Robertson's 1e11.
pub const TESTSET_T_END: OptionRange = OptionRange {
    name: "t_end",
    unit: "",
    range: left_open(0.0, 1e12),
};
/// Fixed step, or initial step: 1e-10 s to 10 s.
pub const DT: OptionRange = OptionRange {
    name: "dt",
    unit: "s",
    range: closed(1e-10, 10.0),
};
/// The first step of an adaptive run (`testset --h0`), s: the range of [`DT`].
pub const H0: OptionRange = OptionRange { name: "h0", ..DT };
/// θ of time-stepping: 1/2 (trapezoidal) to 1 (implicit Euler); below 1/2 the θ-method is
/// unstable on an undamped oscillator.
pub const THETA: OptionRange = OptionRange {
    name: "theta",
    unit: "",
    range: closed(0.5, 1.0),
};
/// Relative tolerance: from 1e-14 (about 50 units of round-off) to 1.
pub const RTOL: OptionRange = OptionRange {
    name: "rtol",
    unit: "",
    range: closed(1e-14, 1.0),
};
/// Absolute tolerance: (0, 1].
pub const ATOL: OptionRange = OptionRange {
    name: "atol",
    unit: "",
    range: left_open(0.0, 1.0),
};
/// Output points of a run or a curve.
pub const POINTS: OptionRange = OptionRange {
    name: "points",
    unit: "",
    range: closed(2.0, 1e7),
};
/// Step cap of one run.
pub const MAX_STEPS: OptionRange = OptionRange {
    name: "max_steps",
    unit: "",
    range: closed(1.0, 1e10),
};
/// Wall-clock limit of one run.
pub const TIME_LIMIT: OptionRange = OptionRange {
    name: "time_limit",
    unit: "s",
    range: left_open(0.0, 1e6),
};
/// Worker threads asked for (more than the machine's cores are capped to them).
pub const THREADS: OptionRange = OptionRange {
    name: "threads",
    unit: "",
    range: closed(1.0, 1024.0),
};
/// The settled share of a sweep's run (its last part, measured).
pub const SETTLE: OptionRange = OptionRange {
    name: "settle",
    unit: "",
    range: left_open(0.0, 1.0),
};
/// Timing repetitions of work-precision.
pub const REPEATS: OptionRange = OptionRange {
    name: "repeats",
    unit: "",
    range: closed(1.0, 100.0),
};
/// Relative tolerance of an independence study's verdict.
pub const VERDICT_TOL: OptionRange = OptionRange {
    name: "tol",
    unit: "",
    range: left_open(0.0, 1.0),
};
/// Refinement ratio between an independence study's levels.
pub const RATIO: OptionRange = OptionRange {
    name: "ratio",
    unit: "",
    range: left_open(1.0, 1e3),
};
/// Levels of an independence study.
pub const LEVELS: OptionRange = OptionRange {
    name: "levels",
    unit: "",
    range: closed(2.0, 12.0),
};
/// Largest |v| of a velocity curve.
pub const V_MAX: OptionRange = OptionRange {
    name: "v_max",
    unit: "m/s",
    range: left_open(0.0, 1e6),
};

/// A value as messages show it: in exponent form when very small or very large (as the
/// ranges print their bounds), otherwise in full.
pub use friction_models::params::show;
use friction_models::params::unit_suffix;

impl OptionRange {
    /// `value` if it lies in the range, else the error that names option, value and range.
    pub fn check(&self, value: f64) -> Result<f64, AppError> {
        if self.range.contains(value) {
            Ok(value)
        } else {
            Err(AppError::Invalid(Invalid {
                field: self.name,
                value: show(value),
                allowed: format!("{}{}", self.range, unit_suffix(self.unit)),
                list: false,
            }))
        }
    }

    /// A whole-number option, checked.
    pub fn count(&self, value: i64) -> Result<usize, AppError> {
        self.check(value as f64).map(|v| v as usize)
    }

    /// Every value of the list field `field` (`dt_list`, `tol_list`), checked against this
    /// range; a list has 1 to 50 values, coarse to fine (each below the one before: the
    /// observed orders are taken between neighbours, and a repeated value is a repeated run).
    pub fn list(&self, field: &'static str, values: &[f64]) -> Result<(), AppError> {
        let invalid = |value: String, allowed: String| {
            Err(AppError::Invalid(Invalid {
                field,
                value,
                allowed,
                list: true,
            }))
        };
        if values.is_empty() || values.len() > 50 {
            return invalid(format!("{} values", values.len()), "1 to 50".into());
        }
        if let Some(&v) = values.iter().find(|&&v| !self.range.contains(v)) {
            let allowed = format!("values {}{}", self.range, unit_suffix(self.unit));
            return invalid(show(v), allowed);
        }
        match values.windows(2).find(|w| w[1] >= w[0]) {
            Some(w) => invalid(
                format!("{} then {}", show(w[0]), show(w[1])),
                "values from coarse to fine, each below the one before".into(),
            ),
            None => Ok(()),
        }
    }
}

/// The worker threads to use: `--threads` checked and capped at the machine's cores; `None`
/// for all of them.
pub fn threads(asked: Option<i64>) -> Result<Option<usize>, AppError> {
    let Some(n) = asked else {
        return Ok(None);
    };
    let n = THREADS.count(n)?;
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    Ok(Some(n.min(cores)))
}

/// The first item of `items` equal to an earlier one: `(earlier, later)` indices. A list option
/// that names a thing twice (an axis, a body, a solver) would repeat its runs or rows.
pub fn first_repeat<T: PartialEq>(items: &[T]) -> Option<(usize, usize)> {
    items
        .iter()
        .enumerate()
        .find_map(|(k, x)| items[..k].iter().position(|o| o == x).map(|j| (j, k)))
}
