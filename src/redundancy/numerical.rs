//! Numerical self-motion of any redundant chain that does not drift: a tangent step along the
//! Jacobian's null space, then Newton (Gauss-Newton) corrections back onto the task until the
//! hand is where it was to rounding, every step. (MoveIt's null-space sliders step along the null
//! space without the correction and drift off it, moveit/moveit#2970.)
//!
//! The tangent is the previous tangent projected on the null space, `t = (I - J^+ J) t_prev`,
//! normalised, so the direction moves continuously through turning points of any coordinate and
//! never flips; for a degree of redundancy 1 it is the null space's only direction. The
//! parameter is the arc length s in joint space (rad).

use super::RedundancyError;
use crate::kinematics::ik::numerical::{TaskMask, error, mask_rows};
use crate::kinematics::{Pose, Robot};
use nalgebra::{DVector, Matrix6, Matrix6xX, Vector6};

/// Newton corrections per step at most.
const MAX_CORRECTIONS: usize = 30;

/// A self-motion in progress (see the module documentation).
#[derive(Debug, Clone)]
pub struct NullSpaceMotion<'a> {
    robot: &'a Robot,
    ee: usize,
    target: Pose,
    q: Vec<f64>,
    tangent: DVector<f64>,
    frames: Vec<Pose>,
    jac: Matrix6xX<f64>,
    trial: Vec<f64>,
    scale: f64,
    /// The components held: the full pose, or a task of Sect. 2.10.2 in the tool frame.
    mask: TaskMask,
}

impl<'a> NullSpaceMotion<'a> {
    /// Starts at `q0` holding end-effector `ee` at its pose there; `direction` (joint space,
    /// one value per joint) is projected on the null space to choose the first tangent (default:
    /// every joint that moves the hand, equally; joints of other branches of a tree stay).
    pub fn new(
        robot: &'a Robot,
        ee: usize,
        q0: &[f64],
        direction: Option<&[f64]>,
    ) -> Result<Self, RedundancyError> {
        Self::for_task(robot, ee, q0, direction, TaskMask::FULL)
    }

    /// [`Self::new`] holding only the components of `mask` (e.g. the position and the approach
    /// axis, [`TaskMask::of_task`]): the other components move along the self-motion, whose
    /// dimension is then n - r.
    pub fn for_task(
        robot: &'a Robot,
        ee: usize,
        q0: &[f64],
        direction: Option<&[f64]>,
        mask: TaskMask,
    ) -> Result<Self, RedundancyError> {
        robot.check_q(q0)?;
        let n = robot.dof();
        let target = robot.fk_ee(q0, ee)?;
        let dir = match direction {
            Some(d) if d.len() == n => DVector::from_column_slice(d),
            Some(d) => {
                return Err(RedundancyError::DirectionLength {
                    got: d.len(),
                    joints: n,
                });
            }
            None => {
                // Every joint that moves the hand, equally; the others stay.
                let jac = robot.jacobian(q0, ee)?;
                DVector::from_iterator(
                    n,
                    jac.column_iter()
                        .map(|c| if c.norm() > 0.0 { 1.0 } else { 0.0 }),
                )
            }
        };
        let mut me = Self {
            robot,
            ee,
            target,
            q: q0.to_vec(),
            tangent: dir,
            frames: vec![Pose::identity(); robot.joints().len()],
            jac: Matrix6xX::zeros(n),
            trial: vec![0.0; n],
            scale: robot.characteristic_length(),
            mask,
        };
        if !me.update_tangent()? {
            return Err(RedundancyError::EmptyNullSpace {
                robot: robot.name.clone(),
            });
        }
        Ok(me)
    }

    /// The current joint vector (rad or m).
    pub fn q(&self) -> &[f64] {
        &self.q
    }

    /// Holds `target` from now on (world, m): the next step's corrections go onto it (the app
    /// keeps one pose across many short walks, so rounding cannot accumulate between them).
    pub fn hold(&mut self, target: Pose) {
        self.target = target;
    }

