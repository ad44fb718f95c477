//! friction-lab's Moreau–Jean time-stepping against Siconos 4.4's, on the Burridge–Knopoff
//! chain of systems.md: ten blocks with Coulomb friction (`coulomb`, F_c = 6 N at the paper's
//! parameters, levels spread by 1 + 0.1·sin i), h = 1e-3, 10 s, θ = 1/2 and θ = 1.
//!
//! The reference trajectories in `tests/data/` were written by Siconos's `EulerMoreauOSI`
//! with a relay (`RelayNSL`, Lemke's algorithm) on the chain as a first-order linear system:
//! `scripts/peers/siconos_chain.py --n 10 --h 1e-3 --theta θ --t-end 10 --every 250`, run
//! with the system python3 and Debian's python3-siconos. Both schemes are the θ-method on the
//! springs with the friction impulse implicit at the end of the step; the blocks stick, break
//! away one after another from t ≈ 5.4 s and slide, and the two codes agree to the tolerance
//! of friction-lab's Gauss–Seidel iteration (measured: 9e-13 m and 8e-12 m/s at θ = 1/2).

use friction_models::{FrictionParams, ModelId, Variant};
use friction_systems::chain::ChainParams;
use friction_systems::{simulate, Scheme};
use integrators::{Options, Output};
use std::sync::Arc;

/// The rows of a reference file: t, then x_1..x_N, then v_1..v_N.
fn reference(name: &str) -> Vec<Vec<f64>> {
    let path = format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    text.lines()
        .skip(1)
        .map(|line| line.split(',').map(|c| c.parse().unwrap()).collect())
        .collect()
}

/// The largest differences of x and of v between friction-lab at `theta` and the reference.
fn differences(theta: f64, name: &str) -> (f64, f64, usize) {
    let rows = reference(name);
    let n = 10;
    assert!(
        rows.iter().all(|r| r.len() == 1 + 2 * n),
        "{name}: 21 columns"
    );
    let system = ChainParams::default()
        .build(&FrictionParams::paper(), |p| {
            ModelId::Coulomb.build(Variant::Odd, p).map(Arc::from)
        })
        .unwrap();
    let grid: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let options = Options {
        output: Output::GridOnly(grid),
        ..Options::fixed(0.0, 10.0, 1e-3)
    };
    let run = simulate(
        &system,
        Scheme::TimeStepping { theta },
        options,
        &mut |_| {},
    )
    .unwrap();
    assert!(run.error.is_none(), "{:?}", run.error);
    assert_eq!(run.solution.len(), rows.len());
    let (mut dx, mut dv, mut moving) = (0.0f64, 0.0f64, 0);
    for (k, row) in rows.iter().enumerate() {
        for i in 0..n {
            let b = run.body_at(i, k);
            assert_eq!(b.t, row[0]);
            dx = dx.max((b.x - row[1 + i]).abs());
            dv = dv.max((b.v - row[1 + n + i]).abs());
            moving += usize::from(row[1 + n + i].abs() > 1e-6);
        }
    }
    (dx, dv, moving)
}

#[test]
fn time_stepping_agrees_with_siconos_on_a_ten_block_chain_at_theta_one_half() {
    let (dx, dv, moving) = differences(0.5, "siconos-chain-10-theta0.5.csv");
    // The comparison covers sliding, not only the blocks at rest.
    assert!(moving > 50, "{moving} moving block states");
    assert!(dx < 1e-10 && dv < 1e-10, "|dx| {dx:e}, |dv| {dv:e}");
}

#[test]
fn time_stepping_agrees_with_siconos_on_a_ten_block_chain_at_theta_one() {
    let (dx, dv, moving) = differences(1.0, "siconos-chain-10-theta1.csv");
    assert!(moving > 50, "{moving} moving block states");
    assert!(dx < 1e-10 && dv < 1e-10, "|dx| {dx:e}, |dv| {dv:e}");
}
