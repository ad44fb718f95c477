//! The comparison of formulations: one nonsmooth problem integrated every way a user would
//! consider at v = 0 — event-driven explicit and implicit solvers with events located,
//! the same solvers on the regularised law over a list of widths ε, naive stepping through
//! sign(0) = 0, and Moreau–Jean time-stepping — every run scored against the **true
//! nonsmooth solution**, and each scheme's cost at a list of target errors.
//!
//! The true solution is the event-driven reference ([`crate::batch::reference`]: a tight
//! explicit 5(4) pair cross-checked by another, or a tight BDF run where the case is stiff),
//! cross-checked besides by a method of another family, Radau IIA with events at
//! [`CHECK_TOLERANCE`]; the two differences are the reference's stated accuracy.
//!
//! A regularised run's error is decomposed: its **model error** — the regularised ODE solved
//! tightly ([`crate::studies::REFERENCE_TOLERANCE`] with BDF), against the true solution —
//! and its **discretisation error**, against that tight solution. The model error as a
//! function of ε is fitted as `e(ε) ≈ C·ε^p` ([`regularisation`]).
//!
//! Each track (a scheme at one ε) runs its resolutions loose to tight, one after the other on
//! one worker, so that it stops as soon as it has met the tightest target, failed, or reached
//! its regularisation floor, and is extended past its list while its error still falls
//! ([`next_resolution`]). The workers take the tracks in turn ([`schedule::in_order`]); a
//! track's runs depend on its own earlier runs alone, so the results do not depend on the
//! thread count, and no worker waits for another's track. A run is timed again only while
//! it is short ([`batch::run_timed`]).
//!
//! The runs fall into independent [`parts`] (the cross-check; each scheme without ε; each
//! width ε with the regularised schemes at it), each made by [`TrueSolution::part`] from the
//! true solution alone, and [`TrueSolution::merge`] makes the comparison of them. A
//! comparison made in one piece ([`compare`]) is the merge of one part holding every run, so
//! parts made on other machines (Dask workers) give it bit for bit.

mod cost;
pub mod regularisation;

pub use cost::{at_target, crossovers, Crossover, Kind, SchemeCost, TargetCosts, TrackRuns};
pub use regularisation::{EpsilonFit, ModelError, NeededWidth, Regularisation};

use super::extend::next_resolution;
use super::{batch, Errors, Measures, Method, Reference, StepKind, StudyCase, StudyRun, WallTimes};
use crate::error::ScenarioError;
use crate::errors::Scales;
use crate::schedule;
use crate::study_run::{REFERENCE_MARGIN, REFERENCE_TOLERANCE};
use crate::verdict::Verdict;
use friction_models::params::show;
use friction_systems::{Scheme, Switching};
use integrators::{Solver, SolverError, Stats, StepControl};
use serde::{Deserialize, Serialize};

/// The method of another family that cross-checks the true solution: Radau IIA (order 5,
/// implicit collocation) with events located, against the explicit 5(4) pairs of the
/// reference.
pub const CHECK_SOLVER: Solver = Solver::RADAU5;
/// The tolerance of that cross-check, rtol = atol.
pub const CHECK_TOLERANCE: f64 = 1e-11;
/// A regularised run within this factor of its model error has reached its floor.
pub const AT_FLOOR: f64 = 2.0;
/// The tolerance of the tight solution of a regularised ODE: the reference's.
pub const TIGHT_TOLERANCE: f64 = REFERENCE_TOLERANCE;
/// The solver of the tight solution of a regularised ODE (stiff for a small ε): BDF, as a
/// stiff case's reference ([`crate::batch`]).
pub const TIGHT_SOLVER: Solver = Solver::BDF;

/// The schemes a comparison runs.
#[derive(Clone, Debug, PartialEq)]
pub struct Schemes {
    /// Solvers run event-driven with events located at v = 0.
    pub event: Vec<Solver>,
    /// Solvers run on the regularised law, at every width of `epsilons`.
    pub regularised: Vec<Solver>,
    /// The widths ε, relative to the true solution's velocity scale (its largest |v|).
    pub epsilons: Vec<f64>,
    /// Solvers run through sign(0) = 0, without events.
    pub naive: Vec<Solver>,
    /// Moreau–Jean's θ, where time-stepping is compared.
    pub theta: Option<f64>,
}

