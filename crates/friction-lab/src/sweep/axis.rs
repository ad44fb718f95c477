//! The axes of a sweep's grid: their text forms (a list, an even range, a log range) and the
//! grid as their product.

use crate::error::AppError;
use serde::Serialize;

/// Most values on one axis.
pub const MAX_AXIS: usize = 1000;
/// Most points in a grid.
pub const MAX_POINTS: usize = 100_000;

/// One axis of the grid.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Axis {
    /// The parameter.
    pub name: String,
    /// Its values, in order.
    pub values: Vec<f64>,
}

/// An axis from its text ([`Axis::parse`]).
impl std::str::FromStr for Axis {
    type Err = String;
    fn from_str(text: &str) -> Result<Axis, String> {
        Axis::parse(text).map_err(|e| e.to_string())
    }
}

impl Axis {
    /// Parses `NAME=V1,V2`, `NAME=START:STOP:COUNT` or `NAME=log:START:STOP:COUNT`.
    pub fn parse(text: &str) -> Result<Axis, AppError> {
        let bad = |why: String| {
            let grid = crate::error::field("grid");
            AppError::Usage(format!("option `{grid}` = `{text}`: {why}"))
        };
        let (name, values) = text
            .split_once('=')
            .ok_or_else(|| bad("expected NAME=VALUES".into()))?;
        let number = |s: &str| -> Result<f64, AppError> {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(format!("`{s}` is not a finite number")))
        };
        let (log, range) = match values.strip_prefix("log:") {
            Some(rest) => (true, Some(rest)),
            None => (false, values.contains(':').then_some(values)),
        };
        let values: Vec<f64> = match range {
            Some(r) => {
                let parts: Vec<&str> = r.split(':').collect();
                let [start, stop, count] = parts[..] else {
                    return Err(bad("a range is START:STOP:COUNT".into()));
                };
                let (start, stop) = (number(start)?, number(stop)?);
                let count = count
                    .trim()
                    .parse::<usize>()
                    .ok()
                    .filter(|c| (1..=MAX_AXIS).contains(c))
                    .ok_or_else(|| {
                        bad(format!(
                            "COUNT `{count}` is out of range: allowed [1, {MAX_AXIS}]"
                        ))
                    })?;
                if log && !(start > 0.0 && stop > 0.0) {
                    return Err(bad("a log range needs START > 0 and STOP > 0".into()));
                }
                let at = |i: usize| {
                    let s = if count == 1 {
                        0.0
                    } else {
                        i as f64 / (count - 1) as f64
                    };
                    // The ends exactly as given; the points between evenly spaced, to 15
                    // significant digits (0.1:1:10 gives 0.7, not 0.7000000000000001).
                    if i == 0 {
                        start
                    } else if i + 1 == count {
                        stop
                    } else if log {
                        significant((start.ln() + s * (stop.ln() - start.ln())).exp())
                    } else {
                        significant(start + s * (stop - start))
                    }
                };
                (0..count).map(at).collect()
            }
            None => values.split(',').map(number).collect::<Result<_, _>>()?,
        };
        Axis::new(name.trim(), values).map_err(|e| bad(e.to_string()))
    }

    /// The axis of parameter `name` over `values`: between 1 and [`MAX_AXIS`] finite numbers.
    pub fn new(name: &str, values: Vec<f64>) -> Result<Axis, AppError> {
        if values.is_empty() || values.len() > MAX_AXIS {
            return Err(AppError::Usage(format!(
                "{} values: allowed 1 to {MAX_AXIS}",
                values.len()
            )));
        }
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            return Err(AppError::Usage(format!("`{v}` is not a finite number")));
        }
        Ok(Axis {
            name: name.to_string(),
            values,
        })
    }
}

/// `x` to 15 significant digits: the value a reader would write for a point of a range
/// (the rounding of its arithmetic, a few units in the 16th digit, left out).
fn significant(x: f64) -> f64 {
    format!("{x:.14e}").parse().unwrap_or(x)
}

/// The grid's points in order (the first axis varying slowest), as `NAME=VALUE` assignments.
pub fn points(axes: &[Axis]) -> Vec<Vec<(String, f64)>> {
    let axes: Vec<(String, &[f64])> = axes
        .iter()
        .map(|a| (a.name.clone(), a.values.as_slice()))
        .collect();
    scenarios::grid::product(&axes)
}
