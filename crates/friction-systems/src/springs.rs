//! The springs of a system sorted once by what their ends are, as the right-hand side
//! ([`crate::hybrid`]) and the passes of a time-stepping scheme ([`crate::moreau_jean`]) read
//! them: between two bodies, or between a body and an anchor (a spring between two anchors is
//! refused by [`crate::System`]). Each pass then runs over its springs with no test of their
//! ends.

use crate::system::{End, System};

/// The force `k·(x_b − x_a) + c·(v_b − v_a)` on end `a` of a spring k with damper c, and
/// `v_b − v_a`.
#[inline]
fn spring_force(k: f64, c: f64, (xa, va): (f64, f64), (xb, vb): (f64, f64)) -> (f64, f64) {
    let dv = vb - va;
    (k * (xb - xa) + c * dv, dv)
}

/// A spring between bodies `a` and `b`: force `f = k·(x_b − x_a) + c·(v_b − v_a)` on `a`,
/// `−f` on `b`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Pair {
    pub a: usize,
    pub b: usize,
    /// Stiffness k, N/m.
    pub k: f64,
    /// Damping c, N·s/m.
    pub c: f64,
}

impl Pair {
    /// The force on `a`, and `v_b − v_a`, with the ends at `(x_a, v_a)` and `(x_b, v_b)`.
    #[inline]
    pub fn force(&self, (xa, va): (f64, f64), (xb, vb): (f64, f64)) -> (f64, f64) {
        spring_force(self.k, self.c, (xa, va), (xb, vb))
    }
}

/// A spring between a body and an anchor moving as `x0 + v·t`: force on the body
/// `f = k·(x_anchor − x) + c·(v_anchor − v)`, whichever end of the declared spring the
/// anchor is (the force on the other end negated, to the bit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Anchored {
    pub body: usize,
    /// The anchor's position at t = 0, m.
    pub x0: f64,
    /// The anchor's velocity, m/s.
    pub v: f64,
    /// Stiffness k, N/m.
    pub k: f64,
    /// Damping c, N·s/m.
    pub c: f64,
}

impl Anchored {
    /// The force on the body at time `t` with the body at `(x, v)`, and `v_anchor − v`.
    #[inline]
    pub fn force(&self, t: f64, body: (f64, f64)) -> (f64, f64) {
        spring_force(self.k, self.c, body, (self.x0 + self.v * t, self.v))
    }
}

/// A system's springs by kind, each kind in the order the system declares them.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Springs {
    pub pairs: Vec<Pair>,
    pub anchored: Vec<Anchored>,
}

/// Where a spring went in [`Springs`]: its index among the pairs or among the springs to
/// anchors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Sorted {
    Pair(usize),
    Anchored(usize),
}

impl Springs {
    /// The springs of `system`, and the springs at each of its bodies in the declared order.
    pub fn of(system: &System) -> (Springs, Vec<Vec<Sorted>>) {
        let mut springs = Springs::default();
        let mut at = vec![Vec::new(); system.bodies.len()];
        for s in &system.springs {
            let (k, c) = (s.k, s.c);
            match (s.a, s.b) {
                (End::Body(a), End::Body(b)) => {
                    for end in [a, b] {
                        at[end].push(Sorted::Pair(springs.pairs.len()));
                    }
                    springs.pairs.push(Pair { a, b, k, c });
                }
                (End::Body(body), End::Anchor(anchor)) | (End::Anchor(anchor), End::Body(body)) => {
                    let anchor = &system.anchors[anchor];
                    at[body].push(Sorted::Anchored(springs.anchored.len()));
                    springs.anchored.push(Anchored {
                        body,
                        x0: anchor.x0,
                        v: anchor.v,
                        k,
                        c,
                    });
                }
                // No force on a body (and refused by `System::validate`).
                (End::Anchor(_), End::Anchor(_)) => {}
            }
        }
        (springs, at)
    }

