//! The axes of a plot: the ranges of the data, padded, the ticks and labels of a log axis,
//! and the one number of decimals of a linear axis's labels.

use super::{drawable, Marker, Plot};

/// The ranges of the x and y axes.
pub(super) type Bounds = ((f64, f64), (f64, f64));

/// The plot range of the data, padded by 5 % on each side (of the decades on log axes);
/// [0, 1] (or [1, 10]) on an axis with no drawable data (an empty plot must still draw, and
/// plotters cannot draw an infinite range).
pub(super) fn bounds(plot: &Plot) -> Bounds {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in drawable(plot) {
        let (x, y) = (to_axis(plot, x), to_axis(plot, y));
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let pad = |a: f64, b: f64| {
        if a > b {
            return (0.0, 1.0);
        }
        let d = if b > a { 0.05 * (b - a) } else { 0.5 };
        (a - d, b + d)
    };
    (from_axis(plot, pad(x0, x1)), from_axis(plot, pad(y0, y1)))
}

/// A value in the space an axis is drawn in: its decade on a log axis.
fn to_axis(plot: &Plot, v: f64) -> f64 {
    if plot.log {
        v.log10()
    } else {
        v
    }
}

/// The range (a, b) of the drawing space ([`to_axis`]) in the data's units, kept within the
/// doubles' normal range (1e±307: a padded log range from data at 1e-300 would reach 0) and
/// of positive width.
fn from_axis(plot: &Plot, (a, b): (f64, f64)) -> (f64, f64) {
    const LIMIT: f64 = 307.0;
    let (a, b) = if plot.log {
        (a.clamp(-LIMIT, LIMIT), b.clamp(-LIMIT, LIMIT))
    } else {
        let limit = 10f64.powf(LIMIT);
        (a.clamp(-limit, limit), b.clamp(-limit, limit))
    };
    let (a, b) = if a < b {
        (a, b)
    } else {
        (b - (b.abs() + 1.0), b)
    };
    if plot.log {
        (10f64.powf(a), 10f64.powf(b))
    } else {
        (a, b)
    }
}

/// The ticks of a log axis over [a, b]: the powers of ten in it (every second, third… when
/// there are more than [`MAX_TICKS`]), or, when fewer than three, the 1-2-5 multiples of the
/// powers of ten, or all nine, whichever first gives three; the two ends of a range narrower
/// than that. (plotters' own ticks start at the first power of ten, and left a range from
/// 2e3 to 4e4 labelled only at 1e4, 2e4 and 3e4.)
pub(super) fn log_ticks(a: f64, b: f64) -> Vec<f64> {
    let (k0, k1) = (a.log10().floor() as i32, b.log10().ceil() as i32);
    let within = |mantissas: &[f64]| -> Vec<f64> {
        (k0..=k1)
            // m/10^−k below one: the nearest double to m·10^k, as the labels print it.
            .flat_map(|k| {
                mantissas.iter().map(move |m| match k {
                    0.. => m * 10f64.powi(k),
                    _ => m / 10f64.powi(-k),
                })
            })
            .filter(|v| (a..=b).contains(v))
            .collect()
    };
    let decades = within(&[1.0]);
    if decades.len() >= 3 {
        let every = decades.len().div_ceil(MAX_TICKS) as i32;
        return decades
            .into_iter()
            .filter(|v| (v.log10().round() as i32).rem_euclid(every) == 0)
            .collect();
    }
    for mantissas in [
        &[1.0, 2.0, 5.0][..],
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0],
    ] {
        let ticks = within(mantissas);
        if ticks.len() >= 3 {
            return ticks;
        }
    }
    vec![a, b]
}

/// The most ticks a log axis labels with powers of ten.
const MAX_TICKS: usize = 10;

/// The most sampled values a log x axis labels one by one ([`sample_ticks`]).
const MAX_SAMPLE_TICKS: usize = 8;

/// The least distance between two labelled samples, as a fraction of the axis's length.
const MIN_SAMPLE_GAP: f64 = 0.08;

