//! Anti-aliased strokes and discs for the PNG figures: a pixel is inked in proportion to how
//! much of it a round pen covers, coverage = clamp(w/2 + 1/2 − d, 0, 1) with d the distance
//! from the pixel's centre to the stroke's centre line (a box filter's coverage of a pixel by
//! a straight edge, to first order), where plotters' bitmap back-end inks a pixel wholly or not
//! at all and thick lines come out stair-stepped.

use std::collections::HashMap;

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

/// The pixels inside `size` (width, height) that a round pen `width` pixels wide covers along
/// the polyline `points`, each once with its largest coverage over the segments (round joins
/// and caps; a pixel shared by two segments is not inked twice), in no particular order.
pub fn stroke(points: &[(f64, f64)], width: u32, size: (u32, u32)) -> HashMap<(i32, i32), f32> {
    let mut inked: HashMap<(i32, i32), f32> = HashMap::new();
    let w = f64::from(width.max(1));
    let reach = (w / 2.0 + 1.0).ceil() as i32;
    let segments: Vec<((f64, f64), (f64, f64))> = match points {
        [only] => vec![(*only, *only)],
        _ => points.windows(2).map(|p| (p[0], p[1])).collect(),
    };
    let pixel = |v: f64, r: i32, n: u32| (v.floor() as i32 + r).clamp(-1, n as i32);
    for (a, b) in segments {
        if !(a.0.is_finite() && a.1.is_finite() && b.0.is_finite() && b.1.is_finite()) {
            continue;
        }
        let x0 = pixel(a.0.min(b.0), -reach, size.0).max(0);
        let x1 = pixel(a.0.max(b.0), reach, size.0).min(size.0 as i32 - 1);
        let y0 = pixel(a.1.min(b.1), -reach, size.1).max(0);
        let y1 = pixel(a.1.max(b.1), reach, size.1).min(size.1 as i32 - 1);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let c = coverage(to_segment((f64::from(x), f64::from(y)), a, b), w);
                if c > 0.0 {
                    let e = inked.entry((x, y)).or_insert(0.0);
                    *e = e.max(c);
                }
            }
        }
    }
    inked
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

    #[test]
    fn a_stroke_inks_its_width_in_total_and_partly_at_its_edges() {
        // A diagonal line of width 3: across it, the coverage sums to about its width times
        // √2 per row (a row cuts the 45° band over 3·√2 pixels), with pixels partly inked.
        let inked = stroke(&[(10.0, 10.0), (60.0, 60.0)], 3, (100, 100));
        let row: Vec<f32> = (0..100)
            .filter_map(|x| inked.get(&(x, 35)).copied())
            .collect();
        let total: f32 = row.iter().sum();
        assert!((total - 3.0 * 2f32.sqrt()).abs() < 0.3, "{row:?}");
        assert!(row.iter().any(|&c| c > 0.05 && c < 0.95), "{row:?}");
        // A horizontal line of width 1 on a pixel row is that row, fully inked.
        let flat = stroke(&[(10.0, 5.0), (20.0, 5.0)], 1, (100, 100));
        assert!(
            flat.iter().all(|(&(_, y), &c)| y == 5 && c == 1.0),
            "{flat:?}"
        );
        assert_eq!(flat.len(), 11);
    }

    #[test]
    fn a_joint_of_two_segments_is_inked_once() {
        // The joint's pixels at their largest coverage, not blended twice.
        let inked = stroke(&[(10.0, 10.0), (30.0, 10.0), (30.0, 30.0)], 4, (100, 100));
        assert!(inked.values().all(|&c| c > 0.0 && c <= 1.0));
        assert_eq!(inked.get(&(30, 10)), Some(&1.0));
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
