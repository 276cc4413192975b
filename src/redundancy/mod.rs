//! Kinematic redundancy (Sect. 2.10.2), pure computation: exact self-motion of redundant arms.
//!
//! [`PlanarSelfMotion`]: the three-link planar arm with a position-only task (n = m = 3, r = 2).
//! The free parameter is the orientation phi of the end-effector in the plane (the angle of (2.83),
//! q1 + q2 + q3 for the textbook arm): for a fixed hand position and a value of phi the closed form
//! of Sect. 2.12.1 gives two solutions (elbow down, elbow up), and the values of phi where a joint
//! meets a limit or the two branches merge are closed-form roots, so the feasible intervals of
//! each branch are exact and the self-motion curves inside the limits are counted exactly.

pub mod collision;
pub mod four_link;
mod geometry;
pub mod locked;
pub mod motion;
pub mod numerical;
pub mod offset_elbow;
pub mod report;
pub mod sampler;
pub mod srs;

use crate::kinematics::{KinematicsError, Robot};
use crate::workspace::exact::chain::PlanarChain;
use std::f64::consts::{PI, TAU};
use thiserror::Error;

/// Why a self-motion cannot be computed.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum RedundancyError {
    /// The robot is not redundant for the task: it has no self-motion.
    #[error("{robot} is not redundant for a full pose ({redundancy}): it has no self-motion")]
    NotRedundant {
        /// The robot's name.
        robot: String,
        /// n, m and r in words.
        redundancy: String,
    },
    /// The robot has none of the structures with an exact self-motion.
    #[error(
        "{robot} is neither an SRS or offset-elbow 7R arm nor a three- or four-link planar arm"
    )]
    NoExactSelfMotion {
        /// The robot's name.
        robot: String,
    },
    /// A planar arm whose exact self-motion does not exist, and why.
    #[error("{robot} has no exact {kind} planar self-motion: {why}")]
    NoPlanarSelfMotion {
        /// The robot's name.
        robot: String,
        /// "three-link" or "four-link".
        kind: &'static str,
        /// Why, in words.
        why: String,
    },
    /// The pose's wrist centre is out of the reach of an SRS arm.
    #[error("the pose's wrist centre is out of reach")]
    WristOutOfReach,
    /// No value of q7 reaches the pose (offset-elbow arm).
    #[error("the pose is out of reach for every q7")]
    OutOfReachForEveryQ7,
    /// A seven-joint arm with a locked joint: no value of it reaches the pose.
    #[error("the pose is out of reach for every value of {parameter}")]
    OutOfReachForEveryValue {
        /// The parameter, e.g. "q3 (locked)".
        parameter: &'static str,
    },
    /// A seven-joint arm with a locked joint that the pose fixes: it keeps one value along the
    /// whole self-motion (an SRS arm's elbow, q4), so it cannot be the self-motion's parameter.
    #[error(
        "{parameter} keeps one value along each branch of this self-motion ({value_deg:.3} deg \
         on one: the hand's pose fixes it, as it fixes an SRS arm's elbow), so it cannot be the \
         parameter; lock another joint, or leave the lock out"
    )]
    LockedJointFixedByPose {
        /// The parameter, e.g. "q4 (locked)".
        parameter: &'static str,
        /// Its value on one branch (deg).
        value_deg: f64,
    },
    /// The null space of the Jacobian is empty at the start of a numerical self-motion.
    #[error(
        "{robot} has no self-motion at this configuration for this task (the null space of its \
         Jacobian is empty)"
    )]
    EmptyNullSpace {
        /// The robot's name.
        robot: String,
    },
    /// The numerical self-motion reached a singularity.
    #[error(
        "the self-motion reached a singularity (the null space of the Jacobian changed dimension)"
    )]
    NullSpaceChanged,
    /// A starting direction of the wrong length.
    #[error("a direction of {got} values for {joints} joints")]
    DirectionLength {
        /// Values given.
        got: usize,
        /// Joints of the robot.
        joints: usize,
    },
    /// A step of the numerical self-motion that is not a number.
    #[error("step {step} is not finite")]
    NonFiniteStep {
        /// The step asked for (rad of joint-space arc).
        step: f64,
    },
    /// The point is not reachable at all (no branch, any phi).
    #[error("the point ({x}, {y}) is out of reach of the arm (distance {distance:.6} m)")]
    Unreachable {
        /// x (m).
        x: f64,
        /// y (m).
        y: f64,
        /// Distance to the reach of the arm's outer circle or inner hole (m).
        distance: f64,
    },
    /// The collision-free intervals need an exact self-motion (the numerical walk has no
    /// parameter to bisect on).
    #[error(
        "{robot} has no exact self-motion here (it is walked numerically): its collision-free          intervals cannot be refined"
    )]
    CellNeedsExact {
        /// The robot's name.
        robot: String,
    },
    /// The cell's obstacles could not be used with the robot.
    #[error(transparent)]
    Collision(#[from] crate::collision::CollisionError),
    /// Bad robot input.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
    /// The inverse kinematics that finds a configuration to start from failed on its input.
    #[error(transparent)]
    Ik(#[from] crate::kinematics::ik::IkError),
    /// Numerical IK did not reach the pose whose self-motion was asked for.
    #[error(
        "numerical IK did not reach the pose (error {position_error:.3e} m, {orientation_error:.3e} rad)"
    )]
    NotReached {
        /// Position error left (m).
        position_error: f64,
        /// Orientation error left (rad).
        orientation_error: f64,
    },
    /// No branch of that name.
    #[error("no branch {name:?} (the branches are: {branches})")]
    NoBranch {
        /// The name asked for.
        name: String,
        /// The branches there are, separated by "; ".
        branches: String,
    },
}

