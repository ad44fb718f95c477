//! The floor of Moreau–Jean time-stepping on the Burridge–Knopoff chain: friction-lab's
//! general scheme (any topology, any law, internal states, the output and energy
//! bookkeeping) against a single-purpose kernel of the same scheme written for this one
//! problem: `coulomb` on every block, 50 s, h = 1e-3, θ = 1/2, N = 100 and 1000.
//!
//! The kernel keeps everything that makes the result the scheme's: the tridiagonal coupling
//! `Ŵ = M − h·θ·(C + h·θ·K)`, red–black nonsmooth Gauss–Seidel with the same tolerances and
//! revisit rule, each contact's problem solved exactly (at rest if the holding force is in the
//! stick interval, else its sliding equation, linear for Coulomb's law, solved in closed form
//! as the general scheme solves it; the θ-method on a contact that keeps sliding), the energy
//! accumulators. It drops what the general scheme owes other systems: springs resolved
//! through their ends, laws that depend on x, carry a state or need Newton's method, the step
//! cache, typed failures, output. Before timing, its final state must agree with the general
//! scheme's to 1e-12 and its sweeps must be the same count.
//!
//! Run: `cargo bench --bench moreau_jean_floor`.

use criterion::{criterion_group, criterion_main, Criterion};
use friction_lab::friction_models::{
    Direction, FrictionModel, FrictionParams, ModelId, SignLaw, Variant,
};
use friction_lab::friction_systems::chain::{scale_levels, ChainParams};
use friction_lab::friction_systems::moreau_jean::{SWEEP_ATOL, SWEEP_RTOL};
use friction_lab::friction_systems::{simulate, Scheme};
use friction_lab::integrators::{Options, Output};
use std::hint::black_box;

const T_END: f64 = 50.0;
const H: f64 = 1e-3;
const THETA: f64 = 0.5;

/// The chain's laws, block by block, as `ChainParams::build` scales them.
fn laws(chain: &ChainParams) -> Vec<Box<dyn FrictionModel>> {
    (1..=chain.n_bodies)
        .map(|i| {
            let p = scale_levels(&FrictionParams::paper(), chain.level(i));
            ModelId::Coulomb.build(Variant::Odd, &p).expect("paper")
        })
        .collect()
}

/// The general scheme: final (x, v) of every block and its sweep count.
fn general(chain: &ChainParams) -> (Vec<(f64, f64)>, usize) {
    let system = chain
        .build(&FrictionParams::paper(), |p| {
            ModelId::Coulomb
                .build(Variant::Odd, p)
                .map(std::sync::Arc::from)
        })
        .expect("valid");
    let options = Options {
        output: Output::GridOnly(vec![T_END]),
        ..Options::fixed(0.0, T_END, H)
    };
    let scheme = Scheme::TimeStepping { theta: THETA };
    let run = simulate(&system, scheme, options, &mut |_| {}).expect("valid");
    assert!(run.error.is_none(), "{:?}", run.error);
    let states = run.final_states().iter().map(|b| (b.x, b.v)).collect();
    (states, run.solution.stats.rhs_evals)
}

/// A contact of the kernel: its law at u = 0± (force and slope, the same at every step for a
/// law that ignores x) and its stick interval.
struct Contact {
    edge: [(f64, f64); 2],
    interval: (f64, f64),
}

impl Contact {
    fn new(law: &dyn FrictionModel) -> Contact {
        let at = |d| {
            let (force, p) = law.evaluate(0.0, 0.0, &[], SignLaw::Frozen(d), &mut [], &mut []);
            (force, p.force_dv)
        };
        let s = law.stick_interval(0.0, &[]);
        Contact {
            edge: [at(Direction::Positive), at(Direction::Negative)],
            interval: (s.lower, s.upper),
        }
    }
}

/// A contact's solution: end velocity, end force, impulse, direction (`None` at rest).
type Solution = (f64, f64, f64, Option<Direction>);

/// The sliding solution on side `d` of `w·u + h·[θ_f·F(u) + (1−θ_f)·f_k] = b` (the surface at
/// rest), if there is one: for Coulomb's law, affine in u on each side, the residual is linear
/// and its root is closed-form, as the general scheme solves it
/// (`FrictionModel::affine_in_velocity`).
fn slide(c: &Contact, d: Direction, theta_f: f64, f_k: f64, w: f64, b: f64) -> Option<Solution> {
    let s = d.sign();
    let (f0, slope) = c.edge[usize::from(d == Direction::Negative)];
    let impulse = |force: f64| H * (theta_f * force + (1.0 - theta_f) * f_k);
    let r0 = s * (impulse(f0) - b);
    if r0 >= 0.0 {
        return None;
    }
    let u = s * (-r0 * (1.0 / (w + H * theta_f * slope)));
    let force = f0 + slope * u;
    Some((u, force, impulse(force), Some(d)))
}

