//! The comparison of formulations scores every scheme against the true nonsmooth solution:
//! the cross-check agrees, time-stepping is measured on the grid, a short list is extended,
//! the regularisation's model error is first order in ε on the belt, and the results do not
//! depend on the thread count.

use friction_models::{FrictionParams, ModelId};
use integrators::Solver;
use scenarios::studies::{compare, Case, CompareSpec, Comparison, Resolutions, Schemes};
use scenarios::{Limits, Scenario};

/// The belt with Coulomb and Stribeck friction (CS), the paper's parameters.
fn belt() -> Case {
    let scenario = Scenario::from_name("belt").unwrap();
    let params = scenario.defaults();
    let friction = FrictionParams::paper();
    Case {
        scenario,
        law: ModelId::Cs.into(),
        friction,
        params,
        t_end: scenario.default_t_end(&params, &friction),
        limits: Limits {
            max_steps: 200_000,
            ..Limits::default()
        },
    }
}

fn spec() -> CompareSpec {
    CompareSpec {
        schemes: Schemes {
            event: vec![Solver::DOPRI5, Solver::RADAU5],
            regularised: vec![Solver::BDF],
            epsilons: vec![1e-2, 1e-3, 1e-4, 1e-5],
            naive: vec![],
            theta: Some(0.5),
        },
        resolutions: Resolutions {
            tolerances: vec![1e-3, 1e-4, 1e-5, 1e-6],
            steps: vec![0.01],
            timestepping_steps: vec![0.01, 0.005],
        },
        targets: vec![1e-2, 1e-3, 1e-4],
        repeats: 0,
    }
}

fn run_on(threads: usize) -> Comparison {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| compare(&belt(), &spec(), &|| {}).unwrap())
}

#[test]
fn every_scheme_is_scored_against_the_true_solution() {
    let c = run_on(2);
    // The true solution (Dormand–Prince at 1e-13 with events) and Radau IIA with events,
    // another family, agree to far below the targets.
    let d = c.cross_check.difference.unwrap();
    assert!(d < 1e-6, "cross-check {d}");
    assert!(c.resolvable <= 1e-6 && c.costs.iter().all(|t| t.resolved));

    // Time-stepping's step ends fall on the output grid: each of its runs is measured there.
    let mj: Vec<_> = (c.runs.iter())
        .filter(|r| r.scheme == "moreau-jean (timestepping)")
        .collect();
    assert!(mj.iter().all(|r| r.run.errors.grid_relative.is_finite()));
    // Its list (0.01, 0.005) stops short of 1e-4; it is halved until the error meets it.
    assert!(mj.len() > 2, "{} runs", mj.len());
    let at = |target: f64, scheme: &str| {
        let t = c.costs.iter().find(|t| t.target == target).unwrap();
        t.costs.iter().find(|s| s.scheme == scheme).unwrap().clone()
    };
    let reached = at(1e-4, "moreau-jean (timestepping)").reached.unwrap();
    assert!(
        reached.resolution < 0.005 && reached.error <= 1e-4,
        "{reached:?}"
    );

    // A regularised run's error has two parts: against its own tight solution, and the model
    // error of its ε against the true one.
    for r in &c.runs {
        assert_eq!(
            r.epsilon.is_some(),
            r.discretisation_error.is_some() || r.run.failure.is_some()
        );
    }
    let reg = c.regularisation.as_ref().unwrap();
    let errors: Vec<f64> = reg.widths.iter().map(|w| w.error).collect();
    assert!(errors.windows(2).all(|w| w[1] < w[0]), "{errors:?}");
    // On the belt the regularised law's drift through each stick phase is first order in ε.
    let fit = reg.fit.as_ref().unwrap();
    assert!(reg.falls && (fit.order - 1.0).abs() < 0.25, "{fit:?}");
    // At ε = 1e-2 of the velocity scale the model error is of the solution's size: no
    // tolerance reaches 1e-2 there, and the reason names the floor.
    let wide = at(1e-2, "bdf (regularized)");
    assert!(wide.reached.is_none() || wide.epsilon.unwrap() < 1e-2 * c.velocity_scale);

    // Explicit with events is cheaper than implicit with events at every target here.
    for t in &c.costs {
        assert_eq!(t.cheapest.as_deref(), Some("dopri5 (event)"), "{t:?}");
    }
}

