//! Holding joints: a robot with some joint variables frozen at given values, as a smaller robot
//! of its own. The app drags one hand of a branched robot with the other chains held, solves a
//! degenerate closed-form solution with its free joints held, and a seven-joint arm becomes a
//! six-joint one by locking a joint.

use super::pose::Pose;
use super::{Drive, Joint, JointGeometry, JointKind, Robot};
use nalgebra::{Rotation3, Translation3};

/// A robot with some joints held, and how its joint variables map back to the original's.
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct Held {
    /// The robot whose q holds only the free variables.
    pub robot: Robot,
    /// `free[i]` is the original index of the held robot's `q[i]`.
    pub free: Vec<usize>,
}

impl Held {
    /// The original robot's q: `full` (the held values) with the free entries set from `q`.
    pub fn expand(&self, q: &[f64], full: &mut [f64]) {
        for (&k, &v) in self.free.iter().zip(q) {
            full[k] = v;
        }
    }
}

/// With several end-effectors: `robot` with every actuated joint on another end-effector's
/// chain held at its value in `q` ([`hold_joints`]), so that moving end-effector `ee` moves
/// nothing the others hang from. `None` when nothing is held.
pub fn hold_other_chains(robot: &Robot, q: &[f64], ee: usize) -> Option<Held> {
    let ees = robot.end_effectors();
    if ees.len() < 2 {
        return None;
    }
    let joints = robot.joints();
    let mut held_joint = vec![false; joints.len()];
    for (i, e) in ees.iter().enumerate() {
        if i != ee {
            for &j in robot.chain_to(e.parent) {
                held_joint[j] = true;
                match &joints[j].drive {
                    Drive::Coupled(terms) => {
                        for &(src, _) in terms {
                            held_joint[src] = true;
                        }
                    }
                    Drive::Closure(c) => {
                        held_joint[c.mechanism.crank] = true;
                        held_joint[c.mechanism.arm] = true;
                    }
                    _ => {}
                }
            }
        }
    }
    let held: Vec<bool> = robot
        .actuated_joints()
        .iter()
        .map(|&j| held_joint[j])
        .collect();
    hold_joints(robot, q, &held)
}

/// A copy of `robot` in which every `q[k]` with `held[k]` is turned into a fixed joint at its
/// value in `q` (rad or m; coupled joints keep their live terms, the held ones folded into the
/// offset), with the map from the copy's q indices to the original's. `None` when nothing is
/// held, or when a closed loop is read from one held and one free joint.
pub fn hold_joints(robot: &Robot, q: &[f64], held: &[bool]) -> Option<Held> {
    if !held.iter().any(|&h| h) {
        return None;
    }
    let joints = robot.joints();
    let dof_of = |j: usize| match joints[j].drive {
        Drive::Actuated(k) => Some(k),
        _ => None,
    };
    let mut free = Vec::new();
    let mut out = Vec::with_capacity(joints.len());
    for (ji, j) in joints.iter().enumerate() {
        let mut nj = j.clone();
        match &j.drive {
            Drive::Actuated(k) if held[*k] => hold(&mut nj, q[*k]),
            Drive::Actuated(k) => {
                nj.drive = Drive::Actuated(free.len());
                free.push(*k);
            }
            Drive::Coupled(terms) => {
                let mut constant = 0.0;
                let mut live = Vec::new();
                for &(src, c) in terms {
                    match dof_of(src) {
                        Some(k) if held[k] => constant += c * q[k],
                        _ => live.push((src, c)),
                    }
                }
                if live.is_empty() {
                    hold(&mut nj, constant);
                } else {
                    nj.drive = Drive::Coupled(live);
                    nj.offset += constant;
                }
            }
            Drive::Closure(c) => {
                let held_src = [c.mechanism.crank, c.mechanism.arm]
                    .map(|s| dof_of(s).is_some_and(|k| held[k]));
                if held_src.iter().any(|&h| h) {
                    // A loop read from a held and a free joint has no closed form here.
                    if !held_src.iter().all(|&h| h) {
                        return None;
                    }
                    hold(&mut nj, robot.joint_variable(ji, q));
                }
            }
            Drive::None => {}
        }
        out.push(nj);
    }
    let ees = robot.end_effectors().to_vec();
    let robot = Robot::new(robot.name.clone(), robot.base, out, ees).ok()?;
    Some(Held { robot, free })
}

/// Turns a joint into a fixed one at variable `value` (offset included in the geometry).
fn hold(j: &mut Joint, value: f64) {
    let v = value + j.offset;
    match (&mut j.geometry, j.kind) {
        (JointGeometry::Dh { row, .. }, JointKind::Revolute) => row.theta = v,
        (JointGeometry::Dh { row, .. }, JointKind::Prismatic) => row.d = v,
        (
            JointGeometry::Origin {
                parent_from_joint,
                axis,
            },
            kind,
        ) => {
            let m = match kind {
                JointKind::Revolute => Pose::from_parts(
                    Translation3::identity(),
                    Rotation3::from_axis_angle(axis, v),
                ),
                JointKind::Prismatic => Pose::from_parts(
                    Translation3::from(axis.into_inner() * v),
                    Rotation3::identity(),
                ),
                JointKind::Fixed => Pose::identity(),
            };
            *parent_from_joint *= m;
        }
        _ => {}
    }
    j.kind = JointKind::Fixed;
    j.drive = Drive::None;
    j.offset = 0.0;
}
