//! The `friction-lab` program as a user runs it: its files, its listing, and its errors on
//! bad input (a clear message naming the field, a non-zero exit code, and no output).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn friction_lab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_friction-lab"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `simulate` with `args` into the folder `name` under `dir`: its output and its summary.
fn simulated(dir: &std::path::Path, name: &str, args: &[&str]) -> (Output, serde_json::Value) {
    let out = dir.join(name);
    let mut argv = vec!["simulate"];
    argv.extend_from_slice(args);
    argv.extend(["--out", out.to_str().unwrap()]);
    let o = friction_lab(&argv);
    let summary = serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap())
        .unwrap_or_else(|e| panic!("{name}: {e}: {}", stderr(&o)));
    (o, summary)
}

#[test]
fn models_json_lists_every_model_and_parameter() {
    let o = friction_lab(&["models", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let models = v["models"].as_array().unwrap();
    let names: Vec<_> = models.iter().map(|m| m["name"].as_str().unwrap()).collect();
    assert_eq!(&names[..6], &["AV", "CS", "CVS", "DV", "SD", "SV"]);
    assert!(names.contains(&"lugre") && names.contains(&"karnopp"));
    let f_s = v["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "F_s")
        .unwrap();
    assert_eq!(f_s["default"], 7.5);
    assert_eq!(f_s["unit"], "N");
    assert_eq!(f_s["range_text"], "[0, inf)");
    assert_eq!(f_s["sets"]["lugre-1995"], 1.5);
    assert_eq!(
        models[0]["equation_printed"],
        "F = F_s + mu_v*v + S(v); at rest F in [F_s - C2, F_s + C1]"
    );
}

#[test]
fn curve_writes_csv_png_svg_and_key_values() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sd");
    let o = friction_lab(&[
        "curve",
        "SD",
        "--out",
        out.to_str().unwrap(),
        "--points",
        "500",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let png = std::fs::read(out.join("curve-SD.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let svg = std::fs::read_to_string(out.join("curve-SD.svg")).unwrap();
    assert!(svg.contains("displacement X (m)") && svg.contains("friction force F (N)"));
    let csv = std::fs::read_to_string(out.join("curve-SD.csv")).unwrap();
    assert!(csv.starts_with("variant,branch,t,x,v,z,force\n"));
    assert_eq!(csv.lines().count(), 1 + 2 * 500 + 2);
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("curve-SD.json")).unwrap()).unwrap();
    assert_eq!(json["key_values"]["right_of_zero"], 7.5);
    assert_eq!(json["key_values"]["left_of_zero"], -7.5);
    // F = F_s + F_c (1 - exp(-sigma X / F_c)) at X = 8/3 + 2.
    let expected = 7.5 + 6.0 * (1.0 - (-5.0 * (8.0 / 3.0 + 2.0) / 6.0f64).exp());
    let end = json["key_values"]["end_force"].as_f64().unwrap();
    assert!(
        (end - expected).abs() < 1e-12 * expected,
        "{end} vs {expected}"
    );
}

#[test]
fn printed_variant_and_parameter_overrides_reach_the_curve() {
    let dir = tempfile::tempdir().unwrap();
    let params = dir.path().join("p.toml");
    std::fs::write(&params, "F_s = 8\nC1 = 2.0\n").unwrap();
    let out = dir.path().join("av");
    let o = friction_lab(&[
        "curve",
        "av",
        "--out",
        out.to_str().unwrap(),
        "--variant",
        "printed",
        "--params",
        params.to_str().unwrap(),
        "--set",
        "C1=1",
        "--v-max",
        "0.5",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("curve-AV-printed.json")).unwrap()).unwrap();
    // As printed: limits F_s - C2 = 8 - 1.5 and F_s + C1 = 8 + 1 (--set wins over the file).
    assert_eq!(json["key_values"]["left_of_zero"], 6.5);
    assert_eq!(json["key_values"]["right_of_zero"], 9.0);
    assert_eq!(json["key_values"]["end_abscissa"], 0.5);
}

#[test]
fn reproduce_writes_six_figures_notes_and_report_deterministically() {
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str| {
        let out = dir.path().join(name);
        let o = friction_lab(&["reproduce", "--out", out.to_str().unwrap()]);
        assert!(o.status.success(), "{}", stderr(&o));
        out
    };
    let (a, b) = (run("a"), run("b"));
    for (n, m) in [
        (2, "AV"),
        (3, "CS"),
        (4, "CVS"),
        (5, "DV"),
        (6, "SD"),
        (7, "SV"),
    ] {
        for ext in ["csv", "png", "svg"] {
            let name = format!("figures/figure-{n}-{m}.{ext}");
            let first = std::fs::read(a.join(&name)).unwrap();
            assert_eq!(
                first,
                std::fs::read(b.join(&name)).unwrap(),
                "{name} differs"
            );
        }
    }
    let notes = std::fs::read_to_string(a.join("reproduction.md")).unwrap();
    assert_eq!(notes.matches("## Figure ").count(), 6);
    // The report names what computed it, where and when.
    let report = std::fs::read_to_string(a.join("report.md")).unwrap();
    let provenance = report.lines().nth(2).unwrap();
    assert!(
        provenance.starts_with(&format!(
            "Computed by friction-lab {} (commit `",
            env!("CARGO_PKG_VERSION")
        )) && provenance.contains("logical cores")
            && provenance.ends_with("threads."),
        "{provenance}"
    );
    // Figure 5 (two claims) and Figure 6 ("about -10") and Figure 7 (levels off).
    assert_eq!(notes.matches("**disagrees**").count(), 4, "{notes}");
    let table: serde_json::Value =
        serde_json::from_slice(&std::fs::read(a.join("table2.json")).unwrap()).unwrap();
    let models = &table["models"];
    assert_eq!(models["CVS"]["stick_slip"]["paper"], false);
    assert_eq!(
        models["lugre"]["stribeck"]["paper"],
        serde_json::Value::Null
    );
    assert_eq!(
        without_provenance(&a.join("table2.json")),
        without_provenance(&b.join("table2.json"))
    );
    // The closed loop: the models as plants and compensators, and the hunting map.
    for file in [
        "closed-loop/closed-loop.md",
        "closed-loop/closed-loop.json",
        "closed-loop/hunting-map.csv",
    ] {
        assert_eq!(
            without_provenance(&a.join(file)),
            without_provenance(&b.join(file)),
            "{file} differs"
        );
    }
    assert!(a.join("closed-loop/closed-loop-error.png").is_file());
    let loops = std::fs::read_to_string(a.join("closed-loop/closed-loop.md")).unwrap();
    assert!(
        loops.contains("| lugre | hunting |"),
        "the 1995 example hunts: {loops}"
    );
    let report = std::fs::read_to_string(a.join("report.md")).unwrap();
    assert!(
        report.contains("## Closed loop: hunting and friction compensation"),
        "{report}"
    );
    assert!(report.contains("[Figure 6 (SD)](figures/figure-6-SD.png)"));
    // The paper's claim tested: every scheme against the true solution, the same twice.
    assert!(report.contains("## Explicit, implicit and time-stepping against the true solution"));
    assert!(
        report.contains("| [belt rig with CS](compare/belt-CS.png) | dopri5 (event)"),
        "{report}"
    );
    for file in ["compare/belt-CS-cost.csv", "compare/two_mass-lugre.csv"] {
        assert_eq!(
            std::fs::read(a.join(file)).unwrap(),
            std::fs::read(b.join(file)).unwrap(),
            "{file} differs"
        );
    }
    // The chain, integrated three ways: work-precision at N = 100, cost against N.
    let wp = std::fs::read_to_string(a.join("studies/work-precision-chain-100.csv")).unwrap();
    for label in [
        "dopri5,",
        "bdf (regularized),",
        "moreau-jean (timestepping),fixed,",
    ] {
        assert!(wp.contains(label), "{label}");
    }
    let cost = std::fs::read_to_string(a.join("studies/cost-chain.csv")).unwrap();
    assert_eq!(cost.lines().count(), 1 + 5 * 3, "five sizes, three methods");
    // Time-stepping: a step size h = 1e-3 s (no tolerance), 4000 steps at every N.
    assert!(cost.contains("\n1000,moreau-jean (timestepping),0.001,,4000,"));
    for f in [
        "cost-chain-timing.png",
        "cost-chain-timing.csv",
        "work-precision-chain-100.png",
        "work-precision-belt-CS-timing.png",
    ] {
        assert!(a.join("studies").join(f).exists(), "{f}");
    }
    // The belt's wall times: five repeats each, their median within their extremes and
    // quartiles.
    let timing =
        std::fs::read_to_string(a.join("studies/work-precision-belt-CS-timing.csv")).unwrap();
    let mut rows = timing.lines();
    assert_eq!(
        rows.next().unwrap(),
        "solver,h,tol,repeats,wall_time_median_s,wall_time_min_s,wall_time_q1_s,\
         wall_time_q3_s,wall_time_max_s"
    );
    for row in rows {
        let cells: Vec<&str> = row.split(',').collect();
        let t: Vec<f64> = cells[4..].iter().map(|c| c.parse().unwrap()).collect();
        assert_eq!(cells[3], "5", "{row}");
        let [median, min, q1, q3, max] = [t[0], t[1], t[2], t[3], t[4]];
        assert!(
            min <= q1 && q1 <= median && median <= q3 && q3 <= max,
            "{row}"
        );
    }
    assert_eq!(
        std::fs::read(a.join("studies/cost-chain.csv")).unwrap(),
        std::fs::read(b.join("studies/cost-chain.csv")).unwrap()
    );
    // Its JSON says what each size studied.
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(a.join("studies/cost-chain.json")).unwrap()).unwrap();
    let cases = json["cases"].as_array().unwrap();
    let sizes: Vec<u64> = cases
        .iter()
        .map(|c| c["bodies"].as_u64().unwrap())
        .collect();
    assert_eq!(sizes, [10, 30, 100, 300, 1000]);
    assert_eq!(cases[4]["switching"], "event");
    assert_eq!(cases[4]["t_end"], 4.0);
    let description = cases[4]["description"].as_str().unwrap();
    assert!(description.contains("1000"), "{description}");
    assert!(report
        .contains("[Work against precision at N = 100](studies/work-precision-chain-100.png)"));
}

/// Runs `args` with an output folder that must not be created, and returns stderr.
fn rejected(args: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut all: Vec<&str> = args.to_vec();
    all.extend(["--out", out.to_str().unwrap()]);
    let o = friction_lab(&all);
    assert!(!o.status.success(), "{args:?} was accepted");
    assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    assert!(!Path::new(&out).exists(), "{args:?} wrote output");
    let text = stderr(&o);
    assert!(!text.contains("panicked"), "{args:?}: {text}");
    text
}

#[test]
fn bad_parameters_are_rejected_with_name_value_and_range() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["curve", "AV", "--set", "v_s=0"],
            "parameter `v_s` = 0 is out of range: allowed (0, inf) m/s",
        ),
        (
            &["curve", "CS", "--set", "F_s=-1"],
            "parameter `F_s` = -1 is out of range: allowed [0, inf) N",
        ),
        (
            &["curve", "SD", "--set", "sigma=nan"],
            "parameter `sigma` = NaN is out of range: allowed (0, inf) N/m",
        ),
        (
            &["curve", "SD", "--set", "F_c=inf"],
            "parameter `F_c` = inf is out of range",
        ),
        (
            &["curve", "SD", "--set", "mu_s=0.7"],
            "unknown parameter `mu_s` (did you mean `mu_v`?); known parameters: F_s, F_c",
        ),
        (
            &["curve", "SD", "--set", "F_s"],
            "--set `F_s`: expected NAME=VALUE",
        ),
        (
            &["curve", "SD", "--set", "F_s=abc"],
            "`abc` is not a number",
        ),
        (
            // Only the last would be used: a script that appends its --set's twice.
            &[
                "curve", "SD", "--set", "F_s=8", "--set", "F_c=5", "--set", "F_s=9",
            ],
            "option `--set`: parameter `F_s` is set twice, F_s=8 and F_s=9: set each parameter \
             once (only the last would be used)",
        ),
        (
            &["curve", "SD", "--set", "F_s=7,F_c=5"],
            "`7,F_c=5` is not a number (one parameter per --set: --set F_s=… --set …)",
        ),
        (
            &["curve", "SD", "--set", "F_s=7,8"],
            "`7,8` is not a number (one value per --set: a list of values is a sweep",
        ),
        (
            &["curve", "SD", "--param-set", "steel"],
            "option `--param-set` = `steel` is no parameter set: known sets: paper, lugre-1995",
        ),
        // A value with a leading hyphen reaches the option's own message, not clap's
        // "unexpected argument '-1' found".
        (
            &["simulate", "belt", "--model", "CS", "--t-end", "-1"],
            "option `--t-end` = -1 is out of range: allowed [1e-6, 1e6] s",
        ),
        (
            &["simulate", "belt", "--model", "-x"],
            "invalid value '-x' for '--model <MODEL>': unknown model `-x`",
        ),
        (
            &["compare", "belt", "--model", "CS", "--targets", "1e-3,2"],
            "option `--targets` has 2: allowed values (0, 1): a relative error of 1 or more has \
             no correct digit",
        ),
        (
            &["stiffness", "belt", "--model", "CS", "--parameter", "abc"],
            "option `--parameter`: unknown parameter `abc`; known parameters: m, F_ex, k,",
        ),
        (
            &[
                "curve",
                "lugre",
                "--param-set",
                "lugre-1995",
                "--set",
                "F_s=0",
            ],
            "parameter `F_s` = 0 is not allowed here",
        ),
        (
            &["reproduce", "--set", "mu_v=-0.5"],
            "parameter `mu_v` = -0.5 is out of range: allowed [0, inf) N*s/m",
        ),
        // reproduce runs every rig and the chain at their own settings: a rig's or the
        // chain's parameter is refused by name, a misspelt one as unknown.
        (
            &["reproduce", "--set", "F_ex=20"],
            "parameter `F_ex` is not a friction parameter: reproduce runs every rig and the \
             chain at their own (the paper's) settings",
        ),
        (
            &["reproduce", "--set", "n_bodies=5"],
            "parameter `n_bodies` is not a friction parameter",
        ),
        (
            &["reproduce", "--set", "F_x=3"],
            "unknown parameter `F_x` (did you mean `F_s`?); known parameters: F_s, F_c",
        ),
        (
            &["curve", "gms", "--set", "n_gms=17"],
            "parameter `n_gms` = 17 is out of range: allowed [1, 16]",
        ),
        (
            &["curve", "gms", "--set", "n_gms=2.5"],
            "parameter `n_gms` = 2.5 is not allowed here: the number of slip blocks must be a \
             whole number in [1, 16]",
        ),
    ];
    for (args, message) in cases {
        let text = rejected(args);
        assert!(text.contains(message), "{args:?}: {text}");
    }
}

#[test]
fn bad_options_and_files_are_rejected() {
    let dir = tempfile::tempdir().unwrap();
    let malformed = dir.path().join("bad.toml");
    std::fs::write(&malformed, "F_c = 6\nF_s = = 3\n").unwrap();
    let twice = dir.path().join("twice.toml");
    std::fs::write(&twice, "F_s = 7\nF_c = 6\nF_s = 8\n").unwrap();
    let text_value = dir.path().join("text.toml");
    std::fs::write(&text_value, "F_s = \"high\"\n").unwrap();
    let negative = dir.path().join("negative.toml");
    std::fs::write(&negative, "F_s = -1\n").unwrap();
    let negative_message = format!(
        "parameter file {} (--params): parameter `F_s` = -1 is out of range",
        negative.display()
    );
    let unknown = dir.path().join("unknown.toml");
    std::fs::write(&unknown, "mass = 2.0\n").unwrap();
    let missing = dir.path().join("missing.toml");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["curve", "bouc-wen"],
            "unknown model `bouc-wen`; known models: AV, CS",
        ),
        (
            vec!["curve", "AV", "--variant", "even"],
            "unknown variant `even`; allowed: odd, printed",
        ),
        (
            vec!["curve", "AV", "--points", "1"],
            "option `--points` = 1 is out of range: allowed [2, 1e7]",
        ),
        (
            vec!["curve", "AV", "--t-end", "3"],
            "--t-end does not apply to AV",
        ),
        (
            vec!["curve", "DV", "--t-end", "-1"],
            "option `--t-end` = -1 is out of range: allowed [1e-6, 1e6] s",
        ),
        (
            vec!["curve", "AV", "--params", malformed.to_str().unwrap()],
            "bad.toml (--params): line 2: ",
        ),
        (
            vec!["curve", "AV", "--params", twice.to_str().unwrap()],
            "twice.toml (--params): line 3: duplicate key (`F_s = 8`)",
        ),
        (
            vec!["curve", "AV", "--params", text_value.to_str().unwrap()],
            "`F_s` must be a number, found string",
        ),
        (
            vec!["curve", "AV", "--params", unknown.to_str().unwrap()],
            "unknown parameter `mass`",
        ),
        (
            vec!["curve", "AV", "--params", negative.to_str().unwrap()],
            &negative_message,
        ),
        // An end time derived from the parameters is blamed on them, before any run.
        (
            vec![
                "simulate",
                "force-ramp",
                "--model",
                "CS",
                "--set",
                "rate=1e308",
            ],
            "the end time of scenario force-ramp, 2·max(F_s, F_c)/rate with F_s = 7.5, F_c = \
             6, rate = 1e308, is 1.500e-307 s: allowed [1e-6, 1e6] s",
        ),
        (
            vec![
                "independence",
                "oscillation",
                "--model",
                "dahl",
                "--set",
                "omega=1e-9",
            ],
            "the end time of scenario oscillation, three periods, 6π/omega with omega = 1e-9, \
             is 1.885e10 s",
        ),
        (
            vec!["curve", "AV", "--params", missing.to_str().unwrap()],
            "missing.toml",
        ),
    ];
    for (args, message) in cases {
        let text = rejected(&args);
        assert!(text.contains(message), "{args:?}: {text}");
    }
}

#[test]
fn simulate_writes_trajectory_summary_and_figures() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("belt");
    let o = friction_lab(&[
        "simulate",
        "belt",
        "--model",
        "SV",
        "--solver",
        "dopri5",
        "--out",
        out.to_str().unwrap(),
        "--t-end",
        "5",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
    assert!(csv.starts_with("t,x,v,friction,mode,z\n"), "{}", &csv[..40]);
    assert!(csv.contains(",stick,") && csv.contains(",slip-,"));
    let s: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["system"], "belt");
    assert_eq!(
        (s["n_bodies"].as_u64(), s["n_contacts"].as_u64()),
        (Some(1), Some(1))
    );
    assert_eq!(s["status"], "ok");
    assert_eq!(s["t_reached"], 5.0);
    assert_eq!(s["parameters"]["k"], 100.0);
    // events.csv lists every switch, summary.json counts them by the mode entered.
    let events = std::fs::read_to_string(out.join("events.csv")).unwrap();
    let switches = events.lines().count() - 1;
    assert_eq!(s["stats"]["events"].as_u64().unwrap() as usize, switches);
    let counted: u64 = s["event_counts"]
        .as_object()
        .unwrap()
        .values()
        .map(|n| n.as_u64().unwrap())
        .sum();
    assert_eq!(counted as usize, switches);
    assert!(events.starts_with("t,body,from,to\n") && events.contains(",body,stick,slip-\n"));
    // final.csv: the one body at the end, as the trajectory's last row has it.
    let last = csv.lines().last().unwrap().split_once(',').unwrap().1;
    assert_eq!(
        std::fs::read_to_string(out.join("final.csv")).unwrap(),
        format!("body,x,v,friction,mode,z\nbody,{last}\n")
    );
    for stem in [
        "history-x",
        "history-v",
        "history-friction",
        "phase-portrait",
        "friction-velocity",
        "friction-displacement",
    ] {
        assert!(
            out.join(format!("{stem}.png")).exists() && out.join(format!("{stem}.svg")).exists(),
            "{stem}"
        );
    }
    // Friction is drawn against the sliding velocity, as a tribologist reads it.
    let svg = std::fs::read_to_string(out.join("friction-velocity.svg")).unwrap();
    assert!(
        svg.contains("sliding velocity v − v_surface (m/s)"),
        "{svg}"
    );
}

/// The paper's block under LuGre with the 1995 bristles (sigma0 = 1e5 N/m): a stiff run.
const LUGRE_BLOCK: [&str; 6] = [
    "simulate",
    "paper-block",
    "--model",
    "lugre",
    "--param-set",
    "lugre-1995",
];

#[test]
fn a_stiff_run_reports_hairers_stiffness_diagnostic() {
    let dir = tempfile::tempdir().unwrap();
    let run = |solver: Option<&str>| {
        let out = dir.path().join(solver.unwrap_or("default"));
        let mut args = LUGRE_BLOCK.to_vec();
        args.extend(["--t-end", "0.5", "--out", out.to_str().unwrap()]);
        args.extend(solver.iter().flat_map(|s| ["--solver", s]));
        let o = friction_lab(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let s: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
        (stderr(&o), s)
    };
    let (note, s) = run(Some("dopri5"));
    assert!(
        note.contains("dopri5 found the problem stiff at t = "),
        "{note}"
    );
    let t = s["stiffness_detected_at"].as_f64().unwrap();
    assert!(t > 0.0 && t < 0.5, "{t}");
    // By default the run switches to Radau IIA where Dormand-Prince's test fires, with no
    // advice to: far fewer evaluations of f.
    let (note, auto) = run(None);
    assert_eq!(auto["solver"], "auto");
    assert_eq!(auto["method_switches"][0]["to"], "radau5", "{auto}");
    assert!(!note.contains("found the problem stiff"), "{note}");
    let evals = |s: &serde_json::Value| s["stats"]["rhs_evals"].as_f64().unwrap();
    assert!(
        evals(&auto) * 10.0 < evals(&s),
        "{} {}",
        evals(&auto),
        evals(&s)
    );
}

#[test]
fn a_failing_solver_keeps_its_trajectory_and_exits_non_zero() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fail");
    // RK4 with h = 0.01 on LuGre's stiff bristles (sigma0 = 1e5 N/m) overflows.
    let mut args = LUGRE_BLOCK.to_vec();
    args.extend([
        "--solver",
        "rk4",
        "--dt",
        "0.01",
        "--out",
        out.to_str().unwrap(),
    ]);
    let o = friction_lab(&args);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("non-finite state at t = "),
        "{}",
        stderr(&o)
    );
    let s: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(
        s["status"], "diverged",
        "a non-finite state is a divergence"
    );
    assert!(s["error"]
        .as_str()
        .unwrap()
        .starts_with("non-finite state at t = "));
    let rows = std::fs::read_to_string(out.join("trajectory.csv"))
        .unwrap()
        .lines()
        .count();
    assert!(
        rows > 2,
        "the trajectory up to the failure is kept ({rows} lines)"
    );
}

