//! Denavit–Hartenberg rows in the standard (Siciliano) and modified (Craig) conventions.

use super::pose::{Pose, rot_x, rot_z, trans_x, trans_z};
use serde::{Deserialize, Serialize};

/// Which Denavit–Hartenberg convention a table uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Convention {
    /// Siciliano / Spong: `A_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i)`, eq. (2.52).
    #[default]
    Standard,
    /// Craig: `A_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i)`; row i stores
    /// `a_{i-1}` and `alpha_{i-1}`.
    Modified,
}

impl Convention {
    /// Name as written in model files.
    pub fn as_str(self) -> &'static str {
        match self {
            Convention::Standard => "standard",
            Convention::Modified => "modified",
        }
    }
}

/// One row of a DH table, in the order of the textbook's tables (Tables 2.1-2.8: a_i, alpha_i,
/// d_i, theta_i). Lengths in metres, angles in radians.
///
/// Build it with named fields, so that a and d cannot be swapped:
/// `DhRow { a: 0.4318, alpha: 0.0, d: 0.0, theta: 0.0 }`. [`DhRow::default`] is all zeros.
///
/// For a revolute joint `theta` is ignored at evaluation time (theta = q + offset); for a
/// prismatic joint `d` is ignored (d = q + offset). For a fixed row both are used as stored.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub struct DhRow {
    /// Link length a (m): along x_i (standard) or x_{i-1} (modified).
    pub a: f64,
    /// Link twist alpha (rad).
    pub alpha: f64,
    /// Link offset d (m) along z.
    pub d: f64,
    /// Joint angle theta (rad) about z.
    pub theta: f64,
}

impl std::fmt::Display for DhRow {
    /// `a = 0.4318 m, alpha = -90°, d = 0.15005 m, theta = 0°` (angles shown in degrees).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "a = {} m, alpha = {}°, d = {} m, theta = {}°",
            self.a,
            self.alpha.to_degrees(),
            self.d,
            self.theta.to_degrees()
        )
    }
}

impl DhRow {
    /// The homogeneous transform `A_i` of this row with the given `theta` and `d` (the caller
    /// has already put the joint variable into one of them), eq. (2.52) for the standard
    /// convention.
    ///
    /// # Examples
    ///
    /// Eq. (2.52) written out for alpha = pi/2: `A = [[c, 0, s, a c], [s, 0, -c, a s],
    /// [0, 1, 0, d], [0, 0, 0, 1]]`.
    ///
    /// ```
    /// use armlab::kinematics::{Convention, DhRow};
    /// use std::f64::consts::FRAC_PI_2;
    ///
    /// let row = DhRow { a: 0.2, alpha: FRAC_PI_2, d: 0.1, theta: 0.0 };
    /// let (theta, d) = (0.7, row.d); // a revolute joint: theta = q + offset
    /// let m = row.transform(Convention::Standard, theta, d).to_homogeneous();
    /// let (s, c) = theta.sin_cos();
    /// let expected = [
    ///     [c, 0.0, s, 0.2 * c],
    ///     [s, 0.0, -c, 0.2 * s],
    ///     [0.0, 1.0, 0.0, 0.1],
    ///     [0.0, 0.0, 0.0, 1.0],
    /// ];
    /// for (i, row) in expected.iter().enumerate() {
    ///     for (j, v) in row.iter().enumerate() {
    ///         assert!((m[(i, j)] - v).abs() < 1e-15, "A[{i}][{j}]");
    ///     }
    /// }
    /// ```
    pub fn transform(&self, convention: Convention, theta: f64, d: f64) -> Pose {
        match convention {
            Convention::Standard => rot_z(theta) * trans_z(d) * trans_x(self.a) * rot_x(self.alpha),
            Convention::Modified => rot_x(self.alpha) * trans_x(self.a) * rot_z(theta) * trans_z(d),
        }
    }
}

/// Converts a serial standard-DH table to the modified convention, where that is exact.
///
/// Standard `A_i = Rz(th_i) Tz(d_i) Tx(a_i) Rx(al_i)` regrouped as
/// `[Rz(th_1) Tz(d_1)] [Tx(a_1) Rx(al_1) Rz(th_2) Tz(d_2)] ...`: modified row i takes
/// `a_{i-1}, alpha_{i-1}` from standard row i-1, and the last `Tx(a_n) Rx(alpha_n)` moves into the
/// tool. Returns the rows and the extra tool-side transform (`flange_from_tool` to prepend to the
/// tool). Always exact.
///
/// # Examples
///
/// Both tables give the same chain: the product of the standard rows equals the product of the
/// modified rows followed by the extra tool transform.
///
/// ```
/// use armlab::kinematics::dh::standard_to_modified;
/// use armlab::kinematics::{Convention, DhRow, Pose};
/// use std::f64::consts::FRAC_PI_2;
///
/// let standard = [
///     DhRow { a: 0.0, alpha: FRAC_PI_2, d: 0.3, theta: 0.0 },
///     DhRow { a: 0.4, alpha: 0.0, d: 0.0, theta: 0.0 },
///     DhRow { a: 0.35, alpha: -FRAC_PI_2, d: 0.05, theta: 0.0 },
/// ];
/// let q = [0.3, -0.5, 1.1];
/// let (modified, tool_extra) = standard_to_modified(&standard);
/// let mut t_std = Pose::identity();
/// let mut t_mod = Pose::identity();
/// for ((s, m), q) in standard.iter().zip(&modified).zip(q) {
///     t_std *= s.transform(Convention::Standard, q, s.d);
///     t_mod *= m.transform(Convention::Modified, q, m.d);
/// }
/// t_mod *= tool_extra;
/// assert!((t_std.to_homogeneous() - t_mod.to_homogeneous()).amax() < 1e-15);
/// ```
pub fn standard_to_modified(rows: &[DhRow]) -> (Vec<DhRow>, Pose) {
    let mut out = Vec::with_capacity(rows.len());
    let mut prev = (0.0, 0.0);
    for r in rows {
        out.push(DhRow {
            a: prev.0,
            alpha: prev.1,
            d: r.d,
            theta: r.theta,
        });
        prev = (r.a, r.alpha);
    }
    (out, trans_x(prev.0) * rot_x(prev.1))
}

/// Converts a serial modified-DH table to the standard convention.
///
/// The first row's `Rx(alpha_0) Tx(a_0)` moves into the base (`base_from_first`, to append to
/// the base). Always exact.
pub fn modified_to_standard(rows: &[DhRow]) -> (Pose, Vec<DhRow>) {
    let mut out = Vec::with_capacity(rows.len());
    let base_extra = match rows.first() {
        Some(r) => rot_x(r.alpha) * trans_x(r.a),
        None => Pose::identity(),
    };
    for (i, r) in rows.iter().enumerate() {
        let (a, alpha) = rows.get(i + 1).map_or((0.0, 0.0), |n| (n.a, n.alpha));
        out.push(DhRow {
            a,
            alpha,
            d: r.d,
            theta: r.theta,
        });
    }
    (base_extra, out)
}
