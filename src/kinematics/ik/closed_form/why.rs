//! Why an arm has no closed form: the structural test that failed, in words a student can check
//! against the DH table ("joints 4-6 do not intersect: a5 = 0.1 m, no spherical wrist").
//!
//! [`diagnose`] runs only after detection failed; it repeats the structural conditions of the
//! families one by one and names the first that does not hold.

use super::chain::{Chain, Row, normalize_checked};
use crate::kinematics::robot::Robot;
use thiserror::Error;

/// Why [`super::ClosedForm::detect`] found no closed-form family for a robot.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum NoClosedForm {
    /// The robot is not one serial chain of DH rows.
    #[error(
        "not a serial DH chain: {0}; closed forms are detected from a DH table (numerical IK works \
         for any chain)"
    )]
    NotSerialDh(&'static str),
    /// A joint follows others (a closed chain or a mimic joint).
    #[error(
        "joint {joint} is coupled to other joints (closed chain or mimic joint): the closed forms \
         need one variable per joint"
    )]
    Coupled {
        /// The coupled joint's name.
        joint: String,
    },
    /// The chain is given by origins and axes (a URDF) and no DH table could be derived from
    /// them (a tree, for instance), and why.
    #[error(transparent)]
    NoDhTable(#[from] crate::kinematics::dh_derive::NoDhTable),
    /// The DH table derived from a URDF chain does not make a valid robot.
    #[error("the DH table derived from the chain is not a valid robot: {source}")]
    InvalidDerivedTable {
        /// Why.
        source: crate::kinematics::ModelError,
    },
    /// The closed forms solve robots with a single end-effector.
    #[error(
        "end-effector {ee} of {count}: the closed forms solve robots with a single end-effector"
    )]
    SeveralEndEffectors {
        /// The end-effector asked for.
        ee: usize,
        /// How many the robot has.
        count: usize,
    },
    /// The number of joint variables has no family.
    #[error("{count} joints: {why}")]
    JointCount {
        /// Number of joint variables.
        count: usize,
        /// What that means.
        why: &'static str,
    },
    /// The joint count fits a family but the geometry does not.
    #[error("{why}")]
    Geometry {
        /// What in the geometry rules the families out, in words.
        why: String,
    },
}

/// Why `robot` has no closed form (call only when detection failed).
pub(super) fn diagnose(robot: &Robot) -> NoClosedForm {
    let chain = match normalize_checked(robot) {
        Ok(c) => c,
        Err(e) => return e,
    };
    let rows = &chain.rows;
    let tol = 1e-12 * chain.scale();
    match rows.len() {
        0 | 1 => NoClosedForm::JointCount {
            count: rows.len(),
            why: "one joint variable sets one coordinate; there is no inverse problem to solve in \
                  closed form",
        },
        5 => NoClosedForm::JointCount {
            count: 5,
            why: "a 5-joint arm cannot reach a general pose and no closed-form family of Sect. 2.12 \
                  has 5 joints (numerical IK with a task of 5 components works)",
        },
        n if n >= 7 => NoClosedForm::JointCount {
            count: n,
            why: "more joints than the 6 components of a pose: the arm is redundant (Sect. 2.10.2) \
                  and a pose has infinitely many solutions; use numerical IK",
        },
        6 => geometry(match wrist_problem(&rows[3..], tol) {
            Some(w) => {
                format!("{w}: no spherical wrist, so position and orientation do not decouple")
            }
            None => match arm_problem(&rows[..3], tol) {
                Some(a) => format!(
                    "joints 4-6 form a spherical wrist, but joints 1-3 are no positioning arm with a \
                     closed form: {a}"
                ),
                None => unmatched(),
            },
        }),
        4 => geometry(match planar_problem(rows) {
            Some(p) => format!(
                "4 joints: only the SCARA (three revolute joints, one prismatic, all axes \
                 parallel) has a closed form; {p}"
            ),
            None => unmatched(),
        }),
        _ => geometry(three_or_two(&chain, tol)),
    }
}

/// [`NoClosedForm::Geometry`] with its reason.
fn geometry(why: String) -> NoClosedForm {
    NoClosedForm::Geometry { why }
}

fn unmatched() -> String {
    "no closed-form family of Sect. 2.12 matches this DH table (a length vanishes where the \
     formulas need it)"
        .into()
}

fn three_or_two(chain: &Chain, tol: f64) -> String {
    let rows = &chain.rows;
    let Some(planar) = planar_problem(rows) else {
        return unmatched();
    };
    if rows.len() == 2 {
        return format!("not a two-link planar arm: {planar}");
    }
    let arm = arm_problem(rows, tol).unwrap_or_else(|| "the arm's lengths vanish".into());
    let wrist = wrist_problem(rows, tol).unwrap_or_else(|| "a length vanishes".into());
    format!("not planar ({planar}); not a positioning arm ({arm}); not a spherical wrist ({wrist})")
}

