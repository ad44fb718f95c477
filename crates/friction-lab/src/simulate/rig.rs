//! A rig's run: its files (trajectory, summary, events) and figures (time histories, phase
//! portrait, friction against velocity and against displacement, stiffness along the run, the
//! spectrum of the velocity).

use super::delivered::{made_of_record, Advice};
use super::spectra::{add_spectra, measured_span, no_spectrum_note, Measured, MIN_SPECTRUM_POINTS};
use super::stiffness::add_stiffness;
use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::laws::ModelChoice;
use crate::made::Made;
use crate::plot::{Corner, Marker, Plot, Series, BLUE};
use crate::progress::Progress;
use crate::run_record::{
    event_counts, Integrated, RunRecord, RunSetup, RunSummary, StiffnessSummary, RIG_BODY,
};
use crate::trajectory::{RecordAs, StepDoubling, Trajectory};
use crate::window::Window;
use friction_models::Parameters;
use friction_systems::{BodyState, ContactEvent};
use integrators::StepControl;
use scenarios::analysis::closed_loop::ClosedLoop;
use scenarios::run::Outcome;
use scenarios::{Law, RunSpec};
use std::path::Path;

/// The one run record of a rig's `outcome` (a system of one body, named `body`, and one
/// contact), described by `setup`, with what its closed loop did (a controlled rig).
fn rig_record(
    outcome: &Outcome,
    setup: RunSetup,
    closed_loop: Option<ClosedLoop>,
    step_doubling: Option<StepDoubling>,
) -> RunRecord {
    let state = |r: &scenarios::Row| BodyState {
        t: r.t,
        x: r.x,
        v: r.v,
        friction: r.friction,
        mode: Some(r.mode),
        z: r.z,
    };
    let events: Vec<ContactEvent> = outcome
        .events
        .iter()
        .map(|e| ContactEvent {
            t: e.t,
            contact: 0,
            body: 0,
            from: e.from,
            to: e.to,
        })
        .collect();
    let integrated = Integrated {
        error: outcome.error.clone(),
        t_reached: outcome.last().map(|r| r.t),
        event_counts: event_counts(&events),
        stats: outcome.stats.into(),
        wall_time_s: outcome.wall_time_s,
        energy_residual: outcome.energy.map(|e| e.residual),
        energy: outcome.energy,
        friction_work: outcome.friction_work,
        loop_area: outcome.loop_area,
        stiffness_detected_at: outcome.stiffness_detected_at,
        method_switches: outcome.method_switches.clone(),
        stiffness: StiffnessSummary::of(&outcome.stiffness),
        instability: outcome.instability,
        step_doubling,
        closed_loop,
    };
    RunRecord {
        summary: RunSummary::new(setup, integrated),
        bodies: vec![RIG_BODY.to_string()],
        trajectory: Trajectory::of_outcome(outcome),
        finals: outcome.last().map(state).into_iter().collect(),
        events,
    }
}

/// The error estimate of a fixed-step run that ended, by step doubling: the run `spec` again at
/// half its step, its trajectory against `outcome`'s ([`Trajectory::doubling_difference`]);
/// `None` for an adaptive step, a run that stopped, or a run at h/2 that stopped.
fn step_doubling(
    spec: &RunSpec,
    outcome: &Outcome,
    what: &str,
) -> Result<Option<StepDoubling>, AppError> {
    let StepControl::Fixed { h } = spec.step else {
        return Ok(None);
    };
    if outcome.error.is_some() {
        return Ok(None);
    }
    let t_end = spec.end_time();
    let bar = Progress::time(t_end, &format!("{what} at h/2 (its error estimate)"));
    let half = RunSpec {
        step: StepControl::Fixed { h: h / 2.0 },
        ..spec.clone()
    };
    let fine = scenarios::run(&half, &mut |t| bar.at(t)).map_err(AppError::from)?;
    bar.finish();
    Ok(match fine.error {
        Some(_) => None,
        None => Trajectory::of_outcome(outcome).doubling_difference(&Trajectory::of_outcome(&fine)),
    })
}

/// The rows a figure draws: the trajectory's, with the body just before each switch put
/// before the row at the switch, so that a jump of the friction is drawn where it happens (at
/// the switch's x, v and t) and not as a line from the last point before the switch.
fn drawn_rows(o: &Outcome) -> Vec<&scenarios::Row> {
    let mut before = o.before_switches.iter().peekable();
    let mut out = Vec::with_capacity(o.rows.len() + o.before_switches.len());
    for r in &o.rows {
        while let Some(b) = before.next_if(|b| b.t <= r.t) {
            out.push(b);
        }
        out.push(r);
    }
    out
}

