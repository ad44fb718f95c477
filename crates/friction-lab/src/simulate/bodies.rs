//! The bodies of a system a run writes and draws: chosen by name or 1-based index, or the
//! default choice.

use crate::error::AppError;
use crate::simulate::request::DEFAULT_TRAJECTORY_BODIES;
use friction_systems::System;

/// The bodies `chosen` (names or 1-based indices), or by default every body up to
/// [`DEFAULT_TRAJECTORY_BODIES`], else that many evenly spaced.
pub fn chosen_bodies(system: &System, chosen: &[String]) -> Result<Vec<usize>, AppError> {
    let n = system.bodies.len();
    if chosen.is_empty() {
        let k = n.min(DEFAULT_TRAJECTORY_BODIES);
        return Ok(if k <= 1 {
            vec![0]
        } else {
            (0..k).map(|j| j * (n - 1) / (k - 1)).collect()
        });
    }
    let indices: Vec<usize> = chosen
        .iter()
        .map(|token| {
            if let Some(i) = system.bodies.iter().position(|b| &b.name == token) {
                return Ok(i);
            }
            match token.parse::<usize>() {
                Ok(i) if (1..=n).contains(&i) => Ok(i - 1),
                _ => Err(no_body(system, token)),
            }
        })
        .collect::<Result<_, _>>()?;
    // A body chosen twice would repeat its rows in the tidy trajectory.csv.
    if let Some((j, k)) = crate::ranges::first_repeat(&indices) {
        return Err(AppError::Usage(format!(
            "option `{}`: `{}` and `{}` are the same body, {}: choose each body once",
            crate::error::field("bodies"),
            chosen[j],
            chosen[k],
            system.bodies[indices[k]].name
        )));
    }
    Ok(indices)
}

/// The error for a `--bodies` token that is no body's name or index. The option splits at
/// commas, so a body whose name has one is chosen by its index: said, with the index.
fn no_body(system: &System, token: &str) -> AppError {
    let n = system.bodies.len();
    let hint: String = system
        .bodies
        .iter()
        .enumerate()
        .filter(|(_, b)| b.name.contains(','))
        .map(|(i, b)| {
            let name = &b.name;
            format!(
                "; body \"{name}\" has a comma: choose it by its index, {}",
                i + 1
            )
        })
        .collect();
    AppError::Usage(format!(
        "option `{}`: `{token}` is no body: allowed a body's name or an index in [1, {n}]{hint}",
        crate::error::field("bodies")
    ))
}
