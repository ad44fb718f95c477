//! The scenario parameters (`m`, `F_ex`, `k`, …), declared with their units and ranges like
//! the friction parameters.

use friction_models::parameters;
use friction_models::params::Range;

/// [0, 1]: a fraction.
const FRACTION: Range = Range {
    min: 0.0,
    min_inclusive: true,
    max: 1.0,
    max_inclusive: true,
};

parameters! {
    /// Parameters of the rigs; each scenario reads the ones it lists in
    /// [`crate::Rig::parameters`].
    pub struct ScenarioParams {
        /// Mass of the body.
        m: "m", "kg", Range::POSITIVE, "mass of the sliding body";
        /// Constant external force.
        f_ex: "F_ex", "N", Range::FINITE, "constant external driving force";
        /// Spring stiffness.
        k: "k", "N/m", Range::NON_NEGATIVE, "stiffness of the spring holding the body";
        /// Damping of the spring.
        c: "c", "N*s/m", Range::NON_NEGATIVE, "damping in parallel with the spring holding the body";
        /// Belt velocity.
        v_belt: "v_belt", "m/s", Range::FINITE, "velocity of the belt under the body";
        /// Initial displacement.
        x0: "x0", "m", Range::FINITE, "initial displacement";
        /// Initial velocity.
        v0: "v0", "m/s", Range::FINITE, "initial velocity";
        /// Rate of a rising force.
        rate: "rate", "N/s", Range::POSITIVE, "rate of the rising applied force";
        /// Amplitude of a prescribed oscillation.
        amplitude: "amplitude", "m", Range::POSITIVE, "amplitude of the prescribed oscillation";
        /// Angular frequency of a prescribed oscillation.
        omega: "omega", "rad/s", Range::POSITIVE, "angular frequency of the prescribed oscillation (of x, or of v)";
        /// Mean velocity of a prescribed velocity oscillation.
        v_mean: "v_mean", "m/s", Range::FINITE, "mean velocity of the prescribed velocity oscillation";
        /// Velocity amplitude of a prescribed velocity oscillation.
        v_amplitude: "v_amplitude", "m/s", Range::NON_NEGATIVE, "velocity amplitude of the prescribed velocity oscillation";
        /// Load of the pre-sliding test as a fraction of F_s.
        fraction: "fraction", "1", FRACTION, "applied load of the presliding test as a fraction of F_s";
        /// Largest velocity of a velocity sweep.
        v_max: "v_max", "m/s", Range::POSITIVE, "largest |v| of the velocity sweep";
        /// Proportional gain of the servo's PID.
        kp: "kp", "N/m", Range::NON_NEGATIVE, "proportional gain of the servo's PID";
        /// Integral gain of the servo's PID.
        ki: "ki", "N/(m*s)", Range::NON_NEGATIVE, "integral gain of the servo's PID";
        /// Derivative gain of the servo's PID.
        kd: "kd", "N*s/m", Range::NON_NEGATIVE, "derivative gain of the servo's PID";
        /// The servo's set point.
        x_ref: "x_ref", "m", Range::FINITE, "the servo's set point (its reference at t = 0)";
        /// The servo's reference velocity.
        v_ref: "v_ref", "m/s", Range::FINITE, "the servo's reference velocity: r = x_ref + v_ref*t";
    }
}

impl Default for ScenarioParams {
    /// The common defaults; scenarios override a few (see `Rig::defaults`).
    fn default() -> Self {
        ScenarioParams {
            m: 1.0,
            f_ex: 15.0,
            k: 100.0,
            c: 0.0,
            v_belt: 0.05,
            x0: 0.0,
            v0: 0.0,
            rate: 1.0,
            amplitude: 0.1,
            omega: 2.0 * std::f64::consts::PI,
            v_mean: 0.1,
            v_amplitude: 0.05,
            fraction: 0.5,
            v_max: 1.0,
            kp: 3.0,
            ki: 4.0,
            kd: 6.0,
            x_ref: 1.0,
            v_ref: 0.0,
        }
    }
}
