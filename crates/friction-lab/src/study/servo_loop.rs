//! The closed loop of a rig or a system with a controller ([`LoopStudy`]): its run under the
//! hunting protocol's solver and tolerances, the loop's measures and regime, and the
//! describing function's prediction of its hunting cycle where the loop is of the form it
//! takes ([`scenarios::analysis::servo_loop`]).

use super::{Study, StudyFiles};
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Plot, Series, RED};
use friction_models::params::show;
use friction_systems::{simulate, Run, Scheme, System};
use integrators::{even_grid, Options, Output};
use scenarios::analysis::servo_loop::{analyse, LoopAnalysis};
use scenarios::phenomena::Protocol;
use scenarios::studies::StudyCase;
use serde::Serialize;

/// The closed loop of `case`, run to its end time with `points` output points.
pub struct LoopStudy<'a> {
    /// The problem: the servo rig, or a system file with a controller.
    pub case: &'a dyn StudyCase,
    /// Output points over the run, evenly spaced (the loop's measures read them).
    pub points: usize,
}

/// What the study found: the analysis, the position error r − x at the output points, and the
/// run's failure, if it failed.
pub struct LoopResult {
    /// The simulated measures beside the prediction.
    pub analysis: LoopAnalysis,
    /// (t, r, x) of the controlled body at the recorded times.
    pub trace: Vec<(f64, f64, f64)>,
    /// Why the run stopped early, where it did.
    pub failed: Option<String>,
}

impl LoopStudy<'_> {
    /// The case's system with a controller, or why it has none.
    fn system(&self) -> Result<System, AppError> {
        let system = self.case.system()?.ok_or_else(|| self.no_loop())?;
        if system.controllers.is_empty() {
            return Err(self.no_loop());
        }
        Ok(system)
    }

    fn no_loop(&self) -> AppError {
        AppError::Usage(format!(
            "{} has no controller: closed-loop analyses the servo rig, or a system file with a \
             [[controller]] table (docs/systems.md)",
            self.case.describe()
        ))
    }

    /// The run under the hunting protocol ([`Protocol::default`]: its solver, tolerances and
    /// bounds), event-driven, recorded at the even output points and at every event.
    fn integrate<'s>(&self, system: &'s System) -> Result<Run<'s>, AppError> {
        let protocol = Protocol::default();
        let t_end = self.case.t_end();
        let options = Options {
            step: protocol.step,
            output: Output::Grid(even_grid(0.0, t_end, self.points)),
            max_steps: protocol.limits.max_steps,
            ..Options::adaptive(0.0, t_end, 1e-10, 1e-12)
        };
        Ok(simulate(
            system,
            Scheme::events(protocol.solver),
            options,
            &mut |_| {},
        )?)
    }
}

/// The lines a front end prints: the simulated loop, and the prediction or why there is none.
pub fn loop_lines(r: &LoopResult) -> Vec<String> {
    let a = &r.analysis;
    let mut lines = vec![format!(
        "body \"{}\" under kp = {} N/m, ki = {} N/(m·s), kd = {} N·s/m: {}",
        a.body,
        show(a.pid.kp),
        show(a.pid.ki),
        show(a.pid.kd),
        a.simulated
    )];
    match (&a.idealised, &a.not_predicted) {
        (_, Some(why)) => lines.push(format!("describing function: no prediction, {why}")),
        (Some(mass), None) => {
            let levels = format!(
                "m = {} kg, F_c = {} N, F_s = {} N, F_v = {} N·s/m",
                show(mass.m),
                show(mass.f_c),
                show(mass.f_s),
                show(mass.f_v)
            );
            if a.predicted.is_empty() {
                lines.push(format!(
                    "describing function ({levels}): no hunting cycle predicted"
                ));
            }
            for c in &a.predicted {
                lines.push(format!(
                    "describing function ({levels}): a cycle of period {:.4} s, half range of \
                     x {:.4} m, {:.4} s at rest a period",
                    c.period, c.half_range, c.stick_time
                ));
            }
        }
        (None, None) => {}
    }
    lines
}

impl Study for LoopStudy<'_> {
    type Result = LoopResult;

    fn name(&self) -> &'static str {
        "closed loop"
    }

    fn check(&self) -> Result<(), AppError> {
        self.system().map(|_| ())
    }

    fn runs(&self) -> usize {
        1
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<LoopResult, AppError> {
        let system = self.system()?;
        let run = self.integrate(&system)?;
        progress();
        let analysis = analyse(&system, &run).ok_or_else(|| self.no_loop())?;
        let c = &system.controllers[0];
        let trace = (run.body(c.body).into_iter())
            .take_while(|b| b.x.is_finite())
            .map(|b| (b.t, c.reference.at(b.t).0, b.x))
            .collect();
        Ok(LoopResult {
            analysis,
            trace,
            failed: run.error.as_ref().map(ToString::to_string),
        })
    }

    fn failure(&self, r: &LoopResult) -> Option<AppError> {
        let why = r.failed.as_ref()?;
        Some(AppError::StudyRun(format!(
            "closed loop: the run failed, {why}; the measures are those of the part it computed"
        )))
    }

    /// `{stem}.json` (the simulated measures, the regime and the prediction), `{stem}.csv`
    /// (t, the reference r, the position x and the error r − x at the recorded times),
    /// `{stem}-predicted.csv` (the predicted cycles) and `{stem}-error` (the error against
    /// time).
    fn write(&self, r: &LoopResult, out: &mut StudyFiles) -> Result<(), AppError> {
        #[derive(Serialize)]
        struct Summary<'a> {
            #[serde(flatten)]
            analysis: &'a LoopAnalysis,
            failed: &'a Option<String>,
        }
        let summary = Summary {
            analysis: &r.analysis,
            failed: &r.failed,
        };
        out.add_json(&super::study_file(self.case, &[], &summary))?;
        let mut trace = Table::new(&["t", "r", "x", "error"]);
        for &(t, reference, x) in &r.trace {
            trace.rows.push(vec![
                Cell::Num(t),
                Cell::Num(reference),
                Cell::Num(x),
                Cell::Num(reference - x),
            ]);
        }
        out.files.add_table(out.path(".csv"), trace)?;
        let mut predicted = Table::new(&[
            "period",
            "omega",
            "force_amplitude",
            "half_range",
            "stick_time",
        ]);
        for c in &r.analysis.predicted {
            predicted.rows.push(
                [
                    c.period,
                    c.omega,
                    c.force_amplitude,
                    c.half_range,
                    c.stick_time,
                ]
                .map(Cell::Num)
                .to_vec(),
            );
        }
        out.files.add_table(out.path("-predicted.csv"), predicted)?;
        out.files.add_plot(
            &out.path("-error"),
            &Plot {
                title: format!("Closed loop of {}: position error", self.case.describe()),
                x_label: "time t (s)".into(),
                y_label: "position error r − x (m)".into(),
                series: vec![Series {
                    label: None,
                    points: r.trace.iter().map(|&(t, r, x)| (t, r - x)).collect(),
                    color: RED,
                    width: 1,
                    marker: Default::default(),
                    dash: Default::default(),
                }],
                legend: Corner::UpperRight,
                log: false,
            },
        )
    }
}
