//! The geometric constructions behind the closed-form solutions of Sect. 2.12, as numbers a
//! figure or an overlay can draw: the two-link arm's triangle with alpha, beta and theta2 of
//! Fig. 2.31 (Sect. 2.12.1), and the wrist point of a manipulator with spherical wrist,
//! `p_W = p_e - d6 a_e` (2.93, Fig. 2.32). Pure f64, no graphics.

pub mod steps;
pub mod textbook;

use crate::kinematics::{JointKind, KinematicsError, Robot};
use nalgebra::Vector3;
use thiserror::Error;

/// Why a construction does not exist.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum ConstructionError {
    /// The point is out of the two-link arm's reach: no triangle.
    #[error(
        "no triangle: the point is {distance:.6} m from the shoulder, the links reach \
         {inner:.6} m to {outer:.6} m"
    )]
    OutOfReach {
        /// |p| (m).
        distance: f64,
        /// |a1 - a2| (m).
        inner: f64,
        /// a1 + a2 (m).
        outer: f64,
    },
    /// The robot has no spherical wrist (its last three axes do not meet in a point).
    #[error("{robot} has no spherical wrist: {why}")]
    NoSphericalWrist {
        /// The robot's name.
        robot: String,
        /// What fails, in words.
        why: &'static str,
    },
    /// A family whose construction is not drawn yet.
    #[error("{family}: the construction of this family is not drawn yet")]
    NotDrawn {
        /// The family's name.
        family: &'static str,
    },
    /// Bad robot input.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
    /// The arm of a figure has no closed form.
    #[error("no closed form: {0}")]
    ClosedForm(#[from] crate::kinematics::ik::closed_form::NoClosedForm),
    /// The closed form refused its input.
    #[error(transparent)]
    Ik(#[from] crate::kinematics::ik::IkError),
    /// No figure of that name.
    #[error("no figure {name:?} (the figures are: {figures})")]
    NoFigure {
        /// The name asked for.
        name: String,
        /// The figures there are, separated by ", ".
        figures: String,
    },
}

/// One posture of the two-link arm's triangle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoLinkPosture {
    /// "elbow up" (theta2 in (-pi, 0)) or "elbow down" (theta2 in (0, pi)).
    pub name: &'static str,
    /// theta1 = alpha + beta (elbow up) or alpha - beta (elbow down) (rad).
    pub theta1: f64,
    /// theta2 = -acos(c2) (elbow up) or +acos(c2) (elbow down) (rad).
    pub theta2: f64,
    /// The elbow, the end of link 1 (plane coordinates, m).
    pub elbow: [f64; 2],
}

/// The cosine-theorem construction of Sect. 2.12.1 (Fig. 2.31) for a two-link arm with link
/// lengths a1, a2 and the point p (plane coordinates of the shoulder frame, m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoLinkConstruction {
    /// Link lengths (m).
    pub a1: f64,
    /// See `a1`.
    pub a2: f64,
    /// The point reached (m).
    pub p: [f64; 2],
    /// |p| (m): the side of the triangle opposite the elbow.
    pub distance: f64,
    /// c2 = (p_x^2 + p_y^2 - a1^2 - a2^2) / (2 a1 a2).
    pub c2: f64,
    /// alpha = Atan2(p_y, p_x) (rad).
    pub alpha: f64,
    /// beta = acos((p_x^2 + p_y^2 + a1^2 - a2^2) / (2 a1 |p|)), in [0, pi] (rad).
    pub beta: f64,
    /// Elbow up (theta2 < 0) and elbow down (theta2 > 0), in that order.
    pub postures: [TwoLinkPosture; 2],
}

