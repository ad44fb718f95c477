//! Periodic orbits against exact facts: the stick–slip cycle of a block on a belt (its period
//! in closed form, its multipliers {1, 0}), the monodromy of a two-block cycle against finite
//! differences of its flow, and van der Pol's smooth cycle (its period, and its nontrivial
//! multiplier by Liouville's formula).

use friction_models::{FrictionParams, ModelId, Variant};
use friction_systems::system::End;
use friction_systems::{simulate, FrictionSystem, Scheme, Switching, System};
use integrators::{Mode, OdeProblem, Options, Solver};
use periodic::{find_orbit, flow, guess_from_run, FlowOptions, ShootingOptions, Stability};
use std::sync::Arc;

/// The static law (stick up to F_s = 7.5 N, slide at F_c = 6 N).
fn law() -> Arc<dyn friction_models::FrictionModel> {
    Arc::from(
        ModelId::Static
            .build(Variant::Odd, &FrictionParams::paper())
            .unwrap(),
    )
}

/// A block of 1 kg on a wall's spring k = 10 N/m, on a belt at 0.1 m/s.
fn block() -> System {
    let mut s = System::default();
    let body = s.add_body("block", 1.0, 0.0, 0.0);
    let wall = s.add_anchor("wall", 0.0, 0.0);
    s.add_spring(End::Body(body), End::Anchor(wall), 10.0, 0.0);
    s.add_contact(body, 0.1, law());
    s
}

/// The run's guess after `t_end` from rest, event-driven.
fn settled_guess(system: &System, t_end: f64) -> periodic::Guess {
    let options = Options::adaptive(0.0, t_end, 1e-10, 1e-12);
    let run = simulate(system, Scheme::events(Solver::DOPRI5), options, &mut |_| {}).unwrap();
    assert!(run.error.is_none(), "{:?}", run.error);
    let n = run.problem.dim() - run.problem.quadratures();
    guess_from_run(&run.solution, n).unwrap()
}

#[test]
fn a_stick_slip_cycle_has_its_closed_form_period_and_the_multipliers_one_and_zero() {
    // Slip is a harmonic arc about x_c = F_c/k from x_c + d to x_c − d (d = (F_s − F_c)/k)
    // through the far side, where (x − x_c, v/ω) turns by 2π − 2·atan(d/u), u = v_b/ω; stick
    // carries the block back at v_b over 2d.
    let (m, k, v_b, f_s, f_c) = (1.0_f64, 10.0_f64, 0.1, 7.5, 6.0);
    let omega = (k / m).sqrt();
    let (d, u) = ((f_s - f_c) / k, v_b / omega);
    let exact = (2.0 * std::f64::consts::PI - 2.0 * (d / u).atan()) / omega + 2.0 * d / v_b;
    let system = block();
    let guess = settled_guess(&system, 60.0);
    assert!(
        (guess.period - exact).abs() < 1e-6,
        "{} vs {exact}",
        guess.period
    );
    let problem = FrictionSystem::new(&system, Switching::Event);
    let orbit = find_orbit(
        &problem,
        guess.t,
        (&guess.y, &guess.modes, guess.period),
        &ShootingOptions::default(),
    )
    .unwrap();
    assert!(orbit.residual <= 1e-10, "{}", orbit.residual);
    assert!(
        (orbit.period - exact).abs() < 1e-9,
        "{} vs {exact}",
        orbit.period
    );
    // Two switches a period: slip to stick, stick to slip.
    let switches: Vec<_> = (orbit.flow.segments.iter())
        .filter_map(|s| {
            s.switch
                .as_ref()
                .map(|w| (w.before.clone(), w.after.clone()))
        })
        .collect();
    assert_eq!(switches.len(), 2, "{switches:?}");
    let mu = &orbit.floquet.multipliers;
    assert_eq!(mu.len(), 2);
    assert!(orbit.floquet.trivial_error < 1e-10, "{mu:?}");
    assert!(mu[1].0.hypot(mu[1].1) < 1e-10, "{mu:?}");
    assert_eq!(orbit.floquet.stability, Stability::Stable);
}

