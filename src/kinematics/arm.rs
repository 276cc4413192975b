//! The arm of one end-effector in a tree: the chain of joints from the root to it, as a serial
//! robot of its own. Fingers, a head or the other arm hang off that chain and do not count for
//! anything done to this arm (its DH table, closed form, n/m/r, self-motion, workspace,
//! calibration). A joint of the chain that mimics a joint off it follows that joint's value,
//! frozen at the given q.

use super::hold::hold_joints;
use super::robot::{Drive, EndEffector, Joint, JointId, NamedConfig, PointMass, Robot};
use super::{KinematicsError, ModelError};
use thiserror::Error;

/// Why an end-effector has no arm of its own.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ArmError {
    /// Nothing moves between the root and the end-effector (a frame fixed to the base).
    #[error("no moving joint between the root and \"{ee}\" (a frame fixed to the base)")]
    NoMovingJoint {
        /// The end-effector's name.
        ee: String,
    },
    /// A joint of the chain is closed or coupled through a joint off it.
    #[error(
        "joint \"{joint}\" of the chain to \"{ee}\" is coupled or closed through a joint off it"
    )]
    CoupledOffChain {
        /// The joint's name.
        joint: String,
        /// The end-effector's name.
        ee: String,
    },
    /// Bad input (end-effector index, q).
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
    /// The chain did not make a valid robot.
    #[error(transparent)]
    Model(#[from] ModelError),
}

/// One end-effector's arm as a serial robot, and how its q maps back to the whole robot's.
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct Arm {
    /// The chain from the root to the end-effector, alone: one end-effector (index 0), the
    /// whole robot's base, joint names and limits; the whole robot's named configurations
    /// restricted to the chain.
    pub robot: Robot,
    /// `free[i]` is the whole robot's q index of the arm's `q[i]`.
    pub free: Vec<usize>,
    /// The end-effector's index in the whole robot.
    pub ee: usize,
    /// The moving joints of the chain (mimic joints included), names root to tip.
    pub chain: Vec<String>,
}

impl Arm {
    /// The whole robot's q: `full` (the values of the joints off the chain) with the chain's
    /// entries set from the arm's `q`.
    pub fn expand(&self, q: &[f64], full: &mut [f64]) {
        for (&k, &v) in self.free.iter().zip(q) {
            full[k] = v;
        }
    }

    /// The arm's q read from the whole robot's `full`.
    pub fn restrict(&self, full: &[f64]) -> Vec<f64> {
        self.free.iter().map(|&k| full[k]).collect()
    }

    /// Whether the arm is the whole robot (a serial chain with one end-effector).
    pub fn is_whole(&self, whole: &Robot) -> bool {
        self.robot.joints().len() == whole.joints().len() && whole.end_effectors().len() == 1
    }

    /// The names of the chain's moving joints, root to tip (actuated and coupled).
    pub fn chain_names(&self) -> Vec<String> {
        self.chain.clone()
    }
}

/// End-effector `ee`'s arm at the whole robot's `q` (which matters only for chain joints that
/// follow a joint off the chain). An error when `ee` does not exist, `q` is wrong, or the chain
/// is closed through a joint off it.
pub fn arm_of(robot: &Robot, ee: usize, q: &[f64]) -> Result<Arm, ArmError> {
    robot.check_q(q)?;
    let e = robot.end_effector(ee)?.clone();
    let chain = robot.chain_to(e.parent).to_vec();
    let keep = kept_joints(robot, &chain);
    let held: Vec<bool> = robot.actuated_joints().iter().map(|&j| !keep[j]).collect();
    let (base_robot, free) = match hold_joints(robot, q, &held) {
        Some(h) => (h.robot, h.free),
        None => (robot.clone(), (0..robot.dof()).collect()),
    };
    let kept: Vec<JointId> = (0..keep.len()).filter(|&j| keep[j]).collect();
    let out = prune(&base_robot, &kept, &e.name)?;
    if !out.iter().any(|j| matches!(j.drive, Drive::Actuated(_))) {
        return Err(ArmError::NoMovingJoint { ee: e.name });
    }
    let chain_names = chain
        .iter()
        .filter(|&&j| !matches!(base_robot.joints()[j].drive, Drive::None))
        .map(|&j| robot.joints()[j].name.clone())
        .collect();
    let ees = vec![EndEffector {
        name: e.name.clone(),
        parent: kept
            .iter()
            .position(|&c| c == e.parent)
            .unwrap_or(kept.len() - 1),
        tool: e.tool,
    }];
    let mut arm = Robot::new(robot.name.clone(), robot.base, out, ees)?;
    arm.description = format!(
        "The arm of end-effector \"{}\" of {}: the chain from the root to it.",
        e.name, robot.name
    );
    arm.masses = carried_masses(robot, &kept, q)?;
    arm.configurations = robot
        .configurations
        .iter()
        .map(|c| NamedConfig {
            name: c.name.clone(),
            q: free.iter().map(|&k| c.q[k]).collect(),
        })
        .collect();
    Ok(Arm {
        robot: arm,
        free,
        ee,
        chain: chain_names,
    })
}

