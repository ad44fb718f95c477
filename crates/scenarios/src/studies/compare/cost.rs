//! The cost of each scheme at a target error, and which scheme is cheapest: the runs of a
//! scheme's tracks interpolated log–log between the two that bracket the target
//! ([`super::super::reached`]), the cheapest of its tracks taken (a regularised scheme's at
//! its best ε), a tie where the two cheapest lie within each other's brackets, and the
//! crossovers where the cheapest changes between two targets.

use crate::studies::{reached, winner, Cost, Reached, StudyRun, WallTimes, Winner};
use serde::Serialize;

/// Which side of the paper's question a scheme is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    /// An explicit method (Dormand–Prince, RK4).
    Explicit,
    /// An implicit method, or time-stepping (an implicit problem per step).
    Implicit,
    /// `auto`: explicit until Hairer's stiffness test fires, implicit after; on neither side.
    Switching,
}

/// One scheme's cost at one target.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SchemeCost {
    /// The scheme (`dopri5 (event)`, `bdf (regularized)`, `moreau-jean (timestepping)`).
    pub scheme: String,
    /// Its kind.
    pub kind: Kind,
    /// How its cheapest track met the target; `None` where none did (see `reason`).
    pub reached: Option<Reached>,
    /// The regularisation width of the track that met it, m/s (regularised schemes).
    pub epsilon: Option<f64>,
    /// The wall time at the target, s: the median over the repeats of the run that met it,
    /// scaled by the interpolated work over its work (wall time follows work within a scheme);
    /// `None` where the target was not reached. Not deterministic: kept out of the JSON.
    #[serde(skip)]
    pub wall_time: Option<f64>,
    /// The spread of that wall time: the run's quartiles, scaled the same way.
    #[serde(skip)]
    pub wall_spread: Option<[f64; 2]>,
    /// Why the target was not reached; `None` where it was.
    pub reason: Option<String>,
}

/// Which scheme is cheapest at one target.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TargetCosts {
    /// The target error (the grid error relative to the solution's scale).
    pub target: f64,
    /// Whether the true solution resolves it (`false`: the target lies below the
    /// reference's accuracy, and its costs are not a claim).
    pub resolved: bool,
    /// Every scheme's cost.
    pub costs: Vec<SchemeCost>,
    /// The cheapest scheme; `None` where no scheme met the target. (A scheme at exactly the
    /// cost of one listed before it made the same runs, and is not counted as a second one.)
    pub cheapest: Option<String>,
    /// The next cheapest scheme, where one met the target too.
    pub runner_up: Option<String>,
    /// The runner-up's work over the cheapest's.
    pub factor: Option<f64>,
    /// Whether the two are within each other's brackets: the resolutions cannot tell them
    /// apart, and neither is called cheaper.
    pub tie: bool,
    /// Which kind is cheaper, the cheapest explicit scheme or the cheapest implicit one
    /// (`auto` on neither side), a tie where their brackets overlap
    /// ([`crate::studies::winner`]); `None` where neither met the target.
    pub kind: Option<Winner>,
    /// The cheapest implicit scheme's work over the cheapest explicit one's, where both met
    /// the target.
    pub implicit_over_explicit: Option<f64>,
}

/// A change of the cheapest scheme between two targets.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Crossover {
    /// The scheme cheapest at the looser target.
    pub from: String,
    /// The scheme cheapest at the tighter one.
    pub to: String,
    /// The two targets it lies between, loose then tight.
    pub between: [f64; 2],
    /// The target at which the two schemes' interpolated costs are equal (log–log between
    /// the two targets); `None` where one of them did not meet both.
    pub at: Option<f64>,
}

/// A track's runs, loose to tight, with what a cost needs besides.
pub struct TrackRuns<'a> {
    /// The scheme the track belongs to.
    pub scheme: &'a str,
    /// The scheme's kind.
    pub kind: Kind,
    /// Its regularisation width, m/s.
    pub epsilon: Option<f64>,
    /// Its runs, loose to tight.
    pub runs: Vec<&'a StudyRun>,
    /// Why the track stopped short of the tightest target, in words (`None`: it met it).
    pub stopped: Option<String>,
}