/// The resolutions every scheme starts from, loose to tight.
#[derive(Clone, Debug, PartialEq)]
pub struct Resolutions {
    /// Tolerances of the adaptive solvers (rtol = atol).
    pub tolerances: Vec<f64>,
    /// Step sizes of the fixed-step solvers, s.
    pub steps: Vec<f64>,
    /// Step sizes of Moreau–Jean's scheme, s.
    pub timestepping_steps: Vec<f64>,
}

/// What a comparison runs and what it asks of them.
#[derive(Clone, Debug, PartialEq)]
pub struct CompareSpec {
    /// The schemes.
    pub schemes: Schemes,
    /// Their resolutions.
    pub resolutions: Resolutions,
    /// The target errors, loose to tight ([`Errors::grid_relative`]).
    pub targets: Vec<f64>,
    /// Timings of each run beyond the first (the wall time is their median).
    pub repeats: usize,
}

/// The second opinion on the true solution: a method of another family.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CrossCheck {
    /// The scheme (`radau5 (event)`).
    pub scheme: String,
    /// Its tolerance.
    pub tolerance: f64,
    /// Its grid error against the true solution; `None` where it failed.
    pub difference: Option<f64>,
    /// Why it failed.
    pub failure: Option<String>,
}

/// One run of the comparison.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ComparedRun {
    /// The scheme.
    pub scheme: String,
    /// Its regularisation width, m/s (regularised schemes).
    pub epsilon: Option<f64>,
    /// The run, its errors against the true solution.
    #[serde(flatten)]
    pub run: StudyRun,
    /// A regularised run's grid error against its own ODE's tight solution (its
    /// discretisation error); `None` for the other schemes.
    pub discretisation_error: Option<f64>,
}

/// Why a track stopped.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TrackEnd {
    /// The scheme.
    pub scheme: String,
    /// Its regularisation width, m/s.
    pub epsilon: Option<f64>,
    /// Why it stopped, in words; `None` where it met the tightest target.
    pub stopped: Option<String>,
}

/// A comparison of formulations (see the module).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Comparison {
    /// The true solution's source.
    pub reference: Reference,
    /// Its cross-check by another family.
    pub cross_check: CrossCheck,
    /// The error below which the reference cannot resolve a run: the larger of
    /// [`REFERENCE_MARGIN`] times its estimated error and its difference from the
    /// cross-check (infinite where the cross-check failed). A target below it is not claimed.
    pub resolvable: f64,
    /// The true solution's velocity scale (its largest |v|), m/s: what ε is relative to.
    pub velocity_scale: f64,
    /// Every run, track by track (a run's `solver` names its track: the scheme, with ε for a
    /// regularised one).
    pub runs: Vec<ComparedRun>,
    /// The regularised schemes' model error against ε; `None` where none was compared.
    pub regularisation: Option<Regularisation>,
    /// Every scheme's cost at each target, loose to tight.
    pub costs: Vec<TargetCosts>,
    /// Where the cheapest scheme changes.
    pub crossovers: Vec<Crossover>,
    /// Why each track stopped.
    pub tracks: Vec<TrackEnd>,
}

/// One scheme at one ε, and its runs so far.
struct Track {
    method: Method,
    scheme: String,
    epsilon: Option<f64>,
    planned: Vec<StepControl>,
    runs: Vec<ComparedRun>,
    /// The tight solution of its regularised ODE, and its model error.
    tight: Option<(Measures, f64)>,
    stopped: Option<Option<String>>,
}

/// The scheme's name in tables: its method and treatment (`dopri5 (event)`).
pub fn scheme_name(scheme: Scheme) -> String {
    Method::peer(scheme).label()
}

impl Track {
    fn new(scheme: Scheme, planned: Vec<StepControl>) -> Track {
        Track {
            method: Method::peer(scheme),
            scheme: scheme_name(scheme),
            epsilon: match scheme.parameter() {
                Some(("epsilon", e)) => Some(e),
                _ => None,
            },
            planned,
            runs: Vec::new(),
            tight: None,
            stopped: None,
        }
    }

    /// The name of its runs: the scheme's, with ε for a regularised one
    /// (`bdf (regularized, ε = 1.86e-5)`).
    fn label(&self) -> String {
        match self.epsilon {
            Some(e) => format!("{}, ε = {e:.2e})", self.scheme.trim_end_matches(')')),
            None => self.scheme.clone(),
        }
    }

    /// The next resolution after its last run ([`next_resolution`]); `Err` with why the
    /// track ends.
    fn next(&self) -> Result<StepControl, String> {
        let runs: Vec<&StudyRun> = self.runs.iter().map(|r| &r.run).collect();
        next_resolution(&runs, &self.planned)
    }

