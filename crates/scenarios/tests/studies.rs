//! The study code recovers known orders, sees the jump at v = 0 cost an order, and judges
//! step-size independence correctly where the answer is known.

use friction_models::{FrictionParams, ModelId};
use friction_systems::{Scheme, Switching};
use integrators::Solver;
use scenarios::studies::{
    convergence, independence, Case, ErrorMeasure, Fit, Method, Reference, StudyCase,
};
use scenarios::{Limits, Scenario};

/// The block pushed by 15 N against viscous friction: smooth, with a closed form.
fn viscous_block() -> Case {
    Case {
        scenario: Scenario::PAPER_BLOCK,
        law: ModelId::Viscous.into(),
        friction: FrictionParams::paper(),
        params: Scenario::PAPER_BLOCK.defaults(),
        t_end: 5.0,
        limits: Limits::default(),
    }
}

fn fit(case: &Case, method: Method, steps: &[f64], measure: ErrorMeasure) -> Fit {
    let c = convergence(case, &[method], steps, &[], &|| {}).unwrap();
    let t = c.orders.iter().find(|t| t.measure == measure).unwrap();
    t.fit.expect("an asymptotic range")
}

fn slope(case: &Case, method: Method, steps: &[f64], measure: ErrorMeasure) -> f64 {
    fit(case, method, steps, measure).slope
}

#[test]
fn the_study_recovers_the_orders_of_the_methods_on_a_smooth_problem() {
    let case = viscous_block();
    let c = convergence(
        &case,
        &[Method::events(Solver::RK4)],
        &[0.4, 0.2],
        &[],
        &|| {},
    )
    .unwrap();
    assert!(
        matches!(c.reference, Reference::ClosedForm(_)),
        "{:?}",
        c.reference
    );
    // RK4's order, with an interval that holds 4, from every pair of the four steps.
    let rk4 = fit(
        &case,
        Method::events(Solver::RK4),
        &[0.4, 0.2, 0.1, 0.05],
        ErrorMeasure::GridRelative,
    );
    assert!((rk4.slope - 4.0).abs() < 0.2, "rk4 {rk4:?}");
    assert!(rk4.ci[0] < 4.0 && 4.0 < rk4.ci[1], "rk4 {rk4:?}");
    assert!(rk4.ci[1] - rk4.ci[0] < 0.5, "rk4 {rk4:?}");
    assert_eq!((rk4.pairs_used, rk4.range), (3, [0.05, 0.4]));
    let dopri5 = slope(
        &case,
        Method::events(Solver::DOPRI5),
        &[1.0, 0.5, 0.25, 0.125],
        ErrorMeasure::GridRelative,
    );
    assert!((dopri5 - 5.0).abs() < 0.3, "dopri5 {dopri5}");
    let euler = slope(
        &case,
        Method::events(Solver::IMPLICIT_EULER),
        &[0.04, 0.02, 0.01, 0.005],
        ErrorMeasure::GridRelative,
    );
    assert!((euler - 1.0).abs() < 0.1, "implicit Euler {euler}");
}

/// Free vibration against Coulomb friction with stiction (m = 1, k = 100, x0 = 0.5): every
/// half period π/10 s the velocity crosses zero and the friction jumps; after four half
/// periods the body sticks at x = 0.02 m.
fn coulomb_vibration() -> Case {
    Case {
        scenario: Scenario::FREE_VIBRATION,
        law: ModelId::Static.into(),
        friction: FrictionParams::paper(),
        params: Scenario::FREE_VIBRATION.defaults(),
        t_end: 2.0,
        limits: Limits::default(),
    }
}

#[test]
fn stepping_through_v_0_costs_rk4_its_order_and_event_location_restores_it() {
    let steps = [2e-2, 1e-2, 5e-3, 2.5e-3];
    let naive = slope(
        &coulomb_vibration(),
        Method::of(Scheme::EventDriven {
            solver: Solver::RK4,
            switching: Switching::Naive,
        }),
        &steps,
        ErrorMeasure::GridRelative,
    );
    assert!((naive - 1.0).abs() < 0.25, "naive {naive}");
    let switched = slope(
        &coulomb_vibration(),
        Method::events(Solver::RK4),
        &steps,
        ErrorMeasure::GridRelative,
    );
    assert!((switched - 4.0).abs() < 0.25, "switched {switched}");
    // The switched events are the closed form's: reversals every π/ω.
    let c = convergence(
        &coulomb_vibration(),
        &[Method::events(Solver::RK4)],
        &[1e-3],
        &[],
        &|| {},
    )
    .unwrap();
    let m = &c.runs[0].measures;
    for (k, t) in m.event_times.iter().take(4).enumerate() {
        assert!(
            (t - (k + 1) as f64 * std::f64::consts::PI / 10.0).abs() < 1e-9,
            "event {k} at {t}"
        );
    }
    assert!(
        (m.final_state[0] - 0.02).abs() < 1e-9,
        "rest at {}",
        m.final_state[0]
    );
}

