//! Issue 27, every family that decomposes: a six-revolute arm whose last three axes meet (a
//! spherical wrist) but whose first three joints are none of the named arms (any lengths and
//! twists) is Pieper's general case: the wrist centre fixes theta3 by a quartic, then theta1 and
//! theta2, then the wrist its two postures (up to 8 solutions). Checked against computations
//! written here: a forward kinematics of the DH rows multiplied out in the test, and a
//! brute-force Newton search over all six joints that finds no solution the solver missed.
//! `ARMLAB_EVIDENCE=full` runs 1000 poses per arm with 1000 starts each.

use crate::common;

use common::closed_form::*;
use nalgebra::Matrix4;

/// (a, alpha, d) of the first three rows; the wrist is the textbook's (d4, d6 below).
type Rows3 = [(f64, f64, f64); 3];

/// Twists of 1.1 and 0.7 rad: no named arm.
const GENERIC: Rows3 = [(0.15, 1.1, 0.3), (0.4, 0.7, 0.1), (0.05, -1.2, 0.08)];
/// a1 = 0 (the quartic would be a square): G = 0 is solved apart.
const NO_A1: Rows3 = [(0.0, 0.9, 0.3), (0.45, -0.5, 0.05), (0.1, 1.3, 0.0)];
/// Axes 1 and 2 parallel (alpha1 = 0), axis 3 skew to them: q_z is fixed by the height.
const PARALLEL12: Rows3 = [(0.3, 0.0, 0.25), (0.35, 1.0, 0.06), (0.04, -0.8, 0.1)];
/// The wrist: d4 along axis 4 to the wrist centre, d6 to the flange.
const D4: f64 = 0.35;
const D6: f64 = 0.1;
/// Base and tool transforms (nothing axis-aligned).
fn base() -> Pose {
    Pose::translation(0.1, -0.2, 0.05) * rot_z(0.3)
}
fn tool() -> Pose {
    Pose::translation(0.01, 0.02, 0.04) * rot_y(0.25)
}

/// Joint offsets, so that theta = q + offset is exercised.
const OFFSETS: [f64; 6] = [0.2, -0.4, 0.1, 0.0, 0.3, -0.1];

fn arm(rows: &Rows3) -> Robot {
    let mut r: Vec<Row> = rows
        .iter()
        .zip(OFFSETS)
        .map(|(&(a, alpha, d), off)| rv(a, alpha, d, off))
        .collect();
    r.push(rv(0.0, -FRAC_PI_2, D4, OFFSETS[3]));
    r.push(rv(0.0, FRAC_PI_2, 0.0, OFFSETS[4]));
    r.push(rv(0.0, 0.0, D6, OFFSETS[5]));
    Robot::from_dh("pieper", Convention::Standard, &r, base(), tool()).unwrap()
}

/// The arm's forward kinematics multiplied out here, base and tool included.
fn fk_here(rows: &Rows3, q: &[f64]) -> Matrix4<f64> {
    let mut t = base().to_homogeneous();
    for (i, &(a, alpha, d)) in rows.iter().enumerate() {
        t *= dh_matrix(a, alpha, d, q[i] + OFFSETS[i]);
    }
    t *= dh_matrix(0.0, -FRAC_PI_2, D4, q[3] + OFFSETS[3]);
    t *= dh_matrix(0.0, FRAC_PI_2, 0.0, q[4] + OFFSETS[4]);
    t *= dh_matrix(0.0, 0.0, D6, q[5] + OFFSETS[5]);
    t * tool().to_homogeneous()
}

/// The family, then [`all_solutions_evidence`] on [`fk_here`], solutions in wrist pairs labelled
/// "branch k, wrist ...": 1000 poses x 1000 starts with `ARMLAB_EVIDENCE=full`, 60 x 150
/// otherwise.
fn check(rows: &Rows3, seed: u64) -> Evidence {
    let r = arm(rows);
    assert_eq!(
        *cf(&r).family(),
        Family::Decoupled6 {
            arm: ArmKind::General3R
        },
        "{}",
        cf(&r).name()
    );
    let size = if full_evidence() {
        (1000, 1000)
    } else {
        (60, 150)
    };
    let pairs = |res: &IkResult| {
        assert!(res.solutions.len().is_multiple_of(2), "{}", show(res));
        for s in &res.solutions {
            assert!(
                s.posture.to_string().contains("branch") && s.posture.to_string().contains("wrist")
            );
        }
    };
    all_solutions_evidence(&r, |q: &[f64]| fk_here(rows, q), size, 8, seed, pairs)
}

#[test]
fn a_general_three_revolute_arm_with_a_spherical_wrist_has_every_solution() {
    let ev = check(&GENERIC, 1);
    eprintln!("generic: {ev:?}");
    assert!(ev.converged > 0 && ev.solutions > 0);
}

#[test]
fn with_no_first_link_length_the_wrist_centre_fixes_theta3_directly() {
    let ev = check(&NO_A1, 2);
    eprintln!("a1 = 0: {ev:?}");
    assert!(ev.converged > 0 && ev.solutions > 0);
}

#[test]
fn with_parallel_first_axes_the_height_fixes_theta3() {
    let ev = check(&PARALLEL12, 3);
    eprintln!("alpha1 = 0: {ev:?}");
    assert!(ev.converged > 0 && ev.solutions > 0);
}

/// Eight solutions do occur for the generic arm: the quartic's four real roots are found, not
/// only two (a test of the count, against the brute force above that would miss nothing).
#[test]
fn the_generic_arm_reaches_eight_solutions() {
    let counts = solution_counts(&arm(&GENERIC), |q| fk_here(&GENERIC, q), 400, 9);
    assert!(counts[8] > 0 && counts[4] > 0, "counts by size {counts:?}");
}

/// A point out of reach is unreachable, with a positive lower bound on the gap.
#[test]
fn a_pose_out_of_reach_is_unreachable() {
    let r = arm(&GENERIC);
    let c = cf(&r);
    let t = Pose::translation(3.0, 1.0, 0.5);
    let res = c.solve(&r, &Target::Pose(t)).unwrap();
    match res.status {
        IkStatus::Unreachable { distance } => assert!(distance > 1.0, "{distance}"),
        s => panic!("{s:?}"),
    }
}
