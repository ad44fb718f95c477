//! A run's errors against its reference, each in its own quantity and unit: the position
//! x (m), the velocity v (m/s) and a law's internal state z (m), absolute and relative to the
//! solution's scale in that quantity; the residual of the run's own energy balance (J); the
//! times of events and the durations of stick phases (s). An error that does not exist for a
//! run is NaN, written as an empty cell and JSON `null`, never 0 (which would read as exact).

use crate::cases::Measures;
pub use crate::quantity::Quantity;
use serde::Serialize;

/// The solution's scale in each quantity: the largest |x|, |v| and |z| of the reference over
/// the time grid and at the end, the measure of "relative". NaN for a quantity the solution
/// does not have (z without internal states).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Scales {
    /// Largest |x|, m.
    pub x: f64,
    /// Largest |v|, m/s.
    pub v: f64,
    /// Largest |z|, m.
    pub z: f64,
}

impl Scales {
    /// The scales of `reference`'s solution.
    pub fn of(reference: &Measures) -> Scales {
        let largest = |q: Quantity| {
            let grid = (reference.grid.iter())
                .flat_map(|row| row.iter().zip(&reference.quantities))
                .filter(|(_, &c)| c == q)
                .map(|(y, _)| y.abs());
            let last = (reference.final_state.iter())
                .zip(&reference.final_quantities)
                .filter(|(_, &c)| c == q)
                .map(|(y, _)| y.abs());
            grid.chain(last).fold(f64::NAN, f64::max)
        };
        Scales {
            x: largest(Quantity::Position),
            v: largest(Quantity::Velocity),
            z: largest(Quantity::InternalState),
        }
    }

    /// The scale of quantity `q`.
    pub fn of_quantity(&self, q: Quantity) -> f64 {
        match q {
            Quantity::Position => self.x,
            Quantity::Velocity => self.v,
            Quantity::InternalState => self.z,
        }
    }
}

/// Errors of a run against the reference (see the module).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct Errors {
    /// The largest relative error at the end: max over every body's x, v, z of
    /// |Δ(t_end)| / the solution's scale in that quantity ([`Scales`]); dimensionless.
    pub final_relative: f64,
    /// The largest relative error on the common time grid: max over the measured bodies' x,
    /// v, z and the grid's times of |Δ(t)| / the solution's scale in that quantity;
    /// dimensionless. The error the work–precision and stiffness studies plot and target.
    pub grid_relative: f64,
    /// max |Δx| on the grid over the measured bodies, m.
    pub x: f64,
    /// max |Δv| on the grid over the measured bodies, m/s.
    pub v: f64,
    /// max |Δz| on the grid over the measured bodies, m (NaN without internal states).
    pub z: f64,
    /// `x` over the solution's largest |x|.
    pub x_relative: f64,
    /// `v` over the solution's largest |v|.
    pub v_relative: f64,
    /// `z` over the solution's largest |z|.
    pub z_relative: f64,
    /// |residual| of the run's own energy balance
    /// `Δ(kinetic + spring) − W_ext − W_belt + D`, J (NaN where the run keeps none: the
    /// prescribed motions).
    pub energy: f64,
    /// `energy` over the balance's largest term.
    pub energy_relative: f64,
    /// max |Δt| over the events, s: NaN when there are none (a regularised run, LuGre) or
    /// when the numbers of events differ.
    pub event_times: f64,
    /// max |Δ| over the stick durations, s: NaN when there are no stick phases or when their
    /// numbers differ.
    pub stick_durations: f64,
}

/// One of a run's errors against its reference ([`Errors`]), by the name the study files give
/// it (the runs' tables prefix `error_`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorMeasure {
    /// [`Errors::final_relative`].
    FinalRelative,
    /// [`Errors::grid_relative`].
    GridRelative,
    /// [`Errors::x`].
    X,
    /// [`Errors::v`].
    V,
    /// [`Errors::z`].
    Z,
    /// [`Errors::x_relative`].
    XRelative,
    /// [`Errors::v_relative`].
    VRelative,
    /// [`Errors::z_relative`].
    ZRelative,
    /// [`Errors::energy`].
    Energy,
    /// [`Errors::energy_relative`].
    EnergyRelative,
    /// [`Errors::event_times`].
    EventTimes,
    /// [`Errors::stick_durations`].
    StickDurations,
}

