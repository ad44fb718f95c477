//! A list of resolutions extended while it falls short: a method whose error still falls at
//! the end of its list is given a tenth of its last tolerance, down to
//! [`TIGHTEST_TOLERANCE`], or half its last step, down to the finest listed step over
//! [`FINEST_STEP_DIVISOR`], before a study says it did not reach its target (`compare` and
//! `stiffness` extend so; a too-short list never decides a winner).

use super::StudyRun;
use friction_models::params::show;
use integrators::StepControl;

/// The tightest tolerance a list is extended to.
pub const TIGHTEST_TOLERANCE: f64 = 1e-13;
/// A fixed-step list is extended down to its finest step over this.
pub const FINEST_STEP_DIVISOR: f64 = 64.0;
/// A run whose error falls by less than this factor from the run before has stopped
/// falling: its list is not extended.
pub const STILL_FALLING: f64 = 0.9;

/// `x` to six significant digits: a resolution extended by tenths or halves stays the
/// decimal number it names (1e-11, not 1.0000000000000001e-11).
fn decimal(x: f64) -> f64 {
    format!("{x:.5e}")
        .parse()
        .expect("a formatted number parses")
}

/// The resolution after `runs` (loose to tight, the runs of `listed` and of its extension so
/// far): the next of `listed`, or past its end a tenth of the last tolerance or half the last
/// step while the error of the last two runs judged ok still falls (or fewer than two were
/// judged ok); `Err` with why the list ends (also: the tightest run failed).
pub fn next_resolution(runs: &[&StudyRun], listed: &[StepControl]) -> Result<StepControl, String> {
    if let Some(&s) = listed.get(runs.len()) {
        return Ok(s);
    }
    // A failure at the tightest (a step or time limit, not an explicit step's instability)
    // would only repeat at a tighter one.
    if let Some(r) = runs.last().filter(|r| !r.diverged) {
        if let Some(e) = &r.failure {
            return Err(format!("its run at {} failed: {e}", show(r.resolution)));
        }
    }
    let ok: Vec<&&StudyRun> = runs.iter().filter(|r| r.verdict.is_ok()).collect();
    // Fewer than two runs judged ok: the list was too loose to tell, and goes on.
    let falling = match ok.as_slice() {
        [.., a, b] => b.errors.grid_relative < STILL_FALLING * a.errors.grid_relative,
        _ => true,
    };
    let last = runs.last().map_or(f64::NAN, |r| r.resolution);
    let finest_step = (listed.iter())
        .filter_map(|s| match s {
            StepControl::Fixed { h } => Some(*h),
            StepControl::Adaptive { .. } => None,
        })
        .fold(f64::INFINITY, f64::min);
    let (next, limit) = match listed.last() {
        Some(StepControl::Adaptive { .. }) => {
            let tol = decimal(last / 10.0);
            let next = (tol >= TIGHTEST_TOLERANCE).then_some(StepControl::Adaptive {
                rtol: tol,
                atol: tol,
                h0: None,
            });
            (next, format!("tol {TIGHTEST_TOLERANCE:e}"))
        }
        _ => {
            let h = decimal(last / 2.0);
            let next = (h >= decimal(finest_step / FINEST_STEP_DIVISOR))
                .then_some(StepControl::Fixed { h });
            (next, format!("h/{FINEST_STEP_DIVISOR}"))
        }
    };
    match (falling, next) {
        (true, Some(s)) => Ok(s),
        (true, None) => Err(format!(
            "its list ends at {} (extended to {limit}) with the error still falling",
            show(last)
        )),
        (false, _) => Err(format!(
            "its error stopped falling at {} (error {})",
            show(last),
            show(ok.last().map_or(f64::NAN, |r| r.errors.grid_relative))
        )),
    }
}