#[test]
fn the_independence_verdict_is_negative_for_a_coarse_step_and_positive_for_a_fine_one() {
    let case = viscous_block();
    let coarse = independence(
        &case,
        Method::events(Solver::RK4),
        2.0,
        2.0,
        3,
        1e-6,
        &|| {},
    )
    .unwrap();
    assert!(!coarse.independent, "{:?}", coarse.outputs);
    let fine = independence(
        &case,
        Method::events(Solver::RK4),
        1e-2,
        2.0,
        3,
        1e-6,
        &|| {},
    )
    .unwrap();
    assert!(fine.independent, "{:?}", fine.outputs);
    // The Richardson estimate of the remaining error in v(5) bounds the true error.
    let v = fine
        .outputs
        .iter()
        .find(|o| o.name.starts_with("final v"))
        .unwrap();
    let exact = 30.0 * (1.0 - (-2.5f64).exp());
    assert!(
        (v.values[2] - exact).abs() <= 2.0 * v.remaining_error + 1e-12,
        "{v:?}"
    );
}

#[test]
fn levels_outside_the_asymptotic_range_do_not_make_a_small_richardson_estimate() {
    // GMS's stiff bristles in free vibration: RK4 diverges at 1e-3 (level 0: non-finite) and
    // at 5e-4 (level 1: beyond the system's reach by t = 0.45 s; it once ended at x = -1.9e70 m
    // and made the differences fall by 2e68 in one halving, an order of 226 whose Richardson
    // estimate called x independent), ends at 86 m at 2.5e-4, and is accurate only from
    // 1.25e-4. The differences then still fall far faster than RK4's order allows (an order
    // of 32). Taken at most at order 4, the estimate must bound the true error of the finest
    // level, here against BDF at 1e-11.
    let case = Case {
        scenario: Scenario::FREE_VIBRATION,
        law: ModelId::Gms.into(),
        params: Scenario::FREE_VIBRATION.defaults(),
        t_end: 10.0,
        ..viscous_block()
    };
    let study = independence(
        &case,
        Method::events(Solver::RK4),
        1e-3,
        2.0,
        5,
        1e-6,
        &|| {},
    )
    .unwrap();
    assert_eq!(study.first_level, 2, "{:?}", study.failed);
    assert!(
        study.failed.iter().all(|f| f.diverged),
        "{:?}",
        study.failed
    );
    let x = &study.outputs[0];
    assert!(x.name.starts_with("final x"), "{x:?}");
    // 86 m to 1.6e-8 m in one halving: an observed order far beyond RK4's 4.
    assert!(x.order.is_some_and(|p| p > 20.0), "{x:?}");
    let bdf = Solver::from_name("bdf").unwrap();
    let tight = integrators::StepControl::Adaptive {
        rtol: 1e-11,
        atol: 1e-13,
        h0: None,
    };
    let truth = case
        .measure(Scheme::events(bdf), tight)
        .unwrap()
        .measures
        .final_state[0];
    let error = (x.values.last().unwrap() - truth).abs();
    assert!(error > 1e-10, "a true error to bound: {error:e}");
    assert!(error <= x.remaining_error, "{error:e} against {x:?}");
}

#[test]
fn the_stiffness_verdict_names_a_crossover_only_inside_the_sweep() {
    use scenarios::studies::{
        crossover, Cost, Reached, StepKind, Stiffness, StiffnessPoint, Winner,
    };
    // Each value's winner (None: no method met the target there), among the methods studied.
    let studied = |outcomes: &[Option<bool>], kinds: &[bool]| {
        let points: Vec<StiffnessPoint> = outcomes
            .iter()
            .enumerate()
            .map(|(i, &w)| StiffnessPoint {
                value: 10f64.powi(-(i as i32)),
                costs: kinds
                    .iter()
                    .map(|&implicit| Cost {
                        solver: if implicit { "bdf" } else { "dopri5" }.into(),
                        implicit,
                        reached: w.map(|_| Reached {
                            resolution: 1e-6,
                            step: StepKind::Adaptive,
                            error: 1e-4,
                            stats: integrators::Stats::default(),
                            work: 10,
                            work_estimate: 10.0,
                            work_bracket: [Some(9.0), Some(10.0)],
                        }),
                    })
                    .collect(),
                winner: w.map(|i| {
                    if i {
                        Winner::Implicit
                    } else {
                        Winner::Explicit
                    }
                }),
                reference: Reference::ClosedForm("exact".into()),
                reference_limit: None,
            })
            .collect();
        Stiffness {
            parameter: "epsilon".into(),
            target: 1e-3,
            crossover: crossover(&points),
            points,
        }
    };
    let sweep = |wins: &[bool]| {
        studied(
            &wins.iter().map(|&w| Some(w)).collect::<Vec<_>>(),
            &[true, false],
        )
    };
    // The crossover of the files is the verdict's: none where one kind wins everywhere (the
    // JSON once named the first value then) or the winner changes twice.
    let named: Vec<Option<f64>> = [
        &[true, true, true][..],
        &[false, true, true],
        &[false, true, false],
    ]
    .iter()
    .map(|w| sweep(w).crossover)
    .collect();
    assert_eq!(named, [None, Some(0.1), None]);
    assert_eq!(
        sweep(&[true, true, true]).verdict(),
        "the implicit solvers win at every epsilon of the sweep: no crossover in this range"
    );
    assert_eq!(
        sweep(&[false, false]).verdict(),
        "the explicit solvers win at every epsilon of the sweep: no crossover in this range"
    );
    assert_eq!(
        sweep(&[false, true, true]).verdict(),
        "the implicit solvers overtake the explicit ones from epsilon = 0.1"
    );
    assert!(sweep(&[false, true, false])
        .verdict()
        .starts_with("the winner changes more than once"));
    // One kind studied: no winner (`stiffness --solvers bdf`, or a time-stepped study, said
    // "the implicit solvers win at every epsilon").
    let only_implicit = studied(&[Some(true), Some(true)], &[true]);
    assert_eq!(
        only_implicit.verdict(),
        "only implicit methods were studied (bdf): nothing to compare them with; their cost \
         against epsilon is in stiffness.csv"
    );
    assert_eq!(only_implicit.crossover, None);
    assert!(studied(&[Some(false)], &[false])
        .verdict()
        .starts_with("only explicit methods were studied (dopri5)"));
    // A value where no method met the target has no winner (it counted as the explicit
    // solvers' win), and a crossover is read over the others.
    let gap = studied(&[Some(false), None, Some(true), Some(true)], &[true, false]);
    assert_eq!(
        gap.verdict(),
        "the implicit solvers overtake the explicit ones from epsilon = 0.01; no method met \
         the target at epsilon = 0.1"
    );
    assert_eq!(gap.crossover, Some(0.01));
    assert_eq!(
        studied(&[None, None], &[true, false]).verdict(),
        "no method met the target at any epsilon of the sweep"
    );
}

