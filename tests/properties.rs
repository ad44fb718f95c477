//! Property-based tests (proptest): the validation of every numeric option and parameter
//! against its documented range, the system-file parser on arbitrary text, and the solvers on
//! random valid inputs (no panic: finite output or a clean error). Each property runs a small,
//! fixed number of cases so that the suite stays within seconds.

use clap::Parser;
use friction_lab::friction_models::{FrictionParams, ModelId, Parameters};
use friction_lab::ranges::{self, OptionRange};
use friction_lab::scenarios::{Scenario, ScenarioParams};
use friction_lab_cli::{Cli, Command};
use proptest::prelude::*;

/// Numbers of every kind: ordinary, tiny, huge, negative, zero, NaN and infinities.
fn any_number() -> impl Strategy<Value = f64> {
    prop_oneof![
        -1e3..1e3f64,
        -30.0..30.0f64,
        any::<f64>(),
        Just(0.0),
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(5e-324),
    ]
    .prop_map(|x| {
        if x.abs() < 30.0 && x.fract() != 0.0 {
            10f64.powf(x) * x.signum()
        } else {
            x
        }
    })
}

/// The simulate arguments of `belt --model CS` with one more option.
fn simulate_belt(extra: &[String]) -> Result<Cli, clap::Error> {
    let mut args: Vec<String> = [
        "friction-lab",
        "simulate",
        "belt",
        "--model",
        "CS",
        "--out",
        "o",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.extend(extra.iter().cloned());
    Cli::try_parse_from(args)
}

fn checked(option: &OptionRange, value: f64) {
    // The field's option: `t_end` is `--t-end`.
    let long = option.name.replace('_', "-");
    let whole = option.name == "points" || option.name == "max_steps";
    if whole && !(value.is_finite() && value.fract() == 0.0) {
        // Not a whole number: clap refuses it before any check of ours.
        return;
    }
    let text = if value.is_nan() {
        "NaN".to_string()
    } else if whole {
        format!("{}", value as i64)
    } else {
        value.to_string()
    };
    let cli = simulate_belt(&[format!("--{long}"), text]).expect("a number parses");
    let Command::Simulate(args) = cli.command else {
        unreachable!()
    };
    match args.request.rig_spec(Scenario::BELT) {
        Ok(_) => assert!(
            option.range.contains(value),
            "--{long} {value} was accepted outside {}",
            option.range
        ),
        Err(e) => {
            assert!(!option.range.contains(value), "--{long} {value}: {e}");
            assert_eq!(friction_lab_cli::exit_code(&e), 2);
            let message = e.to_string();
            assert!(
                message.contains(&format!("`{}`", option.name)) && message.contains("allowed"),
                "{message}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn every_numeric_option_of_simulate_is_accepted_exactly_in_its_range(x in any_number()) {
        for option in [ranges::T_END, ranges::DT, ranges::RTOL, ranges::ATOL, ranges::TIME_LIMIT] {
            checked(&option, x);
        }
        for option in [ranges::POINTS, ranges::MAX_STEPS] {
            let n = x.trunc().clamp(-1e12, 1e12);
            checked(&option, n);
        }
    }

    #[test]
    fn every_parameter_is_accepted_exactly_in_its_range(x in any_number(), k in 0usize..64) {
        let friction = FrictionParams::specs();
        let rig = ScenarioParams::specs();
        let spec = if k < friction.len() { &friction[k] } else { &rig[k % rig.len()] };
        let options = friction_lab::params::ParamSource {
            set: vec![format!("{}={x}", spec.name)],
            ..Default::default()
        };
        let options = friction_lab::params::ParamSource { param_set: Some("paper".into()), ..options };
        // Scenario parameters are checked for a scenario that reads them.
        let scenario = Scenario::ALL
            .into_iter()
            .find(|s| s.parameters().contains(&spec.name));
        match options.resolve_for(scenario) {
            Ok(_) => prop_assert!(spec.range.contains(x), "{} = {x} accepted", spec.name),
            Err(e) => {
                prop_assert_eq!(friction_lab_cli::exit_code(&e), 2);
                prop_assert!(e.to_string().contains(spec.name), "{}", e);
            }
        }
    }

    #[test]
    fn the_system_file_parser_never_panics(text in "\\PC{0,400}") {
        let _ = friction_lab::friction_systems::file::parse(&text);
    }

    #[test]
    fn the_system_file_parser_rejects_mutated_values_with_the_key(
        key in prop::sample::select(vec!["m", "k", "c", "v", "x0", "surface_velocity", "constant"]),
        x in any_number(),
    ) {
        let base = "[[body]]\nname = \"a\"\nm = 1.0\nx0 = 0.0\n[[anchor]]\nname = \"w\"\nv = 0.0\n\
                    [[spring]]\nbetween = [\"a\", \"w\"]\nk = 1.0\nc = 0.0\n\
                    [[contact]]\nbody = \"a\"\nsurface_velocity = 0.0\nmodel = \"CS\"\n\
                    [[force]]\nbody = \"a\"\nconstant = 0.0\n";
        let value = if x.is_nan() { "nan".to_string() } else if x.is_infinite() {
            if x > 0.0 { "inf".into() } else { "-inf".into() }
        } else { format!("{x:e}") };
        let text = base.replacen(&format!("\n{key} = "), &format!("\n{key} = {value}\n# "), 1);
        let valid = x.is_finite()
            && match key {
                "m" => x > 0.0,
                "k" | "c" => x >= 0.0,
                _ => true,
            };
        match friction_lab::friction_systems::file::parse(&text) {
            Ok(_) => prop_assert!(valid, "{key} = {value} accepted"),
            Err(e) => {
                prop_assert!(!valid, "{key} = {value}: {e}");
                prop_assert!(e.contains(&format!("`{key}`")), "{e}");
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn solvers_on_random_valid_belts_give_finite_output_or_a_clean_error(
        m in 0.05..20.0f64,
        k in 1.0..2000.0f64,
        v_belt in -1.0..1.0f64,
        model in prop::sample::select(vec!["CS", "CVS", "AV", "SV", "static", "lugre", "dahl"]),
        solver in prop::sample::select(vec!["dopri5", "rk4", "implicit-euler", "bdf"]),
        switching in prop::sample::select(vec!["event", "regularized", "naive"]),
    ) {
        use friction_lab::integrators::{Solver, StepControl};
        use friction_lab::friction_systems::Scheme;
        use friction_lab::scheme::SwitchingName;
        use friction_lab::scenarios::{run, Limits, RunSpec};
        let mut params = Scenario::BELT.defaults();
        params.m = m;
        params.k = k;
        params.v_belt = v_belt;
        let solver = Solver::from_name(solver).unwrap();
        let step = if solver.is_fixed_step() {
            StepControl::Fixed { h: 1e-3 }
        } else {
            StepControl::Adaptive { rtol: 1e-6, atol: 1e-8, h0: None }
        };
        let spec = RunSpec {
            scenario: Scenario::BELT,
            law: model.parse::<ModelId>().unwrap().into(),
            friction: FrictionParams::paper(),
            params,
            scheme: Scheme::EventDriven {
                solver,
                switching: switching.parse::<SwitchingName>().unwrap().switching(1e-3).unwrap(),
            },
            step,
            t_end: Some(1.0),
            output_points: 11,
            limits: Limits { max_steps: 200_000, time_limit: Some(5.0), ..Limits::default() },
        };
        let o = run(&spec, &mut |_| {}).expect("valid input");
        prop_assert!(!o.rows.is_empty());
        for r in &o.rows {
            prop_assert!(r.t.is_finite() && r.x.is_finite() && r.v.is_finite() && r.friction.is_finite());
        }
        if let Some(e) = &o.error {
            prop_assert!(!e.to_string().is_empty());
        }
    }
}

/// The fuzz target's hand-written seeds parse as they should (three systems, one parameter
/// file, one bad file), and every input of its minimised corpus goes through both parsers with
/// the target's own invariants: a system that parses is valid, and setting the parameters of a
/// parameter file keeps every parameter in range.
#[test]
fn the_fuzz_seeds_and_corpus_go_through_both_parsers() {
    use friction_lab::friction_systems::file::parse;
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz");
    let mut systems = Vec::new();
    for entry in std::fs::read_dir(root.join("seeds")).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if parse(&text).is_ok() {
            systems.push(name.clone());
        }
        if name == "params.toml" {
            let pairs = friction_lab::params::parse_params(&text).unwrap();
            assert_eq!(pairs.len(), 5);
        }
    }
    systems.sort();
    assert_eq!(
        systems,
        [
            "lugre-chain-end.toml",
            "one-body-belt.toml",
            "two-masses.toml"
        ]
    );
    let mut inputs = 0;
    for entry in std::fs::read_dir(root.join("corpus/parsers")).unwrap() {
        let bytes = std::fs::read(entry.unwrap().path()).unwrap();
        let Ok(text) = std::str::from_utf8(&bytes) else {
            continue;
        };
        inputs += 1;
        if let Ok(system) = parse(text) {
            assert!(system.validate().is_ok());
        }
        if let Ok(pairs) = friction_lab::params::parse_params(text) {
            let mut p = FrictionParams::paper();
            for (name, value) in pairs {
                let _ = p.set(&name, value);
            }
            assert!(p.validate().is_ok());
        }
    }
    assert!(inputs > 100, "{inputs} corpus inputs");
}
