//! The paper's closed-loop criterion (`closed-loop/`): the servo rig with each of the six
//! models and LuGre as the plant and as the compensator ([`ClosedLoopStudy`]), and a hunting
//! map of the servo over the integral gain and the static level.

use super::Part;
use crate::error::AppError;
use crate::laws::ModelChoice;
use crate::simulate::{SimulationRequest, Target as RunTarget};
use crate::study::{conduct, ClosedLoopStudy, ClosedLoops, Output, TASKS};
use crate::sweep::{Axis, PointResult, Start, SweepRequest};
use friction_models::ModelId;
use scenarios::phenomena::Protocol;
use scenarios::stick_slip::Regime;
use scenarios::{Law, Scenario};

/// The hunting map's integral gains, N/(m·s).
const MAP_KI: [f64; 6] = [0.0, 0.5, 1.0, 2.0, 4.0, 8.0];
/// The hunting map's static levels, N (F_c = 6 N).
const MAP_F_S: [f64; 5] = [6.0, 6.5, 7.0, 7.5, 9.0];

/// The report's section on the closed loop.
pub struct ClosedLoopPart;

/// The plants and compensators: the paper's six models and LuGre (the 1995 example's).
fn plants() -> Vec<Law> {
    ModelId::PAPER
        .iter()
        .chain([&ModelId::LuGre])
        .map(|&m| Law::from(m))
        .collect()
}

/// The RMS tracking error of `plant` on `task` with `compensator`, mm, as the report says it.
fn rms(r: &ClosedLoops, plant: ModelId, task: &str, compensator: Option<ModelId>) -> String {
    let c = compensator.map(Law::from);
    match r.tracking(&Law::from(plant), task, c.as_ref()) {
        Some(t) if t.failed.is_none() && t.stuck => {
            format!("{:.1} mm (stuck: never moved)", 1e3 * t.rms_error)
        }
        Some(t) if t.failed.is_none() => format!("{:.1} mm", 1e3 * t.rms_error),
        _ => "failed".into(),
    }
}

/// The section's paragraph on the plants at the set point.
fn reads_regulation(r: &ClosedLoops) -> String {
    let named = |hunting: Option<bool>| -> Vec<String> {
        (r.regulation.iter())
            .filter(|g| g.closed_loop.as_ref().map(|c| c.hunting) == Some(hunting))
            .map(|g| g.plant.to_string())
            .collect()
    };
    let lugre = (r.regulation.iter())
        .find(|g| g.plant == Law::from(ModelId::LuGre))
        .and_then(|g| g.closed_loop.as_ref());
    let cycle = lugre.map_or_else(
        || "failed".to_string(),
        |c| {
            format!(
                "period {:.2} s, amplitude {:.1} mm",
                c.period,
                1e3 * c.amplitude
            )
        },
    );
    format!(
        "- [The plants at the set point](closed-loop/closed-loop.md) (1 m, 800 s; \
         [the position error](closed-loop/closed-loop-error.png)): hunting with {}; converged \
         with {}; not settled with {}. LuGre at the 1995 parameters, the paper's example: {cycle}.\n",
        or_none(&named(Some(true))),
        or_none(&named(Some(false))),
        or_none(&named(None)),
    )
}

/// `names` joined, or "none".
fn or_none(names: &[String]) -> String {
    if names.is_empty() {
        "none".into()
    } else {
        names.join(", ")
    }
}

/// The section's paragraph on compensation: the two mismatches the issue names, against none
/// and the plant's own model, on each task.
fn reads_tracking(r: &ClosedLoops) -> String {
    let mut s = String::from(
        "- [Friction compensation](closed-loop/closed-loop.md) (the compensator's steady friction \
         at the reference velocity, at the plant's parameters), RMS tracking error of \
         x_r = sin(ωt) m:",
    );
    for task in TASKS {
        let (lugre, cvs, coulomb) = (ModelId::LuGre, ModelId::Cvs, ModelId::Coulomb);
        s += &format!(
            " at ω = {} rad/s, LuGre's plant {} uncompensated, {} by Coulomb, {} by LuGre; \
             CVS's {} uncompensated, {} by LuGre, {} by CVS.",
            task.omega,
            rms(r, lugre, task.name, None),
            rms(r, lugre, task.name, Some(coulomb)),
            rms(r, lugre, task.name, Some(lugre)),
            rms(r, cvs, task.name, None),
            rms(r, cvs, task.name, Some(lugre)),
            rms(r, cvs, task.name, Some(cvs)),
        );
    }
    s + "\n"
}