/// The switched belt (CS, event switching), which has no closed form.
fn switched_belt() -> Case {
    Case {
        scenario: Scenario::BELT,
        law: ModelId::Cs.into(),
        friction: FrictionParams::paper(),
        params: Scenario::BELT.defaults(),
        t_end: 5.0,
        limits: Limits::default(),
    }
}

#[test]
fn the_reference_is_an_independent_tight_run_cross_checked_by_another() {
    use scenarios::studies::reference;
    let case = switched_belt();
    let tsit45 = Solver::from_name("tsit45").unwrap();
    let solver_of = |r: &Reference| match r {
        Reference::Run {
            solver,
            cross_check,
            ..
        } => (*solver, *cross_check),
        other => panic!("{other:?}"),
    };
    // Always cross-checked by the other 5(4) pair: their difference is the reference's
    // estimated error.
    let (r, _) = reference(&case, &[Method::events(Solver::RK4)]).unwrap();
    assert_eq!((solver_of(&r).0, solver_of(&r).1 .0), ("dopri5", "tsit45"));
    let (r, _) = reference(&case, &[Method::events(Solver::DOPRI5)]).unwrap();
    assert_eq!((solver_of(&r).0, solver_of(&r).1 .0), ("tsit45", "dopri5"));
    let (r, _) = reference(
        &case,
        &[Method::events(Solver::DOPRI5), Method::events(tsit45)],
    )
    .unwrap();
    let (solver, (other, difference)) = solver_of(&r);
    assert_eq!((solver, other), ("dopri5", "tsit45"));
    // Two independent 5(4) codes at 1e-13 agree far below the tolerances a study uses.
    assert!(difference < 1e-10, "{difference:e}");
    assert_eq!(r.estimated_error(), difference);
}

#[test]
fn a_study_whose_reference_fails_starts_no_run_after_it() {
    use scenarios::studies::{work_precision, Method};
    use std::sync::atomic::{AtomicUsize, Ordering};
    // 100 steps: the reference (Dormand–Prince at 1e-13 over 5 s) fails. RK4's runs at
    // 1e-3 and 1e-4 are expected longer (5e3 and 5e4 steps against about 7e2), and were
    // scheduled, and run to their own step cap, before it.
    let case = Case {
        limits: Limits {
            max_steps: 100,
            ..Limits::default()
        },
        ..switched_belt()
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let ran = AtomicUsize::new(0);
    let e = pool
        .install(|| {
            work_precision(
                &case,
                &[Method::events(Solver::RK4)],
                &[1e-3, 1e-4],
                &[],
                1,
                &|| {
                    ran.fetch_add(1, Ordering::Relaxed);
                },
            )
        })
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("the reference run (dopri5) failed: too many steps"),
        "{e}"
    );
    assert_eq!(ran.into_inner(), 0);
}

/// The viscous block, its runs at h = 0.01 capped at ten steps (so they fail), every run's
/// step recorded.
struct Counted {
    block: Case,
    calls: std::sync::Mutex<Vec<f64>>,
}

impl StudyCase for Counted {
    fn describe(&self) -> String {
        self.block.describe()
    }
    fn t_end(&self) -> f64 {
        self.block.t_end
    }
    fn dim(&self) -> Result<usize, scenarios::ScenarioError> {
        self.block.dim()
    }
    fn with_parameter(
        &self,
        name: &str,
        value: f64,
    ) -> Result<Box<dyn StudyCase>, scenarios::ScenarioError> {
        self.block.with_parameter(name, value)
    }
    fn measure(
        &self,
        scheme: Scheme,
        step: integrators::StepControl,
    ) -> Result<scenarios::studies::Measured, scenarios::ScenarioError> {
        let h = step.given_step().unwrap_or(0.0);
        self.calls.lock().unwrap().push(h);
        let capped = Case {
            limits: Limits {
                max_steps: 10,
                ..Limits::default()
            },
            ..self.block.clone()
        };
        if h == 0.01 { &capped } else { &self.block }.measure(scheme, step)
    }
    fn closed_form(&self) -> Option<(String, scenarios::studies::Measures)> {
        self.block.closed_form()
    }
}

