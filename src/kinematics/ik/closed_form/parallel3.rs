//! Six revolute joints with axes 2, 3 and 4 parallel and no spherical wrist: the Universal
//! Robots family (UR3/5/10 and their e-series), solved in closed form with up to 8 solutions.
//!
//! The rows (standard DH, (2.52)) are those of the UR documentation up to the signs of the
//! twists: a1 = 0 and alpha1 = +-pi/2; alpha2 = alpha3 = 0 (axes 2, 3, 4 parallel, along z1);
//! a4 = 0, alpha4 = +-pi/2; a5 = 0, alpha5 = +-pi/2; a6 = 0, alpha6 = 0. With these,
//!
//! - the rotation of frame 4 in frame 1 is `Rz(theta2 + theta3 + theta4) Rx(alpha4)`, so the
//!   origin of frame 4 lies at height D = d2 + d3 + d4 along z1, and so does the origin of frame 5
//!   (d5 runs along z4, normal to z1). With o5 = p - d6 z6 and z1 = s1 (sin theta1, -cos theta1, 0)
//!   in frame 0, `z1 . (o5 - o1) = D` gives `r sin(theta1 - phi) = s1 D` (two shoulders);
//! - the third row of `R_6^1` is `s4 (sin theta5 cos theta6, -sin theta5 sin theta6, -s5 cos theta5)`,
//!   which gives theta5 (two wrists) and theta6;
//! - then `A2 A3 A4` is known: theta2 + theta3 + theta4 from its rotation and the planar
//!   two-link problem of Sect. 2.12.1 for theta2, theta3 from its origin (two elbows).

use super::chain::{Row, Twist};
use super::posture::{Elbow, FreeReason, Posture, Shoulder, WristFlip};
use crate::kinematics::pose::Pose;
use nalgebra::{Matrix4, Vector3};

/// The numbers the closed form needs.
#[derive(Debug, Clone)]
pub(super) struct Parallel3 {
    /// sin(alpha1), sin(alpha4), sin(alpha5): each +-1.
    s1: f64,
    s4: f64,
    s5: f64,
    /// d1, a2, a3, D = d2 + d3 + d4, d5, d6 (m).
    d1: f64,
    a2: f64,
    a3: f64,
    dd: f64,
    d5: f64,
    d6: f64,
    /// Length tolerance (m).
    tol: f64,
}

/// One solution before offsets: the six theta and its posture.
pub(super) type Sol6 = ([f64; 6], Posture);

impl Parallel3 {
    /// Recognises the six rows (see the module docs).
    pub(super) fn detect(rows: &[Row], tol: f64) -> Option<Self> {
        if rows.len() != 6 || rows.iter().any(|r| !r.revolute) {
            return None;
        }
        let zero = |v: f64| v.abs() <= tol;
        let s1 = rows[0].twist.perpendicular_sign()?;
        let s4 = rows[3].twist.perpendicular_sign()?;
        let s5 = rows[4].twist.perpendicular_sign()?;
        let parallel = rows[1].twist == Twist::Zero && rows[2].twist == Twist::Zero;
        let lengths = zero(rows[0].a)
            && zero(rows[3].a)
            && zero(rows[4].a)
            && zero(rows[5].a)
            && !zero(rows[1].a)
            && !zero(rows[2].a);
        if !parallel || !lengths || rows[5].twist != Twist::Zero {
            return None;
        }
        Some(Self {
            s1,
            s4,
            s5,
            d1: rows[0].d,
            a2: rows[1].a,
            a3: rows[2].a,
            dd: rows[1].d + rows[2].d + rows[3].d,
            d5: rows[4].d,
            d6: rows[5].d,
            tol,
        })
    }

    /// Every solution (theta values, before offsets) for the flange pose `t` in frame 0, at most
    /// 8, written to `out`; the count, or the distance out of reach.
    pub(super) fn solve(&self, t: &Pose, out: &mut [Sol6; 8]) -> Result<usize, f64> {
        let m = t.to_homogeneous();
        let z6 = Vector3::new(m[(0, 2)], m[(1, 2)], m[(2, 2)]);
        let p = Vector3::new(m[(0, 3)], m[(1, 3)], m[(2, 3)]);
        let o5 = p - z6 * self.d6;
        // r sin(theta1 - phi) = s1 D: the wrist must lie outside the cylinder of radius |D|.
        let r = o5.x.hypot(o5.y);
        let s = self.s1 * self.dd;
        if r < s.abs() - self.tol {
            return Err(s.abs() - r);
        }
        let phi = o5.y.atan2(o5.x);
        let asin = (s / r.max(f64::MIN_POSITIVE)).clamp(-1.0, 1.0).asin();
        let mut n = 0;
        let mut unreachable: f64 = f64::INFINITY;
        for (k, th1) in [phi + asin, phi + std::f64::consts::PI - asin]
            .into_iter()
            .enumerate()
        {
            let shoulder = if r <= s.abs() + self.tol {
                Shoulder::Boundary
            } else if k == 0 {
                Shoulder::Right
            } else {
                Shoulder::Left
            };
            match self.after_shoulder(th1, shoulder, &m, &mut out[n..]) {
                Ok(c) => n += c,
                Err(d) => unreachable = unreachable.min(d),
            }
            if shoulder == Shoulder::Boundary {
                break;
            }
        }
        if n == 0 { Err(unreachable) } else { Ok(n) }
    }

