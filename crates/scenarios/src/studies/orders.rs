//! Observed orders over the asymptotic range: the local order of each refinement pair, the
//! longest run of consecutive pairs whose orders agree, and a least-squares fit over it with a
//! 95 % interval that also covers the drift of the local orders (Roache's grid-convergence
//! practice, made strict for nonsmooth problems: a pair that is not in the asymptotic range
//! never enters the fit).

use serde::Serialize;

/// A pair whose finer error is at or below this fraction of the solution's scale is at the
/// round-off floor (the reference runs at rtol = atol = 1e-13): it says nothing of the order.
pub const ROUND_OFF: f64 = 1e-12;

/// The local orders of the pairs of an asymptotic range lie within this of each other
/// (largest minus smallest).
pub const ORDER_AGREEMENT: f64 = 0.5;

/// The fewest pairs (three resolutions) an order rests on: one pair is a local order, not an
/// observed one (two agreeing pairs are the least evidence of an asymptotic range).
pub const MIN_PAIRS: usize = 2;

/// The observed order between two refinements: log(e_i/e_(i+1)) / log(h_i/h_(i+1)), which
/// does not assume halving.
pub fn observed_order(e: (f64, f64), h: (f64, f64)) -> f64 {
    (e.0 / e.1).ln() / (h.0 / h.1).ln()
}

/// The order of one refinement pair, with what keeps it out of the asymptotic range.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PairOrder {
    /// Coarser resolution.
    pub from: f64,
    /// Finer resolution.
    pub to: f64,
    /// Local order ([`observed_order`]).
    pub order: f64,
    /// The finer error is at the round-off floor ([`ROUND_OFF`] of the solution's scale), or
    /// an error of the pair is undefined: the pair says nothing of the order.
    pub round_off: bool,
    /// Above that floor, the finer error did not decrease: the refinement has not reached the
    /// asymptotic range, or the error has saturated (a limit cycle's phase drift, for one,
    /// holds it at the cycle's amplitude).
    pub stalled: bool,
    /// The coarser error is as large as the solution's scale: the run has no correct digit (an
    /// unstable or unresolved step).
    pub no_correct_digit: bool,
    /// The pair is in the asymptotic range and enters the fit.
    pub in_range: bool,
}

impl PairOrder {
    /// Neither at round-off, stalled, nor without a correct digit: a candidate for the
    /// asymptotic range.
    pub fn usable(&self) -> bool {
        !self.round_off && !self.stalled && !self.no_correct_digit
    }
}

/// A least-squares fit of log(error) against log(resolution) over the asymptotic range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// The slope: the observed order (or, over tolerances, the exponent of tolerance
    /// proportionality).
    pub slope: f64,
    /// Its 95 % interval: slope ± the larger of t(0.975, n − 2)·(standard error) (n points)
    /// and the spread of the local orders it rests on. The regression sees scatter, not drift:
    /// local orders that still converge (as p + c·h does) lie near a line, and the
    /// regression's interval alone shrinks with the drift and can miss the order they converge
    /// to; where they converge geometrically at a ratio up to ½ (halving h, one correction
    /// term) that limit lies within their spread of the fitted slope.
    pub ci: [f64; 2],
    /// log(error) at log(resolution) = 0: the fitted line is error = e^intercept · h^slope.
    pub intercept: f64,
    /// How many pairs it rests on.
    pub pairs_used: usize,
    /// The finest and the coarsest resolution it rests on.
    pub range: [f64; 2],
}

impl Fit {
    /// The fitted error at resolution `h`.
    pub fn at(&self, h: f64) -> f64 {
        (self.intercept + self.slope * h.ln()).exp()
    }
}