#[test]
fn a_run_that_failed_is_not_timed_again() {
    use scenarios::studies::{work_precision, Method};
    // One thread, so that each first run ends before its repeats start: three repeats of the
    // run that succeeds, none of the one that failed (they would fail alike).
    let case = Counted {
        block: viscous_block(),
        calls: Default::default(),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let w = pool
        .install(|| {
            work_precision(
                &case,
                &[Method::events(Solver::RK4)],
                &[0.01, 0.005],
                &[],
                4,
                &|| {},
            )
        })
        .unwrap();
    let calls = case.calls.into_inner().unwrap();
    assert_eq!(calls.iter().filter(|&&h| h == 0.01).count(), 1, "{calls:?}");
    assert_eq!(
        calls.iter().filter(|&&h| h == 0.005).count(),
        4,
        "{calls:?}"
    );
    assert!(matches!(
        w.runs[0].failure,
        Some(integrators::SolverError::TooManySteps { .. })
    ));
    assert!(w.runs[0].wall_time.median > 0.0 && w.runs[1].failure.is_none());
    // The failed run was timed once, the other four times.
    assert_eq!(
        (w.runs[0].wall_time.repeats, w.runs[1].wall_time.repeats),
        (1, 4)
    );
}

#[test]
fn a_system_study_draws_regularised_bdf_and_time_stepping_beside_its_solvers() {
    use friction_systems::chain::ChainParams;
    use scenarios::studies::{work_precision, Method, SystemCase};
    use std::sync::Arc;
    let system = ChainParams {
        n_bodies: 5,
        ..ChainParams::default()
    }
    .build(&FrictionParams::paper(), |p| {
        ModelId::Coulomb
            .build(friction_models::Variant::Odd, p)
            .map(Arc::from)
    })
    .unwrap();
    let case = SystemCase::new("chain", system, 10.0);
    let peers = [
        Method::peer(Scheme::EventDriven {
            solver: Solver::BDF,
            switching: Switching::Regularized { epsilon: 1e-3 },
        }),
        Method::peer(Scheme::TimeStepping { theta: 0.5 }),
    ];
    let labels: Vec<String> = peers.iter().map(Method::label).collect();
    assert_eq!(labels, ["bdf (regularized)", "moreau-jean (timestepping)"]);
    let mut methods = vec![Method::events(Solver::DOPRI5)];
    methods.extend(peers);
    let w = work_precision(&case, &methods, &[1e-2, 1e-3], &[1e-6, 1e-8], 1, &|| {}).unwrap();
    let errors = |label: &str| -> Vec<f64> {
        w.runs
            .iter()
            .filter(|r| r.solver == label)
            .map(|r| r.errors.grid_relative)
            .collect()
    };
    // Time-stepping takes the step sizes and converges (Coulomb: continuous at break-away).
    let stepped = errors("moreau-jean (timestepping)");
    assert_eq!(stepped.len(), 2);
    assert!(stepped[1] < stepped[0] / 20.0, "{stepped:?}");
    // Regularised BDF takes the tolerances; its error against the event-driven reference stops
    // at the regularisation's, far above event-driven Dormand–Prince at the same tolerance.
    let regularized = errors("bdf (regularized)");
    let dopri5 = errors("dopri5");
    assert_eq!(regularized.len(), 2);
    assert!(
        regularized[1] > 100.0 * dopri5[1],
        "{regularized:?} {dopri5:?}"
    );
}

/// Every result of a sweep study is that of its case run alone, whatever the number of
/// threads and with the timing repeats in the same list.
#[test]
fn a_sweep_in_one_list_gives_each_case_its_own_results_on_one_or_two_threads() {
    use scenarios::batch::{expected_steps, run_cases, Posed};
    use scenarios::studies::{run_against_reference, Method, StudyCase};
    let belt = switched_belt();
    let stiff = belt.with_parameter("k", 400.0).unwrap();
    let cases: [&dyn StudyCase; 2] = [&belt, stiff.as_ref()];
    let solvers = [Solver::RK4, Solver::DOPRI5, Solver::IMPLICIT_EULER];
    let methods = solvers.map(Method::events);
    let jobs = Method::jobs(&methods, &[0.01, 0.005], &[1e-4, 1e-6], false);
    assert_eq!(jobs.len(), 6);
    // The list's order: implicit Euler (order 1) at 1e-6 expects 5·1e3 steps, RK4 at
    // h = 0.005 expects 1e3, Dormand–Prince at 1e-6 5·10 = 50.
    let steps = |j: usize| expected_steps(&jobs[j].0, jobs[j].1, 5.0);
    assert!((steps(5) - 5e3).abs() < 1e-9, "{}", steps(5));
    assert!((steps(1) - 1e3).abs() < 1e-9, "{}", steps(1));
    assert!((steps(3) - 50.0).abs() < 1e-9, "{}", steps(3));
    // Debug text compares NaN errors (event counts that differ) as equal.
    let without_times = |mut runs: Vec<scenarios::studies::StudyRun>| {
        runs.iter_mut()
            .for_each(|r| r.wall_time = Default::default());
        format!("{runs:?}")
    };
    let alone: Vec<_> = cases
        .iter()
        .map(|&c| {
            let (r, m, runs) = run_against_reference(c, &methods, &jobs, &|| {}).unwrap();
            (r, m, without_times(runs))
        })
        .collect();
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let counted = std::sync::atomic::AtomicUsize::new(0);
        let together = pool
            .install(|| {
                let posed = cases.map(|case| Posed {
                    case,
                    reference_for: Some(&methods),
                    jobs: &jobs,
                });
                run_cases(&posed, 2, &|| {
                    counted.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                })
            })
            .unwrap();
        // Progress counts the runs and their timing repeats, not the reference runs.
        assert_eq!(counted.into_inner(), 2 * jobs.len() * 3);
        for (c, (r, m, runs)) in together.into_iter().zip(&alone) {
            assert_eq!(c.reference.as_ref(), Some(&(r.clone(), m.clone())));
            assert!(c.runs.iter().all(|r| r.errors.grid_relative.is_finite()));
            assert_eq!(&without_times(c.runs), runs, "{threads} threads");
        }
    }
    // The stiffer belt is a different problem: its reference differs.
    assert_ne!(alone[0].1, alone[1].1);
}