#[test]
fn the_monodromy_through_the_switches_is_the_derivative_of_the_flow() {
    // Two blocks, the first on the belt: a cycle with stick phases of one block only, so that
    // the flow over a period is smooth in the initial state where the switch sequence holds.
    let mut s = System::default();
    let a = s.add_body("a", 1.0, 0.0, 0.0);
    let b = s.add_body("b", 2.0, 0.0, 0.0);
    let wall = s.add_anchor("wall", 0.0, 0.0);
    s.add_spring(End::Body(a), End::Anchor(wall), 10.0, 0.0);
    s.add_spring(End::Body(a), End::Body(b), 50.0, 0.5);
    s.add_contact(a, 0.1, law());
    let guess = settled_guess(&s, 400.0);
    let problem = FrictionSystem::new(&s, Switching::Event);
    let options = FlowOptions::default();
    let base = flow(
        &problem,
        (guess.t, guess.period),
        &guess.y,
        &guess.modes,
        &options,
    )
    .unwrap();
    assert!(
        base.segments.iter().filter(|s| s.switch.is_some()).count() >= 2,
        "a cycle with switches"
    );
    let n = problem.dim() - problem.quadratures();
    let mut worst = 0.0_f64;
    for c in 0..n {
        let delta = 1e-6;
        let end = |sign: f64| {
            let mut y = guess.y.clone();
            y[c] += sign * delta;
            flow(
                &problem,
                (guess.t, guess.period),
                &y,
                &guess.modes,
                &options,
            )
            .unwrap()
            .y_end
        };
        let (up, down) = (end(1.0), end(-1.0));
        for r in 0..n {
            let fd = (up[r] - down[r]) / (2.0 * delta);
            worst = worst.max((fd - base.sensitivity[(r, c)]).abs());
        }
    }
    assert!(
        worst < 1e-5,
        "monodromy against central differences: {worst:e}"
    );
}

/// Van der Pol's oscillator x'' − μ(1 − x²)x' + x = 0 with the divergence of its field,
/// μ(1 − x²), as a quadrature: its integral over a period is log of the nontrivial multiplier
/// (Liouville: the product of the multipliers is exp ∮ div f dt).
struct VanDerPol {
    mu: f64,
}

impl OdeProblem for VanDerPol {
    fn dim(&self) -> usize {
        3
    }

    fn rhs(&self, _t: f64, y: &[f64], _modes: &[Mode], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = self.mu * (1.0 - y[0] * y[0]) * y[1] - y[0];
        dy[2] = self.mu * (1.0 - y[0] * y[0]);
    }

    /// Analytic over (x, y): finite differences would put their rounding noise into the
    /// variational equations.
    fn jacobian(
        &self,
        _t: f64,
        y: &[f64],
        _modes: &[Mode],
        jac: &mut Vec<integrators::Entry>,
    ) -> bool {
        jac.extend([
            (0, 1, 1.0),
            (1, 0, -2.0 * self.mu * y[0] * y[1] - 1.0),
            (1, 1, self.mu * (1.0 - y[0] * y[0])),
        ]);
        true
    }

    fn quadratures(&self) -> usize {
        1
    }
}

#[test]
fn van_der_pols_cycle_has_its_known_period_and_liouvilles_multiplier() {
    let problem = VanDerPol { mu: 1.0 };
    // A rough guess: on the x axis near the cycle, period 2π.
    let orbit = find_orbit(
        &problem,
        0.0,
        (&[2.0, 0.0, 0.0], &[Mode(0)], 2.0 * std::f64::consts::PI),
        &ShootingOptions::default(),
    )
    .unwrap();
    // The period of van der Pol's cycle at μ = 1 (Strogatz 2015, §7.5; to 13 digits,
    // 6.663286859323).
    assert!(
        (orbit.period - 6.663_286_859_323).abs() < 1e-9,
        "{}",
        orbit.period
    );
    let divergence = orbit.flow.y_end[2] - orbit.y0[2];
    let mu = &orbit.floquet.multipliers;
    assert!(orbit.floquet.trivial_error < 1e-9, "{mu:?}");
    assert!(
        (mu[1].0 - divergence.exp()).abs() < 1e-9,
        "{mu:?} vs {}",
        divergence.exp()
    );
    assert_eq!(orbit.floquet.stability, Stability::Stable);
}