/// The wall time at a target: `met`'s median and quartiles scaled by `work / met.work`.
fn wall_at(wall: &WallTimes, met_work: usize, work: f64) -> (f64, [f64; 2]) {
    let scale = work / met_work.max(1) as f64;
    (wall.median * scale, [wall.q1 * scale, wall.q3 * scale])
}

/// The cost of `scheme` at `target`: the cheapest of its tracks that met it, or the reason
/// none did (the closest track's: the one whose best `ok` error came nearest).
pub fn scheme_cost(scheme: &str, tracks: &[TrackRuns], target: f64) -> SchemeCost {
    let mine: Vec<&TrackRuns> = tracks.iter().filter(|t| t.scheme == scheme).collect();
    let kind = mine.first().map_or(Kind::Explicit, |t| t.kind);
    let best = (mine.iter())
        .filter_map(|t| Some((*t, reached(&t.runs, target)?)))
        .min_by(|a, b| a.1.work_estimate.total_cmp(&b.1.work_estimate));
    match best {
        Some((track, r)) => {
            let met = (track.runs.iter())
                .find(|run| run.resolution == r.resolution)
                .expect("the run that met the target is among the track's");
            let (wall, spread) = wall_at(&met.wall_time, met.work, r.work_estimate);
            SchemeCost {
                scheme: scheme.to_string(),
                kind,
                epsilon: track.epsilon,
                reached: Some(r),
                wall_time: Some(wall),
                wall_spread: Some(spread),
                reason: None,
            }
        }
        None => {
            let closest = |t: &&&TrackRuns| {
                (t.runs.iter())
                    .filter(|r| r.verdict.is_ok())
                    .map(|r| r.errors.grid_relative)
                    .fold(f64::INFINITY, f64::min)
            };
            let track = mine.iter().min_by(|a, b| closest(a).total_cmp(&closest(b)));
            let reason = match track {
                Some(t) => {
                    let error = closest(&t);
                    let why = t.stopped.clone().unwrap_or_else(|| "its runs end".into());
                    match error.is_finite() {
                        true => format!(
                            "smallest error {}{}: {why}",
                            show(error),
                            t.epsilon
                                .map_or(String::new(), |e| format!(" (ε = {})", show(e)))
                        ),
                        false => format!("no run ended ok: {why}"),
                    }
                }
                None => "not run".to_string(),
            };
            SchemeCost {
                scheme: scheme.to_string(),
                kind,
                epsilon: None,
                reached: None,
                wall_time: None,
                wall_spread: None,
                reason: Some(reason),
            }
        }
    }
}

/// A number as the reports write it.
fn show(x: f64) -> String {
    friction_models::params::show(x)
}

/// The work range a cost's bracket leaves possible (an open lower bound reaching down to 0).
fn range(r: &Reached) -> (f64, f64) {
    let [lo, hi] = r.work_bracket;
    (lo.unwrap_or(0.0), hi.unwrap_or(r.work_estimate))
}