/// A pair whose error does not decrease far above round-off is stalled, not round-off; one at
/// the floor is round-off; one whose coarser run has no correct digit is out too; none of them
/// enters the asymptotic range.
#[test]
fn pairs_at_the_floor_stalled_or_without_a_correct_digit_stay_out_of_the_range() {
    use scenarios::studies::orders;
    let flags = |pairs: &[scenarios::studies::PairOrder]| -> Vec<(bool, bool, bool)> {
        pairs
            .iter()
            .map(|p| (p.round_off, p.stalled, p.in_range))
            .collect()
    };
    // Second order down to h = 0.0125, then at the floor (scale 1: below 1e-12).
    let floor = [
        (0.1, 1e-2),
        (0.05, 2.5e-3),
        (0.025, 6.25e-4),
        (0.0125, 1.5625e-4),
        (0.00625, 1e-13),
    ];
    let (pairs, fit) = orders(&floor, 1.0);
    let (t, f, o) = (true, false, true);
    assert_eq!(flags(&pairs), [(f, f, o), (f, f, o), (f, f, o), (t, f, f)]);
    let fit = fit.unwrap();
    assert!((fit.slope - 2.0).abs() < 1e-12, "{fit:?}");
    assert_eq!((fit.pairs_used, fit.range), (3, [0.0125, 0.1]));
    // An error saturated at 0.21 (a limit cycle's phase drift), then first order.
    let saturated = [
        (0.04, 0.21),
        (0.02, 0.21),
        (0.01, 0.1),
        (0.005, 0.05),
        (0.0025, 0.025),
    ];
    let (pairs, fit) = orders(&saturated, 1.0);
    assert_eq!(flags(&pairs), [(f, t, f), (f, f, o), (f, f, o), (f, f, o)]);
    // The stalled pair is left out; the other three lie on a slope of 1 (0.21 → 0.1 is 1.07).
    let fit = fit.unwrap();
    assert!((fit.slope - 1.0).abs() < 0.03, "{fit:?}");
    assert!(fit.ci[0] < 1.0 && 1.0 < fit.ci[1], "{fit:?}");
    // A missing error (event counts that differ from the reference's) leaves its pair out.
    let missing = [
        (0.02, f64::NAN),
        (0.01, 0.04),
        (0.005, 0.02),
        (0.0025, 0.01),
    ];
    let (pairs, fit) = orders(&missing, 1.0);
    assert!(pairs[0].round_off && !pairs[1].round_off);
    assert_eq!(fit.unwrap().pairs_used, 2);
    // RK4 past its stability bound at the coarsest step (the belt at h = 0.5, k = 100: an
    // error of 1e51), then fourth order: the unstable run has no correct digit. With one
    // fourth-order pair left there is no asymptotic range; with two there is.
    let unstable = [(0.5, 1e51), (0.25, 0.16), (0.125, 0.01), (0.0625, 0.000625)];
    for n in [3, 4] {
        let (pairs, fit) = orders(&unstable[..n], 1.0);
        assert!(pairs[0].no_correct_digit && !pairs[0].in_range, "{pairs:?}");
        assert_eq!(fit.is_some(), n == 4, "{fit:?}");
        if let Some(fit) = fit {
            assert!((fit.slope - 4.0).abs() < 1e-12, "{fit:?}");
            assert!(
                fit.ci[1] - fit.ci[0] < 1e-9,
                "three points on a line: {fit:?}"
            );
        }
    }
}

