//! The thresholds of the protocols (documented in `docs/phenomena.md`).

/// Stiction: the force ramp's rate, per second, as a fraction of max(F_s, F_c): the load
/// reaches the static level in ten seconds, slow beside every model's own time scale.
pub const STICTION_RATE: f64 = 0.1;
/// Stiction: the least relative excess of the break-away force over the kinetic level
/// after it (Coulomb friction has none; the paper's F_s = 7.5 N over F_c = 6 N is 25 %).
pub const STATIC_EXCESS: f64 = 0.01;
/// Pre-sliding: smallest displacement under load that counts, m.
pub const PRESLIDING_MIN: f64 = 1e-9;
/// Pre-sliding: smallest fraction of the displacement recovered after release ("mostly
/// recovered": more than half).
pub const PRESLIDING_RECOVERY: f64 = 0.5;
/// Stribeck and viscous: smallest relative change of steady friction.
pub const STEADY_CHANGE: f64 = 0.01;
/// Stribeck: velocities at which steady friction is sampled, 0.01·v_s to 5·v_s.
pub const STRIBECK_POINTS: usize = 25;
/// Hysteresis: smallest width of the friction–velocity loop under a velocity that
/// oscillates without reversing, |∮F dv| over F_max·2a.
pub const LAG_WIDTH: f64 = 1e-3;
/// Hysteresis: smallest energy lost per pre-sliding cycle, ∮F dx over F_max·4A.
pub const PRESLIDING_DISSIPATION: f64 = 1e-3;
/// Stick–slip: length of the belt run, s (the second half is the settled part).
pub const STICK_SLIP_T_END: f64 = 40.0;
/// Stick–slip: stick phases (entries into stick in the switching log) needed in the
/// settled part.
pub const STICK_PHASES: usize = 2;
/// Stick–slip: least number of stick phases per cycle of the settled oscillation
/// (sustained stick–slip sticks once per cycle; a transient that dies out does not).
pub const STICK_PER_CYCLE: f64 = 0.5;
/// Rising static friction: smallest relative fall of the break-away force from the
/// slowest force rate to the fastest.
pub const BREAKAWAY_CHANGE: f64 = 0.1;
/// Rising static friction: the longest time for the load to reach F_s, s (a Dahl contact's
/// τ is 12 s at v_s: a ramp of 1000 τ would slide for hours at speeds where its state
/// equation is stiff).
pub const LONGEST_RAMP: f64 = 100.0;
/// Rising static friction: a break-away exists only if the peak friction before gross
/// sliding reaches this fraction of F_s.
pub const BREAKAWAY_MIN: f64 = 0.01;
/// Hunting: length of the servo run, s (the second half is the settled part): at least
/// seven cycles of every hunting model of the catalog (their periods are 24–52 s).
pub const HUNTING_T_END: f64 = 800.0;
/// Hunting: output points of the servo run (0.1 s apart).
pub const HUNTING_POINTS: usize = 8001;
/// Hunting: how many successive stops must close in on the set point for an unsettled loop
/// to count as dying out.
pub const DYING_STOPS: usize = 3;
/// Hunting: the least relative fall of the error from one stop to the next that counts as
/// closing in (Coulomb friction under the 1995 PID: about 55 %).
pub const DYING_RATIO: f64 = 0.1;
