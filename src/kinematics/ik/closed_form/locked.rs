//! A seven-revolute arm with one joint locked: the six-revolute arm left is solved by the
//! general elimination ([`super::general6`]), so every value of the locked joint gives every
//! solution, exactly (as ssik reduces a 7R arm to 6R). The locked joint is merged into its
//! neighbour: `A_(k-1) A_k = Rz(theta_(k-1)) [L_(k-1) Rz(theta_k) L_k]`; locking the first or
//! the last joint moves it into the base or the tool.

use super::chain;
use super::general6::{General6, Link, MAX_BRANCHES};
use crate::kinematics::ik::IkError;
use crate::kinematics::{Pose, Robot};
use nalgebra::{Matrix6, Vector6};

/// A solution on the exact robot meets the pose to this (m and rad).
pub const EXACT_CHECK: f64 = 1e-12;

/// Most solutions for one value of the locked joint.
pub const MAX_LOCKED_SOLUTIONS: usize = MAX_BRANCHES;

/// A serial arm of seven revolute joints with joint `locked` held at a given value.
#[derive(Debug, Clone)]
pub struct LockedArm {
    links: [Link; 7],
    offsets: [f64; 7],
    base_inv: Pose,
    tool_inv: Pose,
    locked: usize,
}

impl LockedArm {
    /// The arm of `robot` (a serial chain of seven revolute joints, with a DH table or one
    /// derived from its axes) with joint `locked` (0-based) locked; `None` otherwise.
    pub fn new(robot: &Robot, locked: usize) -> Option<Self> {
        if locked >= 7 || robot.end_effectors().len() != 1 {
            return None;
        }
        let chain = chain::normalize(robot)?;
        let rows = &chain.rows;
        if rows.len() != 7 || rows.iter().any(|r| !r.revolute) {
            return None;
        }
        Some(Self {
            links: std::array::from_fn(|i| Link::dh(rows[i].a, rows[i].d, rows[i].sa, rows[i].ca)),
            offsets: std::array::from_fn(|i| rows[i].offset),
            base_inv: chain.base.inverse(),
            tool_inv: chain.tool.inverse(),
            locked,
        })
    }

    /// The locked joint (0-based).
    pub fn locked(&self) -> usize {
        self.locked
    }

    /// Every solution for the tool pose `world_from_tool` with the locked joint at `value`
    /// (rad): joint vectors (rad, not wrapped into the limits; `q[locked] = value`), at most
    /// [`MAX_LOCKED_SOLUTIONS`], each Newton-polished and checked by forward kinematics of the
    /// six-joint arm to 1e-12; the count. A special six-joint arm the elimination cannot solve is
    /// [`IkError::Degenerate`].
    pub fn solve(
        &self,
        world_from_tool: &Pose,
        value: f64,
        out: &mut [[f64; 7]; MAX_LOCKED_SOLUTIONS],
    ) -> Result<usize, IkError> {
        let g = self.base_inv * world_from_tool * self.tool_inv;
        let goal = Link {
            r: *g.rotation.matrix(),
            t: g.translation.vector,
        };
        let k = self.locked;
        let (s, c) = (value + self.offsets[k]).sin_cos();
        let ak = Link::rz(c, s).then(&self.links[k]);
        let mut six = [self.links[0]; 6];
        let goal6 = match k {
            0 => {
                six.copy_from_slice(&self.links[1..]);
                ak.inverse().then(&goal)
            }
            6 => {
                six.copy_from_slice(&self.links[..6]);
                goal.then(&ak.inverse())
            }
            _ => {
                let mut j = 0;
                for (i, l) in self.links.iter().enumerate() {
                    if i == k {
                        continue;
                    }
                    six[j] = if i == k - 1 { l.then(&ak) } else { *l };
                    j += 1;
                }
                goal
            }
        };
        let mut sols = [[0.0; 6]; MAX_BRANCHES];
        let n = General6::from_links(six)
            .solve_goal(&goal6, &mut sols)
            .map_err(|why| IkError::Degenerate { reason: why.text() })?;
        for (o, th) in out.iter_mut().zip(&sols[..n]) {
            o[k] = value;
            for (j, t) in th.iter().enumerate() {
                let i = if j < k { j } else { j + 1 };
                o[i] = t - self.offsets[i];
            }
        }
        Ok(n)
    }

    /// [`Self::solve`], then each solution checked by `robot`'s own forward kinematics and
    /// polished by Newton's method over the six free joints where it misses by more than
    /// [`EXACT_CHECK`] (a chain read from a URDF is solved on its derived DH table, exact only to
    /// 1e-9 rad; the robot's joints are the truth); a solution that stays off is dropped.
    pub fn solve_exact(
        &self,
        robot: &Robot,
        world_from_tool: &Pose,
        value: f64,
        out: &mut [[f64; 7]; MAX_LOCKED_SOLUTIONS],
    ) -> Result<usize, IkError> {
        let n = self.solve(world_from_tool, value, out)?;
        let mut kept = 0;
        for i in 0..n {
            let mut q = out[i];
            if self.polish(robot, world_from_tool, &mut q) {
                out[kept] = q;
                kept += 1;
            }
        }
        Ok(kept)
    }

    /// `guess` with the locked joint set to `value`, polished by Newton on `robot` over the free
    /// joints (continuation along a self-motion); `None` if it does not meet `t` to
    /// [`EXACT_CHECK`].
    pub fn continue_at(
        &self,
        robot: &Robot,
        t: &Pose,
        guess: &[f64; 7],
        value: f64,
    ) -> Option<[f64; 7]> {
        let mut q = *guess;
        q[self.locked] = value;
        self.polish(robot, t, &mut q).then_some(q)
    }

    /// Newton on the free joints until `robot`'s forward kinematics meets `t` to
    /// [`EXACT_CHECK`]; whether it does.
    fn polish(&self, robot: &Robot, t: &Pose, q: &mut [f64; 7]) -> bool {
        for _ in 0..6 {
            let Ok(p) = robot.fk(q) else {
                return false;
            };
            let dp = t.translation.vector - p.translation.vector;
            // The rotation error as sin(angle) times the axis, from the skew part of the
            // rotation: `scaled_axis` goes through acos and cannot see below 3e-8 rad.
            let d = (t.rotation * p.rotation.inverse()).into_inner();
            let dr = nalgebra::Vector3::new(
                d[(2, 1)] - d[(1, 2)],
                d[(0, 2)] - d[(2, 0)],
                d[(1, 0)] - d[(0, 1)],
            ) * 0.5;
            // The skew part also vanishes at a half turn: the trace tells that apart.
            if dp.norm() <= EXACT_CHECK && dr.norm() <= EXACT_CHECK && d.trace() > 2.0 {
                return true;
            }
            let Ok(jac) = robot.jacobian(q, 0) else {
                return false;
            };
            let mut j = Matrix6::zeros();
            for (c, i) in (0..7).filter(|&i| i != self.locked).enumerate() {
                j.set_column(c, &jac.column(i));
            }
            let e = Vector6::new(dp.x, dp.y, dp.z, dr.x, dr.y, dr.z);
            let Some(step) = j.lu().solve(&e) else {
                return false;
            };
            for (c, i) in (0..7).filter(|&i| i != self.locked).enumerate() {
                q[i] += step[c];
            }
        }
        false
    }
}
