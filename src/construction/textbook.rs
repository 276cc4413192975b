//! What each of the excerpt's figures shows, computed (`armlab figure NAME`): the arm, its
//! configuration and the solutions or constructions drawn. The figures themselves only paint
//! these ([`crate::figure::textbook`]); the workspace ones are workspace figures of the arm named
//! here.

use super::{ConstructionError, TwoLinkConstruction, WristPoint};
use crate::kinematics::Robot;
use crate::kinematics::ik::closed_form::{ClosedForm, RawSolutions};
use crate::kinematics::models;
use nalgebra::Vector3;

/// Every figure: name and what it shows.
pub const FIGURES: [(&str, &str); 6] = [
    (
        "2.29",
        "joint-space rectangle of the two-link arm with limits, segments ab, bc, cd, da, ae, ef, fd",
    ),
    (
        "2.30",
        "workspace of the two-link arm with points A-H, its arcs and the elbow-up / elbow-down / both regions",
    ),
    (
        "2.31",
        "the two admissible postures of the two-link arm for one point, with alpha, beta and theta2",
    ),
    (
        "2.32",
        "a manipulator with spherical wrist: p_e, a_e, d6 and p_W = p_e - d6 a_e (2.93)",
    ),
    (
        "2.33",
        "the four configurations of the anthropomorphic arm compatible with one wrist position",
    ),
    (
        "problem-2.17",
        "workspace of the three-link arm with the problem's data",
    ),
];

/// The point of Fig. 2.31 (m): reached by both postures of the two-link arm.
pub const FIG_2_31_POINT: [f64; 2] = [1.2, 0.8];
/// The configuration of Fig. 2.32 (rad).
pub const FIG_2_32_Q: [f64; 6] = [0.3, 0.5, 0.6, 0.4, 0.9, 0.2];
/// The configuration whose wrist position Fig. 2.33 solves for (rad).
pub const FIG_2_33_Q: [f64; 3] = [0.5, 0.8, -1.0];

/// A workspace figure's view, as the excerpt draws it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WorkspaceView {
    /// The joint-space rectangle (Fig. 2.29).
    JointSpace,
    /// The arm's plane (Fig. 2.30, Problem 2.17).
    Plane,
}

/// What a figure of the excerpt is drawn from.
#[derive(Debug, Clone)]
pub enum Subject {
    /// A workspace figure of `robot`.
    Workspace {
        /// The arm.
        robot: Robot,
        /// Its name in the figure's title.
        title: &'static str,
        /// The view.
        view: WorkspaceView,
    },
    /// Fig. 2.31: both postures of the two-link arm (a1 = a2 = 1 m) for one point.
    TwoLinkPostures(TwoLinkConstruction),
    /// Fig. 2.32: the anthropomorphic arm with spherical wrist at `q`, and its wrist point.
    SphericalWrist {
        /// The arm.
        robot: Robot,
        /// Its configuration (rad).
        q: [f64; 6],
        /// p_e, a_e, d6 and p_W (2.93).
        wrist: WristPoint,
    },
    /// Fig. 2.33: the anthropomorphic arm's solutions for one wrist position.
    FourConfigurations {
        /// The arm.
        robot: Robot,
        /// The wrist position solved for (world, m).
        p: Vector3<f64>,
        /// Each solution's posture label and joint vector (rad), in the excerpt's order:
        /// shoulder-right/elbow-up, shoulder-left/elbow-up, shoulder-right/elbow-down,
        /// shoulder-left/elbow-down.
        solutions: Vec<(String, [f64; 3], usize)>,
    },
}

impl Subject {
    /// The caption naming the figure's source, e.g. "Fig. 2.30".
    pub fn source(name: &str) -> &'static str {
        match name {
            "2.29" => "Fig. 2.29",
            "2.30" => "Fig. 2.30",
            "2.31" => "Fig. 2.31",
            "2.32" => "Fig. 2.32",
            "2.33" => "Fig. 2.33",
            _ => "Problem 2.17",
        }
    }
}

/// What figure `name` ([`FIGURES`]) shows: its arm, and the solutions or constructions it draws.
pub fn subject(name: &str) -> Result<Subject, ConstructionError> {
    Ok(match name {
        "2.29" | "2.30" => Subject::Workspace {
            robot: models::planar2_fig2_30(),
            title: "two-link arm",
            view: if name == "2.29" {
                WorkspaceView::JointSpace
            } else {
                WorkspaceView::Plane
            },
        },
        "problem-2.17" => Subject::Workspace {
            robot: models::planar3(),
            title: "three-link arm of Problem 2.17",
            view: WorkspaceView::Plane,
        },
        "2.31" => Subject::TwoLinkPostures(TwoLinkConstruction::new(1.0, 1.0, FIG_2_31_POINT)?),
        "2.32" => {
            let robot = models::anthropomorphic_spherical_wrist();
            let wrist = WristPoint::of(&robot, &FIG_2_32_Q)?;
            Subject::SphericalWrist {
                robot,
                q: FIG_2_32_Q,
                wrist,
            }
        }
        "2.33" => four_configurations()?,
        other => {
            return Err(ConstructionError::NoFigure {
                name: other.to_string(),
                figures: FIGURES.map(|f| f.0).join(", "),
            });
        }
    })
}

/// Fig. 2.33: every closed-form solution of the anthropomorphic arm for the wrist position of
/// [`FIG_2_33_Q`], with its index among the solutions (its posture colour).
fn four_configurations() -> Result<Subject, ConstructionError> {
    let robot = models::anthropomorphic3r();
    let cf = ClosedForm::detect(&robot)?;
    let p = robot.fk(&FIG_2_33_Q)?.translation.vector;
    let mut raw = RawSolutions::default();
    let n = cf.solve_position_raw(&p, &mut raw)?;
    let order = [
        "right, elbow up",
        "left, elbow up",
        "right, elbow down",
        "left, elbow down",
    ];
    let mut ks: Vec<usize> = (0..n.min(4)).collect();
    ks.sort_by_key(|&k| {
        let label = raw.postures[k].label();
        order.iter().position(|o| label.ends_with(o)).unwrap_or(4)
    });
    let solutions = ks
        .into_iter()
        .map(|k| {
            let q = &raw.q[k];
            (raw.postures[k].label(), [q[0], q[1], q[2]], k)
        })
        .collect();
    Ok(Subject::FourConfigurations {
        robot,
        p,
        solutions,
    })
}
