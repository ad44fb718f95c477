//! Pseudo-arclength continuation in one parameter p (Keller 1977; Seydel 2010, §4.5; Doedel's
//! AUTO): of periodic orbits, the unknowns u = (y₀, T, p) and the equations of
//! [`crate::shooting`] closed by the arclength condition; of equilibria, u = (y, p) and
//! f(y, p) = 0. Each step predicts along the branch's tangent τ (the kernel of the equations'
//! Jacobian, oriented as the last) and corrects by Newton on
//!
//! ```text
//! G(u) = 0,   τᵀ·(u − u_pred) = 0,
//! ```
//!
//! the step length growing by 1.5 after an easy correction (at most 3 iterations) and halving
//! after a failed one. The parameter enters the arclength scaled by its range's width, so that
//! a step of 0.05 is a twentieth of the range where the branch runs along p, and a cycle's
//! period scaled by the first one's. ∂/∂p is a difference quotient (forward in the corrector,
//! central for the tangent). Along the branch the stability is read from the Floquet multipliers (cycles) or
//! the eigenvalues (equilibria), and the points where it changes are located and named:
//! [`SpecialKind`].

use crate::flow::{flow, HybridFlow};
use crate::variational::field;
use crate::{Floquet, OrbitError, ShootingOptions};
use integrators::stability::jacobian;
use integrators::{Mode, OdeProblem};
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// A problem that depends on one parameter: the problem at each value, handed to a callback
/// (the problem may borrow what is built for the value).
pub trait Family: Sync {
    /// Calls `f` with the problem at parameter value `p`.
    fn with_problem(
        &self,
        p: f64,
        f: &mut dyn FnMut(&dyn OdeProblem) -> Result<(), OrbitError>,
    ) -> Result<(), OrbitError>;
}

/// How a branch is followed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContinuationOptions {
    /// Newton's tolerance and iterations, and the flow's integration.
    pub shooting: ShootingOptions,
    /// The parameter's range: the branch stops where it leaves it.
    pub range: (f64, f64),
    /// The first step, in the scaled arclength.
    pub step: f64,
    /// The smallest step: below it the branch stops (it cannot be followed further).
    pub min_step: f64,
    /// The largest step.
    pub max_step: f64,
    /// The most points.
    pub max_points: usize,
}

impl ContinuationOptions {
    /// Steps from 0.02 (1e-5 to 0.1) over `range`, at most 400 points.
    pub fn over(range: (f64, f64)) -> Self {
        ContinuationOptions {
            shooting: ShootingOptions::default(),
            range,
            step: 0.02,
            min_step: 1e-5,
            max_step: 0.1,
            max_points: 400,
        }
    }

    fn p_scale(&self) -> f64 {
        (self.range.1 - self.range.0).abs().max(f64::MIN_POSITIVE)
    }

    /// Whether p lies in the range.
    fn contains(&self, p: f64) -> bool {
        let (a, b) = self.range;
        a.min(b) <= p && p <= a.max(b)
    }

    /// The next step after a correction of `iterations`: 1.5 times longer after an easy one.
    fn next_step(&self, step: f64, iterations: usize) -> f64 {
        match iterations <= 3 {
            true => (1.5 * step).min(self.max_step),
            false => step,
        }
    }
}

/// Where a branch changes: its kind, the parameter value and the points it lies between.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SpecialPoint {
    /// What happens there.
    pub kind: SpecialKind,
    /// The parameter's value (interpolated between the two points, or refined).
    pub p: f64,
    /// The indices of the branch's points it lies between.
    pub between: (usize, usize),
}

/// The kinds of special points.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpecialKind {
    /// The branch turns back in p (the parameter's tangent changes sign): two orbits or
    /// equilibria meet and vanish.
    Fold,
    /// A Floquet multiplier crosses −1: a cycle of twice the period branches off.
    PeriodDoubling,
    /// A complex pair of multipliers crosses the unit circle: a torus branches off.
    NeimarkSacker,
    /// A real multiplier crosses +1 with no fold: a branch point.
    BranchPoint,
    /// A complex pair of eigenvalues of an equilibrium crosses the imaginary axis: a cycle is
    /// born (refined by the secant method on the pair's real part).
    Hopf,
    /// An equilibrium's real eigenvalue crosses 0 with no fold: a branch point.
    SteadyBranchPoint,
    /// The sequence of segments (modes) of the orbit changes: a stick or slip segment appears
    /// or vanishes (a grazing or sliding bifurcation of the hybrid orbit).
    SegmentsChange,
}

