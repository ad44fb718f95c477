//! The paper's closed-loop criterion on its models ([`ClosedLoopStudy`]): each model as the
//! plant of the servo rig at its set point (does it hunt, with what period and amplitude; the
//! position error against time), and each as the friction compensator of every plant on a
//! slow and a fast reference (the tracking error, against no compensation); and the
//! describing-function prediction of the hunting cycle beside the simulated one.

use super::{Study, StudyFiles};
use crate::error::AppError;
use crate::plot::{Corner, Plot, Series, PALETTE};
use friction_systems::{CompensatedAt, Compensation, Reference};
use integrators::even_grid;
use scenarios::analysis::closed_loop::ClosedLoop;
use scenarios::analysis::describing_function::{
    break_away_gain, predict_hunting, HuntingPrediction, Pid, StictionMass,
};
use scenarios::phenomena::{own_parameters, thresholds, Protocol};
use scenarios::stick_slip::Regime;
use scenarios::tracking::run_tracking;
use scenarios::{Law, Outcome, RunSpec, Scenario, ScenarioParams};
use serde::Serialize;
use std::f64::consts::PI;

/// Points of the position error drawn and kept per plant.
const DRAWN_POINTS: usize = 801;
/// Output points of a tracking run.
pub const TRACKING_POINTS: usize = 4001;

/// A reference the compensated loop tracks: x_r = A·sin ωt, A = 1 m, from rest at x = 0.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Task {
    /// Its name in the files (`slow`, `fast`).
    pub name: &'static str,
    /// ω, rad/s; the largest reference speed is A·ω.
    pub omega: f64,
}

impl Task {
    /// The reference.
    pub fn reference(&self) -> Reference {
        Reference::Sinusoid {
            x0: 0.0,
            amplitude: 1.0,
            omega: self.omega,
        }
    }
}

/// The two tasks: 0.1 m/s and 1 m/s at most, each run over two periods of the slow one.
pub const TASKS: [Task; 2] = [
    Task {
        name: "slow",
        omega: 0.1,
    },
    Task {
        name: "fast",
        omega: 1.0,
    },
];

/// The length of every tracking run: two periods of the slow task, s.
pub fn tracking_t_end() -> f64 {
    4.0 * PI / TASKS[0].omega
}

/// The plants, the compensators and the protocol of a closed-loop study.
pub struct ClosedLoopStudy<'a> {
    /// The plants, each at its Table 2 parameter set ([`own_parameters`]).
    pub plants: &'a [Law],
    /// The compensators tried on every plant besides none, each at the plant's parameters
    /// (the same friction levels, another shape), evaluated at the reference velocity.
    pub compensators: &'a [Law],
    /// The laws whose describing-function prediction is set beside their simulated cycle at
    /// the set point, each idealised at its Table 2 parameters
    /// ([`StictionMass::idealising`]); simulated as the plants are.
    pub idealised: &'a [Law],
    /// The solver, tolerances and bounds of every run (event switching).
    pub protocol: Protocol,
}

/// One plant at the servo's set point.
#[derive(Clone, Debug, Serialize)]
pub struct Regulation {
    /// The plant.
    #[serde(serialize_with = "law_name")]
    pub plant: Law,
    /// Its closed loop ([`ClosedLoop`]); `None` where the run failed.
    pub closed_loop: Option<ClosedLoop>,
    /// Why the run failed, if it did.
    pub failed: Option<String>,
    /// The position error r − x at 801 even times, for the figure.
    #[serde(skip)]
    pub error: Vec<(f64, f64)>,
}

/// One plant tracking one task with one compensator (or none).
#[derive(Clone, Debug, Serialize)]
pub struct Tracking {
    /// The plant.
    #[serde(serialize_with = "law_name")]
    pub plant: Law,
    /// The compensator, `None` for none.
    #[serde(serialize_with = "maybe_law_name")]
    pub compensator: Option<Law>,
    /// The task's name.
    pub task: &'static str,
    /// The RMS tracking error, m (NaN, written null, where the run failed).
    pub rms_error: f64,
    /// The largest tracking error, m (NaN where the run failed).
    pub max_error: f64,
    /// Whether the body never moved: its error is then the reference's own (`false` where
    /// the run failed).
    pub stuck: bool,
    /// Why the run failed, if it did.
    pub failed: Option<String>,
}

