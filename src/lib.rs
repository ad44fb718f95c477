//! The `friction-lab` command line: its options (clap) and one call into the library
//! [`friction_lab`] per command, whose files it writes and whose messages it prints.

pub mod commands;

use clap::{Parser, Subcommand};
use friction_lab::error::{as_option, spell_fields, AppError, ErrorKind};
use friction_lab::made::Made;
use friction_lab::provenance::shell_line;
use friction_lab::study::solver_studies::{NamedStudy, STUDIES};
use friction_lab::trajectory::RecordAs;
use friction_lab::{destination, ranges};

/// The exit codes, as `--help` lists them.
pub const EXIT_CODES: &str = "Exit codes:
    0  success
    1  a run failed (solver error, step or time limit): the files written keep what was
       computed and summary.json says where and why; or writing the output failed
    2  bad input (an option, a parameter, a file, the output folder): nothing was run or
       written
  130  stopped by Ctrl-C, SIGTERM or SIGHUP: the runs in progress end at their next step and
       the files keep what was computed, as for 1, marked partial (`status: stopped` in their
       .friction-lab-output) and written beside --out as <out>.stopped where it holds a
       complete result (a second signal quits, writing nothing)";

/// Dry-friction models and the solvers that integrate them.
#[derive(Parser, Debug)]
#[command(name = "friction-lab", version, about, long_about = None, after_help = EXIT_CODES)]
pub struct Cli {
    /// The command to run.
    #[command(subcommand)]
    pub command: Command,
    /// Size of a one-panel figure in inches, WIDTHxHEIGHT (default 3.5x2.6, a journal's
    /// column; 6x4 a page): the text keeps its size in points, so a smaller figure is a denser
    /// one; panels side by side each take this size.
    #[arg(long, global = true, value_name = "WxH", allow_hyphen_values = true)]
    pub figure_size: Option<String>,
    /// Resolution of the PNG figures, pixels per inch (default 300, for print; 150 on screen).
    /// SVG figures state their size in inches and scale without it.
    #[arg(long, global = true, value_name = "DPI", allow_hyphen_values = true)]
    pub dpi: Option<f64>,
    /// Replace the output folder even where it now holds files friction-lab did not write
    /// (they are deleted with it); without it such a folder is refused.
    #[arg(long, global = true)]
    pub replace: bool,
}

pub use friction_lab::delivery::Delivery;