impl ErrorMeasure {
    /// Every measure, in the order the runs' tables list them.
    pub const ALL: [ErrorMeasure; 12] = [
        ErrorMeasure::FinalRelative,
        ErrorMeasure::GridRelative,
        ErrorMeasure::X,
        ErrorMeasure::V,
        ErrorMeasure::Z,
        ErrorMeasure::XRelative,
        ErrorMeasure::VRelative,
        ErrorMeasure::ZRelative,
        ErrorMeasure::Energy,
        ErrorMeasure::EnergyRelative,
        ErrorMeasure::EventTimes,
        ErrorMeasure::StickDurations,
    ];

    /// The measures a convergence study fits orders to: the two relative errors of the
    /// state, the event times and the stick durations.
    pub const ORDERED: [ErrorMeasure; 4] = [
        ErrorMeasure::FinalRelative,
        ErrorMeasure::GridRelative,
        ErrorMeasure::EventTimes,
        ErrorMeasure::StickDurations,
    ];

    /// The name the study files give it.
    pub fn name(self) -> &'static str {
        match self {
            ErrorMeasure::FinalRelative => "final_relative",
            ErrorMeasure::GridRelative => "grid_relative",
            ErrorMeasure::X => "x",
            ErrorMeasure::V => "v",
            ErrorMeasure::Z => "z",
            ErrorMeasure::XRelative => "x_relative",
            ErrorMeasure::VRelative => "v_relative",
            ErrorMeasure::ZRelative => "z_relative",
            ErrorMeasure::Energy => "energy",
            ErrorMeasure::EnergyRelative => "energy_relative",
            ErrorMeasure::EventTimes => "event_times",
            ErrorMeasure::StickDurations => "stick_durations",
        }
    }

    /// Its unit (`1` for a relative error).
    pub fn unit(self) -> &'static str {
        match self {
            ErrorMeasure::X | ErrorMeasure::Z => "m",
            ErrorMeasure::V => "m/s",
            ErrorMeasure::Energy => "J",
            ErrorMeasure::EventTimes | ErrorMeasure::StickDurations => "s",
            _ => "1",
        }
    }

    /// Its name with its unit, short enough for an axis: the definitions are the fields'
    /// of [`Errors`] (and docs/studies.md's table of measures).
    pub fn label(self) -> &'static str {
        match self {
            ErrorMeasure::FinalRelative => "relative error at t_end (1)",
            ErrorMeasure::GridRelative => "relative error on the grid (1)",
            ErrorMeasure::X => "error in x, max |Δx| (m)",
            ErrorMeasure::V => "error in v, max |Δv| (m/s)",
            ErrorMeasure::Z => "error in z, max |Δz| (m)",
            ErrorMeasure::XRelative => "relative error in x (1)",
            ErrorMeasure::VRelative => "relative error in v (1)",
            ErrorMeasure::ZRelative => "relative error in z (1)",
            ErrorMeasure::Energy => "energy-balance residual (J)",
            ErrorMeasure::EnergyRelative => "relative energy residual (1)",
            ErrorMeasure::EventTimes => "error of event times (s)",
            ErrorMeasure::StickDurations => "error of stick durations (s)",
        }
    }

    /// The scale an error of this measure is judged against (round-off, no correct digit):
    /// 1 for a relative error, the span `t_end` for a time, the solution's scale for an
    /// absolute error of the state, NaN for the energy residual (whose relative twin is the
    /// one to judge by).
    pub fn scale(self, scales: &Scales, t_end: f64) -> f64 {
        match self {
            ErrorMeasure::X => scales.x,
            ErrorMeasure::V => scales.v,
            ErrorMeasure::Z => scales.z,
            ErrorMeasure::Energy => f64::NAN,
            ErrorMeasure::EventTimes | ErrorMeasure::StickDurations => t_end,
            _ => 1.0,
        }
    }

    /// Its value among `errors`.
    pub fn of(self, errors: &Errors) -> f64 {
        let e = errors;
        match self {
            ErrorMeasure::FinalRelative => e.final_relative,
            ErrorMeasure::GridRelative => e.grid_relative,
            ErrorMeasure::X => e.x,
            ErrorMeasure::V => e.v,
            ErrorMeasure::Z => e.z,
            ErrorMeasure::XRelative => e.x_relative,
            ErrorMeasure::VRelative => e.v_relative,
            ErrorMeasure::ZRelative => e.z_relative,
            ErrorMeasure::Energy => e.energy,
            ErrorMeasure::EnergyRelative => e.energy_relative,
            ErrorMeasure::EventTimes => e.event_times,
            ErrorMeasure::StickDurations => e.stick_durations,
        }
    }
}