/// One computed point of a branch of cycles.
#[derive(Clone, Debug, PartialEq)]
pub struct CyclePoint {
    /// The parameter.
    pub p: f64,
    /// The period, s.
    pub period: f64,
    /// The state at the start of the orbit (on its section).
    pub y0: Vec<f64>,
    /// The flow over one period.
    pub flow: HybridFlow,
    /// The multipliers and the stability.
    pub floquet: Floquet,
    /// Newton's iterations for this point.
    pub iterations: usize,
}

impl CyclePoint {
    /// The orbit's segments as their modes, in order.
    pub fn mode_sequence(&self) -> Vec<Vec<Mode>> {
        self.flow.segments.iter().map(|s| s.modes.clone()).collect()
    }
}

/// One computed point of a branch of equilibria.
#[derive(Clone, Debug, PartialEq)]
pub struct EquilibriumPoint {
    /// The parameter.
    pub p: f64,
    /// The equilibrium.
    pub y: Vec<f64>,
    /// The eigenvalues of the Jacobian there, (re, im), by decreasing real part.
    pub eigenvalues: Vec<(f64, f64)>,
    /// Whether every eigenvalue has a negative real part (beyond 1e-9 of its size).
    pub stable: bool,
}

/// A branch: its points in order, its special points, and why it ended.
#[derive(Clone, Debug, PartialEq)]
pub struct Branch<P> {
    /// The points.
    pub points: Vec<P>,
    /// The special points.
    pub special: Vec<SpecialPoint>,
    /// Why the continuation stopped.
    pub ended: String,
}

/// The residual of a cycle point: its gap, its phase offset, the end's vector field.
struct CycleEval {
    flow: HybridFlow,
    f_end: DVector<f64>,
}

/// The flow of `family` at p from (y, modes) over T, and the field at its end.
fn cycle_eval(
    family: &dyn Family,
    p: f64,
    (y, modes, period): (&[f64], &[Mode], f64),
    options: &ShootingOptions,
) -> Result<CycleEval, OrbitError> {
    let mut out = None;
    family.with_problem(p, &mut |problem| {
        let n = problem.dim() - problem.quadratures();
        let hybrid = flow(problem, (0.0, period), y, modes, &options.flow)?;
        let f_end = field(problem, 0.0, &hybrid.y_end, &hybrid.modes_end, n);
        out = Some(CycleEval {
            flow: hybrid,
            f_end,
        });
        Ok(())
    })?;
    out.ok_or_else(|| OrbitError::Unsupported("the family gave no problem".into()))
}

/// A segment shorter than this fraction of the period where the corrector fails is taken as
/// vanishing: the branch's mode sequence ends there.
pub const VANISHING_SEGMENT: f64 = 0.02;

/// The relative step of the central differences in p.
const P_STEP: f64 = 1e-6;