/// One law's describing-function prediction of the servo's cycle and its simulated cycle.
#[derive(Clone, Debug, Serialize)]
pub struct Described {
    /// The law.
    #[serde(serialize_with = "law_name")]
    pub plant: Law,
    /// The mass with its friction idealised; `None` for a law without an idealisation.
    pub idealised: Option<StictionMass>,
    /// |C·N| at the phase crossover as the mass starts to move ([`break_away_gain`]).
    pub break_away_gain: Option<f64>,
    /// The cycles of the harmonic balance; none predicted where empty.
    pub predicted: Vec<HuntingPrediction>,
    /// The simulated run at the set point (Table 2's hunting run).
    pub simulated: Regulation,
}

fn law_name<S: serde::Serializer>(law: &Law, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&law.to_string())
}

fn maybe_law_name<S: serde::Serializer>(law: &Option<Law>, s: S) -> Result<S::Ok, S::Error> {
    match law {
        Some(law) => s.serialize_str(&law.to_string()),
        None => s.serialize_none(),
    }
}

/// What a closed-loop study measured.
#[derive(Clone, Debug, Serialize)]
pub struct ClosedLoops {
    /// Each plant at the set point, in order.
    pub regulation: Vec<Regulation>,
    /// Each plant, task and compensator (none first, then in order).
    pub tracking: Vec<Tracking>,
    /// Each idealised law's predicted and simulated cycle.
    pub describing_function: Vec<Described>,
}

impl ClosedLoops {
    /// The tracking of `plant` on `task` with `compensator`.
    pub fn tracking(
        &self,
        plant: &Law,
        task: &str,
        compensator: Option<&Law>,
    ) -> Option<&Tracking> {
        self.tracking
            .iter()
            .find(|t| &t.plant == plant && t.task == task && t.compensator.as_ref() == compensator)
    }
}

impl ClosedLoopStudy<'_> {
    fn spec(&self, plant: &Law, t_end: f64, points: usize) -> RunSpec {
        let (friction, params) = (own_parameters(plant), ScenarioParams::default());
        (self.protocol).spec(Scenario::SERVO, plant, friction, params, t_end, points)
    }

    fn regulate(&self, plant: &Law) -> Result<Regulation, AppError> {
        // Table 2's hunting run.
        let spec = self.spec(plant, thresholds::HUNTING_T_END, thresholds::HUNTING_POINTS);
        let o = scenarios::run(&spec, &mut |_| {})?;
        Ok(Regulation {
            plant: plant.clone(),
            closed_loop: match &o.error {
                Some(_) => None,
                None => ClosedLoop::of_outcome(&o),
            },
            failed: o.error.as_ref().map(|e| e.to_string()),
            error: drawn_error(&o),
        })
    }

    /// The idealisation of `law` and the cycles its harmonic balance predicts in the servo.
    fn predict(&self, law: &Law) -> (Option<StictionMass>, Option<f64>, Vec<HuntingPrediction>) {
        let p = ScenarioParams::default();
        let pid = Pid {
            kp: p.kp,
            ki: p.ki,
            kd: p.kd,
        };
        match StictionMass::idealising(law, &own_parameters(law), p.m) {
            Some(mass) => (
                Some(mass),
                break_away_gain(&mass, &pid),
                predict_hunting(&mass, &pid),
            ),
            None => (None, None, Vec::new()),
        }
    }

    fn track(
        &self,
        plant: &Law,
        compensator: Option<&Law>,
        task: Task,
    ) -> Result<Tracking, AppError> {
        let spec = self.spec(plant, tracking_t_end(), TRACKING_POINTS);
        let compensation = compensator
            .map(|c| {
                Ok::<_, AppError>(Compensation {
                    model: c.build(&spec.friction)?,
                    at: CompensatedAt::Reference,
                })
            })
            .transpose()?;
        let reference = task.reference();
        let o = run_tracking(&spec, &reference, compensation.as_ref(), &mut |_| {})?;
        let (rms_error, max_error, stuck) = match &o.error {
            Some(_) => (f64::NAN, f64::NAN, false),
            None => {
                let c = ClosedLoop::of(&o, &reference);
                (c.rms_error, c.max_error, c.stuck)
            }
        };
        Ok(Tracking {
            plant: plant.clone(),
            compensator: compensator.cloned(),
            task: task.name,
            rms_error,
            max_error,
            stuck,
            failed: o.error.as_ref().map(|e| e.to_string()),
        })
    }
}

