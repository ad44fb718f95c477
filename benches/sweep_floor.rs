//! The floor of a one-body ensemble: the stick–slip map's points (the belt, `CVS`, 40 s, each
//! run extended until it settles) as friction-lab's sweep runs them, against a single-purpose
//! kernel of the same computation written for this one problem.
//!
//! The kernel keeps everything that makes a point's result the scheme's: Hairer's
//! Dormand–Prince 5(4) with its initial step (HINIT), its PI control and FSAL, the same
//! tolerances (rtol 1e-8, atol 1e-10) over the same five unknowns (x, v and the three energy
//! accumulators, which the error norm reads), the event-driven switching of the belt's contact
//! (slip → stick where v − v_belt reaches zero and the spring's force is inside the stick
//! interval, stick → slip where it leaves it), each event located on the dense output by the
//! same Illinois iteration to the same tolerance and the method restarted after it, the 2,001
//! evenly spaced output points a run records, and the settled-state measures
//! ([`Settled::of`]) with the run's span doubled until it settles ([`until_settled`]). It drops
//! what the general code owes other problems: any number of bodies, springs and contacts,
//! laws with internal states or that depend on x, the mass matrix, the checks of finite values
//! and of the reach, the stiffness test, the rows at events, the energy balance's closing, the
//! step and time limits. Before timing, every point's measures must agree with the general
//! code's to 1e-6 and its f evaluations within 1 %.
//!
//! Run: `cargo bench --bench sweep_floor`.

use criterion::{criterion_group, criterion_main, Criterion};
use friction_lab::friction_models::{FrictionParams, ModelId, SignLaw, Variant};
use friction_lab::integrators::even_grid;
use friction_lab::integrators::events::{illinois, TIME_TOLERANCE, ZERO};
use friction_lab::scenarios::analysis::settled::{until_settled, Settled, Trace};
use friction_lab::scenarios::stick_slip::belt_run;
use friction_lab::scenarios::{RunSpec, Scenario};
use friction_lab::sweep::PointRun;
use std::hint::black_box;

const T_END: f64 = 40.0;
const POINTS: usize = 2001;
const RTOL: f64 = 1e-8;
const ATOL: f64 = 1e-10;
const SETTLE: f64 = 0.5;
/// The map's grid, thinned: every 11th value of its 100 per axis, 10 × 10 points.
const EVERY: usize = 11;

/// The map's axes: v_belt and k, each log-spaced with 100 values.
fn grid() -> Vec<(f64, f64)> {
    let log = |a: f64, b: f64, i: usize| 10f64.powf(a.log10() + (b / a).log10() * i as f64 / 99.0);
    let values = || (0..100).step_by(EVERY);
    values()
        .flat_map(|i| values().map(move |j| (log(0.01, 1.0, i), log(10.0, 1000.0, j))))
        .collect()
}

/// The general code: a sweep's point run, as `friction-lab sweep` runs it.
fn general_point(v_belt: f64, k: f64) -> PointRun {
    let base = belt_run(ModelId::Cvs, &FrictionParams::paper());
    let mut params = base.params;
    (params.v_belt, params.k) = (v_belt, k);
    PointRun::Rig(RunSpec {
        params,
        t_end: Some(T_END),
        output_points: POINTS,
        ..base
    })
}

/// The contact's modes.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    SlipPositive,
    SlipNegative,
    Stick,
}

/// The belt (`m·ẍ + k·x = −F(ẋ − v_belt)`, no damper) with `CVS`:
/// `F(w) = F_c·s + μ_v·w + exp(−(w/v_s)²)·(C1·[s > 0] − C2·[s < 0])`, s the slip
/// direction,, stick interval
/// `[−(F_c + C2), F_c + C1]`.
#[derive(Clone, Copy)]
struct Belt {
    m: f64,
    k: f64,
    v_belt: f64,
    f_c: f64,
    mu_v: f64,
    c1: f64,
    c2: f64,
    v_s: f64,
}

type State = [f64; 5];

impl Belt {
    fn new(v_belt: f64, k: f64) -> Belt {
        let p = FrictionParams::paper();
        Belt {
            m: Scenario::BELT.defaults().m,
            k,
            v_belt,
            f_c: p.f_c,
            mu_v: p.mu_v,
            c1: p.c1,
            c2: p.c2,
            v_s: p.v_s,
        }
    }