    /// [`Self::solve`] into the closed form's raw solutions (before offsets).
    pub(super) fn solve_raw(&self, t: &Pose, out: &mut super::RawSolutions) {
        let mut sols = [([0.0; 6], Posture::default()); 8];
        match self.solve(t, &mut sols) {
            Ok(n) => {
                for (k, (q, posture)) in sols[..n].iter().enumerate() {
                    out.q[k] = *q;
                    out.postures[k] = *posture;
                }
                out.len = n;
            }
            Err(d) => out.unreachable = Some(d),
        }
    }

    /// The wrist and elbow solutions for shoulder angle `th1`.
    ///
    /// Allocation-free and with few transcendental calls (this is the UR5's hot path, issue 27):
    /// `A1^-1 T` and the products with `(A5 A6)^-1` are written out entry by entry for the
    /// twists +-pi/2 and 0 the family has, and the sines and cosines of the angles found are
    /// read off their own atan2 arguments instead of being recomputed.
    fn after_shoulder(
        &self,
        th1: f64,
        shoulder: Shoulder,
        m: &Matrix4<f64>,
        out: &mut [Sol6],
    ) -> Result<usize, f64> {
        let m1 = self.in_frame1(th1, m);
        // Third row of R_6^1 = s4 (sin t5 cos t6, -sin t5 sin t6, -s5 cos t5):
        // cos theta5 = -s4 s5 m22.
        let c5 = (-self.s4 * self.s5 * m1[2][2]).clamp(-1.0, 1.0);
        let base5 = c5.acos();
        let sin5 = ((1.0 - c5) * (1.0 + c5)).sqrt();
        let mut n = 0;
        let mut gap: f64 = f64::INFINITY;
        for (w, (th5, st5)) in [(base5, sin5), (-base5, -sin5)].into_iter().enumerate() {
            let singular = st5.abs() < 1e-10;
            // theta6 from (s4 m20, -s4 m21) = sin theta5 (cos theta6, sin theta6).
            let (th6, ct6, st6) = if singular {
                (0.0, 1.0, 0.0)
            } else {
                let (x6, y6) = (self.s4 * m1[2][0] / st5, -self.s4 * m1[2][1] / st5);
                let h = x6.hypot(y6);
                (y6.atan2(x6), x6 / h, y6 / h)
            };
            // Frame 4 in frame 1: M (A5 A6)^-1 = A2 A3 A4. Only its x axis and origin in the
            // plane of axes 2-4 are needed: (A5 A6)^-1 has rotation R56^T, whose first column is
            // R56's first row (cos t5 cos t6, -cos t5 sin t6, sin t5 s5), and origin
            // -R56^T p56 = -(sin t6 s5 d5, cos t6 s5 d5, d6) (A5 A6 from (2.52), a5 = a6 = 0).
            let r0 = [c5 * ct6, -c5 * st6, st5 * self.s5];
            let v = [st6 * self.s5 * self.d5, ct6 * self.s5 * self.d5, self.d6];
            let dot = |row: &[f64; 4], u: &[f64; 3]| row[0] * u[0] + row[1] * u[1] + row[2] * u[2];
            let th234 = dot(&m1[1], &r0).atan2(dot(&m1[0], &r0));
            let (x, y) = (m1[0][3] - dot(&m1[0], &v), m1[1][3] - dot(&m1[1], &v));
            let c3 =
                (x * x + y * y - self.a2 * self.a2 - self.a3 * self.a3) / (2.0 * self.a2 * self.a3);
            if c3.abs() > 1.0 + 1e-12 {
                let reach = (
                    self.a2.abs() + self.a3.abs(),
                    (self.a2.abs() - self.a3.abs()).abs(),
                );
                let d = x.hypot(y);
                gap = gap.min((d - reach.0).max(reach.1 - d).max(0.0));
                continue;
            }
            let wrist = if singular {
                WristFlip::Singular
            } else if w == 0 {
                WristFlip::Up
            } else {
                WristFlip::Down
            };
            let ctx = Elbows {
                shoulder,
                wrist,
                th: [th1, th234, th5, th6],
                xy: [x, y],
                c3,
            };
            n += self.elbows(&ctx, &mut out[n..]);
            if singular {
                break;
            }
        }
        if n == 0 { Err(gap) } else { Ok(n) }
    }

