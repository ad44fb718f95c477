//! The span of time a run's figures draw (`--window T0:T1`): its time histories, phase
//! portraits, friction plots, space–time pictures and stiffness, and the span its spectrum is
//! taken over. The data files keep every point.

use crate::error::AppError;

/// A span of time [from, to], s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Window {
    /// Its start, s.
    pub from: f64,
    /// Its end, s.
    pub to: f64,
}

impl Window {
    /// `T0:T1`, checked against the run's span [0, `t_end`]: 0 ≤ T0 < T1 ≤ t_end; an error
    /// names the option, the value and the allowed range.
    pub fn parse(text: &str, t_end: f64) -> Result<Window, AppError> {
        let bad = |why: String| {
            AppError::Usage(format!("{} {text}: {why}", crate::error::field("window")))
        };
        let (a, b) = text
            .split_once(':')
            .ok_or_else(|| bad("expected T0:T1 in seconds, such as 10:20".into()))?;
        let number = |s: &str| {
            s.trim()
                .parse::<f64>()
                .map_err(|_| bad(format!("`{s}` is not a number of seconds")))
        };
        let (from, to) = (number(a)?, number(b)?);
        if !(0.0 <= from && from < to && to <= t_end) {
            return Err(bad(format!(
                "allowed 0 <= T0 < T1 <= {t_end} s, the run's end time"
            )));
        }
        Ok(Window { from, to })
    }

    /// Whether `window` draws time `t`: every time without one.
    pub fn draws(window: Option<Window>, t: f64) -> bool {
        window.is_none_or(|w| (w.from..=w.to).contains(&t))
    }

    /// What a figure's title adds for `window`: nothing without one.
    pub fn note(window: Option<Window>) -> String {
        window.map_or_else(String::new, |w| format!(", t = {}…{} s", w.from, w.to))
    }
}

#[cfg(test)]
mod tests {
    use super::Window;

    #[test]
    fn a_window_is_read_and_checked_against_the_run() {
        assert_eq!(
            Window::parse("10:20.5", 50.0).unwrap(),
            Window {
                from: 10.0,
                to: 20.5
            }
        );
        let message = |text: &str| Window::parse(text, 50.0).unwrap_err().to_string();
        assert!(message("10").contains("window 10: expected T0:T1"));
        assert!(message("a:3").contains("`a` is not a number"));
        assert!(message("20:10").contains("allowed 0 <= T0 < T1 <= 50 s"));
        assert!(message("10:60").contains("allowed 0 <= T0 < T1 <= 50 s"));
        assert!(message("-1:10").contains("allowed"));
        assert!(message("NaN:10").contains("allowed"));
        let w = Some(Window { from: 1.0, to: 2.0 });
        assert!(Window::draws(w, 1.5) && !Window::draws(w, 2.5) && Window::draws(None, 9.0));
        assert_eq!(Window::note(w), ", t = 1…2 s");
    }
}
