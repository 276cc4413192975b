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
//! wrist postures of one arm branch keep one number. Pure compute, no allocation beyond the label
//! strings.

use super::IkSolution;
use super::closed_form::BRANCH_LABELS;
use super::solver::joint_distance;
use crate::kinematics::Robot;

/// A solution continues a previous one only if their joint distance (the Euclidean norm of the
/// wrapped differences, rad or m) is below this: a farther jump is a new target, not a motion.
pub const MAX_STEP: f64 = 1.0;

/// The branch number (1-based) of a label that is "branch k" or has it as one of its parts
/// ("wrist flip, branch 3"), if it has one.
pub fn branch_number(label: &str) -> Option<usize> {
    label
        .split(", ")
        .find_map(|part| BRANCH_LABELS.iter().position(|l| *l == part).map(|k| k + 1))
}

/// The label's parts other than its "branch k" (joined by ", "): the group a branch number is
/// unique in.
fn other_parts(label: &str) -> String {
    label
        .split(", ")
        .filter(|part| !BRANCH_LABELS.contains(part))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `label` with its "branch k" part replaced by "branch `k`".
fn with_number(label: &str, k: usize) -> String {
    label
        .split(", ")
        .map(|part| {
            if BRANCH_LABELS.contains(&part) {
                BRANCH_LABELS[k - 1]
            } else {
                part
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// Renumbers the "branch k" solutions of `new` so that each keeps the number of the solution of
/// `previous` it continues (nearest first, within [`MAX_STEP`], among labels with the same other
/// parts); the others take the lowest numbers free in their group, in their sorted order. `new`
/// is then sorted by number (stably). Solutions with other labels, and a `new` that shares no
/// branch with `previous` (a jump), are left as they are.
pub fn continue_numbers(robot: &Robot, previous: &[IkSolution], new: &mut [IkSolution]) {
    let old: Vec<(usize, &[f64], String)> = previous
        .iter()
        .filter_map(|s| {
            branch_number(&s.posture).map(|k| (k, s.q.as_slice(), other_parts(&s.posture)))
        })
        .filter(|(_, q, _)| q.len() == robot.dof())
        .collect();
    let fresh: Vec<usize> = (0..new.len())
        .filter(|&i| branch_number(&new[i].posture).is_some() && new[i].q.len() == robot.dof())
        .collect();
    if old.is_empty() || fresh.is_empty() {
        return;
    }
    // Every (new, old) pair within a step, nearest first: a greedy matching.
    let mut pairs: Vec<(f64, usize, usize)> = Vec::with_capacity(old.len() * fresh.len());
    let groups: Vec<String> = new.iter().map(|s| other_parts(&s.posture)).collect();
    for &i in &fresh {
        for (j, (_, q, group)) in old.iter().enumerate() {
            let d = joint_distance(robot, &new[i].q, q);
            if d < MAX_STEP && *group == groups[i] {
                pairs.push((d, i, j));
            }
        }
    }
    if pairs.is_empty() {
        return;
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut number: Vec<Option<usize>> = vec![None; new.len()];
    let mut taken = vec![false; old.len()];
    for (_, i, j) in pairs {
        if number[i].is_none() && !taken[j] {
            number[i] = Some(old[j].0);
            taken[j] = true;
        }
    }
    let mut used: Vec<(usize, &str)> = (0..new.len())
        .filter_map(|i| number[i].map(|k| (k, groups[i].as_str())))
        .collect();
    // The rest, in their sorted order, take the lowest numbers free in their group.
    for &i in &fresh {
        if number[i].is_none() {
            let g = groups[i].as_str();
            let k = (1..=BRANCH_LABELS.len())
                .find(|k| !used.contains(&(*k, g)))
                .unwrap_or(BRANCH_LABELS.len());
            number[i] = Some(k);
            used.push((k, g));
        }
    }
    for &i in &fresh {
        if let Some(k) = number[i] {
            new[i].posture = with_number(&new[i].posture, k);
        }
    }
    // Branches by number; other labels keep their places after them.
    new.sort_by_key(|s| branch_number(&s.posture).unwrap_or(usize::MAX));
}
