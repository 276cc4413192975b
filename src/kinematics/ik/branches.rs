//! Branch numbers that stay with their branch while the target moves.
//!
//! A general six-revolute arm has no geometric posture names: its solutions are "branch 1" to
//! "branch 16" in a sorted order (by theta1, then theta2, ... wrapped into (-pi, pi]), which is
//! stable for one target but not along a path: when a branch's theta1 passes another's, or passes
//! pi, the sorted numbers swap although nothing happened to the arm. Following a moving target
//! (the app's gizmo, a path), [`continue_numbers`] gives each new solution the number of the
//! previous solution it continues, the one nearest in joint space within [`MAX_STEP`]; a branch
//! that appears (two are born at a singularity) takes the lowest free number, and a branch that
//! disappears frees its number. A label with other parts, such as Pieper's general case's
//! "wrist flip, branch 3", is numbered among the labels with the same other parts, so that both
//! wrist postures of one arm branch keep one number. The numbers are the `branch` field of the
//! solutions' [`Posture`]s; no label is read. Pure compute.

use super::closed_form::Posture;
use super::solver::joint_distance;
use super::{IkSolution, SolutionPosture};
use crate::kinematics::Robot;

/// A solution continues a previous one only if their joint distance (the Euclidean norm of the
/// wrapped differences, rad or m) is below this: a farther jump is a new target, not a motion.
pub const MAX_STEP: f64 = 1.0;

/// The branch number of a numbered solution and its group (the posture less the number), if it
/// has a number.
fn numbered(s: &IkSolution) -> Option<(u8, Posture)> {
    match &s.posture {
        SolutionPosture::ClosedForm(p) => p.branch.map(|k| (k, p.without_branch())),
        SolutionPosture::Numerical { .. } => None,
    }
}

/// Renumbers the "branch k" solutions of `new` so that each keeps the number of the solution of
/// `previous` it continues (nearest first, within [`MAX_STEP`], among postures with the same
/// other parts); the others take the lowest numbers free in their group, in their sorted order.
/// `new` is then sorted by number (stably). Solutions without a number, and a `new` that shares
/// no branch with `previous` (a jump), are left as they are.
pub fn continue_numbers(robot: &Robot, previous: &[IkSolution], new: &mut [IkSolution]) {
    let old: Vec<(u8, &[f64], Posture)> = previous
        .iter()
        .filter_map(|s| numbered(s).map(|(k, g)| (k, s.q.as_slice(), g)))
        .filter(|(_, q, _)| q.len() == robot.dof())
        .collect();
    let groups: Vec<Option<Posture>> = new.iter().map(|s| numbered(s).map(|(_, g)| g)).collect();
    let fresh: Vec<usize> = (0..new.len())
        .filter(|&i| groups[i].is_some() && new[i].q.len() == robot.dof())
        .collect();
    if old.is_empty() || fresh.is_empty() {
        return;
    }
    // Every (new, old) pair within a step, nearest first: a greedy matching.
    let mut pairs: Vec<(f64, usize, usize)> = Vec::with_capacity(old.len() * fresh.len());
    for &i in &fresh {
        for (j, (_, q, group)) in old.iter().enumerate() {
            let d = joint_distance(robot, &new[i].q, q);
            if d < MAX_STEP && Some(*group) == groups[i] {
                pairs.push((d, i, j));
            }
        }
    }
    if pairs.is_empty() {
        return;
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut number: Vec<Option<u8>> = vec![None; new.len()];
    let mut taken = vec![false; old.len()];
    for (_, i, j) in pairs {
        if number[i].is_none() && !taken[j] {
            number[i] = Some(old[j].0);
            taken[j] = true;
        }
    }
    let mut used: Vec<(u8, Option<Posture>)> = (0..new.len())
        .filter_map(|i| number[i].map(|k| (k, groups[i])))
        .collect();
    // The rest, in their sorted order, take the lowest numbers free in their group.
    for &i in &fresh {
        if number[i].is_none() {
            let g = groups[i];
            let k = (1..=u8::MAX)
                .find(|k| !used.contains(&(*k, g)))
                .unwrap_or(u8::MAX);
            number[i] = Some(k);
            used.push((k, g));
        }
    }
    for &i in &fresh {
        if let (Some(k), SolutionPosture::ClosedForm(p)) = (number[i], &mut new[i].posture) {
            p.branch = Some(k);
        }
    }
    // Branches by number; other solutions keep their places after them.
    new.sort_by_key(|s| s.posture.branch().map_or(usize::MAX, usize::from));
}