#[test]
fn bad_scenario_input_is_rejected_and_writes_nothing() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["simulate", "bogus", "--model", "CS"],
            "unknown scenario `bogus`; known scenarios: paper-block",
        ),
        (
            &["simulate", "belt", "--model", "CS", "--set", "k=-1"],
            "parameter `k` = -1 is out of range: allowed [0, inf) N/m",
        ),
        (
            &["simulate", "belt", "--model", "CS", "--set", "k=0"],
            "parameter `k` = 0 is out of range for belt: allowed (0, inf) N/m",
        ),
        (
            &["simulate", "paper-block", "--model", "CS", "--set", "k=5"],
            "parameter `k` is not used by scenario paper-block (it reads: m, F_ex, x0, v0)",
        ),
        (
            &["simulate", "belt", "--model", "CS", "--set", "m=0"],
            "parameter `m` = 0 is out of range: allowed (0, inf) kg",
        ),
        (
            &["simulate", "belt", "--model", "CS", "--switching", "smooth"],
            "unknown switching `smooth`; allowed: event, regularized, naive",
        ),
        (
            &["simulate", "belt", "--model", "CS", "--solver", "euler"],
            "unknown solver `euler`; known solvers: rk4",
        ),
        (
            &["simulate", "belt", "--model", "CS", "--rtol", "0"],
            "option `--rtol` = 0 is out of range: allowed [1e-14, 1]",
        ),
        (
            &["simulate", "belt", "--model", "CS", "--t-end", "-2"],
            "option `--t-end` = -2 is out of range: allowed [1e-6, 1e6] s",
        ),
        (
            &["simulate", "force-ramp", "--model", "CS", "--set", "rate=0"],
            "parameter `rate` = 0 is out of range: allowed (0, inf) N/s",
        ),
        (
            &["phenomena", "--threads", "0"],
            "option `--threads` = 0 is out of range: allowed [1, 1024]",
        ),
        (
            &["phenomena", "--solver", "rk4"],
            "solver `rk4` needs a fixed step",
        ),
        (
            &[
                "simulate",
                "belt",
                "--model",
                "CS",
                "--solver",
                "bdf",
                "--fixed-step",
            ],
            "option `--fixed-step` does not apply to solver `bdf`: it chooses its own steps \
             from --rtol and --atol; allowed with rk4, dopri5, implicit-euler",
        ),
        (
            &[
                "simulate",
                "chain",
                "--model",
                "elasto-plastic",
                "--solver",
                "esdirk34",
                "--fixed-step",
            ],
            "option `--fixed-step` does not apply to solver `esdirk34`",
        ),
    ];
    for (args, message) in cases {
        let text = rejected(args);
        assert!(text.contains(message), "{args:?}: {text}");
    }
}

/// Runs a study command on one and on two threads into `dir` and asserts that `files` are
/// identical; returns the one-thread folder.
fn identical_on_one_and_two_threads(
    dir: &std::path::Path,
    args: &[&str],
    files: &[&str],
) -> std::path::PathBuf {
    let run = |threads: &str| {
        let out = dir.join(format!("{}-t{threads}", args[0]));
        let mut all = args.to_vec();
        all.extend(["--threads", threads, "--out", out.to_str().unwrap()]);
        let o = friction_lab(&all);
        assert!(o.status.success(), "{}", stderr(&o));
        out
    };
    let (one, two) = (run("1"), run("2"));
    for name in files {
        let (a, b) = (
            without_provenance(&one.join(name)),
            without_provenance(&two.join(name)),
        );
        assert_eq!(
            a, b,
            "{name} of {} differs between 1 and 2 threads",
            args[0]
        );
    }
    // The provenance says how many threads.
    for (folder, threads) in [(&one, 1), (&two, 2)] {
        if let Some(json) = files.iter().find(|f| f.ends_with(".json")) {
            let v: serde_json::Value =
                serde_json::from_slice(&std::fs::read(folder.join(json)).unwrap()).unwrap();
            assert_eq!(v["provenance"]["threads"], threads, "{json}");
        }
    }
    one
}

/// The bytes of the file `path`; for a JSON file, its text without the `provenance` (the
/// date, the machine and the thread count differ between runs; the results do not).
fn without_provenance(path: &std::path::Path) -> Vec<u8> {
    let bytes = std::fs::read(path).unwrap();
    if path.extension().is_some_and(|e| e == "json") {
        let mut v: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
        if let Some(o) = v.as_object_mut() {
            o.remove("provenance");
        }
        return serde_json::to_vec_pretty(&v).unwrap();
    }
    bytes
}

/// Every folder names where its files come from: `provenance.json` lists every file written
/// (the CSV files and figures carry no header of their own) and the command line as typed,
/// and every JSON file opens with the same provenance.
#[test]
fn every_folder_names_its_provenance_and_lists_its_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run with space");
    let o = friction_lab(&[
        "simulate",
        "belt",
        "--model",
        "CVS",
        "--t-end",
        "2",
        "--set",
        "v_belt=0.1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let sidecar: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("provenance.json")).unwrap()).unwrap();
    let command = format!(
        "friction-lab simulate belt --model CVS --t-end 2 --set v_belt=0.1 --out '{}'",
        out.display()
    );
    assert_eq!(sidecar["provenance"]["command"], command.as_str());
    assert_eq!(
        sidecar["provenance"]["friction_lab"],
        env!("CARGO_PKG_VERSION")
    );
    let mut listed: Vec<String> = (sidecar["files"].as_array().unwrap().iter())
        .map(|f| f.as_str().unwrap().to_string())
        .collect();
    listed.sort();
    let mut present: Vec<String> = (std::fs::read_dir(&out).unwrap())
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| !name.starts_with('.') && name != "provenance.json")
        .collect();
    present.sort();
    assert_eq!(listed, present);
    assert!(
        present.contains(&"trajectory.csv".to_string()),
        "{present:?}"
    );
    for json in present.iter().filter(|name| name.ends_with(".json")) {
        let text = std::fs::read_to_string(out.join(json)).unwrap();
        assert!(text.starts_with("{\n  \"provenance\""), "{json}: {text}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["provenance"], sidecar["provenance"], "{json}");
    }
}

/// Every study's JSON opens with its provenance: the version and git commit, the date, the
/// machine and the thread count; `report.md` names the same.
#[test]
fn every_study_names_its_provenance() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c");
    let o = friction_lab(&[
        "converge",
        "belt",
        "--model",
        "CS",
        "--t-end",
        "1",
        "--solvers",
        "rk4",
        "--dt-list",
        "0.01,0.005,0.0025",
        "--threads",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(out.join("converge.json")).unwrap();
    assert!(
        text.trim_start().starts_with("{\n  \"provenance\""),
        "{text}"
    );
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let p = &v["provenance"];
    assert_eq!(p["friction_lab"], env!("CARGO_PKG_VERSION"));
    let head = Command::new("git").args(["rev-parse", "HEAD"]).output();
    if let Some(head) = head.ok().filter(|h| h.status.success()) {
        assert_eq!(
            p["commit"],
            String::from_utf8_lossy(&head.stdout).trim(),
            "{p}"
        );
    }
    let date = p["date"].as_str().unwrap();
    assert!(
        date.len() == 20 && date.starts_with("20") && date.ends_with('Z'),
        "{date}"
    );
    assert_eq!(p["threads"], 1);
    assert_eq!(
        p["command"],
        format!(
            "friction-lab converge belt --model CS --t-end 1 --solvers rk4 --dt-list \
             0.01,0.005,0.0025 --threads 1 --out {}",
            out.display()
        )
        .as_str()
    );
    let cores = std::thread::available_parallelism().unwrap().get();
    assert_eq!(p["machine"]["logical_cores"], cores);
    assert!(!p["machine"]["cpu"].as_str().unwrap().is_empty());
}

#[test]
fn studies_on_one_and_two_threads_write_identical_files() {
    let dir = tempfile::tempdir().unwrap();
    let one = identical_on_one_and_two_threads(
        dir.path(),
        &[
            "converge",
            "free-vibration",
            "--model",
            "static",
            "--switching",
            "naive",
            "--solvers",
            "rk4,dopri5,bdf",
            "--t-end",
            "2",
        ],
        &[
            "converge.csv",
            "converge.json",
            "converge.png",
            "converge.svg",
        ],
    );
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(one.join("converge.json")).unwrap()).unwrap();
    assert_eq!(json["runs"].as_array().unwrap().len(), 4 + 4 + 3);
    assert!(
        json["reference"]["Run"]["solver"].is_string(),
        "the reference solver is named"
    );
    // The file says what it studied.
    assert_eq!(json["case"]["switching"], "naive");
    assert_eq!(json["case"]["t_end"], 2.0);
    let description = json["case"]["description"].as_str().unwrap();
    assert!(
        description.contains("free-vibration") && description.contains("static"),
        "{description}"
    );
    // A sweep's values and a study's timing repeats share one list of runs.
    let one = identical_on_one_and_two_threads(
        dir.path(),
        &[
            "stiffness",
            "belt",
            "--model",
            "CS",
            "--parameter",
            "k",
            "--values",
            "100,400",
            "--solvers",
            "dopri5,bdf",
            "--tol-list",
            "1e-4,1e-6",
            "--t-end",
            "2",
        ],
        &["stiffness.csv", "stiffness.json", "stiffness.svg"],
    );
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(one.join("stiffness.json")).unwrap()).unwrap();
    assert_eq!(json["points"].as_array().unwrap().len(), 2);
    // Swept over k, not epsilon, a rig keeps event switching by default.
    assert_eq!(json["case"]["switching"], "event");
    identical_on_one_and_two_threads(
        dir.path(),
        &[
            "work-precision",
            "belt",
            "--model",
            "CS",
            "--solvers",
            "rk4,dopri5",
            "--dt-list",
            "0.01,0.005",
            "--tol-list",
            "1e-4,1e-6",
            "--t-end",
            "2",
        ],
        &[
            "work-precision.csv",
            "work-precision.json",
            "work-precision.svg",
        ],
    );
}

#[test]
fn bad_study_input_is_rejected() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["converge", "belt", "--model", "CS", "--dt-list", "0.01,-1"],
            "option `--dt-list` has -1: allowed values [1e-10, 10] s",
        ),
        (
            &["independence", "belt", "--model", "CS", "--ratio", "1"],
            "option `--ratio` = 1 is out of range: allowed (1, 1000]",
        ),
        (
            &["independence", "belt", "--model", "CS", "--levels", "1"],
            "option `--levels` = 1 is out of range: allowed [2, 12]",
        ),
        (
            &[
                "stiffness",
                "belt",
                "--model",
                "CS",
                "--parameter",
                "stiffness",
            ],
            "unknown parameter `stiffness`",
        ),
        (
            &["converge", "velocity-sweep", "--model", "CS"],
            "velocity-sweep has none",
        ),
        (
            // Orders are taken between neighbours: a list must refine.
            &[
                "converge",
                "belt",
                "--model",
                "CS",
                "--dt-list",
                "0.005,0.01",
            ],
            "option `--dt-list` has 0.005 then 0.01: allowed values from coarse to fine",
        ),
        (
            &[
                "work-precision",
                "belt",
                "--model",
                "CS",
                "--tol-list",
                "1e-4,1e-4",
            ],
            "option `--tol-list` has 1e-4 then 1e-4: allowed values from coarse to fine",
        ),
        (
            // stiffness did not check its lists at all.
            &["stiffness", "belt", "--model", "CS", "--tol-list", "1e-300"],
            "option `--tol-list` has 1e-300: allowed values [1e-14, 1]",
        ),
        (
            &[
                "stiffness",
                "belt",
                "--model",
                "CS",
                "--solvers",
                "bdf,dopri5,bdf",
            ],
            "option `--solvers` names `bdf` twice: allowed each solver once",
        ),
        (
            // Every value would give the same runs, and a vacuous verdict.
            &[
                "stiffness",
                "belt",
                "--model",
                "CS",
                "--parameter",
                "sigma0",
            ],
            "option `--parameter`: parameter `sigma0` is not read by model `CS`",
        ),
    ];
    for (args, message) in cases {
        let text = rejected(args);
        assert!(text.contains(message), "{args:?}: {text}");
    }
}

#[test]
fn simulate_chain_writes_the_system_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("chain");
    let o = friction_lab(&[
        "simulate",
        "chain",
        "--model",
        "static",
        "--set",
        "n_bodies=30",
        "--set",
        "F_c=5",
        "--t-end",
        "20",
        "--points",
        "101",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let fin = std::fs::read_to_string(out.join("final.csv")).unwrap();
    let lines: Vec<&str> = fin.lines().collect();
    assert_eq!(lines[0], "body,x,v,friction,mode");
    assert_eq!(lines.len(), 31, "one row per body");
    assert!(lines[1].starts_with("b1,") && lines[30].starts_with("b30,"));
    let events = std::fs::read_to_string(out.join("events.csv")).unwrap();
    assert!(events.starts_with("t,body,from,to\n"));
    assert!(events.lines().count() > 30, "every block breaks away");
    assert!(events.contains(",stick,slip+"));
    // 20 of the 30 bodies by default, at 101 grid points: the tidy trajectory.
    let tidy = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
    assert!(tidy.starts_with("t,body,x,v,friction,mode\n"));
    assert_eq!(tidy.lines().count(), 1 + 101 * 20);
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["n_bodies"], 30);
    assert_eq!(summary["status"], "ok");
    assert_eq!(summary["parameters"]["F_c"], 5.0);
    assert_eq!(summary["parameters"]["n_bodies"], 30.0);
    assert!(summary["energy"]["relative_residual"].as_f64().unwrap() < 1e-6);
    let by_kind = summary["event_counts"].as_object().unwrap();
    let counted: u64 = by_kind.values().map(|v| v.as_u64().unwrap()).sum();
    assert_eq!(counted as usize, events.lines().count() - 1);
    for f in [
        "space-time.png",
        "space-time.svg",
        "velocity.png",
        "velocity.svg",
        "phase-portrait.png",
        "phase-portrait.svg",
        "spectrum.csv",
        "spectrum.json",
        "spectrum.png",
        "velocity-space-time.png",
        "velocity-space-time.svg",
        "friction-velocity.png",
        "friction-velocity.svg",
    ] {
        assert!(out.join(f).exists(), "{f}");
    }
    // The line figures and the spectra draw four of the twenty bodies written, spread over
    // them; every body's velocity is in the space–time picture, in bands of equal width.
    let svg = std::fs::read_to_string(out.join("velocity.svg")).unwrap();
    assert!(svg.contains("velocities of 4 of the 20 bodies written"));
    let spectrum = std::fs::read_to_string(out.join("spectrum.csv")).unwrap();
    assert_eq!(spectrum.lines().next(), Some("frequency,b1,b10,b20,b30"));
    let picture = std::fs::read_to_string(out.join("velocity-space-time.svg")).unwrap();
    assert!(
        picture.contains(" m/s") && picture.contains(" to "),
        "band labels"
    );
}

/// The stiffness along a chain too large for its eigenvalues (120 unknowns): power iteration's
/// spectral radius at 21 points at least, within the bound of Gershgorin's theorem. With the
/// static model a sliding body adds no slope, so J's eigenvalues are ±i·√λ(K)/√m with λ(K) ≤
/// k_driver + 4·k_chain = 410: ρ ≤ √410, and a sliding run of four bodies or more comes within
/// 10 % of it.
#[test]
fn simulate_measures_the_stiffness_of_a_large_chain() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("chain");
    let o = friction_lab(&[
        "simulate",
        "chain",
        "--model",
        "static",
        "--set",
        "n_bodies=60",
        "--set",
        "F_c=5",
        "--t-end",
        "20",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("stiffness.csv")).unwrap();
    assert!(csv.starts_with("t,h,rho,h_rho\n"), "{csv}");
    let rows = csv.lines().count() - 1;
    assert!(rows >= 21, "{rows} points");
    assert!(out.join("stiffness.png").exists() && out.join("stiffness.svg").exists());
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    let stiffness = &summary["stiffness"];
    assert_eq!(stiffness["points"].as_u64().unwrap() as usize, rows);
    let bound = 410f64.sqrt();
    let max_rho = stiffness["max_rho"].as_f64().unwrap();
    assert!(
        max_rho <= bound * 1.001 && max_rho > 0.9 * bound,
        "{stiffness}"
    );
}

/// A rig, the chain, a system file and a prescribed motion write one `summary.json` schema:
/// the same fields in the same order (docs/files.md), and the same four data files.
#[test]
fn every_run_writes_one_summary_schema() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("two.toml");
    std::fs::write(
        &file,
        "[[body]]\nname = \"a\"\nm = 1\nv0 = 0.1\n[[body]]\nname = \"b\"\nm = 1\n\
         [[spring]]\nbetween = [\"a\", \"b\"]\nk = 10\n\
         [[contact]]\nbody = \"a\"\nmodel = \"coulomb\"\n",
    )
    .unwrap();
    let runs: [&[&str]; 4] = [
        &["belt", "--model", "CVS", "--t-end", "2"],
        &["prescribed-motion", "--model", "dahl"],
        &[
            "chain",
            "--model",
            "coulomb",
            "--set",
            "n_bodies=3",
            "--t-end",
            "2",
        ],
        &["--system", file.to_str().unwrap(), "--t-end", "2"],
    ];
    let mut schemas = Vec::new();
    for (k, args) in runs.iter().enumerate() {
        let out = dir.path().join(format!("run{k}"));
        let mut all = vec!["simulate", "--out", out.to_str().unwrap()];
        all.extend(*args);
        let o = friction_lab(&all);
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
        let s: serde_json::Value = serde_json::from_str(&text).unwrap();
        let keys: Vec<String> = s.as_object().unwrap().keys().cloned().collect();
        schemas.push((args[0], keys));
        for f in ["trajectory.csv", "final.csv", "events.csv"] {
            assert!(out.join(f).is_file(), "{args:?}: {f}");
        }
        assert_eq!(s["status"], "ok", "{args:?}");
        assert_eq!(s["t_reached"], s["t_end"], "{args:?}");
    }
    for (name, keys) in &schemas[1..] {
        assert_eq!(keys, &schemas[0].1, "{name} against belt");
    }
}

/// A stiffness study of the chain sweeps its coupling: the explicit method pays for a stiff
/// spring between the blocks (they stick and slip against their neighbours every few
/// milliseconds, each switch a restart and a run of rejected steps), BDF does not.
#[test]
fn stiffness_of_the_chain_sweeps_its_coupling_spring() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("stiff");
    let o = friction_lab(&[
        "stiffness",
        "chain",
        "--model",
        "CS",
        "--parameter",
        "k_chain",
        "--values",
        "100,1e6",
        "--solvers",
        "dopri5,bdf",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("stiffness.json")).unwrap()).unwrap();
    let work = |value: usize, solver: &str| -> f64 {
        let costs = json["points"][value]["costs"].as_array().unwrap();
        let cost = costs.iter().find(|c| c["solver"] == solver).unwrap();
        assert!(!cost["reached"].is_null(), "{solver} reached the target");
        cost["reached"]["work"].as_f64().unwrap()
    };
    let (explicit, implicit) = (
        work(1, "dopri5") / work(0, "dopri5"),
        work(1, "bdf") / work(0, "bdf"),
    );
    assert!(explicit > 10.0, "Dormand–Prince: {explicit}");
    assert!(implicit < 2.0, "BDF: {implicit}");
    assert_eq!(json["crossover"], 1e6);
}

/// Two bodies in a row from a fixed frame, the first on a belt at 0.1 m/s with CS.
const TWO_BODIES: &str = r#"
[[body]]
name = "m1"
m = 1.0
[[body]]
name = "m2"
m = 0.5
[[anchor]]
name = "frame"
[[spring]]
between = ["frame", "m1"]
k = 100.0
[[spring]]
between = ["m1", "m2"]
k = 50.0
c = 0.2
[[contact]]
body = "m1"
surface_velocity = 0.1
model = "CS"
"#;

