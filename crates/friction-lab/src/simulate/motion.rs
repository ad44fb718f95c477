//! The figures of a system's drawn bodies (the first [`super::DRAWN_BODIES`] written), one
//! colour each: their velocities against time (`velocity.png`) and their phase portraits,
//! velocity against displacement (`phase-portrait.png`), where a stick–slip cycle is a closed
//! loop with a flat edge at the surface's speed.

use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use friction_systems::{Run, System};
use std::path::Path;

/// Adds `velocity` and `phase-portrait` of the first `drawn` of `bodies` (indices into
/// `system`) of `run` to `files`, in `out`.
pub fn add_motion(
    files: &mut Artifacts,
    out: &Path,
    run: &Run,
    system: &System,
    bodies: &[usize],
    drawn: usize,
    title: &str,
) -> Result<(), AppError> {
    let of = |what: &str| match drawn < bodies.len() {
        true => format!(
            "{title}: {what} of the first {drawn} of {} bodies written",
            bodies.len()
        ),
        false => format!("{title}: {what}"),
    };
    let states: Vec<_> = bodies[..drawn].iter().map(|&i| (i, run.body(i))).collect();
    let series = |point: &dyn Fn(&friction_systems::BodyState) -> (f64, f64)| {
        (states.iter().enumerate())
            .map(|(c, (i, states))| Series {
                label: Some(system.bodies[*i].name.clone()),
                points: states.iter().map(point).collect(),
                color: PALETTE[c],
                width: 2,
                marker: Marker::None,
            })
            .collect()
    };
    let velocity = Plot {
        title: of("velocities"),
        x_label: "time t (s)".into(),
        y_label: "velocity v (m/s)".into(),
        series: series(&|b| (b.t, b.v)),
        legend: Corner::UpperRight,
        log: false,
    };
    files.add_plot(&out.join("velocity"), &velocity)?;
    let phase = Plot {
        title: of("phase portraits"),
        x_label: "displacement x (m)".into(),
        y_label: "velocity v (m/s)".into(),
        series: series(&|b| (b.x, b.v)),
        legend: Corner::UpperRight,
        log: false,
    };
    files.add_plot(&out.join("phase-portrait"), &phase)
}
