//! Fuzzes the two text parsers of friction-lab: the system file (TOML of bodies, anchors,
//! springs, contacts and forces) and the parameter file (`NAME = number` lines), then the
//! parameters through the same range checks as `--params`. Neither may panic or hang; every
//! rejection is an error value. Run from the repository root with a nightly toolchain:
//! `cargo fuzz run parsers fuzz/corpus/parsers fuzz/seeds`.
#![no_main]

use friction_lab::friction_models::{FrictionParams, Parameters};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(system) = friction_lab::friction_systems::file::parse(text) {
        // A file that parses declares a valid system.
        assert!(system.validate().is_ok());
    }
    if let Ok(pairs) = friction_lab::params::parse_params(text) {
        let mut p = FrictionParams::paper();
        for (name, value) in pairs {
            let _ = p.set(&name, value);
        }
        assert!(p.validate().is_ok(), "set() keeps every parameter in range");
    }
});
