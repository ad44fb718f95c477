//! What the caller asks of a run: time span, step control, limits and output.

use crate::error::SolverError;

/// How the step size is chosen. Serialised as plain numbers with a tag:
/// `{"control": "fixed", "h": 0.001}` or
/// `{"control": "adaptive", "rtol": 1e-8, "atol": 1e-10, "h0": null}`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(tag = "control", rename_all = "lowercase")]
pub enum StepControl {
    /// Constant step `h` (the last step before the end or an event is shortened to land
    /// exactly on it, never overshooting).
    Fixed {
        /// Step size, s.
        h: f64,
    },
    /// Error-controlled steps with tolerance `atol + rtol·|y|` per component.
    Adaptive {
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance.
        atol: f64,
        /// Initial step; `None` lets the method choose (Hairer's HINIT for Dormand–Prince).
        h0: Option<f64>,
    },
}

/// As reports write it: `fixed step h = 0.01 s`, `rtol 1e-10, atol 1e-12` (with `, h0 = …
/// s` where a first step is given).
impl std::fmt::Display for StepControl {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        use crate::error::shown;
        match *self {
            StepControl::Fixed { h } => write!(f, "fixed step h = {} s", shown(&h)),
            StepControl::Adaptive { rtol, atol, h0 } => {
                write!(f, "rtol {}, atol {}", shown(&rtol), shown(&atol))?;
                match h0 {
                    Some(h) => write!(f, ", h0 = {} s", shown(&h)),
                    None => Ok(()),
                }
            }
        }
    }
}

impl StepControl {
    /// The step the run prescribes: the fixed step `h`, or an adaptive run's `h0`; `None`
    /// when the method is to choose its first step.
    pub fn given_step(&self) -> Option<f64> {
        match *self {
            StepControl::Fixed { h } | StepControl::Adaptive { h0: Some(h), .. } => Some(h),
            StepControl::Adaptive { h0: None, .. } => None,
        }
    }
}

/// Guard against chattering: an error when more than `max_events` event instants fall
/// within a window of `window` times the problem's own time scale
/// ([`crate::OdeProblem::time_scale`], its shortest natural period; seconds for a problem
/// without one). Simultaneous switches of several components are one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ZenoGuard {
    /// Event instants allowed in one window.
    pub max_events: usize,
    /// Window length, in units of the problem's time scale.
    pub window: f64,
}

impl ZenoGuard {
    /// The window in seconds for a problem whose time scale is `scale` (s).
    pub fn window_s(&self, scale: Option<f64>) -> f64 {
        self.window * scale.unwrap_or(1.0)
    }
}

impl Default for ZenoGuard {
    fn default() -> Self {
        ZenoGuard {
            max_events: 100,
            window: 1e-6,
        }
    }
}

/// Which points the solution records.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Output {
    /// The end of every accepted step, and both sides of every event.
    #[default]
    Steps,
    /// These times (increasing), by dense output, and both sides of every event.
    Grid(Vec<f64>),
    /// These times (increasing), by dense output, and nothing else: for large systems, whose
    /// events are read from the event records rather than from recorded states.
    GridOnly(Vec<f64>),
}

/// `n` evenly spaced times from `t0` to `t_end` (n ≥ 2), t_i = t0 + (t_end − t0)·i/(n − 1),
/// with the ends exactly `t0` and `t_end`: computed so, the last point may land one rounding
/// above `t_end`, where an integration that stops at `t_end` never records it.
pub fn even_grid(t0: f64, t_end: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| {
            if i + 1 == n {
                t_end
            } else {
                t0 + (t_end - t0) * i as f64 / (n - 1) as f64
            }
        })
        .collect()
}

impl Output {
    /// The output times, for the grid outputs.
    pub fn grid(&self) -> Option<&[f64]> {
        match self {
            Output::Steps => None,
            Output::Grid(t) | Output::GridOnly(t) => Some(t),
        }
    }

    /// Whether both sides of every event are recorded.
    pub fn records_events(&self) -> bool {
        !matches!(self, Output::GridOnly(_))
    }
}

