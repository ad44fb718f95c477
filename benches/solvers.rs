//! Explicit against implicit solvers on the friction problems, and a study sweep on one and
//! two threads. Run: `cargo bench --bench solvers`. Each configuration's statistics are
//! printed once before it is timed.

use criterion::{criterion_group, criterion_main, Criterion};
use friction_lab::friction_models::{FrictionParams, ModelId};
use friction_lab::friction_systems::{Scheme, Switching};
use friction_lab::integrators::{Solver, StepControl};
use friction_lab::scenarios::studies::{self, Case};
use friction_lab::scenarios::{run, Limits, RunSpec, Scenario};
use std::hint::black_box;

fn spec(
    scenario: Scenario,
    model: ModelId,
    switching: Switching,
    friction: FrictionParams,
    solver: &str,
    step: StepControl,
    t_end: f64,
) -> RunSpec {
    RunSpec {
        scenario,
        law: model.into(),
        friction,
        params: scenario.defaults(),
        scheme: Scheme::EventDriven {
            solver: Solver::from_name(solver).unwrap(),
            switching,
        },
        step,
        t_end: Some(t_end),
        output_points: 2,
        limits: Limits::default(),
    }
}

fn adaptive(tol: f64) -> StepControl {
    StepControl::Adaptive {
        rtol: tol,
        atol: tol,
        h0: None,
    }
}

fn solvers(c: &mut Criterion) {
    let paper = FrictionParams::paper();
    let cases = [
        (
            "paper-block AV",
            Scenario::PAPER_BLOCK,
            ModelId::Av,
            Switching::Event,
            paper,
            5.0,
        ),
        (
            "belt CS switched",
            Scenario::BELT,
            ModelId::Cs,
            Switching::Event,
            paper,
            5.0,
        ),
        (
            "belt CS regularized eps=1e-3",
            Scenario::BELT,
            ModelId::Cs,
            Switching::Regularized { epsilon: 1e-3 },
            paper,
            5.0,
        ),
        (
            "paper-block LuGre (stiff)",
            Scenario::PAPER_BLOCK,
            ModelId::LuGre,
            Switching::Event,
            FrictionParams::lugre_1995(),
            1.0,
        ),
    ];
    let methods = [
        ("rk4 dt=1e-4", "rk4", StepControl::Fixed { h: 1e-4 }),
        ("dopri5 tol=1e-6", "dopri5", adaptive(1e-6)),
        ("implicit-euler tol=1e-6", "implicit-euler", adaptive(1e-6)),
        ("bdf tol=1e-6", "bdf", adaptive(1e-6)),
        ("esdirk34 tol=1e-6", "esdirk34", adaptive(1e-6)),
    ];
    for (name, scenario, model, switching, friction, t_end) in cases {
        let mut group = c.benchmark_group(name);
        group.sample_size(10);
        for (label, solver, step) in methods {
            let s = spec(scenario, model, switching, friction, solver, step, t_end);
            let o = run(&s, &mut |_| {}).unwrap();
            println!("{name} / {label}: {:?}, failure: {:?}", o.stats, o.error);
            group.bench_function(label, |b| {
                b.iter(|| black_box(run(&s, &mut |_| {}).unwrap().stats))
            });
        }
        group.finish();
    }
}

fn study_threads(c: &mut Criterion) {
    let case = Case {
        scenario: Scenario::BELT,
        law: ModelId::Cs.into(),
        friction: FrictionParams::paper(),
        params: Scenario::BELT.defaults(),
        t_end: 10.0,
        limits: Limits::default(),
    };
    let four = [
        Solver::RK4,
        Solver::DOPRI5,
        Solver::IMPLICIT_EULER,
        Solver::from_name("bdf").unwrap(),
    ]
    .map(studies::Method::events);
    // The command's defaults: `friction-lab work-precision belt --model CS`.
    let all = Solver::ALL.map(studies::Method::events);
    let configurations: [(&str, &[studies::Method], usize); 2] = [
        ("work-precision sweep (belt CS, 28 runs)", &four, 1),
        (
            "work-precision study (belt CS, 40 runs, 3 repeats)",
            &all,
            3,
        ),
    ];
    for (name, methods, repeats) in configurations {
        let mut group = c.benchmark_group(name);
        group.sample_size(10);
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            group.bench_function(format!("{threads} thread(s)"), |b| {
                b.iter(|| {
                    pool.install(|| {
                        black_box(
                            studies::work_precision(
                                &case,
                                methods,
                                &[0.01, 0.003, 0.001, 0.0003],
                                &[1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8],
                                repeats,
                                &|| {},
                            )
                            .unwrap()
                            .runs
                            .len(),
                        )
                    })
                })
            });
        }
        group.finish();
    }
}

criterion_group!(benches, solvers, study_threads);
criterion_main!(benches);
