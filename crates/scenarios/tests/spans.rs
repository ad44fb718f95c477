//! A run extended span by span ([`scenarios::run_until`]) gives the outcomes of the runs from
//! the start, bit for bit.

use friction_models::{FrictionParams, ModelId};
use friction_systems::Scheme;
use integrators::Solver;
use scenarios::analysis::settled::{spanned, until_settled};
use scenarios::stick_slip::belt_run;
use scenarios::{run, run_until, Outcome, RunSpec};

fn belt(v_belt: f64, k: f64, solver: Solver) -> RunSpec {
    let base = belt_run(ModelId::Cvs, &FrictionParams::paper());
    let mut params = base.params;
    (params.v_belt, params.k) = (v_belt, k);
    RunSpec {
        params,
        scheme: Scheme::events(solver),
        output_points: 2001,
        ..base
    }
}

/// The outcome after `spans` spans, by both ways.
fn both(spec: &RunSpec, spans: usize) -> (Outcome, Outcome) {
    let mut seen = 0;
    let extended = run_until(spec, &mut |_| {
        seen += 1;
        seen == spans
    })
    .unwrap();
    let mut seen = 0;
    let fresh = until_settled(
        |factor| run(&spanned(spec, factor), &mut |_| {}),
        |_| {
            seen += 1;
            seen == spans
        },
    )
    .unwrap();
    (extended, fresh)
}

/// `spec` over `spans` spans both ways: the same outcome, over `t_last`, with more than
/// `events` events.
fn assert_extended_is_fresh(spec: &RunSpec, spans: usize, t_last: f64, events: usize) {
    let (extended, fresh) = both(spec, spans);
    assert_eq!(fresh.rows.last().unwrap().t, t_last);
    assert!(fresh.events.len() > events, "{} events", fresh.events.len());
    assert_eq!(extended.events, fresh.events);
    assert_eq!(extended.rows, fresh.rows);
    assert_eq!(extended.stats, fresh.stats);
}

#[test]
fn a_stick_slip_run_extended_twice_is_the_run_over_four_spans() {
    assert_extended_is_fresh(&belt(0.01, 10.0, Solver::DOPRI5), 3, 160.0, 5);
}

#[test]
fn an_auto_run_extended_to_eight_spans_is_the_run_over_eight() {
    assert_extended_is_fresh(&belt(0.03, 30.0, Solver::AUTO), 4, 320.0, 20);
}

#[test]
fn an_extended_runs_wall_time_counts_its_spans() {
    let spec = belt(0.01, 10.0, Solver::DOPRI5);
    let mut times = Vec::new();
    let o = run_until(&spec, &mut |o| {
        times.push(o.wall_time_s);
        times.len() == 3
    })
    .unwrap();
    assert!(times[0] > 0.0, "{times:?}");
    assert!(times.windows(2).all(|w| w[1] >= w[0]), "{times:?}");
    assert_eq!(o.wall_time_s, times[2]);
}