/// The asymptotic range is the longest run of consecutive usable pairs whose local orders
/// agree within 0.5 (of two equally long, the finer); orders that never agree give none, and
/// the verdict says so and why.
#[test]
fn the_order_rests_on_the_longest_run_of_agreeing_pairs_or_there_is_none() {
    use scenarios::studies::{orders, OrderTable, StepKind};
    let table = |points: &[(f64, f64)], step| {
        let (pairs, fit) = orders(points, 1.0);
        OrderTable {
            solver: "rk4".into(),
            measure: ErrorMeasure::FinalRelative,
            step,
            pairs,
            fit,
            formal: (step == StepKind::Fixed).then_some(4.0),
        }
    };
    // Halving h from 0.001, each pair with local order p: errors e_(k+1) = e_k / 2^p.
    let halving = |e0: f64, local: &[f64]| -> Vec<(f64, f64)> {
        let mut points = vec![(0.001, e0)];
        for p in local {
            let (h, e) = *points.last().unwrap();
            points.push((h / 2.0, e / 2f64.powf(*p)));
        }
        points
    };
    // The LuGre belt's RK4 final state of issue 36: orders 20.8, stalled (−1.01), 3.26, 7.88.
    let t = table(&halving(1e-2, &[20.8, -1.01, 3.26, 7.88]), StepKind::Fixed);
    assert_eq!(t.fit, None, "{t:?}");
    assert!(t.pairs.iter().all(|p| !p.in_range));
    assert_eq!(
        t.verdict(),
        "no asymptotic range (of 4 pairs: 1 stalled; 3 usable (20.80, 3.26, 7.88), no 2 \
         consecutive of which agree within 0.5)"
    );
    // A pre-asymptotic start (orders 2.9, 3.2), then fourth order over three pairs: the range
    // is the three, not the two.
    let t = table(
        &halving(1e-3, &[2.9, 3.2, 4.05, 3.98, 4.0]),
        StepKind::Fixed,
    );
    let fit = t.fit.unwrap();
    assert_eq!(fit.pairs_used, 3, "{t:?}");
    assert_eq!(fit.range, [0.001 / 32.0, 0.001 / 4.0]);
    assert!(fit.ci[0] < 4.0 && 4.0 < fit.ci[1], "{fit:?}");
    assert!(fit.ci[1] - fit.ci[0] < 1.0, "{fit:?}");
    assert!(t.verdict().starts_with("order 4.0"), "{}", t.verdict());
    // Its interval holds RK4's formal order 4: nothing is added.
    assert_eq!(t.against_formal(), None);
    // Sixth order from a fourth-order method is named, with its likely causes; so is first.
    let above = table(&halving(1e-3, &[6.0, 6.02, 5.98]), StepKind::Fixed);
    assert!(
        above
            .verdict()
            .ends_with("; above the formal order 4: a pre-asymptotic range, or errors of opposite sign cancelling (at a switch)"),
        "{}",
        above.verdict()
    );
    let below = table(&halving(1e-3, &[1.0, 1.02, 0.98]), StepKind::Fixed);
    assert!(
        (below.against_formal().unwrap()).starts_with("below the formal order 4"),
        "{}",
        below.verdict()
    );
    // Two runs of two agreeing pairs: the finer is taken.
    let fit = table(&halving(1e-3, &[1.0, 1.1, 3.0, 2.0, 2.1]), StepKind::Fixed).fit;
    assert!((fit.unwrap().slope - 2.05).abs() < 0.01, "{fit:?}");
    // An error that has saturated (local orders agreeing near 0) is not called converged.
    let t = table(&halving(0.2, &[0.1, -0.05, 0.12]), StepKind::Fixed);
    assert!(t.pairs[1].stalled, "{t:?}");
    let t = table(&halving(0.2, &[0.1, 0.02, 0.12]), StepKind::Fixed);
    assert!(
        t.verdict()
            .ends_with("the interval holds 0: no convergence shown"),
        "{}",
        t.verdict()
    );
    // Over tolerances the slope is tolerance proportionality, never called an order.
    let t = table(
        &[(1e-4, 1e-3), (1e-6, 1e-5), (1e-8, 1e-7)],
        StepKind::Adaptive,
    );
    assert!(
        t.verdict().starts_with("error ∝ tol^1.00"),
        "{}",
        t.verdict()
    );
    assert_eq!(t.quantity(), "tolerance_exponent");
    let undefined = table(&[(0.02, f64::NAN), (0.01, f64::NAN)], StepKind::Fixed);
    assert_eq!(
        undefined.verdict(),
        "no asymptotic range (of 1 pairs: 1 at round-off or undefined)"
    );
    let single = table(&[(0.02, 0.1)], StepKind::Fixed);
    assert_eq!(
        single.verdict(),
        "no asymptotic range (fewer than two resolutions)"
    );
}

/// The 95 % factor of Student's t: the table's values, and the expansion joining them.
#[test]
fn the_confidence_factor_is_students_t() {
    use scenarios::studies::student_t_975;
    assert_eq!(student_t_975(1), 12.706);
    assert_eq!(student_t_975(30), 2.042);
    // t(0.975; 40) = 2.0211, t(0.975; 120) = 1.9799 (Abramowitz & Stegun, Table 26.10).
    assert!((student_t_975(40) - 2.0211).abs() < 2e-4);
    assert!((student_t_975(120) - 1.9799).abs() < 1e-4);
}

/// A run of a stiffness study at tolerance `tol` with grid error `error` and `work`.
fn costed(tol: f64, error: f64, work: usize) -> scenarios::studies::StudyRun {
    scenarios::studies::StudyRun {
        solver: "m".into(),
        resolution: tol,
        step: scenarios::studies::StepKind::Adaptive,
        errors: scenarios::studies::Errors {
            grid_relative: error,
            ..scenarios::studies::Errors::UNMEASURED
        },
        measures: Default::default(),
        stats: integrators::Stats::default(),
        work,
        failure: None,
        verdict: scenarios::verdict::Verdict::OK,
        diverged: false,
        wall_time: Default::default(),
    }
}

/// The median and spread of a run's wall times: quartiles by linear interpolation between
/// the order statistics (numpy's default).
#[test]
fn wall_times_give_their_median_extremes_and_quartiles() {
    let t = scenarios::studies::WallTimes::of(&[5.0, 1.0, 4.0, 2.0, 3.0]);
    assert_eq!((t.repeats, t.median, t.min, t.max), (5, 3.0, 1.0, 5.0));
    assert_eq!((t.q1, t.q3), (2.0, 4.0));
    let t = scenarios::studies::WallTimes::of(&[1.0, 2.0, 3.0, 10.0]);
    assert_eq!((t.median, t.q1, t.q3), (2.5, 1.75, 4.75));
}