/// The position error r − x of a regulation run at [`DRAWN_POINTS`] even times (the recorded
/// rows nearest below each).
fn drawn_error(o: &Outcome) -> Vec<(f64, f64)> {
    let Some(reference) = &o.reference else {
        return Vec::new();
    };
    let Some(last) = o.rows.last() else {
        return Vec::new();
    };
    let mut k = 0;
    even_grid(0.0, last.t, DRAWN_POINTS)
        .into_iter()
        .map(|t| {
            while k + 1 < o.rows.len() && o.rows[k + 1].t <= t {
                k += 1;
            }
            let r = &o.rows[k];
            (r.t, reference.at(r.t).0 - r.x)
        })
        .collect()
}

/// A job of the study.
enum Job<'a> {
    Regulate(&'a Law),
    Track(&'a Law, Option<&'a Law>, Task),
    Predict(&'a Law),
}

enum Done {
    Regulation(Regulation),
    Tracking(Tracking),
    Prediction(Option<StictionMass>, Option<f64>, Vec<HuntingPrediction>),
}

impl ClosedLoopStudy<'_> {
    /// The idealised laws that are not plants, whose set-point runs the study adds.
    fn extra(&self) -> impl Iterator<Item = &Law> {
        (self.idealised.iter()).filter(|l| !self.plants.contains(l))
    }
}

impl Study for ClosedLoopStudy<'_> {
    type Result = ClosedLoops;

    fn name(&self) -> &'static str {
        "closed loop"
    }

    fn runs(&self) -> usize {
        self.plants.len() * (1 + (1 + self.compensators.len()) * TASKS.len())
            + self.extra().count()
            + self.idealised.len()
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<ClosedLoops, AppError> {
        use rayon::prelude::*;
        let mut jobs: Vec<Job> = (self.plants.iter().chain(self.extra()))
            .map(Job::Regulate)
            .collect();
        jobs.extend(self.idealised.iter().map(Job::Predict));
        for plant in self.plants {
            for task in TASKS {
                jobs.push(Job::Track(plant, None, task));
                for c in self.compensators {
                    jobs.push(Job::Track(plant, Some(c), task));
                }
            }
        }
        let done = jobs
            .par_iter()
            .map(|job| {
                let d = match *job {
                    Job::Regulate(plant) => Done::Regulation(self.regulate(plant)?),
                    Job::Track(plant, c, task) => Done::Tracking(self.track(plant, c, task)?),
                    Job::Predict(law) => {
                        let (mass, gain, cycles) = self.predict(law);
                        Done::Prediction(mass, gain, cycles)
                    }
                };
                progress();
                Ok(d)
            })
            .collect::<Result<Vec<Done>, AppError>>()?;
        let (mut regulation, mut tracking, mut predictions) = (Vec::new(), Vec::new(), Vec::new());
        for d in done {
            match d {
                Done::Regulation(r) => regulation.push(r),
                Done::Tracking(t) => tracking.push(t),
                Done::Prediction(mass, gain, cycles) => predictions.push((mass, gain, cycles)),
            }
        }
        let describing_function = (self.idealised.iter().zip(predictions))
            .map(|(law, (idealised, break_away_gain, predicted))| Described {
                plant: law.clone(),
                idealised,
                break_away_gain,
                predicted,
                simulated: (regulation.iter())
                    .find(|g| &g.plant == law)
                    .cloned()
                    .unwrap_or_else(|| unreachable!("every idealised law is regulated")),
            })
            .collect();
        regulation.truncate(self.plants.len());
        Ok(ClosedLoops {
            regulation,
            tracking,
            describing_function,
        })
    }

    /// `{stem}.md` (the hunting table and the tracking tables), `{stem}.json` (every run's
    /// measures) and `{stem}-error.png`/`.svg` (the position error of every plant, a panel
    /// each).
    fn write(&self, result: &ClosedLoops, out: &mut StudyFiles) -> Result<(), AppError> {
        out.files
            .add(out.path(".md"), markdown(self, result).into_bytes());
        out.files
            .add_panels(&out.path("-error"), &error_figure(result))?;
        out.add_json(result)
    }
}

/// A length in millimetres, `-` for an undefined one.
fn mm(x: f64) -> String {
    if x.is_finite() {
        format!("{:.2}", 1e3 * x)
    } else {
        "-".into()
    }
}