/// The whole robot's masses as the arm carries them: each on its joint's nearest kept ancestor
/// (a gripper's links ride on the last link; at the whole robot's `q`), renumbered; masses on
/// the base stay there.
fn carried_masses(robot: &Robot, kept: &[JointId], q: &[f64]) -> Result<Vec<PointMass>, ArmError> {
    let frames = robot.fk_frames(q)?;
    let mut out = Vec::with_capacity(robot.masses.len());
    for m in &robot.masses {
        let Some(on) = m.joint else {
            out.push(*m);
            continue;
        };
        let mut j = Some(on);
        while let Some(a) = j.filter(|a| !kept.contains(a)) {
            j = robot.joints()[a].parent;
        }
        let carried = match j {
            Some(a) => PointMass {
                joint: kept.iter().position(|&c| c == a),
                com: (frames[a].inverse() * (frames[on] * nalgebra::Point3::from(m.com))).coords,
                mass: m.mass,
            },
            None => PointMass {
                joint: None,
                com: (robot.base.inverse() * (frames[on] * nalgebra::Point3::from(m.com))).coords,
                mass: m.mass,
            },
        };
        out.push(carried);
    }
    Ok(out)
}

/// Which joints an arm keeps: the chain, and the joints off it that a chain joint follows (a
/// mimic's leader on another branch, as a gripper's fingers follow one knuckle).
fn kept_joints(robot: &Robot, chain: &[JointId]) -> Vec<bool> {
    let mut keep = vec![false; robot.joints().len()];
    for &j in chain {
        keep[j] = true;
        match &robot.joints()[j].drive {
            Drive::Coupled(terms) => terms.iter().for_each(|&(src, _)| keep[src] = true),
            Drive::Closure(c) => {
                keep[c.mechanism.crank] = true;
                keep[c.mechanism.arm] = true;
            }
            _ => {}
        }
    }
    keep
}

/// The `kept` joints of `robot` (held joints already fixed), renumbered: parents, coupling
/// terms and loop joints point into the kept list.
fn prune(robot: &Robot, kept: &[JointId], ee: &str) -> Result<Vec<Joint>, ArmError> {
    let new_id = |old: JointId| kept.iter().position(|&c| c == old);
    let mut out: Vec<Joint> = Vec::with_capacity(kept.len());
    for &j in kept {
        let mut nj = robot.joints()[j].clone();
        // A leader off the chain keeps its variable; where it sits does not matter here.
        nj.parent = nj.parent.and_then(new_id);
        let broken = || ArmError::CoupledOffChain {
            joint: nj.name.clone(),
            ee: ee.to_string(),
        };
        match &mut nj.drive {
            Drive::Coupled(terms) => {
                for t in terms.iter_mut() {
                    t.0 = new_id(t.0).ok_or_else(broken)?;
                }
            }
            Drive::Closure(c) => {
                c.mechanism.crank = new_id(c.mechanism.crank).ok_or_else(broken)?;
                c.mechanism.arm = new_id(c.mechanism.arm).ok_or_else(broken)?;
            }
            _ => {}
        }
        out.push(nj);
    }
    Ok(out)
}
