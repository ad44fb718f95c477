//! Figures 2–7 of the paper: which model each draws, what the paper says it shows, and the
//! paper's claims in a form that can be checked against the curve the equations give.

use crate::curves::{Curve, Sample};
use friction_models::ModelId;
use serde::Serialize;

/// A claim the paper makes about one of its figures.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub enum Claim {
    /// The force jumps at zero velocity or displacement (`true`) or is continuous there.
    JumpAtZero(bool),
    /// The force just left of zero is about this value, N.
    LeftOfZero(f64),
    /// The force just right of zero is about this value, N.
    RightOfZero(f64),
    /// The force at the end of the positive branch is about this value (and its negative at
    /// the end of the negative branch), N.
    EndLevel(f64),
    /// On the positive branch the force first falls below its value at zero (Stribeck drop).
    FallsAwayFromZero,
    /// At the end of the range the force levels off (`true`) or is still growing (`false`).
    LevelsOff(bool),
}

/// A numeric claim agrees when within this fraction of the paper's value: the paper reads
/// its values off its own plots ("about −10", "~17").
pub const NUMERIC_TOLERANCE: f64 = 0.10;

/// The curve levels off when its slope over the last 10 % of its range, times the whole
/// range, is below this fraction of its end value (see [`relative_end_slope`]).
pub const LEVEL_OFF_FRACTION: f64 = 0.05;

/// One figure of the paper.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PaperFigure {
    /// Figure number in the paper.
    pub number: u32,
    /// The model drawn.
    pub model: ModelId,
    /// The paper's caption.
    pub caption: &'static str,
    /// What the paper's text says the figure shows (paraphrased, quotes marked).
    pub paper_says: &'static str,
    /// The checkable claims of that text.
    pub claims: &'static [Claim],
    /// What the equations show that no claim captures, written by hand from the equations.
    pub remarks: &'static str,
}

/// Figures 2–7.
pub const PAPER_FIGURES: [PaperFigure; 6] = [
    PaperFigure {
        number: 2,
        model: ModelId::Av,
        caption: "Adhesion and viscous friction curve.",
        paper_says: "\"A sharp drop in friction is observed near zero velocity, representing the \
                     Stribeck effect, followed by stabilization and a linear growth at higher \
                     velocities, which reflects the combination of Coulomb friction with a \
                     viscous contribution.\"",
        claims: &[Claim::FallsAwayFromZero, Claim::LevelsOff(false)],
        remarks: "AV has no Coulomb term: the level it falls to is the static level F_s, and the \
                  Stribeck amplitude C1 comes on top of F_s, so AV starts at F_s + C1 = 9 N, above \
                  the break-away level the other models use.",
    },
    PaperFigure {
        number: 3,
        model: ModelId::Cs,
        caption: "Friction between Coulomb and static.",
        paper_says: "\"A rapid decrease of the force is observed near zero velocity, representing \
                     the Stribeck effect, followed by stabilisation toward a constant value in the \
                     dynamic regime (Coulomb friction).\"",
        claims: &[Claim::FallsAwayFromZero, Claim::LevelsOff(true)],
        remarks: "With C1 = C2 = F_s - F_c the force falls from F_s = 7.5 N to F_c = 6 N within a \
                  few Stribeck velocities (v_s = 0.1 m/s).",
    },
    PaperFigure {
        number: 4,
        model: ModelId::Cvs,
        caption: "Friction combining Coulomb, viscous, and static components.",
        paper_says: "\"A sharp discontinuity appears near zero velocity\"; \"for positive \
                     velocities, the friction force tends toward a positive increasing value\"; \
                     \"the kinks around v = 0 suggest a regularized friction model\".",
        claims: &[
            Claim::JumpAtZero(true),
            Claim::FallsAwayFromZero,
            Claim::LevelsOff(false),
        ],
        remarks: "Eq. (7) is not regularised: the force jumps by 2 F_s = 15 N at v = 0, and the \
                  kinks the paper sees are the Stribeck drop. The paper's claims that the problem \
                  is stiff because of the jump, and that the curve is smooth, contradict each \
                  other; the solver studies measure what the jump does to a solver.",
    },
    PaperFigure {
        number: 5,
        model: ModelId::Dv,
        caption: "Friction combining Dahl and viscous components.",
        paper_says: "\"At zero displacement, there's again a jump discontinuity\"; \"for positive \
                     shifts, the friction force saturates toward a finite positive value\".",
        claims: &[Claim::JumpAtZero(true), Claim::LevelsOff(true)],
        remarks: "DV has no static term, so nothing jumps at rest: the Dahl force starts at 0 and \
                  grows like sigma*|X|. Only the Dahl part saturates (at F_c = 6 N); the viscous \
                  part mu_v*v keeps growing with the prescribed velocity t(t+1).",
    },
    PaperFigure {
        number: 6,
        model: ModelId::Sd,
        caption: "Friction combining Static and Dahl components.",
        paper_says: "\"At Shift = 0, there is a sharp discontinuity, where the force jumps from \
                     about -10 to about +8\"; for positive shifts the force \"approaches a higher \
                     limiting value\".",
        claims: &[
            Claim::JumpAtZero(true),
            Claim::LeftOfZero(-10.0),
            Claim::RightOfZero(8.0),
            Claim::LevelsOff(true),
        ],
        remarks: "Eq. (10) read with sign(v) on the static term is odd: the jump is from -F_s to \
                  +F_s (-7.5 to +7.5 N) and the two limits are +-(F_s + F_c) = +-13.5 N. An \
                  asymmetric jump like the paper's needs asymmetric parameters that Table 1 does \
                  not give. As printed (static term always +F_s) there is no jump at all.",
    },
    PaperFigure {
        number: 7,
        model: ModelId::Sv,
        caption: "Friction combining Static and Viscous components.",
        paper_says: "\"A sharp discontinuity occurs at Shift = 0, where the force jumps from a \
                     large negative value to a large positive value\"; \"for positive shifts, the \
                     force gradually approaches a limiting value (~17)\", for negative ones ~-17.",
        claims: &[
            Claim::JumpAtZero(true),
            Claim::EndLevel(17.0),
            Claim::LevelsOff(true),
        ],
        remarks: "At t = 2 s the force is 16.4 N, the paper's ~17, but it does not level off: \
                  the viscous term mu_v*v grows with the prescribed velocity, so the value at the \
                  end of the plot depends on where the plot stops (19.5 N at t = 3 s).",
    },
];