impl RedundancyError {
    /// Whether the error says the arm (or the pose) has no exact self-motion of the kind asked
    /// for, rather than that the input was bad: the numerical self-motion may still apply.
    pub fn unsupported(&self) -> bool {
        matches!(
            self,
            Self::NotRedundant { .. }
                | Self::NoExactSelfMotion { .. }
                | Self::NoPlanarSelfMotion { .. }
                | Self::WristOutOfReach
                | Self::OutOfReachForEveryQ7
                | Self::OutOfReachForEveryValue { .. }
                | Self::EmptyNullSpace { .. }
                | Self::NullSpaceChanged
                | Self::DirectionLength { .. }
                | Self::NonFiniteStep { .. }
        )
    }
}

/// One solution of the self-motion at one value of the parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchSolution {
    /// Branch name, e.g. "elbow down".
    pub name: String,
    /// Joint vector (rad).
    pub q: Vec<f64>,
    /// Every joint within its limits.
    pub within_limits: bool,
    /// |p(q) - p_target| by forward kinematics (m).
    pub position_error: f64,
    /// |phi(q) - phi| by forward kinematics (rad).
    pub orientation_error: f64,
}

/// The self-motion of the three-link planar arm holding its hand at a point.
///
/// # Examples
///
/// The arm of Problem 2.17 holding its hand at (0.6, 0.2) m: for each orientation phi in a
/// feasible interval, the elbow-down and elbow-up solutions.
///
/// ```
/// use armlab::kinematics::models::built_in;
/// use armlab::redundancy::PlanarSelfMotion;
///
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// let arm = built_in("planar3").expect("a built-in model");
/// let motion = PlanarSelfMotion::new(&arm, [0.6, 0.2])?;
/// assert_eq!(motion.parameter(), "phi");
/// let (pieces, _merges) = motion.feasible();
/// let [lo, hi] = pieces[0].first().copied().expect("elbow down is feasible");
/// let phi = 0.5 * (lo + hi);
/// for s in motion.solutions(&arm, phi) {
///     let p = arm.fk(&s.q)?.translation.vector;
///     assert!((p.x - 0.6).abs() < 1e-12 && (p.y - 0.2).abs() < 1e-12, "{}", s.name);
///     assert!(s.orientation_error < 1e-12);
/// }
/// assert!(motion.manifolds(&arm) >= 1);
/// // Out of reach (a1 + a2 + a3 = 1 m): an error.
/// assert!(PlanarSelfMotion::new(&arm, [1.5, 0.0]).is_err());
/// # Ok(())
/// # }
/// ```
#[derive(Debug, Clone)]
pub struct PlanarSelfMotion {
    chain: PlanarChain,
    frame_z: f64,
    /// Tool x-axis angle at q = 0 in the plane (rad): phi = phi0 + sum s_k q_k.
    phi0: f64,
    names: Vec<String>,
    target: [f64; 2],
    world_from_base: crate::kinematics::Pose,
}

