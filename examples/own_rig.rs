//! A rig written outside friction-lab, run and studied like a built-in one.
//!
//! A body on a slope, held from above by a spring: `m·ẍ + k·x = m·g·sin θ − F(ẋ)`, released
//! at rest from the spring's natural length (x along the slope, downhill positive). It
//! implements the public `Rig` trait with its own parameter (the angle θ) beside the
//! scenario parameters it reads (`m`, `k`); wrapped as `Scenario::own`, it runs through
//! `scenarios::run` and a convergence study, without a line of friction-lab changed; registered
//! (`Scenario::register`), it is found by its name as a built-in one is, here by the command
//! line's own library call.
//!
//! With Coulomb friction F_c < m·g·sin θ the body slides down one half-period
//! `π·√(m/k)` to `x = 2·(m·g·sin θ − F_c)/k`, where it stops and sticks for good when the
//! net force there, `m·g·sin θ − k·x`, is within ±F_c; with stiction F_s > m·g·sin θ it never
//! moves.
//!
//! Run: `cargo run --release --example own_rig`.

use clap::Parser;
use friction_lab::artifacts::Data;
use friction_lab::columns::Column;
use friction_lab::friction_models::{FrictionModel, FrictionParams, ModelId};
use friction_lab::friction_systems::{End, Profile, Scheme, System, STICK};
use friction_lab::integrators::{Solver, StepControl};
use friction_lab::scenarios::cases::Case;
use friction_lab::scenarios::rig::RIG_BODY;
use friction_lab::scenarios::studies::{self, ErrorMeasure, Method};
use friction_lab::scenarios::{
    Apparatus, EndTime, Law, Limits, Rig, RunSpec, Scenario, ScenarioParams,
};
use std::sync::Arc;

/// Standard gravity, m/s².
pub const G: f64 = 9.80665;

/// A spring-held body on a slope of angle θ.
pub struct Slope {
    /// The slope's angle θ, rad.
    pub angle: f64,
}

/// The one instance `Scenario::own` refers to: a slope of 45°, where `m·g·sin θ` = 6.93 N
/// at m = 1 kg lies between the paper's F_c = 6 N and F_s = 7.5 N.
pub static SLOPE: Slope = Slope {
    angle: std::f64::consts::FRAC_PI_4,
};

impl Slope {
    /// The weight's component along the slope, m·g·sin θ, N.
    pub fn downhill(&self, m: f64) -> f64 {
        m * G * self.angle.sin()
    }
}

impl Rig for Slope {
    fn name(&self) -> &'static str {
        "slope"
    }
    fn equation(&self) -> &'static str {
        "m*x'' + k*x = m*g*sin(theta) - F(x'), from rest at x = 0"
    }
    fn parameters(&self) -> &'static [&'static str] {
        &["m", "k"]
    }
    fn has_body(&self) -> bool {
        true
    }
    fn end_time(&self, _: &ScenarioParams, _: &FrictionParams) -> EndTime {
        EndTime::Fixed(1.0)
    }
    fn apparatus(
        &self,
        p: &ScenarioParams,
        _: &FrictionParams,
        law: Arc<dyn FrictionModel>,
    ) -> Apparatus {
        let mut s = System::default();
        let body = s.add_body(RIG_BODY, p.m, 0.0, 0.0);
        let top = s.add_anchor("top", 0.0, 0.0);
        s.add_spring(End::Body(body), End::Anchor(top), p.k, 0.0);
        s.add_force(body, self.downhill(p.m), Profile::None);
        s.add_contact(body, 0.0, law);
        Apparatus::Body(s)
    }
}

/// What the example measured.
#[derive(Debug)]
pub struct Report {
    /// With Coulomb friction: where and when the body stopped, and `2·(m·g·sin θ − F_c)/k`,
    /// `π·√(m/k)`.
    pub coulomb_stop: ((f64, f64), (f64, f64)),
    /// With Coulomb friction: the contact's mode at the end.
    pub coulomb_final_mode: friction_lab::integrators::Mode,
    /// With stiction (the `Static` model): the largest |x| of the run.
    pub static_largest_x: f64,
    /// Dormand–Prince's fixed-step order on the final state (where the body stuck), fitted by the
    /// study.
    pub dopri5_order: Option<f64>,
}