/// The section's paragraph on the describing function: each idealised law's predicted cycles
/// against its simulated one.
fn reads_describing(r: &ClosedLoops) -> String {
    let rows: Vec<String> = (r.describing_function.iter())
        .map(|d| {
            let predicted = match &d.predicted[..] {
                [] => "none predicted".to_string(),
                cycles => (cycles.iter())
                    .map(|c| {
                        format!(
                            "a cycle of {:.2} s and {:.1} mm predicted",
                            c.period,
                            1e3 * c.half_range
                        )
                    })
                    .collect::<Vec<_>>()
                    .join(" and "),
            };
            let simulated = match (&d.simulated.closed_loop, &d.simulated.failed) {
                (Some(c), None) => match c.hunting {
                    Some(true) => format!(
                        "{:.2} s and {:.1} mm simulated",
                        c.period,
                        1e3 * c.amplitude
                    ),
                    Some(false) => "converged in simulation".into(),
                    None => "not settled in simulation".into(),
                },
                _ => "the simulation failed".into(),
            };
            format!("{}: {predicted}, {simulated}", d.plant)
        })
        .collect();
    format!(
        "- [The describing function](closed-loop/closed-loop.md) of each law idealised as a \
         mass with Coulomb friction, stiction and viscous friction, balanced against the PID: \
         {}.\n",
        rows.join("; ")
    )
}

/// The section's paragraph on the hunting map.
fn reads_map(points: &[PointResult]) -> String {
    let count = |regime: Regime| points.iter().filter(|p| p.regime == Some(regime)).count();
    format!(
        "- [The hunting map](closed-loop/hunting-map.png) of the servo with `static` friction \
         (F_c = 6 N) over ki ∈ {{{}}} N/(m·s) × F_s ∈ {{{}}} N: hunting at {} of {} points, \
         converged at {}, at rest in the dead zone at {}, stuck (never moved) at {}, not \
         settled at {} (each point run again over up to eight times its span while it has not \
         settled).\n",
        MAP_KI.map(|v| v.to_string()).join(", "),
        MAP_F_S.map(|v| v.to_string()).join(", "),
        count(Regime::Hunting),
        points.len(),
        count(Regime::Converged),
        count(Regime::DeadZone),
        count(Regime::Stuck),
        count(Regime::Unsettled),
    )
}

impl Part for ClosedLoopPart {
    fn heading(&self) -> String {
        "Closed loop: hunting and friction compensation".into()
    }

    fn folder(&self) -> &'static str {
        "closed-loop"
    }

    fn conduct(&self, target: &mut Output) -> Result<String, AppError> {
        let laws = plants();
        let mut compensators = laws.clone();
        compensators.push(Law::from(ModelId::Coulomb));
        let idealised = [ModelId::Static, ModelId::Coulomb, ModelId::LuGre].map(Law::from);
        let study = ClosedLoopStudy {
            plants: &laws,
            compensators: &compensators,
            idealised: &idealised,
            protocol: Protocol::default(),
        };
        let loops = conduct(&study, target, "closed-loop")?;
        let map = SweepRequest {
            simulation: SimulationRequest::new(
                RunTarget::Rig(Scenario::SERVO),
                Some(ModelChoice::Catalog(ModelId::Static)),
            ),
            axes: vec![
                Axis::new("ki", MAP_KI.to_vec())?,
                Axis::new("F_s", MAP_F_S.to_vec())?,
            ],
            settle: 0.5,
            start: Start::Rest,
            range: None,
            threads: None,
        };
        let points = map.conduct(target, "hunting-map")?;
        Ok(format!(
            "The paper's second criterion, a model's prediction of the limit cycles of a closed \
             loop, on the servo rig (docs/closed-loop.md): the 1995 example's PID positioning \
             a unit mass, each model as the plant at its Table 2 parameters, integrated as \
             Table 2's protocols are.\n\n{}{}{}{}",
            reads_regulation(&loops),
            reads_describing(&loops),
            reads_tracking(&loops),
            reads_map(&points)
        ))
    }
}
