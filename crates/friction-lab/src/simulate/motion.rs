//! The line figures of a system's bodies, at most [`LINE_BODIES`] of those written, spread
//! over them ([`spread`]), one colour each: their velocities against time (`velocity.png`) and
//! their phase portraits, velocity against displacement (`phase-portrait.png`), where a
//! stick–slip cycle is a closed loop with a flat edge at the surface's speed. Every body's
//! velocity is in `velocity-space-time.png` (`space_time`).

use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use crate::window::Window;
use friction_systems::{BodyState, Run};
use std::path::Path;

/// Most bodies a line figure draws: more lines over a long run are no longer told apart.
pub const LINE_BODIES: usize = 4;

/// At most `most` of `bodies`, spread evenly over them: the first and the last, and between
/// them at equal steps of the list.
pub fn spread(bodies: &[usize], most: usize) -> Vec<usize> {
    let (n, k) = (bodies.len(), bodies.len().min(most));
    match k {
        0 | 1 => bodies[..k].to_vec(),
        _ => (0..k)
            .map(|j| bodies[(j * (n - 1) + (k - 1) / 2) / (k - 1)])
            .collect(),
    }
}

/// Adds `velocity`, `phase-portrait` and `friction-velocity` of the bodies `shown` (indices
/// into the system) of the `written` ones of `run` to `files`, in `out`, over `window`.
pub fn add_motion(
    files: &mut Artifacts,
    out: &Path,
    run: &Run,
    (shown, written): (&[usize], usize),
    title: &str,
    window: Option<Window>,
) -> Result<(), AppError> {
    let of = |what: &str| match shown.len() < written {
        true => format!(
            "{title}: {what} of {} of the {written} bodies written",
            shown.len()
        ),
        false => format!("{title}: {what}"),
    };
    let system = &run.problem.system;
    let states: Vec<_> = (shown.iter())
        .map(|&i| {
            let states: Vec<BodyState> = (run.body(i).into_iter())
                .filter(|b| Window::draws(window, b.t))
                .collect();
            (i, states)
        })
        .collect();
    let series = |point: &dyn Fn(&BodyState) -> (f64, f64)| {
        (states.iter().enumerate())
            .map(|(c, (i, states))| Series {
                label: Some(system.bodies[*i].name.clone()),
                points: states.iter().map(point).collect(),
                color: PALETTE[c],
                width: 2,
                marker: Marker::None,
                dash: body_dash(c),
            })
            .collect()
    };
    let plot = |what: &str, x_label: &str, y_label: &str, series| Plot {
        title: of(what),
        x_label: x_label.into(),
        y_label: y_label.into(),
        series,
        legend: Corner::UpperRight,
        log: false,
    };
    let v = "velocity v (m/s)";
    files.add_plot(
        &out.join("velocity"),
        &plot("velocities", "time t (s)", v, series(&|b| (b.t, b.v))),
    )?;
    files.add_plot(
        &out.join("phase-portrait"),
        &plot(
            "phase portraits",
            "displacement x (m)",
            v,
            series(&|b| (b.x, b.v)),
        ),
    )?;
    // Friction against the velocity relative to the body's surface (the floor's 0, a belt's
    // or a disc's own), for the bodies drawn that have a contact, in their colours above.
    let friction: Vec<Series> = (states.iter().enumerate())
        .filter_map(|(c, (i, states))| {
            let contact = system.contacts.iter().find(|k| k.body == *i)?;
            Some(Series {
                label: Some(system.bodies[*i].name.clone()),
                points: (states.iter())
                    .map(|b| (b.v - contact.surface_velocity, b.friction))
                    .collect(),
                color: PALETTE[c],
                width: 2,
                marker: Marker::None,
                dash: body_dash(c),
            })
        })
        .collect();
    files.add_plot(
        &out.join("friction-velocity"),
        &plot(
            "friction against relative velocity",
            "relative velocity v − v_surface (m/s)",
            "friction force F (N)",
            friction,
        ),
    )
}

/// The dash pattern of the `c`-th body drawn: a pattern as well as a colour, so that the bodies
/// are told apart in greyscale.
fn body_dash(c: usize) -> crate::plot::Dash {
    crate::plot::Dash::ALL[c % crate::plot::Dash::ALL.len()]
}

#[cfg(test)]
mod tests {
    use super::spread;

    #[test]
    fn the_bodies_drawn_are_spread_over_those_written() {
        let bodies: Vec<usize> = (0..20).collect();
        assert_eq!(spread(&bodies, 4), [0, 6, 13, 19]);
        assert_eq!(spread(&bodies[..3], 4), [0, 1, 2]);
        assert_eq!(spread(&[7], 4), [7]);
        assert_eq!(spread(&[], 4), Vec::<usize>::new());
        assert_eq!(spread(&[2, 4, 6, 8, 10], 2), [2, 10]);
    }
}
