//! The spherical wrist (Sect. 2.12.5) with any signs of the twists +-pi/2.
//!
//! With alpha4 = s4 pi/2 and alpha5 = s5 pi/2,
//! `Rx(s4 pi/2) Rz(theta5) Rx(-s4 pi/2) = Ry(-s4 theta5)` (a rotation about
//! `Rx(s4 pi/2) z = -s4 y`), so
//!
//! `R_3^6 Rx(alpha6)^T = Rz(theta4) Rx(s4 pi/2) Rz(theta5) Rx(s5 pi/2) Rz(theta6)`
//! `                  = Rz(theta4) Ry(-s4 theta5) Rx((s4 + s5) pi/2) Rz(theta6)`.
//!
//! If s5 = -s4 (the textbook wrist of Table 2.5, and the Puma 560) the last factor is the identity
//! and (theta4, -s4 theta5, theta6) are ZYZ Euler angles; if s5 = s4 it is `Rx(pi)`, and since
//! `Rx(pi) Rz(theta6) = Rz(-theta6) Rx(pi)`, (theta4, -s4 theta5, -theta6) are the ZYZ angles of
//! `R Rx(pi)`. The two ZYZ solutions (2.19)-(2.20) then give (2.111)-(2.112) for any such wrist.

use super::chain::Row;
use crate::kinematics::orientation::SINGULAR_EPS;
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;

/// A spherical wrist: three revolute joints with a4 = a5 = 0, d5 = 0, alpha4, alpha5 = +-pi/2.
#[derive(Debug, Clone)]
pub(super) struct Wrist {
    /// sin(alpha4).
    s4: f64,
    /// theta6 = -psi when the two twists have the same sign.
    negate6: bool,
    /// `Rx(alpha6)^T` (times `Rx(pi)` when the twists have the same sign).
    post: Matrix3<f64>,
}

impl Wrist {
    /// Recognises the three rows of a spherical wrist.
    pub(super) fn detect(rows: &[Row], len_tol: f64) -> Option<Self> {
        let [r4, r5, r6] = [*rows.first()?, *rows.get(1)?, *rows.get(2)?];
        if rows.len() != 3 || !(r4.revolute && r5.revolute && r6.revolute) {
            return None;
        }
        if r4.a.abs() > len_tol || r5.a.abs() > len_tol || r5.d.abs() > len_tol {
            return None;
        }
        let s4 = r4.twist.perpendicular_sign()?;
        let s5 = r5.twist.perpendicular_sign()?;
        // Rx(alpha6)^T
        let rx6t = Matrix3::new(1.0, 0.0, 0.0, 0.0, r6.ca, r6.sa, 0.0, -r6.sa, r6.ca);
        let negate6 = s4 == s5;
        let post = if negate6 {
            rx6t * Matrix3::from_diagonal(&Vector3::new(1.0, -1.0, -1.0))
        } else {
            rx6t
        };
        Some(Wrist { s4, negate6, post })
    }

    /// Joint values (theta4, theta5, theta6) for `R_3^6 = r36`: the no-flip solution first.
    /// Returns the count (1 at the wrist singularity, where theta4 = 0 is chosen) and whether the
    /// wrist is singular.
    ///
    /// The ZYZ angles are those of `orientation::zyz_from_rotation` and
    /// `zyz_from_rotation_negative`, (2.19)-(2.20): phi from the third column, theta =
    /// Atan2(+-sqrt(r13^2 + r23^2), r33), and psi from the residual `(Rz(phi) Ry(theta))^T R`
    /// (exact near the singularity), written out with the sines and cosines taken from the matrix
    /// so that no trigonometric call beyond three atan2 is needed; the second solution is
    /// (phi + pi, -theta, psi + pi), (2.112).
    #[inline]
    pub(super) fn solve(&self, r36: &Matrix3<f64>, out: &mut [[f64; 3]; 2]) -> (usize, bool) {
        let m = r36 * self.post;
        let (m00, m10, m20) = (m[(0, 0)], m[(1, 0)], m[(2, 0)]);
        let (m02, m12, m22) = (m[(0, 2)], m[(1, 2)], m[(2, 2)]);
        let s = (m02 * m02 + m12 * m12).sqrt();
        let singular = s < SINGULAR_EPS;
        let (cp, sp, phi) = if singular {
            (1.0, 0.0, 0.0)
        } else {
            (m02 / s, m12 / s, m12.atan2(m02))
        };
        let theta = s.atan2(m22);
        // Residual (Rz(phi) Ry(theta))^T R: psi = Atan2(res_10, res_00).
        let x00 = cp * m00 + sp * m10;
        let x10 = -sp * m00 + cp * m10;
        let psi = x10.atan2(m22 * x00 - s * m20);
        let sign6 = if self.negate6 { -1.0 } else { 1.0 };
        out[0] = [phi, -self.s4 * theta, sign6 * psi];
        if singular {
            return (1, true);
        }
        let flip = |a: f64| if a > 0.0 { a - PI } else { a + PI };
        out[1] = [flip(phi), self.s4 * theta, sign6 * flip(psi)];
        (2, false)
    }
}