    /// Records `run` and decides whether the track goes on.
    fn record(&mut self, run: ComparedRun, tightest: f64) {
        let r = &run.run;
        let ok = r.verdict.is_ok();
        let error = r.errors.grid_relative;
        self.stopped = match (&r.failure, r.diverged) {
            (Some(e), false) => Some(Some(format!(
                "its run at {} failed: {e}",
                show(r.resolution)
            ))),
            _ if ok && error <= tightest => Some(None),
            _ => match self.tight {
                Some((_, floor)) if floor > tightest && error <= AT_FLOOR * floor => {
                    Some(Some(format!(
                        "it reached the regularisation floor: model error {} at ε = {}",
                        show(floor),
                        show(self.epsilon.unwrap_or(f64::NAN))
                    )))
                }
                _ => None,
            },
        };
        self.runs.push(run);
    }
}

/// The planned resolutions of `scheme`.
fn planned(scheme: Scheme, r: &Resolutions) -> Vec<StepControl> {
    let fixed = |steps: &[f64]| steps.iter().map(|&h| StepControl::Fixed { h }).collect();
    match scheme.solver() {
        None => fixed(&r.timestepping_steps),
        Some(s) if s.is_fixed_step() => fixed(&r.steps),
        Some(_) => (r.tolerances.iter())
            .map(|&tol| StepControl::Adaptive {
                rtol: tol,
                atol: tol,
                h0: None,
            })
            .collect(),
    }
}

/// Every track of `s` in order, its scheme and, for a regularised one, the index of its
/// width in `epsilons` (the absolute widths, m/s): the event-driven solvers, the naive ones,
/// time-stepping, then each regularised solver at every width.
fn track_schemes(s: &Schemes, epsilons: &[f64]) -> Vec<(Scheme, Option<usize>)> {
    let events = (s.event.iter()).map(|&solver| Scheme::events(solver));
    let naive = (s.naive.iter()).map(|&solver| Scheme::EventDriven {
        solver,
        switching: Switching::Naive,
    });
    let stepping = (s.theta.iter()).map(|&theta| Scheme::TimeStepping { theta });
    let plain = events
        .chain(naive)
        .chain(stepping)
        .map(|scheme| (scheme, None));
    let regularised = (s.regularised.iter()).flat_map(|&solver| {
        (epsilons.iter().enumerate()).map(move |(j, &epsilon)| {
            let switching = Switching::Regularized { epsilon };
            (Scheme::EventDriven { solver, switching }, Some(j))
        })
    });
    plain.chain(regularised).collect()
}

/// Which of a comparison's runs one part makes ([`parts`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Part {
    /// Whether it makes the cross-check.
    pub cross_check: bool,
    /// The indices of the regularisation widths whose tight solutions it makes.
    pub widths: Vec<usize>,
    /// The indices of the tracks it runs: the event-driven solvers, the naive ones,
    /// time-stepping, then each regularised solver at every width.
    pub tracks: Vec<usize>,
}

impl Part {
    /// The part that makes every run of `spec`.
    pub fn whole(spec: &CompareSpec) -> Part {
        let (plain, widths) = track_counts(&spec.schemes);
        Part {
            cross_check: true,
            widths: (0..widths).collect(),
            tracks: (0..plain + spec.schemes.regularised.len() * widths).collect(),
        }
    }
}

/// How many tracks of `s` have no width, and how many widths are compared.
fn track_counts(s: &Schemes) -> (usize, usize) {
    let plain = s.event.len() + s.naive.len() + usize::from(s.theta.is_some());
    let widths = match s.regularised.is_empty() {
        true => 0,
        false => s.epsilons.len(),
    };
    (plain, widths)
}

/// The independent parts of the comparison `spec`: the cross-check; each scheme without ε,
/// alone; each width ε with every regularised scheme at it (they share its tight solution).
/// Merged ([`TrueSolution::merge`]) they give the comparison made in one piece.
pub fn parts(spec: &CompareSpec) -> Vec<Part> {
    let (plain, widths) = track_counts(&spec.schemes);
    let solvers = spec.schemes.regularised.len();
    let alone = (0..plain).map(|i| Part {
        cross_check: false,
        widths: Vec::new(),
        tracks: vec![i],
    });
    let at_width = (0..widths).map(|j| Part {
        cross_check: false,
        widths: vec![j],
        tracks: (0..solvers).map(|k| plain + k * widths + j).collect(),
    });
    let check = Part {
        cross_check: true,
        widths: Vec::new(),
        tracks: Vec::new(),
    };
    std::iter::once(check)
        .chain(alone)
        .chain(at_width)
        .collect()
}

