//! Stiffness along a run: `stiffness.csv` (the step h, the spectral radius ρ of the Jacobian
//! and h·ρ at each recorded point) and its figure.

use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, BLUE, RED};
use crate::window::Window;
use friction_systems::StiffnessPoint;
use std::path::Path;

/// `log10(h·ρ)` against t, with Dormand–Prince's stability boundary on the negative real axis
/// (h·ρ ≈ 3.3) as a line: above it an explicit step of that size is unstable on the stiffest
/// mode.
fn stiffness_plot(stiffness: &[StiffnessPoint], name: &str, window: Option<Window>) -> Plot {
    let points: Vec<(f64, f64)> = (stiffness.iter())
        .filter(|p| p.h_rho > 0.0 && Window::draws(window, p.t))
        .map(|p| (p.t, p.h_rho.log10()))
        .collect();
    let (t0, t1) = (
        points.first().map_or(0.0, |p| p.0),
        points.last().map_or(0.0, |p| p.0),
    );
    let boundary = DOPRI5_BOUNDARY.log10();
    Plot {
        title: format!("{name}: stiffness along the run"),
        x_label: "time t (s)".into(),
        y_label: "log10 h·ρ(∂f/∂y) (1)".into(),
        series: vec![
            Series {
                label: Some("h·ρ at the recorded points".into()),
                points,
                color: BLUE,
                width: 2,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            },
            Series {
                label: Some("dopri5's stability boundary, 3.3".into()),
                points: vec![(t0, boundary), (t1, boundary)],
                color: RED,
                width: 1,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            },
        ],
        legend: Corner::default(),
        log: false,
    }
}

/// `stiffness.csv` (t, h, ρ and h·ρ at each point of `stiffness`) and its figure
/// `stiffness.png`/`.svg` over `window`, for the run `name` (none for a run without points).
pub fn add_stiffness(
    files: &mut Artifacts,
    out: &Path,
    stiffness: &[StiffnessPoint],
    name: &str,
    window: Option<Window>,
) -> Result<(), AppError> {
    if stiffness.is_empty() {
        return Ok(());
    }
    let path = out.join("stiffness.csv");
    let mut table = Table::new(&["t", "h", "rho", "h_rho"]);
    for p in stiffness {
        table
            .rows
            .push([p.t, p.h, p.rho, p.h_rho].map(Cell::Num).to_vec());
    }
    files.add_table(path.clone(), table)?;
    files.add_plot(
        &out.join("stiffness"),
        &stiffness_plot(stiffness, name, window),
    )
}

/// Dormand–Prince's stability boundary on the negative real axis (Hairer & Wanner, *Solving
/// ODEs I*, Fig. IV.2.1): about 3.3.
const DOPRI5_BOUNDARY: f64 = 3.3;