/// The commands of `friction-lab` (README.md describes each).
#[derive(Subcommand, Debug)]
pub enum Command {
    /// List every friction model with its equation, its parameters and the named sets.
    #[command(after_help = EXIT_CODES)]
    Models {
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Draw one friction curve: force against velocity, or against displacement under the
    /// paper's prescribed motion (DV, SD, SV, dahl).
    #[command(after_help = EXIT_CODES)]
    Curve(commands::Writing<friction_lab::curve::CurveRequest>),
    /// Integrate one scenario: trajectory.csv, summary.json and figures.
    #[command(after_help = EXIT_CODES)]
    Simulate(commands::Writing<friction_lab::simulate::SimulationRequest>),
    /// Decide Table 2 by simulation, beside the paper's table.
    #[command(after_help = EXIT_CODES)]
    Phenomena(commands::Writing<friction_lab::study::PhenomenaRequest>),
    /// Sweep a rig, the chain or a system file over a grid of parameters: the settled state at every point
    /// (stick phases per cycle, amplitude and period, friction, solver statistics).
    #[command(after_help = EXIT_CODES)]
    Sweep(commands::Writing<friction_lab::sweep::SweepRequest>),
    /// Run one problem of the standard stiff test set (van-der-pol, robertson, hires, orego,
    /// pollution): the state at the end time and the significant correct digits against its
    /// published reference.
    #[command(after_help = EXIT_CODES)]
    Testset(commands::Writing<friction_lab::testset::TestSetRequest>),
    /// Reproduce the paper into one folder: Figures 2-7 with notes, the experiment, Table 2,
    /// the solver studies, and a report.md that links them.
    #[command(after_help = EXIT_CODES)]
    Reproduce(commands::Writing<friction_lab::reproduce::ReproduceRequest>),
}

/// The process exit code of a failed command (as `--help` lists them, [`EXIT_CODES`]): 2 for
/// bad input, 1 for a failure while running, 130 for a command stopped by a signal before it
/// computed anything.
pub fn exit_code(e: &AppError) -> i32 {
    match e.kind() {
        ErrorKind::BadInput => 2,
        ErrorKind::Failed => 1,
        ErrorKind::Stopped => 130,
    }
}

/// A parsed command line: the line itself, and what it asks for.
pub struct Invocation {
    /// The words as typed, as one line ([`shell_line`]; the program by its file name).
    pub line: String,
    /// What it asks for.
    pub request: Request,
}

/// What a command line asks for: one of [`Cli`]'s commands, or a named study ([`STUDIES`])
/// with its options.
pub enum Request {
    /// A command [`Cli`] declares.
    Command(Box<Cli>),
    /// A study of [`STUDIES`], built in or registered.
    Study(StudyInvocation),
}

/// A study as the command line asked for it.
pub struct StudyInvocation {
    /// The study.
    pub study: NamedStudy,
    /// Its options, parsed by its declaration.
    pub matches: clap::ArgMatches,
    /// The folder its files go to.
    pub out: std::path::PathBuf,
    /// `--figure-size`.
    pub figure_size: Option<String>,
    /// `--dpi`.
    pub dpi: Option<f64>,
    /// `--replace`.
    pub replace: bool,
}

/// The whole command line: [`Cli`]'s commands, and a command for each study in [`STUDIES`]
/// (built in or registered) with the study's declared options and `--out`; an option's value
/// may start with a hyphen.
pub fn command() -> clap::Command {
    use clap::{Args, CommandFactory};
    (STUDIES.all().into_iter())
        .fold(Cli::command(), |cli, study| {
            // `--out` as every command declares it ([`commands::Writing`]), then the study's
            // options; `about` last: a request's own doc comment would replace it.
            let out = commands::Writing::<commands::Nothing>::augment_args(clap::Command::new(
                study.name(),
            ));
            let command = study.declare(out);
            cli.subcommand(command.about(study.about()).after_help(EXIT_CODES))
        })
        // An option's value may start with a hyphen, so that `--t-end -1` or `--model -x` reaches
        // the option's own message (its range, the known names) instead of clap's "unexpected
        // argument '-1'". Positional arguments keep clap's reading: a mistyped option there is
        // still told apart, with its nearest spelling.
        .mut_subcommands(|c| {
            c.mut_args(
                |a| match a.is_positional() || !a.get_action().takes_values() {
                    true => a,
                    false => a.allow_hyphen_values(true),
                },
            )
        })
}

/// Parses `words` (the program's name first) as [`command`] does.
pub fn parse_from<I, T>(words: I) -> Result<Invocation, clap::Error>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    use clap::FromArgMatches;
    let words: Vec<std::ffi::OsString> = words.into_iter().map(Into::into).collect();
    let mut typed: Vec<String> = (words.iter())
        .map(|w| w.to_string_lossy().into_owned())
        .collect();
    if let Some(program) = typed.first_mut() {
        let name = std::path::Path::new(program.as_str()).file_name();
        *program = name.map_or(String::new(), |n| n.to_string_lossy().into_owned());
    }
    let line = shell_line(&typed);
    let matches = command().try_get_matches_from(words)?;
    if let Some((name, options)) = matches.subcommand() {
        if let Some(study) = STUDIES.find(name) {
            let request = Request::Study(StudyInvocation {
                study,
                out: options
                    .get_one::<std::path::PathBuf>("out")
                    .cloned()
                    .unwrap_or_default(),
                matches: options.clone(),
                figure_size: matches.get_one::<String>("figure_size").cloned(),
                dpi: matches.get_one::<f64>("dpi").copied(),
                replace: matches.get_flag("replace"),
            });
            return Ok(Invocation { line, request });
        }
    }
    let cli = Cli::from_arg_matches(&matches)?;
    Ok(Invocation {
        line,
        request: Request::Command(Box::new(cli)),
    })
}