/// Wraps an angle into [-pi, pi).
fn wrap(a: f64) -> f64 {
    (a + PI).rem_euclid(TAU) - PI
}

impl PlanarSelfMotion {
    /// The self-motion of a three-link planar arm (closed-form family) holding its end-effector
    /// at `target` (plane coordinates, m).
    pub fn new(robot: &Robot, target: [f64; 2]) -> Result<Self, RedundancyError> {
        let not = |why: String| RedundancyError::NoPlanarSelfMotion {
            robot: robot.name.clone(),
            kind: "three-link",
            why,
        };
        let (chain, frame) = PlanarChain::from_robot(robot).map_err(|e| not(e.to_string()))?;
        if chain.n != 3 {
            return Err(not(format!(
                "it has {} joints: a planar position task (r = 2) leaves no self-motion",
                chain.n
            )));
        }
        let t0 = robot.fk(&[0.0; 3])?;
        let x = frame.world_from_base.rotation.inverse() * t0.rotation * nalgebra::Vector3::x();
        let me = Self {
            names: crate::workspace::PostureClassifier::new(robot)
                .class_names()
                .to_vec(),
            phi0: x.y.atan2(x.x),
            frame_z: frame.z,
            world_from_base: frame.world_from_base,
            target,
            chain,
        };
        let d = me.reach_gap();
        if d > 1e-12 * me.chain.scale {
            return Err(RedundancyError::Unreachable {
                x: target[0],
                y: target[1],
                distance: d,
            });
        }
        Ok(me)
    }

    /// The orientation phi (rad) of configuration `q`: the tool x axis's angle in the plane.
    pub fn phi_of(&self, robot: &Robot, q: &[f64]) -> Option<f64> {
        let t = robot.fk(q).ok()?;
        let x = self.world_from_base.rotation.inverse() * t.rotation * nalgebra::Vector3::x();
        Some(x.y.atan2(x.x))
    }

    /// Distance (m) of the target outside the reach of the links, limits ignored (0 inside).
    fn reach_gap(&self) -> f64 {
        let l = self.chain.len;
        let d = (self.target[0] - self.chain.c1[0]).hypot(self.target[1] - self.chain.c1[1]);
        let outer = l[0] + l[1] + l[2];
        let inner = (2.0 * l.iter().copied().fold(0.0, f64::max) - outer).max(0.0);
        (d - outer).max(inner - d).max(0.0)
    }