/// One run of a part as it travels: a [`ComparedRun`] but for its scheme (the merge knows
/// it), its measures (no longer needed) and its failure, kept as its message.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct RunRecord {
    solver: String,
    resolution: f64,
    step: StepKind,
    errors: Errors,
    stats: Stats,
    work: usize,
    failure: Option<String>,
    verdict: Verdict,
    diverged: bool,
    wall_time: WallTimes,
    discretisation_error: Option<f64>,
}

impl RunRecord {
    fn of(r: ComparedRun) -> RunRecord {
        let run = r.run;
        RunRecord {
            solver: run.solver,
            resolution: run.resolution,
            step: run.step,
            errors: run.errors,
            stats: run.stats,
            work: run.work,
            failure: run.failure.map(|e| e.to_string()),
            verdict: run.verdict,
            diverged: run.diverged,
            wall_time: run.wall_time,
            discretisation_error: r.discretisation_error,
        }
    }

    /// The run of `track`.
    fn run_of(self, track: &Track) -> ComparedRun {
        ComparedRun {
            scheme: track.scheme.clone(),
            epsilon: track.epsilon,
            run: StudyRun {
                solver: self.solver,
                resolution: self.resolution,
                step: self.step,
                errors: self.errors,
                measures: Measures::default(),
                stats: self.stats,
                work: self.work,
                failure: (self.failure).map(|message| SolverError::Reported { message }),
                verdict: self.verdict,
                diverged: self.diverged,
                wall_time: self.wall_time,
            },
            discretisation_error: self.discretisation_error,
        }
    }
}

/// One track's runs and why it stopped, as a part hands them on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct TrackRecord {
    runs: Vec<RunRecord>,
    stopped: Option<String>,
}

/// What one part of a comparison made ([`TrueSolution::part`]): plain data, to be sent
/// between processes (serde) and merged ([`TrueSolution::merge`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ComparePart {
    cross_check: Option<CrossCheck>,
    model_errors: Vec<(usize, ModelError)>,
    tracks: Vec<(usize, TrackRecord)>,
}

/// The true nonsmooth solution a comparison scores every run against (see the module).
pub struct TrueSolution {
    /// Its source: the event-driven reference of a study of an implicit solver (the explicit
    /// pairs are then free to be the reference).
    pub reference: Reference,
    /// Its measures.
    measures: Measures,
    /// Its largest |v|, m/s: what the widths ε are relative to.
    pub velocity_scale: f64,
}

impl TrueSolution {
    /// The true solution of `case`; refused where the case does not move (no scale to be
    /// relative to, no jump crossed).
    pub fn of(case: &dyn StudyCase) -> Result<TrueSolution, ScenarioError> {
        let (reference, measures) = batch::reference(case, &[Method::events(CHECK_SOLVER)])?;
        let velocity_scale = Scales::of(&measures).v;
        if velocity_scale.is_nan() || velocity_scale <= 0.0 {
            return Err(ScenarioError::Invalid(format!(
                "{} does not move on [0, {}] s (its largest |v| is {}): there is no motion to \
                 compare the schemes on; integrate longer, or start it moving",
                case.describe(),
                show(case.t_end()),
                show(velocity_scale)
            )));
        }
        Ok(TrueSolution {
            reference,
            measures,
            velocity_scale,
        })
    }

    /// The widths of `spec`, m/s.
    fn epsilons(&self, spec: &CompareSpec) -> Vec<f64> {
        let relative = &spec.schemes.epsilons;
        relative.iter().map(|e| e * self.velocity_scale).collect()
    }

