//! Eigenvalues of a small dense real matrix, without eigenvectors: reduction to upper Hessenberg
//! form by stabilised elementary similarity transforms (Gaussian elimination with row pivoting),
//! then Francis' implicit double-shift QR iteration on the Hessenberg matrix (the EISPACK
//! `elmhes` and `hqr` routines, as described in Wilkinson and Reinsch's *Handbook for Automatic
//! Computation*, vol. II, and in Golub and Van Loan, Sect. 7.5).
//!
//! The general six-revolute solver needs only the eigenvalues of its 24 x 24 companion matrix
//! (every real root x3 of the eliminant); a Schur decomposition that also accumulates the
//! orthogonal factor (nalgebra's `Schur`) does about twice the work. The iteration is capped, so
//! a matrix on which it cycles returns `None` instead of spinning.
//!
//! Row-major arrays keep the row operations of both phases on contiguous memory.

/// Iterations allowed per eigenvalue before giving up (with exceptional shifts at 10 and 20).
const MAX_ITERATIONS: usize = 30;

/// The eigenvalues of `a` (row-major, destroyed) as (real, imaginary) parts, complex ones in
/// conjugate pairs; `None` if the QR iteration does not converge within its cap or meets a
/// non-finite number.
pub(super) fn eigenvalues<const N: usize>(a: &mut [[f64; N]; N]) -> Option<[(f64, f64); N]> {
    if a.iter().flatten().any(|v| !v.is_finite()) {
        return None;
    }
    hessenberg(a);
    let mut out = [(0.0, 0.0); N];
    hqr(a, &mut out).then_some(out)
}

/// Reduces `a` to upper Hessenberg form in place by elementary similarity transforms with
/// partial pivoting (`elmhes`); the entries below the subdiagonal are set to zero.
fn hessenberg<const N: usize>(a: &mut [[f64; N]; N]) {
    for m in 1..N.saturating_sub(1) {
        // The pivot: the largest entry of column m - 1 on or below row m.
        let mut x = 0.0f64;
        let mut piv = m;
        for (j, row) in a.iter().enumerate().skip(m) {
            if row[m - 1].abs() > x.abs() {
                x = row[m - 1];
                piv = j;
            }
        }
        if piv != m {
            // Swap rows and columns m and piv: a similarity.
            a.swap(piv, m);
            for row in a.iter_mut() {
                row.swap(piv, m);
            }
        }
        if x == 0.0 {
            continue;
        }
        for i in m + 1..N {
            let y = a[i][m - 1];
            if y == 0.0 {
                continue;
            }
            let y = y / x;
            a[i][m - 1] = 0.0;
            // Row i -= y row m (columns m..N; column m - 1 is now zero) ...
            let (upper, lower) = a.split_at_mut(i);
            for (t, s) in lower[0][m..].iter_mut().zip(&upper[m][m..]) {
                *t -= y * s;
            }
            // ... and column m += y column i, which keeps the similarity.
            for row in a.iter_mut() {
                row[m] += y * row[i];
            }
        }
    }
}

/// The eigenvalues of the upper Hessenberg matrix `a` (destroyed) by Francis' double-shift QR
/// iteration with deflation (`hqr`), written to `out`; false on no convergence. A little over
/// 80 lines: the deflation loop and its 1x1 / 2x2 block endings read as one algorithm (the shift
/// search and the double step are already apart).
fn hqr<const N: usize>(a: &mut [[f64; N]; N], out: &mut [(f64, f64); N]) -> bool {
    let mut norm = 0.0;
    for (i, row) in a.iter().enumerate() {
        for v in &row[i.saturating_sub(1)..] {
            norm += v.abs();
        }
    }
    if N == 0 {
        return true;
    }
    let mut nn = N - 1;
    // The accumulated exceptional shifts.
    let mut t = 0.0;
    let mut its = 0;
    loop {
        // The lowest l with a negligible subdiagonal entry a[l][l - 1] (l = 0: none).
        let mut l = nn;
        while l >= 1 {
            let mut s = a[l - 1][l - 1].abs() + a[l][l].abs();
            if s == 0.0 {
                s = norm;
            }
            if a[l][l - 1].abs() + s == s {
                a[l][l - 1] = 0.0;
                break;
            }
            l -= 1;
        }
        let mut x = a[nn][nn];
        if l == nn {
            // One real root.
            out[nn] = (x + t, 0.0);
            if nn == 0 {
                return true;
            }
            nn -= 1;
            its = 0;
            continue;
        }
        let mut y = a[nn - 1][nn - 1];
        let mut w = a[nn][nn - 1] * a[nn - 1][nn];
        if l == nn - 1 {
            // Two roots: the eigenvalues of the trailing 2 x 2 block.
            let p = 0.5 * (y - x);
            let q = p * p + w;
            let z = q.abs().sqrt();
            x += t;
            if q >= 0.0 {
                let z = p + z.copysign(p);
                let second = if z != 0.0 { x - w / z } else { x + z };
                out[nn - 1] = (x + z, 0.0);
                out[nn] = (second, 0.0);
            } else {
                out[nn - 1] = (x + p, -z);
                out[nn] = (x + p, z);
            }
            if nn < 2 {
                return true;
            }
            nn -= 2;
            its = 0;
            continue;
        }
        if its == MAX_ITERATIONS {
            return false;
        }
        if its == 10 || its == 20 {
            // An exceptional shift, to break a cycle.
            t += x;
            for (i, row) in a.iter_mut().enumerate().take(nn + 1) {
                row[i] -= x;
            }
            let s = a[nn][nn - 1].abs() + a[nn - 1][nn - 2].abs();
            x = 0.75 * s;
            y = x;
            w = -0.4375 * s * s;
        }
        its += 1;
        let (m, pqr) = shift_start(a, l, nn, [x, y, w]);
        double_step(a, l, m, nn, pqr);
    }
}