/// The slope with `model` at the paper's parameters, m = 1 kg, k = 100 N/m.
fn case(model: ModelId) -> Case {
    Case {
        scenario: Scenario::own(&SLOPE),
        law: Law::from(model),
        friction: FrictionParams::paper(),
        params: ScenarioParams::default(),
        t_end: 1.0,
        limits: Limits::default(),
    }
}

/// Runs the slope with `model`, Dormand–Prince at tight tolerances.
fn simulate(model: ModelId) -> friction_lab::scenarios::Outcome {
    let spec: RunSpec = case(model).spec(
        Scheme::events(Solver::DOPRI5),
        StepControl::Adaptive {
            rtol: 1e-12,
            atol: 1e-12,
            h0: None,
        },
    );
    let o = friction_lab::scenarios::run(&spec, &mut |_| {}).expect("a valid rig");
    assert!(o.error.is_none(), "{:?}", o.error);
    o
}

/// Runs the slope with Coulomb friction and with stiction, and studies Dormand–Prince's
/// convergence on it.
pub fn run() -> Report {
    let p = ScenarioParams::default();
    let f_c = FrictionParams::paper().f_c;
    let coulomb = simulate(ModelId::Coulomb);
    let stop = coulomb
        .events
        .iter()
        .find(|e| e.to == STICK)
        .expect("the body stops");
    let at_stop = coulomb
        .rows
        .iter()
        .find(|r| r.t >= stop.t)
        .expect("rows after the stop");
    let stiction = simulate(ModelId::Static);
    let study = studies::convergence(
        &case(ModelId::Coulomb),
        &[Method::events(Solver::DOPRI5)],
        &[0.04, 0.02, 0.01, 0.005, 0.0025],
        &[],
        &|| {},
    )
    .expect("the study runs");
    Report {
        coulomb_stop: (
            (at_stop.x, stop.t),
            (
                2.0 * (SLOPE.downhill(p.m) - f_c) / p.k,
                std::f64::consts::PI * (p.m / p.k).sqrt(),
            ),
        ),
        coulomb_final_mode: coulomb.last().expect("rows").mode,
        static_largest_x: (stiction.rows.iter()).fold(0.0, |a, r| a.max(r.x.abs())),
        dopri5_order: (study.orders.iter())
            .find(|o| o.measure == ErrorMeasure::FinalRelative)
            .and_then(|o| o.fit.map(|f| f.slope)),
    }
}

/// Registers the slope and runs `friction-lab simulate slope --model coulomb` through the
/// command line's own library call, as a user's program built on it would: the rig is found
/// by its name, as a built-in one is. Returns the summary's rig and status, and the final x.
pub fn by_name() -> (String, String, f64) {
    Scenario::register(&SLOPE).expect("slope is a name of its own");
    let words = [
        "friction-lab",
        "simulate",
        "slope",
        "--model",
        "coulomb",
        "--solver",
        "dopri5",
        "--rtol",
        "1e-12",
        "--atol",
        "1e-12",
        "--out",
        "by-name",
    ];
    let cli = friction_lab_cli::Cli::try_parse_from(words).expect("slope is a rig's name");
    let made = friction_lab_cli::make(&cli.command).expect("the run is made");
    let Some(Data::Json(summary)) = made.files.get("summary.json") else {
        panic!("a summary");
    };
    let field = |k: &str| summary[k].as_str().unwrap_or_default().to_string();
    let Some(Data::Table(last)) = made.files.get("final.csv") else {
        panic!("a final state");
    };
    let x = (last.columns().into_iter())
        .find_map(|(name, column)| match column {
            Column::Numbers(x) if name == "x" => x.last().copied(),
            _ => None,
        })
        .expect("a column x");
    (field("system"), field("status"), x)
}

#[allow(dead_code)]
fn main() {
    let (scenario, status, x) = by_name();
    println!("simulate {scenario}: {status}, final x = {x:.6} m");
    let r = run();
    let ((x, t), (x_exact, t_exact)) = r.coulomb_stop;
    println!(
        "Coulomb: stopped at x = {x:.6} m, t = {t:.6} s (exact {x_exact:.6} m, {t_exact:.6} s)"
    );
    println!("static: largest |x| = {:e} m", r.static_largest_x);
    println!(
        "Dormand–Prince order on the final state: {:?}",
        r.dopri5_order
    );
}