/// The cost to reach a target is interpolated in log–log between the runs that bracket it,
/// with the bracket as its uncertainty; two kinds within each other's brackets are a tie
/// (issue 36: Dormand–Prince at 86 evaluations and BDF at 74 were read as an implicit win).
#[test]
fn the_cost_at_the_target_is_interpolated_and_overlapping_brackets_tie() {
    use scenarios::studies::{reached, winner, Cost, Winner};
    let runs = [costed(1e-2, 1e-2, 100), costed(1e-3, 1e-4, 1000)];
    let r = reached(&runs.iter().collect::<Vec<_>>(), 1e-3).unwrap();
    // Half way in log(error) from 1e-2 to 1e-4: half way in log(work), 10^2.5.
    assert!((r.work_estimate - 10f64.powf(2.5)).abs() < 1e-9, "{r:?}");
    assert_eq!(r.work_bracket, [Some(100.0), Some(1000.0)]);
    assert_eq!((r.resolution, r.work), (1e-3, 1000));
    // The loosest run already meets it: the cost is at most its work.
    let r = reached(&[&costed(1e-2, 1e-4, 50)], 1e-3).unwrap();
    assert_eq!(
        (r.work_estimate, r.work_bracket),
        (50.0, [None, Some(50.0)])
    );
    // A run judged inaccurate does not meet the target; before one that does, it bounds the
    // cost from below but is no point to interpolate from.
    let mut bad = costed(1e-2, 1e-4, 20);
    bad.verdict = scenarios::verdict::Verdict::against_reference(2.0);
    assert_eq!(reached(&[&bad], 1e-3), None);
    let r = reached(&[&bad, &costed(1e-3, 1e-4, 80)], 1e-3).unwrap();
    assert_eq!(
        (r.work_estimate, r.work_bracket),
        (80.0, [Some(20.0), Some(80.0)])
    );
    let cost = |implicit: bool, estimate: f64, lo: f64, hi: f64| Cost {
        solver: if implicit { "bdf" } else { "dopri5" }.into(),
        implicit,
        reached: Some(scenarios::studies::Reached {
            work_estimate: estimate,
            work_bracket: [Some(lo), Some(hi)],
            ..reached(&[&costed(1e-2, 1e-4, 50)], 1e-3).unwrap()
        }),
    };
    let tie = [cost(false, 86.0, 60.0, 120.0), cost(true, 74.0, 50.0, 90.0)];
    assert_eq!(winner(&tie), Some(Winner::Tie));
    let apart = [
        cost(false, 300.0, 200.0, 400.0),
        cost(true, 74.0, 50.0, 90.0),
    ];
    assert_eq!(winner(&apart), Some(Winner::Implicit));
    assert_eq!(winner(&apart[..1]), Some(Winner::Explicit));
}

/// Dormand–Prince under a name of the user's choosing.
#[derive(Debug)]
struct Named(&'static str);

impl integrators::OneStepMethod for Named {
    fn name(&self) -> &'static str {
        self.0
    }
    fn order(&self) -> usize {
        5
    }
    fn is_implicit(&self) -> bool {
        false
    }
    fn is_fixed_step(&self) -> bool {
        false
    }
    fn stepper(
        &self,
        options: &integrators::Options,
        dim: usize,
    ) -> Result<Box<dyn integrators::Stepper>, integrators::SolverError> {
        let d = integrators::Dopri5::new(options.step, options.h_max(), options.max_steps, dim);
        Ok(Box::new(d))
    }
}

static CLASH: Named = Named("dopri5");
static MINE: Named = Named("my-dopri5");

#[test]
fn an_own_method_is_studied_beside_the_built_ins_under_its_own_name_only() {
    use scenarios::studies::{work_precision, Method};
    let case = switched_belt();
    let tolerances = [1e-6, 1e-8];
    let run = |own: &'static Named| {
        let methods = [
            Method::events(Solver::DOPRI5),
            Method::events(Solver::own(own)),
        ];
        work_precision(&case, &methods, &[], &tolerances, 0, &|| {})
    };
    // Under a name of its own: the same runs as the built-in method it wraps.
    let wp = run(&MINE).unwrap();
    let of = |name: &str| -> Vec<_> {
        let runs = wp.runs.iter().filter(|r| r.solver == name);
        runs.map(|r| (r.resolution, r.stats, r.errors.final_relative))
            .collect()
    };
    assert_eq!(of("my-dopri5").len(), 2);
    assert_eq!(of("my-dopri5"), of("dopri5"));
    // Under a built-in method's name: refused before any run, naming the clash.
    let message = run(&CLASH).unwrap_err().to_string();
    assert!(message.contains("both named `dopri5`"), "{message}");
}

