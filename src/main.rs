//! The `friction-lab` command line; README.md and `friction-lab --help` describe its commands.

use friction_lab::error::{as_option, bounded, spell_fields};
use friction_lab::integrators::interrupt;

/// The exit code of a command stopped by a signal (Ctrl-C, SIGTERM, SIGHUP): 128 + SIGINT's 2,
/// the shell's code for Ctrl-C.
const INTERRUPTED: i32 = 130;

/// Ctrl-C, SIGTERM or SIGHUP (a cluster's scheduler at the end of a job's time) asks every run
/// in progress to stop at its next step ([`interrupt::request`]): each ends as a run that
/// reaches a time limit does, keeping what it computed, and the command writes its files.
/// A second signal quits at once; the output folder is then left as it was (the temporary
/// folder is removed by the next run into the same parent folder).
fn stop_on_signal() {
    let handler = || {
        if interrupt::requested() {
            std::process::exit(INTERRUPTED);
        }
        interrupt::request();
        eprintln!(
            "\nfriction-lab: stopping: the runs in progress end at their next step and the \
             files keep what they computed (a second Ctrl-C quits at once, writing nothing)"
        );
    };
    // Without a handler (none can be installed) a signal ends the process as by default.
    let _ = ctrlc::set_handler(handler);
}

fn main() {
    let invocation = match friction_lab_cli::parse_from(std::env::args_os()) {
        Ok(invocation) => invocation,
        // --help and --version print as they are; a usage error with what was typed shortened
        // (error::bounded).
        Err(e) if !e.use_stderr() => e.exit(),
        Err(e) => {
            eprint!(
                "{}",
                bounded(&spell_fields(&e.render().to_string(), &as_option))
            );
            std::process::exit(e.exit_code());
        }
    };
    stop_on_signal();
    // Progress of long work: a bar on a terminal, a heartbeat line without one.
    friction_lab::progress::observe_with(std::sync::Arc::new(terminal::Terminal));
    let result = friction_lab_cli::invoke(invocation);
    if let Err(e) = &result {
        // A request's field as its option: `t_end` as `--t-end`.
        eprintln!("error: {}", bounded(&e.message(&as_option)));
    }
    if interrupt::requested() {
        std::process::exit(INTERRUPTED);
    }
    if let Err(e) = result {
        std::process::exit(friction_lab_cli::exit_code(&e));
    }
}
