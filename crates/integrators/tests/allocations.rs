//! No heap allocation per accepted step in the steady loop of the hand-written methods: a
//! counting global allocator (counting only on the test's own thread) watches a stretch of
//! steps after the first ones, with output on a sparse grid and events being watched.

use integrators::counting::Counting;
use integrators::{
    Control, Crossing, Dopri5, Entry, EventSpec, ImplicitEuler, Integrator, Mode, NewtonKind,
    OdeProblem, Options, Output, Rk4, Stepper,
};

#[global_allocator]
static GLOBAL: Counting = Counting;

/// x'' = −x with an analytic Jacobian and an event function watched at every step that never
/// reaches zero (g = 2 + x, |x| ≤ 1).
struct Watched;

impl OdeProblem for Watched {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], _m: &[Mode], f: &mut [f64]) {
        f[0] = y[1];
        f[1] = -y[0];
    }
    fn jacobian(&self, _t: f64, _y: &[f64], _m: &[Mode], jac: &mut Vec<Entry>) -> bool {
        jac.extend([(0, 1, 1.0), (1, 0, -1.0)]);
        true
    }
    fn n_events(&self) -> usize {
        1
    }
    fn event_spec(&self, _i: usize, _m: &[Mode]) -> Option<EventSpec> {
        Some(EventSpec {
            name: "never",
            crossing: Crossing::Either,
        })
    }
    fn event(&self, _i: usize, _t: f64, y: &[f64], _m: &[Mode]) -> f64 {
        2.0 + y[0]
    }
    fn on_events(&self, _f: &[usize], _t: f64, _y: &mut [f64], _m: &mut [Mode]) -> Control {
        Control::Continue
    }
}

/// Allocations during `steps` steps of `stepper` (after 50 steps of warm-up), watching an
/// event that never fires and recording a 3-point grid.
fn allocations(stepper: Box<dyn Stepper>, options: Options, steps: usize) -> usize {
    let problem = Watched;
    let options = Options {
        output: Output::Grid(vec![0.0, 1e3, 2e3]),
        ..options
    };
    let mut run = Integrator::new(&problem, stepper, &[1.0, 0.0], &[Mode(0)], options).unwrap();
    for _ in 0..50 {
        run.step().unwrap();
    }
    Counting::start();
    for _ in 0..steps {
        run.step().unwrap();
    }
    Counting::stop()
}

#[test]
fn the_steady_loop_of_the_hand_written_methods_does_not_allocate() {
    let fixed = Options::fixed(0.0, 1e3, 1e-2);
    let adaptive = Options::adaptive(0.0, 1e3, 1e-8, 1e-10);
    let cases: [(&str, Box<dyn Stepper>, Options); 5] = [
        ("rk4", Box::new(Rk4::new(1e-2, 2)), fixed.clone()),
        (
            "dopri5",
            Box::new(Dopri5::new(
                adaptive.step,
                adaptive.h_max(),
                adaptive.max_steps,
                2,
            )),
            adaptive.clone(),
        ),
        (
            "dopri5 fixed",
            Box::new(Dopri5::new(fixed.step, fixed.h_max(), fixed.max_steps, 2)),
            fixed.clone(),
        ),
        (
            "implicit-euler",
            Box::new(ImplicitEuler::new(
                fixed.step,
                NewtonKind::Modified,
                fixed.h_max(),
                fixed.max_steps,
                2,
            )),
            fixed.clone(),
        ),
        (
            "implicit-euler adaptive",
            Box::new(ImplicitEuler::new(
                adaptive.step,
                NewtonKind::Modified,
                adaptive.h_max(),
                adaptive.max_steps,
                2,
            )),
            adaptive.clone(),
        ),
    ];
    for (name, stepper, options) in cases {
        let n = allocations(stepper, options, 1000);
        assert_eq!(n, 0, "{name}: {n} allocations in 1000 steps");
    }
}