    /// The law at sliding velocity `w` with sign(w) frozen to the slip mode's direction (as
    /// the event-driven scheme evaluates it inside a step).
    fn law(&self, w: f64, mode: Mode) -> f64 {
        let (plus, minus) = match mode {
            Mode::SlipPositive => (1.0, 0.0),
            Mode::SlipNegative => (0.0, 1.0),
            Mode::Stick => (0.0, 0.0),
        };
        let e = (-(w / self.v_s).powi(2)).exp();
        self.f_c * (plus - minus) + self.mu_v * w + e * (self.c1 * plus - self.c2 * minus)
    }

    fn bounds(&self) -> (f64, f64) {
        (-(self.f_c + self.c2), self.f_c + self.c1)
    }

    /// The friction force in `mode` at (x, v): the law in slip, the holding force in stick.
    fn friction(&self, mode: Mode, x: f64, v: f64) -> f64 {
        match mode {
            Mode::Stick => -self.k * x,
            _ => self.law(v - self.v_belt, mode),
        }
    }

    /// ẋ, v̇ and the accumulators' rates (external work, dissipation, the belt's work).
    fn rhs(&self, mode: Mode, y: &State) -> State {
        let (x, v) = (y[0], y[1]);
        let other = -self.k * x;
        let force = self.friction(mode, x, v);
        let (dx, dv) = match mode {
            Mode::Stick => (self.v_belt, 0.0),
            _ => (v, (other - force) / self.m),
        };
        [dx, dv, 0.0, force * (v - self.v_belt), -force * self.v_belt]
    }

    /// The event function watched in `mode` (the break-away to slip+ and slip− in stick).
    fn event(&self, mode: Mode, which: usize, x: f64, v: f64) -> f64 {
        let (lower, upper) = self.bounds();
        match (mode, which) {
            (Mode::Stick, 0) => upper + self.k * x,
            (Mode::Stick, _) => -self.k * x - lower,
            _ => v - self.v_belt,
        }
    }

    /// Whether `before → after` is the crossing watched in `mode`.
    fn crossed(mode: Mode, before: f64, after: f64) -> bool {
        match mode {
            Mode::SlipNegative => before < 0.0 && after >= 0.0,
            _ => before > 0.0 && after <= 0.0,
        }
    }
}