    /// Name of the parameter: "phi".
    pub fn parameter(&self) -> &'static str {
        "phi"
    }

    /// Branch names (elbow down, elbow up) in branch order.
    pub fn branch_names(&self) -> [String; 2] {
        [0, 1].map(|b| {
            self.names
                .get(self.chain.branch_class[b] as usize)
                .cloned()
                .unwrap_or_else(|| format!("branch {b}"))
        })
    }

    /// The last link's absolute angle for end-effector orientation `phi` (rad).
    fn alpha3(&self, phi: f64) -> f64 {
        phi - self.phi0 + self.chain.beta[2]
    }

    /// Both branches at orientation `phi` (rad), each FK-checked; a branch is missing where the
    /// wrist point is out of the two-link reach.
    pub fn solutions(&self, robot: &Robot, phi: f64) -> Vec<BranchSolution> {
        let names = self.branch_names();
        let a3 = self.alpha3(phi);
        (0..2)
            .filter_map(|b| {
                let (q, within) = self.chain.solve_unlimited(self.target, a3, b)?;
                let (pe, oe) = self.errors(robot, &q, phi);
                Some(BranchSolution {
                    name: names[b].clone(),
                    q: q.to_vec(),
                    within_limits: within,
                    position_error: pe,
                    orientation_error: oe,
                })
            })
            .collect()
    }

    fn errors(&self, robot: &Robot, q: &[f64; 3], phi: f64) -> (f64, f64) {
        let Ok(t) = robot.fk(q) else {
            return (f64::INFINITY, f64::INFINITY);
        };
        let want = self.world_from_base
            * nalgebra::Point3::new(self.target[0], self.target[1], self.frame_z);
        let pe = (t.translation.vector - want.coords).norm();
        let x = self.world_from_base.rotation.inverse() * t.rotation * nalgebra::Vector3::x();
        (pe, wrap(x.y.atan2(x.x) - phi).abs())
    }

    /// The feasible intervals of phi (rad) of each branch inside the joint limits, as pieces of
    /// [-pi, pi] (an interval across +-pi given as two), and the values of phi where the two
    /// branches merge (the wrist point on the two-link arm's outer or inner circle).
    pub fn feasible(&self) -> ([Vec<[f64; 2]>; 2], Vec<f64>) {
        let mut bp = [0.0; 16];
        let n = self.chain.breakpoints(self.target, &mut bp);
        let mut cuts: Vec<f64> = bp[..n].to_vec();
        cuts.push(0.0);
        cuts.sort_by(f64::total_cmp);
        cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-15);
        let mut pieces: [Vec<[f64; 2]>; 2] = [Vec::new(), Vec::new()];
        for i in 0..cuts.len() {
            let (lo, hi) = (cuts[i], if i + 1 < cuts.len() { cuts[i + 1] } else { TAU });
            if hi - lo <= 0.0 {
                continue;
            }
            for (b, list) in pieces.iter_mut().enumerate() {
                if self.chain.feasible(self.target, 0.5 * (lo + hi), b) {
                    match list.last_mut() {
                        Some(l) if (l[1] - lo).abs() < 1e-15 => l[1] = hi,
                        _ => list.push([lo, hi]),
                    }
                }
            }
        }
        let merges: Vec<f64> = self.chain.merge_angles(self.target);
        let to_phi = |a: f64| a + self.phi0 - self.chain.beta[2];
        let pieces = pieces.map(|list| split_at_pi(&circular_merge(list), to_phi));
        (
            pieces,
            merges.into_iter().map(|a| wrap(to_phi(a))).collect(),
        )
    }

    /// The number of disjoint self-motion curves inside the limits: the feasible intervals of
    /// both branches, joined where the branches merge (one or two without limits, Lenarcic).
    pub fn manifolds(&self, robot: &Robot) -> usize {
        let (pieces, merges) = self.feasible();
        let same = |a: usize, b: usize, phi: f64| {
            let s = self.solutions(robot, phi);
            let names = self.branch_names();
            let q = |k: usize| s.iter().find(|x| x.name == names[k]).map(|x| x.q.clone());
            match (q(a), q(b)) {
                (Some(x), Some(y)) => x.iter().zip(&y).all(|(u, v)| {
                    let d = (u - v).rem_euclid(TAU);
                    d.min(TAU - d) < 1e-6
                }),
                _ => false,
            }
        };
        count_manifolds(&pieces, &merges, &same)
    }
}

/// A branch's joint vector `q` checked by forward kinematics against `target`: position error
/// (m), rotation angle of `R^T R_target` (rad), and the limits.
pub(crate) fn checked(
    robot: &Robot,
    target: &crate::kinematics::Pose,
    name: String,
    q: &[f64],
    limits: &[[f64; 2]],
) -> BranchSolution {
    let (pe, oe) = match robot.fk(q) {
        Ok(t) => (
            (t.translation.vector - target.translation.vector).norm(),
            crate::kinematics::orientation::angle_axis_from_rotation(
                &(t.rotation.inverse() * target.rotation),
            )
            .angle,
        ),
        Err(_) => (f64::INFINITY, f64::INFINITY),
    };
    BranchSolution {
        name,
        q: q.to_vec(),
        within_limits: geometry::within(q, limits),
        position_error: pe,
        orientation_error: oe,
    }
}