/// The figures of a simulation over `window`: (file stem, plot). Friction is drawn against
/// the sliding velocity `v − v_surface` (a belt's speed subtracted; the body's v on the
/// floor).
fn figures(o: &Outcome, name: &str, window: Option<Window>) -> Vec<(&'static str, Plot)> {
    // A quantity of a row, given the surface velocity.
    type Pick = fn(&scenarios::Row, f64) -> f64;
    let sliding = if o.surface_velocity == 0.0 {
        "sliding velocity v (m/s)"
    } else {
        "sliding velocity v − v_surface (m/s)"
    };
    let specs: [(&str, &str, &str, &str, Pick, Pick); 6] = [
        (
            "history-x",
            "displacement",
            "time t (s)",
            "displacement x (m)",
            |r, _| r.t,
            |r, _| r.x,
        ),
        (
            "history-v",
            "velocity",
            "time t (s)",
            "velocity v (m/s)",
            |r, _| r.t,
            |r, _| r.v,
        ),
        (
            "history-friction",
            "friction force",
            "time t (s)",
            "friction force F (N)",
            |r, _| r.t,
            |r, _| r.friction,
        ),
        (
            "phase-portrait",
            "phase portrait",
            "displacement x (m)",
            "velocity v (m/s)",
            |r, _| r.x,
            |r, _| r.v,
        ),
        (
            "friction-velocity",
            "friction against sliding velocity",
            sliding,
            "friction force F (N)",
            |r, surface| r.v - surface,
            |r, _| r.friction,
        ),
        (
            "friction-displacement",
            "friction against displacement",
            "displacement x (m)",
            "friction force F (N)",
            |r, _| r.x,
            |r, _| r.friction,
        ),
    ];
    let rows: Vec<&scenarios::Row> = (drawn_rows(o).into_iter())
        .filter(|r| Window::draws(window, r.t))
        .collect();
    specs
        .into_iter()
        .map(|(stem, what, xl, yl, fx, fy)| {
            (
                stem,
                Plot {
                    title: format!("{name}: {what}"),
                    x_label: xl.into(),
                    y_label: yl.into(),
                    series: vec![Series {
                        label: None,
                        points: (rows.iter())
                            .map(|r| (fx(r, o.surface_velocity), fy(r, o.surface_velocity)))
                            .collect(),
                        color: BLUE,
                        width: 2,
                        marker: Marker::None,
                        dash: crate::plot::Dash::Solid,
                    }],
                    legend: Corner::default(),
                    log: false,
                },
            )
        })
        .collect()
}

/// The body's velocity over `window`, else over the last half of the run, at as many evenly
/// spaced times as it has recorded points there (at most [`scenarios::analysis::spectrum::MAX_SAMPLES`]),
/// interpolated linearly: a rig's recorded points are its output grid and its switches;
/// `None` for fewer than eight.
fn even_velocity(rows: &[scenarios::Row], window: Option<Window>) -> Option<Measured> {
    let (first, last) = (rows.first()?.t, rows.last()?.t);
    let (from, to) = measured_span(window, (first, last));
    let inside = rows.iter().filter(|r| (from..=to).contains(&r.t)).count();
    let n = inside.min(scenarios::analysis::spectrum::MAX_SAMPLES);
    if n < MIN_SPECTRUM_POINTS || to <= from {
        return None;
    }
    let dt = (to - from) / (n - 1) as f64;
    let mut k = 0;
    let v = (0..n)
        .map(|i| {
            let t = from + i as f64 * dt;
            while k + 2 < rows.len() && rows[k + 1].t <= t {
                k += 1;
            }
            let (a, b) = (&rows[k], &rows[(k + 1).min(rows.len() - 1)]);
            match b.t > a.t {
                true => a.v + (b.v - a.v) * ((t - a.t) / (b.t - a.t)).clamp(0.0, 1.0),
                false => b.v,
            }
        })
        .collect();
    Some(Measured {
        from,
        to,
        dt,
        bodies: vec![(RIG_BODY.to_string(), v)],
    })
}