/// The study as Markdown.
fn markdown(study: &ClosedLoopStudy, r: &ClosedLoops) -> String {
    let mut s = String::from(
        "# The models in closed loop\n\nThe servo rig (a unit mass on the floor, PID kp = 3 \
         N/m, ki = 4 N/(m·s), kd = 6 N·s/m; docs/closed-loop.md) with each model as the plant, \
         at its Table 2 parameters, integrated by the Table 2 protocol.\n\n## At the set point \
         (1 m, 800 s)\n\n| plant | closed loop | period (s) | amplitude (mm) | stuck per cycle \
         (s) | final error (mm) |\n|---|---|---|---|---|---|\n",
    );
    for g in &r.regulation {
        match (&g.closed_loop, &g.failed) {
            (Some(c), None) => {
                let verdict = match Regime::of_closed_loop(c) {
                    Regime::Hunting => "hunting",
                    Regime::Converged => "converged",
                    Regime::DeadZone => "dead zone",
                    Regime::Stuck => "stuck (never moved)",
                    _ => "not settled",
                };
                s += &format!(
                    "| {} | {verdict} | {} | {} | {} | {} |\n",
                    g.plant,
                    num(c.period),
                    mm(c.amplitude),
                    num(c.stick_time_per_cycle),
                    mm(c.final_error)
                );
            }
            (_, why) => {
                let why = why.as_deref().unwrap_or("no controller");
                s += &format!("| {} | failed: {why} | | | | |\n", g.plant)
            }
        }
    }
    s += "\nThe position error against time: `closed-loop-error.png`.\n";
    for task in TASKS {
        s += &format!(
            "\n## Tracking x_r = sin({} t) m (at most {} m/s), RMS error (mm) over {:.1} s\n\n\
             Each column a compensator (the feed-forward of its steady friction at the \
             reference velocity, at the plant's parameters), `none` first.\n\n| plant | none |",
            task.omega,
            task.omega,
            tracking_t_end()
        );
        for c in study.compensators {
            s += &format!(" {c} |");
        }
        s += "\n|---|---|";
        s += &"---|".repeat(study.compensators.len());
        s += "\n";
        for plant in study.plants {
            s += &format!("| {plant} |");
            let cell = |c: Option<&Law>| match r.tracking(plant, task.name, c) {
                Some(t) if t.failed.is_none() && t.stuck => format!("{} stuck", mm(t.rms_error)),
                Some(t) if t.failed.is_none() => mm(t.rms_error),
                Some(_) => "failed".into(),
                None => "-".into(),
            };
            s += &format!(" {} |", cell(None));
            for c in study.compensators {
                let mut v = cell(Some(c));
                if c == plant {
                    v = format!("**{v}**");
                }
                s += &format!(" {v} |");
            }
            s += "\n";
        }
    }
    s += "\nBold: the plant's own model as its compensator. Stuck: the body never moved, so \
          its error is the reference's own. Failed runs: `closed-loop.json` says why.\n";
    if !r.describing_function.is_empty() {
        s += &describing_markdown(r);
    }
    s
}

/// A number to two decimals, `-` for an undefined one.
fn num(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.2}")
    } else {
        "-".into()
    }
}

/// The describing-function section: each idealised law's predicted cycles beside its
/// simulated one.
fn describing_markdown(r: &ClosedLoops) -> String {
    let mut s = String::from(
        "\n## The describing function beside the simulation\n\nEach law idealised as the mass \
         with Coulomb friction F_c, stiction F_s and viscous friction F_v; its describing \
         function (force in, position out, the mass and its friction together) balanced \
         against the PID, 1 + C(jω)·N(U, ω) = 0 (docs/closed-loop.md). Gain: |C·N| at the \
         phase crossover as the mass starts to move (N jumps there from 0). Predicted amplitude: half the range of x in the response to \
         U·sin ωt (the simulated one: half the range of the error).\n\n| law | F_c, F_s, F_v \
         | gain | predicted period (s) | U (N) | amplitude (mm) | stuck per period (s) | \
         simulated | period (s) | amplitude (mm) | stuck per cycle (s) |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for d in &r.describing_function {
        let ideal = d.idealised.map_or_else(
            || "no idealisation".to_string(),
            |m| format!("{}, {}, {}", m.f_c, m.f_s, m.f_v),
        );
        let gain = d.break_away_gain.map_or_else(|| "-".into(), num);
        let simulated = match (&d.simulated.closed_loop, &d.simulated.failed) {
            (Some(c), None) => match c.hunting {
                Some(true) => format!(
                    "hunting | {} | {} | {}",
                    num(c.period),
                    mm(c.amplitude),
                    num(c.stick_time_per_cycle)
                ),
                Some(false) => "converged | | | ".into(),
                None => "not settled | | | ".into(),
            },
            (_, why) => format!(
                "failed: {} | | | ",
                why.as_deref().unwrap_or("no controller")
            ),
        };
        if d.predicted.is_empty() {
            s += &format!(
                "| {} | {ideal} | {gain} | none | | | | {simulated} |\n",
                d.plant
            );
        }
        for c in &d.predicted {
            s += &format!(
                "| {} | {ideal} | {gain} | {} | {} | {} | {} | {simulated} |\n",
                d.plant,
                num(c.period),
                num(c.force_amplitude),
                mm(c.half_range),
                num(c.stick_time)
            );
        }
    }
    s
}

