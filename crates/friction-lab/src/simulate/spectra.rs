//! The spectra of a system's motion: the amplitude spectrum of the velocity of each drawn body
//! (the bodies of the line figures, `motion::spread`)
//! over the last half of the run (the first half left to the transient, as a sweep's
//! settled part; at most its last [`scenarios::analysis::spectrum::MAX_SAMPLES`] points), with its dominant
//! frequency: `spectrum.csv`, `spectrum.json` and a figure.

use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use crate::window::Window;
use friction_systems::{Run, System};
use scenarios::analysis::spectrum::Spectrum;
use serde::Serialize;
use std::path::Path;

/// The part of the run whose spectrum is taken: its last half.
const MEASURED: f64 = 0.5;

/// One body's dominant component, as `spectrum.json` lists it.
#[derive(Serialize)]
struct Dominant<'a> {
    body: &'a str,
    /// Hz; `null` for a body at rest or moving steadily.
    dominant_frequency: Option<f64>,
    /// m/s.
    amplitude: Option<f64>,
}

/// What `spectrum.json` holds.
#[derive(Serialize)]
struct SpectrumFile<'a> {
    /// The span measured, s.
    from: f64,
    to: f64,
    /// The frequency resolution, Hz.
    resolution: f64,
    bodies: Vec<Dominant<'a>>,
}

/// The velocities whose spectra are taken: each body's name and its samples, evenly spaced
/// `dt` apart from `from` to `to`.
pub struct Measured {
    /// The first sample's time, s.
    pub from: f64,
    /// The last sample's time, s.
    pub to: f64,
    /// The spacing of the samples, s.
    pub dt: f64,
    /// Each body's name and velocity samples, m/s.
    pub bodies: Vec<(String, Vec<f64>)>,
}

/// The span a spectrum is measured over: `window` where one is given, else the last half of
/// `[t0, t1]`.
pub fn measured_span(window: Option<Window>, (t0, t1): (f64, f64)) -> (f64, f64) {
    window.map_or((t1 - MEASURED * (t1 - t0), t1), |w| (w.from, w.to))
}

/// The fewest evenly spaced points a spectrum is measured from.
pub const MIN_SPECTRUM_POINTS: usize = 8;

/// The note of a run whose spectrum is not measured: fewer than [`MIN_SPECTRUM_POINTS`]
/// recorded points in `window` (or in the last half of the run), and what gives more.
pub fn no_spectrum_note(window: Option<Window>) -> String {
    let span = match window {
        Some(w) => format!("the window {}:{} s", w.from, w.to),
        None => "the last half of the run".into(),
    };
    format!(
        "no spectrum: {span} holds fewer than {MIN_SPECTRUM_POINTS} output points; widen {} or \
         record more points ({})",
        crate::error::field("window"),
        crate::error::field("points")
    )
}

/// The velocities of `bodies` of a system's `run` at its recorded points within `window`,
/// else over the last half of the run (at most its last [`scenarios::analysis::spectrum::MAX_SAMPLES`]
/// points; the system records its evenly spaced output grid only); `None` for fewer than
/// eight points.
pub fn system_velocities(
    run: &Run,
    system: &System,
    bodies: &[usize],
    window: Option<Window>,
) -> Option<Measured> {
    let t = &run.solution.t;
    let (&t0, &t1) = (t.first()?, t.last()?);
    let (from, to) = measured_span(window, (t0, t1));
    let start = t.partition_point(|&s| s < from);
    let end = t.partition_point(|&s| s <= to);
    // A longer span is measured over its last samples (`Spectrum::of`).
    let start = start.max(end.saturating_sub(scenarios::analysis::spectrum::MAX_SAMPLES));
    if end < start + MIN_SPECTRUM_POINTS {
        return None;
    }
    Some(Measured {
        from: t[start],
        to: t[end - 1],
        dt: (t[end - 1] - t[start]) / (end - start - 1) as f64,
        bodies: (bodies.iter())
            .map(|&i| {
                let v = (start..end).map(|k| run.body_at(i, k).v).collect();
                (system.bodies[i].name.clone(), v)
            })
            .collect(),
    })
}

/// Adds the spectra of `measured` to `files`, in `out`: `spectrum.csv`, `spectrum.json` and
/// its figure; returns a line per body with its dominant frequency.
pub fn add_spectra(
    files: &mut Artifacts,
    out: &Path,
    measured: &Measured,
    title: &str,
) -> Result<Vec<String>, AppError> {
    let (from, to) = (measured.from, measured.to);
    let spectra: Vec<(&str, Spectrum)> = (measured.bodies.iter())
        .map(|(name, v)| (name.as_str(), Spectrum::of(v, measured.dt)))
        .collect();
    let mut header = vec!["frequency"];
    header.extend(spectra.iter().map(|(i, _)| *i));
    let mut table = Table::new(&header);
    let bins = spectra.first().map_or(0, |(_, s)| s.frequency.len());
    for k in 0..bins {
        let mut row = vec![Cell::Num(spectra[0].1.frequency[k])];
        row.extend(spectra.iter().map(|(_, s)| Cell::Num(s.amplitude[k])));
        table.rows.push(row);
    }
    files.add_table(out.join("spectrum.csv"), table)?;
    let resolution = spectra
        .first()
        .and_then(|(_, s)| s.frequency.get(1).copied())
        .unwrap_or(0.0);
    files.add_json(
        out.join("spectrum.json"),
        &SpectrumFile {
            from,
            to,
            resolution,
            bodies: (spectra.iter())
                .map(|(i, s)| Dominant {
                    body: i,
                    dominant_frequency: s.dominant,
                    amplitude: s.dominant_amplitude,
                })
                .collect(),
        },
    )?;
    let plot = Plot {
        title: format!("{title}: spectrum of v over t = {from:.3}…{to:.3} s"),
        x_label: "frequency f (Hz)".into(),
        y_label: "amplitude of v (m/s)".into(),
        series: (spectra.iter().enumerate())
            .map(|(c, (i, s))| Series {
                label: Some(i.to_string()),
                points: (s.frequency.iter().copied())
                    .zip(s.amplitude.iter().copied())
                    .collect(),
                color: PALETTE[c % PALETTE.len()],
                width: 2,
                marker: Marker::None,
                dash: crate::plot::Dash::Solid,
            })
            .collect(),
        legend: Corner::UpperRight,
        log: false,
    };
    files.add_plot(&out.join("spectrum"), &plot)?;
    Ok((spectra.iter())
        .map(|(i, s)| match (s.dominant, s.dominant_amplitude) {
            (Some(f), Some(a)) => format!(
                "{i}: dominant frequency {f:.4} Hz (amplitude {a:.3e} m/s, resolution {resolution:.3e} Hz)"
            ),
            _ => format!("{i}: no oscillation in the span measured"),
        })
        .collect())
}
