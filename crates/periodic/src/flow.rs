//! The hybrid flow over a span, segment by segment, with its sensitivity through every switch:
//! the monodromy matrix `M = Φ_N·S_{N−1}·Φ_{N−1}·…·S_1·Φ_1` when the span is a period.

use crate::saltation::{switch, Switch};
use crate::variational::Variational;
use crate::OrbitError;
use integrators::{Mode, OdeProblem, Options, Solver};
use nalgebra::DMatrix;

/// How the flow is integrated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlowOptions {
    /// The solver of each smooth segment (state and variational equations together).
    pub solver: Solver,
    /// Its relative tolerance.
    pub rtol: f64,
    /// Its absolute tolerance.
    pub atol: f64,
    /// The most switches in one flow.
    pub max_switches: usize,
}

impl Default for FlowOptions {
    /// `auto` (Dormand–Prince, switched to Radau IIA where it finds the problem stiff) at
    /// rtol = 1e-12, atol = 1e-14: the sensitivities to about 1e-11.
    fn default() -> Self {
        FlowOptions {
            solver: Solver::AUTO,
            rtol: 1e-12,
            atol: 1e-14,
            max_switches: 100_000,
        }
    }
}

/// One smooth piece of the flow: its modes, where it starts and ends, its sensitivity and the
/// switch that ends it (none for the last piece, which ends at the span's end).
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// The modes throughout.
    pub modes: Vec<Mode>,
    /// Start time, s.
    pub t0: f64,
    /// End time, s.
    pub t1: f64,
    /// The state at the start.
    pub y0: Vec<f64>,
    /// The smooth flow's sensitivity `Φ = ∂y(t1⁻)/∂y(t0⁺)` over the dynamic unknowns.
    pub sensitivity: DMatrix<f64>,
    /// The switch at t1, if the segment ends at one.
    pub switch: Option<Switch>,
}

/// The flow from (t0, y0) in modes0 over a span: its segments, the state and modes at the end
/// and the product of the segments' sensitivities and saltation matrices.
#[derive(Clone, Debug, PartialEq)]
pub struct HybridFlow {
    /// The segments, in order.
    pub segments: Vec<Segment>,
    /// The state at the end.
    pub y_end: Vec<f64>,
    /// The modes at the end.
    pub modes_end: Vec<Mode>,
    /// `∂y(t_end)/∂y(t0)` over the dynamic unknowns, through every switch.
    pub sensitivity: DMatrix<f64>,
}

/// The hybrid flow of `problem` from (t0, y0) in `modes0` to `t0 + span`: each segment
/// integrated with its variational equations (`Φ' = J·Φ`, `Φ(t₀) = I`) until an event fires,
/// the switch made by the problem's handler with its saltation matrix
/// ([`crate::saltation::switch`]). A problem with a singular mass matrix is refused.
pub fn flow(
    problem: &dyn OdeProblem,
    (t0, span): (f64, f64),
    y0: &[f64],
    modes0: &[Mode],
    options: &FlowOptions,
) -> Result<HybridFlow, OrbitError> {
    if problem.mass().is_some_and(|m| m.contains(&0.0)) {
        return Err(OrbitError::Unsupported(
            "a differential-algebraic problem (a zero on the mass diagonal): its orbits are \
             not computed yet"
                .into(),
        ));
    }
    let variational = Variational::new(problem);
    let n = variational.n;
    let t_end = t0 + span;
    let (mut t, mut y, mut modes) = (t0, y0.to_vec(), modes0.to_vec());
    let mut total = DMatrix::identity(n, n);
    let mut segments = Vec::new();
    loop {
        let run = Options::adaptive(t, t_end, options.rtol, options.atol);
        let solution = options
            .solver
            .solve(&variational, &variational.start(&y), &modes, run)
            .map_err(|f| OrbitError::Solver {
                t: f.solution.last().map_or(t, |(t, _)| t),
                error: f.error,
            })?;
        let (t1, z) = solution.last().expect("a solution records its end");
        let sensitivity = variational.sensitivity(z);
        total = &sensitivity * total;
        let y_minus = z[..variational.big].to_vec();
        let event = solution.events.last().filter(|e| e.t == t1 && t1 < t_end);
        let Some(event) = event else {
            segments.push(Segment {
                modes: modes.clone(),
                t0: t,
                t1,
                y0: y,
                sensitivity,
                switch: None,
            });
            return Ok(HybridFlow {
                segments,
                y_end: y_minus,
                modes_end: modes,
                sensitivity: total,
            });
        };
        if segments.len() >= options.max_switches {
            return Err(OrbitError::TooManySwitches(options.max_switches));
        }
        let name = event.names.first().copied().unwrap_or("event");
        let (y_plus, after, switch) = switch(problem, &event.fired, name, t1, &y_minus, &modes)?;
        total = &switch.saltation * total;
        segments.push(Segment {
            modes: modes.clone(),
            t0: t,
            t1,
            y0: std::mem::replace(&mut y, y_plus),
            sensitivity,
            switch: Some(switch),
        });
        (t, modes) = (t1, after);
    }
}