#[test]
fn a_body_whose_name_has_a_comma_is_chosen_by_its_index() {
    // `--bodies` splits at commas: the name cannot be given, and the refusal says which index
    // to give instead (the second body here).
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("comma.toml");
    std::fs::write(&file, TWO_BODIES.replace("\"m2\"", "\"right, m2\"")).unwrap();
    let system = file.to_str().unwrap();
    let e = rejected(&["simulate", "--system", system, "--bodies", "right, m2"]);
    assert!(
        e.contains("`right` is no body: allowed a body's name or an index in [1, 2]; body \"right, m2\" has a comma: choose it by its index, 2"),
        "{e}"
    );
    let out = dir.path().join("by-index");
    let o = friction_lab(&[
        "simulate",
        "--system",
        system,
        "--bodies",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let fin = std::fs::read_to_string(out.join("final.csv")).unwrap();
    assert!(fin.contains("\n\"right, m2\","), "{fin}");
}

#[test]
fn simulate_and_study_a_system_file() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("two.toml");
    std::fs::write(&file, TWO_BODIES).unwrap();
    let out = dir.path().join("sim");
    let o = friction_lab(&[
        "simulate",
        "--system",
        file.to_str().unwrap(),
        "--bodies",
        "m2,1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let fin = std::fs::read_to_string(out.join("final.csv")).unwrap();
    assert!(fin.contains("\nm2,") && fin.contains(",none\n"), "{fin}");
    let tidy = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
    assert!(
        tidy.lines().nth(1).unwrap().starts_with("0,m2,"),
        "chosen order"
    );
    let study = dir.path().join("study");
    let o = friction_lab(&[
        "converge",
        "--system",
        file.to_str().unwrap(),
        "--bodies",
        "m1,m2",
        "--solvers",
        "rk4",
        "--t-end",
        "2",
        "--out",
        study.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(study.join("converge.json")).unwrap()).unwrap();
    let order = json["orders"]
        .as_array()
        .unwrap()
        .iter()
        .find(|o| o["measure"] == "final_relative")
        .unwrap()["order"]
        .as_f64()
        .unwrap();
    assert!((order - 4.0).abs() < 0.5, "RK4 order {order}");
}

#[test]
fn bad_system_input_is_rejected_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.toml");
    std::fs::write(
        &file,
        "[[body]]\nname = \"a\"\nm = 1.0\n[[contact]]\nbody = \"a\"\nmodel = \"CS\"\nparams = { F_s = -2.0 }\n",
    )
    .unwrap();
    let path = file.to_str().unwrap();
    let body = "[[body]]\nname = \"a\"\nm = 1.0\n";
    let anchors = "[[anchor]]\nname = \"w1\"\n[[anchor]]\nname = \"w2\"\n";
    let spring = |ends: &str| {
        let file = dir.path().join(format!("spring-{}.toml", ends.len()));
        let text = format!("{body}{anchors}[[spring]]\nbetween = {ends}\nk = 1.0\n");
        std::fs::write(&file, text).unwrap();
        file.to_str().unwrap().to_string()
    };
    let (to_itself, anchors_only) = (spring("[\"a\", \"a\"]"), spring("[\"w1\", \"w2\"]"));
    let cases: &[(&[&str], &str)] = &[
        (
            &["simulate", "--system", path],
            "bad.toml: [[contact]] 1: `params.F_s`: parameter `F_s` = -2 is out of range: allowed [0, inf) N",
        ),
        (
            &["simulate", "--system", &to_itself],
            "[[spring]] 1: `between` = [\"a\", \"a\"]: a spring joins two different bodies, or \
             a body and an anchor",
        ),
        (
            &["simulate", "--system", &anchors_only],
            "[[spring]] 1: `between` = [\"w1\", \"w2\"]: a spring joins",
        ),
        (
            // A dimensionless range has no unit after it, and a large value an exponent.
            &["simulate", "belt", "--model", "gms", "--set", "n_gms=1e12"],
            "error: parameter `n_gms` = 1e12 is out of range: allowed [1, 16]\n",
        ),
        (
            &["simulate", "chain", "--model", "CS", "--set", "n_bodies=0"],
            "error: chain: `n_bodies` = 0 is out of range: allowed [1, 1000000], a whole number",
        ),
        (
            &["simulate", "chain", "--model", "CS", "--set", "m=0"],
            "error: chain: `m` = 0 is out of range: allowed (0, inf) kg",
        ),
        (
            &["simulate", "chain", "--model", "CS", "--set", "spread=1.5"],
            "`spread` = 1.5 is out of range: allowed [0, 1)",
        ),
        (
            &["simulate", "chain"],
            "option `--model` is required for the chain",
        ),
        (
            &["simulate", "chain", "--model", "CS", "--bodies", "b99"],
            "option `--bodies`: `b99` is no body: allowed a body's name or an index in [1, 10]",
        ),
        (
            &["simulate", "chain", "--model", "CS", "--bodies", "b2,3,2"],
            "option `--bodies`: `b2` and `2` are the same body, b2: choose each body once",
        ),
        (
            &["simulate", "belt", "--model", "CS", "--bodies", "1"],
            "option `--bodies` applies to systems",
        ),
        (
            &["simulate", "--system", "/nonexistent/system.toml"],
            "system file /nonexistent/system.toml:",
        ),
        (
            // The chain's spring to its neighbour is `k_chain`; a rig's spring is `k`.
            &["stiffness", "chain", "--model", "CS", "--parameter", "k"],
            "unknown parameter `k` of the chain; known: n_bodies, m, k_chain, k_driver, \
             v_driver, spread, and the friction parameters its law reads",
        ),
        (
            &["stiffness", "chain", "--model", "CS", "--parameter", "sigma"],
            "parameter `sigma` is not read by model `CS` (it reads: F_c, F_s, C1, C2, v_s)",
        ),
        (
            // No run of the study reads the width under time-stepping: every value the same.
            &[
                "stiffness",
                "chain",
                "--model",
                "CS",
                "--scheme",
                "time-stepping",
            ],
            "parameter `epsilon` is read on a system only under --switching regularized, or \
             event (by its regularised BDF peer); not timestepping",
        ),
        (
            // 2e10 recorded numbers would exhaust the memory before the first step.
            &[
                "simulate",
                "chain",
                "--model",
                "coulomb",
                "--set",
                "n_bodies=100000",
                "--points",
                "100000",
            ],
            "option `--points` = 100000 would record 2.00003e10 numbers for the system's 200003 \
             unknowns: allowed at most 2.5e8 numbers, so at most 1249 points",
        ),
        (
            // The report time-steps the chain with `static` friction, whose sliding force
            // at rest (F_c) lies outside its stick interval [-F_s, F_s] once F_s = 0; the
            // message speaks of what reproduce takes (no file, no --switching).
            &["reproduce", "--set", "F_s=0"],
            "the parameters given cannot be used by reproduce: its chain studies time-step \
             the chain (Moreau-Jean), and with them model `static`: its sliding force at \
             v_rel = 0+",
        ),
        (
            // Its numbers as every message shows them: an exponent from 1e6 on.
            &["reproduce", "--set", "F_c=1e6"],
            "its sliding force at v_rel = 0+, 1.0841470984807897e6 N, lies outside its stick \
             interval [-8.131103238605922, 8.131103238605922] N",
        ),
    ];
    for (args, message) in cases {
        let text = rejected(args);
        assert!(text.contains(message), "{args:?}: {text}"); // reproduce takes no --switching and no file: its messages do not speak of them.
        if args[0] == "reproduce" {
            assert!(
                !text.contains("--switching") && !text.contains("[[contact]]"),
                "{text}"
            );
        }
    }
}

#[test]
fn independence_with_an_adaptive_solver_and_a_changing_event_count_reports_it() {
    // Dormand–Prince at tolerances 1e-3 … 1.25e-4 on the belt finds different numbers of events
    // at different tolerances: the study says so instead of failing.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("i");
    let o = friction_lab(&[
        "independence",
        "belt",
        "--model",
        "CS",
        "--solver",
        "dopri5",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("independence.csv")).unwrap();
    let counts: Vec<&str> = csv
        .lines()
        .filter(|l| l.starts_with("number of events,"))
        .collect();
    assert_eq!(counts.len(), 4, "{csv}");
    assert!(counts.iter().all(|l| l.ends_with(",false")), "{counts:?}");
}

/// Names in `dir` that start with friction-lab's temporary prefix.
fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".friction-lab-"))
        .collect()
}

#[test]
fn a_folder_is_written_whole_or_not_at_all() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r");
    let curve = |out: &Path| friction_lab(&["curve", "CS", "--out", out.to_str().unwrap()]);
    // A folder friction-lab did not write, with something in it: refused, untouched, exit 2.
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let o = curve(&out);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("friction-lab did not write and it is not empty"));
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 1);
    // An empty folder is written; a second run replaces it whole, even where a file of the
    // set is in the way as a folder (the reproducer: table2.json as a folder made reproduce
    // fail half-way).
    std::fs::remove_file(out.join("notes.txt")).unwrap();
    assert!(curve(&out).status.success());
    std::fs::remove_file(out.join("curve-CS.json")).unwrap();
    std::fs::create_dir(out.join("curve-CS.json")).unwrap();
    // A file an earlier run wrote (listed in the marker) that this one does not write.
    std::fs::write(out.join("stale.csv"), "from an earlier run").unwrap();
    let marker = out.join(".friction-lab-output");
    let listed = std::fs::read_to_string(&marker).unwrap() + "stale.csv\n";
    std::fs::write(&marker, listed).unwrap();
    let o = curve(&out);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.join("curve-CS.json").is_file());
    assert!(
        !out.join("stale.csv").exists(),
        "the folder is replaced whole"
    );
    // A run killed while writing leaves its temporary folder; the next run removes it.
    let killed = dir.path().join(".friction-lab-AbC123");
    std::fs::create_dir(&killed).unwrap();
    std::fs::write(killed.join(".friction-lab-output"), "").unwrap();
    assert!(curve(&out).status.success());
    assert!(
        temporaries(dir.path()).is_empty(),
        "{:?}",
        temporaries(dir.path())
    );
    // The temporary folder of a run still writing beside it (its marker locked, as a living
    // run holds it) is left alone; once the lock is gone, it is stale and removed.
    let writing = dir.path().join(".friction-lab-XyZ789");
    std::fs::create_dir(&writing).unwrap();
    let marker = writing.join(".friction-lab-output");
    std::fs::write(&marker, "").unwrap();
    let lock = std::fs::File::open(&marker).unwrap();
    lock.lock().unwrap();
    assert!(curve(&out).status.success());
    assert_eq!(temporaries(dir.path()), [".friction-lab-XyZ789"]);
    drop(lock);
    assert!(curve(&out).status.success());
    assert!(temporaries(dir.path()).is_empty());
    // A file where the folder should be: refused with exit 2.
    let file = dir.path().join("file");
    std::fs::write(&file, "x").unwrap();
    let o = curve(&file);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("it exists and is not a folder"));
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(&out).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o755);
    }
}

#[test]
fn every_reproducer_of_unbounded_or_unchecked_input_is_rejected_with_its_range() {
    let dir = tempfile::tempdir().unwrap();
    let zero_file = if Path::new("/dev/zero").exists() {
        "/dev/zero".to_string()
    } else {
        let big = dir.path().join("big.toml");
        std::fs::write(&big, vec![b'#'; 2 << 20]).unwrap();
        big.to_string_lossy().into_owned()
    };
    let cases: &[(&[&str], &str)] = &[
        // Negative numbers are values, not flags.
        (
            &["curve", "AV", "--v-max", "-inf"],
            "option `--v-max` = -inf is out of range",
        ),
        (
            &["curve", "AV", "--points", "-1"],
            "option `--points` = -1 is out of range",
        ),
        (
            &["converge", "belt", "--model", "CS", "--dt-list", "-1e-3"],
            "option `--dt-list` has -0.001: allowed values [1e-10, 10] s",
        ),
        // Tolerances are checked whatever the solver.
        (
            &[
                "simulate", "belt", "--model", "CS", "--solver", "rk4", "--rtol", "0",
            ],
            "option `--rtol` = 0 is out of range: allowed [1e-14, 1]",
        ),
        (
            &[
                "simulate", "belt", "--model", "CS", "--solver", "rk4", "--atol", "-1",
            ],
            "option `--atol` = -1 is out of range: allowed (0, 1]",
        ),
        (
            &["simulate", "belt", "--model", "CS", "--atol", "1e309"],
            "option `--atol` = inf is out of range",
        ),
        // Inputs that ran without end.
        (
            &[
                "simulate",
                "belt",
                "--model",
                "CS",
                "--points",
                "1000000000",
            ],
            "option `--points` = 1e9 is out of range: allowed [2, 1e7]",
        ),
        (
            &["simulate", "belt", "--model", "CS", "--params", &zero_file],
            "the most a parameter file may hold",
        ),
        (
            &["phenomena", "--threads", "1000000000"],
            "option `--threads` = 1e9 is out of range: allowed [1, 1024]",
        ),
        (
            &["simulate", "belt", "--model", "CS", "--t-end", "1e12"],
            "option `--t-end` = 1e12 is out of range: allowed [1e-6, 1e6] s",
        ),
        (
            &["converge", "belt", "--model", "CS", "--tol-list", "1e-300"],
            "option `--tol-list` has 1e-300: allowed values [1e-14, 1]",
        ),
        (
            &["converge", "belt", "--model", "CS", "--dt-list", "5e-324"],
            "option `--dt-list` has 5e-324",
        ),
        (
            &["converge", "belt", "--model", "CS", "--t-end", "5e-324"],
            "option `--t-end` = 5e-324 is out of range",
        ),
        (
            &["independence", "belt", "--model", "CS", "--start", "1e-12"],
            "option `--start` = 1e-12 (finest level 1.25e-13) is out of range for rk4",
        ),
        (
            &[
                "work-precision",
                "belt",
                "--model",
                "CS",
                "--repeats",
                "1000",
            ],
            "option `--repeats` = 1000 is out of range: allowed [1, 100]",
        ),
        (
            &["phenomena", "--atol", "1e12"],
            "option `--atol` = 1e12 is out of range: allowed (0, 1]",
        ),
        (
            &["simulate", "belt", "--model", "CS", "--max-steps", "0"],
            "option `--max-steps` = 0 is out of range",
        ),
        (
            &["simulate", "belt", "--model", "CS", "--time-limit", "-1"],
            "option `--time-limit` = -1 is out of range",
        ),
    ];
    for (args, message) in cases {
        let text = rejected(args);
        assert!(text.contains(message), "{args:?}: {text}");
    }
}

#[test]
fn a_run_that_hits_its_step_cap_or_time_limit_keeps_its_result_and_exits_1() {
    let dir = tempfile::tempdir().unwrap();
    for (what, args, message) in [
        (
            "steps",
            vec!["simulate", "belt", "--model", "CS", "--max-steps", "50"],
            "too many steps: 50 steps taken",
        ),
        (
            "time",
            vec![
                "simulate",
                "chain",
                "--model",
                "static",
                "--set",
                "n_bodies=2000",
                "--time-limit",
                "0.05",
            ],
            "time limit: 0.05 s of wall time used",
        ),
        (
            "diffsol steps",
            vec![
                "simulate",
                "belt",
                "--model",
                "CS",
                "--solver",
                "tsit45",
                "--max-steps",
                "20",
            ],
            "too many steps: 20 steps taken",
        ),
    ] {
        let out = dir.path().join(what);
        let mut all = args.clone();
        all.extend(["--out", out.to_str().unwrap()]);
        let o = friction_lab(&all);
        assert_eq!(o.status.code(), Some(1), "{what}: {}", stderr(&o));
        assert!(stderr(&o).contains(message), "{what}: {}", stderr(&o));
        assert!(
            stderr(&o).contains(&format!("error: the solver failed: {message}")),
            "{what}: {}",
            stderr(&o)
        );
        // A cap reached within a few natural periods is not blamed on the periods.
        assert!(
            !stderr(&o).contains("natural period"),
            "{what}: {}",
            stderr(&o)
        );
        let summary: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
        assert_eq!(summary["status"], "failed");
        let rows = std::fs::read_to_string(out.join("trajectory.csv"))
            .unwrap()
            .lines()
            .count();
        assert!(rows > 1, "{what}: the trajectory up to the failure is kept");
    }
}

#[test]
fn the_exit_codes_are_listed_in_every_help() {
    for command in [
        vec!["--help"],
        vec!["simulate", "--help"],
        vec!["converge", "--help"],
        vec!["reproduce", "--help"],
    ] {
        let o = friction_lab(&command);
        assert!(o.status.success());
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(
            text.contains("Exit codes:")
                && text.contains("2  bad input")
                && text.contains("130  stopped by Ctrl-C"),
            "{command:?}: {text}"
        );
    }
}

#[test]
fn progress_shows_as_a_heartbeat_without_a_terminal() {
    // stderr is a pipe here, as under nohup or CI; a heartbeat period of 0 s prints every update.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c");
    let o = Command::new(env!("CARGO_BIN_EXE_friction-lab"))
        .args(["converge", "belt", "--model", "CS", "--t-end", "1"])
        .args(["--out", out.to_str().unwrap()])
        .env("FRICTION_LAB_HEARTBEAT_S", "0")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stderr(&o);
    assert!(text.contains("converge: 1 runs done, 11 left, "), "{text}");
    assert!(text.contains("converge: 12 runs done, 0 left, "), "{text}");
    assert!(text.lines().all(|l| l.ends_with(" s elapsed")), "{text}");
}

#[test]
fn a_study_bounds_each_run_and_draws_the_failed_ones() {
    // Every run capped at 100 steps: the fine RK4 runs fail, and the plot names them.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c");
    let o = friction_lab(&[
        "converge",
        "belt",
        "--model",
        "CS",
        "--solvers",
        "rk4",
        "--t-end",
        "1",
        "--max-steps",
        "100",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("converge.csv")).unwrap();
    let failed = csv
        .lines()
        .filter(|l| l.contains("too many steps: 100"))
        .count();
    // h = 0.02 takes 50 steps; 0.01, 0.005 and 0.0025 take more than 100.
    assert_eq!(failed, 3, "{csv}");
    // A failed run stopped early: it has no error against the reference (every `error_`
    // column is empty), while the run that finished has the nine that exist for it: the two
    // relative errors, x and v absolute and relative, the energy residual absolute and
    // relative, and the event times (no internal state, and no completed stick phase: those
    // errors are undefined).
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let error_columns: Vec<usize> = (0..header.len())
        .filter(|&i| header[i].starts_with("error_"))
        .collect();
    assert_eq!(error_columns.len(), 12, "{header:?}");
    for line in csv.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        let measured = error_columns
            .iter()
            .filter(|&&i| !cells[i].is_empty())
            .count();
        let expected = if line.contains("too many steps") {
            0
        } else {
            9
        };
        assert_eq!(measured, expected, "{line}");
    }
    let svg = std::fs::read_to_string(out.join("converge.svg")).unwrap();
    assert!(
        svg.contains("failed run (drawn at the top)"),
        "the failed runs' crosses are named"
    );
    // A step cap is not a divergence: no word of stability.
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("3 of 4 runs failed"), "{text}");
    assert!(!text.contains("diverged"), "{text}");
}

#[test]
fn time_stepping_runs_rigs_and_chains_and_refuses_what_it_cannot_do() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("belt");
    let o = friction_lab(&[
        "simulate",
        "belt",
        "--model",
        "static",
        "--scheme",
        "time-stepping",
        "--theta",
        "1",
        "--dt",
        "1e-3",
        "--t-end",
        "5",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["solver"], "moreau-jean");
    assert_eq!(summary["scheme"], "time-stepping");
    assert_eq!(summary["switching"], "timestepping");
    assert_eq!(summary["parameters"]["theta"], 1.0);
    assert_eq!(summary["stats"]["steps"], 5000);
    // Stuck on the belt (v_belt = 0.05) the body moves with it to the last digit.
    let csv = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
    let stuck: Vec<&str> = csv.lines().filter(|l| l.contains(",stick")).collect();
    assert!(stuck.len() > 10, "{} stuck rows", stuck.len());
    for row in stuck {
        assert_eq!(row.split(',').nth(2), Some("0.05"), "{row}");
    }
    // A time-stepped run into `dir/name` that must succeed: its summary.json.
    let time_stepped = |name: &str, args: &[&str]| -> serde_json::Value {
        let out = dir.path().join(name);
        let mut all = vec!["simulate"];
        all.extend_from_slice(args);
        all.extend(["--scheme", "time-stepping", "--out", out.to_str().unwrap()]);
        let o = friction_lab(&all);
        assert!(o.status.success(), "{}", stderr(&o));
        let summary: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
        assert_eq!(summary["solver"], "moreau-jean");
        summary
    };
    let summary = time_stepped(
        "chain",
        &[
            "chain",
            "--model",
            "static",
            "--set",
            "n_bodies=20",
            "--t-end",
            "20",
        ],
    );
    assert!(summary["energy"]["relative_residual"].as_f64().unwrap() < 1e-10);
    assert!(summary["event_counts"]["slip+"].as_u64().unwrap() >= 20);
    let e = rejected(&[
        "simulate",
        "prescribed-motion",
        "--model",
        "CS",
        "--scheme",
        "time-stepping",
    ]);
    assert!(e.contains("no body to time-step"), "{e}");
    // GMS, four slip blocks each with its state, time-stepped (refused before 2026-11-25):
    // the discrete energy balance holds at θ = 1/2.
    let summary = time_stepped("gms", &["belt", "--model", "gms"]);
    assert!(summary["energy"]["relative_residual"].as_f64().unwrap() < 1e-12);
    // CS with F_s = 5 N below its sliding force at rest, F_c + C1 = 7.5 N: a holding force
    // between them has no solution; refused before any step (it failed at t = 0.006 s).
    let e = rejected(&[
        "simulate",
        "belt",
        "--model",
        "CS",
        "--set",
        "F_s=5",
        "--scheme",
        "time-stepping",
    ]);
    assert!(
        e.contains(
            "its sliding force at v_rel = 0+, 7.5 N, lies outside its stick interval [-5, 5] N"
        ),
        "{e}"
    );
    assert!(e.contains("F_s >= 7.5"), "{e}");
    let e = rejected(&[
        "simulate",
        "belt",
        "--model",
        "CS",
        "--scheme",
        "time-stepping",
        "--theta",
        "0.4",
    ]);
    assert!(
        e.contains("option `--theta` = 0.4 is out of range: allowed [0.5, 1]"),
        "{e}"
    );
}