/// Follows the branch of periodic orbits of `family` from the orbit (y₀, modes, T) at `p0`
/// (converged, e.g. by [`crate::find_orbit`]), in the direction of increasing p when
/// `increasing`.
pub fn continue_cycles(
    family: &dyn Family,
    p0: f64,
    (y0, modes, period0): (&[f64], &[Mode], f64),
    increasing: bool,
    options: &ContinuationOptions,
) -> Result<Branch<CyclePoint>, OrbitError> {
    let first = cycle_eval(family, p0, (y0, modes, period0), &options.shooting)?;
    let n = first.f_end.len();
    // u = (y[..n], T/T₀, p/scale): the period in units of the first, the parameter in those
    // of its range, so that neither dominates the arclength.
    let scales = (period0, options.p_scale());
    let (t_scale, scale) = scales;
    let pack = |y: &[f64], t: f64, p: f64| {
        let mut u = DVector::zeros(n + 2);
        u.rows_mut(0, n).copy_from_slice(&y[..n]);
        u[n] = t / t_scale;
        u[n + 1] = p / scale;
        u
    };
    let unpack = |u: &DVector<f64>, tail: &[f64]| {
        let mut y = u.rows(0, n).iter().copied().collect::<Vec<f64>>();
        y.extend_from_slice(&tail[n..]);
        (y, u[n] * t_scale, u[n + 1] * scale)
    };
    let point = |p: f64, y: Vec<f64>, t: f64, e: CycleEval, iterations: usize| {
        let floquet = Floquet::of(&e.flow.sensitivity).ok_or(OrbitError::Singular)?;
        Ok::<CyclePoint, OrbitError>(CyclePoint {
            p,
            period: t,
            y0: y,
            flow: e.flow,
            floquet,
            iterations,
        })
    };
    let mut points = vec![point(p0, y0.to_vec(), period0, first, 0)?];
    let mut tangent = DVector::zeros(n + 2);
    tangent[n + 1] = if increasing { 1.0 } else { -1.0 };
    let mut step = options.step;
    let mut special = Vec::new();
    // The last two steps' arclengths and parameter changes, for a fold's vertex.
    let mut previous: Option<(f64, f64)> = None;
    let ended;
    loop {
        if points.len() >= options.max_points {
            ended = format!("{} points, the most asked for", options.max_points);
            break;
        }
        let last = points.last().expect("the branch has its start");
        let u_last = pack(&last.y0, last.period, last.p);
        // The section through the last point, normal to its flow.
        let mut normal = DVector::zeros(n);
        family.with_problem(last.p, &mut |problem| {
            normal = field(problem, 0.0, &last.y0, modes, n);
            Ok(())
        })?;
        let normal = normal.normalize();
        // The tangent at the last point: the kernel of its Jacobian, oriented as before.
        let jac = cycle_jacobian(family, last, modes, &normal, scales, &options.shooting)?;
        tangent = kernel(&jac, &tangent).ok_or(OrbitError::Singular)?;
        let corrected = loop {
            let predicted = &u_last + step * &tangent;
            match correct_cycle(
                family,
                (&predicted, &tangent, step),
                (modes, &normal, &last.y0),
                (scales, &unpack),
                &options.shooting,
            ) {
                Ok(c) => break Some(c),
                Err(_) if step / 2.0 >= options.min_step => step /= 2.0,
                Err(_) => break None,
            }
        };
        let Some((u, iterations)) = corrected else {
            // A segment about to vanish: the mode sequence the branch is followed in ends.
            let shortest = shortest_phase(&last.flow);
            if shortest < VANISHING_SEGMENT * last.period {
                special.push(SpecialPoint {
                    kind: SpecialKind::SegmentsChange,
                    p: last.p,
                    between: (points.len() - 1, points.len() - 1),
                });
                ended = format!(
                    "a segment shrinks to zero length near p = {} ({} s of a {} s period): the \
                     cycle leaves its mode sequence there (a grazing or sliding bifurcation)",
                    last.p, shortest, last.period
                );
            } else {
                ended = format!(
                    "the corrector failed at the smallest step {} near p = {}",
                    options.min_step, last.p
                );
            }
            break;
        };
        let (y, t, p) = unpack(&u, &last.y0);
        let e = cycle_eval(family, p, (&y, modes, t), &options.shooting)?;
        let next = point(p, y, t, e, iterations)?;
        let k = points.len();
        let arc = (&u - &u_last).norm();
        let turn = previous
            .filter(|&(_, dp)| dp * (p - last.p) < 0.0)
            .map(|(arc_before, _)| {
                fold_vertex([-arc_before, 0.0, arc], [points[k - 2].p, last.p, p])
            });
        special.extend(cycle_changes(&points[k - 1], &next, k, turn));
        previous = Some((arc, p - last.p));
        points.push(next);
        if !options.contains(p) {
            ended = format!("p = {p} left the range");
            break;
        }
        step = options.next_step(step, iterations);
    }
    // A multiplier through +1 beside a turn is the fold's own.
    let folds: Vec<(usize, usize)> = (special.iter())
        .filter(|s| s.kind == SpecialKind::Fold)
        .map(|s| s.between)
        .collect();
    special.retain(|s| {
        s.kind != SpecialKind::BranchPoint
            || !folds
                .iter()
                .any(|f| s.between.0 + 1 >= f.0 && s.between.1 <= f.1 + 1)
    });
    Ok(Branch {
        points,
        special,
        ended,
    })
}

