//! One body at equal error: friction-lab's Dormand–Prince against diffsol's Tsit45 driven
//! through diffsol's own API (its closures, its root finding, a fresh solver from the root
//! at every switch), on the switched belt of the speed issue: m = 1, k = 100, belt at
//! 0.5 m/s, CVS at the paper's parameters (F_c = 6, F_s = 7.5, v_s = 0.1, mu_v = 0.5), 10 s,
//! rtol = atol = 1e-5 … 1e-10. Both evaluate the same friction law (`FrictionModel`).
//!
//! Run: `cargo bench --bench tsit45`. Before timing, each run's error at t = 10 s against
//! Dormand–Prince at 1e-13 is printed; after it, the criterion medians are read back and
//! `target/criterion/dopri5-vs-tsit45.png` (and `.svg`) draws error against median time.

use criterion::{criterion_group, criterion_main, Criterion};
use diffsol::{
    NalgebraMat, NonLinearOp, OdeBuilder, OdeEquations, OdeSolverMethod, OdeSolverState,
    OdeSolverStopReason, RkState, Vector,
};
use friction_lab::friction_models::{
    Direction, FrictionModel, FrictionParams, ModelId, SignLaw, Variant,
};
use friction_lab::friction_systems::{simulate, End, Scheme, Switching, System};
use friction_lab::integrators::{Options, Output, Solver};
use friction_lab::plot::{self, Corner, Marker, Plot, Series, PALETTE};
use std::cell::{Cell, RefCell};
use std::hint::black_box;
use std::path::Path;
use std::sync::Arc;

const M: f64 = 1.0;
const K: f64 = 100.0;
const V_BELT: f64 = 0.5;
const T_END: f64 = 10.0;
const TOLERANCES: [f64; 6] = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];

fn law() -> Arc<dyn FrictionModel> {
    Arc::from(
        ModelId::Cvs
            .build(Variant::Odd, &FrictionParams::paper())
            .expect("paper parameters"),
    )
}

/// The belt as a friction-lab system: a body on a spring to a wall, on a moving belt.
fn belt() -> System {
    let mut s = System::default();
    let body = s.add_body("body", M, 0.0, 0.0);
    let wall = s.add_anchor("wall", 0.0, 0.0);
    s.add_spring(End::Body(body), End::Anchor(wall), K, 0.0);
    s.add_contact(body, V_BELT, law());
    s
}

/// friction-lab: event-switched Dormand–Prince; the final (x, v) and the events.
fn friction_lab(system: &System, tol: f64) -> ([f64; 2], usize) {
    let options = Options {
        output: Output::GridOnly(vec![T_END]),
        ..Options::adaptive(0.0, T_END, tol, tol)
    };
    let run = simulate(
        system,
        Scheme::EventDriven {
            solver: Solver::DOPRI5,
            switching: Switching::Event,
        },
        options,
        &mut |_| {},
    )
    .expect("valid system");
    assert!(run.error.is_none(), "{:?}", run.error);
    let b = run.final_states()[0];
    (([b.x, b.v]), run.solution.stats.events)
}

/// The contact's mode in the diffsol driver.
#[derive(Clone, Copy, PartialEq)]
enum Mode {
    Slip(Direction),
    Stick,
}

/// diffsol: Tsit45 with diffsol's root finding; at each root the mode switches and a new
/// solver starts from the root. Returns the final (x, v) and the number of switches.
fn diffsol_tsit45(model: &dyn FrictionModel, tol: f64) -> ([f64; 2], usize) {
    // From rest on a belt moving forward: sliding backwards relative to it.
    let mode = Cell::new(Mode::Slip(Direction::Negative));
    let start = RefCell::new(vec![0.0, 0.0]);
    let rhs = |y: &[f64], _p: &[f64], _t: f64, dy: &mut [f64]| match mode.get() {
        Mode::Stick => {
            dy[0] = V_BELT;
            dy[1] = 0.0;
        }
        Mode::Slip(d) => {
            let f = model.force(y[0], y[1] - V_BELT, &[], SignLaw::Frozen(d));
            dy[0] = y[1];
            dy[1] = (-K * y[0] - f) / M;
        }
    };
    // Slipping: v_rel = 0. Stuck: the holding force −k·x leaving the stick interval.
    let root = |y: &[f64], _p: &[f64], _t: f64, g: &mut [f64]| match mode.get() {
        Mode::Stick => {
            let s = model.stick_interval(y[0], &[]);
            let held = -K * y[0];
            g[0] = s.upper - held;
            g[1] = held - s.lower;
        }
        Mode::Slip(_) => {
            g[0] = y[1] - V_BELT;
            g[1] = 1.0;
        }
    };
    let problem = OdeBuilder::<NalgebraMat<f64>>::new()
        .t0(0.0)
        .rtol(tol)
        .atol(vec![tol; 2])
        .rhs(rhs)
        .init(
            |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(&start.borrow()),
            2,
        )
        .root(root, 2)
        .build()
        .expect("a valid problem");
    let (mut t, mut switches) = (0.0, 0);
    loop {
        // A fresh state at t: y from `start`, f(t, y), diffsol's initial step for order 4.
        let mut state: RkState<_> = RkState::new_without_initialise(&problem).expect("a state");
        let mut s = state.as_mut();
        *s.t = t;
        problem.eqn.rhs().call_inplace(s.y, t, s.dy);
        s.set_step_size(problem.h0, &problem.atol, problem.rtol, &problem.eqn, 4);
        let mut solver = problem.tsit45_solver(state).expect("a solver");
        solver.set_stop_time(T_END).expect("a stop time");
        let (t_root, index) = loop {
            match solver.step().expect("a step") {
                OdeSolverStopReason::InternalTimestep => {}
                OdeSolverStopReason::TstopReached => {
                    let y = solver.state().y;
                    return ([y.get_index(0), y.get_index(1)], switches);
                }
                // A root at the restart point itself is the switch just made.
                OdeSolverStopReason::RootFound(r, _) if r <= t => {}
                OdeSolverStopReason::RootFound(r, i) => break (r, i),
            }
        };
        let y = solver.interpolate(t_root).expect("the root's state");
        let (x, mut v) = (y.get_index(0), y.get_index(1));
        let next = match mode.get() {
            Mode::Stick if index == 0 => Mode::Slip(Direction::Positive),
            Mode::Stick => Mode::Slip(Direction::Negative),
            Mode::Slip(_) => {
                v = V_BELT;
                let s = model.stick_interval(x, &[]);
                let held = -K * x;
                if s.contains(held) {
                    Mode::Stick
                } else if held > s.upper {
                    Mode::Slip(Direction::Positive)
                } else {
                    Mode::Slip(Direction::Negative)
                }
            }
        };
        mode.set(next);
        switches += 1;
        t = t_root;
        *start.borrow_mut() = vec![x, v];
    }
}

