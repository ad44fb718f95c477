//! The periodic orbit of a rig's body or a system ([`scenarios::orbit`]): its period, its
//! segments and switches, its Floquet multipliers through the switches, and the orbit sampled
//! for its phase portrait.

use super::{Study, StudyFiles};
use crate::error::AppError;
use crate::output::{Cell, Table};
use crate::plot::{Corner, Dash, Marker, Plot, Series, PALETTE};
use friction_models::params::show;
use scenarios::orbit::{periodic_orbit, Orbit, OrbitSettings};
use scenarios::studies::StudyCase;

/// The periodic orbit of `case`.
pub struct OrbitStudy<'a> {
    /// The problem: a rig with a body, the chain or a system file.
    pub case: &'a dyn StudyCase,
    /// How the orbit is looked for.
    pub settings: OrbitSettings,
}

/// The lines a front end prints of an orbit: its period against the settled run's, Newton's
/// residual, the multipliers and the stability.
pub fn orbit_lines(o: &Orbit) -> Vec<String> {
    let multipliers: Vec<String> = (o.floquet.multipliers.iter())
        // `+ 0.0` writes −0 as 0.
        .map(|&(re, im)| match im {
            0.0 => format!("{:.6e}", re + 0.0),
            im => format!("{:.6e} ± {:.6e}i", re + 0.0, im.abs()),
        })
        .collect();
    let switches = o.segments.iter().filter(|s| s.ends_with.is_some()).count();
    vec![
        format!(
            "period {} s ({} segments, {switches} switches; the settled run's cycle {} s), \
             residual {:.1e} after {} Newton iterations",
            show(o.period),
            o.segments.len(),
            show(o.guessed_period),
            o.residual,
            o.iterations
        ),
        format!(
            "Floquet multipliers: {} (the first is the trivial one, 1 to {:.1e}): {}",
            multipliers.join(", "),
            o.floquet.trivial_error,
            format!("{:?}", o.floquet.stability).to_lowercase()
        ),
    ]
}

impl Study for OrbitStudy<'_> {
    type Result = Orbit;

    fn name(&self) -> &'static str {
        "orbit"
    }

    fn runs(&self) -> usize {
        1
    }

    fn run(&self, progress: &(dyn Fn() + Sync)) -> Result<Orbit, AppError> {
        let system = self.case.system()?.ok_or_else(|| {
            AppError::Usage(format!(
                "{} imposes a motion on its contact: it has no body whose orbit to find (choose \
                 a rig with a body, the chain or a system file)",
                self.case.describe()
            ))
        })?;
        let orbit = periodic_orbit(&system, &self.settings)?;
        progress();
        Ok(orbit)
    }

    /// `{stem}.json` (the orbit: period, residual, multipliers, segments), `{stem}.csv` (the
    /// orbit sampled: t, then each body's x and v), `{stem}-segments.csv` and the phase
    /// portrait `{stem}` (each body's v against x).
    fn write(&self, o: &Orbit, out: &mut StudyFiles) -> Result<(), AppError> {
        #[derive(serde::Serialize)]
        struct Summary<'a> {
            period: f64,
            guessed_period: f64,
            guessed_at: f64,
            residual: f64,
            iterations: usize,
            floquet: &'a periodic::Floquet,
            amplitudes: Vec<(String, f64)>,
            segments: &'a [scenarios::orbit::OrbitSegment],
        }
        let summary = Summary {
            period: o.period,
            guessed_period: o.guessed_period,
            guessed_at: o.guessed_at,
            residual: o.residual,
            iterations: o.iterations,
            floquet: &o.floquet,
            amplitudes: (0..o.bodies.len())
                .map(|i| (o.bodies[i].clone(), o.amplitude(i)))
                .collect(),
            segments: &o.segments,
        };
        out.add_json(&super::study_file(self.case, &[], &summary))?;
        let mut header = vec!["t".to_string()];
        for b in &o.bodies {
            header.push(format!("x_{b}"));
            header.push(format!("v_{b}"));
        }
        let mut samples = Table::new(&header.iter().map(String::as_str).collect::<Vec<_>>());
        for (k, &t) in o.t.iter().enumerate() {
            let mut row = vec![Cell::Num(t)];
            for i in 0..o.bodies.len() {
                row.push(Cell::Num(o.x[i][k]));
                row.push(Cell::Num(o.v[i][k]));
            }
            samples.rows.push(row);
        }
        out.files.add_table(out.path(".csv"), samples)?;
        let mut segments = Table::new(&["t0", "t1", "modes", "ends_with"]);
        for s in &o.segments {
            segments.rows.push(vec![
                Cell::Num(s.t0),
                Cell::Num(s.t1),
                Cell::Text(s.modes.join(" ")),
                Cell::Text(s.ends_with.unwrap_or_default().to_string()),
            ]);
        }
        out.files.add_table(out.path("-segments.csv"), segments)?;
        out.files
            .add_plot(&out.path(""), &phase_portrait(o, self.case))
    }
}

/// Each body's velocity against its displacement over the orbit, a body a colour and a dash.
fn phase_portrait(o: &Orbit, case: &dyn StudyCase) -> Plot {
    let series = (0..o.bodies.len())
        .map(|i| Series {
            label: (o.bodies.len() > 1).then(|| o.bodies[i].clone()),
            points: o.x[i].iter().copied().zip(o.v[i].iter().copied()).collect(),
            color: PALETTE[i % PALETTE.len()],
            width: 2,
            marker: Marker::None,
            dash: Dash::ALL[i % Dash::ALL.len()],
        })
        .collect();
    Plot {
        title: format!(
            "Periodic orbit of {}: period {} s, {}",
            case.describe(),
            show(format!("{:.6e}", o.period).parse().unwrap_or(o.period)),
            format!("{:?}", o.floquet.stability).to_lowercase()
        ),
        x_label: "displacement x (m)".into(),
        y_label: "velocity v (m/s)".into(),
        series,
        legend: Corner::UpperRight,
        log: false,
    }
}