/// Options of one integration.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// Start time.
    pub t0: f64,
    /// End time.
    pub t_end: f64,
    /// Step-size control.
    pub step: StepControl,
    /// Largest step; `None` for `t_end − t0` (as in Hairer's codes).
    pub h_max: Option<f64>,
    /// Most steps (accepted and rejected) before giving up; the driver also counts the steps
    /// of methods that do not count their own (diffsol's).
    pub max_steps: usize,
    /// Wall-clock limit of the integration, s: the run ends with [`SolverError::TimeLimit`]
    /// and keeps what it computed. `None`: no limit.
    pub time_limit: Option<f64>,
    /// When the wall-clock limit starts counting: `None` for the start of this run; a command
    /// of many runs gives its own start, so that [`Options::time_limit`] bounds the whole
    /// command (a run started after it has passed ends at its first step).
    pub time_limit_since: Option<std::time::Instant>,
    /// Chattering guard.
    pub zeno: ZenoGuard,
    /// What to record.
    pub output: Output,
}

impl Options {
    /// Adaptive stepping from `t0` to `t_end` with tolerances `rtol`, `atol`.
    pub fn adaptive(t0: f64, t_end: f64, rtol: f64, atol: f64) -> Self {
        Options {
            t0,
            t_end,
            step: StepControl::Adaptive {
                rtol,
                atol,
                h0: None,
            },
            h_max: None,
            max_steps: 10_000_000,
            time_limit: None,
            time_limit_since: None,
            zeno: ZenoGuard::default(),
            output: Output::Steps,
        }
    }

    /// Fixed steps of `h` from `t0` to `t_end`.
    pub fn fixed(t0: f64, t_end: f64, h: f64) -> Self {
        Options {
            step: StepControl::Fixed { h },
            ..Options::adaptive(t0, t_end, 1e-6, 1e-6)
        }
    }

    /// Checks every option: finite times with `t_end > t0`, positive finite step and
    /// tolerances.
    pub fn validate(&self) -> Result<(), SolverError> {
        let positive = |name, value: f64| {
            if value.is_finite() && value > 0.0 {
                Ok(())
            } else {
                Err(SolverError::InvalidOption {
                    name,
                    value,
                    allowed: "(0, inf)",
                })
            }
        };
        for (name, value) in [("t0", self.t0), ("t_end", self.t_end)] {
            if !value.is_finite() {
                return Err(SolverError::InvalidOption {
                    name,
                    value,
                    allowed: "a finite number",
                });
            }
        }
        if self.t_end <= self.t0 {
            return Err(SolverError::EndBeforeStart {
                t0: self.t0,
                t_end: self.t_end,
            });
        }
        match self.step {
            StepControl::Fixed { h } => positive("dt", h)?,
            StepControl::Adaptive { rtol, atol, h0 } => {
                positive("rtol", rtol)?;
                positive("atol", atol)?;
                if let Some(h) = h0 {
                    positive("dt", h)?;
                }
            }
        }
        if let Some(h) = self.h_max {
            positive("h_max", h)?;
        }
        if let Some(limit) = self.time_limit {
            positive("time_limit", limit)?;
        }
        if self.max_steps == 0 {
            return Err(SolverError::InvalidOption {
                name: "max_steps",
                value: 0.0,
                allowed: "[1, inf)",
            });
        }
        positive("zeno window", self.zeno.window)?;
        Ok(())
    }

    /// The largest step.
    pub fn h_max(&self) -> f64 {
        self.h_max.unwrap_or(self.t_end - self.t0)
    }
}

#[cfg(test)]
mod tests {
    use super::StepControl;

    #[test]
    fn a_step_control_reads_as_reports_write_it() {
        let adaptive = StepControl::Adaptive {
            rtol: 1e-10,
            atol: 1e-12,
            h0: None,
        };
        assert_eq!(adaptive.to_string(), "rtol 1e-10, atol 1e-12");
        let started = StepControl::Adaptive {
            rtol: 1e-6,
            atol: 1e-6,
            h0: Some(0.001),
        };
        assert_eq!(started.to_string(), "rtol 1e-6, atol 1e-6, h0 = 0.001 s");
        assert_eq!(
            StepControl::Fixed { h: 0.01 }.to_string(),
            "fixed step h = 0.01 s"
        );
    }
}
