//! The amplitude spectrum of a signal sampled at even times: where a system's motion puts its
//! energy (a brake's squeal is its dominant frequency).
//!
//! The samples, less their mean, are weighted by a Hann window w_n = sin²(πn/(N−1)) and
//! transformed, X_k = Σ w_n x_n e^{−2πikn/N}; the one-sided amplitude at f_k = k/(N·Δt) is
//! A_k = 2|X_k|/Σw_n, which is a sinusoid's amplitude when f_k is its frequency. The dominant
//! frequency is the largest A_k above f = 0, refined by the parabola through the peak and its
//! two neighbours (Grandke 1983): its error is a few thousandths of the resolution 1/(N·Δt)
//! for a pure tone, against half the resolution for the bin alone.

/// An amplitude spectrum: frequencies and amplitudes, and its strongest component.
#[derive(Clone, Debug, PartialEq)]
pub struct Spectrum {
    /// f_k = k/(N·Δt), Hz, k = 0 … N/2.
    pub frequency: Vec<f64>,
    /// A_k, in the signal's unit.
    pub amplitude: Vec<f64>,
    /// The dominant frequency, Hz, interpolated between bins; `None` for a signal with no
    /// component above f = 0 (constant, or fewer than four samples).
    pub dominant: Option<f64>,
    /// The amplitude at the dominant frequency (the peak's, interpolated).
    pub dominant_amplitude: Option<f64>,
}

/// The fewest samples of which a spectrum is taken.
const MIN_SAMPLES: usize = 4;

/// The most samples of which a spectrum is taken (the transform costs N²/2 products): a
/// longer signal's last [`MAX_SAMPLES`] are taken.
pub const MAX_SAMPLES: usize = 8192;

impl Spectrum {
    /// The spectrum of `x` sampled every `dt` seconds (of its last [`MAX_SAMPLES`]).
    pub fn of(x: &[f64], dt: f64) -> Spectrum {
        let x = &x[x.len().saturating_sub(MAX_SAMPLES)..];
        let n = x.len();
        if n < MIN_SAMPLES || dt.is_nan() || dt <= 0.0 {
            return Spectrum {
                frequency: Vec::new(),
                amplitude: Vec::new(),
                dominant: None,
                dominant_amplitude: None,
            };
        }
        let mean = x.iter().sum::<f64>() / n as f64;
        let weight: Vec<f64> = (0..n)
            .map(|i| {
                (std::f64::consts::PI * i as f64 / (n - 1) as f64)
                    .sin()
                    .powi(2)
            })
            .collect();
        let total: f64 = weight.iter().sum();
        let y: Vec<f64> = (x.iter().zip(&weight))
            .map(|(v, w)| (v - mean) * w)
            .collect();
        let bins = n / 2 + 1;
        // e^{−2πim/N} for m < N: the phase k·i of X_k is taken modulo N.
        let twiddle: Vec<(f64, f64)> = (0..n)
            .map(|m| (-2.0 * std::f64::consts::PI * m as f64 / n as f64).sin_cos())
            .collect();
        let amplitude: Vec<f64> = (0..bins)
            .map(|k| {
                let (re, im) = (y.iter().enumerate()).fold((0.0, 0.0), |(re, im), (i, v)| {
                    let (sin, cos) = twiddle[k * i % n];
                    (re + v * cos, im + v * sin)
                });
                let scale = if k == 0 { 1.0 } else { 2.0 };
                scale * re.hypot(im) / total
            })
            .collect();
        let resolution = 1.0 / (n as f64 * dt);
        let frequency: Vec<f64> = (0..bins).map(|k| k as f64 * resolution).collect();
        let peak = (1..bins)
            .max_by(|&a, &b| amplitude[a].total_cmp(&amplitude[b]))
            .filter(|&k| amplitude[k] > 0.0);
        let (dominant, dominant_amplitude) = match peak {
            Some(k) if k + 1 < bins => {
                let (a, b, c) = (amplitude[k - 1], amplitude[k], amplitude[k + 1]);
                let denominator = a - 2.0 * b + c;
                let p = if denominator == 0.0 {
                    0.0
                } else {
                    0.5 * (a - c) / denominator
                };
                (
                    Some((k as f64 + p) * resolution),
                    Some(b - 0.25 * (a - c) * p),
                )
            }
            Some(k) => (Some(frequency[k]), Some(amplitude[k])),
            None => (None, None),
        };
        Spectrum {
            frequency,
            amplitude,
            dominant,
            dominant_amplitude,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tone(f: f64, a: f64, offset: f64, seconds: f64, rate: f64) -> Vec<f64> {
        let n = (seconds * rate) as usize;
        (0..n)
            .map(|i| offset + a * (2.0 * std::f64::consts::PI * f * i as f64 / rate).sin())
            .collect()
    }

    #[test]
    fn a_tone_on_a_bin_is_found_with_its_amplitude() {
        // 10 s at 200 Hz: bins every 0.1 Hz, 7 Hz on one; the offset is not a component.
        let s = Spectrum::of(&tone(7.0, 0.2, 3.0, 10.0, 200.0), 1.0 / 200.0);
        assert!((s.dominant.unwrap() - 7.0).abs() < 1e-9, "{:?}", s.dominant);
        assert!(
            (s.dominant_amplitude.unwrap() - 0.2).abs() < 1e-3,
            "{:?}",
            s.dominant_amplitude
        );
        assert_eq!(s.frequency.len(), 1001);
        assert!((s.frequency[1] - 0.1).abs() < 1e-12);
    }

    #[test]
    fn a_tone_between_bins_is_placed_within_a_tenth_of_the_resolution() {
        // 7.33 Hz lies a third of the way between two bins: the bin alone is 0.03 Hz off.
        let s = Spectrum::of(&tone(7.33, 0.2, 0.0, 10.0, 200.0), 1.0 / 200.0);
        assert!(
            (s.dominant.unwrap() - 7.33).abs() < 0.01,
            "{:?}",
            s.dominant
        );
        let a = s.dominant_amplitude.unwrap();
        assert!((a - 0.2).abs() < 0.2 * 0.05, "{a}");
    }

    #[test]
    fn a_long_signal_is_measured_over_its_last_samples() {
        let long = tone(7.0, 0.2, 0.0, 100.0, 200.0);
        let s = Spectrum::of(&long, 1.0 / 200.0);
        assert_eq!(s.frequency.len(), MAX_SAMPLES / 2 + 1);
        assert!((s.dominant.unwrap() - 7.0).abs() < 0.01, "{:?}", s.dominant);
    }

    #[test]
    fn a_constant_signal_has_no_dominant_frequency() {
        let s = Spectrum::of(&[1.5; 100], 0.01);
        assert_eq!((s.dominant, s.dominant_amplitude), (None, None));
        assert!(Spectrum::of(&[1.0, 2.0], 0.01).frequency.is_empty());
    }
}
