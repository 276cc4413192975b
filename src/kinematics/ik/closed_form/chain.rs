//! The DH table of a serial robot normalised for the closed forms: standard convention (a modified
//! table is converted exactly, its first `Rx(alpha_0) Tx(a_0)` going into the base), leading and
//! trailing fixed rows folded into the base and the tool, one row per joint variable.

use super::why::NoClosedForm;
use crate::kinematics::dh::{Convention, DhRow, modified_to_standard};
use crate::kinematics::orientation::wrap_angle;
use crate::kinematics::pose::{Pose, rot_x, rot_z, trans_x, trans_z};
use crate::kinematics::robot::{Drive, JointGeometry, JointKind, Robot};
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::{FRAC_PI_2, PI};

/// Tolerance (rad) within which a DH twist counts as 0, pi or +-pi/2.
pub(super) const TWIST_TOL: f64 = 1e-12;

/// A DH twist classified by what it means for consecutive axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Twist {
    /// alpha = 0: parallel axes.
    Zero,
    /// alpha = pi: antiparallel axes.
    Pi,
    /// alpha = +pi/2.
    PlusHalf,
    /// alpha = -pi/2.
    MinusHalf,
    /// Anything else.
    Other,
}

impl Twist {
    fn of(alpha: f64) -> Self {
        let w = wrap_angle(alpha);
        if w.abs() <= TWIST_TOL {
            Twist::Zero
        } else if (w.abs() - PI).abs() <= TWIST_TOL {
            Twist::Pi
        } else if (w - FRAC_PI_2).abs() <= TWIST_TOL {
            Twist::PlusHalf
        } else if (w + FRAC_PI_2).abs() <= TWIST_TOL {
            Twist::MinusHalf
        } else {
            Twist::Other
        }
    }

    /// cos(alpha) = +-1 for parallel or antiparallel axes.
    pub(super) fn parallel_sign(self) -> Option<f64> {
        match self {
            Twist::Zero => Some(1.0),
            Twist::Pi => Some(-1.0),
            _ => None,
        }
    }

    /// sin(alpha) = +-1 for perpendicular axes.
    pub(super) fn perpendicular_sign(self) -> Option<f64> {
        match self {
            Twist::PlusHalf => Some(1.0),
            Twist::MinusHalf => Some(-1.0),
            _ => None,
        }
    }
}

/// One joint of the normalised chain, standard DH: `A_i = Rz(theta) Tz(d) Tx(a) Rx(alpha)`, (2.52).
#[derive(Debug, Clone, Copy)]
pub(super) struct Row {
    /// Zero-based position in the chain (the joint variable's index).
    pub index: usize,
    /// Revolute (theta = q + offset) or prismatic (d = q + offset).
    pub revolute: bool,
    /// Link length (m).
    pub a: f64,
    /// Link offset d (m); the constant one of a revolute joint.
    pub d: f64,
    /// The constant theta of a prismatic joint (rad).
    pub theta: f64,
    /// Joint offset added to q.
    pub offset: f64,
    /// Classified twist.
    pub twist: Twist,
    /// cos(alpha), sin(alpha).
    pub ca: f64,
    /// sin(alpha).
    pub sa: f64,
}

impl Row {
    /// `Rz(theta) Rx(alpha)`, the rotation part of `A_i` for joint angle `theta`.
    #[inline]
    pub(super) fn rotation(&self, theta: f64) -> Matrix3<f64> {
        let (s, c) = crate::kinematics::trig::sin_cos(theta);
        Matrix3::new(
            c,
            -s * self.ca,
            s * self.sa,
            s,
            c * self.ca,
            -c * self.sa,
            0.0,
            self.sa,
            self.ca,
        )
    }

    /// The angle theta of this row for the joint value `v` (theta for a revolute joint, d for a
    /// prismatic one, offsets included).
    #[inline]
    pub(super) fn theta_of(&self, v: f64) -> f64 {
        if self.revolute { v } else { self.theta }
    }

    /// `Rx(alpha) w`.
    pub(super) fn rx(&self, w: &Vector3<f64>) -> Vector3<f64> {
        Vector3::new(
            w.x,
            self.ca * w.y - self.sa * w.z,
            self.sa * w.y + self.ca * w.z,
        )
    }
}

/// A serial chain in normal form: `T = base * A_1 ... A_n * tool`.
#[derive(Debug, Clone)]
pub(super) struct Chain {
    /// World from DH frame 0.
    pub base: Pose,
    /// One row per joint variable, in q order.
    pub rows: Vec<Row>,
    /// Frame n from tool.
    pub tool: Pose,
}

