//! Six revolute joints with axes 2, 3 and 4 parallel and nothing else required (IK-Geo's
//! `three_parallel`): any lengths and twists elsewhere, so the Universal Robots arm is the
//! special case [`super::parallel3`] solves faster. Up to 8 solutions, in closed form.
//!
//! In standard DH (2.52), axes 2-4 parallel means alpha2, alpha3 in {0, pi}; let
//! s = cos(alpha2) cos(alpha3) = +-1. The direction h = z1 of the parallel axes is
//! `Rz(theta1) (0, -sin alpha1, cos alpha1)` in frame 0 (theta1 alone) and
//! `g = s (0, sin alpha4, cos alpha4)` in frame 4 (a constant: turning about h leaves it). So:
//!
//! - the origin o5 of frame 5 is fixed to the flange (`o5 = p6 + R6 w6`), and its component along
//!   h is `h . (o5 - o1) = H + s (cos alpha4 d5 + sin alpha4 a5 sin theta5)` with
//!   `H = d2 + cos(alpha2) d3 + s d4` and `h . o1 = cos alpha1 d1`;
//! - axis 6, z5, is fixed to the flange, and `h . z5 = s (cos alpha4 cos alpha5 - sin alpha4
//!   sin alpha5 cos theta5)`.
//!
//! Both equations are linear in (cos theta1, sin theta1, cos theta5, sin theta5) (IK-Geo's
//! subproblem 6): sin theta5 and cos theta5 are affine in theta1, and `cos^2 + sin^2 = 1` is a
//! trigonometric polynomial of degree 2 in theta1, a quartic (up to 4 roots). Where a5 = 0 or
//! sin alpha5 = 0 one equation holds theta1 alone (two roots), and the other gives theta5 (two
//! more). Then theta6 and theta2 + theta3 + theta4 follow from the orientation, and theta2,
//! theta3 from the planar two-link problem of Sect. 2.12.1 (two elbows).

use super::arm_general::{Trig1, affine_roots, eval1, mul, quadratic_roots};
use super::chain::{Row, Twist};
use super::planar::{TwoLinkSol, two_link};
use super::posture::{Elbow, FreeReason, Posture};
use super::{MAX_SOLUTIONS, RawSolutions};
use crate::kinematics::pose::Pose;
use crate::kinematics::trig::sin_cos;
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;

/// Below this a sine counts as zero (the case splits above).
const SIN_TOL: f64 = 1e-9;

/// How theta1 and theta5 are found.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Case {
    /// The quartic in theta1 (a5 != 0, sin alpha5 != 0).
    Quartic,
    /// a5 = 0: the position along h fixes theta1, the axis of joint 6 then cos theta5.
    NoA5,
    /// sin alpha5 = 0: the axis of joint 6 fixes theta1, the position then sin theta5.
    Parallel56,
}

/// The numbers the closed form needs.
#[derive(Debug, Clone)]
pub(super) struct Parallel3General {
    rows: [Row; 6],
    /// cos(alpha2) cos(alpha3) = +-1.
    s: f64,
    /// cos(alpha2) = +-1.
    c2: f64,
    /// Rx(alpha2) Rx(alpha3) Rx(alpha4): frame 4 in frame 1 is `Rz(psi) C` (psi = theta2 +
    /// c2 theta3 + s theta4).
    c: Matrix3<f64>,
    /// Frame 5's origin in frame 6 (m).
    w6: Vector3<f64>,
    /// `h . o5 = k1 + s sin(alpha4) a5 sin theta5`.
    k1: f64,
    /// `h . z5 = s cos(alpha4) cos(alpha5) - s sin(alpha4) sin(alpha5) cos theta5`.
    k2: f64,
    case: Case,
    len_tol: f64,
}

impl Parallel3General {
    /// Recognises six revolute rows with axes 2-4 parallel (neither axis 1 nor axis 5 parallel
    /// to them, a2, a3 != 0).
    pub(super) fn detect(rows: &[Row], len_tol: f64) -> Option<Self> {
        if rows.len() != 6 || rows.iter().any(|r| !r.revolute) {
            return None;
        }
        let c2 = rows[1].twist.parallel_sign()?;
        let c3 = rows[2].twist.parallel_sign()?;
        let parallel = |r: &Row| matches!(r.twist, Twist::Zero | Twist::Pi);
        if parallel(&rows[0]) || parallel(&rows[3]) {
            return None;
        }
        if rows[1].a.abs() <= len_tol || rows[2].a.abs() <= len_tol {
            return None;
        }
        let (r4, r5, r6) = (&rows[3], &rows[4], &rows[5]);
        let no_a5 = r5.a.abs() <= len_tol;
        let parallel56 = r5.sa.abs() <= SIN_TOL;
        let case = match (no_a5, parallel56) {
            (false, false) => Case::Quartic,
            (true, false) => Case::NoA5,
            (false, true) => Case::Parallel56,
            // Axes 5 and 6 the same line: not a six-joint arm.
            (true, true) => return None,
        };
        let s = c2 * c3;
        let rx = |r: &Row| Matrix3::new(1.0, 0.0, 0.0, 0.0, r.ca, -r.sa, 0.0, r.sa, r.ca);
        let hh = rows[1].d + c2 * rows[2].d + s * r4.d;
        Some(Self {
            rows: std::array::from_fn(|i| rows[i]),
            s,
            c2,
            c: rx(&rows[1]) * rx(&rows[2]) * rx(r4),
            w6: Vector3::new(-r6.a, -r6.sa * r6.d, -r6.ca * r6.d),
            k1: rows[0].ca * rows[0].d + hh + s * r4.ca * r5.d,
            k2: s * r4.ca * r5.ca,
            case,
            len_tol,
        })
    }

