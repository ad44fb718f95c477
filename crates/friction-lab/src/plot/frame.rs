//! A panel's frame: its title and axis names set in type ([`Lines`]), and the room they leave
//! the plotting area ([`Frame`]). Each text is set at the largest of its sizes at which it
//! fits its length on one line, else on two lines at its smallest size, broken at the space
//! that leaves the longer line shortest. No name is set smaller than the tick labels
//! ([`TICK_SIZE`]); a text that fits no two lines keeps what fits and ends in an ellipsis.

use super::{register_font, Plot, FAMILY};
use plotters::prelude::*;

/// The margin around a panel's title, axes and labels, design pixels.
pub(super) const MARGIN: u32 = 15;

/// The height of the x axis's tick marks and labels below the plotting area, without the
/// axis name, design pixels.
const X_TICKS: u32 = 30;

/// The width of the y axis's tick marks and labels left of the plotting area, without the axis
/// name, design pixels (a label of six characters, "0.0025", at [`TICK_SIZE`]).
const Y_TICKS: u32 = 52;

/// A panel's title and axis names set for its size, and the label areas they take.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Frame {
    /// The title, above the plotting area.
    pub title: Lines,
    /// The x axis's name, below its tick labels.
    pub x_name: Lines,
    /// The y axis's name, left of its tick labels, turned a quarter left.
    pub y_name: Lines,
    /// The height of the x label area (ticks and name), design pixels.
    pub x_area: u32,
    /// The width of the y label area (ticks and name), design pixels.
    pub y_area: u32,
}

impl Frame {
    /// The frame of `plot` on a panel of `panel` design pixels (its legend strip aside): the
    /// title set to the panel's width within its margins, the x name to the plotting area's
    /// width as a one-line y name leaves it, the y name to its height.
    pub fn of(plot: &Plot, (w, h): (u32, u32)) -> Frame {
        let title = Lines::set(&plot.title, w.saturating_sub(2 * MARGIN + 20), TITLE_SIZES);
        let one_line = Y_TICKS + text_height(AXIS_NAME_SIZES.0) + 4;
        let x_name = Lines::set(
            &plot.x_label,
            w.saturating_sub(2 * MARGIN + one_line),
            AXIS_NAME_SIZES,
        );
        let x_area = X_TICKS + x_name.height() + 2;
        let y_length = h.saturating_sub(2 * MARGIN + title.title_height() + x_area);
        let y_name = Lines::set(&plot.y_label, y_length, AXIS_NAME_SIZES);
        let y_area = Y_TICKS + y_name.height() + 4;
        Frame {
            title,
            x_name,
            y_name,
            x_area,
            y_area,
        }
    }

    /// The plotting area inside the frame, design pixels.
    pub fn plot_area(&self, (w, h): (u32, u32)) -> (f64, f64) {
        (
            f64::from(w.saturating_sub(2 * MARGIN + self.y_area)),
            f64::from(h.saturating_sub(2 * MARGIN + self.title.title_height() + self.x_area)),
        )
    }

    /// The plotting area's top below the panel's, design pixels.
    pub fn plot_top(&self) -> f64 {
        f64::from(MARGIN + self.title.title_height())
    }
}

/// The font size of the tick labels, design pixels (7.2 pt): the smallest text of a figure.
pub(super) const TICK_SIZE: u32 = 15;

/// The largest and smallest font sizes of a plot's title, design pixels.
pub(super) const TITLE_SIZES: (u32, u32) = (22, 16);

/// The largest and smallest font sizes of the axes' names, design pixels.
pub(super) const AXIS_NAME_SIZES: (u32, u32) = (17, TICK_SIZE);

/// The space between two lines of a name, design pixels.
pub(super) const LINE_GAP: u32 = 3;

/// The room a panel's title takes besides its margin, design pixels: 5 above and below each
/// line (plotters' `titled`, whose padding is half the text height, at most 5).
const TITLE_PADDING: u32 = 10;

/// A text set in lines at one font size.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Lines {
    /// The lines, one or two.
    pub lines: Vec<String>,
    /// The font size, design pixels.
    pub size: u32,
}

/// The width of `text` at font size `size`, design pixels (ten a character where the font
/// cannot say).
pub(super) fn text_width(text: &str, size: u32) -> u32 {
    register_font();
    (FAMILY, size)
        .into_font()
        .box_size(text)
        .map_or(10 * text.chars().count() as u32, |(w, _)| w)
}

