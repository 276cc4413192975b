//! Any three-revolute positioning arm: Pieper's general case. Six-revolute arms whose last three
//! axes meet (a spherical wrist) decouple into this position problem for the wrist centre,
//! whatever the first three joints' lengths and twists (Pieper 1968; IK-Geo's "spherical" family
//! solves the same problem by its subproblem 5). The named arms of [`super::arm`] are special
//! cases with formulas of their own; this one covers the rest, up to 4 solutions.
//!
//! Derivation, standard DH `A_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i)` (2.52), point w in
//! frame 3. In frame 2, `A_3 w = Rz(theta3) u` with `u = (a3, 0, d3) + Rx(alpha3) w`; in frame 1,
//! `A_2 A_3 w = Rz(theta2) q(theta3)` with `q = (a2, 0, d2) + Rx(alpha2) Rz(theta3) u`, each
//! component affine in (cos theta3, sin theta3). With `m = Rz(-theta1) p - (a1, 0, d1) =
//! Rx(alpha1) Rz(theta2) q`, write `Rz(theta2) q = (g, k, q_z)`, `(X, Y)` for `(p_x, p_y)` turned by
//! `-theta1` (so `X^2 + Y^2 = rho^2 = p_x^2 + p_y^2`) and `m_z = p_z - d1`:
//!
//! - `X - a1 = g`, `Y = c_alpha1 k - s_alpha1 q_z`, `m_z = s_alpha1 k + c_alpha1 q_z`;
//! - `|m|^2 = |q|^2` gives `2 a1 X = rho^2 + a1^2 + m_z^2 - |q|^2`, so `g = G / (2 a1)` with
//!   `G = rho^2 - a1^2 + m_z^2 - |q|^2` (affine in theta3);
//! - `k = (m_z - c_alpha1 q_z) / s_alpha1` (affine) and `g^2 + k^2 = q_x^2 + q_y^2 =: Q`, so
//!   `F = G^2 + 4 a1^2 (k^2 - Q) = 0`: a trigonometric polynomial of degree 2 in theta3, a quartic
//!   in tan(theta3 / 2). Its roots are the eigenvalues of the quartic's companion matrix, each
//!   refined by Newton's method on F.
//!
//! Two special cases make F a square or vanish, and are solved apart: `a1 = 0` (then `G = 0` is
//! affine in theta3, two roots, and `g = +-sqrt(Q - k^2)`) and `alpha1 = 0 or pi` (then
//! `q_z = c_alpha1 m_z` is affine, `X` follows from `|m|^2 = |q|^2` and `k = +-sqrt(Q - g^2)`).
//! Then `theta1 = atan2(p_y, p_x) - atan2(Y, X)` and `theta2 = atan2(k, g) - atan2(q_y, q_x)`.

use super::chain::Row;
use super::posture::FreeReason;
use super::{COS_TOL, general6::branch_posture};
use nalgebra::Vector3;

/// `a0 + ac cos + as sin` of theta3.
pub(super) type Trig1 = [f64; 3];
/// `f0 + fc cos + fs sin + fc2 cos 2 theta + fs2 sin 2 theta` of theta3.
pub(super) type Trig2 = [f64; 5];

/// Shifts of theta3 (rad) tried for the half-angle tangent, the one keeping the quartic's
/// leading coefficient largest chosen (a root at theta3 = shift + pi is at infinity).
const SHIFTS: [f64; 4] = [0.0, 0.713, -1.931, 2.417];

/// Which equation fixes theta3.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Case {
    /// The quartic F = 0 (a1 != 0, alpha1 not 0 or pi).
    Quartic,
    /// a1 = 0: G = 0, affine.
    NoA1,
    /// alpha1 = 0 or pi (cos alpha1 = f): q_z = f m_z, affine.
    ParallelAxes12 { f: f64 },
}

/// A general three-revolute positioning arm with the numbers its equations need.
#[derive(Debug, Clone, Copy)]
pub(super) struct GeneralArm {
    a1: f64,
    d1: f64,
    sa1: f64,
    ca1: f64,
    /// q(theta3) = q0 + qc cos theta3 + qs sin theta3, per component (frame 1 before theta2).
    q: [Trig1; 3],
    case: Case,
    len_tol: f64,
}

/// `a * b` for two affine trigonometric polynomials (cos^2 = (1 + cos 2)/2, ...).
pub(super) fn mul(a: &Trig1, b: &Trig1) -> Trig2 {
    [
        a[0] * b[0] + 0.5 * (a[1] * b[1] + a[2] * b[2]),
        a[0] * b[1] + a[1] * b[0],
        a[0] * b[2] + a[2] * b[0],
        0.5 * (a[1] * b[1] - a[2] * b[2]),
        0.5 * (a[1] * b[2] + a[2] * b[1]),
    ]
}