/// Runs a parsed command line ([`run`], or a study: [`run_study`]).
pub fn invoke(invocation: Invocation) -> Result<(), AppError> {
    match invocation.request {
        Request::Command(cli) => run(*cli, &invocation.line),
        Request::Study(study) => run_study(study, &invocation.line),
    }
}

/// Runs a named study, its figure format and output folder checked first, and writes its
/// files, their provenance naming the command line `line`.
pub fn run_study(s: StudyInvocation, line: &str) -> Result<(), AppError> {
    let delivery = Delivery::parse(s.figure_size.as_deref(), s.dpi, s.replace, line)?;
    destination::check(&s.out, delivery.replace)?;
    let _claim = destination::claim(&s.out)?;
    let threads = ranges::threads(s.study.threads(&s.matches)?)?;
    deliver(s.study.run(&s.matches, &s.out)?, &s.out, threads, delivery)
}

/// Runs one parsed command, its figure format and output folder checked first
/// ([`friction_lab::plot::Format::parse`], [`destination::check`]); its files' provenance
/// names the command line `line`.
pub fn run(cli: Cli, line: &str) -> Result<(), AppError> {
    let delivery = Delivery::parse(cli.figure_size.as_deref(), cli.dpi, cli.replace, line)?;
    let _claim = match cli.command.out_folder() {
        Some(out) => {
            destination::check(out, delivery.replace)?;
            Some(destination::claim(out)?)
        }
        None => None,
    };
    match &cli.command {
        Command::Models { json } => {
            if cli.figure_size.is_some() || cli.dpi.is_some() {
                return Err(AppError::Usage(
                    "--figure-size and --dpi: `models` draws no figure".into(),
                ));
            }
            commands::models::run(*json)
        }
        Command::Phenomena(args) => commands::phenomena::run(args, delivery),
        Command::Reproduce(args) => commands::reproduce::run(args, delivery),
        command => {
            let (out, threads) = command.destination();
            let threads = ranges::threads(threads)?;
            deliver(make(command)?, out, threads, delivery)
        }
    }
}

impl Command {
    /// The folder the command writes into (`models` writes none).
    fn out_folder(&self) -> Option<&std::path::Path> {
        match self {
            Command::Models { .. } => None,
            Command::Phenomena(a) => Some(&a.out),
            Command::Reproduce(a) => Some(&a.out),
            other => Some(other.destination().0),
        }
    }

    /// The output folder and `--threads` of a command that makes one run's or one study's
    /// files (the commands [`make`] runs).
    fn destination(&self) -> (&std::path::Path, Option<i64>) {
        match self {
            Command::Curve(a) => (&a.out, None),
            Command::Simulate(a) => (&a.out, None),
            Command::Sweep(a) => (&a.out, a.request.threads),
            Command::Testset(a) => (&a.out, None),
            Command::Phenomena(a) => (&a.out, a.request.threads),
            Command::Models { .. } | Command::Reproduce(_) => (std::path::Path::new("."), None),
        }
    }
}

/// Writes what a command made as the folder `out` (figures drawn in `format` on `threads`
/// threads, all cores when `None`), prints what was written and the notes, and returns the
/// failure.
pub fn deliver(
    made: Made,
    out: &std::path::Path,
    threads: Option<usize>,
    delivery: Delivery,
) -> Result<(), AppError> {
    let written = delivery.write(made.files, out, threads)?;
    println!("{}", written.line());
    for note in &made.notes {
        println!("{}", spell_fields(note, &as_option));
    }
    for warning in made.warnings.iter().chain(written.stop_note().iter()) {
        print_note(warning);
    }
    made.failure.map_or(Ok(()), Err)
}

/// Prints `warning` on stderr as a note, each option it names spelled as the command line
/// takes it (`--t-end`).
pub fn print_note(warning: &str) {
    eprintln!("note: {}", spell_fields(warning, &as_option));
}

