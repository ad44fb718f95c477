//! Anti-aliased strokes and discs for the PNG figures: a pixel is inked in proportion to how
//! much of it a round pen covers, coverage = clamp(w/2 + 1/2 − d, 0, 1) with d the distance
//! from the pixel's centre to the stroke's centre line (a box filter's coverage of a pixel by
//! a straight edge, to first order), where plotters' bitmap back-end inks a pixel wholly or not
//! at all and thick lines come out stair-stepped.

/// The coverage of a pixel whose centre lies `d` pixels from the centre line of a pen
/// `width` pixels wide.
fn coverage(d: f64, width: f64) -> f32 {
    (width / 2.0 + 0.5 - d).clamp(0.0, 1.0) as f32
}

/// The distance from `p` to the segment from `a` to `b`.
fn to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let length2 = dx * dx + dy * dy;
    let t = if length2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

/// The columns of row `y` (pixel centres) within `reach` of the segment from `a` to `b`, with
/// `lo` ≤ x ≤ `hi` (the segment's box widened by `reach`): a span that holds every pixel of
/// the row whose centre lies closer than `reach` to the segment, found on the infinite band of
/// half-width `reach` about its line (the segment's capsule lies inside that band and box).
fn row_span(y: f64, a: (f64, f64), b: (f64, f64), reach: f64, lo: f64, hi: f64) -> (f64, f64) {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    if dy == 0.0 {
        return (lo, hi);
    }
    let centre = a.0 + (y - a.1) * dx / dy;
    let half = reach * dx.hypot(dy) / dy.abs();
    ((centre - half).max(lo), (centre + half).min(hi))
}

/// The pixels inside `size` (width, height) that a round pen `width` pixels wide covers along
/// the polyline `points`, each once with its largest coverage over the segments (round joins
/// and caps; a pixel shared by two segments is not inked twice), in the order the segments
/// first reach them. Each segment's pixels are searched row by row over the span its band
/// crosses ([`row_span`]), not over its whole bounding box, and kept in a buffer over the
/// polyline's box.
pub fn stroke(points: &[(f64, f64)], width: u32, size: (u32, u32)) -> Vec<((i32, i32), f32)> {
    let w = f64::from(width.max(1));
    let reach = (w / 2.0 + 1.0).ceil() as i32;
    // Coverage is positive closer than w/2 + 1/2 to the centre line.
    let inking = w / 2.0 + 0.5;
    let segments: Vec<((f64, f64), (f64, f64))> = match points {
        [only] => vec![(*only, *only)],
        _ => points.windows(2).map(|p| (p[0], p[1])).collect(),
    };
    let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let segments: Vec<_> = (segments.into_iter())
        .filter(|(a, b)| finite(a) && finite(b))
        .collect();
    let pixel = |v: f64, r: i32, n: u32| (v.floor() as i32 + r).clamp(-1, n as i32);
    let boxed = |(a, b): &((f64, f64), (f64, f64))| {
        [
            pixel(a.0.min(b.0), -reach, size.0).max(0),
            pixel(a.0.max(b.0), reach, size.0).min(size.0 as i32 - 1),
            pixel(a.1.min(b.1), -reach, size.1).max(0),
            pixel(a.1.max(b.1), reach, size.1).min(size.1 as i32 - 1),
        ]
    };
    // The buffer's box: every segment's.
    let Some([bx0, bx1, by0, by1]) = segments.iter().map(boxed).reduce(|p, q| {
        [
            p[0].min(q[0]),
            p[1].max(q[1]),
            p[2].min(q[2]),
            p[3].max(q[3]),
        ]
    }) else {
        return Vec::new();
    };
    if bx1 < bx0 || by1 < by0 {
        return Vec::new();
    }
    let columns = (bx1 - bx0 + 1) as usize;
    let mut best = vec![0f32; columns * (by1 - by0 + 1) as usize];
    let mut reached: Vec<usize> = Vec::new();
    for segment in &segments {
        let (a, b) = *segment;
        let [x0, x1, y0, y1] = boxed(segment);
        let (lo, hi) = (a.0.min(b.0) - inking, a.0.max(b.0) + inking);
        for y in y0..=y1 {
            let (from, to) = row_span(f64::from(y), a, b, inking, lo, hi);
            // One pixel more on each side than the span: it is found in floating point.
            let from = (from.floor() as i32 - 1).max(x0);
            let to = (to.ceil() as i32 + 1).min(x1);
            for x in from..=to {
                let c = coverage(to_segment((f64::from(x), f64::from(y)), a, b), w);
                if c > 0.0 {
                    let i = (y - by0) as usize * columns + (x - bx0) as usize;
                    if best[i] == 0.0 {
                        reached.push(i);
                    }
                    best[i] = best[i].max(c);
                }
            }
        }
    }
    (reached.into_iter())
        .map(|i| {
            let (x, y) = (bx0 + (i % columns) as i32, by0 + (i / columns) as i32);
            ((x, y), best[i])
        })
        .collect()
}