pub(super) fn eval1(a: &Trig1, c: f64, s: f64) -> f64 {
    a[0] + a[1] * c + a[2] * s
}

impl GeneralArm {
    /// The arm of three revolute rows positioning `w` (frame 3); `None` where joint 3 cannot
    /// move the point (it lies on axis 3) or axes 1 and 2 coincide.
    pub(super) fn detect(rows: &[Row; 3], w: &Vector3<f64>, len_tol: f64) -> Option<Self> {
        let [r1, r2, r3] = rows;
        if !(r1.revolute && r2.revolute && r3.revolute) {
            return None;
        }
        let v = r3.rx(w);
        let u = Vector3::new(r3.a + v.x, v.y, r3.d + v.z);
        if u.x.hypot(u.y) <= len_tol {
            return None;
        }
        // Rx(alpha2) Rz(theta3) u, then + (a2, 0, d2).
        let (ca2, sa2) = (r2.ca, r2.sa);
        let q = [
            [r2.a, u.x, -u.y],
            [-sa2 * u.z, ca2 * u.y, ca2 * u.x],
            [r2.d + ca2 * u.z, sa2 * u.y, sa2 * u.x],
        ];
        let case = if r1.twist.parallel_sign().is_some() {
            if r1.a.abs() <= len_tol {
                return None;
            }
            Case::ParallelAxes12 { f: r1.ca.signum() }
        } else if r1.a.abs() <= len_tol {
            Case::NoA1
        } else {
            Case::Quartic
        };
        Some(GeneralArm {
            a1: r1.a,
            d1: r1.d,
            sa1: r1.sa,
            ca1: r1.ca,
            q,
            case,
            len_tol,
        })
    }

    /// |q|^2, affine in theta3 (q turns u about a fixed axis).
    fn q_squared(&self) -> Trig1 {
        let sq = self
            .q
            .iter()
            .map(|c| mul(c, c))
            .fold([0.0; 5], |acc, t| std::array::from_fn(|i| acc[i] + t[i]));
        [sq[0], sq[1], sq[2]]
    }

    /// Every solution (theta1..theta3, offsets included) for the point `p` (frame 0), sorted by
    /// the angles wrapped into (-pi, pi] and labelled "branch k" in that order; `Err(gap)` when
    /// none reaches it, the gap (m) a lower bound: the distance between the shells that the
    /// point's distance from joint 2's origin and `|q|` can take.
    pub(super) fn solve(
        &self,
        p: &Vector3<f64>,
        out: &mut [super::arm::ArmSol; 4],
    ) -> Result<usize, f64> {
        let rho2 = p.x * p.x + p.y * p.y;
        let mz = p.z - self.d1;
        let qq = self.q_squared();
        let mut th3 = [0.0; 4];
        let n3 = match self.case {
            Case::Quartic => {
                let g: Trig1 = [rho2 - self.a1 * self.a1 + mz * mz - qq[0], -qq[1], -qq[2]];
                let k = self.k_of(mz);
                let (gg, kk) = (mul(&g, &g), mul(&k, &k));
                let (qx2, qy2) = (mul(&self.q[0], &self.q[0]), mul(&self.q[1], &self.q[1]));
                let a4 = 4.0 * self.a1 * self.a1;
                let f: Trig2 = std::array::from_fn(|i| gg[i] + a4 * (kk[i] - qx2[i] - qy2[i]));
                quadratic_roots(&f, &mut th3)
            }
            Case::NoA1 => affine_roots(&[rho2 + mz * mz - qq[0], -qq[1], -qq[2]], &mut th3),
            Case::ParallelAxes12 { f } => {
                let qz = &self.q[2];
                affine_roots(&[qz[0] - f * mz, qz[1], qz[2]], &mut th3)
            }
        };
        let mut n = 0;
        let mut sols = [[0.0; 3]; 8];
        for &t3 in &th3[..n3] {
            let (s3, c3) = t3.sin_cos();
            let [qx, qy, qz] = self.q.map(|c| eval1(&c, c3, s3));
            let big_q = qx * qx + qy * qy;
            // (g, k) pairs: one for the quartic, two (+-) in the special cases.
            let mut gk = [(0.0, 0.0); 2];
            let m = match self.case {
                Case::Quartic => {
                    let g = (rho2 - self.a1 * self.a1 + mz * mz - qx * qx - qy * qy - qz * qz)
                        / (2.0 * self.a1);
                    gk[0] = (g, (mz - self.ca1 * qz) / self.sa1);
                    1
                }
                Case::NoA1 => {
                    let k = (mz - self.ca1 * qz) / self.sa1;
                    plus_minus(big_q - k * k, big_q).map_or(0, |g| {
                        gk = [(g, k), (-g, k)];
                        if g == 0.0 { 1 } else { 2 }
                    })
                }
                Case::ParallelAxes12 { .. } => {
                    let x =
                        (rho2 + self.a1 * self.a1 + mz * mz - big_q - qz * qz) / (2.0 * self.a1);
                    let g = x - self.a1;
                    plus_minus(big_q - g * g, big_q).map_or(0, |k| {
                        gk = [(g, k), (g, -k)];
                        if k == 0.0 { 1 } else { 2 }
                    })
                }
            };
            for &(g, k) in &gk[..m] {
                let (x, y) = (g + self.a1, self.ca1 * k - self.sa1 * qz);
                let t1 = p.y.atan2(p.x) - y.atan2(x);
                let t2 = k.atan2(g) - qy.atan2(qx);
                if n < sols.len() {
                    sols[n] = [t1, t2, t3];
                    n += 1;
                }
            }
        }
        self.keep(p, &mut sols, n, out)
            .ok_or_else(|| self.gap(rho2, mz, &qq))
    }