impl TwoLinkConstruction {
    /// The construction for `p` (m), or why it does not exist.
    pub fn new(a1: f64, a2: f64, p: [f64; 2]) -> Result<Self, ConstructionError> {
        let d2 = p[0] * p[0] + p[1] * p[1];
        let distance = d2.sqrt();
        let (inner, outer) = ((a1 - a2).abs(), a1 + a2);
        let slack = 1e-12 * outer;
        if !(distance.is_finite() && distance <= outer + slack && distance >= inner - slack)
            || distance == 0.0
        {
            return Err(ConstructionError::OutOfReach {
                distance,
                inner,
                outer,
            });
        }
        let c2 = ((d2 - a1 * a1 - a2 * a2) / (2.0 * a1 * a2)).clamp(-1.0, 1.0);
        let alpha = p[1].atan2(p[0]);
        let beta = ((d2 + a1 * a1 - a2 * a2) / (2.0 * a1 * distance))
            .clamp(-1.0, 1.0)
            .acos();
        let posture = |name, theta1: f64, theta2| TwoLinkPosture {
            name,
            theta1,
            theta2,
            elbow: [a1 * theta1.cos(), a1 * theta1.sin()],
        };
        let t2 = c2.acos();
        Ok(Self {
            a1,
            a2,
            p,
            distance,
            c2,
            alpha,
            beta,
            postures: [
                posture("elbow up", alpha + beta, -t2),
                posture("elbow down", alpha - beta, t2),
            ],
        })
    }
}

/// The decoupling point of a manipulator with spherical wrist (Sect. 2.12.2, Fig. 2.32).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WristPoint {
    /// End-effector position p_e (world, m).
    pub p_e: Vector3<f64>,
    /// Approach unit vector a_e, the tool z axis (world).
    pub a_e: Vector3<f64>,
    /// d6: the distance from the wrist point to the end-effector along a_e (m).
    pub d6: f64,
    /// p_W = p_e - d6 a_e (2.93) (world, m).
    pub p_w: Vector3<f64>,
}

impl WristPoint {
    /// The wrist point of a six-joint robot at q: the meeting point W of its last three axes
    /// (read from the Jacobian), d6 = a_e . (p_e - W), and p_W by (2.93). Refused when the last
    /// three axes do not meet, or when the tool is not offset along a_e alone (then (2.93) does
    /// not give W).
    pub fn of(robot: &Robot, q: &[f64]) -> Result<Self, ConstructionError> {
        let no = |why: &'static str| ConstructionError::NoSphericalWrist {
            robot: robot.name.clone(),
            why,
        };
        if robot.dof() != 6 || (3..6).any(|k| robot.dof_joint(k).kind != JointKind::Revolute) {
            return Err(no("it needs six joints, the last three revolute"));
        }
        let t = robot.fk(q)?;
        let jac = robot.jacobian(q, 0)?;
        let p_e = t.translation.vector;
        let axis = |k: usize| {
            let c = jac.column(k);
            let w = Vector3::new(c[3], c[4], c[5]);
            (
                p_e + w.cross(&Vector3::new(c[0], c[1], c[2])),
                w.normalize(),
            )
        };
        let tol = 1e-9 * robot.characteristic_length();
        let (o4, w4) = axis(3);
        let (o5, w5) = axis(4);
        let (o6, w6) = axis(5);
        let (w_a, g_a) = meet(&o4, &w4, &o5, &w5);
        let (w_b, g_b) = meet(&o5, &w5, &o6, &w6);
        if g_a > tol || g_b > tol || (w_a - w_b).norm() > tol {
            return Err(no("its last three axes do not meet in a point"));
        }
        let a_e = t.rotation * Vector3::z();
        let d6 = a_e.dot(&(p_e - w_a));
        let p_w = p_e - a_e * d6; // (2.93)
        if (p_w - w_a).norm() > tol {
            return Err(no(
                "its tool is offset off the approach axis, so (2.93) misses W",
            ));
        }
        Ok(Self { p_e, a_e, d6, p_w })
    }
}

/// Closest point of line (a, u) to line (b, v) (points, unit directions) halfway between the
/// lines, and the gap between them (m); infinite gap for parallel lines.
pub(crate) fn meet(
    a: &Vector3<f64>,
    u: &Vector3<f64>,
    b: &Vector3<f64>,
    v: &Vector3<f64>,
) -> (Vector3<f64>, f64) {
    let w0 = a - b;
    let (uu, uv, vv) = (u.dot(u), u.dot(v), v.dot(v));
    let (du, dv) = (u.dot(&w0), v.dot(&w0));
    let den = uu * vv - uv * uv;
    if den.abs() < 1e-12 {
        return (*a, f64::INFINITY);
    }
    let s = (uv * dv - vv * du) / den;
    let t = (uu * dv - uv * du) / den;
    let pa = a + u * s;
    let pb = b + v * t;
    (0.5 * (pa + pb), (pa - pb).norm())
}