#[test]
fn sweep_runs_a_grid_in_parallel_measures_the_settled_cycle_and_rejects_bad_axes() {
    let dir = tempfile::tempdir().unwrap();
    let sweep = |threads: &str, name: &str| {
        let out = dir.path().join(name);
        let o = friction_lab(&[
            "sweep",
            "belt",
            "--model",
            "static",
            "--grid",
            "v_belt=0.05,1",
            "--grid",
            "k=log:50:200:3",
            "--t-end",
            "40",
            "--threads",
            threads,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read_to_string(out.join("sweep.csv")).unwrap()
    };
    let csv = sweep("1", "one");
    assert_eq!(csv, sweep("2", "two"), "rows depend on the thread count");
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(
        rows[0][..4],
        ["v_belt", "k", "stick_phases", "stick_per_cycle"]
    );
    assert_eq!(
        rows.len(),
        1 + 2 * 3,
        "the product of the axes, the first slowest"
    );
    assert_eq!((rows[1][0], rows[1][1], rows[3][1]), ("0.05", "50", "200"));
    let col = |name: &str| rows[0].iter().position(|c| *c == name).unwrap();
    // v_belt = 0.05, k = 100: the closed-form cycle of stick (2(F_s − F_c)/(k·v_b)) and slip
    // ((π − 2φ)/ω, tan φ = −v_b·k/(ω·(F_s − F_c))), one stick phase per cycle.
    let (f_s, f_c, k, v_b) = (7.5, 6.0, 100.0, 0.05);
    let omega: f64 = f64::sqrt(k);
    let phi = -(v_b / (omega * (f_s - f_c) / k)).atan();
    let period = 2.0 * (f_s - f_c) / (k * v_b) + (std::f64::consts::PI - 2.0 * phi) / omega;
    let measured: f64 = rows[2][col("period")].parse().unwrap();
    assert!((measured - period).abs() < 1e-3, "{measured} vs {period}");
    let per_cycle: f64 = rows[2][col("stick_per_cycle")].parse().unwrap();
    assert!((per_cycle - 1.0).abs() < 0.05, "{per_cycle}");
    // v_belt = 1 > F_c/√(k·m) at every k: steady sliding after the start, no stick phase.
    for row in &rows[4..] {
        assert_eq!(row[col("stick_phases")], "0", "{row:?}");
    }
    for (grid, message) in [
        ("v_belt=abc", "`abc` is not a finite number"),
        (
            "v_belt=0:1:0",
            "COUNT `0` is out of range: allowed [1, 1000]",
        ),
        ("k=log:0:10:3", "a log range needs START > 0"),
        ("k=-5,10", "parameter `k` = -5 is out of range"),
        ("nonsense=1", "nonsense"),
    ] {
        let e = rejected(&["sweep", "belt", "--model", "static", "--grid", grid]);
        assert!(e.contains(message), "{grid}: {e}");
    }
    // Axes that would run the same point twice or make every point the same run.
    for (grids, message) in [
        (
            &["v_belt=0.1", "v_belt=0.2"][..],
            "parameter `v_belt` has two axes; give all its values in one",
        ),
        (
            &["sigma0=1e4,1e5"][..],
            "parameter `sigma0` is not read by model `static` (it reads: F_c, F_s): every \
             value would give the same run",
        ),
        (
            &["epsilon=1e-3,1e-2"][..],
            "parameter `epsilon` is read only under --switching regularized, not event",
        ),
    ] {
        let mut args = vec!["sweep", "belt", "--model", "static"];
        for g in grids {
            args.extend(["--grid", g]);
        }
        let e = rejected(&args);
        assert!(e.contains(message), "{grids:?}: {e}");
    }
    // A point's value is applied after the --set's: the set value would be swept over silently.
    let e = rejected(&[
        "sweep", "belt", "--model", "CS", "--set", "F_s=7", "--grid", "F_s=8,9",
    ]);
    assert!(
        e.contains(
            "option `--grid`: parameter `F_s` is also given by --set F_s=7: every point would \
             override it; give its values in the axis only"
        ),
        "{e}"
    );
}

#[test]
fn the_parts_of_a_sweep_by_point_range_are_its_rows_in_order() {
    // Spread over machines or Dask tasks: parts 0:2, 2:5 and 5:6 of a 6-point grid give the
    // whole sweep's rows, bit for bit; a range outside the grid is refused with its bounds.
    let dir = tempfile::tempdir().unwrap();
    let sweep = |name: &str, range: Option<&str>| {
        let out = dir.path().join(name);
        let mut args = vec!["sweep", "belt", "--model", "CS", "--t-end", "10"];
        args.extend(["--grid", "v_belt=0.1,0.2,0.3", "--grid", "k=50,100"]);
        if let Some(range) = range {
            args.extend(["--point-range", range]);
        }
        args.extend(["--out", out.to_str().unwrap()]);
        let o = friction_lab(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
        (csv, String::from_utf8_lossy(&o.stdout).into_owned())
    };
    let (whole, said) = sweep("whole", None);
    assert!(said.contains("6 points, 0 failed"), "{said}");
    let mut lines = whole.lines();
    let header = lines.next().unwrap();
    let mut parts = Vec::new();
    for (name, range, note) in [
        ("a", "0:2", "2 points, 0 failed"),
        ("b", "2:5", "3 points, 0 failed"),
        ("c", "5:6", "1 point, 0 failed"),
    ] {
        let (csv, said) = sweep(name, Some(range));
        assert!(said.contains(note), "{range}: {said}");
        let mut rows = csv.lines();
        assert_eq!(rows.next(), Some(header));
        parts.extend(rows.map(str::to_string));
    }
    assert_eq!(parts, lines.collect::<Vec<_>>());
    let e = rejected(&[
        "sweep",
        "belt",
        "--model",
        "CS",
        "--grid",
        "v_belt=0.1,0.2",
        "--point-range",
        "1:3",
    ]);
    assert!(
        e.contains("allowed START:END with 0 <= START <= END <= 2 (the grid's points)"),
        "{e}"
    );
}

#[test]
fn phenomena_keeps_the_decided_cells_when_a_protocol_run_fails() {
    // Ten steps are too few for any protocol run: every cell fails in the solver, and the
    // table still says so, cell by cell (before: exit 2, as for bad input, and no file).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = friction_lab(&[
        "phenomena",
        "--model",
        "coulomb",
        "--max-steps",
        "10",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("8 cells of Table 2 are undecided"), "{e}");
    assert!(e.contains("10 steps"), "{e}");
    let table: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("table2.json")).unwrap()).unwrap();
    let mut cells = table["models"]["coulomb"].as_object().unwrap().clone();
    // The simulation cost's runs hit the bound too: no run reached the accuracy.
    let cost = cells.remove("simulation_cost").unwrap();
    for system in ["belt", "two_mass"] {
        assert!(cost[system]["cheapest"].is_null(), "{cost}");
        assert!(cost[system]["failed"].as_str().is_some(), "{cost}");
    }
    assert_eq!(cells.len(), 8);
    for (name, cell) in &cells {
        assert!(cell["measured"].is_null(), "{name}: {cell}");
        assert!(
            cell["failed"].as_str().unwrap().contains("coulomb"),
            "{name}: {cell}"
        );
    }
    let md = std::fs::read_to_string(out.join("table2.md")).unwrap();
    assert!(md.contains("| Stiction | failed |"), "{md}");
    assert!(md.contains("8 cells are undecided"), "{md}");
    // The limits are checked as every command's are.
    let e = rejected(&["phenomena", "--time-limit", "-1"]);
    assert!(e.contains("time-limit") && e.contains("-1"), "{e}");
    let e = rejected(&["phenomena", "--max-steps", "0"]);
    assert!(e.contains("max-steps"), "{e}");
}

#[test]
fn phenomena_judges_the_chosen_models_at_the_given_parameters() {
    let dir = tempfile::tempdir().unwrap();
    let judge = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let mut args = vec!["phenomena", "--model", "viscous", "--model", "coulomb"];
        args.extend(extra);
        args.extend(["--out", out.to_str().unwrap()]);
        let o = friction_lab(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let table: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("table2.json")).unwrap()).unwrap();
        let md = std::fs::read_to_string(out.join("table2.md")).unwrap();
        (table["models"].clone(), md)
    };
    let (own, md) = judge("own", &[]);
    let models: Vec<&String> = own.as_object().unwrap().keys().collect();
    assert_eq!(
        models,
        ["viscous", "coulomb"],
        "the models in the order given"
    );
    assert_eq!(own["viscous"]["viscous"]["measured"], true);
    assert!(md
        .contains("parameter set `paper` (`lugre-1995` for lugre, lugre-vd, elasto-plastic, gms)"));
    // Without its viscous coefficient the viscous model shows no viscous friction.
    let (set, md) = judge("set", &["--set", "mu_v=0"]);
    assert_eq!(set["viscous"]["viscous"]["measured"], false);
    assert!(
        md.contains("parameter set `paper`, `mu_v=0` for every model"),
        "{md}"
    );
    let e = rejected(&["phenomena", "--model", "viscous", "--set", "mu_v=-1"]);
    assert!(e.contains("mu_v"), "{e}");
    // Without a static level (F_s = 0) the force ramps rise to F_c: Coulomb's law breaks away
    // at F_c = 6 N at every rate, so no rising static friction. (The ramps rose to F_s, at
    // rate 0, and the command was refused for a parameter `rate` it was never given.)
    let (bare, _) = judge("bare", &["--set", "F_s=0"]);
    let rising = &bare["coulomb"]["rising_static_friction"];
    assert_eq!(rising["measured"], false, "{rising}");
    for key in ["breakaway_1000tau_N", "breakaway_10tau_N"] {
        let f = rising["evidence"][key].as_f64().unwrap();
        assert!((f - 6.0).abs() < 1e-6, "{key} = {f}");
    }
    // A --set read by neither the protocols nor a judged model is accepted, and said; F_s,
    // which neither model reads either, scales the ramps, and is not.
    let out = dir.path().join("unread");
    let mut args = vec!["phenomena", "--model", "viscous", "--model", "coulomb"];
    args.extend([
        "--set",
        "sigma0=1e4",
        "--set",
        "F_s=8",
        "--set",
        "epsilon=0.1",
    ]);
    args.extend(["--out", out.to_str().unwrap()]);
    let o = friction_lab(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains(
            "note: option `--set`: parameter `sigma0` is read by none of the judged models: every \
             value would give the same table"
        ),
        "{e}"
    );
    assert!(
        e.contains("parameter `epsilon` is not read by the protocols, which switch at v = 0"),
        "{e}"
    );
    assert!(!e.contains("`F_s`"), "{e}");
}

/// A study of a rig reads `--variant`: SD as printed (+F_s whatever the direction) is
/// another law than its sign-consistent reading, and the study says which it ran.
#[test]
fn a_study_runs_the_reading_that_variant_names() {
    let dir = tempfile::tempdir().unwrap();
    let study = |variant: &str| {
        let out = dir.path().join(variant);
        let o = friction_lab(&[
            "converge",
            "belt",
            "--model",
            "SD",
            "--variant",
            variant,
            "--t-end",
            "3",
            "--solvers",
            "rk4",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("converge.json")).unwrap()).unwrap();
        let csv = std::fs::read_to_string(out.join("converge.csv")).unwrap();
        (
            json["case"]["description"].as_str().unwrap().to_string(),
            csv,
        )
    };
    let (odd, odd_runs) = study("odd");
    let (printed, printed_runs) = study("printed");
    assert_eq!(odd, "belt with SD (event switching)");
    assert_eq!(printed, "belt with SD (as printed) (event switching)");
    assert_ne!(odd_runs, printed_runs);
}

#[test]
fn converge_and_work_precision_name_the_runs_that_failed() {
    // LuGre's bristles are stiff: Dormand-Prince with fixed steps of 0.02 to 0.0025 s is
    // unstable at every one, and no order line has anything to fit. The study writes its files
    // and says so, with the first failure; with nothing measured it exits 1 (a study with one
    // run measured exits 0, as work-precision below).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c");
    let o = friction_lab(&[
        "converge",
        "belt",
        "--model",
        "lugre",
        "--solvers",
        "dopri5",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("error: converge: every run failed (4 of 4), nothing was measured"),
        "{}",
        stderr(&o)
    );
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains(
            "dopri5          4 of 4 runs failed (status in converge.csv); the first, at h = \
             0.02: non-finite state at t = 0.02"
        ),
        "{text}"
    );
    let csv = std::fs::read_to_string(out.join("converge.csv")).unwrap();
    assert_eq!(csv.matches("non-finite state").count(), 4, "{csv}");
    // Why, once: the fixed steps are past the explicit method's stability limit.
    let why = "an explicit method diverged with a fixed step: it is unstable once h times the \
               problem's fastest rate";
    assert_eq!(text.matches(why).count(), 1, "{text}");
    assert!(text.contains("a smaller step in --dt-list"), "{text}");
    // work-precision says it the same way: RK4 at its two coarsest steps.
    let out = dir.path().join("w");
    let o = friction_lab(&[
        "work-precision",
        "belt",
        "--model",
        "lugre",
        "--solvers",
        "rk4",
        "--repeats",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains(
            "rk4             2 of 6 runs failed (status in work-precision.csv); the first, at \
             h = 0.01: non-finite state"
        ),
        "{text}"
    );
    assert!(text.contains(why), "{text}");
}

#[test]
fn a_study_of_the_chain_spans_its_horizon_of_predictability_by_default() {
    // simulate runs the chain over 50 s; a study over 10 s (docs/studies.md: over 50 s the
    // chaotic chain's fixed-step errors saturate and their fitted orders are noise).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c");
    let o = friction_lab(&[
        "converge",
        "chain",
        "--model",
        "CS",
        "--solvers",
        "rk4",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("converge.json")).unwrap()).unwrap();
    assert_eq!(json["case"]["t_end"], 10.0);
    // Within it, RK4's fourth order shows on the grid error of the default chain.
    let rk4 = json["orders"]
        .as_array()
        .unwrap()
        .iter()
        .find(|o| o["solver"] == "rk4" && o["measure"] == "grid_relative")
        .unwrap();
    let order = rk4["order"].as_f64().unwrap();
    assert!((order - 4.0).abs() < 0.3, "{rk4}");
    let ci: Vec<f64> = (rk4["order_ci"].as_array().unwrap().iter())
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(ci[0] <= order && order <= ci[1], "{rk4}");
    assert!(rk4["pairs_used"].as_u64().unwrap() >= 2, "{rk4}");
}

#[test]
fn studies_of_a_chain_draw_regularised_bdf_and_time_stepping_beside_the_solvers() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("k");
    let o = friction_lab(&[
        "stiffness",
        "chain",
        "--model",
        "coulomb",
        "--set",
        "n_bodies=3",
        "--t-end",
        "10",
        "--values",
        "1e-2,1e-3",
        "--solvers",
        "dopri5",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("stiffness.csv")).unwrap();
    // At each width: the studied solver and the two peers.
    assert_eq!(csv.lines().count(), 1 + 2 * 3, "{csv}");
    for label in [
        ",dopri5,",
        ",bdf (regularized),",
        ",moreau-jean (timestepping),true,",
    ] {
        assert_eq!(csv.matches(label).count(), 2, "{label}: {csv}");
    }
}

#[test]
fn stiffness_of_a_rig_over_epsilon_is_regularized_unless_told_otherwise() {
    // The regularisation width changes nothing under event switching; without --switching
    // the study of a rig over epsilon is regularized, so Dormand–Prince's cost grows as
    // epsilon shrinks. With --switching event every value would give the same runs (they
    // did, and the verdict was vacuous): refused.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s");
    let o = friction_lab(&[
        "stiffness",
        "belt",
        "--model",
        "CS",
        "--values",
        "1e-1,1e-4",
        "--solvers",
        "dopri5",
        "--t-end",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("stiffness.csv")).unwrap();
    let mut rows = csv.lines();
    let header: Vec<&str> = rows.next().unwrap().split(',').collect();
    let column = header.iter().position(|&h| h == "rhs_evals").unwrap();
    let evals: Vec<f64> = rows
        .map(|r| r.split(',').nth(column).unwrap().parse().unwrap())
        .collect();
    assert!(evals[1] > 5.0 * evals[0], "{evals:?}");
    // At epsilon = 1e-4 Dormand–Prince's stiffness test fires: the reference there is BDF's
    // tight run, cross-checked by the explicit pair (Tsit45, as Dormand–Prince is studied).
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("stiffness.json")).unwrap())
            .unwrap();
    let reference = |i: usize| &json["points"][i]["reference"]["Run"];
    assert_eq!(reference(0)["solver"], "tsit45", "{}", reference(0));
    assert!(reference(0)["stiffness_detected_at"].is_null());
    assert_eq!(reference(1)["solver"], "bdf", "{}", reference(1));
    assert_eq!(reference(1)["cross_check"][0], "tsit45");
    assert!(reference(1)["stiffness_detected_at"].as_f64().unwrap() < 2.0);
    let e = rejected(&["stiffness", "belt", "--model", "CS", "--switching", "event"]);
    assert!(
        e.contains("option `--parameter`: parameter `epsilon` is read only under --switching regularized, not event"),
        "{e}"
    );
}

#[test]
fn an_independence_study_judges_the_levels_that_finished_and_exits_1() {
    // RK4 at h = 0.5 on the belt (ω = 10 rad/s, h·ω = 5, beyond RK4's stability bound 2.79)
    // overflows; the finer levels are stable.
    let dir = tempfile::tempdir().unwrap();
    let study = |name: &str, levels: &str| {
        let out = dir.path().join(name);
        let o = friction_lab(&[
            "independence",
            "belt",
            "--model",
            "CS",
            "--solver",
            "rk4",
            "--start",
            "0.5",
            "--levels",
            levels,
            "--t-end",
            "200",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        let said = String::from_utf8_lossy(&o.stdout).into_owned();
        (out, said + &stderr(&o))
    };
    // Four levels: 1 to 3 are judged.
    let (out, text) = study("i", "4");
    assert!(
        text.contains("1 of 4 levels of the independence study failed, the first at level 0 (5e-1): non-finite state")
            && text.contains("levels 1 to 3 are judged"),
        "{text}"
    );
    assert!(
        text.contains("an explicit method diverged with a fixed step")
            && text.contains("a smaller --start"),
        "{text}"
    );
    let csv = std::fs::read_to_string(out.join("independence.csv")).unwrap();
    let levels: Vec<&str> = csv
        .lines()
        .filter(|l| l.starts_with("final x"))
        .map(|l| l.split(',').nth(1).unwrap())
        .collect();
    assert_eq!(levels, ["1", "2", "3"], "{csv}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("independence.json")).unwrap())
            .unwrap();
    assert_eq!(json["failed"][0]["level"], 0, "{json}");
    assert_eq!(json["first_level"], 1, "{json}");
    assert_eq!(json["independent"], false, "{json}");
    // Two levels: one finished, nothing to compare, no files.
    let (out, text) = study("j", "2");
    assert!(
        text.contains("leaving fewer than two levels in a row to compare"),
        "{text}"
    );
    assert!(!out.exists());
}

#[test]
fn a_fixed_step_above_a_tenth_of_the_natural_period_gets_a_note() {
    // The belt: m = 1 kg, k = 100 N/m, period 2π/10 = 0.628 s. Time-stepping at h = 0.1 s
    // resolves it with six steps a period; at the default 1e-3 s with 628.
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let mut args = vec!["simulate", "belt", "--model", "CS", "--t-end", "2"];
        args.extend(extra);
        args.extend(["--out", out.to_str().unwrap()]);
        let o = friction_lab(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        stderr(&o)
    };
    let note = "the fixed step h = 0.1 s is more than a tenth of the shortest natural period, \
                0.628 s: each oscillation is resolved by fewer than ten steps";
    for extra in [
        &["--scheme", "time-stepping", "--dt", "0.1"][..],
        &["--solver", "rk4", "--dt", "0.1"][..],
    ] {
        assert!(run("coarse", extra).contains(note), "{extra:?}");
    }
    assert!(!run("fine", &["--scheme", "time-stepping"]).contains("natural period"));
}

#[test]
fn an_explicit_fixed_step_that_diverges_gets_a_note() {
    // LuGre's bristles (σ0 = 1e5 N/m on 1 kg) decay at a rate of order σ0·|v|/F_c: RK4 at
    // the default 1e-3 s is far beyond its stability limit and the state overflows within
    // ten steps; at 1e-5 s it is stable.
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let mut args = vec!["simulate", "free-vibration", "--model", "lugre"];
        args.extend(["--switching", "naive", "--t-end", "0.05"]);
        args.extend(extra);
        args.extend(["--out", out.to_str().unwrap()]);
        friction_lab(&args)
    };
    let note = "the explicit method diverged with the fixed step h = 0.001 s";
    for solver in [&["--solver", "rk4"][..], &["--fixed-step"][..]] {
        let o = run("coarse", solver);
        assert_eq!(o.status.code(), Some(1), "{solver:?}: {}", stderr(&o));
        assert!(stderr(&o).contains("non-finite state"), "{}", stderr(&o));
        assert!(stderr(&o).contains(note), "{solver:?}: {}", stderr(&o));
    }
    let o = run("fine", &["--solver", "rk4", "--dt", "1e-5"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("diverged"), "{}", stderr(&o));
}

#[test]
fn a_set_parameter_the_model_does_not_read_gets_a_note() {
    // CS reads F_c, F_s, C1, C2 and v_s: `sigma0` changes nothing, and `epsilon` only under
    // regularized switching. Accepted (one set may serve many models), but said.
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, args: &[&str]| {
        let out = dir.path().join(name);
        let mut all = vec!["simulate"];
        all.extend(args);
        all.extend(["--t-end", "1", "--out", out.to_str().unwrap()]);
        let o = friction_lab(&all);
        assert!(o.status.success(), "{}", stderr(&o));
        stderr(&o)
    };
    let e = run(
        "rig",
        &[
            "paper-block",
            "--model",
            "CS",
            "--set",
            "sigma0=5",
            "--set",
            "F_s=8",
        ],
    );
    assert!(
        e.contains(
            "note: option `--set`: parameter `sigma0` is not read by model `CS` (it reads: F_c, \
             F_s, C1, C2, v_s)"
        ),
        "{e}"
    );
    assert!(!e.contains("`F_s`"), "{e}");
    let e = run(
        "epsilon",
        &["belt", "--model", "CS", "--set", "epsilon=1e-3"],
    );
    assert!(
        e.contains("`epsilon` is read only under --switching regularized"),
        "{e}"
    );
    let e = run(
        "regularized",
        &[
            "belt",
            "--model",
            "CS",
            "--set",
            "epsilon=1e-3",
            "--switching",
            "regularized",
        ],
    );
    assert!(!e.contains("not read") && !e.contains("read only"), "{e}");
    // The chain: every contact has the one model.
    let e = run(
        "chain",
        &[
            "chain",
            "--model",
            "coulomb",
            "--set",
            "n_bodies=3",
            "--set",
            "C1=2",
        ],
    );
    assert!(
        e.contains("parameter `C1` is not read by model `coulomb`"),
        "{e}"
    );
    assert!(!e.contains("n_bodies"), "{e}");
    // The studies and sweep say it too; a chain's study under event switching runs its
    // regularised peer, which reads epsilon.
    let other = |name: &str, args: &[&str]| {
        let out = dir.path().join(name);
        let mut all = args.to_vec();
        all.extend(["--out", out.to_str().unwrap()]);
        let o = friction_lab(&all);
        assert!(o.status.success(), "{}", stderr(&o));
        stderr(&o)
    };
    let study = [
        "converge",
        "belt",
        "--model",
        "CS",
        "--solvers",
        "rk4",
        "--t-end",
        "1",
    ];
    let e = other("converge", &[&study[..], &["--set", "sigma0=5"]].concat());
    assert!(
        e.contains("parameter `sigma0` is not read by model `CS`"),
        "{e}"
    );
    let sweep = [
        "sweep",
        "belt",
        "--model",
        "CS",
        "--grid",
        "v_belt=0.1,0.2",
        "--t-end",
        "1",
    ];
    let e = other("sweep", &[&sweep[..], &["--set", "mu_v=1"]].concat());
    assert!(
        e.contains("parameter `mu_v` is not read by model `CS`"),
        "{e}"
    );
    let e = other(
        "peers",
        &[
            "work-precision",
            "chain",
            "--model",
            "CS",
            "--set",
            "n_bodies=2",
            "--set",
            "epsilon=1e-3",
            "--solvers",
            "bdf",
            "--t-end",
            "1",
        ],
    );
    assert!(!e.contains("epsilon"), "{e}");
}

#[test]
fn the_chain_takes_its_parameters_from_a_file_and_names_them_when_one_is_unknown() {
    // A parameter file sets the chain's own parameters as a rig's file sets the rig's (it was
    // refused: "unknown parameter `n_bodies`", with the chain's names missing from the list).
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("chain.toml");
    std::fs::write(&file, "n_bodies = 3\nF_c = 5\n").unwrap();
    let out = dir.path().join("out");
    let o = friction_lab(&[
        "simulate",
        "chain",
        "--model",
        "coulomb",
        "--params",
        file.to_str().unwrap(),
        "--t-end",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["n_bodies"], 3, "{summary}");
    assert_eq!(summary["parameters"]["F_c"], 5.0, "{summary}");
    let e = rejected(&["simulate", "chain", "--model", "coulomb", "--set", "c=1"]);
    assert!(
        e.contains("unknown parameter `c`")
            && e.contains("n_bodies, m, k_chain, k_driver, v_driver, spread"),
        "{e}"
    );
}

#[test]
fn reproduce_keeps_everything_when_the_experiment_fails_for_some_models() {
    // σ = 1e300 N/m: the Dahl models DV, SD and SV fail at the experiment's first step. The
    // report is still written whole, the experiment's table says which failed and why, and
    // the command exits 1 (it exited 1 having written nothing); the other parts run.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = friction_lab(&[
        "reproduce",
        "--set",
        "sigma=1e300",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("the paper's experiment failed for DV, SD, SV"),
        "{e}"
    );
    let md = std::fs::read_to_string(out.join("paper-experiment.md")).unwrap();
    assert!(
        md.contains("| DV | failed: the run over [0, 5] s: step size underflow at t = 0"),
        "{md}"
    );
    assert!(md.contains("| CS | a = 9 m/s^2 |"), "{md}");
    for file in ["report.md", "table2.md", "reproduction.md", "studies"] {
        assert!(out.join(file).exists(), "{file} is missing");
    }
    // The report's section on the experiment says it did not complete, and why.
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        report.contains(
            "## The paper's experiment (section 3)\n\nNot completed: the paper's experiment \
             failed for DV, SD, SV (paper-experiment.md keeps the other models"
        ),
        "{report}"
    );
    assert!(
        report.contains("## Table 2, decided by simulation\n\n[table2.md]"),
        "{report}"
    );
}

#[test]
fn sweep_runs_a_system_file_over_the_regularisation_width() {
    // A system file's contacts carry their own parameters, so epsilon is the one axis it
    // takes (it was refused whole: "a system file has no parameters to sweep"). Each row is
    // the run `simulate --system` makes at that epsilon, step for step.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("two.toml");
    std::fs::write(&file, TWO_BODIES).unwrap();
    let path = file.to_str().unwrap();
    let common = ["--system", path, "--switching", "regularized"];
    let out = dir.path().join("sweep");
    let mut args = vec!["sweep", "--grid", "epsilon=1e-3,1e-2", "--t-end", "5"];
    args.extend(common);
    args.extend(["--out", out.to_str().unwrap()]);
    let o = friction_lab(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("sweep.json")).unwrap()).unwrap();
    assert_eq!(json["target"], path);
    let steps: Vec<u64> = json["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["stats"]["steps"].as_u64().unwrap())
        .collect();
    assert_eq!(steps.len(), 2);
    assert!(
        steps[0] > steps[1],
        "a narrower width takes more steps: {steps:?}"
    );
    // The same run as `simulate` gives, over the span the point needed to settle (a point
    // that has not settled in its span is run again over twice the span).
    let span = json["points"][0]["settled"]["to"].as_f64().unwrap();
    let span = span.to_string();
    let single = dir.path().join("single");
    let mut args = vec!["simulate", "--set", "epsilon=1e-3"];
    args.extend(common);
    args.extend(["--t-end", &span, "--out", single.to_str().unwrap()]);
    let o = friction_lab(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(single.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["stats"]["steps"].as_u64(), Some(steps[0]));
    let e = rejected(&["sweep", "--system", path, "--grid", "F_s=1,2"]);
    assert!(
        e.contains("parameter `F_s` cannot be swept on a system file"),
        "{e}"
    );
    // What a system file does not read is refused, never ignored: its contacts carry their
    // own parameters, and of the friction parameters only epsilon applies.
    let params = dir.path().join("p.toml");
    std::fs::write(&params, "epsilon = 1e-3\nF_s = 1\n").unwrap();
    let p = params.to_str().unwrap();
    for (args, message) in [
        (
            vec!["simulate", "--system", path, "--set", "F_s=1"],
            "option `--set`: parameter `F_s` does not apply to --system",
        ),
        (
            vec!["converge", "--system", path, "--set", "mu_v=1"],
            "option `--set`: parameter `mu_v` does not apply to --system",
        ),
        (
            vec!["simulate", "--system", path, "--param-set", "lugre-1995"],
            "option `--param-set` does not apply to --system",
        ),
        (
            vec!["simulate", "--system", path, "--params", p],
            "parameter `F_s` does not apply to --system",
        ),
        (
            vec![
                "sweep",
                "--system",
                path,
                "--switching",
                "regularized",
                "--set",
                "F_c=1",
                "--grid",
                "epsilon=1e-3",
            ],
            "option `--set`: parameter `F_c` does not apply to --system",
        ),
        (
            vec!["simulate", "--system", path, "--variant", "printed"],
            "option `--variant` does not apply to --system",
        ),
    ] {
        let e = rejected(&args);
        assert!(e.contains(message), "{args:?}: {e}");
    }
}

/// Runs friction-lab with `args` and a heartbeat every 0.2 s, sends it SIGINT once it has
/// printed its first heartbeat (the signal handler is set before any run starts), and returns
/// that line, what it printed on stderr after it, and its exit code.
fn interrupted_at_first_heartbeat(args: &[&str]) -> (String, String, Option<i32>) {
    interrupted_at_heartbeat(args, "")
}

/// As [`interrupted_at_first_heartbeat`], at the first heartbeat that does not start with
/// `skipped` (a study's name and colon; "" skips none).
fn interrupted_at_heartbeat(args: &[&str], skipped: &str) -> (String, String, Option<i32>) {
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_friction-lab"))
        .args(args)
        .env("FRICTION_LAB_HEARTBEAT_S", "0.2")
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
    let first = lines
        .by_ref()
        .map(|l| l.unwrap())
        .find(|l| skipped.is_empty() || !l.starts_with(skipped))
        .unwrap();
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let rest: Vec<String> = lines.map(|l| l.unwrap()).collect();
    (first, rest.join("\n"), child.wait().unwrap().code())
}

#[test]
fn ctrl_c_stops_a_run_at_its_next_step_and_keeps_what_it_computed() {
    // Implicit Euler on a LuGre chain: over a minute at the defaults.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let (first, text, code) = interrupted_at_first_heartbeat(&[
        "simulate",
        "chain",
        "--model",
        "lugre",
        "--solver",
        "implicit-euler",
        "--out",
        out.to_str().unwrap(),
    ]);
    // The first heartbeat: the run is integrating.
    assert!(first.contains(" s elapsed"), "{first}");
    assert_eq!(code, Some(130), "{text}");
    assert!(text.contains("friction-lab: stopping"), "{text}");
    assert!(
        text.contains("error: stopped: interrupted at t = "),
        "{text}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["status"], "failed");
    let error = summary["error"].as_str().unwrap();
    assert!(error.starts_with("interrupted at t = "), "{error}");
    // The trajectory up to the stop: past t = 0, short of the end.
    let t = summary["t_reached"].as_f64().unwrap();
    assert!(
        t > 0.0 && t < summary["t_end"].as_f64().unwrap(),
        "{summary}"
    );
    let rows = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
    assert!(rows.lines().count() > 2, "{rows}");
    // With no earlier folder, the partial result is written in place, marked as such.
    let marker = std::fs::read_to_string(out.join(".friction-lab-output")).unwrap();
    assert!(marker.starts_with("status: stopped\n"), "{marker}");
    assert!(
        text.contains(&format!(
            "note: stopped by a signal: {} holds a partial result",
            out.display()
        )),
        "{text}"
    );
}

/// Every file under `dir` (hidden ones included) with its bytes, by relative path.
fn folder_bytes(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut files = BTreeMap::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(d) = pending.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                pending.push(path);
            } else {
                let bytes = std::fs::read(&path).unwrap();
                files.insert(path.strip_prefix(dir).unwrap().to_path_buf(), bytes);
            }
        }
    }
    files
}