    /// k of `m_z = s_alpha1 k + c_alpha1 q_z`, affine in theta3.
    fn k_of(&self, mz: f64) -> Trig1 {
        let qz = &self.q[2];
        [
            (mz - self.ca1 * qz[0]) / self.sa1,
            -self.ca1 * qz[1] / self.sa1,
            -self.ca1 * qz[2] / self.sa1,
        ]
    }

    /// The candidates that reach `p` (checked by the arm's own forward kinematics, 1e-9 of the
    /// arm's size), without duplicates, sorted and labelled into `out`; `None` if none does.
    fn keep(
        &self,
        p: &Vector3<f64>,
        sols: &mut [[f64; 3]; 8],
        n: usize,
        out: &mut [super::arm::ArmSol; 4],
    ) -> Option<usize> {
        let wrap = crate::kinematics::orientation::wrap_angle;
        let scale = self.scale();
        let mut kept = 0;
        for i in 0..n {
            let s = sols[i].map(wrap);
            let reaches = (self.point(&s) - p).norm() <= 1e-9 * scale;
            let fresh = sols[..kept]
                .iter()
                .all(|o| o.iter().zip(&s).any(|(a, b)| wrap(a - b).abs() > 1e-9));
            if reaches && fresh && kept < 4 {
                sols[kept] = s;
                kept += 1;
            }
        }
        if kept == 0 {
            return None;
        }
        sols[..kept].sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        let on_axis = (p.x * p.x + p.y * p.y).sqrt() <= self.len_tol;
        for (k, (o, s)) in out.iter_mut().zip(&sols[..kept]).enumerate() {
            let mut posture = branch_posture(k);
            if on_axis {
                posture.free[0] = Some(FreeReason::ShoulderAxis);
            }
            *o = super::arm::ArmSol { v: *s, posture };
        }
        Some(kept)
    }

    /// The point for theta1..theta3: `Rz(t1) [(a1, 0, d1) + Rx(alpha1) Rz(t2) q(t3)]`.
    fn point(&self, t: &[f64; 3]) -> Vector3<f64> {
        let (s3, c3) = t[2].sin_cos();
        let [qx, qy, qz] = self.q.map(|c| eval1(&c, c3, s3));
        let (s2, c2) = t[1].sin_cos();
        let (g, k) = (c2 * qx - s2 * qy, s2 * qx + c2 * qy);
        let m = Vector3::new(
            self.a1 + g,
            self.ca1 * k - self.sa1 * qz,
            self.d1 + self.sa1 * k + self.ca1 * qz,
        );
        let (s1, c1) = t[0].sin_cos();
        Vector3::new(c1 * m.x - s1 * m.y, s1 * m.x + c1 * m.y, m.z)
    }

    /// The arm's size (m), for tolerances.
    fn scale(&self) -> f64 {
        1.0 + self.a1.abs() + self.d1.abs() + self.q.iter().flatten().map(|v| v.abs()).sum::<f64>()
    }

    /// A lower bound on the distance from the point to the reachable set: `|m|` lies between
    /// the point's least and greatest distance from joint 2's origin circle, `|q|` between the
    /// extremes of its affine square.
    fn gap(&self, rho2: f64, mz: f64, qq: &Trig1) -> f64 {
        let rho = rho2.sqrt();
        let m_lo = (rho - self.a1.abs()).hypot(mz);
        let m_hi = (rho + self.a1.abs()).hypot(mz);
        let amp = qq[1].hypot(qq[2]);
        let q_lo = (qq[0] - amp).max(0.0).sqrt();
        let q_hi = (qq[0] + amp).max(0.0).sqrt();
        (m_lo - q_hi).max(q_lo - m_hi).max(0.0)
    }
}