/// The kernel: final (x, v) of every block and its sweep count.
fn kernel(chain: &ChainParams) -> (Vec<(f64, f64)>, usize) {
    let n = chain.n_bodies;
    let contacts: Vec<Contact> = laws(chain)
        .iter()
        .map(|l| Contact::new(l.as_ref()))
        .collect();
    let ht = H * THETA;
    let (wc, wd) = (ht * (ht * chain.k_chain), ht * (ht * chain.k_driver));
    let diagonal: Vec<f64> = (0..n)
        .map(|i| chain.m + wd + if i > 0 { wc } else { 0.0 } + if i + 1 < n { wc } else { 0.0 })
        .collect();
    let order: Vec<usize> = (0..n).step_by(2).chain((1..n).step_by(2)).collect();
    let (mut x, mut v, mut v_last) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut x_hat, mut known) = (vec![0.0; n], vec![0.0; n]);
    let (mut dirty, mut drift) = (vec![false; n], vec![0.0; n]);
    let mut solved: Vec<Solution> = vec![(0.0, 0.0, 0.0, None); n];
    // Per block: the friction force and direction at the start of the step.
    let mut start: Vec<(f64, Option<Direction>)> = vec![(0.0, None); n];
    // Spring forces at the start of the step: the driver's on block i, link (i−1, i)'s on i−1.
    let (mut driver, mut link) = (vec![0.0; n], vec![0.0; n]);
    let (mut work, mut dissipated) = (0.0, 0.0);
    let steps = (T_END / H).round() as usize;
    let mut sweeps = 0;
    for k in 0..steps {
        let t1 = k as f64 * H + H;
        for (start, s) in start.iter_mut().zip(&solved) {
            *start = (s.1, s.3);
        }
        known.copy_from_slice(&driver);
        for i in 1..n {
            known[i - 1] += link[i];
            known[i] -= link[i];
        }
        for i in 0..n {
            x_hat[i] = x[i] + H * (1.0 - THETA) * v[i];
            known[i] = chain.m * v[i] + H * (1.0 - THETA) * known[i];
            (v[i], v_last[i]) = (2.0 * v[i] - v_last[i], v[i]);
        }
        let x_driver = chain.v_driver * t1;
        for i in 0..n {
            known[i] += ht * (chain.k_driver * (x_driver - x_hat[i]));
        }
        for i in 1..n {
            let f = ht * (chain.k_chain * (x_hat[i] - x_hat[i - 1]));
            known[i - 1] += f;
            known[i] -= f;
        }
        dirty.fill(true);
        drift.fill(0.0);
        let mut pending = true;
        let mut sweep = 0;
        while pending {
            sweep += 1;
            pending = false;
            for &i in &order {
                if !std::mem::replace(&mut dirty[i], false) {
                    continue;
                }
                let mut b = known[i];
                if i > 0 {
                    b += wc * v[i - 1];
                }
                if i + 1 < n {
                    b += wc * v[i + 1];
                }
                let (c, w) = (&contacts[i], diagonal[i]);
                let (f_k, previous) = start[i];
                let kept = previous.and_then(|d| slide(c, d, THETA, f_k, w, b));
                let s = kept.unwrap_or_else(|| {
                    let held = b * (1.0 / H);
                    if (c.interval.0..=c.interval.1).contains(&held) {
                        (0.0, held, H * held, None)
                    } else {
                        let d = if held > c.interval.1 {
                            Direction::Positive
                        } else {
                            Direction::Negative
                        };
                        slide(c, d, 1.0, 0.0, w, b).expect("a sliding solution")
                    }
                });
                solved[i] = s;
                let dv = s.0 - v[i];
                (v[i], drift[i]) = (s.0, 0.0);
                if dv != 0.0 {
                    let mut touch = |o: usize| {
                        drift[o] += wc * dv;
                        if drift[o].abs() > diagonal[o] * (SWEEP_ATOL + SWEEP_RTOL * v[o].abs()) {
                            dirty[o] = true;
                            pending = true;
                        }
                    };
                    if i > 0 {
                        touch(i - 1);
                    }
                    if i + 1 < n {
                        touch(i + 1);
                    }
                }
            }
        }
        sweeps += sweep;
        for i in 0..n {
            x[i] = x_hat[i] + ht * v[i];
            let f = chain.k_driver * (x_driver - x[i]);
            work += H * (THETA * f + (1.0 - THETA) * driver[i]) * chain.v_driver;
            driver[i] = f;
            dissipated += solved[i].2 * 0.5 * (v_last[i] + v[i]);
        }
        for i in 1..n {
            link[i] = chain.k_chain * (x[i] - x[i - 1]);
        }
    }
    black_box((work, dissipated));
    (x.into_iter().zip(v).collect(), sweeps)
}

fn floor(c: &mut Criterion) {
    let mut group =
        c.benchmark_group("chain coulomb 50 s moreau-jean h 1e-3: general scheme and kernel");
    group.sample_size(10);
    for n in [100, 1000] {
        let chain = ChainParams {
            n_bodies: n,
            ..ChainParams::default()
        };
        let (ours, sweeps) = general(&chain);
        let (floor, kernel_sweeps) = kernel(&chain);
        let gap = ours
            .iter()
            .zip(&floor)
            .map(|(a, b)| (a.0 - b.0).abs().max((a.1 - b.1).abs()))
            .fold(0.0, f64::max);
        println!("N = {n}: {sweeps} sweeps (kernel {kernel_sweeps}), largest difference {gap:.1e}");
        assert_eq!(
            sweeps, kernel_sweeps,
            "the kernel must take the general scheme's sweeps"
        );
        assert!(
            gap <= 1e-12,
            "the kernel must reach the general scheme's state"
        );
        group.bench_function(format!("general N = {n}"), |b| {
            b.iter(|| black_box(general(&chain)))
        });
        group.bench_function(format!("kernel N = {n}"), |b| {
            b.iter(|| black_box(kernel(&chain)))
        });
    }
    group.finish();
}

criterion_group!(benches, floor);
criterion_main!(benches);