impl std::fmt::Display for ErrorMeasure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.name())
    }
}

/// max |a_i − b_i|; NaN (undefined) when the lengths differ.
fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    if a.len() != b.len() {
        return f64::NAN;
    }
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// [`max_diff`] of lists of things that may not exist at all (events, stick phases): NaN
/// where neither list has any, as where their lengths differ.
fn max_diff_of_some(a: &[f64], b: &[f64]) -> f64 {
    if a.is_empty() && b.is_empty() {
        return f64::NAN;
    }
    max_diff(a, b)
}

/// The largest |Δ| of each quantity between rows of `quantities` (x, v, z), NaN for a
/// quantity no column holds.
fn by_quantity<'a>(
    rows: impl Iterator<Item = (&'a [f64], &'a [f64])>,
    quantities: &[Quantity],
) -> [f64; 3] {
    let mut largest = [f64::NAN; 3];
    let slot = |q: Quantity| match q {
        Quantity::Position => 0,
        Quantity::Velocity => 1,
        Quantity::InternalState => 2,
    };
    for (a, b) in rows {
        for ((y, r), &q) in a.iter().zip(b).zip(quantities) {
            let e = &mut largest[slot(q)];
            *e = e.max((y - r).abs());
        }
    }
    largest
}

impl Errors {
    /// Not measured (yet): every error NaN.
    pub const UNMEASURED: Errors = Errors {
        final_relative: f64::NAN,
        grid_relative: f64::NAN,
        x: f64::NAN,
        v: f64::NAN,
        z: f64::NAN,
        x_relative: f64::NAN,
        v_relative: f64::NAN,
        z_relative: f64::NAN,
        energy: f64::NAN,
        energy_relative: f64::NAN,
        event_times: f64::NAN,
        stick_durations: f64::NAN,
    };

