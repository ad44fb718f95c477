//! A run's trajectory as columns of numbers: what `trajectory.csv` holds, for a front end that
//! takes the numbers themselves (Python builds its arrays from them, with no text between).

use crate::error::AppError;
use crate::output::{csv_error, csv_number};
use friction_systems::{mode_name, Run};
use integrators::Mode;
use scenarios::Outcome;
use std::path::Path;

/// How `simulate` hands over a run's record (its summary, trajectory, final states and
/// events).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RecordAs {
    /// As files among the others (`summary.json`, `trajectory.csv`, `final.csv`,
    /// `events.csv`): the command line.
    Files,
    /// As values ([`crate::run_record::RunValues`]), and no file of it: a front end that
    /// makes its own arrays and tables of them (Python).
    Values,
}

/// The error estimate of a fixed-step run by step doubling
/// ([`Trajectory::doubling_difference`]): the largest difference from the same run at half the
/// step, relative to the solution's scale in that quantity, and where it lies.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct StepDoubling {
    /// |y_h − y_{h/2}| over the largest |y_{h/2}| in that quantity.
    pub relative: f64,
    /// The time where it is largest, s.
    pub t: f64,
    /// `x` or `v`.
    pub quantity: &'static str,
    /// The body, for a system (`None` for a rig's one body).
    pub body: Option<String>,
}

/// A fixed-step run whose step-doubling estimate ([`StepDoubling::relative`]) exceeds this is
/// `inaccurate`: an error above a tenth of the solution's scale.
pub const STEP_DOUBLING_INACCURATE: f64 = 0.1;

impl StepDoubling {
    /// Why the run is `inaccurate`, where the estimate exceeds [`STEP_DOUBLING_INACCURATE`].
    pub fn reason(&self, h: f64) -> Option<String> {
        (self.relative > STEP_DOUBLING_INACCURATE).then(|| {
            let body = self
                .body
                .as_ref()
                .map_or(String::new(), |b| format!(" of body \"{b}\""));
            format!(
                "its error estimated by step doubling, the largest difference of {}{body} from \
                 the same run at h/2 = {} s over the solution's scale, is {:.3} at t = {} s \
                 (above {STEP_DOUBLING_INACCURATE})",
                self.quantity,
                crate::ranges::show(h / 2.0),
                self.relative,
                crate::ranges::show(self.t),
            )
        })
    }
}

/// The columns of a run compared by [`step_doubling`]: times, and x and v point by point
/// (within a point body by body).
pub type Columns<'a> = (&'a [f64], &'a [f64], &'a [f64]);

/// The largest difference between `coarse`, a run at a fixed step h, and `fine`, the same run
/// at h/2, at the times both recorded (the output grid; an event's points are left out where
/// the other run has none at that time), `width` bodies a point, named `bodies` (`None` for a
/// rig's one): per quantity (x, v) over the largest |value| of `fine` in it, every body alike.
/// To leading order it is the error of the run at h (the error of h/2 is 2^−p of it for a
/// method of order p, so the estimate is within a factor 2^p/(2^p − 1) ≤ 2 of the truth).
/// `None` where no time is shared or a scale is zero.
pub fn step_doubling(
    coarse: Columns,
    fine: Columns,
    width: usize,
    bodies: Option<&[String]>,
) -> Option<StepDoubling> {
    let scale = |values: &[f64]| values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let scales = [("x", scale(fine.1)), ("v", scale(fine.2))];
    if width == 0 || scales.iter().any(|(_, s)| *s <= 0.0 || s.is_nan()) {
        return None;
    }
    let mut worst: Option<StepDoubling> = None;
    let mut j = 0;
    for (k, &t) in coarse.0.iter().enumerate() {
        while j < fine.0.len() && fine.0[j] < t {
            j += 1;
        }
        if j == fine.0.len() || fine.0[j] != t {
            continue;
        }
        for b in 0..width {
            let (mine, theirs) = (k * width + b, j * width + b);
            let pairs = [
                (coarse.1[mine], fine.1[theirs], scales[0]),
                (coarse.2[mine], fine.2[theirs], scales[1]),
            ];
            for (a, b_value, (quantity, scale)) in pairs {
                let relative = (a - b_value).abs() / scale;
                if worst.as_ref().is_none_or(|w| relative > w.relative) {
                    worst = Some(StepDoubling {
                        relative,
                        t,
                        quantity,
                        body: bodies.map(|names| names[b].clone()),
                    });
                }
            }
        }
    }
    worst
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
    /// The contact's mode per row (`None` for a body without a contact; written `slip+`,
    /// `slip-`, `stick` and `none`).
    pub mode: Vec<Option<Mode>>,
    /// The internal state per row (NaN for a body whose model has none), where any model has
    /// one; `None` otherwise.
    pub z: Option<Vec<f64>>,
}

