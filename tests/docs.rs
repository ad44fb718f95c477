//! The reproduction notes committed in docs/ are what `reproduce` writes today.

use std::process::Command;

#[test]
fn docs_reproduction_md_is_up_to_date() {
    let dir = tempfile::tempdir().unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_friction-lab"))
        .args(["reproduce", "--out", dir.path().to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success());
    let fresh = std::fs::read_to_string(dir.path().join("reproduction.md")).unwrap();
    let committed =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/reproduction.md"))
            .unwrap();
    assert!(
        fresh == committed,
        "docs/reproduction.md is stale: run `cargo run --release -- reproduce --out results && \
         cp results/reproduction.md docs/ && cp results/figures/*.png docs/figures/`"
    );
}
