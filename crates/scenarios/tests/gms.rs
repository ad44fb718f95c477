//! The generalized Maxwell-slip model against the properties Al-Bender, Lampaert and Swevers
//! (2005) build it for: in pre-sliding, a rate-independent hysteresis with non-local memory
//! (Masing's rule and the wiping-out of closed inner loops).

use friction_models::{FrictionModel, FrictionParams, ModelId, Parameters, SignLaw, Variant};
use friction_systems::Switching;
use integrators::{Options, Solver};
use scenarios::motion::{Kinematic, Motion};

/// Slow enough that the Stribeck curve is at F_s (v ≪ v_s) and damping is negligible.
const SPEED: f64 = 1e-6;

/// The paper's set with the slip law's attraction raised to 1e9 N/s, so that a block leaves its
/// stick law within k·|v|·g/C ≈ 1e-7 N of its limit (the switched GMS of the paper).
fn params(attraction: f64) -> FrictionParams {
    let mut p = FrictionParams::paper();
    p.set("C_gms", attraction).unwrap();
    p
}

/// Walks the contact from rest through the turning points `path` (displacements, m) at
/// constant speed; returns the friction force held at rest at each turning point.
fn walk(model: &dyn FrictionModel, path: &[f64]) -> Vec<f64> {
    let mut z = vec![0.0; model.n_states()];
    let mut x = 0.0;
    let mut forces = Vec::new();
    for &target in path {
        let v = SPEED * (target - x).signum();
        let k = Kinematic {
            model,
            motion: Motion::Constant { v },
            switching: Switching::Naive,
        };
        let mut y0 = z.clone();
        y0.extend([0.0, 0.0]);
        let t_end = (target - x).abs() / SPEED;
        let s = Solver::BDF
            .solve(
                &k,
                &y0,
                &[k.mode_at(0.0)],
                Options::adaptive(0.0, t_end, 1e-10, 1e-16),
            )
            .unwrap();
        z = s.y_at(s.len() - 1)[..z.len()].to_vec();
        x = target;
        // The force held at rest on arrival (the springs' force, without the damping of the
        // motion).
        forces.push(model.force(x, 0.0, &z, SignLaw::Discontinuous));
    }
    forces
}

/// The virgin (initial loading) curve of the switched model at low speed:
/// `F(x) = Σ_i min(k_i·x, α_i·F_s)`, with k_i = σ0/n and α_i = (2i − 1)/n².
fn virgin(p: &FrictionParams, x: f64) -> f64 {
    let n = p.n_gms;
    (1..=n as usize)
        .map(|i| (p.sigma0 / n * x).min((2 * i - 1) as f64 / (n * n) * p.f_s))
        .sum()
}

#[test]
fn presliding_follows_masing_and_wipes_out_closed_inner_loops() {
    let p = params(1e9);
    let gms = ModelId::Gms.build(Variant::Odd, &p).unwrap();
    // Blocks break away at (2i − 1)·F_s/(n·σ0) = 18.75, 56.25, 93.75, 131.25 µm; every turning
    // point stays below the last, in pre-sliding.
    let (x1, x2, x3) = (100e-6, 20e-6, 120e-6);
    let f = walk(gms.as_ref(), &[x1, x2, x1, x3]);
    let tol = 1e-6 * p.f_s;
    // The virgin curve.
    assert!(
        (f[0] - virgin(&p, x1)).abs() < tol,
        "{} vs {}",
        f[0],
        virgin(&p, x1)
    );
    // Masing's rule: from the reversal at x1 the curve is the virgin one, doubled in both axes.
    let masing = f[0] - 2.0 * virgin(&p, (x1 - x2) / 2.0);
    assert!((f[1] - masing).abs() < tol, "{} vs {masing}", f[1]);
    // Non-local memory: back at x1 the inner loop closes on the force it left...
    assert!((f[2] - f[0]).abs() < tol, "{} vs {}", f[2], f[0]);
    // ...and the outer curve goes on as if the loop had never been.
    assert!(
        (f[3] - virgin(&p, x3)).abs() < tol,
        "{} vs {}",
        f[3],
        virgin(&p, x3)
    );
    // A Dahl-type single state has no such memory: LuGre's force back at x1 differs from the
    // force it left by more than a hundred times that tolerance.
    let lugre = ModelId::LuGre.build(Variant::Odd, &p).unwrap();
    let g = walk(lugre.as_ref(), &[x1, x2, x1]);
    assert!((g[2] - g[0]).abs() > 100.0 * tol, "{} vs {}", g[2], g[0]);
}

#[test]
fn the_default_attraction_is_within_a_percent_of_the_switched_model() {
    // With C = 1e4·F_s per second (the parameter sets' value) each block leaves its stick law
    // k_i·|v|·g/C early: at 1 µm/s, 0.5 % of the smallest block's share.
    let p = FrictionParams::paper();
    let gms = ModelId::Gms.build(Variant::Odd, &p).unwrap();
    let f = walk(gms.as_ref(), &[100e-6, 20e-6, 100e-6]);
    let exact = virgin(&p, 100e-6);
    assert!((f[0] - exact).abs() < 0.01 * exact, "{} vs {exact}", f[0]);
    assert!((f[2] - f[0]).abs() < 0.01 * exact, "{} vs {}", f[2], f[0]);
}
