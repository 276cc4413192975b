//! A seven-revolute arm with one joint locked: the six-revolute arm left is solved by the
//! closed form of its family where it has one (an SRS arm locked at q3 or q5 leaves a
//! spherical wrist: Pieper's case), else by the general elimination ([`super::general6`]), so
//! every value of the locked joint gives every solution, exactly (as ssik reduces a 7R arm to
//! 6R). The elimination alone missed three quarters of an SRS arm's solutions at q3: its
//! resultant degenerates on such special geometry. The locked joint is merged into its
//! neighbour: `A_(k-1) A_k = Rz(theta_(k-1)) [L_(k-1) Rz(theta_k) L_k]`; locking the first or
//! the last joint moves it into the base or the tool.

use super::chain;
use super::family::Family;
use super::general6::{General6, Link, MAX_BRANCHES};
use crate::kinematics::dh_derive::derive_dh;
use crate::kinematics::hold::{Held, hold_joints};
use crate::kinematics::ik::{IkError, Target};
use crate::kinematics::{Convention, Pose, Robot};
use nalgebra::{Matrix6, Vector6};

/// A solution on the exact robot meets the pose to this (m and rad).
pub const EXACT_CHECK: f64 = 1e-12;

/// Most solutions for one value of the locked joint.
pub const MAX_LOCKED_SOLUTIONS: usize = MAX_BRANCHES;

/// A serial arm of seven revolute joints with joint `locked` held at a given value.
///
/// # Examples
///
/// The Franka Emika Panda with q3 locked: every configuration that puts the tool at a pose with
/// q3 at the value given, the one the pose came from among them.
///
/// ```
/// use armlab::kinematics::ik::closed_form::{LockedArm, MAX_LOCKED_SOLUTIONS};
/// use armlab::kinematics::models::built_in;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let panda = built_in("panda").expect("a built-in model");
/// let q0 = [0.3, -0.4, 0.2, -2.0, 0.1, 1.6, 0.5];
/// let pose = panda.fk(&q0)?;
/// let arm = LockedArm::new(&panda, 2).expect("seven revolute joints");
/// let mut out = [[0.0; 7]; MAX_LOCKED_SOLUTIONS];
/// let n = arm.solve_exact(&panda, &pose, q0[2], &mut out)?;
/// assert!(n >= 1);
/// for q in &out[..n] {
///     assert_eq!(q[2], q0[2]);
///     let gap = (panda.fk(q)?.to_homogeneous() - pose.to_homogeneous()).amax();
///     assert!(gap < 1e-11);
/// }
/// let found = out[..n].iter().any(|q| q.iter().zip(&q0).all(|(a, b)| {
///     armlab::kinematics::orientation::wrap_angle(a - b).abs() < 1e-8
/// }));
/// assert!(found);
/// # Ok(())
/// # }
/// ```
#[derive(Debug, Clone)]
pub struct LockedArm {
    links: [Link; 7],
    offsets: [f64; 7],
    base_inv: Pose,
    tool_inv: Pose,
    locked: usize,
    /// The order of the elimination's loop solved first (see [`General6::starting_at`]).
    first: usize,
    /// Whether the six-joint arm left belongs to a family with its own closed form (found at
    /// two generic values of the locked joint), which then solves every value.
    by_family: bool,
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
        let mut arm = Self {
            links: std::array::from_fn(|i| Link::dh(rows[i].a, rows[i].d, rows[i].sa, rows[i].ca)),
            offsets: std::array::from_fn(|i| rows[i].offset),
            base_inv: chain.base.inverse(),
            tool_inv: chain.tool.inverse(),
            locked,
            first: 0,
            by_family: false,
        };
        // The first sound order at a generic value and pose (angles well away from 0 and from
        // each other: an arm stretched out is singular).
        const THETA: [f64; 6] = [0.61, -1.13, 0.87, 1.42, -0.53, 0.97];
        let six = arm.six_links(0.74);
        let goal = six
            .iter()
            .zip(THETA)
            .fold(Link::rz(1.0, 0.0), |acc, (l, t)| {
                acc.then(&Link::rz(t.cos(), t.sin()).then(l))
            });
        arm.first = General6::from_links(six).sound_order(&goal).unwrap_or(0);
        arm.by_family = [0.61, -1.07]
            .iter()
            .all(|&v| arm.family_of(robot, v).is_some());
        Some(arm)
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
        let (six, goal6) = self.six_at(world_from_tool, value);
        let k = self.locked;
        let mut sols = [[0.0; 6]; MAX_BRANCHES];
        let n = General6::from_links(six)
            .starting_at(self.first)
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