/// `sqrt(x)` where x >= 0, 0 where x is negative by rounding only (relative to `scale`), else
/// `None`.
fn plus_minus(x: f64, scale: f64) -> Option<f64> {
    if x >= 0.0 {
        Some(x.sqrt())
    } else if x >= -COS_TOL * scale.max(1.0) * 1e3 {
        Some(0.0)
    } else {
        None
    }
}

/// The roots theta of `a0 + ac cos + as sin = 0` (0, 1 where tangent, or 2).
pub(super) fn affine_roots(a: &Trig1, out: &mut [f64; 4]) -> usize {
    let r = a[1].hypot(a[2]);
    if r <= 1e-14 * (1.0 + a[0].abs()) {
        return 0;
    }
    let c = -a[0] / r;
    if c.abs() > 1.0 + COS_TOL {
        return 0;
    }
    let phi = a[2].atan2(a[1]);
    let d = c.clamp(-1.0, 1.0).acos();
    out[0] = phi + d;
    if d == 0.0 {
        return 1;
    }
    out[1] = phi - d;
    2
}

/// The real roots theta of the trigonometric polynomial `f` of degree 2 (at most 4): the
/// quartic in `x = tan((theta - shift) / 2)` solved by the eigenvalues of its companion matrix,
/// each root then refined by Newton's method on f.
pub(super) fn quadratic_roots(f: &Trig2, out: &mut [f64; 4]) -> usize {
    let at = |t: f64| {
        let (s, c) = t.sin_cos();
        let (s2, c2) = (2.0 * t).sin_cos();
        f[0] + f[1] * c + f[2] * s + f[3] * c2 + f[4] * s2
    };
    let size = f.iter().map(|v| v.abs()).sum::<f64>();
    if size == 0.0 || !size.is_finite() {
        return 0;
    }
    // The shift whose opposite angle (x at infinity) is farthest from a root.
    let shift = SHIFTS
        .iter()
        .copied()
        .max_by(|a, b| {
            at(a + std::f64::consts::PI)
                .abs()
                .total_cmp(&at(b + std::f64::consts::PI).abs())
        })
        .unwrap_or(0.0);
    let (ss, cs) = shift.sin_cos();
    let (ss2, cs2) = (2.0 * shift).sin_cos();
    // f(psi + shift) in psi: rotate the (cos, sin) pairs.
    let g = [
        f[0],
        f[1] * cs + f[2] * ss,
        f[2] * cs - f[1] * ss,
        f[3] * cs2 + f[4] * ss2,
        f[4] * cs2 - f[3] * ss2,
    ];
    // (1 + x^2)^2 f: x^4 .. x^0.
    let c = [
        g[0] - g[1] + g[3],
        2.0 * g[2] - 4.0 * g[4],
        2.0 * g[0] - 6.0 * g[3],
        2.0 * g[2] + 4.0 * g[4],
        g[0] + g[1] + g[3],
    ];
    if c[0].abs() <= 1e-12 * size {
        return 0;
    }
    let mut comp = [[0.0; 4]; 4];
    for j in 0..4 {
        comp[0][j] = -c[j + 1] / c[0];
    }
    for i in 1..4 {
        comp[i][i - 1] = 1.0;
    }
    let Some(eig) = super::eigen::eigenvalues(&mut comp) else {
        return 0;
    };
    let mut n = 0;
    for &(re, im) in &eig {
        // A double root (the point on the boundary) may come out as a near-real pair.
        if im.abs() > 1e-6 * (1.0 + re.abs()) {
            continue;
        }
        let mut t = 2.0 * re.atan() + shift;
        for _ in 0..4 {
            let (s, c) = t.sin_cos();
            let (s2, c2) = (2.0 * t).sin_cos();
            let d = -f[1] * s + f[2] * c - 2.0 * f[3] * s2 + 2.0 * f[4] * c2;
            let v = at(t);
            if d.abs() <= 1e-14 * size || v == 0.0 {
                break;
            }
            t -= v / d;
        }
        if at(t).abs() <= 1e-9 * size
            && out[..n]
                .iter()
                .all(|o| crate::kinematics::orientation::wrap_angle(o - t).abs() > 1e-9)
            && n < 4
        {
            out[n] = t;
            n += 1;
        }
    }
    n
}