#[test]
fn a_stopped_rerun_keeps_the_complete_folder_and_writes_its_partial_result_beside_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let o = out.to_str().unwrap();
    let chain = [
        "simulate",
        "chain",
        "--model",
        "lugre",
        "--solver",
        "implicit-euler",
    ];
    let short = friction_lab(&[&chain[..], &["--t-end", "0.01", "--out", o]].concat());
    assert!(short.status.success(), "{}", stderr(&short));
    let complete = folder_bytes(&out);
    let marker = String::from_utf8(complete[Path::new(".friction-lab-output")].clone()).unwrap();
    assert!(marker.starts_with("status: complete\n"), "{marker}");
    // The same run over its default minute, stopped twice: the second partial result
    // replaces the first beside the complete folder, which is never touched.
    let beside = dir.path().join("run.stopped");
    for _ in 0..2 {
        let (_, text, code) = interrupted_at_first_heartbeat(&[&chain[..], &["--out", o]].concat());
        assert_eq!(code, Some(130), "{text}");
        assert!(
            text.contains(&format!(
                "note: stopped by a signal: the partial result is in {}; {} keeps the \
                 complete result of an earlier run",
                beside.display(),
                out.display()
            )),
            "{text}"
        );
        assert_eq!(folder_bytes(&out), complete);
        let partial = std::fs::read_to_string(beside.join(".friction-lab-output")).unwrap();
        assert!(partial.starts_with("status: stopped\n"), "{partial}");
        let summary = std::fs::read_to_string(beside.join("summary.json")).unwrap();
        assert!(summary.contains("interrupted at t = "), "{summary}");
    }
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

#[test]
fn ctrl_c_during_reproduce_writes_what_it_computed_and_names_what_it_did_not_run() {
    // Stopped at the first heartbeat of a solver study (on an idle machine, the belt's
    // work-precision; Table 2's come before it): the figures, the experiment and Table 2 are
    // done, the chain's studies (seconds) and the stick-slip map are still to come.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let (first, text, code) =
        interrupted_at_heartbeat(&["reproduce", "--out", out.to_str().unwrap()], "Table 2: ");
    assert!(first.contains(" runs done, "), "{first}");
    assert_eq!(code, Some(130), "{text}");
    // Written whole: the figures, Table 2 and the studies; the report says what is missing.
    for file in [
        "figures/figure-4-CVS.png",
        "table2.md",
        "paper-experiment.md",
        "studies/converge-paper-block-CVS.json",
    ] {
        assert!(out.join(file).is_file(), "{file} missing");
    }
    assert!(!out.join("stick-slip").exists());
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        report.contains(
            "## Stick-slip on the belt: the map and the bifurcation diagram\n\nNot run: the \
             command was stopped by a signal before it."
        ),
        "{report}"
    );
    // The report says at its top that it is partial, and so does the marker.
    assert!(
        report.contains("\n\n**Partial result: the command was stopped by a signal (exit 130).**")
            && report.find("**Partial result").unwrap() < report.find("## Figures 2-7").unwrap(),
        "{report}"
    );
    let marker = std::fs::read_to_string(out.join(".friction-lab-output")).unwrap();
    assert!(marker.starts_with("status: stopped\n"), "{marker}");
}