/// A time-stepped study runs one method, Moreau–Jean (it takes no solver), over the step
/// sizes, against the case's closed form; on
/// the smooth viscous block θ = 1/2 is the trapezoidal rule (order 2) and θ = 1 implicit
/// Euler (order 1).
#[test]
fn a_time_stepped_study_measures_moreau_jeans_order_under_its_own_name() {
    let steps = [0.04, 0.02, 0.01, 0.005];
    let case = viscous_block();
    for (theta, order) in [(0.5, 2.0), (1.0, 1.0)] {
        let stepped = [Method::of(Scheme::TimeStepping { theta })];
        let c = convergence(&case, &stepped, &steps, &[1e-6], &|| {}).unwrap();
        assert!(matches!(c.reference, Reference::ClosedForm(_)));
        let labels: Vec<&str> = c.runs.iter().map(|r| r.solver.as_str()).collect();
        assert_eq!(labels, ["moreau-jean (timestepping)"; 4], "θ = {theta}");
        assert!(c
            .runs
            .iter()
            .all(|r| r.failure.is_none() && r.step == scenarios::studies::StepKind::Fixed));
        let grid = c
            .orders
            .iter()
            .find(|t| t.measure == ErrorMeasure::GridRelative)
            .unwrap();
        assert_eq!(grid.solver, "moreau-jean (timestepping)");
        let p = grid.fit.expect("an asymptotic range").slope;
        println!("θ = {theta}: observed order {p:.3}");
        assert!((p - order).abs() < 0.15, "θ = {theta}: order {p}");
    }
}

/// Without a closed form, a time-stepped study's reference is the event-driven solution of
/// the same nonsmooth problem (time-stepping takes no tolerance, so a tight run of its own
/// cannot exist: the study once failed on it), and the event-driven reference agrees with the
/// reference of the event-switched study to the bit.
#[test]
fn a_time_stepped_study_without_a_closed_form_takes_the_event_driven_reference() {
    use scenarios::studies::reference;
    let belt = switched_belt();
    let stepped = [Method::of(Scheme::TimeStepping { theta: 0.5 })];
    let c = convergence(&belt, &stepped, &[0.01, 0.005], &[1e-6], &|| {}).unwrap();
    let Reference::Run { solver, .. } = c.reference else {
        panic!("{:?}", c.reference)
    };
    assert_eq!(
        solver, "dopri5",
        "the time-stepped method is not a solver studied"
    );
    assert!(c.runs.iter().all(|r| r.failure.is_none()));
    let (_, stepped_reference) = reference(&belt, &stepped).unwrap();
    let (_, event_reference) = reference(&belt, &[]).unwrap();
    assert_eq!(
        stepped_reference.final_state, event_reference.final_state,
        "the same run"
    );
}

/// LuGre on the belt: its bristle deflection z is measured in its own unit beside x and v,
/// each relative to the solution's scale in that quantity, and the energy balance closes to
/// the tolerance.
#[test]
fn a_law_with_an_internal_state_has_its_error_in_z() {
    let case = Case {
        scenario: Scenario::BELT,
        law: ModelId::LuGre.into(),
        params: Scenario::BELT.defaults(),
        t_end: 2.0,
        ..viscous_block()
    };
    let bdf = Method::events(Solver::BDF);
    let c = convergence(&case, &[bdf], &[], &[1e-5, 1e-7], &|| {}).unwrap();
    for r in &c.runs {
        let e = r.errors;
        assert!(e.z > 0.0 && e.z_relative > 0.0, "{e:?}");
        // The bristles deflect by micrometres: z's absolute error is far below x's, while its
        // relative error is of the order of the others.
        assert!(e.z < e.x && e.z_relative > 1e-3 * e.grid_relative, "{e:?}");
        let largest = [e.x_relative, e.v_relative, e.z_relative]
            .into_iter()
            .fold(0.0, f64::max);
        assert_eq!(e.grid_relative, largest, "{e:?}");
        assert!(e.energy_relative < 1e-3, "{e:?}");
    }
    // Tightening the tolerance by 100 reduces every error.
    let [loose, tight] = [&c.runs[0], &c.runs[1]].map(|r| r.errors);
    assert!(tight.x < loose.x && tight.v < loose.v && tight.z < loose.z);
}

/// A stiff case (CS regularised at ε = 1e-4: a slope of F_c/ε across v = 0) is judged stiff by
/// Dormand–Prince's own test in its tight run; its reference is then BDF's tight run,
/// cross-checked by the explicit 5(4) pair, a method of another family. A case that is not
/// stiff keeps the explicit pair.
#[test]
fn a_stiff_case_has_an_implicit_reference_checked_by_an_explicit_one() {
    let belt = Case {
        scenario: Scenario::BELT,
        law: ModelId::Cs.into(),
        params: Scenario::BELT.defaults(),
        t_end: 2.0,
        ..viscous_block()
    };
    let rk4 = |switching| {
        Method::of(Scheme::EventDriven {
            solver: Solver::RK4,
            switching,
        })
    };
    let regularized = rk4(Switching::Regularized { epsilon: 1e-4 });
    let (r, _) = scenarios::studies::reference(&belt, &[regularized]).unwrap();
    let Reference::Run {
        solver,
        cross_check: (check, estimate),
        stiffness_detected_at,
        ..
    } = r
    else {
        panic!("{r:?}")
    };
    assert_eq!(solver, "bdf");
    assert_eq!(check, "dopri5");
    let t = stiffness_detected_at.expect("judged stiff");
    assert!(t > 0.0 && t < 2.0, "{t}");
    assert!(estimate > 0.0 && estimate < 1e-7, "{estimate}");
    let (r, _) = scenarios::studies::reference(&belt, &[rk4(Switching::Event)]).unwrap();
    let Reference::Run {
        solver,
        stiffness_detected_at: None,
        ..
    } = r
    else {
        panic!("{r:?}")
    };
    assert_eq!(solver, "dopri5");
}