/// Runs `curve`, `simulate`, a study, `sweep`, `testset` or `phenomena`, and keeps its files in memory
/// instead of writing them (figures undrawn): the command line writes them. `models` and
/// `reproduce` are refused here.
pub fn make(command: &Command) -> Result<Made, AppError> {
    match command {
        Command::Curve(args) => args.request.run(&args.out),
        Command::Simulate(args) => args.request.run(&args.out, RecordAs::Files),
        Command::Sweep(args) => args.request.run(&args.out),
        Command::Testset(args) => args.request.run(&args.out),
        Command::Phenomena(args) => args.request.run(&args.out),
        Command::Models { .. } | Command::Reproduce(_) => Err(AppError::Usage(
            "models and reproduce write no in-memory result".into(),
        )),
    }
}

/// The reference of every command's options as Markdown (`docs/options.md`), from their one
/// declaration: for each command its arguments and options with their value, default and help.
pub fn options_reference() -> String {
    let cli = command();
    let one_line = |text: String| text.split_whitespace().collect::<Vec<_>>().join(" ");
    let mut out = String::from(
        "# Options of every command\n\nEvery command's arguments and options, with their value, \
         default and meaning, as `friction-lab COMMAND --help` gives them: written from their one \
         declaration, the library's request types, which Python fills from its keyword arguments \
         too (the keyword of `--t-end` is `t_end`, of `--set` `params`). A test holds this page \
         equal to the declarations (`FRICTION_LAB_BLESS=1 cargo test --test docs` rewrites it).\n\n\
         Global options, taken by every command: `--figure-size WxH` (default 3.5x2.6, inches), \
         `--dpi DPI` (default 300), `--replace` (replace an output folder friction-lab wrote \
         even where it now holds files it did not write, deleting them; docs/inputs.md).\n",
    );
    for command in cli.get_subcommands() {
        out += &format!(
            "\n## `friction-lab {}`\n\n{}\n\n| argument or option | value | default | meaning |\n|---|---|---|---|\n",
            command.get_name(),
            one_line(command.get_about().map(|a| a.to_string()).unwrap_or_default())
        );
        for arg in command.get_arguments().filter(|a| !a.is_global_set()) {
            let id = arg.get_id().as_str();
            if matches!(id, "help" | "figure_size" | "dpi") {
                continue;
            }
            let name = match arg.get_long() {
                Some(long) => format!("`--{long}`"),
                None => format!(
                    "`{}`",
                    arg.get_value_names()
                        .map_or(id.to_string(), |v| v[0].to_string())
                ),
            };
            let value = match (arg.get_long(), arg.get_value_names()) {
                (Some(_), Some(names)) if arg.get_action().takes_values() => {
                    format!("`{}`", names[0].replace('|', "\\|"))
                }
                _ => String::new(),
            };
            let defaults: Vec<String> = (arg.get_default_values().iter())
                .map(|d| d.to_string_lossy().into_owned())
                .collect();
            let default = match defaults.is_empty() {
                true => String::new(),
                false => format!("`{}`", defaults.join(",")),
            };
            let help = one_line(arg.get_help().map(|h| h.to_string()).unwrap_or_default());
            out += &format!(
                "| {name} | {value} | {default} | {} |\n",
                help.replace('|', "\\|")
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {

    #[test]
    fn every_numeric_option_takes_a_value_that_begins_with_a_hyphen() {
        // A negative number must reach the option's own range check (docs/inputs.md), not
        // clap's "unexpected argument '-1'".
        let type_of = |parser: clap::builder::ValueParser| {
            clap::Arg::new("x")
                .value_parser(parser)
                .get_value_parser()
                .type_id()
        };
        let numeric = [
            type_of(clap::value_parser!(f64).into()),
            type_of(clap::value_parser!(i64).into()),
        ];
        let cli = super::command();
        let mut refused = Vec::new();
        for command in cli.get_subcommands() {
            for arg in command.get_arguments() {
                let Some(long) = arg.get_long() else {
                    continue;
                };
                if !numeric.contains(&arg.get_value_parser().type_id()) {
                    continue;
                }
                let option = format!("--{long}");
                let words = ["friction-lab", command.get_name(), &option, "-1e-3"];
                if let Err(e) = super::parse_from(words) {
                    if e.kind() == clap::error::ErrorKind::UnknownArgument {
                        refused.push(format!("{} {option}", command.get_name()));
                    }
                }
            }
        }
        assert!(refused.is_empty(), "{refused:?}");
    }
}