impl Trajectory {
    /// A rig's rows, with `z` where its law has an internal state.
    pub fn of_outcome(o: &Outcome) -> Trajectory {
        let column = |f: fn(&scenarios::Row) -> f64| o.rows.iter().map(f).collect();
        Trajectory {
            t: column(|r| r.t),
            bodies: None,
            x: column(|r| r.x),
            v: column(|r| r.v),
            friction: column(|r| r.friction),
            mode: o.rows.iter().map(|r| Some(r.mode)).collect(),
            z: o.has_state.then(|| column(|r| r.z.unwrap_or(f64::NAN))),
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
                t.mode.push(b.mode);
                if let Some(z) = &mut t.z {
                    z.push(b.z.unwrap_or(f64::NAN));
                }
            }
        }
        t
    }

    /// The largest difference between this trajectory, of a fixed step h, and `fine`, the same
    /// run at h/2 ([`step_doubling`]); `None` where the two have different bodies.
    pub fn doubling_difference(&self, fine: &Trajectory) -> Option<StepDoubling> {
        if self.width() != fine.width() {
            return None;
        }
        let names = self.bodies.as_deref();
        step_doubling(
            (&self.t, &self.x, &self.v),
            (&fine.t, &fine.x, &fine.v),
            self.width(),
            names,
        )
    }

    /// The number of bodies per point: a system's bodies written, or a rig's one.
    fn width(&self) -> usize {
        self.bodies.as_ref().map_or(1, Vec::len)
    }

    /// `trajectory.csv`: `t`, for a system `body`, then `x`, `v`, `friction`, `mode` and, where
    /// a model has one, `z` (an empty cell for a body whose model has none). Written row by
    /// row from the columns, so that a long run needs no table of cells beside them; a
    /// non-finite number is refused, naming its row and column.
    pub fn to_csv(&self, path: &Path) -> Result<Vec<u8>, AppError> {
        let io = csv_error(path);
        let mut header = vec!["t"];
        if self.bodies.is_some() {
            header.push("body");
        }
        header.extend(["x", "v", "friction", "mode"]);
        if self.z.is_some() {
            header.push("z");
        }
        let mut w = csv::Writer::from_writer(Vec::new());
        w.write_record(&header).map_err(&io)?;
        let width = self.width();
        let mut record: Vec<String> = Vec::with_capacity(header.len());
        for row in 0..self.x.len() {
            let number = |column: &str, x: f64| csv_number(path, column, row, x);
            record.clear();
            record.push(number("t", self.t[row / width])?);
            if let Some(bodies) = &self.bodies {
                record.push(bodies[row % width].clone());
            }
            record.push(number("x", self.x[row])?);
            record.push(number("v", self.v[row])?);
            record.push(number("friction", self.friction[row])?);
            record.push(self.mode[row].map_or("none", mode_name).to_string());
            if let Some(z) = &self.z {
                record.push(if z[row].is_nan() {
                    String::new()
                } else {
                    number("z", z[row])?
                });
            }
            w.write_record(&record).map_err(&io)?;
        }
        w.into_inner().map_err(|e| io(e.into_error().into()))
    }
}
