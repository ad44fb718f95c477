//! The closed loop from the command line: `simulate servo` reports the loop it ran, and
//! `sweep servo` maps hunting over controller and friction parameters.

use std::process::{Command, Output};

fn friction_lab(args: &[&str]) -> Output {
    let o = Command::new(env!("CARGO_BIN_EXE_friction-lab"))
        .args(args)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

fn json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

#[test]
fn simulate_servo_reports_the_hunting_cycle_and_sweep_maps_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("simulate");
    let o = friction_lab(&[
        "simulate",
        "servo",
        "--model",
        "static",
        "--out",
        out.to_str().unwrap(),
    ]);
    let printed = String::from_utf8(o.stdout).unwrap();
    assert!(
        printed.contains("closed loop: hunting, period 38.24"),
        "{printed}"
    );
    let summary = json(&out.join("summary.json"));
    let c = &summary["closed_loop"];
    assert_eq!(
        (&c["settled"], &c["hunting"]),
        (&true.into(), &true.into()),
        "{c}"
    );
    let period = c["period"].as_f64().unwrap();
    // A summary without a controller has no closed_loop at all.
    let belt = dir.path().join("belt");
    friction_lab(&[
        "simulate",
        "belt",
        "--model",
        "CS",
        "--out",
        belt.to_str().unwrap(),
    ]);
    assert!(json(&belt.join("summary.json"))
        .get("closed_loop")
        .is_none());

    // The hunting map: without integral action the body never moves (kp·1 m = 3 N < F_c):
    // stuck, 1 m off the set point, not converged; F_s = F_c (Coulomb alone) is a transient
    // under PID, stiction hunts.
    let map = dir.path().join("map");
    let args = [
        "sweep",
        "servo",
        "--model",
        "static",
        "--grid",
        "ki=0,4",
        "--grid",
        "F_s=6,7.5",
    ];
    friction_lab(&[&args[..], &["--out", map.to_str().unwrap()]].concat());
    let csv = std::fs::read_to_string(map.join("sweep.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    let col = |name: &str| rows[0].iter().position(|c| *c == name).unwrap();
    let regimes: Vec<&str> = rows[1..].iter().map(|r| r[col("regime")]).collect();
    assert_eq!(regimes, ["Stuck", "Stuck", "Unsettled", "Hunting"], "{csv}");
    assert_eq!(rows[1][col("final_error")], "1", "{csv}");
    // The hunting point is the simulated run: the same period.
    let swept: f64 = rows[4][col("period")].parse().unwrap();
    assert!(
        (swept - period).abs() < 1e-9 * period,
        "{swept} against {period}"
    );
    let svg = std::fs::read_to_string(map.join("sweep.svg")).unwrap();
    assert!(
        svg.contains("hunting (a limit cycle)") && svg.contains("stuck all along"),
        "{svg}"
    );
}

#[test]
fn the_servo_runs_lugre_at_its_papers_parameters_unless_told_otherwise() {
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let args = [
            &["simulate", "servo"][..],
            extra,
            &["--out", out.to_str().unwrap()],
        ]
        .concat();
        friction_lab(&args);
        json(&out.join("summary.json"))
    };
    let default = run("default", &[]);
    assert_eq!(default["model"], "lugre");
    assert_eq!(default["parameters"]["F_s"], 1.5);
    assert_eq!(default["closed_loop"]["hunting"], true);
    // A set named is the set read; a model named is read at the set named, or the paper's.
    assert_eq!(
        run("paper", &["--param-set", "paper"])["parameters"]["F_s"],
        7.5
    );
    let cs = run("cs", &["--model", "CS"]);
    assert_eq!(
        (&cs["model"], &cs["parameters"]["F_s"]),
        (&"CS".into(), &7.5.into())
    );
    // A solver study of the servo runs its default plant too.
    let study = dir.path().join("study");
    let args = [
        "independence",
        "servo",
        "--t-end",
        "2",
        "--solver",
        "bdf",
        "--out",
    ];
    friction_lab(&[&args[..], &[study.to_str().unwrap()]].concat());
    let described = json(&study.join("independence.json"))["case"]["description"].clone();
    assert_eq!(described, "servo with lugre (event switching)");
    // A rig without a law of its own still requires one.
    let o = Command::new(env!("CARGO_BIN_EXE_friction-lab"))
        .args([
            "simulate",
            "belt",
            "--out",
            dir.path().join("belt").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr)
        .contains("option `--model` is required for scenario belt"));
}

#[test]
fn a_system_file_with_a_controller_reports_its_loop_as_the_rig_does() {
    // The servo written as a system file: the same body, contact and PID as the rig.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("servo.toml");
    std::fs::write(
        &file,
        "param_set = \"paper\"\n\n[[body]]\nname = \"mass\"\nm = 1.0\n\n[[contact]]\nbody = \
         \"mass\"\nmodel = \"static\"\n\n[[controller]]\nbody = \"mass\"\nkp = 3.0\nki = 4.0\n\
         kd = 6.0\nreference = { kind = \"constant\", x = 1.0 }\n",
    )
    .unwrap();
    let (system, rig) = (dir.path().join("system"), dir.path().join("rig"));
    let o = friction_lab(&[
        "simulate",
        "--system",
        file.to_str().unwrap(),
        "--t-end",
        "800",
        "--points",
        "8001",
        "--out",
        system.to_str().unwrap(),
    ]);
    let printed = String::from_utf8(o.stdout).unwrap();
    assert!(printed.contains("closed loop: hunting"), "{printed}");
    friction_lab(&[
        "simulate",
        "servo",
        "--model",
        "static",
        "--points",
        "8001",
        "--out",
        rig.to_str().unwrap(),
    ]);
    let (a, b) = (
        json(&system.join("summary.json"))["closed_loop"].clone(),
        json(&rig.join("summary.json"))["closed_loop"].clone(),
    );
    assert_eq!(a["hunting"], true, "{a}");
    for key in ["period", "amplitude", "stick_time_per_cycle", "final_error"] {
        assert_eq!(a[key], b[key], "{key}: system {a}, rig {b}");
    }
    // Without a controller there is no loop to report.
    let plain = dir.path().join("plain");
    std::fs::write(
        &file,
        "param_set = \"paper\"\n\n[[body]]\nname = \"mass\"\nm = 1.0\nv0 = 1.0\n\n[[contact]]\n\
         body = \"mass\"\nmodel = \"coulomb\"\n",
    )
    .unwrap();
    friction_lab(&[
        "simulate",
        "--system",
        file.to_str().unwrap(),
        "--out",
        plain.to_str().unwrap(),
    ]);
    assert!(json(&plain.join("summary.json"))
        .get("closed_loop")
        .is_none());
}
