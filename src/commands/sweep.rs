//! `friction-lab sweep SCENARIO|chain|--system FILE --grid NAME=VALUES ... --out DIR`: the
//! sweep of [`friction_lab::sweep`] over the run `simulate` would make, each point's values set as
//! `--set` would set them.

use super::Writing;
use clap::Args;
use friction_lab::artifacts::Made;
use friction_lab::error::AppError;
use friction_lab::simulate::Simulation;
use friction_lab::sweep::{parse_point_range, points, Axis, Start, Sweep, DEFAULT_SETTLE};

/// Options of `sweep`.
#[derive(Args, Debug)]
pub struct SweepArgs {
    /// What to run at every point: the rig or chain, the model, the solver and the fixed
    /// parameters, as `simulate` takes them.
    #[command(flatten)]
    pub run: Writing<Simulation>,
    /// One axis of the grid, repeatable: NAME=V1,V2,... (a list), NAME=START:STOP:COUNT
    /// (evenly spaced), or NAME=log:START:STOP:COUNT (evenly spaced in log); any friction,
    /// scenario or chain parameter. The grid is the product of the axes, the first varying
    /// slowest.
    #[arg(long = "grid", value_name = "NAME=VALUES", required = true)]
    pub grid: Vec<String>,
    /// The measured, settled part of each run: its last fraction (0, 1] of the time span.
    #[arg(
        long,
        value_name = "FRACTION",
        default_value_t = DEFAULT_SETTLE,
        allow_hyphen_values = true
    )]
    pub settle: f64,
    /// Worker threads (default: all cores); the results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub threads: Option<i64>,
    /// Where every run starts: `rest` (the rig's x0, v0) or `sliding` (the belt only: the
    /// body at rest at the equilibrium of steady sliding, x0 = −F(−v_belt)/k, the other half of
    /// a bifurcation diagram).
    #[arg(long, value_name = "rest|sliding", default_value = "rest")]
    pub start: Start,
    /// Run only the grid points START <= i < END (0-based, in grid order): one part of the
    /// sweep, for spreading it over machines or Dask tasks; its rows equal those of the whole
    /// sweep. Every point of the grid is still checked first.
    #[arg(long, value_name = "START:END")]
    pub point_range: Option<String>,
}

/// Runs `sweep`; its files in memory.
pub fn make(args: &SweepArgs) -> Result<Made, AppError> {
    let axes: Vec<Axis> = args
        .grid
        .iter()
        .map(|g| Axis::parse(g))
        .collect::<Result<_, _>>()?;
    let n = points(&axes).len();
    let sweep = Sweep {
        simulation: args.run.request.clone(),
        axes,
        settle: args.settle,
        start: args.start,
        range: (args.point_range.as_deref())
            .map(|text| parse_point_range(text, n))
            .transpose()?,
        threads: args.threads,
    };
    sweep.run(&args.run.out)
}
