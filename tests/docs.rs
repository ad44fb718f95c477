//! The docs: the notes and tables committed in docs/ are what `reproduce` writes today, and
//! the docs and the help stand alone.

use std::process::Command;

#[test]
fn docs_copies_of_the_reproduction_are_up_to_date() {
    let dir = tempfile::tempdir().unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_friction-lab"))
        .args(["reproduce", "--out", dir.path().to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success());
    // Every figure it draws is laid out cleanly: no text below the tick size, cut short, out
    // of its canvas or on another.
    let mut faults = Vec::new();
    let mut figures = 0;
    for svg in files_under(dir.path(), &["svg"]) {
        figures += 1;
        let text = std::fs::read_to_string(&svg).unwrap();
        for fault in friction_lab::plot::layout_faults(&text) {
            faults.push(format!("{}: {fault}", svg.display()));
        }
    }
    assert!(figures > 50, "{figures} figures");
    assert!(faults.is_empty(), "{}", faults.join("\n"));
    for name in ["reproduction.md", "table2.md", "paper-experiment.md"] {
        let fresh = std::fs::read_to_string(dir.path().join(name)).unwrap();
        let committed =
            std::fs::read_to_string(format!("{}/docs/{name}", env!("CARGO_MANIFEST_DIR"))).unwrap();
        assert!(
            fresh == committed,
            "docs/{name} is stale: run `cargo run --release -- reproduce --out results && \
             cp results/reproduction.md results/table2.md results/paper-experiment.md docs/ && \
             cp results/figures/*.png docs/figures/`"
        );
    }
}

/// The files under `dir`, in every subfolder, whose name ends in one of `extensions`.
fn files_under(dir: &std::path::Path, extensions: &[&str]) -> Vec<std::path::PathBuf> {
    let mut found = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(d) = pending.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                pending.push(path);
            } else if (path.extension().and_then(|e| e.to_str()))
                .is_some_and(|e| extensions.contains(&e))
            {
                found.push(path);
            }
        }
    }
    found
}

#[test]
fn docs_options_is_every_commands_declared_options() {
    let fresh = friction_lab_cli::options_reference();
    let path = format!("{}/docs/options.md", env!("CARGO_MANIFEST_DIR"));
    if std::env::var_os("FRICTION_LAB_BLESS").is_some() {
        std::fs::write(&path, &fresh).unwrap();
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        fresh == committed,
        "docs/options.md is stale: run `FRICTION_LAB_BLESS=1 cargo test --test docs`"
    );
    // Every option of converge is there, with its default.
    assert!(fresh.contains("| `--dt-list` | `DT_LIST` | `0.02,0.01,0.005,0.0025` |"));
}

/// The text files of the repository a user reads: README.md, docs/, the sources (whose doc
/// comments become `--help` and the API docs), the Python package and the scripts.
fn readable_files() -> Vec<std::path::PathBuf> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = vec![root.join("README.md"), root.join("Cargo.toml")];
    for dir in [
        "docs",
        "src",
        "crates",
        "python/src",
        "python/friction_lab",
        "scripts",
    ] {
        files.extend(files_under(&root.join(dir), &["rs", "md", "py", "toml"]));
    }
    files
}

#[test]
fn the_docs_and_the_help_name_no_file_outside_the_repository() {
    // A clone has no `shared/` folder beside it: the docs say everything themselves.
    let outside = |text: &str| text.contains("shared/spec") || text.contains("shared/paper");
    let files = readable_files();
    assert!(files.len() > 100, "{} files read", files.len());
    let named: Vec<String> = files
        .iter()
        .filter(|p| outside(&std::fs::read_to_string(p).unwrap()))
        .map(|p| p.display().to_string())
        .collect();
    assert!(named.is_empty(), "{named:?}");
    let commands: Vec<String> = friction_lab_cli::command()
        .get_subcommands()
        .map(|c| c.get_name().to_string())
        .collect();
    assert!(
        commands.iter().any(|c| c == "simulate") && commands.iter().any(|c| c == "reproduce"),
        "{commands:?}"
    );
    for command in commands {
        let o = Command::new(env!("CARGO_BIN_EXE_friction-lab"))
            .args([command.as_str(), "--help"])
            .output()
            .unwrap();
        let help = String::from_utf8(o.stdout).unwrap();
        assert!(help.contains("Usage:"), "{command}: {help}");
        assert!(!outside(&help), "{command} --help: {help}");
    }
}

#[test]
fn docs_scenarios_gives_every_rig_with_its_equation() {
    use friction_lab::scenarios::Scenario;
    let text = std::fs::read_to_string(format!("{}/docs/scenarios.md", env!("CARGO_MANIFEST_DIR")))
        .unwrap();
    for s in Scenario::ALL {
        let row = format!("| `{}` | {} |", s.name(), s.equation());
        assert!(text.contains(&row), "docs/scenarios.md lacks {row}");
    }
}

#[test]
fn the_help_lists_the_registered_rigs_and_solvers() {
    let help = |command: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_friction-lab"))
            .args([command, "--help"])
            .output()
            .unwrap();
        String::from_utf8(o.stdout).unwrap()
    };
    let rigs = friction_lab::scenarios::SCENARIOS.names().join(", ");
    let solvers: Vec<&str> = friction_lab::integrators::Solver::ALL
        .iter()
        .map(|s| s.name())
        .collect();
    for command in ["simulate", "sweep", "converge", "independence", "stiffness"] {
        let text = help(command);
        assert!(
            text.contains(&rigs),
            "{command} --help lacks `{rigs}`: {text}"
        );
        assert!(
            text.contains(&solvers.join(", ")),
            "{command} --help lacks the solvers {solvers:?}: {text}"
        );
    }
}