    /// The current tangent (unit, joint space).
    pub fn tangent(&self) -> &[f64] {
        self.tangent.as_slice()
    }

    /// Position (m) and orientation (rad) errors of the hand from the pose it holds, over the
    /// components the task holds.
    pub fn errors(&self) -> Result<(f64, f64), RedundancyError> {
        let e = self.error(&self.q)?;
        Ok((e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm()))
    }

    /// The held components' error (the mask's frame, the others zero).
    fn error(&self, q: &[f64]) -> Result<Vector6<f64>, RedundancyError> {
        let t = self.robot.fk_ee(q, self.ee)?;
        Ok(error(&self.target, &t, &self.mask))
    }

    /// The Jacobian at `q` in the mask's frame, the rows of free components zeroed.
    fn jacobian_at(&mut self, q: &[f64]) -> Result<(), RedundancyError> {
        self.robot
            .jacobian_into(q, self.ee, &mut self.frames, &mut self.jac)?;
        if self.mask != TaskMask::FULL {
            let t = self.robot.fk_ee(q, self.ee)?;
            mask_rows(&mut self.jac, &t, &self.mask);
        }
        Ok(())
    }

    /// `J J^T` at the current Jacobian, factored, with 1 on the diagonal of each free component
    /// (its row of J is zero: its right-hand side is too, so it solves to zero); `None` at a
    /// singularity of the task.
    fn jjt(&self) -> Option<nalgebra::Cholesky<f64, nalgebra::Const<6>>> {
        let mut m = Matrix6::zeros();
        for c in self.jac.column_iter() {
            m += c * c.transpose();
        }
        for (i, held) in self.mask.0.iter().enumerate() {
            if !held {
                m[(i, i)] = 1.0;
            }
        }
        m.cholesky()
    }

    /// Projects the tangent on the null space at the current q; false when it vanishes.
    fn update_tangent(&mut self) -> Result<bool, RedundancyError> {
        let q = std::mem::take(&mut self.q);
        let r = self.jacobian_at(&q);
        self.q = q;
        r?;
        let Some(ch) = self.jjt() else {
            return Ok(false);
        };
        let jt = &self.jac * &self.tangent;
        let y = ch.solve(&Vector6::from_column_slice(jt.as_slice()));
        let t = &self.tangent - self.jac.transpose() * y;
        let norm = t.norm();
        if norm < 1e-9 {
            return Ok(false);
        }
        self.tangent = t / norm;
        Ok(true)
    }

    /// One step of arc length `ds` (rad): along the tangent, then Newton corrections onto the
    /// task (`q += J^+ e`) until the error stops decreasing below 1e-15 of the arm's size.
    pub fn step(&mut self, ds: f64) -> Result<(), RedundancyError> {
        if !ds.is_finite() {
            return Err(RedundancyError::NonFiniteStep { step: ds });
        }
        for (t, (q, d)) in self
            .trial
            .iter_mut()
            .zip(self.q.iter().zip(self.tangent.iter()))
        {
            *t = q + ds * d;
        }
        let mut q = std::mem::take(&mut self.trial);
        let mut best = f64::INFINITY;
        let mut last: Option<DVector<f64>> = None;
        for _ in 0..MAX_CORRECTIONS {
            let e = self.error(&q)?;
            let size = e.norm();
            if size >= best {
                // The last correction did not help (rounding): undo it.
                if let Some(d) = &last {
                    for (v, x) in q.iter_mut().zip(d.iter()) {
                        *v -= x;
                    }
                }
                break;
            }
            best = size;
            if size < 1e-15 * self.scale {
                break;
            }
            self.jacobian_at(&q)?;
            let Some(ch) = self.jjt() else {
                break;
            };
            let y = ch.solve(&e);
            let dq = self.jac.transpose() * y;
            for (v, d) in q.iter_mut().zip(dq.iter()) {
                *v += d;
            }
            last = Some(dq);
        }
        self.trial = std::mem::replace(&mut self.q, q);
        if !self.update_tangent()? {
            return Err(RedundancyError::NullSpaceChanged);
        }
        Ok(())
    }
}