/// The (n+1)×(n+2) Jacobian of the cycle equations at `point` in the scaled unknowns
/// (T/T₀, p/scale): [[M − I, f_end·T₀, ∂φ/∂p·scale],
/// [nᵀ, 0, 0]].
fn cycle_jacobian(
    family: &dyn Family,
    point: &CyclePoint,
    modes: &[Mode],
    normal: &DVector<f64>,
    (t_scale, scale): (f64, f64),
    options: &ShootingOptions,
) -> Result<DMatrix<f64>, OrbitError> {
    let n = normal.len();
    let e = cycle_eval(family, point.p, (&point.y0, modes, point.period), options)?;
    let dp = P_STEP * point.p.abs().max(1.0);
    let up = cycle_eval(
        family,
        point.p + dp,
        (&point.y0, modes, point.period),
        options,
    )?;
    let down = cycle_eval(
        family,
        point.p - dp,
        (&point.y0, modes, point.period),
        options,
    )?;
    let mut a = DMatrix::zeros(n + 1, n + 2);
    a.view_mut((0, 0), (n, n))
        .copy_from(&(&e.flow.sensitivity - DMatrix::identity(n, n)));
    a.view_mut((0, n), (n, 1)).copy_from(&(&e.f_end * t_scale));
    for i in 0..n {
        a[(i, n + 1)] = (up.flow.y_end[i] - down.flow.y_end[i]) / (2.0 * dp) * scale;
    }
    a.view_mut((n, 0), (1, n)).copy_from(&normal.transpose());
    Ok(a)
}

/// The unit vector spanning the kernel of the (m)×(m+1) matrix `a`, oriented along `previous`.
fn kernel(a: &DMatrix<f64>, previous: &DVector<f64>) -> Option<DVector<f64>> {
    let (m, cols) = a.shape();
    let mut b = DMatrix::zeros(cols, cols);
    b.view_mut((0, 0), (m, cols)).copy_from(a);
    b.row_mut(m).copy_from(&previous.transpose());
    let mut rhs = DVector::zeros(cols);
    rhs[m] = 1.0;
    let t = b.lu().solve(&rhs)?;
    let t = t.normalize();
    Some(if t.dot(previous) < 0.0 { -t } else { t })
}

type Unpack<'a> = dyn Fn(&DVector<f64>, &[f64]) -> (Vec<f64>, f64, f64) + 'a;

/// Newton on the cycle equations and the arclength condition from `predicted` (∂φ/∂p a
/// forward difference at each iterate).
/// A correction that grows, or that lands farther from the prediction than the step itself (on
/// another sheet of the branch the arclength plane also cuts), fails.
fn correct_cycle(
    family: &dyn Family,
    (predicted, tangent, step): (&DVector<f64>, &DVector<f64>, f64),
    (modes, normal, reference): (&[Mode], &DVector<f64>, &[f64]),
    ((t_scale, scale), unpack): ((f64, f64), &Unpack),
    options: &ShootingOptions,
) -> Result<(DVector<f64>, usize), OrbitError> {
    let n = normal.len();
    let mut u = predicted.clone();
    let r = DVector::from_column_slice(&reference[..n]);
    let mut last_residual = f64::INFINITY;
    for iteration in 0..=CORRECTOR_ITERATIONS {
        let (y, t, p) = unpack(&u, reference);
        if t.is_nan() || t <= 0.0 || (&u - predicted).norm() > step {
            return Err(OrbitError::Singular);
        }
        let e = cycle_eval(family, p, (&y, modes, t), options)?;
        if e.flow.modes_end != modes {
            return Err(OrbitError::ModesDoNotClose {
                start: modes.iter().map(|m| m.0).collect(),
                end: e.flow.modes_end.iter().map(|m| m.0).collect(),
            });
        }
        let gap = DVector::from_iterator(n, (0..n).map(|i| e.flow.y_end[i] - y[i]));
        let y_dyn = DVector::from_column_slice(&y[..n]);
        let phase = normal.dot(&(&y_dyn - &r));
        let arc = tangent.dot(&(&u - predicted));
        let size = y[..n].iter().fold(1.0_f64, |a, v| a.max(v.abs()));
        let residual = gap.amax().max(phase.abs()) / size;
        if residual <= options.tolerance {
            return Ok((u, iteration));
        }
        if iteration >= 2 && residual > last_residual {
            break;
        }
        last_residual = residual;
        let dp = P_STEP * p.abs().max(1.0);
        let up = cycle_eval(family, p + dp, (&y, modes, t), options)?;
        let column = DVector::from_iterator(
            n,
            (0..n).map(|i| (up.flow.y_end[i] - e.flow.y_end[i]) / dp * scale),
        );
        let mut a = DMatrix::zeros(n + 2, n + 2);
        a.view_mut((0, 0), (n, n))
            .copy_from(&(&e.flow.sensitivity - DMatrix::identity(n, n)));
        a.view_mut((0, n), (n, 1)).copy_from(&(&e.f_end * t_scale));
        a.view_mut((0, n + 1), (n, 1)).copy_from(&column);
        a.view_mut((n, 0), (1, n)).copy_from(&normal.transpose());
        a.row_mut(n + 1).copy_from(&tangent.transpose());
        let mut b = DVector::zeros(n + 2);
        b.rows_mut(0, n).copy_from(&(-gap));
        b[n] = -phase;
        b[n + 1] = -arc;
        u += a.lu().solve(&b).ok_or(OrbitError::Singular)?;
    }
    Err(OrbitError::NoConvergence {
        iterations: CORRECTOR_ITERATIONS,
        residual: last_residual,
        wanted: options.tolerance,
    })
}