#[test]
fn a_run_that_cannot_resolve_its_natural_period_is_told_why() {
    // k = 1e300 N/m on 1 kg: a period of 6.3e-150 s, 3.2e150 of them in the belt's 20 s; the
    // run ends in a step-size underflow, and the note names the period.
    let dir = tempfile::tempdir().unwrap();
    for (what, set) in [("rig", "k=1e300"), ("chain", "k_chain=1e300")] {
        let rig = if what == "rig" { "belt" } else { "chain" };
        let out = dir.path().join(what);
        let o = friction_lab(&[
            "simulate",
            rig,
            "--model",
            "CS",
            "--set",
            set,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(1), "{what}: {}", stderr(&o));
        let text = stderr(&o);
        assert!(text.contains("step size underflow"), "{what}: {text}");
        assert!(
            text.contains("of the shortest natural period 2π√(m/(k + kp)) = ")
                && text.contains("check the masses, the stiffnesses and the controllers' gains kp"),
            "{what}: {text}"
        );
    }
}

#[test]
fn the_scheme_is_chosen_apart_from_the_treatment_of_v_zero() {
    // Each refused before anything is run, naming the option and the way out: time-stepping
    // takes no ODE solver and no treatment of v = 0 but its own (a study under it has one
    // method, Moreau–Jean's), and θ is time-stepping's alone.
    let ts = ["--scheme", "time-stepping"];
    let cases: &[(&[&str], &[&str], &str)] = &[
        (
            &["simulate", "belt"],
            &["--solver", "rk4"],
            "option `--solver rk4` does not apply to --scheme time-stepping",
        ),
        (
            &["simulate", "chain"],
            &["--switching", "regularized"],
            "option `--switching regularized` applies to --scheme event-driven",
        ),
        (
            &["converge", "belt"],
            &["--solvers", "rk4,dopri5"],
            "option `--solvers rk4,dopri5` does not apply to --scheme time-stepping",
        ),
        (
            &["independence", "belt"],
            &["--solver", "rk4"],
            "option `--solver rk4` does not apply to --scheme time-stepping",
        ),
    ];
    for (command, option, message) in cases {
        let args: Vec<&str> = [*command, &["--model", "CS"], &ts, *option].concat();
        let e = rejected(&args);
        assert!(e.contains(message), "{args:?}: {e}");
    }
    for (args, message) in [
        (
            ["simulate", "belt", "--model", "CS", "--theta", "0.7"],
            "option `--theta 0.7` applies to --scheme time-stepping",
        ),
        (
            ["simulate", "belt", "--model", "CS", "--scheme", "moreau"],
            "unknown scheme `moreau`; known: event-driven, time-stepping",
        ),
    ] {
        let e = rejected(&args);
        assert!(e.contains(message), "{args:?}: {e}");
    }
    // The former spelling `--switching timestepping` still runs the same scheme, bit for
    // bit, and says how it is spelt now.
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, spelling: [&str; 2]| {
        let out = dir.path().join(name);
        let o = friction_lab(&[
            "simulate",
            "belt",
            "--model",
            "CS",
            "--t-end",
            "2",
            spelling[0],
            spelling[1],
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        (
            std::fs::read(out.join("trajectory.csv")).unwrap(),
            stderr(&o),
        )
    };
    let (new, quiet) = run("new", ["--scheme", "time-stepping"]);
    let (old, note) = run("old", ["--switching", "timestepping"]);
    assert_eq!(new, old);
    assert!(!quiet.contains("now spelt"), "{quiet}");
    assert!(
        note.contains("`--switching timestepping` is now spelt `--scheme time-stepping`"),
        "{note}"
    );
}

/// `--out` is checked before any work: each folder that cannot be written as a whole is
/// refused with exit 2 at once, naming it and why. `reproduce` computes for 13 s or more
/// before writing, so a check after the work would not end within the bound below.
#[test]
fn an_output_folder_that_cannot_be_written_is_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let at = |name: &str| dir.path().join(name);
    std::fs::write(at("afile"), "").unwrap();
    std::fs::create_dir(at("foreign")).unwrap();
    std::fs::write(at("foreign").join("x"), "").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(at("foreign"), at("link")).unwrap();
    let long = at(&"a".repeat(300));
    let cases: Vec<(std::path::PathBuf, &str)> = vec![
        (at("afile"), "it exists and is not a folder"),
        ("/dev/null".into(), "it exists and is not a folder"),
        (
            at("foreign"),
            "friction-lab did not write and it is not empty",
        ),
        (at("link"), "it is a symbolic link (to `"),
        (".".into(), "it names no folder of its own"),
        (
            at(".friction-lab-x"),
            "are friction-lab's temporary folders",
        ),
        (long, "its name is 300 bytes long: allowed at most 255"),
        (at("afile").join("below"), "afile` above it is not a folder"),
    ];
    for (out, why) in cases {
        let mut child = Command::new(env!("CARGO_BIN_EXE_friction-lab"))
            .args(["reproduce", "--out"])
            .arg(&out)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let start = std::time::Instant::now();
        while child.try_wait().unwrap().is_none() {
            if start.elapsed().as_secs() > 10 {
                child.kill().unwrap();
                panic!(
                    "{}: still running after 10 s: computing before checking",
                    out.display()
                );
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        let o = child.wait_with_output().unwrap();
        let text = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{}: {text}", out.display());
        assert!(
            text.contains(&format!("output folder {}: ", out.display())) && text.contains(why),
            "{}: {text}",
            out.display()
        );
    }
    // Nothing was created, beside the folder's own files.
    let mut left: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["afile", "foreign", "link"]);
}

/// A study in which every run failed measured nothing, and says so with exit 1 after writing
/// the files that say which and why (it exited 0).
#[test]
fn a_study_in_which_every_run_failed_exits_one() {
    let dir = tempfile::tempdir().unwrap();
    // LuGre's stiff bristles at fixed steps of 0.02 and 0.01 s: every explicit run diverges.
    // (With v_belt = 1e308 work-precision's reference run fails first, and the study stops.)
    for (study, solvers) in [("converge", "rk4,dopri5"), ("work-precision", "rk4")] {
        let out = dir.path().join(study);
        let o = friction_lab(&[
            study,
            "belt",
            "--model",
            "lugre",
            "--solvers",
            solvers,
            "--dt-list",
            "0.02,0.01",
            "--out",
            out.to_str().unwrap(),
        ]);
        let text = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{study}: {text}");
        assert!(
            text.contains(&format!("error: {study}: every run failed (")),
            "{study}: {text}"
        );
        assert!(text.contains("nothing was measured; the first, "), "{text}");
        let csv = std::fs::read_to_string(out.join(format!("{study}.csv"))).unwrap();
        assert!(csv.lines().skip(1).all(|l| !l.ends_with(",ok")), "{csv}");
    }
    // A stiffness study in which no method meets the target at any value.
    let out = dir.path().join("stiffness");
    let o = friction_lab(&[
        "stiffness",
        "belt",
        "--model",
        "CS",
        "--values",
        "1e-2,1e-3",
        "--target",
        "1e-30",
        "--solvers",
        "dopri5,bdf",
        "--tol-list",
        "1e-3,1e-4",
        "--out",
        out.to_str().unwrap(),
    ]);
    let text = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{text}");
    assert!(
        text.contains(
            "error: stiffness: no method reached the target 1e-30 at any of the 2 values of \
             `epsilon`, nothing was measured"
        ),
        "{text}"
    );
    assert!(out.join("stiffness.csv").is_file());
}

/// A measure that does not exist for a run is an empty cell and JSON `null`, never 0 (which
/// reads as exact): LuGre has no stick phases, a regularised run no events, and a solver that
/// never met a stiffness study's target (below what any resolution reaches, its lists extended
/// to their limits) paid no cost.
#[test]
fn a_measure_that_does_not_exist_is_empty_never_zero() {
    let dir = tempfile::tempdir().unwrap();
    let cell = |csv: &str, row: usize, column: &str| -> String {
        let mut lines = csv.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let k = header.iter().position(|h| *h == column).unwrap();
        lines
            .nth(row)
            .unwrap()
            .split(',')
            .nth(k)
            .unwrap()
            .to_string()
    };
    let study = |name: &str, args: &[&str]| -> (String, serde_json::Value) {
        let out = dir.path().join(name);
        let mut all = args.to_vec();
        all.extend(["--out", out.to_str().unwrap()]);
        let o = friction_lab(&all);
        // The stiffness study below has no method meet its target: nothing measured, exit 1.
        let code = if args[0] == "stiffness" { 1 } else { 0 };
        assert_eq!(o.status.code(), Some(code), "{}", stderr(&o));
        let csv = std::fs::read_to_string(out.join(format!("{}.csv", args[0]))).unwrap();
        let json = std::fs::read(out.join(format!("{}.json", args[0]))).unwrap();
        (csv, serde_json::from_slice(&json).unwrap())
    };
    let (csv, json) = study(
        "lugre",
        &[
            "converge",
            "belt",
            "--model",
            "lugre",
            "--t-end",
            "2",
            "--solvers",
            "rk4",
            "--dt-list",
            "0.002,0.001",
        ],
    );
    for row in 0..2 {
        assert_eq!(cell(&csv, row, "error_stick_durations"), "", "{csv}");
        assert!(
            json["runs"][row]["errors"]["stick_durations"].is_null(),
            "{json}"
        );
        assert_ne!(cell(&csv, row, "error_final_relative"), "", "{csv}");
    }
    let (csv, json) = study(
        "regularised",
        &[
            "converge",
            "belt",
            "--model",
            "CS",
            "--switching",
            "regularized",
            "--t-end",
            "2",
            "--solvers",
            "rk4",
            "--dt-list",
            "0.002,0.001",
        ],
    );
    for row in 0..2 {
        assert_eq!(cell(&csv, row, "events"), "0", "{csv}");
        assert_eq!(cell(&csv, row, "error_event_times"), "", "{csv}");
        assert!(
            json["runs"][row]["errors"]["event_times"].is_null(),
            "{json}"
        );
    }
    let (csv, json) = study(
        "stiffness",
        &[
            "stiffness",
            "belt",
            "--model",
            "CS",
            "--values",
            "1e-2",
            "--solvers",
            "rk4,bdf",
            "--target",
            "1e-14",
            "--dt-list",
            "0.01",
            "--tol-list",
            "1e-4",
            "--t-end",
            "1",
        ],
    );
    for row in 0..2 {
        assert_eq!(cell(&csv, row, "reached"), "false", "{csv}");
        for column in [
            "error",
            "rhs_evals",
            "jacobian_evals",
            "lu_factorizations",
            "linear_solves",
        ] {
            assert_eq!(cell(&csv, row, column), "", "{column}: {csv}");
        }
        assert!(
            json["points"][0]["costs"][row]["reached"].is_null(),
            "{json}"
        );
    }
}

/// One rule for a blown-up run, whatever the scheme: a state beyond 10³ times the system's
/// reach is `diverged`, exit 1. The servo time-stepped at h = 1 s (its controller's force held
/// over each step) used to reach 7.4e84 m as `ok`, the actuator's work balancing the energy
/// books; Dormand–Prince at a fixed step of 1 s reached 3.8e70 m as `inaccurate`, exit 0. At
/// h = 0.5 s the servo's sampled loop is unstable while sliding but ends in each stick phase
/// (exit 0, `inaccurate` for the step map's multiplier). The step-size note takes the
/// controller's natural period 2π√(m/kp) too.
#[test]
fn a_runaway_is_diverged_whatever_the_scheme() {
    let dir = tempfile::tempdir().unwrap();
    let simulate = |name: &str, args: &[&str]| simulated(dir.path(), name, args);
    let servo = |dt| {
        [
            "servo",
            "--model",
            "static",
            "--t-end",
            "100",
            "--scheme",
            "time-stepping",
            "--dt",
            dt,
        ]
    };
    for (name, args, t) in [
        ("servo", &servo("1")[..], 13.4),
        (
            "dopri5",
            &[
                "belt",
                "--model",
                "CVS",
                "--solver",
                "dopri5",
                "--fixed-step",
                "--dt",
                "1",
            ][..],
            1.61,
        ),
    ] {
        let (o, s) = simulate(name, args);
        assert_eq!(o.status.code(), Some(1), "{name}: {}", stderr(&o));
        assert_eq!(s["status"], "diverged", "{name}: {s}");
        let reason = s["reason"].as_str().unwrap();
        assert!(
            reason.starts_with(&format!("at t = {t} the ")),
            "{name}: {reason}"
        );
        assert!(reason.contains("is beyond 1e3 times"), "{name}: {reason}");
        assert!(
            stderr(&o).contains("error: the run diverged"),
            "{name}: {}",
            stderr(&o)
        );
        // What it had is kept, and nothing beyond the bound.
        assert!(s["t_reached"].as_f64().unwrap() < t, "{name}: {s}");
    }
    let (o, _) = simulate("servo-1", &servo("1"));
    assert!(
        stderr(&o).contains("the time-stepping scheme diverged with the step h = 1 s"),
        "{}",
        stderr(&o)
    );
    assert!(
        stderr(&o).contains("more than a tenth of the shortest natural period, 3.63 s"),
        "{}",
        stderr(&o)
    );
    // At h = 0.5 s the sampled loop is unstable while the body slides (the derivative term
    // held over a step multiplies the velocity by about 1 − h·kd/m = −2), but each stick
    // phase ends the growth: no runaway, exit 0. The step map's multiplier says so, and step
    // doubling too: `inaccurate`, not `ok`.
    let (o, s) = simulate("servo-half", &servo("0.5"));
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(s["status"], "inaccurate", "{s}");
    let reason = s["reason"].as_str().unwrap();
    assert!(
        reason.contains("the fixed step h = 0.5 s is beyond the sampled loop's stability limit")
            && reason.contains("step doubling"),
        "{reason}"
    );
    let mu = s["instability"]["multiplier_re"].as_f64().unwrap();
    assert!((-3.0..-1.5).contains(&mu), "{s}");
    // At h = 0.25 s (1 − h·kd/m = −0.5) the sampled loop is stable.
    let (_, s) = simulate("servo-quarter", &servo("0.25"));
    assert!(s["instability"].is_null(), "{s}");
}

/// A fixed-step run estimates its own error by step doubling (the same run at h/2, compared
/// on the output grid over the solution's scale) and is `inaccurate` above 0.1, the estimate
/// in its reason and in `summary.json`'s `step_doubling`. RK4 on the belt at h = 0.1 s was
/// `ok` while its velocity was wrong by more than the solution's scale; at h = 0.001 s the
/// estimate is 1e-7. Adaptive runs have none.
#[test]
fn a_fixed_step_run_estimates_its_error_by_step_doubling() {
    let dir = tempfile::tempdir().unwrap();
    let simulate = |name: &str, args: &[&str]| {
        let (o, summary) = simulated(
            dir.path(),
            name,
            &[&["belt", "--model", "CVS"], args].concat(),
        );
        assert_eq!(o.status.code(), Some(0), "{name}: {}", stderr(&o));
        summary
    };
    let coarse = simulate("coarse", &["--solver", "rk4", "--dt", "0.1"]);
    assert_eq!(coarse["status"], "inaccurate", "{coarse}");
    let estimate = coarse["step_doubling"]["relative"].as_f64().unwrap();
    assert!(estimate > 1.0, "{coarse}");
    let reason = coarse["reason"].as_str().unwrap();
    assert!(
        reason.contains("its error estimated by step doubling")
            && reason.contains("h/2 = 0.05 s")
            && reason.contains(&format!("is {estimate:.3} at t =")),
        "{reason}"
    );
    let fine = simulate("fine", &["--solver", "rk4", "--dt", "0.001"]);
    assert_eq!(fine["status"], "ok", "{fine}");
    let estimate = fine["step_doubling"]["relative"].as_f64().unwrap();
    assert!(estimate > 1e-9 && estimate < 1e-5, "{fine}");
    // Moreau–Jean's first order: h = 0.1 s is inaccurate, the default 1e-3 s is not.
    let stepped = simulate("stepped", &["--scheme", "time-stepping", "--dt", "0.1"]);
    assert_eq!(stepped["status"], "inaccurate", "{stepped}");
    let stepped = simulate("stepped-fine", &["--scheme", "time-stepping"]);
    assert_eq!(stepped["status"], "ok", "{stepped}");
    let adaptive = simulate("adaptive", &[]);
    assert!(adaptive["step_doubling"].is_null(), "{adaptive}");
}

/// Sweeps carry verdicts: every row has the run's status and reason; a diverged point has empty
/// measures and no regime, and never stops the others from being written (exit 1, every row
/// kept). RK4 at h = 1 s on the belt at k = 10 used to be written `ok`, `Unsettled`, with an
/// amplitude of 0.702 m; one runaway point of the time-stepped servo made the whole sweep
/// write nothing.
#[test]
fn a_sweep_writes_every_point_with_its_verdict() {
    let dir = tempfile::tempdir().unwrap();
    let rows = |out: &std::path::Path| -> Vec<std::collections::HashMap<String, String>> {
        let text = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
        let mut reader = csv::Reader::from_reader(text.as_bytes());
        let header = reader.headers().unwrap().clone();
        (reader.records())
            .map(|r| {
                let r = r.unwrap();
                header
                    .iter()
                    .map(String::from)
                    .zip(r.iter().map(String::from))
                    .collect()
            })
            .collect()
    };
    for (name, args, bad) in [
        (
            "belt",
            vec![
                "belt", "--model", "CVS", "--grid", "k=1,10", "--solver", "rk4", "--dt", "1",
            ],
            "10",
        ),
        (
            "servo",
            vec![
                "servo",
                "--model",
                "static",
                "--grid",
                "ki=0,4",
                "--scheme",
                "time-stepping",
                "--dt",
                "1",
            ],
            "4",
        ),
    ] {
        let out = dir.path().join(name);
        let mut argv = vec!["sweep"];
        argv.extend(args);
        argv.extend(["--out", out.to_str().unwrap()]);
        let o = friction_lab(&argv);
        assert_eq!(o.status.code(), Some(1), "{name}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("1 of 2 runs failed or diverged"),
            "{name}: {}",
            stderr(&o)
        );
        let rows = rows(&out);
        assert_eq!(rows.len(), 2, "{name}");
        let axis = if name == "belt" { "k" } else { "ki" };
        for row in &rows {
            let status = row["status"].as_str();
            if row[axis] == bad {
                assert_eq!(status, "diverged", "{name}: {row:?}");
                assert!(!row["reason"].is_empty(), "{name}: {row:?}");
                for measure in ["stick_phases", "period", "x_amplitude", "v_mean", "regime"] {
                    assert_eq!(row[measure], "", "{name}, {measure}: {row:?}");
                }
            } else {
                assert_ne!(status, "diverged", "{name}: {row:?}");
                assert_ne!(row["x_amplitude"], "", "{name}: {row:?}");
            }
        }
    }
    // A fixed-step point is judged by step doubling as `simulate` is: at h = 0.05 s RK4's
    // velocity differs from the run at h/2 by more than a tenth of its scale (`inaccurate`,
    // its measures kept as data, exit 0); at h = 0.001 s it is `ok`.
    for (dt, status) in [("0.05", "inaccurate"), ("0.001", "ok")] {
        let out = dir.path().join(format!("fixed-{dt}"));
        let o = friction_lab(&[
            "sweep",
            "belt",
            "--model",
            "CVS",
            "--grid",
            "k=50",
            "--solver",
            "rk4",
            "--dt",
            dt,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(0), "{dt}: {}", stderr(&o));
        let row = &rows(&out)[0];
        assert_eq!(row["status"], status, "{dt}: {row:?}");
        assert_eq!(
            row["reason"].contains("step doubling"),
            status == "inaccurate",
            "{row:?}"
        );
        assert_ne!(row["x_amplitude"], "", "{dt}: {row:?}");
    }
}

/// Every run is judged. RK4 at h = 1 s on the belt (h·ω = 10, past its stability bound of
/// about 2.8) leaves the belt's reach at t = 2.2 s: it is `diverged` and exits 1, its files
/// kept up to there. At h = 0.3 s it is `inaccurate` (a quarter of the energy unaccounted
/// for): exit 0 with a note. In a study, a run whose error is as large as the solution is
/// `inaccurate`, kept as data, and left out of every fit.
#[test]
fn every_run_is_judged_and_a_diverged_run_exits_one() {
    let dir = tempfile::tempdir().unwrap();
    let simulate = |name: &str, args: &[&str]| simulated(dir.path(), name, args);
    let cvs = |dt| ["belt", "--model", "CVS", "--solver", "rk4", "--dt", dt];
    // RK4 at h = 1 s: the block leaves the belt's reach (10³ times the largest speed its
    // forces can give it) at t = 2.2 s, where the run stops: `diverged`.
    let (o, s) = simulate("diverged", &cvs("1"));
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(s["status"], "diverged", "{s}");
    let reason = s["reason"].as_str().unwrap();
    assert!(
        reason.starts_with("at t = 2.22 the velocity of body \"body\"")
            && reason.contains("is beyond 1e3 times the largest the system's forces"),
        "{reason}"
    );
    assert_eq!(s["t_reached"], 2.21, "{s}");
    assert!(
        stderr(&o).contains("error: the run diverged"),
        "{}",
        stderr(&o)
    );
    let (o, s) = simulate("inaccurate", &cvs("0.3"));
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(s["status"], "inaccurate", "{s}");
    assert!(
        stderr(&o).contains("the run is inaccurate"),
        "{}",
        stderr(&o)
    );
    let (o, s) = simulate("fine", &cvs("0.001"));
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        (s["status"].as_str(), s["reason"].is_null()),
        (Some("ok"), true)
    );
    // A fixed step beyond RK4's stability limit: regularised at ε = 1e-4, the slope F_c/ε of
    // the law near v = 0 is a mode of about −7e4 1/s, which h = 1e-3 multiplies by 1e6 a step
    // (the block chatters within ±ε). The run is judged `inaccurate` for it, saying where: the
    // mode, its factor and its time. At h = 2e-5 it is damped.
    let belt = [
        "belt",
        "--model",
        "CS",
        "--switching",
        "regularized",
        "--set",
        "epsilon=1e-4",
    ];
    let regularised = |dt| [&belt[..], &["--solver", "rk4", "--dt", dt, "--t-end", "1"]].concat();
    let (o, s) = simulate("unstable", &regularised("1e-3"));
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(s["status"], "inaccurate", "{s}");
    let reason = s["reason"].as_str().unwrap();
    assert!(
        reason.contains("the fixed step h = 0.001 s is beyond the method's stability limit"),
        "{reason}"
    );
    let mode = &s["instability"];
    let lambda = mode["lambda_re"].as_f64().unwrap();
    assert!((-1e5..-5e4).contains(&lambda), "{mode}");
    assert!(mode["amplification"].as_f64().unwrap() > 1e5, "{mode}");
    let (o, s) = simulate("stable", &regularised("2e-5"));
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(s["status"], "ok", "{s}");
    assert!(s["instability"].is_null(), "{s}");
    // BDF at tolerance 1e-3 on the regularised belt (ε = 1e-4): a velocity error of 463 m/s on
    // a motion of scale 0.19 m/s. Issue 36 found it `ok` and in the fit.
    let out = dir.path().join("wp");
    let o = friction_lab(
        &[
            &["work-precision"][..],
            &belt,
            &[
                "--solvers",
                "bdf",
                "--tol-list",
                "1e-3",
                "--out",
                out.to_str().unwrap(),
            ],
        ]
        .concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("work-precision.csv")).unwrap();
    let bdf = csv.lines().find(|l| l.starts_with("bdf,")).unwrap();
    // Its velocity is off by 463 m/s on a motion whose largest speed is 0.185 m/s.
    assert!(
        bdf.contains(",inaccurate,its relative error 2500."),
        "{bdf}"
    );
    assert!(bdf.contains("is at least 1: no correct digit"), "{bdf}");
}

/// The reference is always cross-checked, its estimated error written beside it, and a study
/// whose finest error is less than 100 times that estimate says its finest runs are limited
/// by the reference (RK4 down to h = 5e-4 on the belt: 2.3e-10 against a reference good to
/// about 4e-12); a coarser study does not.
#[test]
fn a_study_says_when_its_finest_runs_are_limited_by_the_reference() {
    let dir = tempfile::tempdir().unwrap();
    let study = |name: &str, steps: &str| {
        let out = dir.path().join(name);
        let o = friction_lab(&[
            "converge",
            "belt",
            "--model",
            "CVS",
            "--solvers",
            "rk4",
            "--dt-list",
            steps,
            "--t-end",
            "2",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("converge.json")).unwrap()).unwrap();
        (String::from_utf8_lossy(&o.stdout).into_owned(), json)
    };
    let (text, json) = study("fine", "0.004,0.002,0.001,0.0005");
    let check = &json["reference"]["Run"]["cross_check"];
    assert_eq!(check[0], "tsit45", "{json}");
    let estimate = check[1].as_f64().unwrap();
    assert!(estimate > 0.0 && estimate < 1e-10, "{estimate:e}");
    let limit = json["reference_limit"].as_str().unwrap();
    assert!(
        limit.starts_with("the finest runs are limited by the reference"),
        "{limit}"
    );
    assert!(text.contains(limit), "{text}");
    let (text, json) = study("coarse", "0.02,0.01,0.005");
    assert!(json["reference_limit"].is_null(), "{json}");
    assert!(!text.contains("limited by the reference"), "{text}");
}

/// `sweep` extends a point that has not settled: at v_belt = 0.0044 m/s with k = 56.2 N/m the
/// body is carried by the belt for its first 30 s (the spring loading to F_s), a transient
/// that a 20 s run took for steady sliding; doubled to 80 s, the run settles on stick–slip,
/// one stick phase a cycle. A point that settles at once keeps its span.
#[test]
fn sweep_extends_a_point_until_it_settles() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s");
    let o = friction_lab(&[
        "sweep",
        "belt",
        "--model",
        "CVS",
        "--grid",
        "v_belt=0.0044,0.05",
        "--set",
        "k=56.2341",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let cell =
        |row: usize, column: &str| rows[row][header.iter().position(|h| *h == column).unwrap()];
    assert_eq!(
        (cell(0, "settled"), cell(0, "t_end")),
        ("true", "80"),
        "{csv}"
    );
    let per_cycle: f64 = cell(0, "stick_per_cycle").parse().unwrap();
    assert!((per_cycle - 1.0).abs() < 0.01, "{csv}");
    assert!(cell(0, "drift").parse::<f64>().unwrap() <= 0.01, "{csv}");
    assert_eq!(
        (cell(1, "settled"), cell(1, "t_end")),
        ("true", "20"),
        "{csv}"
    );
}

#[test]
fn phenomena_refuses_a_method_that_cannot_reach_its_tolerance() {
    // Implicit Euler at the default rtol 1e-10 needs about 1e10 steps a simulated second.
    let e = rejected(&["phenomena", "--solver", "implicit-euler"]);
    assert!(
        e.contains(
            "option `--rtol` = 1e-10 is out of reach of solver `implicit-euler`, of order 1: a \
             protocol run would take about 1e10 steps per simulated second"
        ) && e.contains("allowed with it: --rtol >= 1e-6"),
        "{e}"
    );
    let e = rejected(&["phenomena", "--solver", "tr-bdf2", "--rtol", "1e-13"]);
    assert!(e.contains("allowed with it: --rtol >= 1e-12"), "{e}");
    // Within reach: implicit Euler at 1e-5 decides a model's row.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t");
    let o = friction_lab(&[
        "phenomena",
        "--solver",
        "implicit-euler",
        "--rtol",
        "1e-5",
        "--atol",
        "1e-7",
        "--model",
        "CS",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn the_time_limit_bounds_a_command_of_many_runs_as_a_whole() {
    // Table 2 on one thread takes well over a second; with --time-limit 1 the runs that start
    // after the first second end at their first step, at t = 0, and their cells are undecided.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t");
    let o = friction_lab(&[
        "phenomena",
        "--threads",
        "1",
        "--time-limit",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let table: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("table2.json")).unwrap()).unwrap();
    let failed: Vec<&str> = table["models"]
        .as_object()
        .unwrap()
        .values()
        .flat_map(|row| row.as_object().unwrap().values())
        .filter_map(|cell| cell["failed"].as_str())
        .collect();
    let unstarted = failed
        .iter()
        .filter(|f| f.contains("time limit: 1 s of wall time used by t = 0 without"))
        .count();
    assert!(unstarted > 0, "{failed:?}");
    assert!(
        failed.iter().all(|f| f.contains("time limit")),
        "{failed:?}"
    );
    // A sweep likewise; a point stopped at t = 0 measures nothing and has not settled.
    let out = dir.path().join("s");
    let o = friction_lab(&[
        "sweep",
        "belt",
        "--model",
        "lugre",
        "--solver",
        "implicit-euler",
        "--grid",
        "v_belt=0.01:0.2:8",
        "--threads",
        "1",
        "--time-limit",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let unstarted: Vec<&str> = csv
        .lines()
        .filter(|l| {
            l.ends_with("time limit: 1 s of wall time used by t = 0 without reaching the end")
        })
        .collect();
    assert!(!unstarted.is_empty(), "{csv}");
    for row in unstarted {
        // v_belt, then stick_phases and nine measures empty, settled false, drift empty; the
        // status `failed`.
        let cells: Vec<&str> = row.split(',').collect();
        assert_eq!(cells[1], "", "{row}");
        assert_eq!(cells[cells.len() - 2], "failed", "{row}");
        assert!(cells[2..10].iter().all(|c| c.is_empty()), "{row}");
        assert_eq!(cells[10], "false", "{row}");
        // A failed run has no regime: an empty cell, not a transient.
        assert_eq!(cells[11], "", "{row}");
    }
}

/// `sweep` classifies every point as the stick–slip map does, and draws the sweep: the
/// settled amplitude over one axis, the regimes over the plane of two, nothing over three.
/// On the belt with CVS (c = 0, k = 100) the body sticks and slips at 0.1 m/s and slides
/// steadily at 0.8 m/s, above the speed where the Stribeck slope stops feeding it energy.
#[test]
fn sweep_writes_each_points_regime_and_a_figure() {
    let dir = tempfile::tempdir().unwrap();
    let sweep = |name: &str, grid: &[&str]| {
        let out = dir.path().join(name);
        let mut args = vec!["sweep", "belt", "--model", "CVS"];
        for g in grid {
            args.extend(["--grid", g]);
        }
        args.extend(["--out", out.to_str().unwrap()]);
        let o = friction_lab(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        out
    };
    let one = sweep("one", &["v_belt=0.1,0.8"]);
    let csv = std::fs::read_to_string(one.join("sweep.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    let col = rows[0].iter().position(|c| *c == "regime").unwrap();
    assert_eq!(rows[0][col - 1], "settled");
    assert_eq!(
        (rows[1][col], rows[2][col]),
        ("StickSlip", "SteadySliding"),
        "{csv}"
    );
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(one.join("sweep.json")).unwrap()).unwrap();
    assert_eq!(json["points"][0]["regime"], "StickSlip");
    for out in [&one, &sweep("two", &["v_belt=0.1,0.8", "k=50,100"])] {
        assert!(out.join("sweep.png").is_file() && out.join("sweep.svg").is_file());
    }
    let svg = std::fs::read_to_string(one.join("sweep.svg")).unwrap();
    assert!(
        svg.contains("v_belt (m/s)") && svg.contains("stick-slip"),
        "{svg}"
    );
    let three = sweep("three", &["v_belt=0.1", "k=100", "c=0"]);
    assert!(!three.join("sweep.png").exists());
}

/// `sweep --start sliding`: the belt's body started at the equilibrium of steady sliding,
/// the other half of a bifurcation diagram. On the belt with CVS at k = 100 steady sliding is
/// stable at 0.5 m/s, where a start from rest still ends in stick–slip (the two coexist), and
/// unstable at 0.1 m/s, where both starts end in stick–slip. Any other target is refused.
#[test]
fn sweep_starts_from_rest_or_from_steady_sliding() {
    let dir = tempfile::tempdir().unwrap();
    let regimes = |start: &str| {
        let out = dir.path().join(start);
        let o = friction_lab(&[
            "sweep",
            "belt",
            "--model",
            "CVS",
            "--grid",
            "v_belt=0.1,0.5",
            "--start",
            start,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
        let rows: Vec<Vec<String>> = (csv.lines())
            .map(|l| l.split(',').map(String::from).collect())
            .collect();
        let col = rows[0].iter().position(|c| c == "regime").unwrap();
        let json: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("sweep.json")).unwrap()).unwrap();
        assert_eq!(json["start"], start);
        (rows[1][col].clone(), rows[2][col].clone())
    };
    assert_eq!(regimes("rest"), ("StickSlip".into(), "StickSlip".into()));
    assert_eq!(
        regimes("sliding"),
        ("StickSlip".into(), "SteadySliding".into())
    );
    for (args, message) in [
        (
            vec!["sweep", "chain", "--model", "CS", "--grid", "k_chain=10,20"],
            "applies to the belt rig only",
        ),
        (
            vec![
                "sweep",
                "paper-block",
                "--model",
                "CS",
                "--grid",
                "F_ex=10,20",
            ],
            "applies to the belt rig only",
        ),
        (
            vec!["sweep", "belt", "--model", "CS", "--grid", "x0=0,0.1"],
            "sets x0 itself",
        ),
        (
            vec![
                "sweep",
                "belt",
                "--model",
                "CS",
                "--grid",
                "v_belt=0.1",
                "--set",
                "k=0",
            ],
            "needs a spring",
        ),
    ] {
        let mut all = args.clone();
        all.extend(["--start", "sliding"]);
        let e = rejected(&all);
        assert!(e.contains(message), "{args:?}: {e}");
    }
    let e = rejected(&[
        "sweep", "belt", "--model", "CS", "--grid", "k=10", "--start", "moving",
    ]);
    assert!(
        e.contains("unknown start `moving`; known: rest, sliding"),
        "{e}"
    );
}

/// Writes a chain of `n` bodies as the system file `chain.toml` in `dir` (inline tables, a
/// Coulomb contact on the first body only) and returns its path.
fn chain_file(dir: &Path, n: usize) -> PathBuf {
    let file = dir.join("chain.toml");
    let mut text = String::from("anchor=[{name=\"d\",v=0.1}]\nbody=[\n");
    text += &(1..=n)
        .map(|i| format!("{{name=\"b{i}\",m=1}}"))
        .collect::<Vec<_>>()
        .join(",\n");
    text += "]\nspring=[\n{between=[\"d\",\"b1\"],k=10}";
    for i in 1..n {
        text += &format!(",\n{{between=[\"b{i}\",\"b{}\"],k=9}}", i + 1);
    }
    text += "]\ncontact=[\n{body=\"b1\",model=\"coulomb\"}]\n";
    std::fs::write(&file, text).unwrap();
    file
}

#[test]
fn loading_a_system_file_talks_off_a_terminal() {
    // A chain of 10^5 bodies in a file: loading takes about a second, in which no run
    // advances; the heartbeat reports it all the same.
    let dir = tempfile::tempdir().unwrap();
    let file = chain_file(dir.path(), 100_000);
    let out = dir.path().join("run");
    let o = Command::new(env!("CARGO_BIN_EXE_friction-lab"))
        .args(["simulate", "--system", file.to_str().unwrap()])
        .args([
            "--t-end",
            "0.001",
            "--points",
            "2",
            "--out",
            out.to_str().unwrap(),
        ])
        .env("FRICTION_LAB_HEARTBEAT_S", "0.05")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stderr(&o);
    let loading = format!("loading {}: ", file.display());
    assert!(
        text.lines()
            .any(|l| l.starts_with(&loading) && l.ends_with(" s elapsed")),
        "{text}"
    );
}

#[test]
fn a_signal_stops_the_loading_of_a_system_file_at_once() {
    // 3·10^5 bodies: about 3 s to load; stopped at the first heartbeat, 0.2 s in.
    let dir = tempfile::tempdir().unwrap();
    let file = chain_file(dir.path(), 300_000);
    let out = dir.path().join("run");
    let start = std::time::Instant::now();
    let (first, text, code) = interrupted_at_first_heartbeat(&[
        "simulate",
        "--system",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(first.starts_with("loading "), "{first}");
    assert_eq!(code, Some(130), "{text}");
    assert!(
        text.contains(&format!(
            "error: stopped while loading {}: nothing was run or written",
            file.display()
        )),
        "{text}"
    );
    assert!(!out.exists());
    // Well before the load could have ended.
    assert!(start.elapsed().as_secs_f64() < 2.0, "{:?}", start.elapsed());
}

#[test]
fn a_full_disk_names_the_output_folder_and_the_room_it_needs() {
    // A 64 kB tmpfs: the belt's files (1.3 MB) do not fit. Mounting needs root; where it
    // cannot be done the test says so and checks nothing (docs/inputs.md).
    let dir = tempfile::tempdir().unwrap();
    let small = dir.path().join("small");
    std::fs::create_dir(&small).unwrap();
    let mounted = Command::new("mount")
        .args(["-t", "tmpfs", "-o", "size=64k", "tmpfs"])
        .arg(&small)
        .output();
    if !mounted.is_ok_and(|o| o.status.success()) {
        eprintln!("skipped: no tmpfs can be mounted here (it needs root)");
        return;
    }
    let out = small.join("run");
    let o = friction_lab(&[
        "simulate",
        "belt",
        "--model",
        "CS",
        "--out",
        out.to_str().unwrap(),
    ]);
    let listing: Vec<_> = std::fs::read_dir(&small)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    let _ = Command::new("umount").arg(&small).status();
    let text = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{text}");
    assert!(
        text.contains(&format!(
            "error: writing the output folder {} failed at ",
            out.display()
        )) && text.contains("No space left on device")
            && text.contains(" files need ")
            && text.contains(" MB in all, and nothing was written"),
        "{text}"
    );
    assert!(!text.contains(".friction-lab-"), "{text}");
    // The temporary folder is gone with the failure.
    assert!(listing.is_empty(), "{listing:?}");
}

#[test]
fn a_huge_value_is_echoed_shortened() {
    // 100 kB (near the most one argument may hold) where a name or a number belongs: the
    // message names it by its first
    // characters and its length, in a few hundred bytes (from clap and from the program).
    let huge = "x".repeat(100_000);
    let set_value = format!("F_s={huge}");
    let set_name = format!("{huge}=1");
    for args in [
        vec!["simulate", "belt", "--model", &huge],
        vec!["simulate", &huge, "--model", "CS"],
        vec!["simulate", "belt", "--model", "CS", "--solver", &huge],
        vec!["simulate", "belt", "--model", "CS", "--set", &set_value],
        vec!["simulate", "belt", "--model", "CS", "--set", &set_name],
        vec!["simulate", "belt", "--model", "CS", "--param-set", &huge],
    ] {
        let text = rejected(&args);
        assert!(text.len() < 1000, "{} bytes", text.len());
        assert!(text.contains(" bytes]…"), "{text}");
    }
}

#[test]
fn a_bind_mount_of_the_same_device_is_refused_before_any_work() {
    // Same device as its parent, so only the mount table tells; mounting needs root, and
    // where it cannot be done the test says so and checks nothing.
    let dir = tempfile::tempdir().unwrap();
    let (source, target) = (dir.path().join("source"), dir.path().join("target"));
    std::fs::create_dir(&source).unwrap();
    std::fs::create_dir(&target).unwrap();
    let mounted = Command::new("mount")
        .arg("--bind")
        .args([&source, &target])
        .output();
    if !mounted.is_ok_and(|o| o.status.success()) {
        eprintln!("skipped: no bind mount can be made here (it needs root)");
        return;
    }
    let o = friction_lab(&["curve", "SV", "--out", target.to_str().unwrap()]);
    let _ = Command::new("umount").arg(&target).status();
    let text = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{text}");
    assert!(
        text.contains(&format!(
            "output folder {}: it is a mount point",
            target.display()
        )),
        "{text}"
    );
}

#[test]
fn a_sweep_ranges_points_read_as_written() {
    // 0.1 + 6·0.1 is 0.7000000000000001 in floating point: the point is 0.7, as one writes it.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s");
    let o = friction_lab(&[
        "sweep",
        "belt",
        "--model",
        "CS",
        "--grid",
        "v_belt=0.1:1:10",
        "--t-end",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let column: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(
        column,
        ["0.1", "0.2", "0.3", "0.4", "0.5", "0.6", "0.7", "0.8", "0.9", "1"]
    );
}

/// The pixel limit counts a figure's whole canvas: `converge` with a fixed-step and an adaptive
/// solver draws two panels side by side, 200 million pixels at 20x20 in and 500 dpi (each
/// panel alone within the 100 million checked when the options are read). Refused, exit 2,
/// naming the figure, and nothing written.
#[test]
fn the_pixel_limit_counts_the_whole_canvas() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("big");
    let o = friction_lab(&[
        "converge",
        "belt",
        "--model",
        "CVS",
        "--t-end",
        "2",
        "--solvers",
        "rk4,bdf",
        "--figure-size",
        "20x20",
        "--dpi",
        "500",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(
            "the figure converge.png would be 200 million pixels (its panels and legend at \
             500 dpi), over the 100 million allowed: a smaller --figure-size or --dpi"
        ),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
}

/// A rerun never deletes the user's files: friction-lab's marker lists the files it wrote, and
/// a folder that now holds others (notes, plots beside the results) is refused, exit 2, naming
/// them, unless `--replace` says to replace it with them.
#[test]
fn a_rerun_into_a_folder_holding_the_users_files_is_refused_unless_replace() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("belt");
    let run = |extra: &[&str]| {
        let mut args = vec![
            "simulate", "belt", "--model", "CVS", "--t-end", "1", "--out",
        ];
        args.push(out.to_str().unwrap());
        args.extend_from_slice(extra);
        friction_lab(&args)
    };
    assert!(run(&[]).status.success());
    let marker = std::fs::read_to_string(out.join(".friction-lab-output")).unwrap();
    assert!(marker.lines().any(|l| l == "summary.json"), "{marker}");
    // A rerun of friction-lab's own folder replaces it.
    assert!(run(&[]).status.success());
    std::fs::write(out.join("notes.md"), "my notes").unwrap();
    std::fs::create_dir(out.join("mine")).unwrap();
    std::fs::write(out.join("mine").join("plot.png"), "x").unwrap();
    let o = run(&[]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(
            "it now holds files that friction-lab did not write (`mine/plot.png`, `notes.md`), \
             which replacing the folder would delete"
        ) && stderr(&o).contains("pass --replace"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        std::fs::read_to_string(out.join("notes.md")).unwrap(),
        "my notes"
    );
    let o = run(&["--replace"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!out.join("notes.md").exists() && out.join("summary.json").exists());
    // Nothing is left beside the folder: no lock, no temporary folder.
    let beside: Vec<_> = std::fs::read_dir(dir.path()).unwrap().flatten().collect();
    assert_eq!(beside.len(), 1, "{beside:?}");
}

/// One number of a system file set twice, by name and by index or twice alike, by `--set` or
/// by `--grid`: refused (exit 2, nothing written), both spellings named; only the last would
/// have been used.
#[test]
fn a_system_number_set_twice_is_refused_naming_both_spellings() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("servo.toml");
    std::fs::write(
        &file,
        "[[body]]\nname = \"mass\"\nm = 1.0\n[[contact]]\nbody = \"mass\"\nmodel = \"CS\"\n\
         [[controller]]\nbody = \"mass\"\nkp = 20.0\nki = 2.0\nkd = 5.0\n\
         reference = { kind = \"constant\", x = 1.0 }\n",
    )
    .unwrap();
    let system = file.to_str().unwrap();
    let out = dir.path().join("out");
    for (args, message) in [
        (
            vec![
                "simulate",
                "--system",
                system,
                "--set",
                "controller.mass.kp=2",
                "--set",
                "controller.1.kp=5",
            ],
            "`controller.mass.kp` and `controller.1.kp` set the same number, kp of \
             [[controller]] 1: set each number once",
        ),
        (
            vec![
                "simulate",
                "--system",
                system,
                "--set",
                "body.mass.m=2",
                "--set",
                "body.mass.m=3",
            ],
            "`body.mass.m` and `body.mass.m` set the same number, m of [[body]] 1",
        ),
        (
            vec![
                "sweep",
                "--system",
                system,
                "--grid",
                "controller.mass.kp=1,2",
                "--grid",
                "controller.1.kp=3,4",
            ],
            "`controller.mass.kp` and `controller.1.kp` set the same number",
        ),
        (
            vec![
                "sweep",
                "--system",
                system,
                "--grid",
                "controller.mass.kp=1,2",
                "--set",
                "controller.1.kp=3",
            ],
            "set the same number, kp of [[controller]] 1",
        ),
    ] {
        let mut all = args.clone();
        all.extend(["--t-end", "1", "--out", out.to_str().unwrap()]);
        let o = friction_lab(&all);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(message), "{args:?}: {}", stderr(&o));
        assert!(!out.exists(), "{args:?}");
    }
}

/// `testset`: a problem of the stiff test set by one solver, its end state and its significant
/// correct digits against the published reference; elsewhere than the reference's end time
/// there is no reference, and `scd` is null, not 0.
#[test]
fn testset_writes_the_end_state_and_the_digits_against_the_reference() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("hires");
    let o = friction_lab(&[
        "testset",
        "hires",
        "--rtol",
        "1e-8",
        "--atol",
        "1e-8",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("final.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], "t,y1,y2,y3,y4,y5,y6,y7,y8");
    assert_eq!(lines.len(), 2, "{csv}");
    assert!(lines[1].starts_with("3.218122e2,"), "{csv}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(json["solver"], "radau5");
    let stats = &json["stats"];
    let scd = stats["scd"].as_f64().unwrap();
    assert!(scd > 5.0 && scd < 12.0, "{json}");
    assert_eq!(
        stats["steps"].as_u64().unwrap(),
        stats["accepted"].as_u64().unwrap() + stats["rejected"].as_u64().unwrap()
    );
    for field in [
        "rhs_evals",
        "jacobian_evals",
        "lu_factorizations",
        "linear_solves",
        "newton_iterations",
    ] {
        assert!(stats[field].as_u64().unwrap() > 0, "{field}: {json}");
    }
    // Elsewhere than t = 321.8122: no reference, no digits.
    let early = dir.path().join("early");
    let o = friction_lab(&[
        "testset",
        "orego",
        "--solver",
        "rodas",
        "--t-end",
        "100",
        "--out",
        early.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(early.join("summary.json")).unwrap())
            .unwrap();
    assert!(json["stats"]["scd"].is_null(), "{json}");
    assert_eq!(json["t_reached"], 100.0);
    // Robertson at t = 40, where Hairer & Wanner publish its values.
    let forty = dir.path().join("forty");
    let o = friction_lab(&[
        "testset",
        "robertson",
        "--t-end",
        "40",
        "--rtol",
        "1e-8",
        "--atol",
        "1e-14",
        "--out",
        forty.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(forty.join("summary.json")).unwrap())
            .unwrap();
    let scd = json["stats"]["scd"].as_f64().unwrap();
    assert!(scd > 7.0 && scd < 13.0, "{json}");
    // Bad input: exit 2, nothing written, the alternatives named.
    for (args, message) in [
        (
            vec!["testset", "e5"],
            "unknown test problem `e5`; known problems: van-der-pol, robertson, hires, orego, pollution",
        ),
        (
            vec!["testset", "hires", "--solver", "rk4"],
            "option `--solver rk4` takes a fixed step",
        ),
        (
            vec!["testset", "hires", "--rtol", "0"],
            "option `--rtol` = 0 is out of range",
        ),
    ] {
        let bad = dir.path().join("bad");
        let mut all = args.clone();
        all.extend(["--out", bad.to_str().unwrap()]);
        let o = friction_lab(&all);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(message), "{args:?}: {}", stderr(&o));
        assert!(!bad.exists(), "{args:?}");
    }
}

/// `testset` judges a run by its digits as the studies do: fewer than one correct digit is
/// `inaccurate` (reason: the digits; a warning; exit 0), where the run used to be `ok`; and a
/// problem's default absolute tolerance is its own (Robertson: 1e-14·rtol, whose y2 is of order
/// 1e-13), so the defaults give a correct answer.
#[test]
fn testset_calls_a_run_without_a_correct_digit_inaccurate_and_defaults_robertsons_atol() {
    let dir = tempfile::tempdir().unwrap();
    let summary = |out: &std::path::Path| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
    };
    for (problem, solver) in [("robertson", "implicit-euler"), ("hires", "radau5")] {
        let out = dir.path().join(problem);
        let o = friction_lab(&[
            "testset",
            problem,
            "--solver",
            solver,
            "--rtol",
            "1",
            "--atol",
            "1",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let json = summary(&out);
        let scd = json["stats"]["scd"].as_f64().unwrap();
        assert!(scd < 1.0, "{json}");
        assert_eq!(json["status"], "inaccurate", "{json}");
        let reason = json["reason"].as_str().unwrap();
        assert!(
            reason.starts_with(&format!(
                "{scd:.2} significant correct digits, fewer than 1"
            )),
            "{reason}"
        );
        assert!(
            stderr(&o).contains("the run is inaccurate"),
            "{}",
            stderr(&o)
        );
    }
    let out = dir.path().join("robertson-defaults");
    let o = friction_lab(&["testset", "robertson", "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let json = summary(&out);
    assert_eq!(
        (json["rtol"].as_f64(), json["atol"].as_f64()),
        (Some(1e-6), Some(1e-20))
    );
    assert_eq!(json["status"], "ok", "{json}");
    assert!(json["stats"]["scd"].as_f64().unwrap() > 4.0, "{json}");
}

/// `work-precision --testset`: the test set's problems as a study's case, each run measured by
/// its significant correct digits against the published reference, with the same counts as the
/// `testset` command's single run.
#[test]
fn work_precision_takes_a_problem_of_the_stiff_test_set() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("wp");
    let o = friction_lab(&[
        "work-precision",
        "--testset",
        "van-der-pol",
        "--solvers",
        "radau5,rodas",
        "--tol-list",
        "1e-4,1e-7",
        "--repeats",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    for file in [
        "work-precision.csv",
        "work-precision-timing.csv",
        "work-precision.json",
        "work-precision.png",
        "work-precision.svg",
        "work-precision-timing.png",
        "work-precision-timing.svg",
    ] {
        assert!(out.join(file).exists(), "{file}");
    }
    let csv = std::fs::read_to_string(out.join("work-precision.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert!(
        csv.starts_with("solver,tol,rtol,atol,status,scd,work,steps,"),
        "{csv}"
    );
    assert_eq!(rows.len(), 4, "{csv}");
    for pair in rows.chunks(2) {
        let scd = |r: &[&str]| r[5].parse::<f64>().unwrap();
        assert_eq!((pair[0][4], pair[1][4]), ("ok", "ok"), "{csv}");
        // Three decades of tolerance give at least two more correct digits.
        assert!(scd(&pair[1]) > scd(&pair[0]) + 2.0, "{csv}");
    }
    let timing = std::fs::read_to_string(out.join("work-precision-timing.csv")).unwrap();
    assert!(
        timing
            .lines()
            .skip(1)
            .all(|l| l.split(',').nth(2) == Some("2")),
        "{timing}"
    );
    // The single run of `testset` at 1e-7 gives the study's counts and digits.
    let single = dir.path().join("single");
    let o = friction_lab(&[
        "testset",
        "van-der-pol",
        "--solver",
        "rodas",
        "--rtol",
        "1e-7",
        "--atol",
        "1e-7",
        "--out",
        single.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(single.join("summary.json")).unwrap())
            .unwrap();
    let study: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("work-precision.json")).unwrap())
            .unwrap();
    let run = &study["runs"][3];
    assert_eq!(run["solver"], "rodas");
    assert_eq!(run["scd"], json["stats"]["scd"]);
    assert_eq!(run["stats"]["rhs_evals"], json["stats"]["rhs_evals"]);
    assert_eq!(study["problem"], "van-der-pol");
    // Bad input: exit 2, nothing written, the option named.
    for (args, message) in [
        (
            vec!["work-precision", "--testset", "e5"],
            "unknown test problem `e5`",
        ),
        (
            vec!["work-precision", "--testset", "hires", "--solvers", "rk4"],
            "option `--solvers` names `rk4`, which takes a fixed step",
        ),
        (
            vec!["work-precision", "--testset", "hires", "--model", "CS"],
            "cannot be used with",
        ),
        (
            vec![
                "work-precision",
                "--testset",
                "hires",
                "--tol-list",
                "1e-3,1e-2",
            ],
            "option `--tol-list`",
        ),
        (vec!["work-precision"], "the study needs a problem"),
    ] {
        let text = rejected(&args);
        assert!(text.contains(message), "{args:?}: {text}");
    }
}

/// The stiffness along a rig's run: `h·ρ` at its recorded points in `stiffness.csv`, drawn,
/// and summarised in `summary.json`. On LuGre at σ0 = 1e5, Dormand–Prince's steps stay near its
/// stability boundary (h·ρ ≈ 3.3: it is stability-limited), while Radau IIA's go far beyond it.
#[test]
fn simulate_measures_the_stiffness_along_a_rig_run() {
    let dir = tempfile::tempdir().unwrap();
    let mut max = BTreeMap::new();
    for solver in ["dopri5", "radau5"] {
        let out = dir.path().join(solver);
        let o = friction_lab(&[
            "simulate",
            "belt",
            "--model",
            "lugre",
            "--set",
            "sigma0=1e5",
            "--solver",
            solver,
            "--t-end",
            "5",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let csv = std::fs::read_to_string(out.join("stiffness.csv")).unwrap();
        assert!(csv.starts_with("t,h,rho,h_rho\n"), "{csv}");
        assert!(out.join("stiffness.png").exists() && out.join("stiffness.svg").exists());
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        let s = &json["stiffness"];
        assert_eq!(
            s["points"].as_u64().unwrap() as usize,
            csv.lines().count() - 1
        );
        max.insert(solver, s["max_h_rho"].as_f64().unwrap());
    }
    assert!(max["dopri5"] > 2.0 && max["dopri5"] < 6.0, "{max:?}");
    assert!(max["radau5"] > 10.0, "{max:?}");
}

#[test]
fn the_brake_example_is_swept_over_its_disc_speed_by_a_path_of_the_file() {
    // examples/brake.toml: the pad sticks and slips on a slow disc (the Stribeck curve falls
    // below v_s = 0.1 m/s) and slides steadily on a fast one, a sweep over a number of the
    // file by its path. The pad is measured without being named: the first body with a
    // contact (the caliper, the first body, has none).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sweep");
    let o = friction_lab(&[
        "sweep",
        "--system",
        "examples/brake.toml",
        "--grid",
        "contact.pad.surface_velocity=0.05,1",
        "--t-end",
        "10",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    // Both rows ran ("ok" in the last column), so no cell holds a comma.
    let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
    let column = |name: &str| rows[0].iter().position(|h| *h == name).unwrap();
    let regimes: Vec<&str> = rows[1..].iter().map(|r| r[column("regime")]).collect();
    assert_eq!(regimes, ["StickSlip", "SteadySliding"], "{text}");
    assert_eq!(rows[1][column("contact.pad.surface_velocity")], "0.05");
    // The same run's spectrum puts the pad's motion at the stick–slip cycle's frequency, 1 /
    // the period the sweep measured, within the spectrum's resolution.
    let period: f64 = rows[1][column("period")].parse().unwrap();
    let single = dir.path().join("single");
    let o = friction_lab(&[
        "simulate",
        "--system",
        "examples/brake.toml",
        "--bodies",
        "pad",
        "--t-end",
        "10",
        "--out",
        single.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let spectrum: serde_json::Value =
        serde_json::from_slice(&std::fs::read(single.join("spectrum.json")).unwrap()).unwrap();
    let pad = &spectrum["bodies"][0];
    let f = pad["dominant_frequency"].as_f64().unwrap();
    let resolution = spectrum["resolution"].as_f64().unwrap();
    assert_eq!(pad["body"], "pad");
    assert!(
        (f - 1.0 / period).abs() < resolution,
        "{f} Hz against 1/{period} s"
    );
    assert!(String::from_utf8_lossy(&o.stdout).contains("pad: dominant frequency"));
    // A number set by its path is the run's: reported among its parameters, and it changes
    // the run (a stiffer guide pin, another stick–slip).
    let run = |extra: &[&str], name: &str| {
        let out = dir.path().join(name);
        let mut args = vec![
            "simulate",
            "--system",
            "examples/brake.toml",
            "--t-end",
            "2",
        ];
        args.extend(extra);
        args.extend(["--out", out.to_str().unwrap()]);
        let o = friction_lab(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let summary: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
        summary
    };
    let plain = run(&[], "plain");
    let stiffer = run(&["--set", "spring.2.k=8e4"], "stiffer");
    assert_eq!(stiffer["parameters"]["spring.2.k"], 8e4);
    assert_ne!(plain["stats"]["steps"], stiffer["stats"]["steps"]);
    // A path that names no number of the file is refused, naming it.
    for (path, message) in [
        ("body.rotor.m=1", "no [[body]] is named \"rotor\""),
        ("contact.pad.sigma=1", "model `stribeck` does not read it"),
    ] {
        let e = rejected(&["simulate", "--system", "examples/brake.toml", "--set", path]);
        assert!(e.contains(message), "{path}: {e}");
    }
}

/// `--figure-size` and `--dpi` set every figure's size: a PNG of the figure's inches times its
/// resolution (a legend beside the plot widens it), an SVG stating its size in inches; a bad
/// value exits 2 naming the option, the value and the allowed range, and writes nothing.
#[test]
fn figures_take_the_size_and_resolution_asked_for() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("belt");
    let run = |extra: &[&str]| {
        let mut args = vec!["simulate", "belt", "--model", "CS", "--t-end", "5"];
        args.extend(extra);
        args.extend(["--out", out.to_str().unwrap()]);
        friction_lab(&args)
    };
    let o = run(&["--figure-size", "3.5x2.6", "--dpi", "300"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut pngs = 0;
    for entry in std::fs::read_dir(&out).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if name.ends_with(".png") {
            let bytes = std::fs::read(&path).unwrap();
            let word = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
            assert_eq!(word(20), 780, "{name}: 2.6 in at 300 dpi");
            assert!(word(16) >= 1050, "{name}: {} px wide", word(16));
            pngs += 1;
        }
        if name.ends_with(".svg") {
            let text = std::fs::read_to_string(&path).unwrap();
            assert!(
                text.starts_with("<svg width=\"") && text.contains("height=\"2.6in\""),
                "{name}"
            );
        }
    }
    assert!(pngs >= 5, "{pngs} figures");
    let history = std::fs::read(out.join("history-v.png")).unwrap();
    assert_eq!(
        u32::from_be_bytes(history[16..20].try_into().unwrap()),
        1050
    );
    std::fs::remove_dir_all(&out).unwrap();
    for (args, message) in [
        (
            &["--figure-size", "3x30"][..],
            "--figure-size 3x30: the height 30 in is outside [1.5, 20] in",
        ),
        (&["--dpi", "-5"][..], "--dpi -5: outside [50, 1200]"),
        (
            &["--figure-size", "wide"][..],
            "expected WIDTHxHEIGHT in inches",
        ),
    ] {
        let o = run(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(stderr(&o).contains(message), "{args:?}: {}", stderr(&o));
        assert!(!out.exists(), "{args:?} wrote nothing");
    }
}

/// A rig has a spectrum of its velocity: a viscously damped oscillator's dominant frequency is
/// its damped natural frequency √(k/m − (μ_v/2m)²)/2π. `--window T0:T1` draws the figures over
/// that span and measures the spectrum there, the data files keeping the whole run; a window
/// outside the run exits 2.
#[test]
fn a_rigs_spectrum_finds_its_frequency_and_a_window_draws_a_span() {
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let mut args = vec!["simulate", "free-vibration", "--model", "viscous"];
        args.extend(extra);
        args.extend(["--out", out.to_str().unwrap()]);
        (friction_lab(&args), out)
    };
    let json = |path: std::path::PathBuf| -> serde_json::Value {
        serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
    };
    let (o, whole) = run("whole", &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("body: dominant frequency"));
    let spectrum = json(whole.join("spectrum.json"));
    assert_eq!(
        (spectrum["from"].as_f64(), spectrum["to"].as_f64()),
        (Some(5.0), Some(10.0))
    );
    let (m, k, mu_v) = (1.0f64, 100.0f64, 0.5f64);
    let damped = (k / m - (mu_v / (2.0 * m)).powi(2)).sqrt() / (2.0 * std::f64::consts::PI);
    let found = spectrum["bodies"][0]["dominant_frequency"]
        .as_f64()
        .unwrap();
    let resolution = spectrum["resolution"].as_f64().unwrap();
    assert!(
        (found - damped).abs() <= 0.1 * resolution,
        "{found} Hz against {damped} Hz (resolution {resolution} Hz)"
    );
    let (o, window) = run("window", &["--window", "2:4"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let spectrum = json(window.join("spectrum.json"));
    assert_eq!(
        (spectrum["from"].as_f64(), spectrum["to"].as_f64()),
        (Some(2.0), Some(4.0))
    );
    let svg = std::fs::read_to_string(window.join("history-v.svg")).unwrap();
    assert!(svg.contains("t = 2…4 s"), "the title names the window");
    let trajectory = std::fs::read_to_string(window.join("trajectory.csv")).unwrap();
    assert_eq!(
        trajectory.lines().last(),
        std::fs::read_to_string(whole.join("trajectory.csv"))
            .unwrap()
            .lines()
            .last(),
        "the data keep the whole run"
    );
    // A sweep measures settled parts, not spans of time: a window is refused, not ignored.
    let sweep = dir.path().join("sweep");
    let o = friction_lab(&[
        "sweep",
        "belt",
        "--model",
        "CS",
        "--grid",
        "k=50,100",
        "--window",
        "1:2",
        "--out",
        sweep.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("option `--window` = 1:2 applies to simulate"),
        "{}",
        stderr(&o)
    );
    let (o, out) = run("outside", &["--window", "4:12"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--window 4:12: allowed 0 <= T0 < T1 <= 10 s"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
}

#[test]
fn a_system_given_as_json_text_runs_as_the_same_file_does() {
    let dir = tempfile::tempdir().unwrap();
    let json = r#"{"body": [{"name": "block", "m": 1.0}], "anchor": [{"name": "wall"}],
        "spring": [{"between": ["wall", "block"], "k": 100.0}],
        "contact": [{"body": "block", "model": "CS", "surface_velocity": 0.1}]}"#;
    let file = dir.path().join("belt.json");
    std::fs::write(&file, json).unwrap();
    let final_state = |system: &str, out: &str| {
        let out = dir.path().join(out);
        let o = friction_lab(&[
            "simulate",
            "--system",
            system,
            "--t-end",
            "5",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read_to_string(out.join("final.csv")).unwrap()
    };
    let from_file = final_state(file.to_str().unwrap(), "file");
    assert_eq!(final_state(json, "text"), from_file);
    assert!(from_file.lines().count() == 2, "{from_file}");
    // Its errors say where the system came from.
    let e = rejected(&[
        "simulate",
        "--system",
        r#"{"body": [{"name": "b", "mass": 1}]}"#,
    ]);
    assert!(
        e.contains("system (given as JSON): unknown field `mass`"),
        "{e}"
    );
}

#[test]
fn compare_writes_its_tables_and_refuses_a_scheme_option() {
    // compare runs every scheme: a --switching or --scheme would choose one, and is refused
    // by name with exit code 2, nothing written.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c");
    for option in [
        ["--switching", "regularized"],
        ["--scheme", "time-stepping"],
    ] {
        let mut args = vec![
            "compare",
            "belt",
            "--model",
            "CS",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend(option);
        let o = friction_lab(&args);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let expected = format!("option `{}` does not apply to compare", option[0]);
        assert!(stderr(&o).contains(&expected), "{}", stderr(&o));
        assert!(!out.exists());
    }
    // The chain at rest for its first 2 s: no motion to compare on, said so, exit 2.
    let o = friction_lab(&[
        "compare",
        "chain",
        "--model",
        "CS",
        "--t-end",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("does not move on [0, 2] s"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
    let o = friction_lab(&[
        "compare",
        "belt",
        "--model",
        "SV",
        "--event-solvers",
        "dopri5,bdf",
        "--regularized-solvers",
        "bdf",
        "--epsilons",
        "1e-2,1e-3,1e-4",
        "--tol-list",
        "1e-3,1e-4,1e-5",
        "--targets",
        "1e-2,1e-4",
        "--repeats",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let cost = std::fs::read_to_string(out.join("compare-cost.csv")).unwrap();
    // Two targets, five schemes (dopri5 and bdf with events, bdf regularised, dopri5 naive,
    // Moreau–Jean).
    assert_eq!(cost.lines().count(), 1 + 2 * 5, "{cost}");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("at 1e-4: dopri5 (event) cheapest"),
        "{stdout}"
    );
    for f in [
        "compare.csv",
        "compare-epsilon.csv",
        "compare.json",
        "compare.png",
        "compare-epsilon.png",
    ] {
        assert!(out.join(f).exists(), "{f}");
    }
}

/// `orbit` finds the stick–slip cycle of the belt with the static law (m = 1 kg, k = 100 N/m,
/// c = 0, v_belt = 0.05 m/s, F_s = 7.5 N, F_c = 6 N) by shooting: its period against the
/// closed form (a harmonic slip arc about F_c/k turning by 2π − 2·atan(d/u), d = (F_s − F_c)/k,
/// u = v_belt/ω, and a stick phase 2d/v_belt long), its multipliers {1, 0} (the stick phase
/// collapses the velocity), its two switches. Options that do not apply are refused; a run
/// that settles onto no cycle says so, exit 1.
#[test]
fn orbit_finds_the_stick_slip_cycle_with_its_closed_form_period_and_multipliers() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("orbit");
    let o = friction_lab(&[
        "orbit",
        "belt",
        "--model",
        "static",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("orbit.json")).unwrap()).unwrap();
    let (omega, d, v_belt) = (10.0_f64, 0.015_f64, 0.05);
    let u = v_belt / omega;
    let exact = (2.0 * std::f64::consts::PI - 2.0 * (d / u).atan()) / omega + 2.0 * d / v_belt;
    let period = summary["period"].as_f64().unwrap();
    assert!((period - exact).abs() < 1e-9, "{period} vs {exact}");
    assert!(summary["residual"].as_f64().unwrap() <= 1e-10, "{summary}");
    let mu = summary["floquet"]["multipliers"].as_array().unwrap();
    assert_eq!(mu.len(), 2, "{summary}");
    let modulus = |m: &serde_json::Value| m[0].as_f64().unwrap().hypot(m[1].as_f64().unwrap());
    assert!((mu[0][0].as_f64().unwrap() - 1.0).abs() < 1e-9, "{summary}");
    assert!(modulus(&mu[1]) < 1e-9, "{summary}");
    assert_eq!(summary["floquet"]["stability"], "stable");
    let switches: Vec<&str> = (summary["segments"].as_array().unwrap().iter())
        .filter_map(|s| s["ends_with"].as_str())
        .collect();
    assert_eq!(switches.len(), 2, "{summary}");
    assert!(switches.contains(&"v_rel=0"), "{switches:?}");
    // The orbit sampled closes on itself.
    let csv = std::fs::read_to_string(out.join("orbit.csv")).unwrap();
    let rows: Vec<Vec<f64>> = (csv.lines().skip(1))
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 401);
    let (first, last) = (&rows[0], &rows[400]);
    assert!((last[0] - period).abs() < 1e-12, "{last:?}");
    assert!((first[1] - last[1]).abs() < 1e-9 && (first[2] - last[2]).abs() < 1e-9);
    // The servo's hunting cycle with the static law: the orbit's period against the cycle its
    // 200 s run settled onto (a multiplier of 7.9e-3 a cycle: settled to rounding within a few
    // of its 38.2 s cycles), two stick phases a cycle, stable.
    let servo = dir.path().join("servo");
    let o = friction_lab(&[
        "orbit",
        "servo",
        "--model",
        "static",
        "--t-end",
        "200",
        "--out",
        servo.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let hunting: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(servo.join("orbit.json")).unwrap()).unwrap();
    let (period, settled) = (
        hunting["period"].as_f64().unwrap(),
        hunting["guessed_period"].as_f64().unwrap(),
    );
    assert!((period - 38.2413).abs() < 1e-3, "{hunting}");
    assert!(
        (period - settled).abs() < 1e-6 * period,
        "{period} vs {settled}"
    );
    let mu = hunting["floquet"]["multipliers"].as_array().unwrap();
    assert!((modulus(&mu[1]) - 7.85e-3).abs() < 1e-4, "{hunting}");
    assert_eq!(hunting["floquet"]["stability"], "stable");
    // What does not apply is refused; no cycle is a failure that says why.
    let refused = |args: &[&str], message: &str| {
        let o = friction_lab(&[args, &["--out", dir.path().join("r").to_str().unwrap()]].concat());
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(message), "{args:?}: {}", stderr(&o));
    };
    refused(
        &[
            "orbit",
            "belt",
            "--model",
            "CS",
            "--scheme",
            "time-stepping",
        ],
        "option `--scheme` does not apply to orbit",
    );
    refused(
        &["orbit", "oscillation", "--model", "CS"],
        "imposes a motion on its contact: it has no body",
    );
    refused(
        &["orbit", "belt", "--model", "CS", "--samples", "1"],
        "`--samples` = 1",
    );
    let o = friction_lab(&[
        "orbit",
        "belt",
        "--model",
        "viscous",
        "--out",
        dir.path().join("steady").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("settles onto no cycle with switches"),
        "{}",
        stderr(&o)
    );
}

/// `continue` follows the belt's branches over v_belt. With the static law (c = 0) every cycle's
/// period is the closed form of `orbit`'s test at its own v_belt. With CVS the steady sliding
/// loses stability where the damping c + F'(v_belt) crosses zero (c = 0: where the Stribeck
/// drop's slope and the viscous term cancel, found here by bisection on the law's own ∂F/∂v):
/// the Hopf point, to 1e-8; its stick–slip cycle's branch ends where the stick phase vanishes.
#[test]
fn continue_follows_the_belts_cycles_and_finds_the_hopf_point_of_steady_sliding() {
    use friction_models::{Direction, FrictionParams, ModelId, SignLaw, Variant};
    let dir = tempfile::tempdir().unwrap();
    let run = |model: &str, range: &str| {
        let out = dir.path().join(model);
        let o = friction_lab(&[
            "continue",
            "belt",
            "--model",
            model,
            "--parameter",
            "v_belt",
            "--range",
            range,
            "--at",
            "0.5",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let read = |file: &str| -> Vec<Vec<String>> {
            (std::fs::read_to_string(out.join(file)).unwrap().lines())
                .map(|l| l.split(',').map(str::to_string).collect())
                .collect()
        };
        (read("branch.csv"), read("special_points.csv"))
    };
    let (rows, _) = run("static", "0.02:0.5");
    assert_eq!(
        rows[0][..5],
        ["kind", "v_belt", "at", "period", "amplitude"]
    );
    let cycles: Vec<&Vec<String>> = rows.iter().filter(|r| r[0] == "cycle").collect();
    assert!(cycles.len() >= 5, "{rows:?}");
    let (omega, d) = (10.0_f64, 0.015_f64);
    for r in &cycles {
        let v_belt: f64 = r[1].parse().unwrap();
        let exact = (2.0 * std::f64::consts::PI - 2.0 * (d * omega / v_belt).atan()) / omega
            + 2.0 * d / v_belt;
        let period: f64 = r[3].parse().unwrap();
        assert!(
            (period - exact).abs() < 1e-8,
            "{v_belt}: {period} vs {exact}"
        );
        assert_eq!(r[7], "stick slip- stick", "{r:?}");
    }
    // CVS: the Hopf point where F'(v_belt) = 0 (the belt has no damper).
    let law = ModelId::Cvs
        .build(Variant::Odd, &FrictionParams::paper())
        .unwrap();
    let slope = |v: f64| law_slope(&*law, v, SignLaw::Frozen(Direction::Positive));
    let (mut lo, mut hi) = (0.15, 0.3);
    assert!(slope(lo) < 0.0 && slope(hi) > 0.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if slope(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (rows, special) = run("CVS", "0.02:3");
    let hopf: Vec<f64> = (special.iter())
        .filter(|r| r[0] == "hopf")
        .map(|r| r[2].parse().unwrap())
        .collect();
    assert_eq!(hopf.len(), 1, "{special:?}");
    assert!((hopf[0] - lo).abs() < 1e-8, "Hopf at {} vs {lo}", hopf[0]);
    // The stick–slip branch ends where its stick phase vanishes (a grazing–sliding
    // bifurcation), at 0.8186 m/s: steady sliding and stick–slip coexist in between.
    let ends: Vec<f64> = (special.iter())
        .filter(|r| r[0] == "segments-change" && r[1] == "cycle")
        .map(|r| r[2].parse().unwrap())
        .collect();
    assert!(
        ends.len() == 1 && (ends[0] - 0.8186).abs() < 1e-3,
        "{special:?}"
    );
    // Unstable below it, stable above.
    for r in rows.iter().filter(|r| r[0] == "equilibrium") {
        let v: f64 = r[1].parse().unwrap();
        if (v - lo).abs() > 1e-3 {
            assert_eq!(r[6], (v > lo).to_string(), "{r:?}");
        }
    }
    // The row asked for at v_belt = 0.5 is the orbit `orbit` finds there from its own run.
    let at: Vec<&Vec<String>> = (rows.iter())
        .filter(|r| r[0] == "cycle" && r[2] == "true")
        .collect();
    assert!(at.len() == 1 && at[0][1] == "0.5", "{at:?}");
    let out = dir.path().join("orbit-0.5");
    let o = friction_lab(&[
        "orbit",
        "belt",
        "--model",
        "CVS",
        "--set",
        "v_belt=0.5",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let orbit: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("orbit.json")).unwrap()).unwrap();
    let period: f64 = at[0][3].parse().unwrap();
    assert!(
        (period - orbit["period"].as_f64().unwrap()).abs() < 1e-9,
        "{period} vs {orbit}"
    );
}

/// ∂F/∂v of `law` at v under the sign law `sign`.
fn law_slope(
    law: &dyn friction_models::FrictionModel,
    v: f64,
    sign: friction_models::SignLaw,
) -> f64 {
    law.partials(0.0, v, &[], sign, &mut []).force_dv
}

/// The servo's hunting cycle with the static law followed over ki from 4 to 0.5: stable all
/// along (stiction above the Coulomb level makes integral action hunt at every gain), its
/// period growing as ki falls, from the 38.24 s of the default gains. Without a moving surface
/// there is no steady sliding to follow, and the notes say so.
#[test]
fn continue_follows_the_servos_hunting_cycle_over_the_integral_gain() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ki");
    let o = friction_lab(&[
        "continue",
        "servo",
        "--model",
        "static",
        "--t-end",
        "200",
        "--parameter",
        "ki",
        "--range",
        "4:0.5",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let printed = String::from_utf8_lossy(&o.stdout);
    assert!(printed.contains("no steady sliding"), "{printed}");
    let csv = std::fs::read_to_string(out.join("branch.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert!(
        rows.iter().all(|r| r[0] == "cycle" && r[6] == "true"),
        "{csv}"
    );
    let (ki, period): (Vec<f64>, Vec<f64>) = (rows.iter())
        .map(|r| (r[1].parse::<f64>().unwrap(), r[3].parse::<f64>().unwrap()))
        .unzip();
    assert!((period[0] - 38.2413).abs() < 1e-3, "{}", period[0]);
    assert!(
        *ki.last().unwrap() < 0.5,
        "the branch reached the end of the range: {ki:?}"
    );
    assert!(period.windows(2).all(|w| w[1] > w[0]), "{period:?}");
}

/// `closed-loop` on one's own loop: the servo at the 1995 gains hunts as `reproduce` finds it,
/// beside the describing function's cycle; one's own gains change the regime; a system file's
/// loop is analysed, and told why it is not predicted where it is not of the describing
/// function's form; a loop without a controller and bad points are refused; an unsettled loop
/// warns.
#[test]
fn closed_loop_measures_ones_own_loop_beside_the_describing_function() {
    let dir = tempfile::tempdir().unwrap();
    let json = |out: &std::path::Path| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(out.join("closed-loop.json")).unwrap())
            .unwrap()
    };
    // The 1995 example with the static law: Table 2's hunting run and the prediction of
    // docs/closed-loop.md (38.24 s simulated, 11.94 s predicted).
    let out = dir.path().join("static");
    let o = friction_lab(&[
        "closed-loop",
        "servo",
        "--model",
        "static",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let j = json(&out);
    assert_eq!(j["regime"], "Hunting", "{j}");
    let period = j["simulated"]["period"].as_f64().unwrap();
    assert!((period - 38.24).abs() < 0.01, "{period}");
    let predicted = j["predicted"][0]["period"].as_f64().unwrap();
    assert!((predicted - 11.94).abs() < 0.01, "{predicted}");
    assert_eq!(j["pid"]["ki"], 4.0);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("a cycle of period 11.94"), "{text}");
    for file in [
        "closed-loop.csv",
        "closed-loop-predicted.csv",
        "closed-loop-error.png",
    ] {
        assert!(out.join(file).exists(), "{file}");
    }
    // Without integral action: kp·1 m = 3 N never breaks the body away (F_s = 7.5 N), it is
    // stuck; kp = 20 N/m moves it, and it stops off its set point, within F_s/kp = 0.375 m:
    // the dead zone. The describing function (a PD holds no cycle) predicts none.
    for (gains, regime) in [
        (vec!["--set", "ki=0"], "Stuck"),
        (vec!["--set", "ki=0", "--set", "kp=20"], "DeadZone"),
    ] {
        let out = dir.path().join(format!("pd-{}", gains.len()));
        let mut args = vec!["closed-loop", "servo", "--model", "static"];
        args.extend(gains.iter().copied());
        args.extend(["--out", out.to_str().unwrap()]);
        let o = friction_lab(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let j = json(&out);
        assert_eq!(j["regime"], regime, "{gains:?}: {j}");
        assert_eq!(j["predicted"].as_array().unwrap().len(), 0, "{j}");
        let off = j["simulated"]["final_error"].as_f64().unwrap().abs();
        match regime {
            "Stuck" => assert_eq!(off, 1.0, "{j}"),
            _ => assert!(off > 1e-6 && off <= 7.5 / 20.0, "{j}"),
        }
    }
    // A system file: with CS it hunts as `reproduce`'s CS plant does (39.9 s), held by a
    // spring it hunts slower; neither is predicted, and each says why.
    let loop_file = |extra: &str, model: &str| {
        let file = dir
            .path()
            .join(format!("servo-{model}-{}.toml", extra.len()));
        std::fs::write(
            &file,
            format!(
                "[[body]]\nname = \"mass\"\nm = 1.0\n{extra}[[contact]]\nbody = \"mass\"\n\
                 model = \"{model}\"\n[[controller]]\nbody = \"mass\"\nkp = 3.0\nki = 4.0\n\
                 kd = 6.0\nreference = {{ kind = \"constant\", x = 1.0 }}\n"
            ),
        )
        .unwrap();
        file
    };
    let spring = "[[anchor]]\nname = \"wall\"\n[[spring]]\nbetween = [\"wall\", \"mass\"]\n\
                  k = 1.0\nc = 0.0\n";
    for (extra, model, why, period) in [
        ("", "CS", "not of the Coulomb–stiction–viscous form", 39.88),
        (spring, "static", "a spring holds body mass", 46.89),
    ] {
        let out = dir.path().join(format!("system-{model}"));
        let file = loop_file(extra, model);
        let o = friction_lab(&[
            "closed-loop",
            "--system",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let j = json(&out);
        assert!(j["not_predicted"].as_str().unwrap().contains(why), "{j}");
        assert_eq!(j["regime"], "Hunting", "{j}");
        let simulated = j["simulated"]["period"].as_f64().unwrap();
        assert!((simulated - period).abs() < 0.01, "{model}: {simulated}");
    }
    // A system without a controller, and too few points: refused, nothing written.
    let file = dir.path().join("free.toml");
    std::fs::write(&file, "[[body]]\nname = \"mass\"\nm = 1.0\n").unwrap();
    let out = dir.path().join("refused");
    for (args, message) in [
        (
            vec!["--system", file.to_str().unwrap()],
            "has no controller",
        ),
        (
            vec!["servo", "--model", "static", "--points", "5"],
            "`--points` = 5 is out of range: allowed [101, 10000000]",
        ),
    ] {
        let mut all = vec!["closed-loop"];
        all.extend(args.iter().copied());
        all.extend(["--out", out.to_str().unwrap()]);
        let o = friction_lab(&all);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(message), "{args:?}: {}", stderr(&o));
        assert!(!out.exists(), "{args:?}");
    }
    // Ten seconds do not settle the loop: a note on stderr, with the measures.
    let out = dir.path().join("short");
    let o = friction_lab(&[
        "closed-loop",
        "servo",
        "--model",
        "static",
        "--t-end",
        "10",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("note: closed loop: not settled"),
        "{}",
        stderr(&o)
    );
    assert_eq!(json(&out)["regime"], "Unsettled");
}