/// The costs of every scheme of `schemes` at `target`, the cheapest and the runner-up, and
/// whether they tie.
pub fn at_target(schemes: &[String], tracks: &[TrackRuns], target: f64) -> TargetCosts {
    let costs: Vec<SchemeCost> = (schemes.iter())
        .map(|s| scheme_cost(s, tracks, target))
        .collect();
    let work = |c: &SchemeCost| {
        c.reached
            .as_ref()
            .map_or(f64::INFINITY, |r| r.work_estimate)
    };
    // A scheme at exactly the cost of one listed before it made the same runs (`auto` that
    // never switched ran as Dormand–Prince; on a law without a jump at v = 0 naive and
    // regularised stepping are event stepping): it is not a second scheme.
    let repeats_earlier = |i: usize| {
        let w = work(&costs[i]);
        costs[..i].iter().any(|o| work(o) == w)
    };
    let mut met: Vec<&SchemeCost> = (costs.iter().enumerate())
        .filter(|(i, c)| c.reached.is_some() && !repeats_earlier(*i))
        .map(|(_, c)| c)
        .collect();
    met.sort_by(|a, b| work(a).total_cmp(&work(b)));
    let (cheapest, runner_up) = (met.first(), met.get(1));
    let tie = match (cheapest, runner_up) {
        (Some(a), Some(b)) => {
            let ((a_lo, a_hi), (b_lo, b_hi)) = (
                range(a.reached.as_ref().expect("met")),
                range(b.reached.as_ref().expect("met")),
            );
            a_lo.max(b_lo) <= a_hi.min(b_hi)
        }
        _ => false,
    };
    let sides: Vec<Cost> = (costs.iter())
        .filter(|c| c.kind != Kind::Switching)
        .map(|c| Cost {
            solver: c.scheme.clone(),
            implicit: c.kind == Kind::Implicit,
            reached: c.reached.clone(),
        })
        .collect();
    let cheapest_of = |implicit: bool| {
        (sides.iter())
            .filter(|c| c.implicit == implicit)
            .filter_map(|c| c.reached.as_ref().map(|r| r.work_estimate))
            .min_by(f64::total_cmp)
    };
    TargetCosts {
        target,
        resolved: true,
        kind: winner(&sides),
        implicit_over_explicit: cheapest_of(true)
            .zip(cheapest_of(false))
            .map(|(i, e)| i / e),
        cheapest: cheapest.map(|c| c.scheme.clone()),
        runner_up: runner_up.map(|c| c.scheme.clone()),
        factor: cheapest.zip(runner_up).map(|(a, b)| work(b) / work(a)),
        tie,
        costs,
    }
}