/// The position error of every plant at the set point against time: a panel each, named in
/// its title (seven square waves on one panel could not be told apart).
fn error_figure(r: &ClosedLoops) -> Vec<Plot> {
    (r.regulation.iter().enumerate())
        .map(|(i, g)| Plot {
            title: format!("Servo with {} at its set point", g.plant),
            x_label: "time t (s)".into(),
            y_label: "position error r − x (m)".into(),
            series: vec![Series {
                label: None,
                points: g.error.clone(),
                color: PALETTE[i % PALETTE.len()],
                width: 1,
                marker: Default::default(),
                dash: crate::plot::Dash::Solid,
            }],
            legend: Corner::UpperRight,
            log: false,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{ClosedLoopStudy, Study, TASKS};
    use friction_models::ModelId;
    use scenarios::phenomena::{decide, parameters_for, Phenomenon, Protocol};
    use scenarios::Law;

    #[test]
    fn hunting_agrees_with_table_2_and_compensation_restores_coulomb_tracking() {
        let plants = [ModelId::Static, ModelId::Viscous, ModelId::Coulomb].map(Law::from);
        let compensators = [Law::from(ModelId::Coulomb)];
        let c_period = |r: &super::ClosedLoops| r.regulation[0].closed_loop.unwrap().period;
        let study = ClosedLoopStudy {
            plants: &plants,
            compensators: &compensators,
            idealised: &plants,
            protocol: Protocol::default(),
        };
        assert_eq!(study.runs(), 3 * (1 + 2 * TASKS.len()) + 3);
        let r = study.run(&|| {}).unwrap();
        // At the set point: the same cycle as Table 2's hunting cell (the same run).
        let table2 = decide(
            Phenomenon::HUNTING,
            &plants[0],
            &parameters_for(ModelId::Static),
            Protocol::default(),
        )
        .unwrap();
        let c = r.regulation[0].closed_loop.as_ref().unwrap();
        assert!(r.regulation[0].failed.is_none());
        assert_eq!(c.hunting, Some(true));
        assert_eq!(c.period, table2.evidence["period_s"]);
        let c = r.regulation[1].closed_loop.as_ref().unwrap();
        assert_eq!(c.hunting, Some(false), "viscous friction converges");
        assert_eq!(r.regulation[0].error.len(), super::DRAWN_POINTS);
        assert_eq!(r.regulation.len(), 3);
        // The describing function: one cycle for stiction, at under half the simulated period
        // (11.9 s against 38.2 s); none for the linear plant; a cycle for Coulomb friction,
        // whose simulated loop never settles (module `describing_function`).
        let [stiction, viscous, coulomb] = &r.describing_function[..] else {
            panic!("three idealised laws: {:?}", r.describing_function);
        };
        assert_eq!(stiction.predicted.len(), 1);
        let simulated = stiction.simulated.closed_loop.unwrap();
        assert_eq!(simulated.period, c_period(&r));
        assert!(stiction.predicted[0].period < 0.5 * simulated.period);
        assert!(viscous.predicted.is_empty());
        assert_eq!(coulomb.predicted.len(), 1);
        assert_eq!(coulomb.simulated.closed_loop.unwrap().hunting, None);
        // Coulomb friction compensated by its own model at the reference velocity: the
        // feed-forward cancels it wherever the body follows the reference's direction, and
        // the tracking error falls to well under half of the uncompensated one on both tasks.
        for task in TASKS {
            let rms = |c: Option<&Law>| {
                let t = r.tracking(&plants[2], task.name, c).unwrap();
                assert!(t.failed.is_none(), "{:?}", t.failed);
                t.rms_error
            };
            let (none, compensated) = (rms(None), rms(Some(&compensators[0])));
            assert!(
                compensated < 0.5 * none,
                "{}: {compensated} m compensated, {none} m not",
                task.name
            );
        }
    }
}
