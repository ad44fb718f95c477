//! The analytic Jacobian of a system against central differences of its right-hand side, in
//! every mode and treatment; and its size, which makes implicit solvers sparse and linear in N.

use friction_models::{FrictionParams, ModelId, Variant};
use friction_systems::chain::ChainParams;
use friction_systems::{FrictionSystem, Switching, System, SLIP_NEGATIVE, SLIP_POSITIVE, STICK};
use integrators::{linear, Mode, OdeProblem};
use std::sync::Arc;

fn chain(model: ModelId, n: usize) -> System {
    let c = ChainParams {
        n_bodies: n,
        ..ChainParams::default()
    };
    let mut s = c
        .build(&FrictionParams::paper(), |p| {
            model.build(Variant::Odd, p).map(Arc::from)
        })
        .unwrap();
    // A damper between the first two blocks, so that damping terms are checked too.
    s.springs[1].c = 0.7;
    s
}

/// Largest |analytic − central difference| over the bodies' unknowns, relative to the entry.
fn jacobian_error(p: &FrictionSystem, y: &[f64], modes: &[Mode]) -> f64 {
    let n = p.layout.accumulators;
    let mut analytic = vec![0.0; n * n];
    let mut entries = Vec::new();
    assert!(p.jacobian(0.3, y, modes, &mut entries));
    for (i, j, a) in entries {
        analytic[i * n + j] += a;
    }
    let mut worst: f64 = 0.0;
    let (mut fp, mut fm) = (vec![0.0; p.dim()], vec![0.0; p.dim()]);
    for j in 0..n {
        // Large enough that LuGre's bristle force (σ0·z ≈ 5e4 N) leaves no round-off in the
        // difference, small enough for the curvature of the laws.
        let h = 1e-6 * y[j].abs().max(0.1);
        let (mut yp, mut ym) = (y.to_vec(), y.to_vec());
        yp[j] += h;
        ym[j] -= h;
        p.rhs(0.3, &yp, modes, &mut fp);
        p.rhs(0.3, &ym, modes, &mut fm);
        for i in 0..n {
            let fd = (fp[i] - fm[i]) / (2.0 * h);
            let a = analytic[i * n + j];
            worst = worst.max((a - fd).abs() / a.abs().max(1.0));
        }
    }
    worst
}

#[test]
fn the_analytic_jacobian_matches_central_differences_in_every_mode() {
    for model in [
        ModelId::Cs,
        ModelId::Sv,
        ModelId::LuGre,
        ModelId::Dahl,
        ModelId::Gms,
    ] {
        let system = chain(model, 4);
        for switching in [
            Switching::Event,
            Switching::Regularized { epsilon: 0.05 },
            Switching::Naive,
        ] {
            let p = FrictionSystem::new(&system, switching);
            let mut y = p.initial_state();
            // Velocities and internal states away from zero, in both directions.
            for i in 0..4 {
                y[p.layout.x[i]] = 0.01 * (i as f64 + 1.0);
                y[p.layout.v(i)] = if i % 2 == 0 { 0.3 } else { -0.2 };
                // GMS's blocks (deflections of some 1e-5 m) on both sides of their limits.
                for (k, z) in p.layout.z[i].clone().enumerate() {
                    y[z] = if model == ModelId::Gms {
                        1e-5 * (k as f64 + 1.0)
                    } else {
                        0.5
                    };
                }
            }
            let modes = [SLIP_POSITIVE, SLIP_NEGATIVE, STICK, SLIP_POSITIVE];
            if switching == Switching::Event {
                // A stuck body moves with its surface. (Without modes, a body at exactly
                // v_rel = 0 sits on the discontinuity, where no derivative exists.)
                y[p.layout.v(2)] = 0.0;
            }
            let e = jacobian_error(&p, &y, &modes);
            assert!(e < 1e-5, "{model} {switching:?}: relative error {e:e}");
        }
    }
}

#[test]
fn a_chain_jacobian_is_sparse_and_grows_linearly() {
    let mut sizes = Vec::new();
    for n in [100, 1000] {
        let system = chain(ModelId::Cs, n);
        let p = FrictionSystem::new(&system, Switching::Event);
        let y = p.initial_state();
        let modes = vec![SLIP_POSITIVE; n];
        let mut entries = Vec::new();
        p.jacobian(0.0, &y, &modes, &mut entries);
        assert_eq!(
            linear::choice(p.dim(), entries.len()),
            "faer sparse LU",
            "N = {n}"
        );
        sizes.push(entries.len());
    }
    // About 13 entries per block (x row, two springs' four entries in the v row, friction),
    // whatever N.
    assert!(sizes[1] < 14 * 1000 && sizes[1] > 9 * sizes[0], "{sizes:?}");
}