/// An angle in degrees; one that misses a multiple of 90 degrees by a hair says by how much
/// (rad), so that "-90°, not ±90°" never reads as a contradiction.
fn deg(alpha: f64) -> String {
    let v = alpha.to_degrees();
    let r = (v * 1000.0).round() / 1000.0;
    let right = (v / 90.0).round() * 90.0;
    let miss = alpha - right.to_radians();
    if (v - right).abs() < 5e-4 && miss != 0.0 {
        let right = if right == 0.0 { 0.0 } else { right };
        return format!("{v:.9}° ({:.1e} rad from {right}°)", miss.abs());
    }
    format!("{}°", if r == 0.0 { 0.0 } else { r })
}

fn kinds(rows: &[Row]) -> String {
    rows.iter()
        .map(|r| if r.revolute { "R" } else { "P" })
        .collect::<Vec<_>>()
        .join("-")
}

/// Why rows (joints i+1..) are not a planar arm of revolute joints and at most one prismatic.
fn planar_problem(rows: &[Row]) -> Option<String> {
    for (i, r) in rows.iter().enumerate() {
        if r.twist.parallel_sign().is_some() {
            continue;
        }
        return Some(if i + 1 < rows.len() {
            format!(
                "alpha{} = {} is neither 0° nor 180°, so axes {} and {} are not parallel",
                i + 1,
                deg(r.alpha()),
                i + 1,
                i + 2
            )
        } else {
            format!(
                "the last twist alpha{} = {} is neither 0° nor 180° (the planar closed forms need \
                 the last frame's z along the joint axes; move the twist into the tool)",
                i + 1,
                deg(r.alpha())
            )
        });
    }
    let prismatic = rows.iter().filter(|r| !r.revolute).count();
    let revolute = rows.len() - prismatic;
    if prismatic > 1 || revolute > 3 || (rows.len() == 4 && prismatic != 1) {
        return Some(format!(
            "the joints are {}: a planar closed form has two or three revolute joints and at most \
             one prismatic",
            kinds(rows)
        ));
    }
    if rows.len() < 4 && prismatic > 0 {
        return Some(format!(
            "the joints are {}: a prismatic joint along parallel axes moves out of the plane",
            kinds(rows)
        ));
    }
    None
}

/// Why three rows are not a spherical wrist.
fn wrist_problem(rows: &[Row], tol: f64) -> Option<String> {
    if let Some(k) = rows.iter().position(|r| !r.revolute) {
        return Some(format!(
            "joint {} is prismatic (a wrist needs three revolute joints)",
            first_index(rows) + k
        ));
    }
    let j = first_index(rows);
    let (r4, r5) = (rows[0], rows[1]);
    let lengths = [
        (r4.a, format!("a{j}")),
        (r5.a, format!("a{}", j + 1)),
        (r5.d, format!("d{}", j + 1)),
    ];
    for (v, name) in lengths {
        if v.abs() > tol {
            return Some(format!(
                "axes {j}-{} do not intersect in one point: {name} = {v} m, not 0",
                j + 2
            ));
        }
    }
    for (r, k) in [(r4, j), (r5, j + 1)] {
        if r.twist.perpendicular_sign().is_none() {
            return Some(format!(
                "axes {k} and {} are not perpendicular: alpha{k} = {}, not ±90°",
                k + 1,
                deg(r.alpha())
            ));
        }
    }
    None
}

/// The 1-based number of the first of `rows` in the table (rows are the wrist: joints 4-6, or the
/// three joints of a 3-DOF wrist).
fn first_index(rows: &[Row]) -> usize {
    rows.first().map_or(1, |r| r.index + 1)
}

/// Why three rows are not an anthropomorphic, spherical or cylindrical arm.
fn arm_problem(rows: &[Row], tol: f64) -> Option<String> {
    let [r1, r2, r3] = [rows[0], rows[1], rows[2]];
    let perp = |r: Row, k: usize, what: &str| {
        r.twist.perpendicular_sign().is_none().then(|| {
            format!(
                "{what} needs axes {k} and {} perpendicular, but alpha{k} = {}",
                k + 1,
                deg(r.alpha())
            )
        })
    };
    let par = |r: Row, k: usize, what: &str| {
        r.twist.parallel_sign().is_none().then(|| {
            format!(
                "{what} needs axes {k} and {} parallel, but alpha{k} = {}",
                k + 1,
                deg(r.alpha())
            )
        })
    };
    match (r1.revolute, r2.revolute, r3.revolute) {
        (true, true, true) => {
            let what = "an anthropomorphic arm (R-R-R)";
            perp(r1, 1, what).or_else(|| par(r2, 2, what)).or_else(|| {
                (r2.a.abs() <= tol).then(|| format!("{what} needs a2 ≠ 0 (the upper arm)"))
            })
        }
        (true, true, false) => {
            let what = "a spherical arm (R-R-P)";
            perp(r1, 1, what).or_else(|| perp(r2, 2, what))
        }
        (true, false, false) => {
            let what = "a cylindrical arm (R-P-P)";
            par(r1, 1, what).or_else(|| perp(r2, 2, what))
        }
        _ => Some(format!(
            "joints 1-3 are {}; the closed forms cover R-R-R (anthropomorphic), R-R-P (spherical) \
             and R-P-P (cylindrical)",
            kinds(rows)
        )),
    }
}

impl Row {
    /// The twist in radians, recovered from its sine and cosine.
    fn alpha(&self) -> f64 {
        self.sa.atan2(self.ca)
    }
}
