//! What the command line's options share beyond the library's declared settings
//! ([`friction_lab::settings`]): the help of a target argument.

/// The help of a target argument: the names in [`scenarios::SCENARIOS`] (the rigs the
/// argument takes, from the one registry of rigs), then `then` (the other targets).
pub fn scenario_help(what: &str, then: &str) -> String {
    format!(
        "{what}: {} (one contact each), {then}",
        scenarios::SCENARIOS.names().join(", ")
    )
}