/// Whether two joint vectors are the same configuration (each angle equal modulo 2 pi, 1e-6).
pub(crate) fn same_angles(a: &[f64], b: &[f64]) -> bool {
    a.iter().zip(b).all(|(u, v)| {
        let d = (u - v).rem_euclid(TAU);
        d.min(TAU - d) < 1e-6
    })
}

/// Connected self-motion curves: the feasible intervals of every branch (pieces of [-pi, pi],
/// joined across +-pi), two intervals of different branches joined at a candidate point both
/// contain where `same(a, b, psi)` says the branches' solutions coincide.
pub(crate) fn count_manifolds(
    pieces: &[Vec<[f64; 2]>],
    points: &[f64],
    same: &dyn Fn(usize, usize, f64) -> bool,
) -> usize {
    let circ: Vec<(usize, [f64; 2])> = pieces
        .iter()
        .enumerate()
        .flat_map(|(b, p)| join_across_pi(p).into_iter().map(move |i| (b, i)))
        .collect();
    let mut parent: Vec<usize> = (0..circ.len()).collect();
    fn find(p: &mut [usize], i: usize) -> usize {
        let mut i = i;
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    let on = |iv: [f64; 2], a: f64| {
        let t = (a - iv[0]).rem_euclid(TAU);
        t <= (iv[1] - iv[0]) + 1e-9 || t >= TAU - 1e-9
    };
    for &m in points {
        let at: Vec<usize> = (0..circ.len()).filter(|&k| on(circ[k].1, m)).collect();
        for (x, &i) in at.iter().enumerate() {
            for &j in &at[x + 1..] {
                if circ[i].0 != circ[j].0 && same(circ[i].0, circ[j].0, m) {
                    let (a, b) = (find(&mut parent, i), find(&mut parent, j));
                    parent[a] = b;
                }
            }
        }
    }
    (0..circ.len())
        .filter(|&k| find(&mut parent, k) == k)
        .count()
}

/// Merges the last and first intervals of a list on [0, 2 pi) when they meet across 0.
fn circular_merge(mut list: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    if list.len() >= 2 {
        let (first, last) = (list[0], list[list.len() - 1]);
        if first[0] <= 1e-15 && (last[1] - TAU).abs() <= 1e-15 {
            list.pop();
            list[0] = [last[0] - TAU, first[1]];
        }
    }
    list
}

/// Maps intervals of the last link's angle to intervals of phi in [-pi, pi], splitting at +-pi.
fn split_at_pi(list: &[[f64; 2]], to_phi: impl Fn(f64) -> f64) -> Vec<[f64; 2]> {
    let mut out = Vec::new();
    for iv in list {
        let width = iv[1] - iv[0];
        if width >= TAU - 1e-12 {
            out.push([-PI, PI]);
            continue;
        }
        let lo = wrap(to_phi(iv[0]));
        let hi = lo + width;
        if hi <= PI {
            out.push([lo, hi]);
        } else {
            out.push([lo, PI]);
            out.push([-PI, hi - TAU]);
        }
    }
    out.sort_by(|a, b| a[0].total_cmp(&b[0]));
    out
}

/// Joins intervals that touch at +-pi back into one (for counting on the circle).
pub(crate) fn join_across_pi(list: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut v = list.to_vec();
    if v.len() >= 2 {
        let (first, last) = (v[0], v[v.len() - 1]);
        if (first[0] + PI).abs() < 1e-12 && (last[1] - PI).abs() < 1e-12 {
            v.pop();
            v[0] = [last[0] - TAU, first[1]];
        }
    }
    v
}
