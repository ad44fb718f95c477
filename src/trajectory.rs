//! A run's trajectory as columns of numbers: what `trajectory.csv` holds, for a front end that
//! takes the numbers themselves (Python builds its arrays from them, with no text between).

use friction_systems::{mode_name, Run};
use scenarios::Outcome;

/// Where `simulate` puts a run's trajectory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TrajectoryAs {
    /// `trajectory.csv`, among the files (the command line).
    File,
    /// [`Trajectory`]'s columns, and no file (Python).
    Columns,
}

/// The rows of `trajectory.csv` as columns: point by point, and within a point of a system body
/// by body (the bodies written, in [`Trajectory::bodies`]' order).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trajectory {
    /// The output times, s, one per point.
    pub t: Vec<f64>,
    /// A system's bodies written, by name, in column order; `None` for a rig (one body).
    pub bodies: Option<Vec<String>>,
    /// Displacement, m, per row.
    pub x: Vec<f64>,
    /// Velocity, m/s, per row.
    pub v: Vec<f64>,
    /// The force the contact exerts on the body along +x, N, per row.
    pub friction: Vec<f64>,
    /// The contact's mode per row (`slip+`, `slip-`, `stick`; `none` for a body without a
    /// contact).
    pub mode: Vec<&'static str>,
    /// The internal state per row (NaN for a body whose model has none), where any model has
    /// one; `None` otherwise.
    pub z: Option<Vec<f64>>,
}

impl Trajectory {
    /// A rig's rows; `has_state` when its model has an internal state.
    pub fn of_outcome(o: &Outcome, has_state: bool) -> Trajectory {
        let column = |f: fn(&scenarios::Row) -> f64| o.rows.iter().map(f).collect();
        Trajectory {
            t: column(|r| r.t),
            bodies: None,
            x: column(|r| r.x),
            v: column(|r| r.v),
            friction: column(|r| r.friction),
            mode: o.rows.iter().map(|r| r.mode).collect(),
            z: has_state.then(|| column(|r| r.z.unwrap_or(f64::NAN))),
        }
    }

    /// A system's rows for `bodies`, at every recorded point.
    pub fn of_run(run: &Run, bodies: &[usize]) -> Trajectory {
        let points = run.solution.len();
        let rows = points * bodies.len();
        let states = run.problem.layout.has_states();
        let mut t = Trajectory {
            t: run.solution.t.clone(),
            bodies: Some(
                bodies
                    .iter()
                    .map(|&i| run.problem.system.bodies[i].name.clone())
                    .collect(),
            ),
            x: Vec::with_capacity(rows),
            v: Vec::with_capacity(rows),
            friction: Vec::with_capacity(rows),
            mode: Vec::with_capacity(rows),
            z: states.then(|| Vec::with_capacity(rows)),
        };
        for k in 0..points {
            for &i in bodies {
                let b = run.body_at(i, k);
                t.x.push(b.x);
                t.v.push(b.v);
                t.friction.push(b.friction);
                t.mode.push(b.mode.map_or("none", mode_name));
                if let Some(z) = &mut t.z {
                    z.push(b.z.unwrap_or(f64::NAN));
                }
            }
        }
        t
    }
}
