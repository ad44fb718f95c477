//! The layout of a figure checked on its SVG: every text at least the tick labels' size
//! ([`TICK_SIZE`]), whole (not cut to an ellipsis), inside the canvas, and clear of every
//! other text. Each text's box is measured with the figures' font at its size, placed by its
//! anchor and turned by its rotation as the SVG states them.

use super::frame::{text_height, text_width, TICK_SIZE};

/// plotters writes an SVG font size as the size in pixels divided by this (its
/// `SVGBackend::draw_text`).
const SVG_FONT_SCALE: f64 = 1.24;

/// A text's box on the canvas, pixels: left, top, right, bottom.
type TextBox = (f64, f64, f64, f64);

/// One `<text>` element of an SVG.
struct SvgText {
    content: String,
    x: f64,
    y: f64,
    /// Its size in the figure's pixels (the SVG's font size times [`SVG_FONT_SCALE`]).
    size: f64,
    anchor: String,
    dy: String,
    rotated: bool,
}

/// The value of attribute `name` in the attributes `tag`.
fn attribute<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let start = tag.find(&format!(" {name}=\""))? + name.len() + 3;
    tag[start..].split('"').next()
}

/// The `<text>` elements of `svg`.
fn texts(svg: &str) -> Vec<SvgText> {
    (svg.split("<text").skip(1))
        .filter_map(|element| {
            let (tag, rest) = element.split_once('>')?;
            let content = rest.split("</text>").next()?.trim();
            let number = |name| attribute(tag, name)?.parse::<f64>().ok();
            Some(SvgText {
                content: (content.replace("&lt;", "<").replace("&gt;", ">"))
                    .replace("&quot;", "\"")
                    .replace("&apos;", "'")
                    .replace("&#39;", "'")
                    .replace("&amp;", "&"),
                x: number("x")?,
                y: number("y")?,
                size: number("font-size")? * SVG_FONT_SCALE,
                anchor: attribute(tag, "text-anchor").unwrap_or("start").into(),
                dy: attribute(tag, "dy").unwrap_or("").into(),
                rotated: attribute(tag, "transform").is_some_and(|t| t.starts_with("rotate(270")),
            })
        })
        .collect()
}

impl SvgText {
    /// Its box on the canvas: its width and height in the font at its size, from its anchor
    /// (start, middle or end; top at `dy` 0.76em, centre at 0.5ex, bottom at −0.5ex, as plotters
    /// writes them), turned a quarter left about (x, y) where it is rotated.
    fn bounds(&self) -> TextBox {
        let size = self.size.round() as u32;
        let (w, h) = (
            f64::from(text_width(&self.content, size)),
            f64::from(text_height(size)),
        );
        let left = match self.anchor.as_str() {
            "middle" => self.x - w / 2.0,
            "end" => self.x - w,
            _ => self.x,
        };
        let top = match self.dy.as_str() {
            "0.76em" => self.y,
            "-0.5ex" => self.y - h,
            _ => self.y - h / 2.0,
        };
        if !self.rotated {
            return (left, top, left + w, top + h);
        }
        // rotate(270, x, y): (px, py) goes to (x + (py − y), y − (px − x)).
        let turn = |px: f64, py: f64| (self.x + (py - self.y), self.y - (px - self.x));
        let (a, b) = (turn(left, top), turn(left + w, top + h));
        (a.0.min(b.0), a.1.min(b.1), a.0.max(b.0), a.1.max(b.1))
    }
}

/// The faults of the layout of the figure `svg`, each in words: a text smaller than the tick
/// labels, cut to an ellipsis, reaching out of the canvas, or overlapping another text (by
/// more than a pixel). An empty list is a clean layout.
pub fn layout_faults(svg: &str) -> Vec<String> {
    let mut faults = Vec::new();
    let canvas = (attribute(svg, "viewBox").map(|v| {
        let n: Vec<f64> = v
            .split_whitespace()
            .filter_map(|n| n.parse().ok())
            .collect();
        (
            n.get(2).copied().unwrap_or(0.0),
            n.get(3).copied().unwrap_or(0.0),
        )
    }))
    .unwrap_or((0.0, 0.0));
    let texts = texts(svg);
    let boxes: Vec<TextBox> = texts.iter().map(SvgText::bounds).collect();
    for (t, b) in texts.iter().zip(&boxes) {
        if t.size < f64::from(TICK_SIZE) - 0.01 {
            faults.push(format!(
                "\"{}\" is set at {:.1} px, below the tick labels' {TICK_SIZE}",
                t.content, t.size
            ));
        }
        if t.content.ends_with('…') {
            faults.push(format!("\"{}\" is cut short", t.content));
        }
        let slack = 0.5;
        if b.0 < -slack || b.1 < -slack || b.2 > canvas.0 + slack || b.3 > canvas.1 + slack {
            faults.push(format!(
                "\"{}\" at ({:.0}, {:.0})–({:.0}, {:.0}) reaches out of the {} × {} canvas",
                t.content, b.0, b.1, b.2, b.3, canvas.0, canvas.1
            ));
        }
    }
    for i in 0..boxes.len() {
        for j in 0..i {
            let (a, b) = (boxes[i], boxes[j]);
            let overlap = (a.2.min(b.2) - a.0.max(b.0)).min(a.3.min(b.3) - a.1.max(b.1));
            if overlap > 1.0 {
                faults.push(format!(
                    "\"{}\" overlaps \"{}\" by {overlap:.1} px",
                    texts[i].content, texts[j].content
                ));
            }
        }
    }
    faults
}
