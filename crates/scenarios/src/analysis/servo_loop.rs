//! A closed loop analysed two ways: simulated, the system's first controller and its body
//! ([`ClosedLoop`]: hunting, period, amplitude, time stuck per cycle, final error, regime), and
//! predicted by the describing function ([`predict_hunting`]) where the loop is of the form
//! it takes: a mass on a still surface with friction of the Coulomb–stiction–viscous form
//! ([`friction_models::FrictionModel::stiction_levels`]), positioned by an unsaturated,
//! uncompensated PID towards a set point, and acted on by nothing else ([`servo_plant`]).

use super::closed_loop::ClosedLoop;
use super::describing_function::{
    break_away_gain, predict_hunting, HuntingPrediction, Pid, StictionMass,
};
use crate::stick_slip::Regime;
use friction_systems::{End, Reference, Run, System};
use serde::Serialize;

/// A loop's simulated measures beside its describing-function prediction.
#[derive(Clone, Debug, Serialize)]
pub struct LoopAnalysis {
    /// The controlled body's name.
    pub body: String,
    /// The controller's gains.
    pub pid: Pid,
    /// The simulated loop's measures, over the rows recorded (up to a failure).
    pub simulated: ClosedLoop,
    /// What it settled into ([`Regime::of_closed_loop`]).
    pub regime: Regime,
    /// The plant as the describing function takes it; `None` where the loop is not of its
    /// form.
    pub idealised: Option<StictionMass>,
    /// Why the loop is not of the describing function's form, where it is not.
    pub not_predicted: Option<String>,
    /// |C·N| at the phase crossover as the mass starts to move ([`break_away_gain`]).
    pub break_away_gain: Option<f64>,
    /// The cycles of the harmonic balance (none: no hunting predicted).
    pub predicted: Vec<HuntingPrediction>,
}

/// The servo plant of `system`'s first controller as the describing function takes it: its
/// body's mass with its contact's stiction levels (no contact: no friction); or why the loop
/// is not of that form (a spring or a force on the body, a moving surface, a law of another
/// form, a saturated or compensated actuator, a reference other than a set point).
pub fn servo_plant(system: &System) -> Result<StictionMass, String> {
    let Some(c) = system.controllers.first() else {
        return Err("the system has no controller".into());
    };
    let body = &system.bodies[c.body];
    let name = &body.name;
    let touches = |end: &End| matches!(end, End::Body(b) if *b == c.body);
    if system
        .springs
        .iter()
        .any(|s| touches(&s.a) || touches(&s.b))
    {
        return Err(format!(
            "a spring holds body {name}: the describing function takes a mass acted on by \
             friction and the controller alone"
        ));
    }
    if system.forces.iter().any(|f| f.body == c.body) {
        return Err(format!(
            "an external force acts on body {name}: the describing function takes a mass \
             acted on by friction and the controller alone"
        ));
    }
    if c.saturation.is_some() {
        return Err("the actuator saturates: the describing function takes a linear PID".into());
    }
    if c.compensation.is_some() {
        return Err(
            "the controller compensates friction: the describing function takes a PID alone".into(),
        );
    }
    if !matches!(c.reference, Reference::Constant { .. }) {
        return Err(
            "the reference moves: the describing function predicts the cycle about a set point"
                .into(),
        );
    }
    let Some(contact) = system.contacts.iter().find(|k| k.body == c.body) else {
        return Ok(StictionMass {
            m: body.m,
            f_c: 0.0,
            f_s: 0.0,
            f_v: 0.0,
        });
    };
    if contact.surface_velocity != 0.0 {
        return Err(format!(
            "body {name} rubs on a surface moving at {} m/s: the describing function takes a \
             still one",
            contact.surface_velocity
        ));
    }
    StictionMass::of(contact.model.as_ref(), body.m).ok_or_else(|| {
        format!(
            "the friction law {} is not of the Coulomb–stiction–viscous form the describing \
             function takes (static, coulomb, viscous, karnopp, lugre, or a law of one's own \
             that gives its stiction levels)",
            contact.model.name()
        )
    })
}

/// The analysis of `system`'s first controller, its run `run` measured and, where the loop is
/// of the form the describing function takes, its hunting cycle predicted; `None` for a
/// system without a controller.
pub fn analyse(system: &System, run: &Run) -> Option<LoopAnalysis> {
    let simulated = ClosedLoop::of_run(run, system)?;
    let c = system.controllers.first()?;
    let pid = Pid {
        kp: c.kp,
        ki: c.ki,
        kd: c.kd,
    };
    let (idealised, not_predicted) = match servo_plant(system) {
        Ok(mass) => (Some(mass), None),
        Err(why) => (None, Some(why)),
    };
    Some(LoopAnalysis {
        body: system.bodies[c.body].name.clone(),
        pid,
        regime: Regime::of_closed_loop(&simulated),
        simulated,
        break_away_gain: idealised.as_ref().and_then(|m| break_away_gain(m, &pid)),
        predicted: idealised
            .as_ref()
            .map_or_else(Vec::new, |m| predict_hunting(m, &pid)),
        idealised,
        not_predicted,
    })
}
