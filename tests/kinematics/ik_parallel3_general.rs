//! Issue 27, every family that decomposes: six revolute joints with axes 2, 3 and 4 parallel
//! and any other lengths and twists (IK-Geo's `three_parallel`; the Universal Robots arm is its
//! special case): theta1 from a quartic (or from one equation where a5 = 0 or axes 5 and 6 are
//! parallel), theta5, theta6 and the planar two-link problem, up to 8 solutions. Checked against
//! a forward kinematics multiplied out in the test and a brute-force Newton search that finds no
//! solution the solver missed. `ARMLAB_EVIDENCE=full` runs 1000 poses per arm with 1000 starts
//! each.

use crate::common;

use common::closed_form::*;

/// Twists 0 and pi between the parallel axes, everything else skewed: the quartic.
const GENERIC: Rows6 = [
    (0.05, 1.2, 0.3),
    (0.4, 0.0, 0.1),
    (0.35, PI, 0.05),
    (0.08, 0.9, 0.12),
    (0.07, -0.7, 0.1),
    (0.03, 0.4, 0.09),
];
/// a5 = 0: the height along the parallel axes fixes theta1.
const NO_A5: Rows6 = [
    (0.0, FRAC_PI_2, 0.3),
    (-0.4, 0.0, 0.0),
    (-0.35, 0.0, 0.0),
    (0.05, 1.1, 0.1),
    (0.0, -0.8, 0.1),
    (0.02, 0.3, 0.08),
];
/// Axes 5 and 6 parallel (alpha5 = 0): the direction of axis 6 fixes theta1.
const PARALLEL56: Rows6 = [
    (0.1, -1.0, 0.3),
    (0.4, 0.0, 0.05),
    (0.3, 0.0, 0.0),
    (0.0, 1.3, 0.1),
    (0.09, 0.0, 0.1),
    (0.0, 0.5, 0.07),
];
/// Axes 3, 4, 5 parallel, the rest skewed: the general family read from the tool.
const PARALLEL345: Rows6 = [
    (0.05, 0.7, 0.3),
    (0.1, 1.1, 0.05),
    (0.4, 0.0, 0.1),
    (0.35, 0.0, 0.02),
    (0.06, 0.8, 0.1),
    (0.04, -0.5, 0.07),
];

fn check(rows: &Rows6, family: Family, seed: u64) -> Evidence {
    let r = arm6("three parallel", rows);
    assert_eq!(*cf(&r).family(), family, "{}", cf(&r).name());
    let size = if full_evidence() {
        (1000, 1000)
    } else {
        (40, 150)
    };
    all_solutions_evidence(&r, |q: &[f64]| fk6(rows, q), size, 8, seed, |_| {})
}

#[test]
fn three_parallel_axes_with_skewed_ends_have_every_solution() {
    let ev = check(&GENERIC, Family::ThreeParallelGeneral, 1);
    eprintln!("generic: {ev:?}");
    assert!(ev.converged > 0 && ev.most >= 4);
}

#[test]
fn with_a5_zero_the_height_fixes_theta1() {
    let ev = check(&NO_A5, Family::ThreeParallelGeneral, 2);
    eprintln!("a5 = 0: {ev:?}");
    assert!(ev.converged > 0 && ev.most == 8);
}

#[test]
fn with_axes_5_and_6_parallel_the_last_axis_fixes_theta1() {
    let ev = check(&PARALLEL56, Family::ThreeParallelGeneral, 3);
    eprintln!("axes 5, 6 parallel: {ev:?}");
    assert!(ev.converged > 0 && ev.most == 8);
}

#[test]
fn three_parallel_axes_at_3_to_5_are_solved_from_the_tool() {
    let of = ReversedOf::ThreeParallelGeneral;
    let ev = check(&PARALLEL345, Family::Reversed6 { of }, 4);
    eprintln!("axes 3-5: {ev:?}");
    assert!(ev.converged > 0 && ev.most >= 4);
}

/// Eight solutions occur for the generic arm (the quartic's four real roots, two elbows each),
/// and fewer elsewhere.
#[test]
fn the_generic_arm_reaches_eight_solutions() {
    let counts = solution_counts(&arm6("g", &GENERIC), |q| fk6(&GENERIC, q), 600, 9);
    assert!(counts[8] > 0 && counts[4] > 0, "counts by size {counts:?}");
}

/// The labels are "elbow up/down, branch k", both elbows of one branch sharing its number.
#[test]
fn labels_are_elbows_of_numbered_branches() {
    let r = arm6("g", &GENERIC);
    let q = [0.3, -0.5, 0.9, 0.4, 1.1, -0.6];
    let t = pose_from_matrix(&fk6(&GENERIC, &q)).unwrap();
    let res = cf(&r).solve(&r, &Target::Pose(t)).unwrap();
    for s in &res.solutions {
        assert!(
            (s.posture.to_string().starts_with("elbow up, branch ")
                || s.posture.to_string().starts_with("elbow down, branch ")),
            "{}",
            s.posture
        );
    }
}