/// The first column (p, q, r) of the double shift with the trailing block's x, y, w, from row
/// m: the highest m >= l below which two consecutive subdiagonal entries are negligible (the
/// step starts there); m and (p, q, r), scaled.
fn shift_start<const N: usize>(
    a: &[[f64; N]; N],
    l: usize,
    nn: usize,
    [x, y, w]: [f64; 3],
) -> (usize, [f64; 3]) {
    let mut m = nn - 2;
    loop {
        let z = a[m][m];
        let (r0, s0) = (x - z, y - z);
        let p = (r0 * s0 - w) / a[m + 1][m] + a[m][m + 1];
        let q = a[m + 1][m + 1] - z - r0 - s0;
        let r = a[m + 2][m + 1];
        let s = p.abs() + q.abs() + r.abs();
        let (p, q, r) = (p / s, q / s, r / s);
        if m == l {
            return (m, [p, q, r]);
        }
        let u = a[m][m - 1].abs() * (q.abs() + r.abs());
        let v = p.abs() * (a[m - 1][m - 1].abs() + z.abs() + a[m + 1][m + 1].abs());
        if u + v == v {
            return (m, [p, q, r]);
        }
        m -= 1;
    }
}

/// One Francis double step on rows and columns l..=nn from row m, the shift's first column
/// (p, q, r) given: Householder reflections of size 3 chase the bulge down.
fn double_step<const N: usize>(
    a: &mut [[f64; N]; N],
    l: usize,
    m: usize,
    nn: usize,
    [mut p, mut q, mut r]: [f64; 3],
) {
    for i in m + 2..=nn {
        a[i][i - 2] = 0.0;
        if i != m + 2 {
            a[i][i - 3] = 0.0;
        }
    }
    let mut x = 0.0;
    for k in m..nn {
        if k != m {
            p = a[k][k - 1];
            q = a[k + 1][k - 1];
            r = if k != nn - 1 { a[k + 2][k - 1] } else { 0.0 };
            x = p.abs() + q.abs() + r.abs();
            if x != 0.0 {
                p /= x;
                q /= x;
                r /= x;
            }
        }
        let s = (p * p + q * q + r * r).sqrt().copysign(p);
        if s == 0.0 {
            continue;
        }
        if k == m {
            if l != m {
                a[k][k - 1] = -a[k][k - 1];
            }
        } else {
            a[k][k - 1] = -s * x;
        }
        p += s;
        let (xx, yy, zz) = (p / s, q / s, r / s);
        q /= p;
        r /= p;
        // Rows k, k + 1, k + 2 (the third only below the last step).
        let (top, below) = a.split_at_mut(k + 1);
        let (next, further) = below.split_at_mut(1);
        let (rk, rk1) = (&mut top[k], &mut next[0]);
        if k != nn - 1 {
            let rk2 = &mut further[0];
            for j in k..=nn {
                let pp = rk[j] + q * rk1[j] + r * rk2[j];
                rk2[j] -= pp * zz;
                rk1[j] -= pp * yy;
                rk[j] -= pp * xx;
            }
        } else {
            for j in k..=nn {
                let pp = rk[j] + q * rk1[j];
                rk1[j] -= pp * yy;
                rk[j] -= pp * xx;
            }
        }
        // Columns k, k + 1, k + 2.
        for row in a.iter_mut().take(nn.min(k + 3) + 1).skip(l) {
            let mut pp = xx * row[k] + yy * row[k + 1];
            if k != nn - 1 {
                pp += zz * row[k + 2];
                row[k + 2] -= pp * r;
            }
            row[k + 1] -= pp * q;
            row[k] -= pp;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::eigenvalues;

    fn lcg(s: &mut u64) -> f64 {
        *s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    /// Sorted by real part, then imaginary part.
    fn sorted(mut v: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
        v.sort_by(|a, b| a.partial_cmp(b).unwrap());
        v
    }

    /// Random matrices: the same eigenvalues as nalgebra's Schur decomposition (an independent
    /// implementation), matched pairwise after sorting, and their sum the trace.
    #[test]
    fn random_matrices_have_the_eigenvalues_of_an_independent_schur_decomposition() {
        let mut s = 3u64;
        for _ in 0..200 {
            let mut a = [[0.0; 24]; 24];
            for v in a.iter_mut().flatten() {
                *v = lcg(&mut s);
            }
            let m = nalgebra::SMatrix::<f64, 24, 24>::from_fn(|i, j| a[i][j]);
            let want: Vec<(f64, f64)> = m
                .complex_eigenvalues()
                .iter()
                .map(|c| (c.re, c.im))
                .collect();
            let trace: f64 = (0..24).map(|i| a[i][i]).sum();
            let got = eigenvalues(&mut a).unwrap();
            let sum: f64 = got.iter().map(|e| e.0).sum();
            assert!((sum - trace).abs() < 1e-10, "{sum} vs {trace}");
            for (g, w) in sorted(got.to_vec()).iter().zip(sorted(want)) {
                assert!(
                    (g.0 - w.0).abs() < 1e-8 && (g.1 - w.1).abs() < 1e-8,
                    "{g:?} {w:?}"
                );
            }
        }
    }

    /// The companion matrix of a polynomial with known roots, repeated pairs at +-i included
    /// (the general 6R eliminant's spurious factor (1 + x^2)^2 here): those roots.
    #[test]
    fn a_companion_matrix_has_its_polynomials_roots() {
        // (x - 0.5)(x + 2)(x - 3)(x^2 + 1)^2 (x^2 - 2x + 5): roots 0.5, -2, 3, +-i twice, 1 +- 2i.
        let factors: [&[f64]; 6] = [
            &[-0.5, 1.0],
            &[2.0, 1.0],
            &[-3.0, 1.0],
            &[1.0, 0.0, 1.0],
            &[1.0, 0.0, 1.0],
            &[5.0, -2.0, 1.0],
        ];
        let mut poly = vec![1.0];
        for f in factors {
            let mut next = vec![0.0; poly.len() + f.len() - 1];
            for (i, a) in poly.iter().enumerate() {
                for (j, b) in f.iter().enumerate() {
                    next[i + j] += a * b;
                }
            }
            poly = next;
        }
        // Monic of degree 9: x^9 = -sum c_k x^k.
        let mut a = [[0.0; 9]; 9];
        for i in 0..8 {
            a[i][i + 1] = 1.0;
        }
        for k in 0..9 {
            a[8][k] = -poly[k];
        }
        let mut got = eigenvalues(&mut a).unwrap().to_vec();
        let want = sorted(vec![
            (-2.0, 0.0),
            (0.0, -1.0),
            (0.0, -1.0),
            (0.0, 1.0),
            (0.0, 1.0),
            (0.5, 0.0),
            (1.0, -2.0),
            (1.0, 2.0),
            (3.0, 0.0),
        ]);
        // Each wanted root matched to the nearest one found, each found root used once; the
        // double roots at +-i come out to about the square root of the precision.
        for w in &want {
            let (k, d) = got
                .iter()
                .enumerate()
                .map(|(k, g)| (k, (g.0 - w.0).hypot(g.1 - w.1)))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap();
            assert!(d < 1e-6, "{w:?}: {got:?}");
            got.remove(k);
        }
    }

    /// Non-finite input: no answer instead of a spin or a panic.
    #[test]
    fn a_nan_gives_none() {
        let mut a = [[1.0, 2.0], [f64::NAN, 0.0]];
        assert!(eigenvalues(&mut a).is_none());
    }
}