impl Chain {
    /// A length scale for tolerances: 1 m plus every length in the chain.
    pub(super) fn scale(&self) -> f64 {
        1.0 + self.rows.iter().map(|r| r.a.abs() + r.d.abs()).sum::<f64>()
            + self.tool.translation.vector.norm()
    }
}

fn fixed(r: &DhRow) -> Pose {
    rot_z(r.theta) * trans_z(r.d) * trans_x(r.a) * rot_x(r.alpha)
}

/// The normal form of `robot`, if it is a serial DH chain whose joints are actuated one by one
/// (no couplings) and whose first end-effector sits on the last joint; fixed rows are allowed
/// only at the ends.
pub(super) fn normalize(robot: &Robot) -> Option<Chain> {
    normalize_checked(robot).ok()
}

/// Why `robot` is not a serial chain of DH rows with one variable per joint, if it is not.
fn check_serial(robot: &Robot) -> Result<(), NoClosedForm> {
    let joints = robot.joints();
    for j in joints {
        match (j.kind, &j.drive) {
            (JointKind::Fixed, Drive::None) | (_, Drive::Actuated(_)) => {}
            _ => {
                return Err(NoClosedForm::Coupled {
                    joint: j.name.clone(),
                });
            }
        }
    }
    for (i, j) in joints.iter().enumerate() {
        let why = if j.parent != i.checked_sub(1) {
            "a joint branches off an earlier one (the robot is a tree)"
        } else if !matches!(j.geometry, JointGeometry::Dh { .. }) {
            "a joint is given by a URDF origin and axis, not a DH row"
        } else if j.pre != Pose::identity() {
            "a joint has a constant `pre` transform before its DH row"
        } else {
            continue;
        };
        return Err(NoClosedForm::NotSerialDh(why));
    }
    Ok(())
}

/// [`normalize`], saying why a robot has no normal form. A chain given by URDF origins and axes
/// or with `pre` transforms is first turned into the DH table derived from its axes
/// ([`crate::kinematics::dh_derive`]), whose joint values are the same q.
pub(super) fn normalize_checked(robot: &Robot) -> Result<Chain, NoClosedForm> {
    let joints = robot.joints();
    let not_plain_dh = joints
        .iter()
        .any(|j| !matches!(j.geometry, JointGeometry::Dh { .. }) || j.pre != Pose::identity());
    let one_variable_each = joints
        .iter()
        .all(|j| matches!(j.drive, Drive::Actuated(_) | Drive::None));
    if not_plain_dh && one_variable_each {
        let derived = crate::kinematics::dh_derive::derive_dh(robot, 0, Convention::Standard)?;
        let dh = derived
            .robot(&robot.name)
            .map_err(|source| NoClosedForm::InvalidDerivedTable { source })?;
        return normalize_checked(&dh);
    }
    check_serial(robot)?;
    let (conv, table) = robot.dh_table().ok_or(NoClosedForm::NotSerialDh(
        "its DH rows mix the standard and modified conventions",
    ))?;
    let not_last = NoClosedForm::NotSerialDh("the first end-effector is not on the last joint");
    let ee = robot.end_effectors().first().ok_or(not_last.clone())?;
    if ee.parent + 1 != joints.len() {
        return Err(not_last);
    }
    let mut base = robot.base;
    let mut tool = ee.tool;
    let dh: Vec<DhRow> = table.iter().map(|r| r.1).collect();
    let rows = match conv {
        Convention::Standard => dh,
        Convention::Modified => {
            let (extra, rows) = modified_to_standard(&dh);
            base *= extra;
            rows
        }
    };
    let moving = NoClosedForm::NotSerialDh("it has no moving joint");
    let first = table
        .iter()
        .position(|r| r.0 != JointKind::Fixed)
        .ok_or(moving.clone())?;
    let last = table
        .iter()
        .rposition(|r| r.0 != JointKind::Fixed)
        .ok_or(moving)?;
    for r in &rows[..first] {
        base *= fixed(r);
    }
    for r in rows[last + 1..].iter().rev() {
        tool = fixed(r) * tool;
    }
    let mut out = Vec::with_capacity(last + 1 - first);
    for i in first..=last {
        let (kind, _, offset) = table[i];
        if kind == JointKind::Fixed {
            return Err(NoClosedForm::NotSerialDh(
                "a fixed row lies between moving joints",
            ));
        }
        let r = rows[i];
        let (sa, ca) = r.alpha.sin_cos();
        out.push(Row {
            index: out.len(),
            revolute: kind == JointKind::Revolute,
            a: r.a,
            d: r.d,
            theta: r.theta,
            offset,
            twist: Twist::of(r.alpha),
            ca,
            sa,
        });
    }
    Ok(Chain {
        base,
        rows: out,
        tool,
    })
}