    /// Makes the runs of `part` of the comparison `spec` on `case`; `progress` is told of
    /// every run of its tracks.
    pub fn part(
        &self,
        case: &dyn StudyCase,
        spec: &CompareSpec,
        part: &Part,
        progress: &(dyn Fn() + Sync),
    ) -> Result<ComparePart, ScenarioError> {
        let tightest = spec.targets.iter().copied().fold(f64::INFINITY, f64::min);
        let epsilons = self.epsilons(spec);
        let every = track_schemes(&spec.schemes, &epsilons);

        // The cross-check and the tight regularised solutions, one list.
        let check = Scheme::events(CHECK_SOLVER);
        let tight_step = |tol: f64| StepControl::Adaptive {
            rtol: tol,
            atol: tol,
            h0: None,
        };
        let mut first: Vec<[(Method, StepControl); 1]> = Vec::new();
        if part.cross_check {
            first.push([(Method::peer(check), tight_step(CHECK_TOLERANCE))]);
        }
        for &j in &part.widths {
            let scheme = Scheme::EventDriven {
                solver: TIGHT_SOLVER,
                switching: Switching::Regularized {
                    epsilon: epsilons[j],
                },
            };
            first.push([(Method::peer(scheme), tight_step(TIGHT_TOLERANCE))]);
        }
        let posed: Vec<batch::Posed> = (first.iter())
            .map(|jobs| batch::Posed {
                case,
                reference_for: None,
                jobs,
            })
            .collect();
        let mut tight = batch::run_cases(&posed, 0, &|| {})?
            .into_iter()
            .map(|c| c.runs.into_iter().next().expect("one job a case"));
        let cross_check = part.cross_check.then(|| {
            let run = tight.next().expect("the cross-check runs first");
            CrossCheck {
                scheme: scheme_name(check),
                tolerance: CHECK_TOLERANCE,
                difference: (run.failure.is_none())
                    .then(|| Errors::between(&run.measures, &self.measures).grid_relative),
                failure: run.failure.map(|e| e.to_string()),
            }
        });
        let solutions: Vec<(usize, ModelError, Measures)> = (part.widths.iter())
            .zip(tight)
            .map(|(&j, run)| {
                let model = ModelError {
                    epsilon: epsilons[j],
                    relative: spec.schemes.epsilons[j],
                    error: match run.failure {
                        None => Errors::between(&run.measures, &self.measures).grid_relative,
                        Some(_) => f64::NAN,
                    },
                    failure: run.failure.as_ref().map(|e| e.to_string()),
                };
                (j, model, run.measures)
            })
            .collect();

        // The tracks, each a chain of runs on one worker (each run's resolution follows from
        // the track's earlier runs alone), the workers taking the tracks in turn.
        let order: Vec<usize> = (0..part.tracks.len()).collect();
        let tracks = schedule::in_order(
            &order,
            |_| false,
            |k| {
                let i = part.tracks[k];
                let (scheme, width) = every[i];
                let mut t = Track::new(scheme, planned(scheme, &spec.resolutions));
                if let Some(j) = width {
                    let (_, model, measures) = (solutions.iter())
                        .find(|(k, ..)| *k == j)
                        .expect("a part makes the tight solutions of its tracks' widths");
                    t.tight = (model.failure.is_none()).then(|| (measures.clone(), model.error));
                }
                self.run_track(case, &mut t, spec, tightest, progress)?;
                Ok::<_, ScenarioError>((i, t))
            },
        )?;
        Ok(ComparePart {
            cross_check,
            model_errors: (solutions.into_iter())
                .map(|(j, model, _)| (j, model))
                .collect(),
            tracks: (tracks.into_iter())
                .map(|(_, (i, t))| {
                    let record = TrackRecord {
                        stopped: t.stopped.flatten(),
                        runs: t.runs.into_iter().map(RunRecord::of).collect(),
                    };
                    (i, record)
                })
                .collect(),
        })
    }

    /// Runs track `t` of `case` until it stops: each run at the resolution its earlier runs
    /// call for ([`Track::next`]), timed by [`batch::run_timed`], scored against the true
    /// solution, and recorded ([`Track::record`]).
    fn run_track(
        &self,
        case: &dyn StudyCase,
        t: &mut Track,
        spec: &CompareSpec,
        tightest: f64,
        progress: &(dyn Fn() + Sync),
    ) -> Result<(), ScenarioError> {
        while t.stopped.is_none() {
            let step = match t.next() {
                Ok(step) => step,
                Err(why) => {
                    t.stopped = Some(Some(why));
                    break;
                }
            };
            let mut run = batch::run_timed(case, &t.method, step, spec.repeats, progress)?;
            batch::judge(&mut run, &self.measures);
            run.solver = t.label();
            let discretisation_error = (t.tight.as_ref())
                .filter(|_| run.failure.is_none())
                .map(|(m, _)| Errors::between(&run.measures, m).grid_relative);
            let compared = ComparedRun {
                scheme: t.scheme.clone(),
                epsilon: t.epsilon,
                run,
                discretisation_error,
            };
            t.record(compared, tightest);
        }
        Ok(())
    }