/// The check of one claim against a curve.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Finding {
    /// The claim, in words.
    pub claim: String,
    /// What the equations give, in words with the numbers.
    pub computed: String,
    /// Whether the two agree.
    pub agrees: bool,
}

fn within_tolerance(computed: f64, paper: f64) -> bool {
    (computed - paper).abs() <= NUMERIC_TOLERANCE * paper.abs()
}

/// The abscissa of a sample on the curve's own axis.
fn abscissa(curve: &Curve, s: &Sample) -> f64 {
    match curve.axis {
        friction_models::CurveAxis::Velocity => s.v,
        friction_models::CurveAxis::Displacement => s.x,
    }
}

/// The unit of the curve's abscissa.
fn abscissa_unit(curve: &Curve) -> &'static str {
    match curve.axis {
        friction_models::CurveAxis::Velocity => "m/s",
        friction_models::CurveAxis::Displacement => "m",
    }
}

/// Relative slope at the end of the positive branch: the secant slope over the last 10 % of
/// the branch's abscissa range, times that range, over the end value.
pub fn relative_end_slope(curve: &Curve) -> f64 {
    let branch = &curve.positive;
    let last = branch[branch.len() - 1];
    let a_last = abscissa(curve, &last);
    let before = branch
        .iter()
        .rev()
        .find(|s| abscissa(curve, s) <= 0.9 * a_last)
        .unwrap_or(&branch[0]);
    let slope = (last.force - before.force) / (a_last - abscissa(curve, before));
    slope * a_last / last.force.abs()
}

/// Checks one claim against the curve the equations give.
pub fn assess(claim: Claim, curve: &Curve) -> Finding {
    let (left, right) = (curve.left_of_zero, curve.right_of_zero);
    let end = curve.positive[curve.positive.len() - 1].force;
    let end_negative = curve.negative[curve.negative.len() - 1].force;
    match claim {
        Claim::JumpAtZero(paper) => {
            let jump = right - left;
            let computed = jump.abs() > 1e-9 * left.abs().max(right.abs()).max(1.0);
            Finding {
                claim: format!(
                    "the force {} at zero",
                    if paper { "jumps" } else { "is continuous" }
                ),
                computed: format!("from {left:.4} N to {right:.4} N (jump {jump:.4} N)"),
                agrees: computed == paper,
            }
        }
        Claim::LeftOfZero(paper) => Finding {
            claim: format!("just left of zero the force is about {paper} N"),
            computed: format!("{left:.4} N"),
            agrees: within_tolerance(left, paper),
        },
        Claim::RightOfZero(paper) => Finding {
            claim: format!("just right of zero the force is about {paper} N"),
            computed: format!("{right:.4} N"),
            agrees: within_tolerance(right, paper),
        },
        Claim::EndLevel(paper) => Finding {
            claim: format!("the force reaches about +-{paper} N at the ends"),
            computed: format!("{end:.4} N and {end_negative:.4} N"),
            agrees: within_tolerance(end, paper) && within_tolerance(end_negative, -paper),
        },
        Claim::FallsAwayFromZero => {
            let min = curve
                .positive
                .iter()
                .min_by(|a, b| a.force.total_cmp(&b.force))
                .expect("a curve has at least two samples");
            Finding {
                claim: "the force falls as it leaves zero (Stribeck drop)".into(),
                computed: format!(
                    "from {right:.4} N at 0+ to a minimum of {:.4} N at {:.4} {}",
                    min.force,
                    abscissa(curve, min),
                    abscissa_unit(curve)
                ),
                agrees: min.force < right - 1e-9 * right.abs(),
            }
        }
        Claim::LevelsOff(paper) => {
            let slope = relative_end_slope(curve);
            let computed = slope.abs() < LEVEL_OFF_FRACTION;
            Finding {
                claim: format!(
                    "at the end of the range the force {}",
                    if paper { "levels off" } else { "keeps growing" }
                ),
                computed: format!(
                    "end slope x range / end value = {:.1} % ({} {} %)",
                    100.0 * slope,
                    if computed { "below" } else { "above" },
                    100.0 * LEVEL_OFF_FRACTION
                ),
                agrees: computed == paper,
            }
        }
    }
}