    /// `A1^-1 T`, rows 0-2 (the flange in frame 1): `Rx(-alpha1) Tz(-d1) Rz(-theta1) T` with
    /// sin(alpha1) = s1, cos(alpha1) = 0, a1 = 0 (2.52), so row 0 = c1 r0 + s1' r1,
    /// row 1 = s1 (r2 - d1 on the origin), row 2 = s1 (sin t1 r0 - cos t1 r1).
    fn in_frame1(&self, th1: f64, m: &Matrix4<f64>) -> [[f64; 4]; 3] {
        let (s, c) = th1.sin_cos();
        let mut m1 = [[0.0; 4]; 3];
        for j in 0..4 {
            let (a, b, z) = (m[(0, j)], m[(1, j)], m[(2, j)]);
            m1[0][j] = c * a + s * b;
            m1[1][j] = self.s1 * z;
            m1[2][j] = self.s1 * (s * a - c * b);
        }
        m1[1][3] = self.s1 * (m[(2, 3)] - self.d1);
        m1
    }
}

/// What the elbow solutions of one shoulder and wrist branch need.
struct Elbows {
    shoulder: Shoulder,
    wrist: WristFlip,
    /// theta1, theta2 + theta3 + theta4, theta5, theta6.
    th: [f64; 4],
    /// The origin of frame 4 in frame 1's plane.
    xy: [f64; 2],
    /// cos theta3.
    c3: f64,
}

impl Parallel3 {
    /// The elbow up and down solutions (one when stretched or folded) of the planar two-link
    /// problem for theta2, theta3, then theta4, written to `out`; their count.
    fn elbows(&self, e: &Elbows, out: &mut [Sol6]) -> usize {
        let [th1, th234, th5, th6] = e.th;
        let [x, y] = e.xy;
        let c3 = e.c3.clamp(-1.0, 1.0);
        let mut n = 0;
        let base3 = c3.acos();
        let sin3 = ((1.0 - c3) * (1.0 + c3)).sqrt();
        let stretched = (e.c3.abs() - 1.0).abs() < 1e-12;
        let count = if stretched { 1 } else { 2 };
        let towards = y.atan2(x);
        for (th3, s3) in [(base3, sin3), (-base3, -sin3)].into_iter().take(count) {
            // theta2 = Atan2(y, x) - Atan2(a3 s3, a2 + a3 c3) (Sect. 2.12.1); its cosine and
            // sine from the same two vectors, for the elbow's side.
            let (k1, k2) = (self.a2 + self.a3 * c3, self.a3 * s3);
            let th2 = towards - k2.atan2(k1);
            let th4 = th234 - th2 - th3;
            let mut posture = Posture {
                shoulder: Some(e.shoulder),
                elbow: Some(if stretched {
                    if c3 > 0.0 {
                        Elbow::Stretched
                    } else {
                        Elbow::Folded
                    }
                } else if self.elbow_above([x * k1 + y * k2, y * k1 - x * k2], x, y) {
                    Elbow::Up
                } else {
                    Elbow::Down
                }),
                wrist: Some(e.wrist),
                ..Posture::default()
            };
            if e.wrist == WristFlip::Singular {
                posture.free[5] = Some(FreeReason::WristAligned);
            }
            if n < out.len() {
                out[n] = ([th1, th2, th3, th4, th5, th6], posture);
                n += 1;
            }
        }
        n
    }
}

impl Parallel3 {
    /// Whether the elbow (origin of frame 2, along `dir2`, a positive multiple of
    /// (cos theta2, sin theta2)) lies above the line from the shoulder to the wrist point (x, y)
    /// in the arm's plane (frame 1), "above" meaning along the base's z axis, which is s1 y1 in
    /// frame 1 (`Rx(-alpha1) z0`).
    fn elbow_above(&self, dir2: [f64; 2], x: f64, y: f64) -> bool {
        let len = x.hypot(y).max(f64::MIN_POSITIVE);
        let u = [x / len, y / len];
        let along = dir2[0] * u[0] + dir2[1] * u[1];
        (dir2[1] - along * u[1]) * self.a2.signum() * self.s1 > 0.0
    }
}