/// The local orders of successive pairs of `points` (resolution, error), coarse to fine, and
/// the fit over their asymptotic range: the longest run of consecutive usable pairs
/// ([`PairOrder::usable`]) whose local orders lie within [`ORDER_AGREEMENT`] of each other (of
/// two equally long, the finer), if it has at least [`MIN_PAIRS`]; `scale` is the solution's.
pub fn orders(points: &[(f64, f64)], scale: f64) -> (Vec<PairOrder>, Option<Fit>) {
    let mut pairs: Vec<PairOrder> = points
        .windows(2)
        .map(|w| {
            let round_off =
                w[1].1 <= ROUND_OFF * scale || !(w[0].1.is_finite() && w[1].1.is_finite());
            let stalled = !round_off && w[1].1 >= w[0].1;
            PairOrder {
                from: w[0].0,
                to: w[1].0,
                order: observed_order((w[0].1, w[1].1), (w[0].0, w[1].0)),
                round_off,
                stalled,
                no_correct_digit: !round_off && !stalled && w[0].1 >= scale,
                in_range: false,
            }
        })
        .collect();
    let (start, len) = asymptotic_range(&pairs);
    if len < MIN_PAIRS {
        return (pairs, None);
    }
    for p in &mut pairs[start..start + len] {
        p.in_range = true;
    }
    let logs: Vec<(f64, f64)> = points[start..=start + len]
        .iter()
        .map(|p| (p.0.ln(), p.1.ln()))
        .collect();
    let (slope, intercept, regression) = least_squares(&logs);
    let in_range = &pairs[start..start + len];
    let spread = in_range
        .iter()
        .map(|p| p.order)
        .fold(f64::NEG_INFINITY, f64::max)
        - in_range
            .iter()
            .map(|p| p.order)
            .fold(f64::INFINITY, f64::min);
    let half_width = regression.max(spread);
    let fit = Fit {
        slope,
        ci: [slope - half_width, slope + half_width],
        intercept,
        pairs_used: len,
        range: [points[start + len].0, points[start].0],
    };
    (pairs, Some(fit))
}

/// The first index and the length of the longest run of consecutive usable pairs whose orders
/// lie within [`ORDER_AGREEMENT`] of each other; of runs equally long, the finer (later) one.
fn asymptotic_range(pairs: &[PairOrder]) -> (usize, usize) {
    let mut best = (0, 0);
    for start in 0..pairs.len() {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for (k, p) in pairs[start..].iter().enumerate() {
            (lo, hi) = (lo.min(p.order), hi.max(p.order));
            if !p.usable() || hi - lo > ORDER_AGREEMENT {
                break;
            }
            if k + 1 >= best.1 {
                best = (start, k + 1);
            }
        }
    }
    best
}

/// The least-squares line through `points` (at least three): its slope, its intercept, and
/// the half-width of the slope's 95 % confidence interval.
fn least_squares(points: &[(f64, f64)]) -> (f64, f64, f64) {
    let super::Line {
        slope,
        intercept,
        sxx,
    } = super::line(points);
    let residuals: f64 = points
        .iter()
        .map(|p| (p.1 - intercept - slope * p.0).powi(2))
        .sum();
    let dof = points.len() - 2;
    let standard_error = (residuals / dof as f64 / sxx).sqrt();
    (slope, intercept, student_t_975(dof) * standard_error)
}

/// The 0.975 quantile of Student's t distribution with `dof` degrees of freedom (the factor of
/// a two-sided 95 % interval): tabulated to 30 degrees of freedom, above that the
/// Cornish–Fisher expansion about the normal quantile 1.959964 (Abramowitz & Stegun 26.7.5,
/// within 1e-4 from 30 on).
pub fn student_t_975(dof: usize) -> f64 {
    const TABLE: [f64; 30] = [
        12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160,
        2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056,
        2.052, 2.048, 2.045, 2.042,
    ];
    if (1..=30).contains(&dof) {
        return TABLE[dof - 1];
    }
    let (z, nu) = (1.959_964_f64, dof.max(1) as f64);
    z + (z.powi(3) + z) / (4.0 * nu)
        + (5.0 * z.powi(5) + 16.0 * z.powi(3) + 3.0 * z) / (96.0 * nu * nu)
}