/// The ticks of a log x axis over [a, b] at the values the runs were made at, when the plot
/// samples a few of them (the step sizes of a convergence study, the widths of a stiffness
/// sweep, the block counts of a cost study): the distinct x of the marked points, if there
/// are two to [`MAX_SAMPLE_TICKS`] of them, each at least [`MIN_SAMPLE_GAP`] of the axis
/// from the next. (The powers of ten and their 1-2-5 multiples left the finest step of a
/// convergence study, h = 0.0025, without a label.)
pub(super) fn sample_ticks(plot: &Plot, a: f64, b: f64) -> Option<Vec<f64>> {
    let mut xs: Vec<f64> = plot
        .series
        .iter()
        .filter(|s| s.marker != Marker::None)
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .filter(|x| (a..=b).contains(x))
        .collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let span = (b / a).log10();
    let apart = xs
        .windows(2)
        .all(|w| (w[1] / w[0]).log10() >= MIN_SAMPLE_GAP * span);
    ((2..=MAX_SAMPLE_TICKS).contains(&xs.len()) && apart).then_some(xs)
}

/// How a log axis writes its tick labels, one form for the whole axis: decimals where every
/// tick lies in [1e-3, 1e4) (or is 0), else exponent form (so that "0.001" and "1e-4", or
/// "1000" and "1e4", never share an axis).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum TickForm {
    /// 0.02, 1000.
    Decimal,
    /// 1e-4, 2.5e7.
    Exponent,
}

impl TickForm {
    /// The form of an axis with `ticks`.
    pub(super) fn of(ticks: &[f64]) -> TickForm {
        match ticks
            .iter()
            .all(|&v| v == 0.0 || (1e-3..1e4).contains(&v.abs()))
        {
            true => TickForm::Decimal,
            false => TickForm::Exponent,
        }
    }
}

/// A tick label of a log axis in `form`: three significant digits, trailing zeros left out.
pub(super) fn tick_label(v: f64, form: TickForm) -> String {
    let trim = |m: String| {
        if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            m
        }
    };
    if v == 0.0 || form == TickForm::Decimal {
        trim(format!("{v:.4}"))
    } else {
        let text = format!("{v:.2e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        format!("{}e{exponent}", trim(mantissa.to_string()))
    }
}

/// The most decimals a linear axis's labels take; an axis whose ticks need more keeps
/// plotters' own labels.
const MAX_DECIMALS: usize = 6;

/// The number of decimals with which every labelled tick `keys` of a linear axis is written,
/// the same for all ("0.00, 0.05, 0.10", where plotters wrote "0.0, 0.05, 0.1"; "8", not
/// "8.0"): the fewest, up to [`MAX_DECIMALS`], at which each key written and read back is
/// itself to a millionth of the ticks' spacing. `None` for ticks that need more, or that are
/// too large for decimals (1e7 and over).
pub(super) fn common_decimals(keys: &[f64]) -> Option<usize> {
    let mut sorted: Vec<f64> = keys.iter().copied().filter(|k| k.is_finite()).collect();
    sorted.sort_by(f64::total_cmp);
    let largest = sorted.iter().fold(0.0f64, |m, k| m.max(k.abs()));
    if sorted.is_empty() || largest >= 1e7 {
        return None;
    }
    let spacing = (sorted.windows(2))
        .map(|w| w[1] - w[0])
        .filter(|d| *d > 0.0)
        .fold(f64::INFINITY, f64::min);
    let scale = if spacing.is_finite() {
        spacing
    } else {
        largest.max(1.0)
    };
    (0..=MAX_DECIMALS).find(|&d| {
        (sorted.iter()).all(|k| {
            let written: f64 = format!("{k:.d$}").parse().unwrap_or(f64::NAN);
            (written - k).abs() <= 1e-6 * scale
        })
    })
}