    /// The six-joint arm left with the locked joint at `value` (rad): its links and the goal
    /// `A1 ... A6 = goal` of its frame 6 in its frame 0.
    pub(crate) fn six_at(&self, world_from_tool: &Pose, value: f64) -> ([Link; 6], Link) {
        let g = self.base_inv * world_from_tool * self.tool_inv;
        let goal = Link {
            r: *g.rotation.matrix(),
            t: g.translation.vector,
        };
        let ak = self.locked_link(value);
        let goal6 = match self.locked {
            0 => ak.inverse().then(&goal),
            6 => goal.then(&ak.inverse()),
            _ => goal,
        };
        (self.six_links(value), goal6)
    }

    /// The locked joint's link `Rz(theta) L` at `value` (rad).
    fn locked_link(&self, value: f64) -> Link {
        let k = self.locked;
        let (s, c) = (value + self.offsets[k]).sin_cos();
        Link::rz(c, s).then(&self.links[k])
    }

    /// The six links left with the locked joint at `value` (rad): the locked joint merged into
    /// the link before it, `L_(k-1) Rz(theta_k) L_k`; locked first or last, it moves into the
    /// goal instead.
    fn six_links(&self, value: f64) -> [Link; 6] {
        let k = self.locked;
        let ak = self.locked_link(value);
        let mut six = [self.links[0]; 6];
        for (j, (i, l)) in self
            .links
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != k)
            .enumerate()
        {
            six[j] = if k > 0 && k < 6 && i + 1 == k {
                l.then(&ak)
            } else {
                *l
            };
        }
        six
    }

    /// The six-joint arm left at `value` (rad) as a robot of its own, with its closed form,
    /// where that is a family's and not the general elimination.
    ///
    /// The held joint is a fixed row between moving ones, which no family reads: the six-joint
    /// arm is read through its derived DH table (same FK, same q), as a URDF arm is.
    fn family_of(&self, robot: &Robot, value: f64) -> Option<(Held, Robot, super::ClosedForm)> {
        let mut q = [0.0; 7];
        q[self.locked] = value;
        let mut held = [false; 7];
        held[self.locked] = true;
        let six = hold_joints(robot, &q, &held)?;
        let dh = derive_dh(&six.robot, 0, Convention::Standard)
            .ok()?
            .robot(&robot.name)
            .ok()?;
        let cf = super::ClosedForm::detect(&dh).ok()?;
        (!matches!(cf.family(), Family::General6)).then_some((six, dh, cf))
    }

    /// Every solution at `value` by the six-joint arm's family closed form (all its postures,
    /// within the limits or not); `None` where there is none (then the elimination solves).
    fn solve_by_family(
        &self,
        robot: &Robot,
        world_from_tool: &Pose,
        value: f64,
        out: &mut [[f64; 7]; MAX_LOCKED_SOLUTIONS],
    ) -> Option<usize> {
        if !self.by_family {
            return None;
        }
        let (six, dh, cf) = self.family_of(robot, value)?;
        let result = cf.solve(&dh, &Target::Pose(*world_from_tool)).ok()?;
        let mut n = 0;
        for (o, s) in out.iter_mut().zip(&result.solutions) {
            *o = [0.0; 7];
            o[self.locked] = value;
            six.expand(&s.q, o);
            n += 1;
        }
        Some(n)
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
        let n = match self.solve_by_family(robot, world_from_tool, value, out) {
            Some(n) => n,
            None => self.solve(world_from_tool, value, out)?,
        };
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
