//! The spectra of a system's motion: the amplitude spectrum of the velocity of each drawn body
//! (the bodies of the line figures, `motion::spread`)
//! over the last half of the run (the first half left to the transient, as a sweep's
//! settled part; at most its last [`crate::spectrum::MAX_SAMPLES`] points), with its dominant
//! frequency: `spectrum.csv`, `spectrum.json` and a figure.

use crate::artifacts::Artifacts;
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Marker, Plot, Series, PALETTE};
use crate::spectrum::Spectrum;
use friction_systems::{Run, System};
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

/// Adds the spectra of the velocities of `bodies` (indices into `system`) of `run` over the
/// last half of its recorded span to `files`, in `out`; returns a line per body with its
/// dominant frequency. A run of fewer than eight recorded points has none.
pub fn add_spectra(
    files: &mut Artifacts,
    out: &Path,
    run: &Run,
    system: &System,
    bodies: &[usize],
    title: &str,
) -> Result<Vec<String>, AppError> {
    let t = &run.solution.t;
    let (Some(&t0), Some(&t1)) = (t.first(), t.last()) else {
        return Ok(Vec::new());
    };
    let start = t.partition_point(|&s| s < t1 - MEASURED * (t1 - t0));
    // A longer span is measured over its last samples (`Spectrum::of`).
    let start = start.max(t.len().saturating_sub(crate::spectrum::MAX_SAMPLES));
    if t.len() - start < 8 {
        return Ok(Vec::new());
    }
    // The system records its evenly spaced output grid only.
    let dt = (t1 - t[start]) / (t.len() - start - 1) as f64;
    let spectra: Vec<(usize, Spectrum)> = (bodies.iter())
        .map(|&i| {
            let v: Vec<f64> = (start..t.len()).map(|k| run.body_at(i, k).v).collect();
            (i, Spectrum::of(&v, dt))
        })
        .collect();
    let name = |i: usize| system.bodies[i].name.as_str();
    let mut header = vec!["frequency"];
    header.extend(spectra.iter().map(|(i, _)| name(*i)));
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
            from: t[start],
            to: t1,
            resolution,
            bodies: (spectra.iter())
                .map(|(i, s)| Dominant {
                    body: name(*i),
                    dominant_frequency: s.dominant,
                    amplitude: s.dominant_amplitude,
                })
                .collect(),
        },
    )?;
    let plot = Plot {
        title: format!(
            "{title}: spectrum of v over t = {:.3}…{:.3} s",
            t[start], t1
        ),
        x_label: "frequency f (Hz)".into(),
        y_label: "amplitude of v (m/s)".into(),
        series: (spectra.iter().enumerate())
            .map(|(c, (i, s))| Series {
                label: Some(name(*i).to_string()),
                points: (s.frequency.iter().copied())
                    .zip(s.amplitude.iter().copied())
                    .collect(),
                color: PALETTE[c % PALETTE.len()],
                width: 2,
                marker: Marker::None,
            })
            .collect(),
        legend: Corner::UpperRight,
        log: false,
    };
    files.add_plot(&out.join("spectrum"), &plot)?;
    Ok((spectra.iter())
        .map(|(i, s)| match (s.dominant, s.dominant_amplitude) {
            (Some(f), Some(a)) => format!(
                "{}: dominant frequency {f:.4} Hz (amplitude {a:.3e} m/s, resolution {resolution:.3e} Hz)",
                name(*i)
            ),
            _ => format!("{}: no oscillation in the last half of the run", name(*i)),
        })
        .collect())
}
