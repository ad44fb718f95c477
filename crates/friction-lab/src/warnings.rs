//! The advice printed beside a run's or a study's results: why a run failed or ran out of
//! steps and what would avoid it, a step too coarse for the problem's natural period, a
//! parameter given that the run does not read.

use crate::error::field;
use crate::laws::check_read;
use crate::ranges;
use friction_models::ModelId;
use friction_systems::{Scheme, Switching};
use integrators::{SolverError, StepControl};

/// The advice given when `method` found the problem stiff at time `t` (Hairer's test).
pub fn stiffness_warning(method: &str, t: f64) -> String {
    format!("{method} found the problem stiff at t = {t:.6} s; an implicit solver (bdf, esdirk34) may be much faster")
}

/// The advice given when a fixed step `h` (RK4, `--fixed-step`, time-stepping) exceeds a
/// tenth of the shortest natural period `period` of the problem: each oscillation is then
/// resolved by fewer than ten steps, whatever the scheme's stability.
pub fn coarse_step_warning(step: StepControl, period: Option<f64>) -> Option<String> {
    let (StepControl::Fixed { h }, Some(period)) = (step, period) else {
        return None;
    };
    (h > 0.1 * period).then(|| {
        // The period to three significant digits.
        let decimals = (2 - period.log10().floor() as i32).max(0) as usize;
        format!(
            "the fixed step h = {} s is more than a tenth of the shortest natural period, \
             {period:.decimals$} s: each oscillation is resolved by fewer than ten steps",
            ranges::show(h),
        )
    })
}

/// The advice given when a run over `span` seconds ended for lack of steps (too many, or a step
/// below the resolution of t) and spans more than [`MANY_PERIODS`] of the problem's shortest
/// natural period `period`: no solver resolves that many oscillations within the step cap, and
/// the likelier cause is a mass or a stiffness off by orders of magnitude (k = 1e300 N/m on a
/// body of 1 kg ends with a step-size underflow at t = 3e-130 s).
pub fn unresolvable_period_warning(
    span: f64,
    period: Option<f64>,
    error: Option<&SolverError>,
) -> Option<String> {
    let period = period.filter(|&p| lacked_steps(error) && span > MANY_PERIODS * p)?;
    Some(format!(
        "the run spans {:.1e} of the shortest natural period 2π√(m/(k + kp)) = {period:.2e} s, \
         too many to resolve with a few steps each: check the masses, the stiffnesses and the \
         controllers' gains kp, or shorten {}",
        span / period,
        field("t_end"),
    ))
}

/// The number of the shortest natural periods beyond which a run that lacked steps is told
/// why ([`unresolvable_period_warning`]): at ten steps a period, the default step cap.
pub const MANY_PERIODS: f64 = 1e6;

/// Whether a run ended for lack of steps: too many, or a step below the resolution of t.
fn lacked_steps(error: Option<&SolverError>) -> bool {
    matches!(
        error,
        Some(SolverError::TooManySteps { .. } | SolverError::StepSizeUnderflow { .. })
    )
}

/// The advice given when a run under naive switching with an adaptive solver ended for lack
/// of steps: stepping blindly through the jump of the law at v_rel = 0, the error control
/// shrinks the step there until the cap (the belt with CS: 1e7 steps by t = 0.03 s, h =
/// 2.5e-9 s), which is what naive switching exists to show.
pub fn naive_chatter_warning(
    scheme: Scheme,
    step: StepControl,
    error: Option<&SolverError>,
) -> Option<String> {
    let adaptive = matches!(step, StepControl::Adaptive { .. });
    let naive = matches!(
        scheme,
        Scheme::EventDriven {
            switching: Switching::Naive,
            ..
        }
    );
    (naive && adaptive && lacked_steps(error)).then(|| {
        let [switching, scheme, solver, dt] = ["switching", "scheme", "solver", "dt"].map(field);
        format!(
            "naive switching steps blindly through the jump of the friction law at v_rel = 0, \
             where an adaptive solver's error control shrinks the step until the cap: \
             {switching} event locates the switches, regularized smooths the jump (width \
             epsilon), {scheme} time-stepping takes fixed steps that stick exactly; or keep \
             naive with a fixed step ({solver} rk4 {dt} H)"
        )
    })
}

/// The advice on a run that failed or ran out of steps, over `span` seconds of a problem
/// whose shortest natural period is `period`: [`unresolvable_period_warning`],
/// [`unstable_step_warning`] and [`naive_chatter_warning`], each where it applies.
pub fn failure_warnings(
    scheme: Scheme,
    step: StepControl,
    span: f64,
    period: Option<f64>,
    error: Option<&SolverError>,
) -> Vec<String> {
    unresolvable_period_warning(span, period, error)
        .into_iter()
        .chain(unstable_step_warning(scheme, step, error))
        .chain(naive_chatter_warning(scheme, step, error))
        .collect()
}