    /// `h(theta1) . v` as (constant, cos theta1, sin theta1) coefficients.
    fn h_dot(&self, v: &Vector3<f64>) -> Trig1 {
        let r1 = &self.rows[0];
        [r1.ca * v.z, -r1.sa * v.y, r1.sa * v.x]
    }

    /// Every solution (theta values, offsets included) for the flange pose `t` in frame 0 into
    /// `out`. Where there is none, `out.unreachable` is the planar two-link problem's gap (m)
    /// when some (theta1, theta5) pair exists, otherwise NaN (no distance known).
    pub(super) fn solve_raw(&self, t: &Pose, out: &mut RawSolutions) {
        let rf = t.rotation.matrix();
        let o5 = t.translation.vector + rf * self.w6;
        let r6 = &self.rows[5];
        let z5 = rf * Vector3::new(0.0, r6.sa, r6.ca);
        let mut pairs = [(0.0, 0.0); 4];
        let np = self.theta1_theta5(&self.h_dot(&o5), &self.h_dot(&z5), &mut pairs);
        // Branches numbered in the order of theta1, then theta5 (wrapped).
        pairs[..np].sort_by(|a, b| {
            let w = crate::kinematics::orientation::wrap_angle;
            (w(a.0), w(a.1))
                .partial_cmp(&(w(b.0), w(b.1)))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        out.len = 0;
        out.unreachable = None;
        let mut gap = f64::INFINITY;
        for (k, &(th1, th5)) in pairs[..np].iter().enumerate() {
            match self.after(t, &o5, th1, th5, k, out) {
                Ok(()) => {}
                Err(d) => gap = gap.min(d),
            }
        }
        if out.len == 0 {
            // No pair at all: the flange's axis and o5 fit no direction of the parallel axes.
            out.unreachable = Some(if gap.is_finite() { gap } else { f64::NAN });
        }
    }

    /// The (theta1, theta5) pairs (at most 4) from `h . o5` (`pos`) and `h . z5` (`ori`) as
    /// trigonometric polynomials in theta1, into `pairs`; their count.
    fn theta1_theta5(&self, pos: &Trig1, ori: &Trig1, pairs: &mut [(f64, f64); 4]) -> usize {
        let (r4, r5) = (&self.rows[3], &self.rows[4]);
        // s sin(alpha4) a5 sin theta5 = h . o5 - k1; s sin(alpha4) sin(alpha5) cos theta5 =
        // k2 - h . z5.
        let ks = self.s * r4.sa * r5.a;
        let kc = self.s * r4.sa * r5.sa;
        let sin5 = [(pos[0] - self.k1) / ks, pos[1] / ks, pos[2] / ks];
        let cos5 = [(self.k2 - ori[0]) / kc, -ori[1] / kc, -ori[2] / kc];
        let mut np = 0;
        let mut roots = [0.0; 4];
        match self.case {
            Case::Quartic => {
                let (ss, cc) = (mul(&sin5, &sin5), mul(&cos5, &cos5));
                let f = [
                    ss[0] + cc[0] - 1.0,
                    ss[1] + cc[1],
                    ss[2] + cc[2],
                    ss[3] + cc[3],
                    ss[4] + cc[4],
                ];
                let n = quadratic_roots(&f, &mut roots);
                for &th1 in &roots[..n] {
                    let (s1, c1) = th1.sin_cos();
                    let (sv, cv) = (eval1(&sin5, c1, s1), eval1(&cos5, c1, s1));
                    pairs[np] = (th1, sv.atan2(cv));
                    np += 1;
                }
            }
            Case::NoA5 => {
                let n = affine_roots(&[pos[0] - self.k1, pos[1], pos[2]], &mut roots);
                for &th1 in &roots[..n] {
                    let (s1, c1) = th1.sin_cos();
                    let cv = eval1(&cos5, c1, s1);
                    if cv.abs() <= 1.0 + 1e-9 {
                        let a = cv.clamp(-1.0, 1.0).acos();
                        pairs[np] = (th1, a);
                        pairs[np + 1] = (th1, -a);
                        np += if a == 0.0 { 1 } else { 2 };
                    }
                }
            }
            Case::Parallel56 => {
                let n = affine_roots(&[ori[0] - self.k2, ori[1], ori[2]], &mut roots);
                for &th1 in &roots[..n] {
                    let (s1, c1) = th1.sin_cos();
                    let sv = eval1(&sin5, c1, s1);
                    if sv.abs() <= 1.0 + 1e-9 {
                        let a = sv.clamp(-1.0, 1.0).asin();
                        pairs[np] = (th1, a);
                        pairs[np + 1] = (th1, PI - a);
                        np += if (a - PI / 2.0).abs() == 0.0 { 1 } else { 2 };
                    }
                }
            }
        }
        np
    }

    /// theta6, theta2 + theta3 + theta4 and the two elbows for one (theta1, theta5), branch
    /// `k`, appended to `out`; the planar gap if the elbows do not reach.
    fn after(
        &self,
        t: &Pose,
        o5: &Vector3<f64>,
        th1: f64,
        th5: f64,
        k: usize,
        out: &mut RawSolutions,
    ) -> Result<(), f64> {
        let [r1, _, _, _, r5, r6] = &self.rows;
        let (s1, c1) = sin_cos(th1);
        let (s5, c5) = sin_cos(th5);
        let rot_z = |s: f64, c: f64| Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
        let rx = |r: &Row| Matrix3::new(1.0, 0.0, 0.0, 0.0, r.ca, -r.sa, 0.0, r.sa, r.ca);
        let r01 = rot_z(s1, c1) * rx(r1);
        // Y = R1^T R6 Rx(alpha6)^T = Rz(psi) L Rz(theta6), L = C Rz(theta5) Rx(alpha5).
        let y = r01.transpose() * t.rotation.matrix() * rx(r6).transpose();
        let l = self.c * rot_z(s5, c5) * rx(r5);
        let (lz, yz) = (l.column(2), y.column(2));
        let (rr, ss) = ([l[(2, 0)], l[(2, 1)]], [y[(2, 0)], y[(2, 1)]]);
        let n2 = rr[0] * rr[0] + rr[1] * rr[1];
        let aligned = n2 <= SIN_TOL * SIN_TOL;
        let (th6, psi) = if aligned {
            // Axis 6 parallel to axes 2-4: only psi + theta6 is fixed; theta6 = 0.
            let l0 = l.column(0);
            let y0 = y.column(0);
            (0.0, y0.y.atan2(y0.x) - l0.y.atan2(l0.x))
        } else {
            let c6 = (rr[0] * ss[0] + rr[1] * ss[1]) / n2;
            let s6 = (rr[1] * ss[0] - rr[0] * ss[1]) / n2;
            (s6.atan2(c6), yz.y.atan2(yz.x) - lz.y.atan2(lz.x))
        };
        // Origin of frame 4 in frame 1: R1^T (o5 - o1) - Rz(psi) C (a5 c5, a5 s5, d5).
        let o1 = Vector3::new(r1.a * c1, r1.a * s1, r1.d);
        let (sp, cp) = sin_cos(psi);
        let p = r01.transpose() * (o5 - o1)
            - rot_z(sp, cp) * self.c * Vector3::new(r5.a * c5, r5.a * s5, r5.d);
        // a2 e^{i theta2} + a3 e^{i (theta2 + c2 theta3)} = (x, y) - a4 e^{i psi}.
        let a4 = self.rows[3].a;
        let (x, y2) = (p.x - a4 * cp, p.y - a4 * sp);
        let (a2, a3) = (self.rows[1].a, self.rows[2].a);
        let mut tl = [TwoLinkSol::default(); 2];
        let n = two_link(x, y2, a2.abs(), a3.abs(), self.len_tol, &mut tl)?;
        for s in &tl[..n] {
            if out.len >= MAX_SOLUTIONS {
                break;
            }
            // Negative lengths: a e^{i A} = |a| e^{i (A + pi)}.
            let th2 = s.a + if a2 < 0.0 { PI } else { 0.0 };
            let d = s.d + if a2 < 0.0 { PI } else { 0.0 } - if a3 < 0.0 { PI } else { 0.0 };
            let th3 = self.c2 * d;
            let th4 = self.s * (psi - th2 - d);
            let mut posture = Posture {
                elbow: Some(if s.sign == 0.0 {
                    if s.merged_cos > 0.0 {
                        Elbow::Stretched
                    } else {
                        Elbow::Folded
                    }
                } else if s.sign > 0.0 {
                    Elbow::Down
                } else {
                    Elbow::Up
                }),
                branch: Some((k + 1) as u8),
                ..Posture::default()
            };
            if aligned {
                posture.free[5] = Some(FreeReason::AxesAligned);
            }
            out.q[out.len] = [th1, th2, th3, th4, th5, th6];
            out.postures[out.len] = posture;
            out.len += 1;
        }
        Ok(())
    }
}