    /// The comparison `spec` made of `parts`, which must hold the cross-check, every width and
    /// every track once each (as [`parts`] divides them).
    pub fn merge(
        &self,
        spec: &CompareSpec,
        parts: Vec<ComparePart>,
    ) -> Result<Comparison, ScenarioError> {
        let s = &spec.schemes;
        let epsilons = self.epsilons(spec);
        let every = track_schemes(s, &epsilons);
        let (_, widths) = track_counts(s);
        let mut checks = Vec::new();
        let mut models: Vec<Option<ModelError>> = vec![None; widths];
        let mut records: Vec<Option<TrackRecord>> = vec![None; every.len()];
        let apart = |what: String| {
            ScenarioError::Invalid(format!(
                "the parts do not make one comparison: {what} (each part of the comparison \
                 must be given once)"
            ))
        };
        for part in parts {
            checks.extend(part.cross_check);
            for (j, model) in part.model_errors {
                let slot = models.get_mut(j).filter(|m| m.is_none());
                *slot.ok_or_else(|| apart(format!("width {j} given twice or unknown")))? =
                    Some(model);
            }
            for (i, record) in part.tracks {
                let slot = records.get_mut(i).filter(|r| r.is_none());
                *slot.ok_or_else(|| apart(format!("track {i} given twice or unknown")))? =
                    Some(record);
            }
        }
        if checks.len() != 1 {
            return Err(apart(format!("{} cross-checks", checks.len())));
        }
        let cross_check = checks.remove(0);
        let model_errors: Vec<ModelError> = (models.into_iter().enumerate())
            .map(|(j, m)| m.ok_or_else(|| apart(format!("width {j} is missing"))))
            .collect::<Result<_, _>>()?;
        let mut tracks = Vec::new();
        for (i, (record, (scheme, _))) in records.into_iter().zip(&every).enumerate() {
            let record = record.ok_or_else(|| apart(format!("track {i} is missing")))?;
            let mut t = Track::new(*scheme, Vec::new());
            t.runs = (record.runs.into_iter()).map(|r| r.run_of(&t)).collect();
            t.stopped = Some(record.stopped);
            tracks.push(t);
        }

        // The cross-check's difference bounds the reference's error where the reference is
        // the more accurate of the two; its own estimate needs the margin of every study.
        let resolvable = (REFERENCE_MARGIN * self.reference.estimated_error())
            .max(cross_check.difference.unwrap_or(f64::INFINITY));
        let mut names: Vec<String> = Vec::new();
        for t in &tracks {
            if !names.contains(&t.scheme) {
                names.push(t.scheme.clone());
            }
        }
        let track_runs: Vec<TrackRuns> = (tracks.iter())
            .map(|t| TrackRuns {
                scheme: &t.scheme,
                kind: match t.method.scheme.solver() {
                    Some(s) if s == Solver::AUTO => Kind::Switching,
                    _ if t.method.is_implicit() => Kind::Implicit,
                    _ => Kind::Explicit,
                },
                epsilon: t.epsilon,
                runs: t.runs.iter().map(|r| &r.run).collect(),
                stopped: t.stopped.clone().flatten(),
            })
            .collect();
        let mut targets = spec.targets.clone();
        targets.sort_by(|a, b| b.total_cmp(a));
        let costs: Vec<TargetCosts> = (targets.iter())
            .map(|&target| TargetCosts {
                resolved: target >= resolvable,
                ..at_target(&names, &track_runs, target)
            })
            .collect();
        let crossovers = crossovers(&costs);
        let sticks = !self.measures.stick_durations.is_empty();
        let regularisation = (!s.regularised.is_empty())
            .then(|| Regularisation::of(model_errors, &spec.targets, sticks, resolvable));
        Ok(Comparison {
            reference: self.reference.clone(),
            cross_check,
            resolvable,
            velocity_scale: self.velocity_scale,
            costs,
            crossovers,
            regularisation,
            tracks: (tracks.iter())
                .map(|t| TrackEnd {
                    scheme: t.scheme.clone(),
                    epsilon: t.epsilon,
                    stopped: t.stopped.clone().flatten(),
                })
                .collect(),
            runs: tracks.into_iter().flat_map(|t| t.runs).collect(),
        })
    }
}

/// Runs the comparison `spec` on `case` (see the module) in one piece; `progress` is told of
/// every run.
pub fn compare(
    case: &dyn StudyCase,
    spec: &CompareSpec,
    progress: &(dyn Fn() + Sync),
) -> Result<Comparison, ScenarioError> {
    let truth = TrueSolution::of(case)?;
    let whole = truth.part(case, spec, &Part::whole(spec), progress)?;
    truth.merge(spec, vec![whole])
}