/// Calls `put(x, y, coverage)` for the pixels inside `size` of a circle of `radius` about
/// `centre`: the disc where `fill`, else its rim drawn by a pen `width` pixels wide.
pub fn circle(
    centre: (i32, i32),
    radius: u32,
    width: u32,
    fill: bool,
    size: (u32, u32),
    mut put: impl FnMut(i32, i32, f32),
) {
    let r = f64::from(radius);
    let w = f64::from(width.max(1));
    let reach = (r + w / 2.0 + 1.0).ceil() as i32;
    for y in (centre.1 - reach).max(0)..=(centre.1 + reach).min(size.1 as i32 - 1) {
        for x in (centre.0 - reach).max(0)..=(centre.0 + reach).min(size.0 as i32 - 1) {
            let d = f64::from(x - centre.0).hypot(f64::from(y - centre.1));
            let c = if fill {
                (r + 0.5 - d).clamp(0.0, 1.0) as f32
            } else {
                coverage((d - r).abs(), w)
            };
            if c > 0.0 {
                put(x, y, c);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    /// The pixels of `stroke`, by position.
    fn stroked(points: &[(f64, f64)], width: u32) -> HashMap<(i32, i32), f32> {
        let inked = stroke(points, width, (100, 100));
        let n = inked.len();
        let map: HashMap<(i32, i32), f32> = inked.into_iter().collect();
        assert_eq!(map.len(), n, "a pixel listed twice");
        map
    }

    #[test]
    fn a_stroke_inks_its_width_in_total_and_partly_at_its_edges() {
        // A diagonal line of width 3: across it, the coverage sums to about its width times
        // √2 per row (a row cuts the 45° band over 3·√2 pixels), with pixels partly inked.
        let inked = stroked(&[(10.0, 10.0), (60.0, 60.0)], 3);
        let row: Vec<f32> = (0..100)
            .filter_map(|x| inked.get(&(x, 35)).copied())
            .collect();
        let total: f32 = row.iter().sum();
        assert!((total - 3.0 * 2f32.sqrt()).abs() < 0.3, "{row:?}");
        assert!(row.iter().any(|&c| c > 0.05 && c < 0.95), "{row:?}");
        // A horizontal line of width 1 on a pixel row is that row, fully inked.
        let flat = stroked(&[(10.0, 5.0), (20.0, 5.0)], 1);
        assert!(
            flat.iter().all(|(&(_, y), &c)| y == 5 && c == 1.0),
            "{flat:?}"
        );
        assert_eq!(flat.len(), 11);
    }

    #[test]
    fn a_joint_of_two_segments_is_inked_once() {
        // The joint's pixels at their largest coverage, not blended twice.
        let inked = stroked(&[(10.0, 10.0), (30.0, 10.0), (30.0, 30.0)], 4);
        assert!(inked.values().all(|&c| c > 0.0 && c <= 1.0));
        assert_eq!(inked.get(&(30, 10)), Some(&1.0));
    }

    #[test]
    fn the_row_spans_find_every_pixel_the_whole_box_holds() {
        // Every pixel of each segment's bounding box (widened by the pen) against the row
        // spans: the same pixels, the same coverage, for steep, shallow, level, upright and
        // zero-length segments at fractional positions, and pens of 1 to 6 pixels.
        let segments = [
            ((10.3, 12.7), (80.9, 30.1)),
            ((50.5, 5.2), (52.1, 95.8)),
            ((20.0, 40.0), (90.0, 40.0)),
            ((33.0, 10.0), (33.0, 70.0)),
            ((60.2, 60.7), (60.2, 60.7)),
            ((95.5, 3.5), (2.25, 97.75)),
            ((40.0, 41.0), (41.0, 90.0)),
        ];
        for width in 1..=6 {
            for (a, b) in segments {
                let w = f64::from(width);
                let mut whole = HashMap::new();
                for y in 0..100 {
                    for x in 0..100 {
                        let c = coverage(to_segment((f64::from(x), f64::from(y)), a, b), w);
                        if c > 0.0 {
                            whole.insert((x, y), c);
                        }
                    }
                }
                let points = if a == b { vec![a] } else { vec![a, b] };
                assert_eq!(
                    stroked(&points, width),
                    whole,
                    "{a:?} to {b:?}, width {width}"
                );
            }
        }
    }

    #[test]
    fn a_disc_inks_its_area_and_a_ring_its_rim() {
        let mut area = 0.0f32;
        circle((50, 50), 10, 1, true, (100, 100), |_, _, c| area += c);
        let exact = std::f32::consts::PI * 100.0;
        assert!(
            (area - exact).abs() / exact < 0.02,
            "{area} against {exact}"
        );
        let mut rim = 0.0f32;
        circle((50, 50), 10, 2, false, (100, 100), |_, _, c| rim += c);
        let exact = 2.0 * std::f32::consts::PI * 10.0 * 2.0;
        assert!((rim - exact).abs() / exact < 0.05, "{rim} against {exact}");
    }
}