/// The most Newton iterations of one corrector step (a step that needs more is halved).
const CORRECTOR_ITERATIONS: usize = 8;

/// The shortest phase of a cycle's flow: its segments' durations, the last joined to the first
/// where the section cuts one phase in two (the same modes at both ends).
fn shortest_phase(flow: &HybridFlow) -> f64 {
    let s = &flow.segments;
    let mut d: Vec<f64> = s.iter().map(|s| s.t1 - s.t0).collect();
    if s.len() > 1 && s[0].modes == s[s.len() - 1].modes {
        let last = d.pop().unwrap_or(0.0);
        d[0] += last;
    }
    d.into_iter().fold(f64::INFINITY, f64::min)
}

/// The parameter at the vertex of the parabola through (s_i, p_i): where a branch that turned
/// back in p turned.
fn fold_vertex(s: [f64; 3], p: [f64; 3]) -> f64 {
    // Newton's divided differences: p(s) = p0 + d1·(s − s0) + d2·(s − s0)(s − s1).
    let d1 = (p[1] - p[0]) / (s[1] - s[0]);
    let d12 = (p[2] - p[1]) / (s[2] - s[1]);
    let d2 = (d12 - d1) / (s[2] - s[0]);
    if d2 == 0.0 {
        return p[1];
    }
    // p'(s) = d1 + d2·(2s − s0 − s1) = 0.
    let vertex = 0.5 * (s[0] + s[1] - d1 / d2);
    p[0] + d1 * (vertex - s[0]) + d2 * (vertex - s[0]) * (vertex - s[1])
}

/// The periodic orbit of `family` at p near the guess (y, modes, T), by Newton at fixed p
/// ([`crate::find_orbit`]), as a point of a branch.
pub fn cycle_at(
    family: &dyn Family,
    p: f64,
    (y, modes, period): (&[f64], &[Mode], f64),
    options: &ShootingOptions,
) -> Result<CyclePoint, OrbitError> {
    let mut out = None;
    family.with_problem(p, &mut |problem| {
        let orbit = crate::find_orbit(problem, 0.0, (y, modes, period), options)?;
        out = Some(CyclePoint {
            p,
            period: orbit.period,
            y0: orbit.y0,
            flow: orbit.flow,
            floquet: orbit.floquet,
            iterations: orbit.iterations,
        });
        Ok(())
    })?;
    out.ok_or_else(|| OrbitError::Unsupported("the family gave no problem".into()))
}