/// The height of a line of text at font size `size`, design pixels.
pub(super) fn text_height(size: u32) -> u32 {
    register_font();
    (FAMILY, size)
        .into_font()
        .box_size("Ag(|")
        .map_or(size, |(_, h)| h)
}

impl Lines {
    /// `text` set to a length of `length` pixels: on one line at the largest of `sizes`
    /// (largest, smallest) at which it fits; else on two lines at the smallest size, broken at
    /// the space that makes the longer line shortest; a line that still does not fit is cut to
    /// an ellipsis.
    pub fn set(text: &str, length: u32, (largest, smallest): (u32, u32)) -> Lines {
        if let Some(size) = (smallest..=largest)
            .rev()
            .find(|&size| text_width(text, size) <= length)
        {
            return Lines {
                lines: vec![text.to_string()],
                size,
            };
        }
        let size = smallest;
        let width = |s: &str| text_width(s.trim(), size);
        let split = (text.char_indices())
            .filter(|&(_, c)| c == ' ')
            .map(|(i, _)| (&text[..i], &text[i + 1..]))
            .min_by_key(|(a, b)| width(a).max(width(b)));
        let lines = match split {
            Some((a, b)) => vec![
                shortened(a.trim(), size, length),
                shortened(b.trim(), size, length),
            ],
            None => vec![shortened(text, size, length)],
        };
        Lines { lines, size }
    }

    /// Its height with the gaps between its lines, design pixels.
    pub fn height(&self) -> u32 {
        let n = self.lines.len() as u32;
        n * text_height(self.size) + n.saturating_sub(1) * LINE_GAP
    }

    /// The room it takes as a title, its padding included, design pixels.
    pub fn title_height(&self) -> u32 {
        self.lines.len() as u32 * (text_height(self.size) + TITLE_PADDING)
    }

    /// The distance from one line's top to the next one's, design pixels.
    pub fn pitch(&self) -> u32 {
        text_height(self.size) + LINE_GAP
    }
}

/// `text` as it fits `length` pixels at font size `size`: whole where it fits, else cut at its
/// end to an ellipsis.
pub(super) fn shortened(text: &str, size: u32, length: u32) -> String {
    if text_width(text, size) <= length {
        return text.to_string();
    }
    let chars: Vec<char> = text.chars().collect();
    (0..chars.len())
        .rev()
        .map(|n| format!("{}…", chars[..n].iter().collect::<String>().trim_end()))
        .find(|t| text_width(t, size) <= length)
        .unwrap_or_else(|| "…".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_name_too_long_for_one_line_takes_two_at_the_tick_size_and_is_never_smaller() {
        let long = "relative error on the time grid, max over x, v, z of |Δ|/max|reference| (1)";
        let one = text_width(long, AXIS_NAME_SIZES.1);
        let set = Lines::set(long, one * 2 / 3, AXIS_NAME_SIZES);
        assert_eq!(set.size, TICK_SIZE);
        assert_eq!(set.lines.len(), 2, "{:?}", set.lines);
        assert_eq!(set.lines.join(" "), long, "broken at a space, nothing lost");
        for line in &set.lines {
            assert!(text_width(line, set.size) <= one * 2 / 3, "{line}");
        }
        // Where it fits it keeps one line and the largest size.
        let short = Lines::set("time t (s)", 400, AXIS_NAME_SIZES);
        assert_eq!((short.lines.len(), short.size), (1, AXIS_NAME_SIZES.0));
        // What fits no two lines keeps its beginning, each line within the length.
        let cut = Lines::set(long, one / 3, AXIS_NAME_SIZES);
        assert!(
            cut.lines.iter().any(|l| l.ends_with('…')),
            "{:?}",
            cut.lines
        );
        for line in &cut.lines {
            assert!(text_width(line, cut.size) <= one / 3, "{line}");
        }
    }

    #[test]
    fn a_title_is_set_smaller_before_it_is_broken() {
        let title = "Work-precision: belt with CS";
        let at = |size| text_width(title, size);
        // Room for the title at 19 pixels but not at 20.
        let set = Lines::set(title, at(19), TITLE_SIZES);
        assert_eq!((set.lines.len(), set.size), (1, 19));
        let broken = Lines::set(title, at(16) - 1, TITLE_SIZES);
        assert_eq!((broken.lines.len(), broken.size), (2, 16));
        assert!(broken.title_height() > set.title_height());
    }
}
