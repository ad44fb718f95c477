//! Dense LU factorisation with partial pivoting, real and complex, as Hairer's `decsol.f`
//! (subroutines DEC, SOL, DECC and SOLC; C. B. Moler, Algorithm 423, *Comm. ACM* 15 (1972),
//! p. 274): the same pivot choice, multipliers and loop order, so that `radau5` reproduces
//! `radau5.f`'s runs value for value. Matrices are stored by columns, `a[i + j·n]`.

/// A real `n × n` matrix factorised in place (DEC), and solves with it (SOL).
#[derive(Clone, Debug, Default)]
pub struct DenseLu {
    n: usize,
    /// U on and above the diagonal, the negated multipliers below it (DEC's A).
    a: Vec<f64>,
    /// The pivot row of each stage (DEC's IP, 0-based).
    pivots: Vec<usize>,
}

impl DenseLu {
    /// The matrix to factorise, by columns, zeroed to order `n`; then [`DenseLu::factor`].
    pub fn matrix(&mut self, n: usize) -> &mut [f64] {
        self.n = n;
        self.a.clear();
        self.a.resize(n * n, 0.0);
        self.pivots.resize(n, 0);
        &mut self.a
    }

    /// DEC: Gaussian elimination with partial pivoting (the largest |a_ik| of the column);
    /// `false` when a pivot is zero (the matrix is singular, DEC's IER ≠ 0).
    pub fn factor(&mut self) -> bool {
        let (n, a) = (self.n, &mut self.a);
        for k in 0..n.saturating_sub(1) {
            let mut m = k;
            for i in k + 1..n {
                if a[i + k * n].abs() > a[m + k * n].abs() {
                    m = i;
                }
            }
            self.pivots[k] = m;
            let mut t = a[m + k * n];
            if m != k {
                a[m + k * n] = a[k + k * n];
                a[k + k * n] = t;
            }
            if t == 0.0 {
                return false;
            }
            t = 1.0 / t;
            for i in k + 1..n {
                a[i + k * n] = -a[i + k * n] * t;
            }
            for j in k + 1..n {
                a.swap(m + j * n, k + j * n);
                let t = a[k + j * n];
                if t != 0.0 {
                    for i in k + 1..n {
                        a[i + j * n] += a[i + k * n] * t;
                    }
                }
            }
        }
        n == 0 || a[n * n - 1] != 0.0
    }

    /// SOL: overwrites `b` with `A⁻¹·b`.
    pub fn solve(&self, b: &mut [f64]) {
        let (n, a) = (self.n, &self.a);
        if n == 0 {
            return;
        }
        for k in 0..n - 1 {
            let m = self.pivots[k];
            b.swap(m, k);
            let t = b[k];
            for i in k + 1..n {
                b[i] += a[i + k * n] * t;
            }
        }
        for k in (1..n).rev() {
            b[k] /= a[k + k * n];
            let t = -b[k];
            for i in 0..k {
                b[i] += a[i + k * n] * t;
            }
        }
        b[0] /= a[0];
    }
}

/// A complex `n × n` matrix `AR + i·AI` factorised in place (DECC), and solves with it
/// (SOLC).
#[derive(Clone, Debug, Default)]
pub struct DenseComplexLu {
    n: usize,
    ar: Vec<f64>,
    ai: Vec<f64>,
    pivots: Vec<usize>,
}

impl DenseComplexLu {
    /// The real and imaginary parts of the matrix to factorise, by columns, zeroed to order
    /// `n`; then [`DenseComplexLu::factor`].
    pub fn matrix(&mut self, n: usize) -> (&mut [f64], &mut [f64]) {
        self.n = n;
        for part in [&mut self.ar, &mut self.ai] {
            part.clear();
            part.resize(n * n, 0.0);
        }
        self.pivots.resize(n, 0);
        (&mut self.ar, &mut self.ai)
    }