/// The special points between two consecutive cycle points `a` and `b` (b the `k`-th); `turn`
/// the vertex of a fold where the branch turned back in p between the point before `a` and
/// `b`.
fn cycle_changes(a: &CyclePoint, b: &CyclePoint, k: usize, turn: Option<f64>) -> Vec<SpecialPoint> {
    let mut out = Vec::new();
    let between = (k - 1, k);
    let mid = 0.5 * (a.p + b.p);
    // The nontrivial multipliers outside the unit circle, by kind.
    let outside = |f: &Floquet| {
        let mut negative = 0;
        let mut positive = 0;
        let mut complex = 0;
        for &(re, im) in &f.multipliers[1..] {
            if re.hypot(im) > 1.0 {
                match (im != 0.0, re < 0.0) {
                    (true, _) => complex += 1,
                    (false, true) => negative += 1,
                    (false, false) => positive += 1,
                }
            }
        }
        (negative, positive, complex)
    };
    let (na, pa, ca) = outside(&a.floquet);
    let (nb, pb, cb) = outside(&b.floquet);
    if na != nb {
        out.push(SpecialPoint {
            kind: SpecialKind::PeriodDoubling,
            p: mid,
            between,
        });
    }
    if ca != cb {
        out.push(SpecialPoint {
            kind: SpecialKind::NeimarkSacker,
            p: mid,
            between,
        });
    }
    match turn {
        Some(p) => out.push(SpecialPoint {
            kind: SpecialKind::Fold,
            p,
            between: (k - 2, k),
        }),
        None if pa != pb => out.push(SpecialPoint {
            kind: SpecialKind::BranchPoint,
            p: mid,
            between,
        }),
        None => {}
    }
    if !same_cycle(&a.mode_sequence(), &b.mode_sequence()) {
        out.push(SpecialPoint {
            kind: SpecialKind::SegmentsChange,
            p: mid,
            between,
        });
    }
    out
}

/// Whether two cyclic mode sequences are the same up to where they start (the segment the
/// section cuts counted once).
fn same_cycle(a: &[Vec<Mode>], b: &[Vec<Mode>]) -> bool {
    let squash = |s: &[Vec<Mode>]| {
        let mut out: Vec<Vec<Mode>> = Vec::new();
        for m in s {
            if out.last() != Some(m) {
                out.push(m.clone());
            }
        }
        if out.len() > 1 && out.first() == out.last() {
            out.pop();
        }
        out
    };
    let (a, b) = (squash(a), squash(b));
    a.len() == b.len()
        && (0..a.len().max(1)).any(|r| (0..a.len()).all(|i| a[(i + r) % a.len()] == b[i]))
}

/// The eigenvalues of `problem`'s Jacobian at (y, modes), by decreasing real part; `None` for
/// a differential–algebraic problem or a failed decomposition.
fn eigenvalues(problem: &dyn OdeProblem, y: &[f64], modes: &[Mode]) -> Option<Vec<(f64, f64)>> {
    let j = jacobian(problem, 0.0, y, modes)?;
    let schur = nalgebra::linalg::Schur::try_new(j, f64::EPSILON, 10_000)?;
    let mut l: Vec<(f64, f64)> = (schur.complex_eigenvalues().iter())
        .map(|l| (l.re, l.im))
        .collect();
    l.sort_by(|a, b| b.0.total_cmp(&a.0));
    Some(l)
}

/// Whether every eigenvalue decays (Re λ < −1e-9·|λ|).
fn decays(eigenvalues: &[(f64, f64)]) -> bool {
    eigenvalues
        .iter()
        .all(|&(re, im)| re < -1e-9 * re.hypot(im))
}

/// The equilibrium of `family` at p near `y` in `modes` by Newton at fixed p, and its
/// eigenvalues.
pub fn equilibrium_at(
    family: &dyn Family,
    p: f64,
    y: &[f64],
    modes: &[Mode],
    options: &ShootingOptions,
) -> Result<EquilibriumPoint, OrbitError> {
    let mut out = None;
    family.with_problem(p, &mut |problem| {
        let n = problem.dim() - problem.quadratures();
        let mut y = y.to_vec();
        for iteration in 0..=options.max_iterations {
            let f = field(problem, 0.0, &y, modes, n);
            let size = y[..n].iter().fold(1.0_f64, |a, v| a.max(v.abs()));
            if f.amax() <= options.tolerance * size {
                let eigenvalues = eigenvalues(problem, &y, modes).ok_or(OrbitError::Singular)?;
                out = Some(EquilibriumPoint {
                    p,
                    stable: decays(&eigenvalues),
                    y,
                    eigenvalues,
                });
                return Ok(());
            }
            if iteration == options.max_iterations {
                break;
            }
            let j = jacobian(problem, 0.0, &y, modes).ok_or(OrbitError::Singular)?;
            let step = j.lu().solve(&(-f)).ok_or(OrbitError::Singular)?;
            for i in 0..n {
                y[i] += step[i];
            }
        }
        Err(OrbitError::NoConvergence {
            iterations: options.max_iterations,
            residual: f64::NAN,
            wanted: options.tolerance,
        })
    })?;
    out.ok_or_else(|| OrbitError::Unsupported("the family gave no problem".into()))
}