// Dormand–Prince's tableau (the problem is autonomous: no nodes c_i) and Hairer's controller
// constants, as `integrators::dopri5` has them.
const A: [&[f64]; 6] = [
    &[0.2],
    &[3.0 / 40.0, 9.0 / 40.0],
    &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
    &[
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
    ],
    &[
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
    ],
    &[
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];
const SAFE: f64 = 0.9;
const FAC1: f64 = 0.2;
const FAC2: f64 = 10.0;
const BETA: f64 = 0.04;
const EXPO1: f64 = 0.2 - BETA * 0.75;
const FACOLD_MIN: f64 = 1e-4;

/// One run of the kernel over [0, t_end]: the trace of its grid and its f evaluations.
struct Kernel {
    belt: Belt,
    mode: Mode,
    t: f64,
    y: State,
    h: f64,
    facold: f64,
    reject: bool,
    f0: State,
    /// Dense output of the last step, unknown by unknown:
    /// `c0 + θ(c1 + (1−θ)(c2 + θ(c3 + (1−θ)c4)))`.
    cont: [[f64; 5]; 5],
    t_prev: f64,
    /// Each watched function's last value, and whether it starts at zero (a fresh mode).
    last: [f64; 2],
    at_zero: [bool; 2],
    evals: usize,
}

impl Kernel {
    fn new(belt: Belt) -> Kernel {
        let y = [0.0; 5];
        let mode = if -belt.v_belt > 0.0 {
            Mode::SlipPositive
        } else {
            Mode::SlipNegative
        };
        let mut kernel = Kernel {
            belt,
            mode,
            t: 0.0,
            y,
            h: 0.0,
            facold: FACOLD_MIN,
            reject: false,
            f0: [0.0; 5],
            cont: [[0.0; 5]; 5],
            t_prev: 0.0,
            last: [0.0; 2],
            at_zero: [false; 2],
            evals: 0,
        };
        kernel.restart();
        kernel
    }

    fn f(&mut self, y: &State) -> State {
        self.evals += 1;
        self.belt.rhs(self.mode, y)
    }

    fn watched(&self) -> usize {
        if self.mode == Mode::Stick {
            2
        } else {
            1
        }
    }

    /// After the start or an event: FSAL's first stage anew, HINIT at the next step, the
    /// watched functions read at the new state.
    fn restart(&mut self) {
        self.f0 = self.f(&self.y.clone());
        (self.h, self.facold, self.reject) = (0.0, FACOLD_MIN, false);
        for i in 0..self.watched() {
            let g = self.belt.event(self.mode, i, self.y[0], self.y[1]);
            self.at_zero[i] = g.abs() <= ZERO;
            let side = if self.mode == Mode::SlipNegative {
                -1.0
            } else {
                1.0
            };
            self.last[i] = if self.at_zero[i] { side * ZERO } else { g };
        }
    }

    fn hinit(&mut self, t_stop: f64) -> f64 {
        let (y, f0) = (self.y, self.f0);
        let sk = |i: usize| ATOL + RTOL * y[i].abs();
        let dnf: f64 = (0..5).map(|i| (f0[i] / sk(i)).powi(2)).sum();
        let dny: f64 = (0..5).map(|i| (y[i] / sk(i)).powi(2)).sum();
        let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
            1e-6
        } else {
            (dny / dnf).sqrt() * 0.01
        };
        h = h.min(t_stop - self.t);
        let y1: State = std::array::from_fn(|i| y[i] + h * f0[i]);
        let f1 = self.f(&y1);
        let der2 = (0..5)
            .map(|i| ((f1[i] - f0[i]) / sk(i)).powi(2))
            .sum::<f64>()
            .sqrt()
            / h;
        let der12 = der2.abs().max(dnf.sqrt());
        let h1 = if der12 <= 1e-15 {
            (h * 1e-3).max(1e-6)
        } else {
            (0.01 / der12).powf(0.2)
        };
        (100.0 * h).min(h1)
    }

    /// One accepted step towards `t_stop` (rejected attempts retried inside).
    fn step(&mut self, t_stop: f64) {
        if self.h == 0.0 {
            self.h = self.hinit(t_stop);
        }
        loop {
            let mut h = self.h;
            let last = self.t + 1.01 * h - t_stop > 0.0;
            if last {
                h = t_stop - self.t;
            }
            let mut k = [self.f0; 7];
            for s in 1..7 {
                let mut arg = self.y;
                for (i, a) in arg.iter_mut().enumerate() {
                    *a += h * (0..s).fold(0.0, |sum, j| sum + A[s - 1][j] * k[j][i]);
                }
                k[s] = self.f(&arg);
            }
            // The sixth stage's argument is the fifth-order solution; k[6] is f there (FSAL).
            let y1: State = std::array::from_fn(|i| {
                self.y[i] + h * (0..6).fold(0.0, |sum, j| sum + A[5][j] * k[j][i])
            });
            let err = ((0..5)
                .map(|i| {
                    let e = h * (0..7).fold(0.0, |sum, j| sum + E[j] * k[j][i]);
                    let sk = ATOL + RTOL * self.y[i].abs().max(y1[i].abs());
                    (e / sk).powi(2)
                })
                .sum::<f64>()
                / 5.0)
                .sqrt();
            let fac11 = err.powf(EXPO1);
            let fac = (fac11 / self.facold.powf(BETA) / SAFE).clamp(1.0 / FAC2, 1.0 / FAC1);
            let h_new = h / fac;
            if err <= 1.0 {
                self.facold = err.max(FACOLD_MIN);
                for (i, c) in self.cont.iter_mut().enumerate() {
                    let ydiff = y1[i] - self.y[i];
                    let bspl = h * k[0][i] - ydiff;
                    *c = [
                        self.y[i],
                        ydiff,
                        bspl,
                        -h * k[6][i] + ydiff - bspl,
                        h * (0..7).fold(0.0, |sum, j| sum + D[j] * k[j][i]),
                    ];
                }
                self.f0 = k[6];
                self.y = y1;
                self.t_prev = self.t;
                self.t = if last { t_stop } else { self.t + h };
                self.h = match (last, self.reject) {
                    (true, _) => h_new,
                    (false, true) => h_new.min(h),
                    (false, false) => h_new,
                };
                self.reject = false;
                return;
            }
            self.reject = true;
            self.h = h / (1.0 / FAC1).min(fac11 / SAFE);
        }
    }

    /// The state at `t` inside the last step.
    fn dense(&self, t: f64) -> State {
        let th = (t - self.t_prev) / (self.t - self.t_prev);
        let th1 = 1.0 - th;
        self.cont
            .map(|c| c[0] + th * (c[1] + th1 * (c[2] + th * (c[3] + th1 * c[4]))))
    }

    /// The earliest crossing in the last step, located, if any.
    fn crossing(&mut self) -> Option<(f64, usize)> {
        let (t0, t1) = (self.t_prev, self.t);
        let tol = TIME_TOLERANCE * t1.abs().max(t1 - t0).max(f64::MIN_POSITIVE);
        let mut earliest: Option<(f64, usize, f64, f64)> = None;
        let n = self.watched();
        let now: [f64; 2] =
            std::array::from_fn(|i| self.belt.event(self.mode, i, self.y[0], self.y[1]));
        for (i, &g1) in now.iter().enumerate().take(n) {
            if self.at_zero[i] && g1 == 0.0 {
                continue;
            }
            let ga = self.last[i];
            if Belt::crossed(self.mode, ga, g1) {
                let secant = t0 - ga * (t1 - t0) / (g1 - ga);
                if earliest.is_none_or(|(s, ..)| secant < s) {
                    earliest = Some((secant, i, ga, g1));
                }
            }
        }
        let Some((_, i, ga, g1)) = earliest else {
            for (j, &g) in now.iter().enumerate().take(n) {
                if g != 0.0 || !self.at_zero[j] {
                    self.at_zero[j] = false;
                    self.last[j] = g;
                }
            }
            return None;
        };
        let mut g = |t: f64| {
            let y = self.dense(t);
            self.belt.event(self.mode, i, y[0], y[1])
        };
        Some((illinois(&mut g, t0, ga, t1, g1, tol), i))
    }

    /// The switch at `t` by function `which`: the state there from the dense output, the body
    /// put on the belt at an arrival and its new mode decided by the spring's force against the
    /// stick interval, the break-away's direction otherwise; the method restarted. Whether the
    /// contact went into stick.
    fn switch(&mut self, t: f64, which: usize) -> bool {
        let mut y = self.dense(t);
        let from = self.mode;
        self.mode = match from {
            Mode::Stick if which == 0 => Mode::SlipPositive,
            Mode::Stick => Mode::SlipNegative,
            _ => {
                y[1] = self.belt.v_belt;
                let (lower, upper) = self.belt.bounds();
                let f = -self.belt.k * y[0];
                if lower < upper && lower <= f && f <= upper {
                    Mode::Stick
                } else if f > upper {
                    Mode::SlipPositive
                } else {
                    Mode::SlipNegative
                }
            }
        };
        (self.t, self.y) = (t, y);
        self.restart();
        self.mode == Mode::Stick
    }
}