    /// DECC: DEC in complex arithmetic, the pivot the largest |re| + |im| of the column;
    /// `false` when a pivot is zero.
    pub fn factor(&mut self) -> bool {
        let (n, ar, ai) = (self.n, &mut self.ar, &mut self.ai);
        let at = |i: usize, j: usize| i + j * n;
        for k in 0..n.saturating_sub(1) {
            let mut m = k;
            for i in k + 1..n {
                if ar[at(i, k)].abs() + ai[at(i, k)].abs() > ar[at(m, k)].abs() + ai[at(m, k)].abs()
                {
                    m = i;
                }
            }
            self.pivots[k] = m;
            let (mut tr, mut ti) = (ar[at(m, k)], ai[at(m, k)]);
            if m != k {
                ar[at(m, k)] = ar[at(k, k)];
                ai[at(m, k)] = ai[at(k, k)];
                ar[at(k, k)] = tr;
                ai[at(k, k)] = ti;
            }
            if tr.abs() + ti.abs() == 0.0 {
                return false;
            }
            let den = tr * tr + ti * ti;
            tr /= den;
            ti = -ti / den;
            for i in k + 1..n {
                let prodr = ar[at(i, k)] * tr - ai[at(i, k)] * ti;
                let prodi = ai[at(i, k)] * tr + ar[at(i, k)] * ti;
                ar[at(i, k)] = -prodr;
                ai[at(i, k)] = -prodi;
            }
            for j in k + 1..n {
                let (tr, ti) = (ar[at(m, j)], ai[at(m, j)]);
                ar[at(m, j)] = ar[at(k, j)];
                ai[at(m, j)] = ai[at(k, j)];
                ar[at(k, j)] = tr;
                ai[at(k, j)] = ti;
                if tr.abs() + ti.abs() == 0.0 {
                    continue;
                }
                // DECC's three loops: a real, an imaginary or a complex multiplier.
                for i in k + 1..n {
                    let (prodr, prodi) = if ti == 0.0 {
                        (ar[at(i, k)] * tr, ai[at(i, k)] * tr)
                    } else if tr == 0.0 {
                        (-ai[at(i, k)] * ti, ar[at(i, k)] * ti)
                    } else {
                        (
                            ar[at(i, k)] * tr - ai[at(i, k)] * ti,
                            ai[at(i, k)] * tr + ar[at(i, k)] * ti,
                        )
                    };
                    ar[at(i, j)] += prodr;
                    ai[at(i, j)] += prodi;
                }
            }
        }
        n == 0 || ar[n * n - 1].abs() + ai[n * n - 1].abs() != 0.0
    }

    /// SOLC: overwrites `(br, bi)` with `A⁻¹·(br + i·bi)`.
    pub fn solve(&self, br: &mut [f64], bi: &mut [f64]) {
        let (n, ar, ai) = (self.n, &self.ar, &self.ai);
        if n == 0 {
            return;
        }
        let at = |i: usize, j: usize| i + j * n;
        for k in 0..n - 1 {
            let m = self.pivots[k];
            let (tr, ti) = (br[m], bi[m]);
            br[m] = br[k];
            bi[m] = bi[k];
            br[k] = tr;
            bi[k] = ti;
            for i in k + 1..n {
                br[i] += ar[at(i, k)] * tr - ai[at(i, k)] * ti;
                bi[i] += ai[at(i, k)] * tr + ar[at(i, k)] * ti;
            }
        }
        let divide = |br: &mut [f64], bi: &mut [f64], k: usize| {
            let (r, i) = (ar[at(k, k)], ai[at(k, k)]);
            let den = r * r + i * i;
            let prodr = br[k] * r + bi[k] * i;
            let prodi = bi[k] * r - br[k] * i;
            br[k] = prodr / den;
            bi[k] = prodi / den;
        };
        for k in (1..n).rev() {
            divide(br, bi, k);
            let (tr, ti) = (-br[k], -bi[k]);
            for i in 0..k {
                br[i] += ar[at(i, k)] * tr - ai[at(i, k)] * ti;
                bi[i] += ai[at(i, k)] * tr + ar[at(i, k)] * ti;
            }
        }
        divide(br, bi, 0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_real_system_is_solved_with_row_exchanges() {
        // [[0, 2, 1], [1, 1, 0], [4, 0, 2]]·x = b with x = (1, −2, 3): the first pivot is
        // in the third row.
        let mut lu = DenseLu::default();
        let rows = [[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [4.0, 0.0, 2.0]];
        let a = lu.matrix(3);
        for (i, row) in rows.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                a[i + 3 * j] = *v;
            }
        }
        assert!(lu.factor());
        let mut b = [-1.0, -1.0, 10.0];
        lu.solve(&mut b);
        for (x, want) in b.iter().zip([1.0, -2.0, 3.0]) {
            assert!((x - want).abs() < 1e-15, "{b:?}");
        }
        // A singular matrix is reported.
        let a = lu.matrix(2);
        a.copy_from_slice(&[1.0, 2.0, 2.0, 4.0]);
        assert!(!lu.factor());
    }

    #[test]
    fn a_complex_system_is_solved() {
        // [[1 + i, 2], [3i, 1 − i]]·x = b with x = (1 − i, 2 + i).
        let mut lu = DenseComplexLu::default();
        let (ar, ai) = lu.matrix(2);
        ar.copy_from_slice(&[1.0, 0.0, 2.0, 1.0]);
        ai.copy_from_slice(&[1.0, 3.0, 0.0, -1.0]);
        assert!(lu.factor());
        // b1 = (1 + i)(1 − i) + 2(2 + i) = 6 + 2i; b2 = 3i(1 − i) + (1 − i)(2 + i) = 6 + 2i.
        let (mut br, mut bi) = ([6.0, 6.0], [2.0, 2.0]);
        lu.solve(&mut br, &mut bi);
        for (x, want) in br.iter().zip([1.0, 2.0]).chain(bi.iter().zip([-1.0, 1.0])) {
            assert!((x - want).abs() < 1e-15, "{br:?} {bi:?}");
        }
    }
}