/// Follows the branch of equilibria of `family` (in the fixed `modes`) from near `y0` at `p0`,
/// in the direction of increasing p when `increasing`; Hopf points are refined to 1e-12 of the
/// range by the secant method on the real part of the crossing pair.
pub fn continue_equilibria(
    family: &dyn Family,
    p0: f64,
    (y0, modes): (&[f64], &[Mode]),
    increasing: bool,
    options: &ContinuationOptions,
) -> Result<Branch<EquilibriumPoint>, OrbitError> {
    let scale = options.p_scale();
    let first = equilibrium_at(family, p0, y0, modes, &options.shooting)?;
    let n = first.eigenvalues.len();
    let pack = |y: &[f64], p: f64| {
        let mut u = DVector::zeros(n + 1);
        u.rows_mut(0, n).copy_from_slice(&y[..n]);
        u[n] = p / scale;
        u
    };
    // The residual f(y, p) and its Jacobian [J, ∂f/∂p·scale] at u.
    let system =
        |u: &DVector<f64>, tail: &[f64]| -> Result<(DVector<f64>, DMatrix<f64>), OrbitError> {
            let mut y: Vec<f64> = u.rows(0, n).iter().copied().collect();
            y.extend_from_slice(&tail[n..]);
            let p = u[n] * scale;
            let dp = P_STEP * p.abs().max(1.0);
            let at = |p: f64, y: &[f64], with_jacobian: bool| {
                let mut r = None;
                family.with_problem(p, &mut |problem| {
                    let f = field(problem, 0.0, y, modes, n);
                    let j = match with_jacobian {
                        true => Some(jacobian(problem, 0.0, y, modes).ok_or(OrbitError::Singular)?),
                        false => None,
                    };
                    r = Some((f, j));
                    Ok(())
                })?;
                r.ok_or(OrbitError::Singular)
            };
            let (f, j) = at(p, &y, true)?;
            let (f_up, _) = at(p + dp, &y, false)?;
            let (f_down, _) = at(p - dp, &y, false)?;
            let mut a = DMatrix::zeros(n, n + 1);
            a.view_mut((0, 0), (n, n)).copy_from(&j.expect("asked for"));
            a.column_mut(n)
                .copy_from(&((f_up - f_down) * (scale / (2.0 * dp))));
            Ok((f, a))
        };
    let mut points = vec![first];
    let mut tangent = DVector::zeros(n + 1);
    tangent[n] = if increasing { 1.0 } else { -1.0 };
    let mut step = options.step;
    let mut special = Vec::new();
    let mut previous: Option<(f64, f64)> = None;
    let ended;
    loop {
        if points.len() >= options.max_points {
            ended = format!("{} points, the most asked for", options.max_points);
            break;
        }
        let last = points.last().expect("the branch has its start").clone();
        let u_last = pack(&last.y, last.p);
        let (_, a) = system(&u_last, &last.y)?;
        tangent = kernel(&a, &tangent).ok_or(OrbitError::Singular)?;
        let corrected = loop {
            let predicted = &u_last + step * &tangent;
            let mut u = predicted.clone();
            let mut done = None;
            for iteration in 0..=CORRECTOR_ITERATIONS {
                if (&u - &predicted).norm() > step {
                    break;
                }
                let (f, a) = system(&u, &last.y)?;
                let size = u.rows(0, n).iter().fold(1.0_f64, |m, v| m.max(v.abs()));
                if f.amax() <= options.shooting.tolerance * size {
                    done = Some((u.clone(), iteration));
                    break;
                }
                let mut m = DMatrix::zeros(n + 1, n + 1);
                m.view_mut((0, 0), (n, n + 1)).copy_from(&a);
                m.row_mut(n).copy_from(&tangent.transpose());
                let mut b = DVector::zeros(n + 1);
                b.rows_mut(0, n).copy_from(&(-f));
                b[n] = -tangent.dot(&(&u - &predicted));
                match m.lu().solve(&b) {
                    Some(d) => u += d,
                    None => break,
                }
            }
            match done {
                Some(c) => break Some(c),
                None if step / 2.0 >= options.min_step => step /= 2.0,
                None => break None,
            }
        };
        let Some((u, iterations)) = corrected else {
            ended = format!(
                "the corrector failed at the smallest step {} near p = {}",
                options.min_step, last.p
            );
            break;
        };
        let mut y: Vec<f64> = u.rows(0, n).iter().copied().collect();
        y.extend_from_slice(&last.y[n..]);
        let p = u[n] * scale;
        let next = equilibrium_at(family, p, &y, modes, &options.shooting)?;
        let k = points.len();
        let arc = (&u - &u_last).norm();
        if let Some((arc_before, dp)) = previous {
            if dp * (p - last.p) < 0.0 {
                special.push(SpecialPoint {
                    kind: SpecialKind::Fold,
                    p: fold_vertex([-arc_before, 0.0, arc], [points[k - 2].p, last.p, p]),
                    between: (k - 2, k),
                });
            }
        }
        previous = Some((arc, p - last.p));
        let growing = |e: &EquilibriumPoint| {
            let complex = e
                .eigenvalues
                .iter()
                .filter(|l| l.0 > 0.0 && l.1 != 0.0)
                .count();
            let real = e
                .eigenvalues
                .iter()
                .filter(|l| l.0 > 0.0 && l.1 == 0.0)
                .count();
            (complex, real)
        };
        let ((ca, ra), (cb, rb)) = (growing(&last), growing(&next));
        if ca != cb {
            let p_hopf = refine_hopf(family, (&last, &next), modes, &options.shooting)
                .unwrap_or(0.5 * (last.p + next.p));
            special.push(SpecialPoint {
                kind: SpecialKind::Hopf,
                p: p_hopf,
                between: (k - 1, k),
            });
        }
        if ra != rb
            && !special
                .last()
                .is_some_and(|s| s.kind == SpecialKind::Fold && s.between.1 == k)
        {
            special.push(SpecialPoint {
                kind: SpecialKind::SteadyBranchPoint,
                p: 0.5 * (last.p + next.p),
                between: (k - 1, k),
            });
        }
        points.push(next);
        if !options.contains(p) {
            ended = format!("p = {p} left the range");
            break;
        }
        step = options.next_step(step, iterations);
    }
    Ok(Branch {
        points,
        special,
        ended,
    })
}