/// The criterion median of `group/id`, s, read back from criterion's estimates.
fn median(group: &str, id: &str) -> Option<f64> {
    let path = format!("target/criterion/{group}/{id}/new/estimates.json");
    let text = std::fs::read_to_string(path).ok()?;
    let key = "\"median\":{\"confidence_interval\"";
    let at = text.find(key)?;
    let point = text[at..].find("\"point_estimate\":")? + at + "\"point_estimate\":".len();
    let end = text[point..].find(',')? + point;
    text[point..end].parse::<f64>().ok().map(|ns| ns * 1e-9)
}

fn bench(c: &mut Criterion) {
    let system = belt();
    let model = law();
    let (reference, events) = friction_lab(&system, 1e-13);
    let check = diffsol_tsit45(model.as_ref(), 1e-13).0;
    println!(
        "reference (Dormand-Prince at 1e-13): x = {:.15}, v = {:.15}, {events} events; \
         Tsit45 at 1e-13 differs by {:.1e}",
        reference[0],
        reference[1],
        (check[0] - reference[0])
            .abs()
            .max((check[1] - reference[1]).abs())
    );
    let error = |y: [f64; 2]| (y[0] - reference[0]).abs().max((y[1] - reference[1]).abs());
    let group_name = "belt CVS 10 s";
    let mut group = c.benchmark_group(group_name);
    group.sample_size(20);
    let mut errors = Vec::new();
    for tol in TOLERANCES {
        let (ours, n_ours) = friction_lab(&system, tol);
        let (theirs, n_theirs) = diffsol_tsit45(model.as_ref(), tol);
        println!(
            "tol {tol:e}: dopri5 error {:.2e} ({n_ours} events), tsit45 error {:.2e} ({n_theirs} switches)",
            error(ours),
            error(theirs)
        );
        errors.push((tol, error(ours), error(theirs)));
        group.bench_function(format!("friction-lab dopri5 {tol:e}"), |b| {
            b.iter(|| black_box(friction_lab(&system, tol)))
        });
        group.bench_function(format!("diffsol tsit45 {tol:e}"), |b| {
            b.iter(|| black_box(diffsol_tsit45(model.as_ref(), tol)))
        });
    }
    group.finish();
    // Error against median time, both methods, from criterion's own estimates.
    let points = |who: &str, pick: fn(&(f64, f64, f64)) -> f64| -> Vec<(f64, f64)> {
        errors
            .iter()
            .filter_map(|e| Some((median(group_name, &format!("{who} {:e}", e.0))?, pick(e))))
            .collect()
    };
    let series = [
        (
            "friction-lab dopri5",
            points("friction-lab dopri5", |e| e.1),
        ),
        ("diffsol tsit45", points("diffsol tsit45", |e| e.2)),
    ]
    .into_iter()
    .zip(PALETTE)
    .map(|((label, points), color)| Series {
        label: Some(label.into()),
        points,
        color,
        width: 2,
        marker: Marker::Dot,
        dash: friction_lab::plot::Dash::Solid,
    })
    .collect();
    let plot = Plot {
        title: "Switched belt (CVS, 10 s): error at t = 10 s against median time".into(),
        x_label: "median time (s)".into(),
        y_label: "error of (x, v) at t = 10 s".into(),
        series,
        legend: Corner::UpperRight,
        log: true,
    };
    let stem = Path::new("target/criterion/dopri5-vs-tsit45");
    if let Ok(bytes) = plot::png(&plot, &stem.with_extension("png"), &plot::Format::default()) {
        let _ = std::fs::write(stem.with_extension("png"), bytes);
    }
    if let Ok(text) = plot::svg(&plot, &stem.with_extension("svg"), &plot::Format::default()) {
        let _ = std::fs::write(stem.with_extension("svg"), text);
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
