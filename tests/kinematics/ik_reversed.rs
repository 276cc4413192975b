//! Issue 27, every family that decomposes: six-revolute arms that are a named family only when
//! read from the tool back to the base (EAIK reverses the chain for these): a spherical wrist at
//! the base (axes 1-3 meet in one point) and three parallel axes at 3-5 (a Universal Robots arm
//! hung by its flange). Checked against computations written here: a forward kinematics of the
//! DH rows multiplied out in the test, and a brute-force Newton search over all six joints that
//! finds no solution the solver missed. `ARMLAB_EVIDENCE=full` runs 1000 poses per arm with
//! 1000 starts each.

use crate::common;

use common::closed_form::*;
use nalgebra::Matrix4;

/// Axes 1-3 meet (a1 = a2 = d2 = 0, twists +-pi/2), then three joints with skewed twists: read
/// from the tool, Pieper's general case.
const WRIST_FIRST: Rows6 = [
    (0.0, -FRAC_PI_2, 0.3),
    (0.0, FRAC_PI_2, 0.0),
    (0.12, 0.9, 0.2),
    (0.4, -0.6, 0.05),
    (0.3, 1.2, 0.1),
    (0.05, 0.3, 0.08),
];
/// Axes 1-3 meet, then an anthropomorphic arm read backwards: axes 4 and 5 parallel, axis 6
/// meeting axis 5 at a right angle.
const WRIST_FIRST_ELBOW: Rows6 = [
    (0.0, -FRAC_PI_2, 0.3),
    (0.0, FRAC_PI_2, 0.0),
    (0.0, FRAC_PI_2, 0.4),
    (0.35, 0.0, 0.0),
    (0.0, FRAC_PI_2, 0.0),
    (0.0, 0.0, 0.1),
];
/// A Universal Robots arm read backwards: axes 1-2 and 2-3 meet at right angles, axes 3, 4, 5
/// parallel, axis 6 meets axis 5 at a right angle.
const UR_REVERSED: Rows6 = [
    (0.0, FRAC_PI_2, 0.1),
    (0.0, -FRAC_PI_2, 0.09),
    (0.39, 0.0, 0.11),
    (0.42, 0.0, -0.02),
    (0.0, FRAC_PI_2, 0.05),
    (0.0, 0.0, 0.09),
];

fn arm(rows: &Rows6) -> Robot {
    arm6("reversed", rows)
}

fn fk_here(rows: &Rows6, q: &[f64]) -> Matrix4<f64> {
    fk6(rows, q)
}

/// The family, then [`all_solutions_evidence`] on [`fk_here`]: 1000 poses x 1000 starts with
/// `ARMLAB_EVIDENCE=full`, 40 x 150 otherwise.
fn check(rows: &Rows6, of: ReversedOf, seed: u64) -> Evidence {
    let r = arm(rows);
    assert_eq!(
        *cf(&r).family(),
        Family::Reversed6 { of },
        "{}",
        cf(&r).name()
    );
    let size = if full_evidence() {
        (1000, 1000)
    } else {
        (40, 150)
    };
    all_solutions_evidence(&r, |q: &[f64]| fk_here(rows, q), size, 8, seed, |_| {})
}

#[test]
fn a_spherical_wrist_at_the_base_is_pieper_read_from_the_tool() {
    let ev = check(&WRIST_FIRST, ReversedOf::Decoupled(ArmKind::General3R), 1);
    eprintln!("wrist first: {ev:?}");
    assert!(ev.converged > 0 && ev.most >= 4);
}

/// Eight solutions do occur for the wrist-first arm (the quartic of the reversed chain has four
/// real roots there), and so do four.
#[test]
fn the_wrist_first_arm_reaches_eight_solutions() {
    let counts = solution_counts(&arm(&WRIST_FIRST), |q| fk_here(&WRIST_FIRST, q), 600, 9);
    assert!(counts[8] > 0 && counts[4] > 0, "counts by size {counts:?}");
}

#[test]
fn a_spherical_wrist_at_the_base_with_an_elbow_is_the_anthropomorphic_arm_read_from_the_tool() {
    let ev = check(
        &WRIST_FIRST_ELBOW,
        ReversedOf::Decoupled(ArmKind::Anthropomorphic),
        2,
    );
    eprintln!("wrist first, elbow: {ev:?}");
    assert!(ev.converged > 0 && ev.most == 8);
}

#[test]
fn three_parallel_axes_at_3_to_5_are_the_ur_family_read_from_the_tool() {
    let ev = check(&UR_REVERSED, ReversedOf::ThreeParallel, 3);
    eprintln!("UR reversed: {ev:?}");
    assert!(ev.converged > 0 && ev.most == 8);
}

/// The labels name the reversed chain's postures where they sit on this arm: its shoulder at the
/// tool, its wrist at the base. The ball-shoulder model file is this family.
#[test]
fn labels_say_tool_shoulder_and_base_wrist() {
    let r = armlab::model_file::load_model("assets/robots/ball_shoulder_arm.toml").unwrap();
    let c = cf(&r);
    assert_eq!(
        *c.family(),
        Family::Reversed6 {
            of: ReversedOf::Decoupled(ArmKind::Anthropomorphic)
        }
    );
    let q = r.config("ready").unwrap().to_vec();
    let res = c.solve(&r, &Target::Pose(r.fk(&q).unwrap())).unwrap();
    assert_eq!(res.solutions.len(), 8, "{}", show(&res));
    let mut labels: Vec<String> = res
        .solutions
        .iter()
        .map(|s| s.posture.to_string())
        .collect();
    labels.sort();
    for s in ["right", "left"] {
        for e in ["up", "down"] {
            for w in ["no flip", "flip"] {
                let l = format!("tool shoulder {s}, elbow {e}, base wrist {w}");
                assert!(labels.contains(&l), "{l} not in {labels:?}");
            }
        }
    }
}

/// A CAD-rounded ball shoulder (a twist off by 3e-7 rad) is a near miss of the reversed family:
/// solved on the ideal structure, then each solution polished on the exact model to 1e-12.
#[test]
fn a_rounded_ball_shoulder_is_solved_in_closed_form_and_polished() {
    use armlab::kinematics::ik::numerical::NumericalOptions;
    use armlab::kinematics::ik::solver::{SolverChoice, solve};
    let mut rows = WRIST_FIRST_ELBOW;
    rows[1].1 += 3e-7;
    let r = arm(&rows);
    let c = ClosedForm::detect(&r).unwrap();
    assert!(c.near_miss().is_some(), "{}", c.describe());
    assert!(
        matches!(c.family(), Family::Reversed6 { .. }),
        "{}",
        c.name()
    );
    let q = [0.4, -0.7, 0.9, 0.5, 1.1, -0.3];
    let t = pose_from_matrix(&fk_here(&rows, &q)).unwrap();
    let opts = NumericalOptions::default();
    let (res, used) = solve(&r, 0, &Target::Pose(t), None, SolverChoice::Auto, &opts).unwrap();
    assert!(used.to_string().contains("closed form"), "{used}");
    assert_eq!(res.solutions.len(), 8, "{}", show(&res));
    for s in &res.solutions {
        let e = (fk_here(&rows, &s.q) - t.to_homogeneous()).amax();
        assert!(e < 1e-12, "{}: {e:e}", s.posture);
    }
    assert!(res.solutions.iter().any(|s| same_q(&r, &s.q, &q, 1e-9)));
}
