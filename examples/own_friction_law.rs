//! A friction law written outside friction-lab, run through the library like a built-in one.
//!
//! Tustin's exponential law (Tustin 1947; Armstrong-Hélouvry et al. 1994, eq. 2.3):
//! `F(v) = (F_c + (F_s − F_c)·exp(−|v|/v_s))·sign(v) + b·v`, at rest any force in
//! `[−F_s, F_s]`. It implements the public `FrictionModel` trait, sits at the contact of a
//! one-body belt system, is simulated with event-driven stick–slip switching, goes through a
//! convergence study, runs on the belt rig (`Law::Own`) and is judged by the protocols of
//! Table 2, without a line of friction-lab changed.
//!
//! Run: `cargo run --release --example own_friction_law`.

use friction_lab::friction_models::{
    FrictionModel, FrictionParams, Partials, SignLaw, StatePartials, StickInterval,
};
use friction_lab::friction_systems::{simulate, End, Scheme, Switching, System, STICK};
use friction_lab::integrators::{Options, Solver, StepControl};
use friction_lab::scenarios::phenomena::{self, Phenomenon, Protocol};
use friction_lab::scenarios::studies::{self, Method, SystemCase};
use friction_lab::scenarios::{Law, Limits, RunSpec, Scenario, ScenarioParams};
use std::sync::Arc;

/// Tustin's law.
#[derive(Debug)]
pub struct Tustin {
    /// Kinetic level F_c, N.
    pub f_c: f64,
    /// Static level F_s, N.
    pub f_s: f64,
    /// Decay velocity v_s, m/s.
    pub v_s: f64,
    /// Viscous coefficient b, N·s/m.
    pub b: f64,
}

impl FrictionModel for Tustin {
    fn name(&self) -> &str {
        "tustin"
    }

    fn n_states(&self) -> usize {
        0
    }

    /// `F = (F_c + (F_s − F_c)·e^(−|v|/v_s))·sign(v) + b·v`, with sign(v) and |v| = v·sign(v)
    /// evaluated by the law the integration asks for, and `∂F/∂v`; no internal state, so no
    /// rate and no state partials.
    fn evaluate(
        &self,
        _x: f64,
        v: f64,
        _z: &[f64],
        law: SignLaw,
        _rate: &mut [f64],
        _states: &mut [StatePartials],
    ) -> (f64, Partials) {
        let br = law.branches(v);
        let (sign, dsign) = (br.sign(), br.dsign_dv());
        let decay = (self.f_s - self.f_c) * (-(v * sign) / self.v_s).exp();
        // d|v|/dv = sign + v·dsign.
        let dabs = sign + v * dsign;
        let partials = Partials {
            force_dx: 0.0,
            force_dv: (self.f_c + decay) * dsign - decay * dabs / self.v_s * sign + self.b,
        };
        ((self.f_c + decay) * sign + self.b * v, partials)
    }

    fn stick_interval(&self, _x: f64, _z: &[f64]) -> StickInterval {
        StickInterval {
            lower: -self.f_s,
            upper: self.f_s,
        }
    }
}

/// What the example computes.
pub struct Report {
    /// First break-away time, s, and its exact value F_s/(k·v_belt).
    pub first_break_away: (f64, f64),
    /// Number of stick phases in the run.
    pub stick_phases: usize,
    /// Relative residual of the energy balance.
    pub energy_residual: f64,
    /// RK4's observed order on the stick durations, over its asymptotic range (the event
    /// times and the states have none at these steps: their local orders scatter, 5.1, 2.8, 4.9).
    pub rk4_order: Option<f64>,
    /// The belt rig run with the law: its first break-away time, s, and F_s/(k·v_belt).
    pub rig_break_away: (f64, f64),
    /// Table 2's verdict on every phenomenon, in the order of `Phenomenon::ALL`.
    pub table2: Vec<(Phenomenon, bool)>,
}

/// Tustin's law at the levels of the paper's Table 1 (F_c = 6 N, F_s = 7.5 N, v_s = 0.1 m/s,
/// b = μ_v = 0.5 N·s/m).
pub fn law() -> Arc<dyn FrictionModel> {
    Arc::new(Tustin {
        f_c: 6.0,
        f_s: 7.5,
        v_s: 0.1,
        b: 0.5,
    })
}