#[test]
fn the_comparison_is_the_same_on_one_thread_and_on_two() {
    let (one, two) = (run_on(1), run_on(2));
    let key = |c: &Comparison| {
        let runs: Vec<String> = (c.runs.iter())
            .map(|r| {
                format!(
                    "{} {} {:?} {}",
                    r.run.solver, r.run.resolution, r.run.errors, r.run.work
                )
            })
            .collect();
        let costs: Vec<String> = (c.costs.iter())
            .flat_map(|t| &t.costs)
            .map(|s| {
                format!(
                    "{} {:?}",
                    s.scheme,
                    s.reached.as_ref().map(|r| r.work_estimate.to_bits())
                )
            })
            .collect();
        (runs, costs, format!("{:?}", c.regularisation))
    };
    assert_eq!(key(&one), key(&two));
}

#[test]
fn parts_made_apart_and_merged_in_any_order_give_the_comparison_made_in_one_piece() {
    use scenarios::studies::{parts, TrueSolution};
    let (case, spec) = (belt(), spec());
    let whole = run_on(2);
    let divided = parts(&spec);
    // The cross-check; dopri5, radau5 and Moreau–Jean alone; BDF at each of the four widths.
    assert_eq!(divided.len(), 1 + 3 + 4);
    // Each part from its own true solution, as a Dask worker makes it.
    let made: Vec<_> = (divided.iter())
        .map(|part| {
            let truth = TrueSolution::of(&case).unwrap();
            truth.part(&case, &spec, part, &|| {}).unwrap()
        })
        .collect();
    let truth = TrueSolution::of(&case).unwrap();
    let mut reversed = made.clone();
    reversed.reverse();
    let merged = truth.merge(&spec, reversed).unwrap();
    // Every field the files hold (the wall times apart), bit for bit.
    let written = |c: &Comparison| serde_json::to_string(c).unwrap();
    assert_eq!(written(&merged), written(&whole));
    let times = |c: &Comparison| {
        c.runs
            .iter()
            .map(|r| r.run.wall_time.repeats)
            .sum::<usize>()
    };
    assert_eq!(times(&merged), times(&whole));

    // A part missing, or given twice, is refused.
    let missing = truth.merge(&spec, made[1..].to_vec()).unwrap_err();
    assert!(missing.to_string().contains("0 cross-checks"), "{missing}");
    let mut twice = made.clone();
    twice.push(made[1].clone());
    let twice = truth.merge(&spec, twice).unwrap_err();
    assert!(twice.to_string().contains("track 0 given twice"), "{twice}");
}

#[test]
fn a_stiffness_sweep_extends_a_list_that_stops_short_of_its_target() {
    // Tolerances 1e-2 and 1e-3 leave Dormand–Prince short of 1e-5 on the regularised belt;
    // the list is extended by tenths until it meets it, rather than the method being called
    // unable to.
    use friction_systems::{Scheme, Switching};
    use scenarios::studies::{stiffness, Method, Sweep};
    let case = Case {
        t_end: 5.0,
        ..belt()
    };
    let dopri5 = Method::of(Scheme::EventDriven {
        solver: Solver::DOPRI5,
        switching: Switching::Regularized { epsilon: 1e-2 },
    });
    let sweep = Sweep {
        parameter: "epsilon",
        values: &[1e-2],
        target: 1e-5,
    };
    let s = stiffness(&case, sweep, &[dopri5], &[0.01], &[1e-2, 1e-3], &|| {}).unwrap();
    let r = s.points[0].costs[0]
        .reached
        .as_ref()
        .expect("extended until it met the target");
    assert!(r.resolution < 1e-3 && r.error <= 1e-5, "{r:?}");
    // Each extension a tenth of the tolerance before: a decimal, not 1.0000000000000001e-5.
    let digits = format!("{:e}", r.resolution);
    assert!(digits.len() <= 5, "{digits}");
}

