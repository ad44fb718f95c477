//! The studies a front end names: each a request declared with clap and run into its files,
//! the four built-in solver studies ([`NamedStudy::ALL`]) and those a program registers
//! ([`NamedStudy::register`]), held in the registry [`STUDIES`]. The command line makes a
//! command of each and Python a call (`study(name, …)`), both from the study's own
//! declaration.

use super::{
    ClosedLoopRequest, CompareRequest, ContinueRequest, ConvergeRequest, IndependenceRequest,
    OrbitRequest, StiffnessRequest, WorkPrecisionRequest,
};
use crate::error::AppError;
use crate::made::Made;
use clap::{ArgMatches, Args, FromArgMatches};
use std::marker::PhantomData;
use std::path::Path;

/// A study a front end names: its options, declared once, and how the request they make runs.
pub trait StudyRequest: Send + Sync {
    /// The name the command line takes (`work-precision`; Python's `work_precision`).
    fn name(&self) -> &'static str;

    /// What it does, in one line (the command's `--help`).
    fn about(&self) -> &'static str;

    /// `command` with the study's options added (its request's `clap::Args`).
    fn declare(&self, command: clap::Command) -> clap::Command;

    /// The request the parsed options `matches` make, checked and run, its files in `out` (in
    /// memory).
    fn run(&self, matches: &ArgMatches, out: &Path) -> Result<Made, AppError>;

    /// The worker threads the parsed options `matches` ask for (`None`: all cores).
    fn threads(&self, matches: &ArgMatches) -> Result<Option<i64>, AppError>;
}

/// A request that runs into its files.
pub trait Runs {
    /// Checks and runs the request, its files in `out` (in memory).
    fn run(&self, out: &Path) -> Result<Made, AppError>;

    /// The worker threads it asks for (`None`: all cores; the results do not depend on it).
    fn threads(&self) -> Option<i64>;
}

/// The request type `R` as a named study: its options `R`'s declaration, its run `R`'s.
pub struct Declared<R> {
    name: &'static str,
    about: &'static str,
    request: PhantomData<fn() -> R>,
}

impl<R> Declared<R> {
    /// The study `name` (`about`: what it does) of the request `R`.
    pub const fn new(name: &'static str, about: &'static str) -> Declared<R> {
        Declared {
            name,
            about,
            request: PhantomData,
        }
    }
}

impl<R: Args + FromArgMatches + Runs> StudyRequest for Declared<R> {
    fn name(&self) -> &'static str {
        self.name
    }

    fn about(&self) -> &'static str {
        self.about
    }

    fn declare(&self, command: clap::Command) -> clap::Command {
        R::augment_args(command)
    }

    fn run(&self, matches: &ArgMatches, out: &Path) -> Result<Made, AppError> {
        Declared::<R>::request(matches)?.run(out)
    }

    fn threads(&self, matches: &ArgMatches) -> Result<Option<i64>, AppError> {
        Ok(Declared::<R>::request(matches)?.threads())
    }
}

impl<R: FromArgMatches> Declared<R> {
    /// The request the parsed options `matches` make.
    fn request(matches: &ArgMatches) -> Result<R, AppError> {
        R::from_arg_matches(matches).map_err(|e| AppError::Usage(e.to_string()))
    }
}

/// `converge`, as the command line and Python name it.
pub static CONVERGE: Declared<ConvergeRequest> = Declared::new(
    "converge",
    "Convergence study: observed orders against a reference",
);
/// `independence`.
pub static INDEPENDENCE: Declared<IndependenceRequest> = Declared::new(
    "independence",
    "Step-size independence: successive differences, Richardson estimate, verdict",
);
/// `work-precision`.
pub static WORK_PRECISION: Declared<WorkPrecisionRequest> = Declared::new(
    "work-precision",
    "Work-precision: error against cost for every solver",
);
/// `stiffness`.
pub static STIFFNESS: Declared<StiffnessRequest> = Declared::new(
    "stiffness",
    "Stiffness sweep: where the implicit solvers overtake the explicit ones",
);

/// `compare`.
pub static COMPARE: Declared<CompareRequest> = Declared::new(
    "compare",
    "Every scheme at v = 0 (events, regularised over ε, naive, time-stepping) against the true \
     nonsmooth solution: the cost of each at target errors",
);

/// `orbit`.
pub static ORBIT: Declared<OrbitRequest> = Declared::new(
    "orbit",
    "The periodic orbit of a rig or a system by shooting through its switches: period, \
     segments, Floquet multipliers and stability",
);

/// `closed-loop`.
pub static CLOSED_LOOP: Declared<ClosedLoopRequest> = Declared::new(
    "closed-loop",
    "The closed loop of the servo or a system with a controller, at one's own gains and plant: \
     hunting, period, amplitude, regime, beside the describing function's predicted cycle",
);

/// `continue`.
pub static CONTINUE: Declared<ContinueRequest> = Declared::new(
    "continue",
    "The branches of equilibria and periodic orbits over one parameter, by pseudo-arclength \
     continuation: stability along them, folds, Hopf points, period doublings, segment changes",
);

registry::handle!(
    /// A study a front end names: a [`StudyRequest`], built in or a user's own.
    NamedStudy => dyn StudyRequest, STUDIES
);

/// Every study a front end names: the built-in ones ([`NamedStudy::ALL`]) and those registered
/// with [`NamedStudy::register`].
pub static STUDIES: registry::Registry<NamedStudy> =
    registry::Registry::new("study", "studies", &NamedStudy::ALL);

impl NamedStudy {
    /// The built-in studies, in the order the command line lists them.
    pub const ALL: [NamedStudy; 8] = [
        NamedStudy::built_in(&CONVERGE),
        NamedStudy::built_in(&INDEPENDENCE),
        NamedStudy::built_in(&WORK_PRECISION),
        NamedStudy::built_in(&STIFFNESS),
        NamedStudy::built_in(&COMPARE),
        NamedStudy::built_in(&ORBIT),
        NamedStudy::built_in(&CONTINUE),
        NamedStudy::built_in(&CLOSED_LOOP),
    ];
}

macro_rules! runs {
    ($($request:ty),*) => {$(
        impl Runs for $request {
            fn run(&self, out: &Path) -> Result<Made, AppError> {
                <$request>::run(self, out)
            }

            fn threads(&self) -> Option<i64> {
                self.problem.threads
            }
        }
    )*};
}

runs!(
    ConvergeRequest,
    IndependenceRequest,
    WorkPrecisionRequest,
    StiffnessRequest,
    CompareRequest,
    OrbitRequest,
    ContinueRequest,
    ClosedLoopRequest
);
