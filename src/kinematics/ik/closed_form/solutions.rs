//! The labelled, allocation-free result of [`super::ClosedForm::solve_into`]: up to
//! [`MAX_SOLUTIONS`] solutions in a fixed-capacity container, each with its [`Posture`], its
//! limit flag and (when asked for) its errors checked by forward kinematics.

use super::posture::Posture;
use super::{MAX_DOF, MAX_SOLUTIONS};
use crate::kinematics::fk::Frame;
use crate::kinematics::ik::IkStatus;
use crate::kinematics::pose::Pose;
use nalgebra::{Matrix3, Vector3};

/// How much [`super::ClosedForm::solve_into`] checks of each solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Verify {
    /// Postures, 2 pi wrapping into the limits, `within_limits` and duplicate removal; no forward
    /// kinematics (`errors` is `None`). The fastest labelled call.
    Limits,
    /// As `Limits`, and every solution's pose computed by the robot's forward kinematics and
    /// compared with the target (`errors` is `Some`).
    #[default]
    Fk,
}

/// Errors of a solution checked by forward kinematics, against the whole target.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolutionErrors {
    /// |p(FK(q)) - p_target| (m).
    pub position: f64,
    /// Rotation angle of R(FK(q))^T R_target (rad); 0 for a position target.
    pub orientation: f64,
}

/// One closed-form solution.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Solution {
    q: [f64; MAX_DOF],
    dof: usize,
    /// Its posture (shoulder, elbow, wrist, ...); `Display` gives the label.
    pub posture: Posture,
    /// Whether q lies inside the joint limits (with [`super::LIMIT_TOL`] slack).
    pub within_limits: bool,
    /// The forward-kinematics check, with [`Verify::Fk`].
    pub errors: Option<SolutionErrors>,
}

impl Solution {
    /// The joint vector (rad or m), revolute angles wrapped by 2 pi into the limits where
    /// possible, otherwise into (-pi, pi].
    pub fn q(&self) -> &[f64] {
        &self.q[..self.dof]
    }

    pub(super) fn new(q: [f64; MAX_DOF], dof: usize, posture: Posture) -> Self {
        Self {
            q,
            dof,
            posture,
            within_limits: false,
            errors: None,
        }
    }
}

/// Every solution of one closed-form query, in a fixed-capacity container (no allocation).
///
/// # Examples
///
/// Iterating, indexing, and picking the solution nearest the arm's current configuration (the
/// usual choice when following a path):
///
/// ```
/// use armlab::kinematics::ik::closed_form::{ClosedForm, Solutions, Verify};
/// use armlab::kinematics::ik::{IkStatus, Target};
/// use armlab::kinematics::models::built_in;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let puma = built_in("puma560").expect("a built-in model");
/// let cf = ClosedForm::detect(&puma)?;
/// let current = [0.2, -0.7, 0.3, 0.1, 0.6, 0.4];
/// let target = Target::Pose(puma.fk(&current)?);
/// let mut solutions = Solutions::default();
/// cf.solve_into(&puma, &target, Verify::Fk, &mut solutions)?;
/// assert_eq!(solutions.status, IkStatus::Ok);
/// assert_eq!(solutions.as_slice().len(), solutions.len());
/// assert!(solutions.get(solutions.len()).is_none());
/// let distance = |q: &[f64]| -> f64 {
///     q.iter().zip(&current).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt()
/// };
/// let nearest = (&solutions)
///     .into_iter()
///     .min_by(|a, b| distance(a.q()).total_cmp(&distance(b.q())))
///     .expect("eight solutions");
/// assert!(distance(nearest.q()) < 1e-9); // the configuration we came from
/// let errors = nearest.errors.expect("Verify::Fk");
/// assert!(errors.position < 1e-12 && errors.orientation < 1e-12);
/// println!("nearest: {}", nearest.posture);
/// # Ok(())
/// # }
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Solutions {
    items: [Solution; MAX_SOLUTIONS],
    len: usize,
    /// Overall status: [`IkStatus::Ok`], [`IkStatus::Singular`] when a solution is degenerate,
    /// [`IkStatus::Unreachable`] with the distance to the workspace (then there are none).
    pub status: IkStatus,
}

impl Default for Solutions {
    fn default() -> Self {
        Self {
            items: [Solution::default(); MAX_SOLUTIONS],
            len: 0,
            status: IkStatus::Ok,
        }
    }
}

impl Solutions {
    /// Number of solutions.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The solutions, in the order of the family (shoulder right before left, elbow up before
    /// down, wrist no flip before flip).
    pub fn iter(&self) -> std::slice::Iter<'_, Solution> {
        self.items[..self.len].iter()
    }

    /// The solutions as a slice.
    pub fn as_slice(&self) -> &[Solution] {
        &self.items[..self.len]
    }

    /// Solution `i`, if there is one.
    pub fn get(&self, i: usize) -> Option<&Solution> {
        self.as_slice().get(i)
    }

    pub(super) fn clear(&mut self) {
        self.len = 0;
        self.status = IkStatus::Ok;
    }

    pub(super) fn push(&mut self, s: Solution) {
        self.items[self.len] = s;
        self.len += 1;
    }
}

impl<'a> IntoIterator for &'a Solutions {
    type Item = &'a Solution;
    type IntoIter = std::slice::Iter<'a, Solution>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

/// The rotation angle of the rotation matrix `m` (rad), from its skew part and trace through
/// atan2: accurate at small angles and near pi alike (the acos of the trace loses half the
/// digits near 0).
#[inline]
pub(super) fn rotation_angle(m: &Matrix3<f64>) -> f64 {
    let s = Vector3::new(
        m[(2, 1)] - m[(1, 2)],
        m[(0, 2)] - m[(2, 0)],
        m[(1, 0)] - m[(0, 1)],
    )
    .norm()
        * 0.5;
    let c = 0.5 * (m[(0, 0)] + m[(1, 1)] + m[(2, 2)] - 1.0);
    if s < 1e-4 && c > 0.0 {
        // asin(s) = s + s^3/6 + 3 s^5/40 + ...: the first two terms are exact to 1e-17 here, and
        // a verified solution's error is always this small (saves a libm atan2 per solution).
        s + s * s * s / 6.0
    } else {
        s.atan2(c)
    }
}

/// The target as the FK check compares it, prepared once per query: for a pose target `g` =
/// `R_target R_tool^T`, so that the orientation error of a flange frame R is the angle of
/// `R^T g` (similar to `(R R_tool)^T R_target`, so the same angle) without forming the tool frame.
pub(super) struct Check {
    tool: Pose,
    point: Vector3<f64>,
    g: Option<Matrix3<f64>>,
}

impl Check {
    /// For a pose target (orientation checked) or a point (position only), with the robot's
    /// `flange_from_tool`.
    pub(super) fn new(tool: Pose, pose: Option<&Pose>, point: Vector3<f64>) -> Self {
        let g = pose.map(|t| t.rotation.matrix() * tool.rotation.matrix().transpose());
        Self { tool, point, g }
    }

    /// The errors of the flange frame `flange` (world from flange).
    #[inline]
    pub(super) fn errors(&self, flange: &Frame) -> SolutionErrors {
        let [x, y, z] = flange.point_of(&self.tool);
        SolutionErrors {
            position: (Vector3::new(x, y, z) - self.point).norm(),
            orientation: self
                .g
                .as_ref()
                .map_or(0.0, |g| rotation_angle(&flange.rotation_to(g))),
        }
    }
}