/// The advice given when a run with a fixed step diverged ([`scenarios::run::diverged`]): an
/// explicit solver (RK4, or Dormand–Prince with `--fixed-step`) past its stability limit, or
/// any other fixed-step scheme whose state left the system's reach (time-stepping with a
/// controller, whose force is held over each step).
pub fn unstable_step_warning(
    scheme: Scheme,
    step: StepControl,
    error: Option<&SolverError>,
) -> Option<String> {
    let explicit = scheme.solver().is_some_and(|s| !s.is_implicit());
    let StepControl::Fixed { h } = step else {
        return None;
    };
    let dt = field("dt");
    scenarios::run::diverged(explicit, step, error).then(|| match (explicit, scheme) {
        (true, _) => format!(
            "the explicit method diverged with the fixed step h = {} s: {}",
            ranges::show(h),
            unstable_step(&dt)
        ),
        (false, Scheme::TimeStepping { .. }) => format!(
            "the time-stepping scheme diverged with the step h = {} s: a controller's force is \
             held over each step (zero-order hold), and the sampled loop is unstable once h is \
             a fair fraction of the loop's natural period; a smaller {dt} avoids it",
            ranges::show(h)
        ),
        (false, _) => format!(
            "the method diverged with the fixed step h = {} s; a smaller {dt} or an adaptive \
             step avoids it",
            ranges::show(h)
        ),
    })
}

/// The line a study prints when a run of an explicit method diverged with its fixed step:
/// why, and what avoids it ([`unstable_step`] with the study's `option` for its steps).
pub fn diverged_line(option: &str) -> String {
    format!(
        "an explicit method diverged with a fixed step: {}",
        unstable_step(option)
    )
}

/// Why an explicit method with a fixed step diverges, and what avoids it: a smaller step in
/// `option`, or another solver.
pub fn unstable_step(option: &str) -> String {
    format!(
        "it is unstable once h times the problem's fastest rate (a stiff bristle, spring or \
         damper) passes its stability limit (about 2.8 for rk4, 3.3 for dopri5); a smaller \
         {option}, an adaptive solver (dopri5) or an implicit one (bdf) avoids it"
    )
}

/// The advice given for each `--set` of a friction parameter the run does not read
/// ([`check_read`]: one `model` does not list, or `epsilon` where `unread_epsilon` names the
/// treatment of v = 0 asked for, which does not read it).
/// Accepted, as a parameter file's are (a notebook may pass one set to many models), but said:
/// every value would give the same run.
pub fn unread_warnings(
    set: &[String],
    model: Option<ModelId>,
    unread_epsilon: Option<&str>,
) -> Vec<String> {
    set.iter()
        .filter_map(|s| s.split_once('=').map(|(name, _)| name.trim()))
        .filter_map(|name| check_read("set", name, model, unread_epsilon).err())
        .map(|e| e.marked())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use friction_models::FrictionParams;
    use scenarios::RunSpec;

    #[test]
    fn naive_switching_that_runs_out_of_steps_is_told_why_and_what_else_to_use() {
        // The belt with CS under naive switching and Dormand–Prince at the defaults: 1e7 steps
        // by t = 0.03 s, the step shrunk to 2.5e-9 s at the jump.
        let naive = Scheme::EventDriven {
            solver: integrators::Solver::DOPRI5,
            switching: Switching::Naive,
        };
        let spec = RunSpec {
            scheme: naive,
            limits: scenarios::Limits {
                max_steps: 2000,
                ..scenarios::Limits::default()
            },
            ..scenarios::stick_slip::belt_run(ModelId::Cs, &FrictionParams::paper())
        };
        let o = scenarios::run(&spec, &mut |_| {}).unwrap();
        let error = o.error.as_ref();
        assert!(
            matches!(error, Some(SolverError::TooManySteps { max: 2000, .. })),
            "{error:?}"
        );
        let warning = naive_chatter_warning(spec.scheme, spec.step, error).unwrap();
        assert!(
            warning.starts_with("naive switching steps blindly"),
            "{warning}"
        );
        assert!(warning.contains(&format!("{} event", field("switching"))));
        // Not for event switching, nor for a fixed step, nor for a run that did not lack steps.
        let adaptive = spec.step;
        assert_eq!(
            naive_chatter_warning(Scheme::events(integrators::Solver::DOPRI5), adaptive, error),
            None
        );
        let fixed = StepControl::Fixed { h: 1e-3 };
        assert_eq!(naive_chatter_warning(naive, fixed, error), None);
        let limit = SolverError::TimeLimit { t: 1.0, limit: 2.0 };
        assert_eq!(naive_chatter_warning(naive, adaptive, Some(&limit)), None);
        assert_eq!(naive_chatter_warning(naive, adaptive, None), None);
    }
}