/// The kernel's point: its span doubled until it settles; the measures and f evaluations of
/// the last run.
fn floor_point(belt: Belt) -> (Settled, usize) {
    let result: Result<_, ()> = until_settled(
        |factor| Ok(floor_run(belt, factor)),
        |(settled, _): &(Settled, usize)| settled.settled,
    );
    result.expect("the kernel does not fail")
}

/// The kernel's run over `factor` spans of [`T_END`], with the output spacing kept.
fn floor_run(belt: Belt, factor: u32) -> (Settled, usize) {
    let t_end = T_END * f64::from(factor);
    let grid = even_grid(0.0, t_end, (POINTS - 1) * factor as usize + 1);
    let mut kernel = Kernel::new(belt);
    let mut trace = Trace::default();
    let mut next = 0;
    let record = |trace: &mut Trace, t: f64, x: f64, v: f64, mode: Mode| {
        trace.t.push(t);
        trace.x.push(x);
        trace.v.push(v);
        trace.friction.push(belt.friction(mode, x, v));
    };
    if grid[0] == 0.0 {
        record(&mut trace, 0.0, 0.0, 0.0, kernel.mode);
        next = 1;
    }
    while kernel.t < t_end {
        kernel.step(t_end);
        let crossing = kernel.crossing();
        // The grid points before the event, or up to the step's end; one at the event itself
        // is the event's row, which the trace leaves out.
        let until = crossing.map_or(kernel.t, |(t, _)| t);
        while next < grid.len() && grid[next] <= until {
            if grid[next] < until || crossing.is_none() {
                let y = kernel.dense(grid[next]);
                record(&mut trace, grid[next], y[0], y[1], kernel.mode);
            }
            next += 1;
        }
        let Some((t, which)) = crossing else { continue };
        if kernel.switch(t, which) {
            trace.stick_entries.push(t);
        }
    }
    (Settled::of(&trace, SETTLE), kernel.evals)
}