/// `v` written with `decimals` decimals, a rounding of zero written without its sign.
pub(super) fn fixed(v: f64, decimals: usize) -> String {
    let text = format!("{v:.decimals$}");
    match text.parse::<f64>() {
        Ok(0.0) => format!("{:.decimals$}", 0.0),
        _ => text,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_linear_axis_writes_all_its_labels_with_one_number_of_decimals() {
        assert_eq!(common_decimals(&[-0.15, -0.1, -0.05, 0.0, 0.05]), Some(2));
        assert_eq!(common_decimals(&[0.0, 2.0, 4.0, 8.0]), Some(0));
        assert_eq!(common_decimals(&[0.0, 0.25, 0.5, 0.75]), Some(2));
        assert_eq!(common_decimals(&[1.5, 2.0, 2.5]), Some(1));
        // A sum of steps off by a rounding still reads as its decimal.
        assert_eq!(common_decimals(&[0.1, 0.2, 0.30000000000000004]), Some(1));
        assert_eq!(common_decimals(&[1e-8, 2e-8]), None);
        assert_eq!(common_decimals(&[1e7, 2e7]), None);
        assert_eq!(common_decimals(&[3.0]), Some(0));
        assert_eq!(fixed(-0.0000001, 2), "0.00");
        assert_eq!(fixed(-0.1, 2), "-0.10");
    }
    use crate::plot::{Corner, Marker, Series, RED};

    /// A plot of dotted runs at `xs` (y = x) on log axes.
    fn runs_at(xs: &[f64]) -> Plot {
        Plot {
            title: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            series: vec![Series {
                label: None,
                points: xs.iter().map(|&x| (x, x)).collect(),
                color: RED,
                width: 2,
                marker: Marker::Dot,
                dash: crate::plot::Dash::Solid,
            }],
            legend: Corner::default(),
            log: true,
        }
    }

    #[test]
    fn a_log_x_axis_is_labelled_at_a_few_sampled_values() {
        // A convergence study's steps: every one labelled, the finest included.
        let steps = [0.02, 0.01, 0.005, 0.0025];
        assert_eq!(
            sample_ticks(&runs_at(&steps), 0.0022, 0.023),
            Some(vec![0.0025, 0.005, 0.01, 0.02])
        );
        // Too many values (a work–precision plot's errors), or two too close to label apart:
        // the powers of ten and their multiples instead.
        let many: Vec<f64> = (1..=9).map(|k| 10f64.powi(-k)).collect();
        assert_eq!(sample_ticks(&runs_at(&many), 1e-10, 1.0), None);
        assert_eq!(
            sample_ticks(&runs_at(&[1e-3, 1.1e-3, 1e-1]), 1e-4, 1.0),
            None
        );
        // A curve without markers (a reference slope) is not a sample.
        let mut slope = runs_at(&[0.01, 0.1]);
        slope.series[0].marker = Marker::None;
        assert_eq!(sample_ticks(&slope, 1e-3, 1.0), None);
    }

    #[test]
    fn a_log_axis_has_at_least_three_ticks_and_at_most_ten_powers_of_ten() {
        // The work axis of the 100-block chain's work–precision plot.
        assert_eq!(log_ticks(1.8e3, 3.8e4), [2e3, 5e3, 1e4, 2e4]);
        assert_eq!(log_ticks(0.5, 50.0), [0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0]);
        assert_eq!(log_ticks(0.15, 0.6), [0.2, 0.3, 0.4, 0.5, 0.6]);
        assert_eq!(log_ticks(0.9, 20.0), [1.0, 2.0, 5.0, 10.0, 20.0]);
        assert_eq!(log_ticks(3.1e4, 3.2e4), [3.1e4, 3.2e4]);
        let many = log_ticks(1e-12, 1e12);
        assert_eq!(many.len(), 9, "{many:?}");
        assert!(many.iter().all(|v| (v.log10().round() as i32) % 3 == 0));
        assert_eq!(log_ticks(2e-11, 0.5).len(), 10);
    }

    #[test]
    fn log_tick_labels_are_short_and_of_one_form_per_axis() {
        let labels = |ticks: &[f64]| {
            let form = TickForm::of(ticks);
            ticks
                .iter()
                .map(|&v| tick_label(v, form))
                .collect::<Vec<_>>()
        };
        assert_eq!(labels(&[0.02, 1000.0]), ["0.02", "1000"]);
        assert_eq!(labels(&[9.999999999999999e-6, 2.5e7]), ["1e-5", "2.5e7"]);
        // An axis reaching past [1e-3, 1e4) writes all its ticks in exponent form: it
        // mixed "0.001" with "1e-4", and "1000" with "1e4".
        assert_eq!(labels(&[1e-4, 1e-3, 1e-2]), ["1e-4", "1e-3", "1e-2"]);
        assert_eq!(labels(&[100.0, 1000.0, 1e4]), ["1e2", "1e3", "1e4"]);
    }
}
