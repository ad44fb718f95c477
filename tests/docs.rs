//! The notes and tables committed in docs/ are what `reproduce` writes today.

use std::process::Command;

#[test]
fn docs_copies_of_the_reproduction_are_up_to_date() {
    let dir = tempfile::tempdir().unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_friction-lab"))
        .args(["reproduce", "--out", dir.path().to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success());
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