    /// The errors of `m` against `reference`. The state's errors are NaN where the two do
    /// not hold the same quantities on the same grid (a run that stopped early).
    pub fn between(m: &Measures, reference: &Measures) -> Errors {
        let scales = Scales::of(reference);
        let same_grid = m.grid.len() == reference.grid.len()
            && m.quantities == reference.quantities
            && m.grid.iter().all(|row| row.len() == m.quantities.len());
        let [x, v, z] = match same_grid {
            true => by_quantity(
                (m.grid.iter().zip(&reference.grid)).map(|(a, b)| (&a[..], &b[..])),
                &m.quantities,
            ),
            false => [f64::NAN; 3],
        };
        let same_end = m.final_quantities == reference.final_quantities
            && m.final_state.len() == reference.final_state.len();
        let at_end = match same_end {
            true => by_quantity(
                std::iter::once((&m.final_state[..], &reference.final_state[..])),
                &m.final_quantities,
            ),
            false => [f64::NAN; 3],
        };
        let relative = |e: [f64; 3]| -> [f64; 3] {
            let s = [scales.x, scales.v, scales.z];
            [0, 1, 2].map(|i| match s[i] > 0.0 {
                true => e[i] / s[i],
                false => f64::NAN,
            })
        };
        let largest = |e: [f64; 3]| e.iter().copied().fold(f64::NAN, f64::max);
        let [x_relative, v_relative, z_relative] = relative([x, v, z]);
        let (energy, energy_relative) = m.energy.map_or((f64::NAN, f64::NAN), |b| {
            (b.residual.abs(), b.relative_residual)
        });
        Errors {
            final_relative: largest(relative(at_end)),
            grid_relative: largest([x_relative, v_relative, z_relative]),
            x,
            v,
            z,
            x_relative,
            v_relative,
            z_relative,
            energy,
            energy_relative,
            event_times: max_diff_of_some(&m.event_times, &reference.event_times),
            stick_durations: max_diff_of_some(&m.stick_durations, &reference.stick_durations),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use friction_systems::EnergyBalance;
    use Quantity::{InternalState as Z, Position as X, Velocity as V};

    /// A one-body run of a law with an internal state: rows (x, v, z).
    fn measures(grid: Vec<Vec<f64>>, energy: Option<EnergyBalance>) -> Measures {
        Measures {
            final_state: grid.last().unwrap().clone(),
            final_quantities: vec![X, V, Z],
            grid,
            quantities: vec![X, V, Z],
            energy,
            ..Measures::default()
        }
    }

    #[test]
    fn each_quantity_has_its_own_error_and_scale() {
        // The reference moves 2 m at up to 0.5 m/s with bristles of up to 1e-5 m.
        let reference = measures(vec![vec![0.0, 0.5, 1e-5], vec![2.0, -0.1, -4e-6]], None);
        let balance = EnergyBalance {
            residual: -3e-4,
            relative_residual: 2e-3,
            ..EnergyBalance::default()
        };
        let run = measures(
            vec![vec![0.0, 0.5, 1e-5], vec![2.01, -0.2, -3e-6]],
            Some(balance),
        );
        let e = Errors::between(&run, &reference);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
        assert!(
            close(e.x, 0.01) && close(e.v, 0.1) && close(e.z, 1e-6),
            "{e:?}"
        );
        assert!(close(e.x_relative, 0.005), "{e:?}");
        assert!(close(e.v_relative, 0.2), "{e:?}");
        assert!(close(e.z_relative, 0.1), "{e:?}");
        // The largest relative error is v's, whatever the units of the absolute errors.
        assert!(close(e.grid_relative, 0.2), "{e:?}");
        // At the end: x 0.01/2, v 0.1/0.5, z 1e-6/1e-5.
        assert!(close(e.final_relative, 0.2), "{e:?}");
        assert!(
            close(e.energy, 3e-4) && close(e.energy_relative, 2e-3),
            "{e:?}"
        );
        assert!(e.event_times.is_nan() && e.stick_durations.is_nan());
    }

    #[test]
    fn a_quantity_the_run_does_not_have_has_no_error() {
        let two = |v: f64| Measures {
            final_state: vec![1.0, v],
            final_quantities: vec![X, V],
            grid: vec![vec![1.0, v]],
            quantities: vec![X, V],
            ..Measures::default()
        };
        let e = Errors::between(&two(0.3), &two(0.2));
        assert!(
            e.z.is_nan() && e.z_relative.is_nan() && e.energy.is_nan(),
            "{e:?}"
        );
        assert!((e.grid_relative - 0.5).abs() < 1e-12, "{e:?}");
        // A run that stopped early holds fewer grid rows: its state's errors are undefined.
        let mut short = two(0.3);
        short.grid.clear();
        let e = Errors::between(&short, &two(0.2));
        assert!(e.x.is_nan() && e.grid_relative.is_nan(), "{e:?}");
    }

    #[test]
    fn every_measure_names_its_unit() {
        for m in ErrorMeasure::ALL {
            assert!(
                m.label().ends_with(&format!("({})", m.unit())),
                "{m}: {}",
                m.label()
            );
        }
        assert_eq!(ErrorMeasure::V.unit(), "m/s");
        assert_eq!(ErrorMeasure::Energy.unit(), "J");
    }
}