/// A damped oscillator without friction, m·ẍ + c·ẋ + k·x = 0 with m = k = 1 and c = √R:
/// for R ≫ 4 its rates are about −c and −1/c, a stiffness ratio of R. Over three slow time
/// constants (3c) an explicit method's step is held below its stability bound 3.3/c, so its
/// work grows as R; an implicit method's follows the slow solution alone.
fn oscillator(ratio: f64) -> scenarios::studies::SystemCase {
    use friction_systems::{End, System};
    let c = ratio.sqrt();
    let mut s = System::default();
    let wall = s.add_anchor("wall", 0.0, 0.0);
    let body = s.add_body("body", 1.0, 1.0, 0.0);
    s.add_spring(End::Anchor(wall), End::Body(body), 1.0, c);
    scenarios::studies::SystemCase::new(format!("oscillator R = {ratio}"), s, 3.0 * c.max(2.0))
}

#[test]
fn on_a_smooth_stiff_problem_the_implicit_method_wins_above_a_stiffness_ratio() {
    use scenarios::studies::Winner;
    let spec = CompareSpec {
        schemes: Schemes {
            event: vec![Solver::DOPRI5, Solver::RADAU5],
            regularised: vec![],
            epsilons: vec![],
            naive: vec![],
            theta: None,
        },
        // From a tolerance loose enough that no method meets a target with its first run
        // (whose cost is then bounded above only, and ties).
        resolutions: Resolutions {
            tolerances: vec![1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8],
            ..spec().resolutions
        },
        targets: vec![1e-3, 1e-6],
        ..spec()
    };
    let winner = |ratio: f64| {
        let c = compare(&oscillator(ratio), &spec, &|| {}).unwrap();
        assert!(c.regularisation.is_none());
        (c.costs.iter())
            .map(|t| (t.kind, t.implicit_over_explicit.unwrap()))
            .collect::<Vec<_>>()
    };
    // Critically damped (R = 4): nothing is stiff, and Dormand–Prince is cheaper.
    for (kind, ratio) in winner(4.0) {
        assert_eq!(kind, Some(Winner::Explicit), "implicit/explicit {ratio}");
    }
    // R = 1e4: Dormand–Prince needs about 3c/(3.3/c) ≈ 0.9·R steps whatever the target;
    // Radau IIA's work does not grow with R.
    for (kind, ratio) in winner(1e4) {
        assert_eq!(kind, Some(Winner::Implicit), "implicit/explicit {ratio}");
        assert!(ratio < 0.2, "implicit/explicit {ratio}");
    }
}

#[test]
fn a_run_is_timed_again_only_while_its_work_is_short_of_the_limit() {
    // Two timing repeats asked for: a run below `TIMED_ONCE_FROM` counted work is timed three
    // times, a run at or past it (BDF on the regularised law at the smallest widths), and a
    // failed one, once. The spec has both kinds.
    let spec = CompareSpec {
        repeats: 2,
        ..spec()
    };
    let c = compare(&belt(), &spec, &|| {}).unwrap();
    let limit = scenarios::batch::TIMED_ONCE_FROM;
    let (short, long): (Vec<_>, Vec<_>) = (c.runs.iter())
        .map(|r| &r.run)
        .partition(|r| (r.work as f64) < limit && r.failure.is_none());
    assert!(
        !short.is_empty() && !long.is_empty(),
        "{} and {}",
        short.len(),
        long.len()
    );
    for r in short {
        assert_eq!(r.wall_time.repeats, 3, "{} at {}", r.solver, r.resolution);
    }
    for r in long {
        assert_eq!(
            r.wall_time.repeats, 1,
            "{} at {}: work {}",
            r.solver, r.resolution, r.work
        );
    }
}
