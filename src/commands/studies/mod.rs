//! The solver studies: `converge`, `independence`, `work-precision`, `stiffness`, each the
//! library's study of the same name ([`friction_lab::study::solver_studies`]).

use crate::commands::simulate::Target as Run;
use clap::Args;
use friction_lab::laws::ModelChoice;
use friction_lab::settings::{ModelSettings, RunLimits, SchemeChoice};
use friction_lab::simulate::Target;
use friction_lab::study::Problem;
use std::path::PathBuf;

mod converge;
mod independence;
mod stiffness;
mod work_precision;

pub use converge::ConvergeArgs;
pub use independence::IndependenceArgs;
pub use stiffness::StiffnessArgs;
pub use work_precision::WorkPrecisionArgs;

/// The problem a study runs.
#[derive(Args, Debug, Clone)]
pub struct CaseArgs {
    /// The rig (docs/scenarios.md) or the chain; omit it with --system (or, for
    /// work-precision, --testset).
    #[arg(
        help = crate::options::scenario_help(
            "The rig",
            "or chain (the Burridge–Knopoff chain of docs/systems.md, its parameters by --set); \
             omit it with --system (or, for work-precision, --testset)",
        ),
        value_name = "SCENARIO",
        conflicts_with = "system"
    )]
    pub scenario: Option<Run>,
    /// A system file (TOML or JSON, docs/systems.md) to study instead of a scenario.
    #[arg(long, value_name = "FILE.toml")]
    pub system: Option<PathBuf>,
    /// The friction model (scenarios and chain), as `friction-lab models` lists it, or a law
    /// registered by name (from Python: docs/python.md).
    #[arg(long, value_name = "MODEL")]
    pub model: Option<ModelChoice>,
    /// Systems: the bodies whose trajectories, event times and stick phases are measured
    /// (names or 1-based indices) [default: the first body]; the final state is measured on
    /// every body.
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    pub bodies: Vec<String>,
    /// The scheme, and the treatment of v = 0 under the event-driven one.
    #[command(flatten)]
    pub scheme: SchemeChoice,
    /// End time, s [default: the scenario's; 10 for the chain (its horizon of predictability:
    /// docs/studies.md); 20 for a system file].
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub t_end: Option<f64>,
    /// Folder to write into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The bounds of each run (a run past them fails, and the study says which).
    #[command(flatten)]
    pub limits: RunLimits,
    /// Worker threads (default: all cores; more than the machine has are capped to its cores).
    /// The results do not depend on it.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub threads: Option<i64>,
    /// The model's parameters and reading.
    #[command(flatten)]
    pub model_options: ModelSettings,
}

impl CaseArgs {
    /// The problem as the library takes it.
    pub fn problem(&self) -> Problem {
        let target = match (self.scenario, &self.system) {
            (Some(Run::Rig(scenario)), _) => Some(Target::Rig(scenario)),
            (_, Some(file)) => Some(Target::System(file.clone())),
            (Some(Run::Chain), None) => Some(Target::Chain),
            (None, None) => None,
        };
        Problem {
            target,
            model: self.model.clone(),
            bodies: self.bodies.clone(),
            scheme: self.scheme,
            t_end: self.t_end,
            limits: self.limits,
            threads: self.threads,
            model_settings: self.model_options.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::{Cli, Command};
    use clap::Parser;
    use friction_lab::study::{Converge, Independence, Stiffness, WorkPrecision};

    fn parsed(words: &[&str]) -> Command {
        let all = ["fl"].iter().chain(words).chain(&["--out", "x"]);
        Cli::try_parse_from(all).unwrap().command
    }

    #[test]
    fn the_studies_options_default_to_the_librarys_settings() {
        let Command::Converge(c) = parsed(&["converge", "belt"]) else {
            unreachable!()
        };
        let (given, library) = (c.study(), Converge::new(c.case.problem()));
        assert_eq!(
            (given.dt_list, given.tol_list),
            (library.dt_list, library.tol_list)
        );
        let Command::Independence(i) = parsed(&["independence", "belt"]) else {
            unreachable!()
        };
        let (given, library) = (i.study(), Independence::new(i.case.problem()));
        let (g, l) = (given.refinement, library.refinement);
        assert_eq!(
            (g.start, g.ratio, g.levels, g.tol),
            (l.start, l.ratio, l.levels, l.tol)
        );
        let Command::WorkPrecision(w) = parsed(&["work-precision", "belt"]) else {
            unreachable!()
        };
        let (given, library) = (w.study(), WorkPrecision::new(w.case.problem()));
        assert_eq!(given.dt_list, library.dt_list);
        assert_eq!(
            (given.tol_list, given.repeats),
            (library.tol_list, library.repeats)
        );
        let Command::Stiffness(s) = parsed(&["stiffness", "belt"]) else {
            unreachable!()
        };
        let (given, library) = (s.study(), Stiffness::new(s.case.problem()));
        assert_eq!(
            (&given.parameter, &given.values),
            (&library.parameter, &library.values)
        );
        assert_eq!(
            (given.target, given.dt_list),
            (library.target, library.dt_list)
        );
        assert_eq!(given.tol_list, library.tol_list);
    }
}