/// Simulates the rig of `spec` with `model` (the law of `spec`, named) and its files into
/// `out`, in memory: `trajectory.csv` (or its columns), `summary.json`, `events.csv`, the
/// time histories, phase portrait and friction curves and the stiffness along the run (over
/// `window` where one is given), and the spectrum of the velocity (over `window`, else the
/// last half). The warnings are the run's: its stiffness, a step too coarse for its time
/// scale, why it failed.
pub fn simulate_rig(
    spec: &RunSpec,
    model: &ModelChoice,
    out: &Path,
    record_as: RecordAs,
    window: Option<Window>,
) -> Result<Made, AppError> {
    let t_end = spec.end_time();
    let method = spec.scheme.method_name();
    let what = format!("{} {model} {method}", spec.scenario);
    let bar = Progress::time(t_end, &what);
    let outcome = scenarios::run_measuring_stiffness(spec, &mut |t| {
        if t_end > 0.0 {
            bar.at(t);
        }
    })
    .map_err(AppError::from)?;
    bar.finish();
    let step_doubling = step_doubling(spec, &outcome, &what)?;

    let name = format!(
        "{} with {model} ({method}, {} switching{})",
        spec.scenario,
        spec.scheme.treatment_name(),
        Window::note(window)
    );
    let mut files = Artifacts::default();
    for (stem, p) in figures(&outcome, &name, window) {
        files.add_plot(&out.join(stem), &p)?;
    }
    add_stiffness(&mut files, out, &outcome.stiffness, &name, window)?;
    let spectra = match even_velocity(&outcome.rows, window) {
        Some(measured) => add_spectra(&mut files, out, &measured, &name)?,
        None => vec![no_spectrum_note(window)],
    };
    let mut parameters = model.parameters_read(&spec.friction);
    for &p in spec.scenario.parameters() {
        let value = spec.params.value(p).expect("scenario parameters exist");
        parameters.insert(p.to_string(), value);
    }
    parameters.extend(spec.scheme.parameter().map(|(k, v)| (k.to_string(), v)));
    let setup = RunSetup {
        system: spec.scenario.name().to_string(),
        model: Some(model.name().to_string()),
        variant: match spec.law {
            Law::Catalog { variant, .. } => Some(variant),
            Law::Own(_) => None,
        },
        n_bodies: 1,
        n_contacts: 1,
        scheme: spec.scheme.name(),
        solver: method,
        switching: spec.scheme.treatment_name(),
        step: spec.step,
        t_end,
        parameters,
    };
    let closed_loop = ClosedLoop::of_outcome(&outcome);
    let record = rig_record(&outcome, setup, closed_loop, step_doubling);
    let advice = Advice {
        scheme: spec.scheme,
        period: outcome.natural_period,
        own: None,
    };
    let notes = (closed_loop.iter().map(|c| c.to_string()))
        .chain(spectra)
        .collect();
    made_of_record(record, files, out, record_as, advice, notes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use friction_models::{FrictionParams, ModelId};
    use scenarios::RunSpec;

    #[test]
    fn a_figure_draws_each_switch_as_a_jump_at_the_switch() {
        // The belt's stick–slip with the paper's CVS, output every 10 ms: at a re-stick the
        // friction jumps from about −7.5 N to the holding force. Drawn from the trajectory
        // alone, the line ran from the last point of the slip phase to the point at the switch,
        // through states that never were.
        let spec = RunSpec {
            t_end: Some(20.0),
            output_points: 2001,
            ..scenarios::stick_slip::belt_run(ModelId::Cvs, &FrictionParams::paper())
        };
        let o = scenarios::run(&spec, &mut |_| {}).unwrap();
        let drawn = drawn_rows(&o);
        let switches = o.rows.windows(2).filter(|w| w[0].mode != w[1].mode).count();
        assert!(switches >= 30, "{switches} switches");
        assert_eq!(o.before_switches.len(), switches);
        assert_eq!(drawn.len(), o.rows.len() + switches);
        // Every change of mode between two drawn points is at one instant and one state.
        for w in drawn.windows(2) {
            if w[0].mode != w[1].mode {
                assert_eq!((w[0].t, w[0].x, w[0].v), (w[1].t, w[1].x, w[1].v));
            }
        }
        // The friction before a re-stick is CVS's at v_rel = 0⁻: −(F_c + C2) = −7.5 N.
        let p = FrictionParams::paper();
        for b in o
            .before_switches
            .iter()
            .filter(|b| b.mode != friction_systems::STICK)
        {
            assert!((b.friction + p.f_c + p.c2).abs() < 1e-9, "{b:?}");
        }
    }
}
