//! The `friction-lab` command line; see `shared/spec/cli.md` and `friction-lab --help`.

use clap::Parser;

fn main() {
    let cli = friction_lab::Cli::parse();
    if let Err(e) = friction_lab::run(cli) {
        eprintln!("error: {e}");
        std::process::exit(e.exit_code());
    }
}