/// A body (m = 1 kg) held by a spring (k = 100 N/m) on a belt at 0.05 m/s, with Tustin's law,
/// starting at x = 0 carried by the belt (stuck).
pub fn belt() -> System {
    let mut s = System::default();
    let body = s.add_body("block", 1.0, 0.0, 0.05);
    let wall = s.add_anchor("wall", 0.0, 0.0);
    s.add_spring(End::Body(body), End::Anchor(wall), 100.0, 0.0);
    s.add_contact(body, 0.05, law());
    s
}

/// The belt rig with the law: the rig's own parameters (k = 100 N/m), the belt at 0.05 m/s,
/// the block starting at rest relative to it; the paper's parameters give the rig its scales.
fn rig_break_away() -> (f64, f64) {
    let params = ScenarioParams {
        v_belt: 0.05,
        v0: 0.05,
        ..Scenario::BELT.defaults()
    };
    let spec = RunSpec {
        scenario: Scenario::BELT,
        law: Law::Own(law()),
        friction: FrictionParams::paper(),
        params,
        scheme: Scheme::events(Solver::DOPRI5),
        step: StepControl::Adaptive {
            rtol: 1e-10,
            atol: 1e-12,
            h0: None,
        },
        t_end: Some(3.0),
        output_points: 11,
        limits: Limits::default(),
    };
    let o = friction_lab::scenarios::run(&spec, &mut |_| {}).expect("a valid rig");
    assert!(o.error.is_none(), "{:?}", o.error);
    let first = o
        .events
        .iter()
        .find(|e| e.to != friction_lab::friction_systems::STICK)
        .map_or(f64::NAN, |e| e.t);
    (first, 7.5 / (params.k * params.v_belt))
}

/// Simulates the belt and studies RK4's convergence on it.
pub fn run() -> Report {
    let system = belt();
    let options = Options::adaptive(0.0, 10.0, 1e-10, 1e-12);
    let r = simulate(
        &system,
        Scheme::EventDriven {
            solver: Solver::DOPRI5,
            switching: Switching::Event,
        },
        options,
        &mut |_| {},
    )
    .expect("a valid system");
    let events = r.contact_events();
    let first = events
        .iter()
        .find(|e| e.from == STICK)
        .map_or(f64::NAN, |e| e.t);
    let case = SystemCase::new("belt with Tustin's law", system.clone(), 3.0);
    let study = studies::convergence(
        &case,
        &[Method::events(Solver::RK4)],
        &[0.01, 0.005, 0.0025, 0.00125],
        &[],
        &|| {},
    )
    .expect("the study runs");
    let rk4_order = study
        .orders
        .iter()
        .find(|o| o.measure == studies::ErrorMeasure::StickDurations)
        .and_then(|o| o.fit.map(|f| f.slope));
    let table2 = Phenomenon::ALL
        .iter()
        .map(|&phenomenon| {
            let verdict = phenomena::decide(
                phenomenon,
                &Law::Own(law()),
                &FrictionParams::paper(),
                Protocol::default(),
            )
            .expect("the protocol runs");
            (phenomenon, verdict.measured)
        })
        .collect();
    Report {
        first_break_away: (first, 7.5 / (100.0 * 0.05)),
        stick_phases: events.iter().filter(|e| e.to == STICK).count(),
        energy_residual: r.energy().map_or(f64::NAN, |e| e.relative_residual),
        rk4_order,
        rig_break_away: rig_break_away(),
        table2,
    }
}

fn main() {
    let r = run();
    println!(
        "first break-away at t = {:.12} s (exact F_s/(k v_belt) = {} s)",
        r.first_break_away.0, r.first_break_away.1
    );
    println!("stick phases in 10 s: {}", r.stick_phases);
    println!(
        "energy balance: relative residual {:.2e}",
        r.energy_residual
    );
    println!(
        "RK4 observed order on the stick durations: {:?}",
        r.rk4_order
    );
    println!(
        "belt rig: first break-away at t = {:.12} s (exact {} s)",
        r.rig_break_away.0, r.rig_break_away.1
    );
    for (phenomenon, measured) in &r.table2 {
        println!("Table 2, {}: {measured}", phenomenon.name());
    }
}