/// The real part of the complex eigenvalue (Im > 0) nearest the imaginary axis.
fn critical_real_part(e: &EquilibriumPoint) -> Option<f64> {
    (e.eigenvalues.iter())
        .filter(|l| l.1 > 0.0)
        .map(|l| l.0)
        .min_by(|a, b| a.abs().total_cmp(&b.abs()))
}

/// The Hopf point between the equilibria `a` and `b` (a complex pair crossing the imaginary
/// axis between them): the secant method (Illinois' false position) on the pair's real part,
/// each trial p solved by Newton from the interpolated equilibrium, to |Δp| ≤ 1e-12·|p|.
fn refine_hopf(
    family: &dyn Family,
    (a, b): (&EquilibriumPoint, &EquilibriumPoint),
    modes: &[Mode],
    options: &ShootingOptions,
) -> Option<f64> {
    let (mut pa, mut ga) = (a.p, critical_real_part(a)?);
    let (mut pb, mut gb) = (b.p, critical_real_part(b)?);
    if ga * gb > 0.0 {
        return None;
    }
    let mut side = 0;
    for _ in 0..100 {
        let p = (pa * gb - pb * ga) / (gb - ga);
        let w = (p - a.p) / (b.p - a.p);
        let y: Vec<f64> = (a.y.iter().zip(&b.y))
            .map(|(u, v)| u + w * (v - u))
            .collect();
        let e = equilibrium_at(family, p, &y, modes, options).ok()?;
        let g = critical_real_part(&e)?;
        if (pb - pa).abs() <= 1e-12 * p.abs().max(1e-300) || g == 0.0 {
            return Some(p);
        }
        if g * gb > 0.0 {
            (pb, gb) = (p, g);
            if side == -1 {
                ga /= 2.0;
            }
            side = -1;
        } else {
            (pa, ga) = (p, g);
            if side == 1 {
                gb /= 2.0;
            }
            side = 1;
        }
    }
    Some(0.5 * (pa + pb))
}