/// Where the cheapest scheme changes between consecutive targets of `table` (loose to tight,
/// targets where none met it or the two cheapest tie passed over), with the target at which
/// the two schemes' costs cross, interpolated log–log.
pub fn crossovers(table: &[TargetCosts]) -> Vec<Crossover> {
    let decided: Vec<&TargetCosts> = (table.iter())
        .filter(|t| t.cheapest.is_some() && !t.tie)
        .collect();
    let work = |t: &TargetCosts, scheme: &str| {
        (t.costs.iter())
            .find(|c| c.scheme == scheme)
            .and_then(|c| c.reached.as_ref())
            .map(|r| r.work_estimate)
    };
    decided
        .windows(2)
        .filter(|w| w[0].cheapest != w[1].cheapest)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let from = a.cheapest.clone().expect("decided");
            let to = b.cheapest.clone().expect("decided");
            // ln(work_from / work_to) at each target: negative at the first, positive at
            // the second; the crossing is where it is 0.
            let d = |t: &TargetCosts| Some((work(t, &from)?.ln()) - work(t, &to)?.ln());
            let at = d(a).zip(d(b)).and_then(|(d0, d1)| {
                (d0 < d1).then(|| {
                    let (l0, l1) = (a.target.ln(), b.target.ln());
                    (l0 + (l1 - l0) * d0 / (d0 - d1)).exp()
                })
            });
            Crossover {
                from,
                to,
                between: [a.target, b.target],
                at,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::method::StepKind;
    use crate::studies::{Errors, Measures};
    use crate::verdict::Verdict;
    use integrators::Stats;

    fn run(tol: f64, error: f64, work: usize) -> StudyRun {
        StudyRun {
            solver: "s".into(),
            resolution: tol,
            step: StepKind::Adaptive,
            errors: Errors {
                grid_relative: error,
                final_relative: error,
                ..Errors::UNMEASURED
            },
            measures: Measures::default(),
            stats: Stats::default(),
            work,
            failure: None,
            verdict: Verdict::OK,
            diverged: false,
            wall_time: WallTimes::of(&[work as f64 * 1e-6]),
        }
    }

    fn track<'a>(scheme: &'a str, runs: &'a [StudyRun]) -> TrackRuns<'a> {
        TrackRuns {
            scheme,
            kind: if scheme == "b" {
                Kind::Implicit
            } else {
                Kind::Explicit
            },
            epsilon: None,
            runs: runs.iter().collect(),
            stopped: Some("the tolerance list ends".into()),
        }
    }

    #[test]
    fn the_cost_at_a_target_is_interpolated_log_log_between_its_bracket() {
        // Error 1e-2 at work 100, 1e-4 at work 10 000: a slope of −1 in log–log, so the
        // target 1e-3 costs 1 000, bracketed by [100, 10 000].
        let runs = [run(1e-2, 1e-2, 100), run(1e-4, 1e-4, 10_000)];
        let c = scheme_cost("a", &[track("a", &runs)], 1e-3);
        let r = c.reached.unwrap();
        assert!(
            (r.work_estimate - 1000.0).abs() < 1e-9,
            "{}",
            r.work_estimate
        );
        assert_eq!(r.work_bracket, [Some(100.0), Some(10_000.0)]);
        // The wall time scales with the work from the run that met the target.
        assert!((c.wall_time.unwrap() - 1e-3).abs() < 1e-15);
        // Below every run: not reached, with the closest error and why.
        let c = scheme_cost("a", &[track("a", &runs)], 1e-6);
        assert!(c.reached.is_none());
        assert_eq!(
            c.reason.as_deref(),
            Some("smallest error 1e-4: the tolerance list ends")
        );
    }

    #[test]
    fn overlapping_brackets_tie_and_a_change_of_the_cheapest_is_a_crossover() {
        // a: error 10/work, one run a decade; b: cheap to start, its cost growing slowly.
        let a = [
            run(1e-1, 1e-1, 100),
            run(1e-2, 1e-2, 1_000),
            run(1e-3, 1e-3, 10_000),
            run(1e-4, 1e-4, 100_000),
            run(1e-5, 1e-5, 1_000_000),
        ];
        let b = [
            run(1e-1, 1e-1, 3_000),
            run(1e-3, 1e-3, 5_000),
            run(1e-5, 1e-5, 9_000),
        ];
        let tracks = [track("a", &a), track("b", &b)];
        let schemes = ["a".to_string(), "b".to_string()];
        let table: Vec<TargetCosts> = [0.5, 5e-2, 5e-5]
            .iter()
            .map(|&t| at_target(&schemes, &tracks, t))
            .collect();
        // At 0.5 both loosest runs met the target: their costs are bounded above only, a tie.
        assert!(table[0].tie, "{:?}", table[0]);
        // At 5e-2: a within [100, 1 000], b within [3 000, 5 000].
        assert_eq!(table[1].cheapest.as_deref(), Some("a"));
        assert!(!table[1].tie);
        assert!((table[1].costs[0].reached.as_ref().unwrap().work_estimate - 200.0).abs() < 1e-6);
        // A third scheme that made a's runs exactly is no runner-up of a's.
        let same = at_target(
            &["a".into(), "b".into(), "c".into()],
            &[track("a", &a), track("b", &b), track("c", &a)],
            5e-2,
        );
        assert_eq!(same.runner_up.as_deref(), Some("b"));
        // At 5e-5: a within [1e5, 1e6], b within [5 000, 9 000].
        assert_eq!(table[2].cheapest.as_deref(), Some("b"));
        assert_eq!(table[2].kind, Some(Winner::Implicit));
        assert_eq!(table[1].kind, Some(Winner::Explicit));
        assert!(
            (table[1].implicit_over_explicit.unwrap() * 200.0
                - table[1].costs[1].reached.as_ref().unwrap().work_estimate)
                .abs()
                < 1e-6
        );
        let x = crossovers(&table);
        assert_eq!(x.len(), 1, "{x:?}");
        assert_eq!((x[0].from.as_str(), x[0].to.as_str()), ("a", "b"));
        assert_eq!(x[0].between, [5e-2, 5e-5]);
        // Where ln(w_a/w_b), linear in ln(target) between the two, is 0.
        let d = |t: &TargetCosts| {
            let w = |i: usize| t.costs[i].reached.as_ref().unwrap().work_estimate.ln();
            w(0) - w(1)
        };
        let (d0, d1) = (d(&table[1]), d(&table[2]));
        let expected = (5e-2f64.ln() + (5e-5f64.ln() - 5e-2f64.ln()) * d0 / (d0 - d1)).exp();
        let at = x[0].at.unwrap();
        assert!(
            (at / expected - 1.0).abs() < 1e-12 && at < 5e-2 && at > 5e-5,
            "{at}"
        );
    }
}
