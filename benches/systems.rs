//! Systems of many bodies: the Burridge–Knopoff chain (`coulomb`, 50 s) event-driven by
//! Dormand–Prince at rtol 1e-8 and time-stepped by Moreau–Jean at h = 1e-3, θ = 1/2, at
//! N = 10, 100, 1000; the stiffly coupled chain (k_chain = 1e8 N/m, h²θ²k/m = 25, 10 s)
//! time-stepped at N = 100 and 1000, where Newton's correction keeps the sweeps few; implicit
//! Euler with the sparse Jacobian at N = 100 and 1000 (10 s, tolerance 1e-4). Run:
//! `cargo bench --bench systems`. Each configuration's statistics are printed once before it
//! is timed.

use criterion::{criterion_group, criterion_main, Criterion};
use friction_lab::friction_models::{FrictionParams, ModelId, Variant};
use friction_lab::friction_systems::chain::ChainParams;
use friction_lab::friction_systems::{simulate, Scheme, Switching, System};
use friction_lab::integrators::{Options, Output, Solver, Stats};
use std::hint::black_box;
use std::sync::Arc;

fn chain(n: usize) -> System {
    chain_of_stiffness(n, ChainParams::default().k_chain)
}

fn chain_of_stiffness(n: usize, k_chain: f64) -> System {
    ChainParams {
        n_bodies: n,
        k_chain,
        ..ChainParams::default()
    }
    .build(&FrictionParams::paper(), |p| {
        ModelId::Coulomb.build(Variant::Odd, p).map(Arc::from)
    })
    .expect("valid parameters")
}

fn run(system: &System, solver: Solver, options: Options) -> (usize, usize) {
    let scheme = Scheme::EventDriven {
        solver,
        switching: Switching::Event,
    };
    switched(system, scheme, options)
}

fn switched(system: &System, scheme: Scheme, options: Options) -> (usize, usize) {
    let stats = stats(system, scheme, options);
    (stats.steps, stats.events)
}

fn stats(system: &System, scheme: Scheme, options: Options) -> Stats {
    let r = simulate(system, scheme, options, &mut |_| {}).expect("valid");
    assert!(r.error.is_none(), "{:?}", r.error);
    r.solution.stats
}

fn options(t_end: f64, tol: f64, atol: f64) -> Options {
    Options {
        output: Output::GridOnly(vec![t_end]),
        ..Options::adaptive(0.0, t_end, tol, atol)
    }
}

fn chains(c: &mut Criterion) {
    let mut group = c.benchmark_group("chain coulomb 50 s dopri5 rtol 1e-8");
    group.sample_size(10);
    for n in [10, 100, 1000] {
        let system = chain(n);
        let o = options(50.0, 1e-8, 1e-10);
        let (steps, events) = run(&system, Solver::DOPRI5, o.clone());
        println!("N = {n}: {steps} steps, {events} events");
        group.bench_function(format!("N = {n}"), |b| {
            b.iter(|| black_box(run(&system, Solver::DOPRI5, o.clone())))
        });
    }
    group.finish();
    let mut group = c.benchmark_group("chain coulomb 50 s moreau-jean h 1e-3 theta 0.5");
    group.sample_size(10);
    let stepping = Scheme::TimeStepping { theta: 0.5 };
    for n in [10, 100, 1000] {
        let system = chain(n);
        let o = Options {
            output: Output::GridOnly(vec![50.0]),
            ..Options::fixed(0.0, 50.0, 1e-3)
        };
        let (steps, events) = switched(&system, stepping, o.clone());
        println!("N = {n}: {steps} steps, {events} steps that switched");
        group.bench_function(format!("N = {n}"), |b| {
            b.iter(|| black_box(switched(&system, stepping, o.clone())))
        });
    }
    group.finish();
    let mut group =
        c.benchmark_group("chain coulomb k_chain 1e8 10 s moreau-jean h 1e-3 theta 0.5");
    group.sample_size(10);
    for n in [100, 1000] {
        let system = chain_of_stiffness(n, 1e8);
        let o = Options {
            output: Output::GridOnly(vec![10.0]),
            ..Options::fixed(0.0, 10.0, 1e-3)
        };
        let s = stats(&system, stepping, o.clone());
        println!(
            "N = {n}: {} steps, {} sweeps, {} corrections",
            s.steps, s.rhs_evals, s.lu_factorizations
        );
        group.bench_function(format!("N = {n}"), |b| {
            b.iter(|| black_box(switched(&system, stepping, o.clone())))
        });
    }
    group.finish();
    let mut group = c.benchmark_group("chain coulomb 10 s implicit-euler tol 1e-4 (sparse LU)");
    group.sample_size(10);
    for n in [100, 1000] {
        let system = chain(n);
        let o = options(10.0, 1e-4, 1e-6);
        let (steps, events) = run(&system, Solver::IMPLICIT_EULER, o.clone());
        println!("N = {n}: {steps} steps, {events} events");
        group.bench_function(format!("N = {n}"), |b| {
            b.iter(|| black_box(run(&system, Solver::IMPLICIT_EULER, o.clone())))
        });
    }
    group.finish();
}

criterion_group!(benches, chains);
criterion_main!(benches);