fn bench(c: &mut Criterion) {
    let points = grid();
    let general: Vec<PointRun> = points.iter().map(|&(v, k)| general_point(v, k)).collect();
    let belts: Vec<Belt> = points.iter().map(|&(v, k)| Belt::new(v, k)).collect();
    // The kernel's law is the catalog's.
    let law = ModelId::Cvs
        .build(Variant::Odd, &FrictionParams::paper())
        .expect("paper");
    for w in [-0.3, -0.05, 1e-4, 0.02, 0.5] {
        let mode = if w > 0.0 {
            Mode::SlipPositive
        } else {
            Mode::SlipNegative
        };
        let (f, expected) = (
            belts[0].law(w, mode),
            law.force(0.0, w, &[], SignLaw::Discontinuous),
        );
        assert!(
            (f - expected).abs() <= 1e-14 * expected.abs(),
            "F({w}) = {f} against {expected}"
        );
    }
    let (mut evals_general, mut evals_floor) = (0, 0);
    for (run, &belt) in general.iter().zip(&belts) {
        let g = run.run(SETTLE).expect("a valid point");
        let (s, evals) = floor_point(belt);
        // Each measure to 1e-6 of itself or of its scale (1 mm, 1 mm/s, 1 N): a steady
        // sliding's round-off ripple (x − v̄·t of 1e-10 m) has no period to agree on.
        let close = |a: f64, b: f64, scale: f64| {
            (a.is_nan() && b.is_nan()) || (a - b).abs() <= 1e-6 * a.abs().max(scale)
        };
        let (gs, bv) = (g.settled, (belt.v_belt, belt.k));
        assert_eq!(gs.to, s.to, "{bv:?}: the span");
        assert_eq!(gs.stick_phases, s.stick_phases, "{bv:?}: stick phases");
        let oscillates = gs.x_amplitude > 1e-3;
        for (name, a, b, scale) in [
            ("x_amplitude", gs.x_amplitude, s.x_amplitude, 1e-3),
            ("v_mean", gs.v_mean, s.v_mean, 1e-3),
            ("friction_mean", gs.friction_mean, s.friction_mean, 1.0),
            (
                "period",
                gs.period,
                s.period,
                if oscillates { 0.0 } else { f64::INFINITY },
            ),
        ] {
            assert!(
                close(a, b, scale),
                "{bv:?}: {name} {a} against the kernel's {b}"
            );
        }
        evals_general += g.stats.rhs_evals;
        evals_floor += evals;
    }
    let ratio = evals_floor as f64 / evals_general as f64;
    assert!(
        (ratio - 1.0).abs() <= 0.01,
        "f evaluations: kernel {evals_floor}, general {evals_general}"
    );
    eprintln!(
        "{} points: {evals_general} f evaluations (general), {evals_floor} (kernel)",
        points.len()
    );
    let mut group = c.benchmark_group("sweep_floor");
    group.sample_size(10);
    group.bench_function("general", |b| {
        b.iter(|| {
            general
                .iter()
                .map(|r| r.run(SETTLE).expect("valid").settled.period)
                .sum::<f64>()
        })
    });
    group.bench_function("kernel", |b| {
        b.iter(|| {
            belts
                .iter()
                .map(|&belt| floor_point(black_box(belt)).0.period)
                .sum::<f64>()
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