    /// Sorts the springs to anchors by body (keeping the declared order at each body) and
    /// returns where each of `n` bodies' starts, its end last: body k's are
    /// `anchored[start[k]..start[k + 1]]`.
    pub fn sort_anchored_by_body(&mut self, n: usize) -> Vec<usize> {
        self.anchored.sort_by_key(|s| s.body);
        let mut start = vec![0; n + 1];
        for s in &self.anchored {
            start[s.body + 1] += 1;
        }
        for k in 0..n {
            start[k + 1] += start[k];
        }
        start
    }

    /// The same springs with body i renumbered `at[i]`.
    pub fn renumbered(&self, at: &[usize]) -> Springs {
        Springs {
            pairs: self
                .pairs
                .iter()
                .map(|s| Pair {
                    a: at[s.a],
                    b: at[s.b],
                    ..*s
                })
                .collect(),
            anchored: self
                .anchored
                .iter()
                .map(|s| Anchored {
                    body: at[s.body],
                    ..*s
                })
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{spring_force, Anchored, Pair, Sorted, Springs};
    use crate::system::{End, System};

    #[test]
    fn springs_are_sorted_by_their_ends_in_declared_order() {
        let mut system = System::default();
        let anchor = End::Anchor(system.add_anchor("wall", 0.5, 2.0));
        let (b0, b1) = (End::Body(0), End::Body(1));
        for name in ["b0", "b1"] {
            system.add_body(name, 1.0, 0.0, 0.0);
        }
        system.add_spring(anchor, b0, 1.0, 0.1);
        system.add_spring(b0, b1, 2.0, 0.1);
        system.add_spring(b1, anchor, 3.0, 0.1);
        let (springs, at) = Springs::of(&system);
        assert_eq!(
            springs.pairs,
            [Pair {
                a: 0,
                b: 1,
                k: 2.0,
                c: 0.1
            }]
        );
        assert_eq!(
            at,
            [
                [Sorted::Anchored(0), Sorted::Pair(0)],
                [Sorted::Pair(0), Sorted::Anchored(1)]
            ]
        );
        let bodies: Vec<(usize, f64)> = springs.anchored.iter().map(|s| (s.body, s.k)).collect();
        assert_eq!(bodies, [(0, 1.0), (1, 3.0)]);
        assert_eq!((springs.anchored[1].x0, springs.anchored[1].v), (0.5, 2.0));
        let mut renumbered = springs.renumbered(&[1, 0]);
        assert_eq!((renumbered.pairs[0].a, renumbered.pairs[0].b), (1, 0));
        assert_eq!(renumbered.anchored[0].body, 1);
        let start = renumbered.sort_anchored_by_body(3);
        let by_body: Vec<(usize, f64)> =
            renumbered.anchored.iter().map(|s| (s.body, s.k)).collect();
        assert_eq!(by_body, [(0, 3.0), (1, 1.0)]);
        assert_eq!(start, [0, 1, 2, 2]);
    }

    #[test]
    fn an_anchored_spring_pulls_its_body_as_the_declared_spring_does_to_the_bit() {
        let (x0, v, k, c) = (0.3, 0.7, 123.456, 0.789);
        let (t, xb, vb) = (1.234567, 0.987654, -0.3456);
        let anchored = Anchored {
            body: 0,
            x0,
            v,
            k,
            c,
        };
        let (f, dv) = anchored.force(t, (xb, vb));
        let anchor = (x0 + v * t, v);
        // Anchor at end a: the body, end b, takes minus the force on a.
        let (fa, dva) = spring_force(k, c, anchor, (xb, vb));
        assert_eq!(
            (f.to_bits(), dv.to_bits()),
            ((-fa).to_bits(), (-dva).to_bits())
        );
        // Anchor at end b: the body is end a.
        let (fb, dvb) = spring_force(k, c, (xb, vb), anchor);
        assert_eq!((f.to_bits(), dv.to_bits()), (fb.to_bits(), dvb.to_bits()));
        assert_eq!(f, k * (anchor.0 - xb) + c * (v - vb));
    }
}
