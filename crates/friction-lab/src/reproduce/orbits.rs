//! Limit cycles as orbits (`orbits/`): the belt with CVS followed over its belt speed, steady
//! sliding and the stick–slip cycle as branches with their stability, the Hopf point where
//! steady sliding turns stable and the speed where the cycle's stick phase vanishes, between
//! which the two coexist ([`BranchesStudy`]); the servo's hunting cycle with the static law,
//! found as an orbit with its Floquet multipliers ([`OrbitStudy`]).

use super::solver_studies::case;
use super::Part;
use crate::error::AppError;
use crate::study::{conduct, BranchesStudy, OrbitStudy, Output};
use friction_models::params::show;
use friction_models::{FrictionParams, ModelId};
use periodic::{ShootingOptions, SpecialKind};
use scenarios::orbit::OrbitSettings;
use scenarios::Scenario;

/// The belt speeds followed, m/s.
pub const BELT_RANGE: (f64, f64) = (0.02, 3.0);

/// The servo's settling run, s: a few of its 38 s cycles.
pub const SERVO_SETTLE: f64 = 200.0;

/// The report's section of orbits.
pub struct Orbits {
    /// The friction parameters.
    pub friction: FrictionParams,
}

impl Part for Orbits {
    fn heading(&self) -> String {
        "Limit cycles as orbits".into()
    }

    fn folder(&self) -> &'static str {
        "orbits"
    }

    fn conduct(&self, target: &mut Output) -> Result<String, AppError> {
        let settings = |settle: f64| OrbitSettings {
            settle,
            shooting: ShootingOptions::default(),
            samples: 201,
        };
        let belt = case(Scenario::BELT, ModelId::Cvs, &self.friction, 20.0);
        let study = BranchesStudy {
            case: &belt,
            parameter: "v_belt",
            range: BELT_RANGE,
            at: &[],
            settings: settings(20.0),
        };
        let branches = conduct(&study, target, "continue")?;
        let at = |on: &str, kind: SpecialKind| {
            (branches.special.iter())
                .find(|(b, s)| *b == on && s.kind == kind)
                .map_or("none".to_string(), |(_, s)| format!("{:.4} m/s", s.p))
        };
        let (hopf, end) = (
            at("equilibrium", SpecialKind::Hopf),
            at("cycle", SpecialKind::SegmentsChange),
        );
        let servo = case(
            Scenario::SERVO,
            ModelId::Static,
            &self.friction,
            SERVO_SETTLE,
        );
        let orbit = conduct(
            &OrbitStudy {
                case: &servo,
                settings: settings(SERVO_SETTLE),
            },
            target,
            "orbit-servo",
        )?;
        let multipliers: Vec<String> = (orbit.floquet.multipliers.iter())
            .map(|&(re, im)| format!("{:.3e}", re.hypot(im)))
            .collect();
        Ok(format!(
            "The cycles the other sections find by simulating until a run settles, computed as \
             periodic orbits: Newton's shooting through the switches, the monodromy matrix \
             through their saltation matrices, and pseudo-arclength continuation \
             (docs/periodic-orbits.md).\n\n\
             - The belt with CVS over v_belt from {} to {} m/s ([branch.csv](orbits/branch.csv), \
             [special_points.csv](orbits/special_points.csv), \
             [continue.png](orbits/continue.png)): steady sliding is unstable below the Hopf \
             point at {hopf} and stable above it; the stick–slip cycle is stable along its \
             branch, which ends where its stick phase vanishes, at {end}. Between the two, \
             steady sliding and stick–slip coexist.\n\
             - The servo's hunting cycle with the static law \
             ([orbit-servo.json](orbits/orbit-servo.json)): period {} s, Floquet multipliers \
             of moduli {} ({}).\n",
            show(BELT_RANGE.0),
            show(BELT_RANGE.1),
            show(
                format!("{:.6e}", orbit.period)
                    .parse()
                    .unwrap_or(orbit.period)
            ),
            multipliers.join(", "),
            format!("{:?}", orbit.floquet.stability).to_lowercase(),
        ))
    }
}
